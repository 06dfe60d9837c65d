//! `specgen cosim`: the command-line glue over [`specgen::cosim`].

use super::outln;
use super::{failed, Failure};
use specgen::cosim::{
    build, check_ports, check_tables, describe, random_stimulus, run_all, write_trace, Design,
    Exhaustive, Simulator, Stimulus,
};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug, Clone)]
pub struct CosimArgs {
    /// Directory with the Verilog (*.v) and the specgen manifest (<top>.json).
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    /// Number of vectors after the corner cases (random mode) [0..=10000000: the stimulus is held in memory]
    #[arg(long, default_value_t = 100_000, value_parser = clap::value_parser!(u64).range(0..=10_000_000))]
    pub vectors: u64,
    /// Seed of the random vectors.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Every (cos_g, n) pair with cos_g in [0, 1.0], colours varied over every code.
    #[arg(long, conflicts_with = "vectors")]
    pub exhaustive: bool,
    #[arg(long, value_enum, default_value = "verilator")]
    pub simulator: super::values::SimulatorFlag,
    /// On a mismatch, write a VCD of a short replay around the first failure.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Parallel simulator processes [1..=64; default: available cores].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=64))]
    pub jobs: Option<u16>,
    /// Check an RTL changed on purpose against its manifest's configuration (without it, a
    /// file whose SHA-256 is not the manifest's is refused: a stale or mixed directory).
    #[arg(long)]
    pub edited: bool,
    #[command(flatten)]
    pub sim: super::values::SimToolArgs,
}

/// `specgen cosim`: exit 0 when every output matches, 1 on any mismatch, 2 on usage errors.
pub fn run(args: &CosimArgs) -> Result<(), Failure> {
    let design = Design::load(&args.rtl)?;
    design.verify_files(args.edited)?;
    if let Some(trace) = &args.trace {
        design.refuse_output("--trace", trace)?;
        // say before the run, not after it, that the trace has nowhere to go
        let parent = trace
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        if !parent.is_dir() {
            return Err(Failure::Input(format!(
                "invalid --trace {}: the directory {} does not exist",
                trace.display(),
                parent.display()
            )));
        }
    }
    check_tables(&design)?;
    // the directory as it is now: if it changes during the run (a generate swapping it), the
    // results are not judged against it
    let before = design.snapshot();
    let model = design.plan.model();
    let jobs = args
        .jobs
        .map(usize::from)
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
                .min(64)
        })
        .max(1);
    let t0 = Instant::now();
    // a file that does not compile is best told by the simulator; then the ports
    let sim = args.sim.tools();
    let cycles = if args.exhaustive {
        u64::MAX
    } else {
        args.vectors
    };
    let built = build(&design, args.simulator.into(), &sim, false, cycles)?;
    check_ports(&design)?;
    let build_time = t0.elapsed();
    let stims: Vec<Box<dyn Stimulus>> = if args.exhaustive {
        Exhaustive::parts(&design.cfg, jobs as u32 * 2)
            .into_iter()
            .map(|e| Box::new(e) as Box<dyn Stimulus>)
            .collect()
    } else {
        vec![Box::new(random_stimulus(&model, args.vectors, args.seed))]
    };
    let t1 = Instant::now();
    let report = run_all(&built, &design, &model, &stims, jobs);
    if design.snapshot() != before {
        return Err(specgen::error::mismatch(format!(
            "{} changed during the run (written by another command?), so its results were not judged: run cosim again",
            design.dir.display()
        )));
    }
    let report = report?;
    let check_time = t1.elapsed();
    let rate = report.cycles as f64 / check_time.as_secs_f64().max(1e-9);
    outln!(
        "cosim {} ({:?}{}): {} cycles, {} checked, {} results, {} mismatches; build {:.2} s{}, check {:.2} s ({:.1} M cycles/s)",
        design.dir.display(),
        Simulator::from(args.simulator),
        if args.exhaustive { ", exhaustive" } else { "" },
        report.cycles,
        report.checked,
        report.results,
        report.mismatches,
        build_time.as_secs_f64(),
        if built.fresh { "" } else { " (cached)" },
        check_time.as_secs_f64(),
        rate / 1e6
    )?;
    match &report.first {
        None if report.checked > 0 => Ok(()),
        None => Err(failed("no output was checked")),
        Some(m) => {
            let mut msg = format!(
                "{} of {} checked cycles differ from the golden model\n{}",
                report.mismatches,
                report.checked,
                describe(m, &design.cfg)
            );
            if let Some(path) = &args.trace {
                match write_trace(&design, &sim, &model, &stims, m, path) {
                    Ok(()) => msg.push_str(&format!(
                        "trace of the replay around the failure: {}",
                        path.display()
                    )),
                    Err(e) => msg.push_str(&format!("could not write the trace: {e}")),
                }
            }
            Err(failed(msg))
        }
    }
}
