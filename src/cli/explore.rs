//! `specgen explore` and `specgen measure`: the command-line glue over [`specgen::explore`].

use super::values::{MetricFlag, ModelFlag, RomStyleFlag, TargetFlag};
use super::{errln, outln, usage, Failure};
use specgen::config::{Params, Target};
use specgen::explore::{self, Exploration, Metric, Space};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug, Clone)]
pub struct ExploreArgs {
    /// Output directory: points.json/.csv (every point: accuracy, estimate, measurement),
    /// front.csv and front.svg (the front per clock), jobs.json (the sweep's jobs), merge.json
    /// (created, or replaced if it holds only a previous specgen output).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace a previous output even where its files were edited by hand.
    #[arg(long)]
    pub force: bool,
    /// The family explored.
    #[arg(long, value_enum, default_value = "ice40")]
    pub target: TargetFlag,
    /// Models in the space [default: every model]
    #[arg(long, value_enum, value_delimiter = ',')]
    pub models: Vec<ModelFlag>,
    /// F values (cos_g's fractional bits) in the space [each 4..=20]
    #[arg(long, value_delimiter = ',', default_value = "8,10,12,15")]
    pub cos_frac_bits: Vec<u32>,
    /// FI values (intensity's fractional bits) in the space [each 1..=24]
    #[arg(long, value_delimiter = ',', default_value = "8,10,12,15")]
    pub intensity_frac_bits: Vec<u32>,
    /// N, the exponent's width: fixed, as the user's shading needs it [1..=12]
    #[arg(long, default_value_t = 10)]
    pub n_bits: u32,
    /// B, the colours' width: fixed [4..=16]
    #[arg(long, default_value_t = 8)]
    pub color_bits: u32,
    /// The interface of every unit in the space (its edge is measured with it: a `ready` or
    /// `axis` unit's output buffer has paths of its own)
    #[arg(long, value_enum, default_value = "valid")]
    pub interface: super::values::InterfaceFlag,
    /// --dsp-budget values in the space: a number, or "none" (no limit)
    #[arg(long, value_delimiter = ',', default_value = "none")]
    pub dsp_budget: Vec<String>,
    /// --rom-style values in the space (one the family does not write is left out).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "file")]
    pub rom_style: Vec<RomStyleFlag>,
    /// Clocks (MHz) a depth is chosen for and a front drawn at [default: the family's: iCE40
    /// 50,75,100,125; ECP5 100,150,200,250]
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "MHZ,...",
        allow_negative_numbers = true
    )]
    pub clocks: Vec<f64>,
    /// Also K depths spread evenly up to each unit's deepest (a calibration grid for the delay
    /// model: scripts/calibrate_delay.sh) [0..=64]
    #[arg(long, value_name = "K", default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub depths: u32,
    /// The error the front and the choice are drawn by.
    #[arg(long, value_enum, default_value = "max")]
    pub metric: MetricFlag,
    /// The display of the display metrics: srgbB (sRGB, B bits) or gammaG:B (a power law)
    /// [B 1..=16, G 1..=4]
    #[arg(long, value_name = "DISPLAY", default_value = "srgb8")]
    pub display: String,
    /// nextpnr seeds 1..=K of each measured point [1..=20]
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=20))]
    pub seeds: u32,
    /// A point is measured when it is on the estimated front or within this fraction of its
    /// logic cells (at a clock the delay model predicts it within 20% of) [0..=10]
    #[arg(long, default_value_t = 0.15, allow_negative_numbers = true)]
    pub near: f64,
    /// Measure every point of the space, not only those on or near the estimated front.
    #[arg(long)]
    pub measure_all: bool,
    /// A directory of job results (`specgen measure`'s, a sweep's); repeat it to merge shards.
    #[arg(long, value_name = "DIR")]
    pub results: Vec<PathBuf>,
    /// Synthesize every job with the products in the fabric (`synth` without `--dsp`: the
    /// LUT-only figures); said in each job and its fingerprint.
    #[arg(long)]
    pub no_dsp: bool,
    /// Also run the plan's jobs that have no result in the first --results directory, then
    /// merge: one command for a sweep. Killed midway, run it again: only what has no result runs.
    #[arg(long)]
    pub run: bool,
    /// With --run: what runs the jobs (auto: Snakemake with --profile, else specgen's own slots)
    #[arg(long, value_enum, default_value = "auto", requires = "run")]
    pub engine: super::sweep::Engine,
    /// With --run: jobs at once on this machine [1..=64; default: the cores]
    #[arg(long, value_name = "N", requires = "run", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub run_jobs: Option<u32>,
    /// With --run: a Snakemake profile (a cluster's: scripts/sweep/profiles/slurm)
    #[arg(long, value_name = "DIR", requires = "run")]
    pub profile: Option<PathBuf>,
    /// A generated unit (its directory, read by its manifest) as a point of its own, instead of
    /// the space: every unit given is measured (a bench's units on the sweep); repeat it [at
    /// most 1000, each of --target's family].
    #[arg(long, value_name = "DIR", conflicts_with_all = ["models", "cos_frac_bits", "intensity_frac_bits", "n_bits", "color_bits", "dsp_budget", "rom_style", "depths", "measure_all"])]
    pub unit: Vec<PathBuf>,
    /// The yosys the jobs run (its version is in every job's fingerprint).
    #[arg(long, value_name = "PATH", default_value = "yosys")]
    pub yosys: String,
    /// The nextpnr the jobs run [default: the family's].
    #[arg(long, value_name = "PATH")]
    pub nextpnr: Option<String>,
}

