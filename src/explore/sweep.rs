//! The sweep: jobs under fingerprints, their results, the merge, one job's run.

use super::{Measured, Point, Versions};
use crate::config::{Config, Params, Target};
use crate::error::{input, Error};
use crate::plan::Plan;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// One place-and-route of one unit with one seed: what a sweep's engine runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Job {
    /// [`Job::fingerprint`]: the file its result is stored in is `<fingerprint>.json`
    pub fingerprint: String,
    pub point: String,
    pub seed: u32,
    pub params: Params,
    /// SHA-256 of the unit's RTL and tables as specgen writes them ([`rtl_digest`]): a change
    /// of the generator that changes the unit changes every fingerprint it touches
    pub rtl: String,
    /// specgen's and every tool's version, as each prints it
    pub tools: Versions,
    /// synthesized with the family's hard multipliers (`synth --dsp`, the default); false: the
    /// products in the fabric (`explore --no-dsp`, a bench's LUT-only rows)
    #[serde(default = "with_dsp", skip_serializing_if = "is_true")]
    pub dsp: bool,
}

fn with_dsp() -> bool {
    true
}

fn is_true(b: &bool) -> bool {
    *b
}

impl Job {
    pub fn new(point: &Point, rtl: &str, seed: u32, tools: &Versions) -> Job {
        let mut j = Job {
            fingerprint: String::new(),
            point: point.id.clone(),
            seed,
            params: point.params.clone(),
            rtl: rtl.to_string(),
            tools: tools.clone(),
            dsp: true,
        };
        j.fingerprint = j.compute_fingerprint();
        j
    }
    /// The same job with the products in the fabric (synthesis without the hard multipliers).
    pub fn fabric_only(self) -> Job {
        let mut j = Job { dsp: false, ..self };
        j.fingerprint = j.compute_fingerprint();
        j
    }
    /// SHA-256 (first 20 hex digits) of the parameters, the RTL's digest, the seed and the
    /// tools' versions (and the fabric's products, where the job asks for them: a job with the
    /// hard multipliers keeps the fingerprint it had before jobs could ask otherwise).
    pub fn compute_fingerprint(&self) -> String {
        use sha2::Digest;
        let mut what = serde_json::json!({ "params": self.params, "rtl": self.rtl, "seed": self.seed, "tools": self.tools });
        if !self.dsp {
            what["dsp"] = serde_json::Value::Bool(false);
        }
        let digest = sha2::Sha256::digest(what.to_string().as_bytes());
        digest.iter().take(10).map(|b| format!("{b:02x}")).collect()
    }
}

/// Whether `path` holds a whole result of `job` (its own job, its figures checked against it):
/// a run that finds one has nothing to do. A killed run leaves none half-written (results are
/// written atomically).
pub fn whole_result(path: &std::path::Path, job: &Job) -> bool {
    crate::small_file::read(path, 1 << 20)
        .ok()
        .and_then(|t| serde_json::from_str::<JobResult>(&t).ok())
        .is_some_and(|r| r.job == *job && r.check().is_ok())
}

/// A job's result, stored as `<fingerprint>.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct JobResult {
    pub job: Job,
    pub synth: crate::synth::SynthResult,
}

/// The most result files a merge reads from one directory, and the largest.
const MAX_RESULTS: usize = 200_000;
const MAX_RESULT_BYTES: u64 = 1 << 20;

/// Reads every `*.json` result in `dirs` (a missing directory holds none).
pub fn read_results(dirs: &[&Path]) -> Result<Vec<JobResult>, Error> {
    let mut out = Vec::new();
    for dir in dirs {
        let entries = match std::fs::read_dir(dir) {
            Ok(e) => e,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => return Err(Error::io("read", *dir, e)),
        };
        let mut names: Vec<std::path::PathBuf> = Vec::new();
        for e in entries {
            let e = e.map_err(|e| Error::io("read", *dir, e))?;
            let path = e.path();
            if path.extension().is_some_and(|x| x == "json") {
                names.push(path);
            }
            if names.len() > MAX_RESULTS {
                return Err(input(format!("{} holds more than {MAX_RESULTS} result files; allowed at most {MAX_RESULTS} a directory", dir.display())));
            }
        }
        names.sort();
        for path in names {
            let text = crate::small_file::read(&path, MAX_RESULT_BYTES)
                .map_err(|e| input(format!("{} {e}", path.display())))?;
            let r: JobResult = serde_json::from_str(&text).map_err(|e| {
                input(format!(
                    "{} is not a sweep job's result: {e}",
                    path.display()
                ))
            })?;
            let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
            if stem != r.job.fingerprint || r.job.compute_fingerprint() != r.job.fingerprint {
                return Err(input(format!(
                    "{} is not stored under its job's fingerprint ({}): a result renamed or edited by hand",
                    path.display(),
                    r.job.fingerprint
                )));
            }
            r.check().map_err(|why| {
                input(format!(
                    "{}: the measurement is not its job's: {}",
                    path.display(),
                    why.reason()
                ))
            })?;
            out.push(r);
        }
    }
    Ok(out)
}

