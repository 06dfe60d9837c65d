//! `specgen prove`: the command-line glue over [`specgen::prove`].

use super::outln;
use super::{failed, Failure};
use specgen::cosim::Design;
use specgen::prove::{
    environment, prove, prove_datapath, prove_pipelining, Tools, Unbounded, Verdict, OF_THE_BUILT,
};
use std::path::PathBuf;
use std::time::Duration;

#[derive(clap::Args, Debug, Clone)]
pub struct ProveArgs {
    /// Directory with the Verilog (*.v) and the specgen manifest (<top>.json).
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    /// The yosys binary that writes the model and replays a counterexample
    #[arg(long, value_name = "PATH", default_value = "yosys")]
    pub yosys: String,
    /// ABC with pdr (Debian's yosys-abc)
    #[arg(long, value_name = "PATH", default_value = "yosys-abc")]
    pub abc: String,
    /// Seconds any one engine may run (pdr, sat's induction or bounded search, ABC's iprove): a
    /// guard against a run that would never end, not a verdict; a run stopped by it is reported
    /// as out of time, with the depth it reached [1..=86400]
    #[arg(long, value_name = "S", default_value_t = 3600, value_parser = clap::value_parser!(u64).range(1..=86400))]
    pub time_limit: u64,
    /// A bounded search of the first N clock edges from power-up instead of a proof: a failure
    /// within them is refuted with its trace (exit 1); none is reported as holding for N edges,
    /// not as proved (exit 0). Its run time grows with N, not with the machine's luck [1..=1000]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1000), conflicts_with = "pipelining")]
    pub depth: Option<u32>,
    /// Where a counterexample's VCD goes [default: <tmp>/<top>_prove_edge-<pid>.vcd, named in
    /// the message]
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Where the VCD of the run that reaches every cover of the port checker goes (ready/axis,
    /// and --datapath): the unit seen delivering, full, in_ready falling and rising again
    #[arg(long, value_name = "FILE")]
    pub cover_trace: Option<PathBuf>,
    /// Prove an RTL changed on purpose (without it, a file whose SHA-256 is not the manifest's
    /// is refused).
    #[arg(long)]
    pub edited: bool,
    /// Prove instead that pipelining changes nothing: the unit equals its depth-0 twin (the
    /// same parameters, no pipeline registers) fed the same inputs `stages` edges late, for
    /// every input sequence (--interface valid with per-pixel colours)
    #[arg(long)]
    pub pipelining: bool,
    /// Prove instead that a ready/axis unit delivers its datapath's values: the port checker
    /// follows any one pixel and asserts that its delivered result equals what the same
    /// configuration as a valid unit (top <top>_datapath) computes for it: searched for
    /// latency + 8 edges (or --depth N), then proved for every edge by k-induction
    #[arg(long, conflicts_with = "pipelining")]
    pub datapath: bool,
}

/// `specgen prove`: exit 0 when every property is proved, 1 when one fails (its VCD named) or
/// is undecided within the time limit, 2 on usage errors.
pub fn run(args: &ProveArgs) -> Result<(), Failure> {
    let design = Design::load(&args.rtl)?;
    design.verify_files(args.edited)?;
    // the tables the RTL reads are here and right, before any proof reads them
    specgen::cosim::check_tables(&design)?;
    if let Some(t) = &args.trace {
        design.refuse_output("--trace", t)?;
    }
    if let Some(t) = &args.cover_trace {
        design.refuse_output("--cover-trace", t)?;
        if !design.cfg.interface().handshake() {
            return Err(super::usage("invalid --cover-trace: a valid unit's proof has no covers (the port checker is a ready/axis unit's)"));
        }
        if args.trace.as_ref() == Some(t) {
            return Err(super::usage(
                "invalid --cover-trace: the same file as --trace",
            ));
        }
    }
    // the ports the manifest names, as cosim and synth check them: an extra, missing or wider
    // port is refused before anything is proved
    specgen::cosim::check_ports(&design)?;
    if let Some(why) = args
        .pipelining
        .then(|| specgen::prove::pipelining_refused(&design))
        .flatten()
    {
        return Err(super::usage(format!("invalid --pipelining: {why}")));
    }
    if let Some(why) = args
        .datapath
        .then(|| specgen::prove::datapath_refused(&design))
        .flatten()
    {
        return Err(super::usage(format!("invalid --datapath: {why}")));
    }
    let progress: fn(&str) = |line| super::errln!("prove: {line}");
    let tools = Tools {
        yosys: args.yosys.clone(),
        abc: args.abc.clone(),
        limit: Duration::from_secs(args.time_limit),
        depth: args.depth,
        progress: Some(progress),
        cover_trace: args.cover_trace.is_some(),
    };
    tools.check()?;
    let proof = if args.pipelining {
        prove_pipelining(&design, &tools)?
    } else if args.datapath {
        prove_datapath(&design, &tools)?
    } else {
        prove(&design, &tools)?
    };
    let how = &proof.engine;
    let head = format!("prove {} ({}): ", design.dir.display(), proof.name);
    match &proof.verdict {
        Verdict::Proved => {
            outln!("{head}proved, unbounded ({how}), {:.1} s:", proof.seconds)?;
            for p in &proof.properties {
                outln!("  - {p}")?;
            }
            outln!("{OF_THE_BUILT}; assumed: {}", environment(args.pipelining))?;
            at_the_ports(&proof, args.cover_trace.as_deref())
        }
        Verdict::Bounded { depth } => {
            outln!(
                "{head}no property fails within the first {depth} clock edges from power-up ({how}), {:.1} s; a bounded search, not a proof:",
                proof.seconds
            )?;
            for p in &proof.properties {
                outln!("  - {p}")?;
            }
            outln!("{OF_THE_BUILT}; assumed: {}", environment(args.pipelining))?;
            at_the_ports(&proof, args.cover_trace.as_deref())
        }
        Verdict::Unreached { covers, depth } => {
            let mut msg = format!("{head}vacuous: {how}: within the first {depth} clock edges from power-up no run reaches");
            for c in covers {
                msg.push_str(&format!("\n  - {c}"));
            }
            msg.push_str("\nso a proof would say nothing about what the unit never does");
            Err(failed(msg))
        }
        Verdict::Undecided { bounded, out_of_time, reached } => {
            let also = match bounded {
                Some(k) => format!("; the properties hold for the first {k} clock edges from power-up"),
                None => String::new(),
            };
            let why = if *out_of_time {
                let k = match reached {
                    Some(k) => format!("; the last depth completed: k = {k}"),
                    None => "; no depth completed".into(),
                };
                format!("ran out of time ({} s, --time-limit), which is not a verdict{k}", args.time_limit)
            } else {
                "did not conclude within its depth".to_string()
            };
            Err(failed(format!("{head}undecided: {how} {why}; so not proved{also}")))
        }
        Verdict::NotBuilt { differs } => Err(failed(format!(
            "{head}refused: the design the proof reads is not the one synthesis builds ({how}): {differs}; the unit's formal regions (`ifdef FORMAL`, SPECGEN_*) change what it computes, so a proof of it would say nothing of the built unit"
        ))),
        Verdict::Incomplete { bounded, keeps } => Err(failed(format!(
            "{head}not proved: the properties hold for the first {bounded} clock edges from power-up, but the unit keeps state longer than its latency, so the check from any state cannot conclude: {keeps}"
        ))),
        Verdict::Failed { frame, vcd } => {
            let path = args.trace.clone().unwrap_or_else(|| std::env::temp_dir().join(format!("{}-{}.vcd", proof.name, std::process::id())));
            let mut msg = format!("{head}a property fails {frame} clock edge{} into the counterexample ({how})", if *frame == 1 { "" } else { "s" });
            match specgen::output::write_file(&path, vcd) {
                Ok(()) => msg.push_str(&format!("; the replay's trace: {}", path.display())),
                Err(e) => msg.push_str(&format!("; could not write the trace {}: {e}", path.display())),
            }
            msg.push_str("\nthe properties:\n");
            for p in &proof.properties {
                msg.push_str(&format!("  - {p}\n"));
            }
            Err(failed(msg.trim_end().to_string()))
        }
    }
}

/// What the port checker found, after the verdict's own lines.
fn at_the_ports(
    proof: &specgen::prove::Proof,
    cover_trace: Option<&std::path::Path>,
) -> Result<(), Failure> {
    let Some(ports) = &proof.ports else {
        return Ok(());
    };
    let bounded = format!(
        "no property fails within the first {} clock edges from power-up (a bounded search over the checker's rules and the unit's own assertions)",
        ports.depth
    );
    let verdict = match ports.unbounded {
        Unbounded::Proved { k } => format!(
            "proved, unbounded (k-induction with yosys sat, k = {k}, the unit's lemmas tying the checker's state to its own; a lemma is an assertion, none can pass a broken unit); {bounded}"
        ),
        Unbounded::NoLemmas => format!("{bounded}, not a proof: the unit lacks the lemmas the induction needs (the port f_ports, or assertions specgen writes)"),
        Unbounded::Undecided { steps, out_of_time: false } => format!("{bounded}, not a proof: the induction with the unit's lemmas did not close within {steps} edges"),
        Unbounded::Undecided { out_of_time: true, .. } => format!("{bounded}, not a proof: the induction with the unit's lemmas ran out of time"),
        Unbounded::NotTried => format!("{bounded}, not a proof"),
    };
    outln!("at the ports (a checker written from the manifest, apart from the RTL): {verdict}:")?;
    for p in &ports.properties {
        outln!("  - {p}")?;
    }
    if !ports.bounded_only.is_empty() {
        outln!(
            "and by the bounded search alone, of {} edges from power-up, not a proof:",
            ports.depth
        )?;
        for p in &ports.bounded_only {
            outln!("  - {p}")?;
        }
    }
    outln!(
        "covers, all reached in one run by edge {} (none vacuous):",
        ports.covered_by
    )?;
    for c in &ports.covers {
        outln!("  - {c}")?;
    }
    if let (Some(path), Some(vcd)) = (cover_trace, &ports.cover_vcd) {
        specgen::output::write_file(path, vcd).map_err(|e| {
            failed(format!(
                "could not write the covering run's trace {}: {e}",
                path.display()
            ))
        })?;
        outln!("the covering run's trace: {}", path.display())?;
    }
    Ok(())
}