#[derive(clap::Args, Debug, Clone)]
pub struct MeasureArgs {
    /// The sweep's jobs (`specgen explore`'s jobs.json).
    #[arg(long, value_name = "FILE")]
    pub jobs: PathBuf,
    /// The job to run, by its fingerprint.
    #[arg(long, value_name = "FP")]
    pub fingerprint: String,
    /// Where its result goes (written atomically): a sweep keeps it as <results>/<FP>.json.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// The yosys binary (its version must be the one the job was planned with).
    #[arg(long, value_name = "PATH", default_value = "yosys")]
    pub yosys: String,
    /// The nextpnr binary [default: the family's].
    #[arg(long, value_name = "PATH")]
    pub nextpnr: Option<String>,
    /// Keep yosys's netlists here by what made them, so the job of another seed of the same
    /// unit synthesizes it no more (a sweep passes RESULTS/.yosys-cache).
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,
}

/// The most jobs a plan holds; the largest jobs file.
const MAX_JOBS: usize = 100_000;
const MAX_JOBS_BYTES: u64 = 256 << 20;

fn tools(yosys: &str, nextpnr: &Option<String>) -> specgen::synth::Tools {
    specgen::synth::Tools {
        yosys: yosys.to_string(),
        nextpnr: nextpnr.clone(),
        ..Default::default()
    }
}

pub fn read_jobs(path: &Path) -> Result<Vec<explore::Job>, Failure> {
    let text = specgen::small_file::read(path, MAX_JOBS_BYTES)
        .map_err(|e| usage(format!("invalid --jobs: {} {e}", path.display())))?;
    let jobs: Vec<explore::Job> = serde_json::from_str(&text).map_err(|e| {
        usage(format!(
            "invalid --jobs: {} is not a sweep's jobs.json: {e}",
            path.display()
        ))
    })?;
    if jobs.len() > MAX_JOBS {
        return Err(usage(format!(
            "invalid --jobs: {} holds {} jobs; allowed at most {MAX_JOBS}",
            path.display(),
            jobs.len()
        )));
    }
    Ok(jobs)
}