impl JobResult {
    /// The measurement is of its job: the model, depth, widths, family, seed and hard
    /// multipliers the job names, and figures a part can hold (an Fmax in (0, the family's
    /// ceiling] MHz, at most the part's logic cells). A result edited by hand, or copied from another job,
    /// fails here whatever its fingerprint says.
    pub fn check(&self) -> Result<(), Error> {
        let (j, s) = (&self.job, &self.synth);
        let p = &j.params;
        let widths = format!(
            "{}/{}/{}/{}",
            p.cos_frac_bits, p.n_bits, p.color_bits, p.intensity_frac_bits
        );
        let mut wrong = Vec::new();
        if s.model != p.model.name() {
            wrong.push(format!("model {:?}, the job's {}", s.model, p.model.name()));
        }
        if s.stages != p.stages {
            wrong.push(format!("stages {}, the job's {}", s.stages, p.stages));
        }
        if s.widths != widths {
            wrong.push(format!("widths {:?}, the job's {widths}", s.widths));
        }
        if s.target != p.target.name() {
            wrong.push(format!(
                "target {:?}, the job's {}",
                s.target,
                p.target.name()
            ));
        }
        if s.dsp != j.dsp {
            wrong.push(format!("dsp {}, the job's {}", s.dsp, j.dsp));
        }
        if s.fmax_mhz.is_some() && s.seeds != [j.seed] {
            wrong.push(format!("seeds {:?}, the job's [{}]", s.seeds, j.seed));
        }
        let ceiling = crate::family::of(p.target).fmax_ceiling_mhz();
        for f in s
            .fmax_mhz
            .iter()
            .chain(&s.fmax_route_mhz)
            .chain(&s.fmax_seeds)
        {
            if !(f.is_finite() && *f > 0.0 && *f <= ceiling) {
                wrong.push(format!(
                    "an Fmax of {f} MHz (the part's place-and-route reaches at most {ceiling})"
                ));
            }
        }
        if let (Some(c), Some(cap)) = (s.logic_cells, crate::family::of(p.target).logic_capacity())
        {
            if c == 0 || c > cap {
                wrong.push(format!("{c} logic cells (the part has {cap})"));
            }
        }
        match wrong.is_empty() {
            true => Ok(()),
            false => Err(input(wrong.join("; "))),
        }
    }
}

/// What a merge found wrong: the jobs of the plan without exactly one result.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct MergeReport {
    pub jobs: usize,
    pub results: usize,
    pub missing: Vec<String>,
    /// jobs with two results that differ (two shards that ran one job, with different outcomes)
    pub conflicting: Vec<String>,
    /// results of no job of this plan (another plan's, or older tools'): never used
    pub unused: usize,
    /// each measured point's results as one over its seeds (`synth --seeds K --json`'s form,
    /// which `report --hw` reads), by point id
    #[serde(skip)]
    pub synth: BTreeMap<String, crate::synth::SynthResult>,
}

/// Fills each point's `measured` from the results of its jobs (a point with any job
/// missing stays estimated).
pub fn merge(points: &mut [Point], jobs: &[Job], results: &[JobResult]) -> MergeReport {
    let mut by: BTreeMap<&str, Vec<&JobResult>> = BTreeMap::new();
    for r in results {
        by.entry(r.job.fingerprint.as_str()).or_default().push(r);
    }
    let mut report = MergeReport {
        jobs: jobs.len(),
        results: results.len(),
        ..Default::default()
    };
    let planned: BTreeSet<&str> = jobs.iter().map(|j| j.fingerprint.as_str()).collect();
    report.unused = results
        .iter()
        .filter(|r| !planned.contains(r.job.fingerprint.as_str()))
        .count();
    let mut one: BTreeMap<&str, &JobResult> = BTreeMap::new();
    for j in jobs {
        match by.get(j.fingerprint.as_str()).map(Vec::as_slice) {
            None | Some([]) => report
                .missing
                .push(format!("{} ({} seed {})", j.fingerprint, j.point, j.seed)),
            Some([r]) => {
                one.insert(&j.fingerprint, r);
            }
            Some(rs) => {
                let first = serde_json::to_string(&rs[0].synth).unwrap_or_default();
                match rs
                    .iter()
                    .all(|r| serde_json::to_string(&r.synth).unwrap_or_default() == first)
                {
                    true => {
                        one.insert(&j.fingerprint, rs[0]);
                    }
                    false => report
                        .conflicting
                        .push(format!("{} ({} seed {})", j.fingerprint, j.point, j.seed)),
                }
            }
        }
    }
    for p in points.iter_mut() {
        let mine: Vec<&Job> = jobs.iter().filter(|j| j.point == p.id).collect();
        if mine.is_empty()
            || mine
                .iter()
                .any(|j| !one.contains_key(j.fingerprint.as_str()))
        {
            p.measured = None;
            continue;
        }
        let rs: Vec<&JobResult> = mine.iter().map(|j| one[j.fingerprint.as_str()]).collect();
        let s0 = &rs[0].synth;
        let whole: Vec<crate::synth::SynthResult> = rs.iter().map(|r| r.synth.clone()).collect();
        if let Some(w) = crate::synth::SynthResult::over_seeds(&whole) {
            report.synth.insert(p.id.clone(), w);
        }
        let fmax_seeds: Vec<f64> = rs.iter().filter_map(|r| r.synth.fmax_mhz).collect();
        let failed = rs.iter().find(|r| r.synth.fmax_mhz.is_none());
        let cells: Vec<f64> = rs
            .iter()
            .filter_map(|r| r.synth.logic_cells.map(|c| c as f64))
            .collect();
        p.measured = Some(Measured {
            seeds: mine.iter().map(|j| j.seed).collect(),
            fmax_mhz: if failed.is_some() {
                None
            } else {
                crate::synth::median(&fmax_seeds)
            },
            fmax_seeds,
            route_seeds: rs.iter().filter_map(|r| r.synth.fmax_route_mhz).collect(),
            logic_cells: crate::synth::median(&cells).map(|c| c.round() as u64),
            luts: s0.luts,
            flip_flops: s0.flip_flops,
            dsp_blocks: s0.dsp_blocks,
            block_rams: s0.block_rams,
            limited_by: s0.fmax_limited_by.clone(),
            note: failed.map_or_else(|| s0.fmax_note.clone(), |r| r.synth.fmax_note.clone()),
            jobs: mine.iter().map(|j| j.fingerprint.clone()).collect(),
            tools: rs[0].job.tools.clone(),
        });
    }
    report
}

