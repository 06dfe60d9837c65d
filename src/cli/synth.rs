//! `specgen synth`: the command-line glue over [`crate::synth`].

use crate::cosim::Design;
use crate::emit;
use crate::error::Error as Failure;
use crate::synth::{synthesize, table, Target};
use std::path::PathBuf;

#[derive(clap::Args, Debug, Clone)]
pub struct SynthArgs {
    /// Directory with the Verilog and the specgen manifest.
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    #[arg(long, value_enum, default_value = "ice40")]
    pub target: Target,
    /// Map multipliers to DSP blocks (iCE40 SB_MAC16, ECP5 MULT18X18D).
    #[arg(long)]
    pub dsp: bool,
    /// Skip place-and-route (no Fmax).
    #[arg(long, conflicts_with = "seeds")]
    pub no_pnr: bool,
    /// Place-and-route with nextpnr seeds 1..=K and report the median Fmax with its range
    #[arg(long, value_name = "K", default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=20))]
    pub seeds: u32,
    /// Also write the result as JSON to FILE.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Keep nextpnr's log of seed 1 (critical paths) in FILE.
    #[arg(long, value_name = "FILE")]
    pub pnr_log: Option<PathBuf>,
}

pub fn run(args: &SynthArgs) -> Result<(), Failure> {
    let design = Design::load(&args.rtl)?;
    let r = synthesize(&design, args.target, args.dsp, if args.no_pnr { 0 } else { args.seeds }, args.pnr_log.as_deref())?;
    print!("{}", table(&r));
    if let Some(path) = &args.json {
        let mut text = serde_json::to_string_pretty(&r).expect("serialises");
        text.push('\n');
        emit::write_file_atomically(path, text.as_bytes()).map_err(|e| Failure::io("write", path, e))?;
    }
    Ok(())
}