pub fn run(a: &ExploreArgs) -> Result<(), Failure> {
    let range = |flag: &str, v: &[u32], r: &specgen::config::Range| -> Result<(), Failure> {
        match v.iter().find(|&&x| x < r.min || x > r.max) {
            Some(x) => Err(usage(format!(
                "invalid --{flag}: {x} is out of range; allowed {}..={}",
                r.min, r.max
            ))),
            None if v.is_empty() || v.len() > 16 => {
                Err(usage(format!("invalid --{flag}: give 1 to 16 values")))
            }
            None => Ok(()),
        }
    };
    // every list bounded before anything is parsed or computed, and each value taken once
    for (flag, len) in [
        ("models", a.models.len()),
        ("cos-frac-bits", a.cos_frac_bits.len()),
        ("intensity-frac-bits", a.intensity_frac_bits.len()),
        ("dsp-budget", a.dsp_budget.len()),
        ("rom-style", a.rom_style.len()),
        ("clocks", a.clocks.len()),
    ] {
        if len > 16 {
            return Err(usage(format!(
                "invalid --{flag}: {len} values; allowed at most 16"
            )));
        }
    }
    let mut a = a.clone();
    if a.models.is_empty() {
        a.models = <ModelFlag as clap::ValueEnum>::value_variants().to_vec();
    }
    fn once<T: PartialEq + Clone>(v: &mut Vec<T>) {
        let mut seen: Vec<T> = Vec::new();
        v.retain(|x| {
            let new = !seen.contains(x);
            if new {
                seen.push(x.clone());
            }
            new
        });
    }
    once(&mut a.models);
    once(&mut a.cos_frac_bits);
    once(&mut a.intensity_frac_bits);
    once(&mut a.dsp_budget);
    once(&mut a.rom_style);
    once(&mut a.clocks);
    let a = &a;
    range(
        "cos-frac-bits",
        &a.cos_frac_bits,
        &specgen::config::COS_FRAC_BITS,
    )?;
    range(
        "intensity-frac-bits",
        &a.intensity_frac_bits,
        &specgen::config::INTENSITY_FRAC_BITS,
    )?;
    if !(0.0..=10.0).contains(&a.near) {
        return Err(usage(format!("invalid --near: {}; allowed 0..=10", a.near)));
    }
    if let Some(c) = a.clocks.iter().find(|c| !(1.0..=1000.0).contains(*c)) {
        return Err(usage(format!(
            "invalid --clocks: {c}; allowed MHz in [1, 1000]"
        )));
    }
    if a.clocks.len() > 16 || a.models.is_empty() || a.rom_style.is_empty() {
        return Err(usage(
            "invalid --clocks, --models or --rom-style: give 1 to 16 values",
        ));
    }
    let mut budgets = Vec::new();
    for b in &a.dsp_budget {
        budgets.push(match b.trim() {
            "none" => None,
            t => Some(
                t.parse::<u32>()
                    .ok()
                    .filter(|v| *v <= specgen::config::DSP_BUDGET.max)
                    .ok_or_else(|| {
                        usage(format!(
                            "invalid --dsp-budget: {t:?}; allowed \"none\" or 0..={}",
                            specgen::config::DSP_BUDGET.max
                        ))
                    })?,
            ),
        });
    }
    let target: Target = a.target.into();
    let base = Params {
        target,
        n_bits: a.n_bits,
        color_bits: a.color_bits,
        interface: a.interface.into(),
        ..Params::default()
    };
    specgen::config::Config::new(base.clone())?;
    let space = Space {
        base,
        models: a.models.iter().map(|&m| m.into()).collect(),
        cos_frac_bits: a.cos_frac_bits.clone(),
        intensity_frac_bits: a.intensity_frac_bits.clone(),
        dsp_budgets: budgets,
        rom_styles: a.rom_style.iter().map(|&r| r.into()).collect(),
        clocks: a.clocks.clone(),
        spread: a.depths,
        display: specgen::models::display::Display::parse(&a.display)?,
    };
    for dir in &a.results {
        if specgen::output::inside(dir, &a.out) {
            return Err(usage(format!(
                "invalid --results: {} is inside --out {}, which is replaced whole: keep results elsewhere",
                dir.display(),
                a.out.display()
            )));
        }
    }
    let metric: Metric = a.metric.into();
    let clocks = space.clocks();
    // the points counted before any is computed: a depth per clock, the deepest, the spread
    let at_most = a.models.len()
        * a.cos_frac_bits.len()
        * a.intensity_frac_bits.len()
        * space.dsp_budgets.len()
        * a.rom_style.len()
        * (clocks.len().max(3) + 1 + a.depths as usize);
    if a.unit.is_empty() && at_most > explore::MAX_POINTS {
        return Err(usage(format!(
            "the space holds up to {at_most} points; allowed at most {}: narrow it",
            explore::MAX_POINTS
        )));
    }
    let start = std::time::Instant::now();
    // progress on standard error, at most every two seconds
    let said = std::cell::Cell::new(0u64);
    let mut points = match a.unit.is_empty() {
        true => explore::points(&space, &|done, of| {
            let now = start.elapsed().as_secs();
            if now >= said.get() + 2 || done == of {
                said.set(now);
                errln!("explore: {done} of {of} (model, widths) measured by the golden model ({now} s)");
            }
        })?,
        false => explore::unit_points(&units_of(&a.unit, target)?)?,
    };
    if points.len() > explore::MAX_POINTS {
        return Err(usage(format!(
            "the space holds {} points; allowed at most {}: narrow it",
            points.len(),
            explore::MAX_POINTS
        )));
    }
    let ids: Vec<String> = match a.measure_all || !a.unit.is_empty() {
        true => points.iter().map(|p| p.id.clone()).collect(),
        // the fronts of every metric are measured, so a choice by any of them is among
        // measured units
        false => {
            let mut ids = std::collections::BTreeSet::new();
            for m in Metric::ALL {
                ids.extend(explore::candidates(&points, m, &clocks, a.near, 0.8));
            }
            points
                .iter()
                .filter(|p| ids.contains(&p.id))
                .map(|p| p.id.clone())
                .collect()
        }
    };
    let seeds: Vec<u32> = (1..=a.seeds).collect();
    let versions = explore::tool_versions(target, &tools(&a.yosys, &a.nextpnr))?;
    let mut jobs = explore::jobs_of(&points, &ids, &seeds, &versions)?;
    if a.no_dsp {
        jobs = jobs.into_iter().map(explore::Job::fabric_only).collect();
    }
    // one limit for the jobs a plan holds: what `measure` reads
    if jobs.len() > MAX_JOBS {
        return Err(usage(format!("the plan holds {} jobs; allowed at most {MAX_JOBS} (what measure reads): fewer --seeds or a narrower space", jobs.len())));
    }
    // --run: the jobs without a result run now, into the first --results
    let mut failed_jobs = Vec::new();
    if a.run {
        let store = super::sweep::store(&a.results)?;
        let at_once = a.run_jobs.map_or_else(
            || std::thread::available_parallelism().map_or(1, |n| n.get()),
            |n| n as usize,
        );
        let opts = super::sweep::RunOptions {
            engine: a.engine,
            jobs_at_once: at_once,
            profile: a.profile.as_deref(),
            yosys: &a.yosys,
            nextpnr: a.nextpnr.as_deref(),
        };
        failed_jobs = super::sweep::run_jobs(&jobs, store, &opts)?;
    }
    let dirs: Vec<&Path> = a.results.iter().map(PathBuf::as_path).collect();
    let results = explore::read_results(&dirs)?;
    let report = explore::merge(&mut points, &jobs, &results);
    explore::mark_fronts(&mut points, metric, &clocks);
    let e = Exploration {
        generator: "specgen".into(),
        version: specgen::names::VERSION.into(),
        target: target.name().into(),
        part: specgen::timing::part(target).into(),
        metric: metric.name().into(),
        clocks: clocks.clone(),
        seeds,
        points,
    };
    let files = explore::files(&e, metric, &jobs, &report);
    super::write_output(&a.out, &files, a.force)?;
    let measured = e.points.iter().filter(|p| p.measured.is_some()).count();
    outln!(
        "explore: {} points on the {}, {} to measure ({} jobs); {measured} measured, {} jobs without a result, {} with conflicting results, {} results of no job here",
        e.points.len(),
        e.part,
        ids.len(),
        jobs.len(),
        report.missing.len(),
        report.conflicting.len(),
        report.unused
    )?;
    for &mhz in &clocks {
        let front = explore::front_at(&e.points, metric, mhz);
        outln!("front at {mhz} MHz: {}", front.join(", "))?;
    }
    if !report.missing.is_empty() {
        let jobs_file = a.out.join("jobs.json");
        outln!(
            "measure the rest: this command with --run (or scripts/sweep.sh {} RESULTS_DIR, Snakemake; a cluster: --run --profile, see the README), then run it again with --results RESULTS_DIR",
            jobs_file.display()
        )?;
    }
    if !report.conflicting.is_empty() {
        return Err(super::failed(format!(
            "jobs with conflicting results: {}",
            report.conflicting.join(", ")
        )));
    }
    if !failed_jobs.is_empty() {
        return Err(super::failed(format!(
            "{} job(s) failed and have no result ({}); run the command again to retry them",
            failed_jobs.len(),
            failed_jobs
                .iter()
                .take(8)
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(())
}

/// The most units one `explore --unit` takes.
const MAX_UNITS: usize = 1000;

/// The parameters of each generated unit in `dirs` (their manifests'), all of `target`'s family.
fn units_of(dirs: &[PathBuf], target: Target) -> Result<Vec<Params>, Failure> {
    if dirs.len() > MAX_UNITS {
        return Err(usage(format!(
            "invalid --unit: {} units; allowed at most {MAX_UNITS}",
            dirs.len()
        )));
    }
    let mut out = Vec::new();
    for dir in dirs {
        let design =
            specgen::cosim::Design::load(dir).map_err(|e| usage(format!("invalid --unit: {e}")))?;
        // its files checked as every other command checks them (the manifest's fingerprint, every
        // listed file's SHA-256, no stray Verilog): what is measured is the unit specgen writes
        // for these parameters, so it is the Verilog in the directory
        design
            .verify_files(false)
            .map_err(|e| usage(format!("invalid --unit: {e}")))?;
        let params = design.plan.cfg.params.clone();
        if params.target != target {
            return Err(usage(format!(
                "invalid --unit: {} is generated for --target {}; this exploration is of --target {} (one family at a time)",
                dir.display(),
                params.target.name(),
                target.name()
            )));
        }
        out.push(params);
    }
    Ok(out)
}

pub fn measure(a: &MeasureArgs) -> Result<(), Failure> {
    let jobs = read_jobs(&a.jobs)?;
    let job = jobs
        .iter()
        .find(|j| j.fingerprint == a.fingerprint)
        .ok_or_else(|| {
            usage(format!(
                "invalid --fingerprint: {} is no job of {}",
                a.fingerprint,
                a.jobs.display()
            ))
        })?;
    if specgen::output::same_file(&a.out, &a.jobs) {
        return Err(usage(format!(
            "invalid --out: {} is the --jobs file this command reads",
            a.out.display()
        )));
    }
    // one run of a job at a time, whoever starts it (a resumed sweep beside a killed one's
    // jobs, two shards on one directory): the lock beside the result is held for the run's
    // life; taken after another run, that run's whole result is this one's
    let lock_path = {
        let mut p = a.out.clone().into_os_string();
        p.push(".lock");
        PathBuf::from(p)
    };
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&lock_path)
        .map_err(|e| Failure::io("open", &lock_path, e))?;
    // (an flock, released when `lock` closes at the end)
    lock.lock()
        .map_err(|e| Failure::io("lock", &lock_path, e))?;
    if explore::whole_result(&a.out, job) {
        outln!(
            "{}: measured already (by a run beside this one): {}",
            job.fingerprint,
            a.out.display()
        )?;
        return Ok(());
    }
    let r = explore::run_job(
        job,
        &specgen::synth::Tools {
            cache: a.cache.clone(),
            ..tools(&a.yosys, &a.nextpnr)
        },
    )?;
    let mut text = serde_json::to_string_pretty(&r).expect("serialises");
    text.push('\n');
    specgen::output::write_file(&a.out, text.as_bytes())
        .map_err(|e| Failure::io("write", &a.out, e))?;
    outln!(
        "{}: {} seed {}: {} MHz, {} logic cells",
        job.fingerprint,
        job.point,
        job.seed,
        r.synth
            .fmax()
            .map_or("no Fmax".into(), |f| format!("{f:.1}")),
        r.synth.cells().map_or("?".into(), |c| c.to_string())
    )?;
    Ok(())
}

/// `generate --max-error`: the exploration's cheapest measured unit meeting the error and the
/// clock, among those with every parameter the user gave (`given`, by `Params`' field name)
/// and the user's interface; its parameters fill in the rest of `params`, and every chosen one
/// is said to be chosen.
#[allow(clippy::too_many_arguments)]
pub fn choose(
    explored: Option<&Path>,
    params: &Params,
    given: &[&str],
    metric: Metric,
    display: specgen::models::display::Display,
    max_error: f64,
    mhz: f64,
) -> Result<Params, Failure> {
    let (text, what) = match explored {
        Some(p) => (specgen::small_file::read(p, 64 << 20).map_err(|e| usage(format!("invalid --explored: {} {e}", p.display())))?, p.display().to_string()),
        None => match specgen::family::of(params.target).explored() {
            Some(t) => (t.to_string(), format!("the built-in exploration of the {}", specgen::timing::part(params.target))),
            None => {
                return Err(usage(format!(
                    "invalid --max-error: no exploration is built in for --target {}; give one with --explored FILE (specgen explore's points.json)",
                    params.target.name()
                )))
            }
        },
    };
    let e = Exploration::from_text(&text, &what)?;
    let c = explore::choose(
        &e,
        &explore::Question {
            base: params,
            given,
            metric,
            max_error,
            mhz,
            display,
        },
    )?;
    let p = &c.point;
    let m = p.measured.as_ref().expect("a choice is measured");
    let lo = m.fmax_seeds.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = m.fmax_seeds.iter().copied().fold(0.0, f64::max);
    let chosen: Vec<String> = [
        ("model", p.params.model.name().to_string()),
        ("cos-frac-bits", p.params.cos_frac_bits.to_string()),
        (
            "intensity-frac-bits",
            p.params.intensity_frac_bits.to_string(),
        ),
        ("stages", p.params.stages.to_string()),
        (
            "dsp-budget",
            p.params.dsp_budget.map_or("none".into(), |b| b.to_string()),
        ),
        ("rom-style", p.params.rom_style.name().to_string()),
    ]
    .into_iter()
    .filter(|(k, _)| !given.contains(&k.replace('-', "_").as_str()))
    .map(|(k, v)| format!("--{k} {v}"))
    .collect();
    errln!(
        "max-error: chose {} ({} error {:.3e} <= {max_error}, recomputed{}): measured {:.1} MHz median over nextpnr seeds {} ({lo:.1}-{hi:.1}), {} logic cells, {} DSP blocks, {} block RAMs, on today's RTL (sha256 {}); jobs {}; tools {}; from {what}",
        p.id,
        metric.name(),
        c.error,
        match (metric.in_display_codes(), metric.at_pixel()) {
            (true, _) => format!(" codes of {}, the cosine rounded to F bits counted", display.name()),
            (false, true) => ", the cosine rounded to F bits counted".to_string(),
            _ => String::new(),
        },
        m.fmax_mhz.unwrap_or(0.0),
        specgen::synth::seed_list(&m.seeds),
        p.cells(),
        m.dsp_blocks,
        m.block_rams,
        &c.rtl[..16],
        m.jobs.join(" "),
        m.tools.iter().map(|(k, v)| format!("{k} {v:?}")).collect::<Vec<_>>().join(", ")
    );
    if !chosen.is_empty() {
        errln!("max-error: chosen for you: {}", chosen.join(" "));
    }
    if let (true, Some(b)) = (given.contains(&"dsp_budget"), params.dsp_budget) {
        if p.params.dsp_budget != Some(b) {
            errln!(
                "max-error: --dsp-budget {b} is met: the unit takes {} DSP blocks written {}, as it was measured (the same RTL)",
                m.dsp_blocks,
                p.params.dsp_budget.map_or("without a budget".to_string(), |x| format!("with --dsp-budget {x}"))
            );
        }
    }
    if !c.stale.is_empty() {
        errln!(
            "max-error: passed over, measured on an older RTL: {}",
            c.stale.join(", ")
        );
    }
    let chosen = &p.params;
    Ok(Params {
        model: chosen.model,
        cos_frac_bits: chosen.cos_frac_bits,
        intensity_frac_bits: chosen.intensity_frac_bits,
        stages: chosen.stages,
        dsp_budget: chosen.dsp_budget,
        rom_style: chosen.rom_style,
        k: chosen.k.clone(),
        k_frac_bits: chosen.k_frac_bits,
        rounding: chosen.rounding,
        arch: chosen.arch,
        max_squarings: chosen.max_squarings,
        fabric_registers: chosen.fabric_registers,
        ..params.clone()
    })
}

/// What a refusal of `--target-mhz` adds: the nearest measured unit of the same model (and
/// budget) that reaches `mhz`, by widths, and how to choose among measured units.
pub fn nearest_measured(params: &Params, mhz: f64) -> Result<String, Failure> {
    let Some(e) = explore::built_in(params.target)? else {
        return Ok(String::new());
    };
    let near = e
        .points
        .iter()
        .filter(|p| {
            p.params.model == params.model
                && p.params.n_bits == params.n_bits
                && p.params.color_bits == params.color_bits
        })
        .filter(|p| p.params.interface == params.interface)
        .filter(|p| {
            p.measured
                .as_ref()
                .and_then(|m| m.fmax_mhz)
                .is_some_and(|f| f >= mhz)
        })
        // a row of another RTL names no unit
        .filter(|p| specgen::explore::measured_today(p).ok().flatten().is_some())
        .min_by_key(|p| {
            let d = p.params.cos_frac_bits.abs_diff(params.cos_frac_bits)
                + p.params
                    .intensity_frac_bits
                    .abs_diff(params.intensity_frac_bits);
            (d, p.params.dsp_budget != params.dsp_budget, p.cells())
        });
    Ok(match near {
        Some(p) => format!(
            "; the nearest measured unit that reaches it: {} (--cos-frac-bits {} --intensity-frac-bits {} --stages {}{}{}{}), {:.1} MHz median over seeds {}; `generate --max-error E --target-mhz {mhz}` chooses among measured units",
            p.id,
            p.params.cos_frac_bits,
            p.params.intensity_frac_bits,
            p.stages,
            p.params.dsp_budget.map_or(String::new(), |b| format!(" --dsp-budget {b}")),
            if p.params.rom_style != Params::default().rom_style { format!(" --rom-style {}", p.params.rom_style.name()) } else { String::new() },
            if p.params.fabric_registers { " --fabric-registers" } else { "" },
            p.fmax().unwrap_or(0.0),
            p.measured.as_ref().map_or(String::new(), |m| specgen::synth::seed_list(&m.seeds))
        ),
        None => format!("; no measured {} unit of the built-in exploration with --interface {} reaches it", params.model.name(), params.interface.name()),
    })
}

/// The parameters of the unit the user gave on the command line (by `Params`' field name):
/// what `--max-error` may not overwrite.
pub fn given_keys(p: &super::ParamArgs, r: &super::RtlArgs) -> Vec<&'static str> {
    let mut given = Vec::new();
    let mut add = |on: bool, key: &'static str| {
        if on {
            given.push(key);
        }
    };
    add(p.model.is_some(), "model");
    add(p.cos_frac_bits.is_some(), "cos_frac_bits");
    add(p.intensity_frac_bits.is_some(), "intensity_frac_bits");
    add(p.k.is_some(), "k");
    add(p.k_frac_bits.is_some(), "k_frac_bits");
    add(p.rounding.is_some(), "rounding");
    add(p.arch.is_some(), "arch");
    add(p.max_squarings.is_some(), "max_squarings");
    add(r.stages.is_some(), "stages");
    add(r.dsp_budget.is_some(), "dsp_budget");
    add(r.rom_style.is_some(), "rom_style");
    add(r.fabric_registers, "fabric_registers");
    add(r.reset.is_some(), "reset");
    given
}