pub use crate::emit::rtl_digest;

/// The jobs that measure `ids` over `seeds`.
pub fn jobs_of(
    points: &[Point],
    ids: &[String],
    seeds: &[u32],
    tools: &Versions,
) -> Result<Vec<Job>, Error> {
    let want: BTreeSet<&String> = ids.iter().collect();
    let mut jobs = Vec::new();
    for p in points.iter().filter(|p| want.contains(&p.id)) {
        let rtl = rtl_digest(&Plan::new(Config::new(p.params.clone())?)?);
        jobs.extend(seeds.iter().map(|&s| Job::new(p, &rtl, s, tools)));
    }
    Ok(jobs)
}

/// Runs one job: generates its unit in a temporary directory and synthesizes it with its seed.
/// Refused when the tools here are not the ones the job was planned with (its result would be
/// stored under a fingerprint that does not describe it).
pub fn run_job(job: &Job, tools: &crate::synth::Tools) -> Result<JobResult, Error> {
    if job.compute_fingerprint() != job.fingerprint {
        return Err(input(format!(
            "job {} does not match its fingerprint: the plan was edited",
            job.fingerprint
        )));
    }
    let here = tool_versions(job.params.target, tools)?;
    if here != job.tools {
        let diff: Vec<String> = job
            .tools
            .iter()
            .filter(|(k, v)| here.get(*k) != Some(v))
            .map(|(k, v)| format!("{k}: planned {v:?}, here {:?}", here.get(k)))
            .collect();
        return Err(input(format!(
            "job {}: the tools here are not those it was planned with ({}); plan again with `specgen explore`",
            job.fingerprint,
            diff.join("; ")
        )));
    }
    let plan = Plan::new(Config::new(job.params.clone())?)?;
    if rtl_digest(&plan) != job.rtl {
        return Err(input(format!(
            "job {}: this specgen writes another unit for its parameters than the one it was planned with; plan again with `specgen explore`",
            job.fingerprint
        )));
    }
    let dir = crate::process::temp_dir()
        .map_err(|e| Error::io("create a temporary directory in", std::env::temp_dir(), e))?;
    let unit = dir.path().join("unit");
    crate::output::write_dir_atomically(&unit, &crate::emit::generate_files(&plan))?;
    let design = crate::cosim::Design::load(&unit)?;
    // IceStorm's second opinion is not part of an exploration's figures: not run
    let tools = &crate::synth::Tools {
        icetime: String::new(),
        ..tools.clone()
    };
    let synth =
        crate::synth::synthesize(&design, job.params.target, job.dsp, tools, &[job.seed])?.result;
    Ok(JobResult {
        job: job.clone(),
        synth,
    })
}

/// specgen's version and each tool's as it prints it (yosys, the family's nextpnr): part of
/// every job's fingerprint.
pub fn tool_versions(target: Target, tools: &crate::synth::Tools) -> Result<Versions, Error> {
    let mut v = BTreeMap::new();
    v.insert("specgen".to_string(), crate::names::VERSION.to_string());
    v.insert(
        "yosys".to_string(),
        crate::synth::version_of(&tools.yosys, "-V")?,
    );
    if let Some(pnr) = crate::synth::pnr_tool(target, tools)? {
        v.insert(
            "nextpnr".to_string(),
            crate::synth::version_of(&pnr, "--version")?,
        );
    }
    Ok(v)
}
