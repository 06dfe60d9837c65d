//! `specgen explore`: which unit meets an error and a clock at the least cost — a space of
//! units (models, widths, depths, `--dsp-budget`, `--rom-style`, one target), each point's
//! accuracy and cost, and the Pareto front of accuracy against hardware.
//!
//! **What a point is.** A configuration: the user's fixed parameters (the exponent's and the
//! colours' widths, the interface) with one model, one `cos_g` width F, one intensity width
//! FI, one budget, one ROM style and one depth. The depths of a (model, widths) are the
//! shallowest that the delay model predicts at each of the family's explore clocks
//! (`Family::explore_clocks`), and the deepest: a clock is what a user asks for, and a depth
//! past the shallowest that reaches it only costs registers.
//!
//! **Accuracy** comes from the golden model, over every `(cos_g ≤ 1.0, n)` where the space
//! allows (`models::blinn_fidelity`: max, mean and RMS of `|intensity − cos^n|`), and from the
//! picture a user sees (`render::image_figures`: the sphere's PSNR and the largest step between
//! neighbouring pixels beyond the float image's, which is how banding shows). Every depth,
//! budget and ROM style of a (model, widths) computes the same function, so it is measured once.
//!
//! **Cost** is estimated for every point from its datapath (`estimate`: LUTs from each wire's
//! kind and width, flip-flops from every registered cut's live bits, hard blocks from the
//! plan, Fmax from the delay model) and *measured* for the points on or near the estimated
//! front: each is a set of jobs, one `synth` of one unit with one nextpnr seed, whose result is
//! stored under the job's fingerprint (`Job::fingerprint`: the parameters, the seed, and the
//! versions of specgen and of every tool), so a result is reused only for exactly the job that
//! made it. The jobs run on an existing engine (Snakemake, `scripts/sweep/Snakefile`); `merge`
//! takes the result directories of any number of shards and names every job of the plan
//! without exactly one result.
//!
//! **The front** is drawn per clock: among the points whose Fmax (measured median over seeds
//! where there is one, else the delay model's prediction) reaches the clock, those that no
//! other point beats on both error and logic cells. [`choose`] answers `generate --max-error E
//! --target-mhz F` from measured points only.
//!
//! The library returns files; writing them is the caller's.

use crate::config::{Config, Params, RomStyle, SpecularModel, Target};
use crate::datapath::Kind;
use crate::error::{input, Error};
use crate::models::{blinn_fidelity, Model};
use crate::plan::Plan;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The space to explore: the user's base parameters and the values each axis takes.
#[derive(Debug, Clone)]
pub struct Space {
    /// the fixed parameters (target, n_bits, color_bits, interface, …)
    pub base: Params,
    pub models: Vec<SpecularModel>,
    pub cos_frac_bits: Vec<u32>,
    pub intensity_frac_bits: Vec<u32>,
    /// `None`: no budget
    pub dsp_budgets: Vec<Option<u32>>,
    pub rom_styles: Vec<RomStyle>,
    /// the clocks a depth is chosen for; empty: the family's `explore_clocks`
    pub clocks: Vec<f64>,
}

impl Space {
    /// The clocks of this space: the asked ones, else the family's.
    pub fn clocks(&self) -> Vec<f64> {
        match self.clocks.is_empty() {
            true => crate::family::of(self.base.target).explore_clocks().to_vec(),
            false => self.clocks.clone(),
        }
    }
}

/// How far a unit is from Blinn's `cos^n`, on its whole input space and in a picture.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Accuracy {
    /// max |intensity − cos^n| over every (cos_g ≤ 1.0, n), full scale
    pub max: f64,
    pub mean: f64,
    pub rms: f64,
    /// the (cos_g, n) points visited (all of them where the space allows)
    pub points: u64,
    /// 1: every cos_g code; k: every k-th
    pub stride: u32,
    /// the sphere of `render` (n = 1, 4, 16, 128 where the exponent's width allows, 128²
    /// pixels) against float cos^n at the exact cos δ
    pub psnr_db: f64,
    pub max_step_excess: f64,
}

/// The metric `--max-error` bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    Max,
    Mean,
    Rms,
    /// the largest step between neighbouring pixels beyond the float image's
    Step,
}

impl Metric {
    pub const ALL: [Metric; 4] = [Metric::Max, Metric::Mean, Metric::Rms, Metric::Step];
    pub fn name(self) -> &'static str {
        match self {
            Metric::Max => "max",
            Metric::Mean => "mean",
            Metric::Rms => "rms",
            Metric::Step => "step",
        }
    }
    pub fn of(self, a: &Accuracy) -> f64 {
        match self {
            Metric::Max => a.max,
            Metric::Mean => a.mean,
            Metric::Rms => a.rms,
            Metric::Step => a.max_step_excess,
        }
    }
}

/// The exponents of the picture figures: `render`'s defaults that the exponent's width holds.
fn picture_exponents(n_bits: u32) -> Vec<u32> {
    [1u32, 4, 16, 128].into_iter().filter(|&n| n < 1 << n_bits).collect()
}

/// The accuracy of a model (every depth of it computes the same function).
pub fn accuracy(model: &Model) -> Accuracy {
    let f = blinn_fidelity(model);
    let img = crate::render::image_figures(model, &picture_exponents(model.cfg.n_bits()), 128);
    Accuracy { max: f.max, mean: f.mean, rms: f.rms, points: f.points, stride: f.stride, psnr_db: img.psnr_db, max_step_excess: img.max_step_excess }
}

/// A point's cost from its datapath, before any synthesis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    pub luts: u64,
    pub flip_flops: u64,
    /// logic cells (a LUT and a flip-flop share one): LUTs plus half the flip-flops
    pub logic_cells: u64,
    pub dsp_blocks: u64,
    pub block_rams: u64,
    /// the delay model's prediction (none where no delay model speaks for the family)
    pub fmax_mhz: Option<f64>,
    /// the delay model's inputs: the slowest and the mean stretch between registers
    /// (`Plan::stage_delay`, `Plan::stage_delay_mean`)
    pub stage_delay: f64,
    pub stage_delay_mean: f64,
}

/// The cost estimate of a plan: each wire by its kind (a sum or logic a LUT a bit, a table
/// in LUTs two, a product the family leaves in LUTs half its partial-product bits, a product
/// on a block none), every registered cut's live bits a flip-flop each.
pub fn estimate(plan: &Plan) -> Estimate {
    let dp = &plan.datapath;
    let family = crate::family::of(plan.cfg.target());
    let mut luts = 0u64;
    for w in dp.steps.iter().flat_map(|s| &s.wires) {
        luts += match w.kind {
            Kind::Select => 0,
            Kind::Sum | Kind::Logic => w.width as u64,
            Kind::Table => 2 * w.width as u64,
            Kind::Product(a, b) if family.product_blocks(a, b, w.width) == 0 => (a as u64 * b as u64).div_ceil(2),
            Kind::Product(..) => 0,
        };
    }
    let flip_flops: u64 = dp.registered.iter().filter_map(|&k| dp.live.get(k as usize - 1)).flatten().map(|l| l.width as u64).sum();
    let dsp_blocks = dp.product_uses.iter().filter(|u| !u.fabric).map(|u| u.blocks as u64).sum();
    let block_rams = dp.reads.iter().filter(|r| r.block).map(|r| r.table).collect::<BTreeSet<_>>().len() as u64;
    Estimate {
        luts,
        flip_flops,
        logic_cells: luts + flip_flops.div_ceil(2),
        dsp_blocks,
        block_rams,
        fmax_mhz: crate::timing::predicted_fmax(plan),
        stage_delay: plan.stage_delay(),
        stage_delay_mean: plan.stage_delay_mean(),
    }
}

/// A point's figures measured by place-and-route, over its seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    pub seeds: Vec<u32>,
    /// each seed's Fmax, capped by the limits of the blocks the unit uses
    pub fmax_seeds: Vec<f64>,
    /// their median (None: place-and-route failed, typically the unit does not fit)
    pub fmax_mhz: Option<f64>,
    /// nextpnr's own figure of each seed (its routes, before the blocks' limits): what the
    /// delay model is fitted to
    #[serde(default)]
    pub route_seeds: Vec<f64>,
    pub logic_cells: Option<u64>,
    pub luts: u64,
    pub flip_flops: u64,
    pub dsp_blocks: u64,
    pub block_rams: u64,
    /// what limits the clock (routing, or a block's own limit)
    pub limited_by: String,
    /// why Fmax is missing, or what makes it an upper bound
    pub note: String,
    /// the jobs' fingerprints, seed order
    pub jobs: Vec<String>,
    /// the tools that measured it
    pub tools: BTreeMap<String, String>,
}

/// One configuration of the space.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// `<model>-f<F>-fi<FI>-s<stages>[-b<budget>][-<rom style>]`
    pub id: String,
    pub model: String,
    pub cos_frac_bits: u32,
    pub intensity_frac_bits: u32,
    pub stages: u32,
    pub dsp_budget: Option<u32>,
    pub rom_style: String,
    /// the clocks whose shallowest predicted depth this is (empty: the deepest)
    pub chosen_for: Vec<f64>,
    /// the parameters `generate --config` takes to build it
    pub params: Params,
    pub accuracy: Accuracy,
    pub estimate: Estimate,
    pub measured: Option<Measured>,
    /// the clocks at whose front it stands
    pub front: Vec<f64>,
}

impl Point {
    /// Fmax as the front reads it: measured where measured, else predicted.
    pub fn fmax(&self) -> Option<f64> {
        match &self.measured {
            Some(m) => m.fmax_mhz,
            None => self.estimate.fmax_mhz,
        }
    }
    /// Logic cells as the front reads them: measured where measured, else estimated.
    pub fn cells(&self) -> u64 {
        self.measured.as_ref().and_then(|m| m.logic_cells).unwrap_or(self.estimate.logic_cells)
    }
}

fn point_id(p: &Params) -> String {
    let mut id = format!("{}-f{}-fi{}-s{}", p.model.name(), p.cos_frac_bits, p.intensity_frac_bits, p.stages);
    if let Some(b) = p.dsp_budget {
        id.push_str(&format!("-b{b}"));
    }
    if p.rom_style != RomStyle::File {
        id.push_str(&format!("-{}", p.rom_style.name()));
    }
    id
}

/// The shallowest depth of `plan`'s configuration predicted to reach `mhz` (a bisection: the
/// prediction grows with depth), or the deepest where none is; None without a delay model.
fn depth_for(plan: &Plan, mhz: f64, at: &mut BTreeMap<u32, Option<f64>>) -> Result<Option<u32>, Error> {
    let mut predicted = |d: u32| -> Result<Option<f64>, Error> {
        if let Some(f) = at.get(&d) {
            return Ok(*f);
        }
        let f = crate::timing::predicted_fmax(&plan.with_stages(d)?);
        at.insert(d, f);
        Ok(f)
    };
    let deepest = plan.cut_points;
    match predicted(deepest)? {
        None => return Ok(None),
        Some(f) if f < mhz => return Ok(Some(deepest)),
        Some(_) => {}
    }
    let (mut lo, mut hi) = (0u32, deepest);
    while lo < hi {
        let mid = (lo + hi) / 2;
        match predicted(mid)? {
            Some(f) if f >= mhz => hi = mid,
            _ => lo = mid + 1,
        }
    }
    Ok(Some(lo))
}

/// Every point of the space, with its accuracy and estimate. `progress` hears each (model,
/// widths) as it is done: (done, of).
pub fn points(space: &Space, progress: &dyn Fn(usize, usize)) -> Result<Vec<Point>, Error> {
    let clocks = space.clocks();
    let mut shapes = Vec::new();
    for &model in &space.models {
        for &f in &space.cos_frac_bits {
            for &fi in &space.intensity_frac_bits {
                shapes.push((model, f, fi));
            }
        }
    }
    let mut out = Vec::new();
    for (i, &(model, f, fi)) in shapes.iter().enumerate() {
        let base = Params { model, cos_frac_bits: f, intensity_frac_bits: fi, stages: 0, ..space.base.clone() };
        let cfg = Config::new(base.clone())?;
        let golden = Model::new(&cfg);
        let acc = accuracy(&golden);
        for &budget in &space.dsp_budgets {
            for &rom in &space.rom_styles {
                let params = Params { dsp_budget: budget, rom_style: rom, ..base.clone() };
                let cfg = match Config::new(params) {
                    Ok(c) => c,
                    // a style the family does not write, a budget out of range: not in the space
                    Err(_) => continue,
                };
                let plan = Plan::for_model(golden.with_config(cfg))?;
                let mut depths: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
                let mut at = BTreeMap::new();
                for &mhz in &clocks {
                    if let Some(d) = depth_for(&plan, mhz, &mut at)? {
                        depths.entry(d).or_default().push(mhz);
                    }
                }
                depths.entry(plan.cut_points).or_default();
                if clocks.is_empty() || at.values().all(Option::is_none) {
                    // no delay model: a quarter, half, three quarters and all of the cuts
                    for q in 1..=3 {
                        depths.entry(plan.cut_points * q / 4).or_default();
                    }
                }
                for (stages, chosen_for) in depths {
                    let p = plan.with_stages(stages)?;
                    out.push(Point {
                        id: point_id(&p.cfg.params),
                        model: model.name().to_string(),
                        cos_frac_bits: f,
                        intensity_frac_bits: fi,
                        stages,
                        dsp_budget: budget,
                        rom_style: rom.name().to_string(),
                        chosen_for,
                        params: p.cfg.params.clone(),
                        accuracy: acc,
                        estimate: estimate(&p),
                        measured: None,
                        front: Vec::new(),
                    });
                }
            }
        }
        progress(i + 1, shapes.len());
    }
    Ok(out)
}

/// The front at `mhz` by `metric`: the ids of the points reaching the clock that no other point
/// beats on both error and logic cells (ties kept).
pub fn front_at(points: &[Point], metric: Metric, mhz: f64) -> Vec<String> {
    let mut reach: Vec<&Point> = points.iter().filter(|p| p.fmax().is_some_and(|f| f >= mhz)).collect();
    reach.sort_by(|a, b| a.cells().cmp(&b.cells()).then(metric.of(&a.accuracy).total_cmp(&metric.of(&b.accuracy))).then(a.id.cmp(&b.id)));
    let mut best = f64::INFINITY;
    let mut ids = Vec::new();
    for p in reach {
        let e = metric.of(&p.accuracy);
        if e < best {
            best = e;
            ids.push(p.id.clone());
        }
    }
    ids
}

/// Marks every point's `front` with the clocks at whose front it stands.
pub fn mark_fronts(points: &mut [Point], metric: Metric, clocks: &[f64]) {
    for p in points.iter_mut() {
        p.front.clear();
    }
    for &mhz in clocks {
        let ids: BTreeSet<String> = front_at(points, metric, mhz).into_iter().collect();
        for p in points.iter_mut().filter(|p| ids.contains(&p.id)) {
            p.front.push(mhz);
        }
    }
}

/// The points to measure: at each clock, those predicted within `slack` of it (the delay model
/// is a guide) that stand on the estimated front or within `near` of its cells (a point whose
/// estimated cells are at most `(1 + near)` times those of the cheapest front point at least as
/// accurate).
pub fn candidates(points: &[Point], metric: Metric, clocks: &[f64], near: f64, slack: f64) -> Vec<String> {
    let mut ids = BTreeSet::new();
    // a unit that needs more hard multipliers than the part has does not fit: not measured
    let fits = |p: &&Point| crate::family::of(p.params.target).dsp_capacity().is_none_or(|c| p.estimate.dsp_blocks <= c);
    let estimated: Vec<Point> = points.iter().filter(fits).map(|p| Point { measured: None, ..p.clone() }).collect();
    for &mhz in clocks {
        let reach: Vec<&Point> = estimated.iter().filter(|p| p.estimate.fmax_mhz.is_none_or(|f| f >= mhz * slack)).collect();
        let owned: Vec<Point> = reach.iter().map(|&p| Point { estimate: Estimate { fmax_mhz: Some(mhz), ..p.estimate }, ..p.clone() }).collect();
        let front: Vec<&Point> = front_at(&owned, metric, mhz).iter().filter_map(|id| owned.iter().find(|p| &p.id == id)).collect();
        for p in &owned {
            let e = metric.of(&p.accuracy);
            let cheapest = front.iter().filter(|q| metric.of(&q.accuracy) <= e).map(|q| q.cells()).min();
            if cheapest.is_some_and(|c| p.cells() as f64 <= (1.0 + near) * c as f64) {
                ids.insert(p.id.clone());
            }
        }
    }
    points.iter().filter(|p| ids.contains(&p.id)).map(|p| p.id.clone()).collect()
}

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
    pub tools: BTreeMap<String, String>,
}

impl Job {
    pub fn new(point: &Point, rtl: &str, seed: u32, tools: &BTreeMap<String, String>) -> Job {
        let mut j = Job { fingerprint: String::new(), point: point.id.clone(), seed, params: point.params.clone(), rtl: rtl.to_string(), tools: tools.clone() };
        j.fingerprint = j.compute_fingerprint();
        j
    }
    /// SHA-256 (first 20 hex digits) of the parameters, the RTL's digest, the seed and the
    /// tools' versions.
    pub fn compute_fingerprint(&self) -> String {
        use sha2::Digest;
        let what = serde_json::json!({ "params": self.params, "rtl": self.rtl, "seed": self.seed, "tools": self.tools });
        let digest = sha2::Sha256::digest(what.to_string().as_bytes());
        digest.iter().take(10).map(|b| format!("{b:02x}")).collect()
    }
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
            let text = crate::small_file::read(&path, MAX_RESULT_BYTES).map_err(|e| input(format!("{} {e}", path.display())))?;
            let r: JobResult = serde_json::from_str(&text).map_err(|e| input(format!("{} is not a sweep job's result: {e}", path.display())))?;
            let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
            if stem != r.job.fingerprint || r.job.compute_fingerprint() != r.job.fingerprint {
                return Err(input(format!(
                    "{} is not stored under its job's fingerprint ({}): a result renamed or edited by hand",
                    path.display(),
                    r.job.fingerprint
                )));
            }
            out.push(r);
        }
    }
    Ok(out)
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
}

/// Fills each point's `measured` from the results of its jobs (a point with any job
/// missing stays estimated).
pub fn merge(points: &mut [Point], jobs: &[Job], results: &[JobResult]) -> MergeReport {
    let mut by: BTreeMap<&str, Vec<&JobResult>> = BTreeMap::new();
    for r in results {
        by.entry(r.job.fingerprint.as_str()).or_default().push(r);
    }
    let mut report = MergeReport { jobs: jobs.len(), results: results.len(), ..Default::default() };
    let planned: BTreeSet<&str> = jobs.iter().map(|j| j.fingerprint.as_str()).collect();
    report.unused = results.iter().filter(|r| !planned.contains(r.job.fingerprint.as_str())).count();
    let mut one: BTreeMap<&str, &JobResult> = BTreeMap::new();
    for j in jobs {
        match by.get(j.fingerprint.as_str()).map(Vec::as_slice) {
            None | Some([]) => report.missing.push(format!("{} ({} seed {})", j.fingerprint, j.point, j.seed)),
            Some([r]) => {
                one.insert(&j.fingerprint, r);
            }
            Some(rs) => {
                let first = serde_json::to_string(&rs[0].synth).unwrap_or_default();
                match rs.iter().all(|r| serde_json::to_string(&r.synth).unwrap_or_default() == first) {
                    true => {
                        one.insert(&j.fingerprint, rs[0]);
                    }
                    false => report.conflicting.push(format!("{} ({} seed {})", j.fingerprint, j.point, j.seed)),
                }
            }
        }
    }
    for p in points.iter_mut() {
        let mine: Vec<&Job> = jobs.iter().filter(|j| j.point == p.id).collect();
        if mine.is_empty() || mine.iter().any(|j| !one.contains_key(j.fingerprint.as_str())) {
            p.measured = None;
            continue;
        }
        let rs: Vec<&JobResult> = mine.iter().map(|j| one[j.fingerprint.as_str()]).collect();
        let s0 = &rs[0].synth;
        let fmax_seeds: Vec<f64> = rs.iter().filter_map(|r| r.synth.fmax_mhz).collect();
        let failed = rs.iter().find(|r| r.synth.fmax_mhz.is_none());
        let cells: Vec<f64> = rs.iter().filter_map(|r| r.synth.logic_cells.map(|c| c as f64)).collect();
        p.measured = Some(Measured {
            seeds: mine.iter().map(|j| j.seed).collect(),
            fmax_mhz: if failed.is_some() { None } else { crate::synth::median(&fmax_seeds) },
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

/// SHA-256 of what synthesis reads of a unit: its Verilog and table files as specgen writes them
/// (not the manifest, the testbench or the vectors).
pub fn rtl_digest(plan: &Plan) -> String {
    use sha2::Digest;
    let mut h = sha2::Sha256::new();
    let tb = format!("{}_tb.sv", plan.cfg.top());
    let vectors = format!("{}_vectors.hex", plan.cfg.top());
    for (name, bytes) in crate::emit::generate_files(plan) {
        if (name.ends_with(".v") || name.ends_with(".hex")) && name != tb && name != vectors {
            h.update(name.as_bytes());
            h.update((bytes.len() as u64).to_le_bytes());
            h.update(&bytes);
        }
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// The jobs that measure `ids` over `seeds`.
pub fn jobs_of(points: &[Point], ids: &[String], seeds: &[u32], tools: &BTreeMap<String, String>) -> Result<Vec<Job>, Error> {
    let want: BTreeSet<&String> = ids.iter().collect();
    let mut jobs = Vec::new();
    for p in points.iter().filter(|p| want.contains(&p.id)) {
        let rtl = rtl_digest(&Plan::new(Config::new(p.params.clone())?)?);
        jobs.extend(seeds.iter().map(|&s| Job::new(p, &rtl, s, tools)));
    }
    Ok(jobs)
}

/// A whole exploration as it is stored (`points.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Exploration {
    pub generator: String,
    pub version: String,
    pub target: String,
    pub part: String,
    pub metric: String,
    pub clocks: Vec<f64>,
    pub seeds: Vec<u32>,
    pub points: Vec<Point>,
}

impl Exploration {
    /// Reads an exploration (`points.json`), at most 64 MiB.
    pub fn from_text(text: &str, what: &str) -> Result<Exploration, Error> {
        let e: Exploration = serde_json::from_str(text).map_err(|e| input(format!("{what} is not an exploration (`specgen explore`'s points.json): {e}")))?;
        if e.generator != "specgen" {
            return Err(input(format!("{what} is not an exploration written by specgen")));
        }
        Ok(e)
    }
}

/// The most points an exploration holds.
pub const MAX_POINTS: usize = 20_000;

fn csv(points: &[Point]) -> String {
    let mut s = String::from("id,model,cos_frac_bits,intensity_frac_bits,stages,dsp_budget,rom_style,error_max,error_mean,error_rms,psnr_db,max_step_excess,est_logic_cells,est_dsp_blocks,est_block_rams,est_fmax_mhz,measured_seeds,fmax_mhz,fmax_min,fmax_max,logic_cells,dsp_blocks,block_rams,limited_by,front_mhz\n");
    let opt = |v: Option<f64>| v.map_or(String::new(), |f| format!("{f:.1}"));
    for p in points {
        let m = p.measured.as_ref();
        let lo = m.and_then(|m| m.fmax_seeds.iter().copied().reduce(f64::min));
        let hi = m.and_then(|m| m.fmax_seeds.iter().copied().reduce(f64::max));
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{:.6e},{:.6e},{:.6e},{:.2},{:.6e},{},{},{},{},{},{},{},{},{},{},{},\"{}\",{}\n",
            p.id,
            p.model,
            p.cos_frac_bits,
            p.intensity_frac_bits,
            p.stages,
            p.dsp_budget.map_or(String::new(), |b| b.to_string()),
            p.rom_style,
            p.accuracy.max,
            p.accuracy.mean,
            p.accuracy.rms,
            p.accuracy.psnr_db,
            p.accuracy.max_step_excess,
            p.estimate.logic_cells,
            p.estimate.dsp_blocks,
            p.estimate.block_rams,
            opt(p.estimate.fmax_mhz),
            m.map_or(String::new(), |m| m.seeds.iter().map(u32::to_string).collect::<Vec<_>>().join(" ")),
            opt(m.and_then(|m| m.fmax_mhz)),
            opt(lo),
            opt(hi),
            m.and_then(|m| m.logic_cells).map_or(String::new(), |c| c.to_string()),
            m.map_or(String::new(), |m| m.dsp_blocks.to_string()),
            m.map_or(String::new(), |m| m.block_rams.to_string()),
            m.map_or(String::new(), |m| m.limited_by.replace('"', "'")),
            p.front.iter().map(|f| format!("{f}")).collect::<Vec<_>>().join(" "),
        ));
    }
    s
}

/// The measured points as the delay model's calibration rows (`data/delay_calibration.csv`'s
/// columns: family, datapath, stages, the two stretch estimates, nextpnr's median over the
/// seeds and each seed's, and the generate flags beyond the defaults).
pub fn calibration_csv(e: &Exploration) -> String {
    let mut s = String::from("family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args\n");
    let defaults = Params::default();
    for p in &e.points {
        let Some(m) = p.measured.as_ref().filter(|m| m.route_seeds.len() == m.seeds.len() && !m.route_seeds.is_empty()) else { continue };
        let Ok(cfg) = Config::new(p.params.clone()) else { continue };
        let mut args = Vec::new();
        for (flag, v, d) in [
            ("--cos-frac-bits", p.params.cos_frac_bits, defaults.cos_frac_bits),
            ("--n-bits", p.params.n_bits, defaults.n_bits),
            ("--color-bits", p.params.color_bits, defaults.color_bits),
            ("--intensity-frac-bits", p.params.intensity_frac_bits, defaults.intensity_frac_bits),
        ] {
            if v != d {
                args.push(format!("{flag} {v}"));
            }
        }
        if let Some(b) = p.params.dsp_budget {
            args.push(format!("--dsp-budget {b}"));
        }
        if p.params.rom_style != defaults.rom_style {
            args.push(format!("--rom-style {}", p.params.rom_style.name()));
        }
        s.push_str(&format!(
            "{},{},{},{:.1},{:.2},{:.2},{},{}\n",
            e.target,
            cfg.datapath_name(),
            p.stages,
            p.estimate.stage_delay,
            p.estimate.stage_delay_mean,
            crate::synth::median(&m.route_seeds).unwrap_or(0.0),
            m.route_seeds.iter().map(|f| format!("{f:.2}")).collect::<Vec<_>>().join(" "),
            args.join(" ")
        ));
    }
    s
}

/// The colour of a model in the figure.
fn colour(model: &str) -> plotters::style::RGBColor {
    use plotters::style::RGBColor;
    match SpecularModel::ALL.iter().position(|m| m.name() == model) {
        Some(0) => RGBColor(31, 119, 180),
        Some(1) => RGBColor(214, 39, 40),
        Some(2) => RGBColor(44, 160, 44),
        Some(3) => RGBColor(255, 127, 14),
        _ => RGBColor(148, 103, 189),
    }
}

/// The figure: error (log axis) against logic cells, one colour per model, measured points
/// filled and estimated ones hollow, each clock's front a line.
pub fn svg(e: &Exploration, metric: Metric) -> String {
    use plotters::prelude::*;
    let mut out = String::new();
    let pts: Vec<&Point> = e.points.iter().filter(|p| metric.of(&p.accuracy) > 0.0).collect();
    let emin = pts.iter().map(|p| metric.of(&p.accuracy)).fold(f64::INFINITY, f64::min).min(1e-3) / 2.0;
    let emax = pts.iter().map(|p| metric.of(&p.accuracy)).fold(0.0, f64::max).max(1e-2) * 2.0;
    let cmax = pts.iter().map(|p| p.cells()).max().unwrap_or(100) as f64 * 1.08;
    {
        let root = SVGBackend::with_string(&mut out, (900, 600)).into_drawing_area();
        root.fill(&WHITE).expect("svg");
        let title = format!("{}: {} error vs logic cells ({}), filled = measured", e.part, metric.name(), e.target);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..cmax, (emin..emax).log_scale())
            .expect("svg chart");
        chart
            .configure_mesh()
            .x_desc("logic cells (measured where filled, else estimated)")
            .y_desc(format!("{} |intensity - cos^n|", metric.name()))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .expect("svg mesh");
        let styles = [BLACK, RGBColor(100, 100, 100), RGBColor(170, 170, 170), RGBColor(210, 210, 210)];
        for (i, &mhz) in e.clocks.iter().enumerate().rev() {
            let mut line: Vec<(f64, f64)> = pts.iter().filter(|p| p.front.contains(&mhz)).map(|p| (p.cells() as f64, metric.of(&p.accuracy))).collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            let style = styles[i.min(3)];
            chart
                .draw_series(LineSeries::new(line, style.stroke_width(2)))
                .expect("svg front")
                .label(format!("front at {mhz} MHz"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], style.stroke_width(2)));
        }
        for m in SpecularModel::ALL {
            let name = m.name();
            let c = colour(name);
            let mine: Vec<&&Point> = pts.iter().filter(|p| p.model == name).collect();
            if mine.is_empty() {
                continue;
            }
            chart
                .draw_series(mine.iter().map(|p| {
                    let filled = p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some());
                    Circle::new((p.cells() as f64, metric.of(&p.accuracy)), 4, if filled { c.filled() } else { c.stroke_width(1) })
                }))
                .expect("svg points")
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .expect("svg legend");
        root.present().expect("svg");
    }
    out
}

/// The front at each clock as CSV: clock, then the front's points, cheapest first.
fn front_csv(e: &Exploration, metric: Metric) -> String {
    let mut s = format!("clock_mhz,id,{}_error,logic_cells,fmax_mhz,measured\n", metric.name());
    for &mhz in &e.clocks {
        let mut on: Vec<&Point> = e.points.iter().filter(|p| p.front.contains(&mhz)).collect();
        on.sort_by_key(|p| p.cells());
        for p in on {
            s.push_str(&format!(
                "{mhz},{},{:.6e},{},{},{}\n",
                p.id,
                metric.of(&p.accuracy),
                p.cells(),
                p.fmax().map_or(String::new(), |f| format!("{f:.1}")),
                p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some())
            ));
        }
    }
    s
}

/// The files of an exploration: `points.json` (everything), `points.csv`, `front.csv`,
/// `front.svg`, `jobs.json` (the measuring plan), `merge.json` (what the merge found) and
/// `explore.json`, the directory's manifest.
pub fn files(e: &Exploration, metric: Metric, jobs: &[Job], merge: &MergeReport) -> Vec<(String, Vec<u8>)> {
    let json = |v: &dyn erased::Json| {
        let mut t = v.text();
        t.push('\n');
        t.into_bytes()
    };
    let mut files: Vec<(String, Vec<u8>)> = vec![
        ("points.json".into(), json(e)),
        ("points.csv".into(), csv(&e.points).into_bytes()),
        ("front.csv".into(), front_csv(e, metric).into_bytes()),
        ("front.svg".into(), svg(e, metric).into_bytes()),
        ("jobs.json".into(), json(&jobs.to_vec())),
        ("merge.json".into(), json(merge)),
        ("calibration.csv".into(), calibration_csv(e).into_bytes()),
    ];
    // the directory's manifest: what specgen wrote there, so that a later run replaces it
    let listed: Vec<serde_json::Value> = files.iter().map(|(n, b)| serde_json::json!({ "name": n, "sha256": crate::bits::sha256_hex(b, 32) })).collect();
    let manifest = serde_json::json!({ "generator": "specgen", "version": e.version, "exploration": e.part, "files": listed });
    files.push(("explore.json".into(), json(&manifest)));
    files
}

mod erased {
    /// Any serialisable value as pretty JSON.
    pub trait Json {
        fn text(&self) -> String;
    }
    impl<T: serde::Serialize> Json for T {
        fn text(&self) -> String {
            serde_json::to_string_pretty(self).expect("serialises")
        }
    }
}

/// Runs one job: generates its unit in a temporary directory and synthesizes it with its seed.
/// Refused when the tools here are not the ones the job was planned with (its result would be
/// stored under a fingerprint that does not describe it).
pub fn run_job(job: &Job, tools: &crate::synth::Tools) -> Result<JobResult, Error> {
    if job.compute_fingerprint() != job.fingerprint {
        return Err(input(format!("job {} does not match its fingerprint: the plan was edited", job.fingerprint)));
    }
    let here = tool_versions(job.params.target, tools)?;
    if here != job.tools {
        let diff: Vec<String> =
            job.tools.iter().filter(|(k, v)| here.get(*k) != Some(v)).map(|(k, v)| format!("{k}: planned {v:?}, here {:?}", here.get(k))).collect();
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
    let dir = crate::process::temp_dir().map_err(|e| Error::io("create a temporary directory in", std::env::temp_dir(), e))?;
    let unit = dir.path().join("unit");
    crate::output::write_dir_atomically(&unit, &crate::emit::generate_files(&plan))?;
    let design = crate::cosim::Design::load(&unit)?;
    let (synth, _) = crate::synth::synthesize(&design, job.params.target, true, tools, &[job.seed])?;
    Ok(JobResult { job: job.clone(), synth })
}

/// specgen's version and each tool's as it prints it (yosys, the family's nextpnr): part of
/// every job's fingerprint.
pub fn tool_versions(target: Target, tools: &crate::synth::Tools) -> Result<BTreeMap<String, String>, Error> {
    let mut v = BTreeMap::new();
    v.insert("specgen".to_string(), crate::names::VERSION.to_string());
    v.insert("yosys".to_string(), crate::synth::version_of(&tools.yosys, "-V")?);
    if let Some(pnr) = crate::synth::pnr_tool(target, tools)? {
        v.insert("nextpnr".to_string(), crate::synth::version_of(&pnr, "--version")?);
    }
    Ok(v)
}

/// What [`choose`] picked, with its evidence.
#[derive(Debug, Clone)]
pub struct Choice {
    pub point: Point,
    pub error: f64,
}

/// The cheapest measured point of `e` (logic cells, then the higher clock) whose `metric` error
/// is at most `max_error` and whose median Fmax reaches `mhz`, among those whose fixed
/// parameters (the exponent's and colours' widths) are `base`'s. Err: none does, with the
/// nearest points named.
pub fn choose(e: &Exploration, base: &Params, metric: Metric, max_error: f64, mhz: f64) -> Result<Choice, Error> {
    let fits = |p: &&Point| p.params.n_bits == base.n_bits && p.params.color_bits == base.color_bits && p.params.target == base.target;
    let measured: Vec<&Point> = e.points.iter().filter(fits).filter(|p| p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some())).collect();
    let reach = |p: &&&Point| p.measured.as_ref().and_then(|m| m.fmax_mhz).is_some_and(|f| f >= mhz);
    let good = |p: &&&Point| metric.of(&p.accuracy) <= max_error;
    let best = measured
        .iter()
        .filter(reach)
        .filter(good)
        .min_by(|a, b| a.cells().cmp(&b.cells()).then(b.fmax().unwrap_or(0.0).total_cmp(&a.fmax().unwrap_or(0.0))).then(a.id.cmp(&b.id)));
    if let Some(p) = best {
        return Ok(Choice { point: (*p).clone(), error: metric.of(&p.accuracy) });
    }
    let show = |p: &&Point| {
        format!("{} ({} error {:.3e}, {:.1} MHz, {} logic cells)", p.id, metric.name(), metric.of(&p.accuracy), p.fmax().unwrap_or(0.0), p.cells())
    };
    let fastest_good = measured.iter().filter(good).max_by(|a, b| a.fmax().unwrap_or(0.0).total_cmp(&b.fmax().unwrap_or(0.0)));
    let closest_fast = measured.iter().filter(reach).min_by(|a, b| metric.of(&a.accuracy).total_cmp(&metric.of(&b.accuracy)));
    let mut near = Vec::new();
    if let Some(p) = fastest_good {
        near.push(format!("the fastest within the error: {}", show(p)));
    }
    if let Some(p) = closest_fast {
        near.push(format!("the most accurate at the clock: {}", show(p)));
    }
    if measured.is_empty() {
        near.push(format!("no measured point at n_bits {} and color_bits {} on {}", base.n_bits, base.color_bits, base.target.name()));
    }
    Err(Error::Config {
        parameter: "max_error",
        message: format!(
            "no measured unit of the {} exploration ({} points measured) has {} error <= {max_error} at {mhz} MHz; nearest: {}",
            e.part,
            measured.len(),
            metric.name(),
            near.join("; ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn space() -> Space {
        let base = Params { n_bits: 4, color_bits: 4, ..Params::default() };
        Space {
            base,
            models: vec![SpecularModel::Quadratic, SpecularModel::Blinn],
            cos_frac_bits: vec![8],
            intensity_frac_bits: vec![8],
            dsp_budgets: vec![None],
            rom_styles: vec![RomStyle::File],
            clocks: vec![],
        }
    }

    #[test]
    fn a_front_is_what_no_point_beats_on_both() {
        let mut ps = points(&space(), &|_, _| {}).unwrap();
        assert!(ps.len() >= 2);
        let clocks = space().clocks();
        mark_fronts(&mut ps, Metric::Max, &clocks);
        for &mhz in &clocks {
            let on: Vec<&Point> = ps.iter().filter(|p| p.front.contains(&mhz)).collect();
            for p in &on {
                assert!(p.fmax().unwrap() >= mhz);
                // no point reaching the clock is both cheaper-or-equal and strictly better
                assert!(!ps
                    .iter()
                    .any(|q| q.fmax().is_some_and(|f| f >= mhz) && q.cells() <= p.cells() && Metric::Max.of(&q.accuracy) < Metric::Max.of(&p.accuracy)));
            }
            // every point reaching the clock is beaten or matched by a front point
            for q in ps.iter().filter(|q| q.fmax().is_some_and(|f| f >= mhz)) {
                assert!(on.iter().any(|p| p.cells() <= q.cells() && Metric::Max.of(&p.accuracy) <= Metric::Max.of(&q.accuracy)), "{} not covered", q.id);
            }
        }
    }

    #[test]
    fn a_fingerprint_changes_with_params_seed_and_tools() {
        let ps = points(&space(), &|_, _| {}).unwrap();
        let tools: BTreeMap<String, String> = [("yosys".to_string(), "Yosys 0.23".to_string())].into();
        let a = Job::new(&ps[0], "r", 1, &tools);
        assert_eq!(a.fingerprint, a.compute_fingerprint());
        assert_ne!(a.fingerprint, Job::new(&ps[0], "r", 2, &tools).fingerprint);
        assert_ne!(a.fingerprint, Job::new(&ps[1], "r", 1, &tools).fingerprint);
        assert_ne!(a.fingerprint, Job::new(&ps[0], "another RTL", 1, &tools).fingerprint);
        let newer: BTreeMap<String, String> = [("yosys".to_string(), "Yosys 0.70".to_string())].into();
        assert_ne!(a.fingerprint, Job::new(&ps[0], "r", 1, &newer).fingerprint);
    }

    #[test]
    fn a_merge_names_missing_and_conflicting_jobs() {
        let mut ps = points(&space(), &|_, _| {}).unwrap();
        let tools: BTreeMap<String, String> = [("yosys".to_string(), "x".to_string())].into();
        let ids = vec![ps[0].id.clone(), ps[1].id.clone()];
        let jobs = jobs_of(&ps, &ids, &[1, 2], &tools).unwrap();
        assert_eq!(jobs.len(), 4);
        let result = |j: &Job, f: f64| JobResult {
            job: j.clone(),
            synth: crate::synth::SynthResult { fmax_mhz: Some(f), logic_cells: Some(100), ..Default::default() },
        };
        let mut rs = vec![result(&jobs[0], 50.0), result(&jobs[1], 60.0), result(&jobs[2], 70.0), result(&jobs[2], 71.0)];
        let report = merge(&mut ps, &jobs, &rs);
        assert_eq!(report.missing.len(), 1);
        assert!(report.missing[0].starts_with(&jobs[3].fingerprint));
        assert_eq!(report.conflicting.len(), 1);
        assert_eq!(ps[0].measured.as_ref().unwrap().fmax_mhz, Some(55.0));
        assert!(ps[1].measured.is_none());
        rs.pop();
        rs.push(result(&jobs[3], 80.0));
        let report = merge(&mut ps, &jobs, &rs);
        assert!(report.missing.is_empty() && report.conflicting.is_empty());
        assert_eq!(ps[1].measured.as_ref().unwrap().fmax_mhz, Some(75.0));
    }

    #[test]
    fn the_choice_is_the_cheapest_measured_point_meeting_both() {
        let mut ps = points(&space(), &|_, _| {}).unwrap();
        for (i, p) in ps.iter_mut().enumerate() {
            p.measured = Some(Measured {
                seeds: vec![1],
                fmax_seeds: vec![50.0 + 10.0 * i as f64],
                fmax_mhz: Some(50.0 + 10.0 * i as f64),
                route_seeds: vec![],
                logic_cells: Some(100 + i as u64),
                luts: 0,
                flip_flops: 0,
                dsp_blocks: 0,
                block_rams: 0,
                limited_by: String::new(),
                note: String::new(),
                jobs: vec![],
                tools: BTreeMap::new(),
            });
        }
        let e = Exploration {
            generator: "specgen".into(),
            version: "x".into(),
            target: "ice40".into(),
            part: "p".into(),
            metric: "max".into(),
            clocks: vec![],
            seeds: vec![1],
            points: ps.clone(),
        };
        let base = &space().base;
        let c = choose(&e, base, Metric::Max, 1.0, 50.0).unwrap();
        assert_eq!(c.point.id, ps[0].id);
        let c = choose(&e, base, Metric::Max, 1.0, 55.0).unwrap();
        assert_eq!(c.point.id, ps[1].id);
        let err = choose(&e, base, Metric::Max, 1e-9, 50.0).unwrap_err();
        assert_eq!(err.parameter(), Some("max_error"));
        assert!(err.reason().contains("nearest"), "{}", err.reason());
        let other = Params { n_bits: 10, ..base.clone() };
        assert!(choose(&e, &other, Metric::Max, 1.0, 50.0).is_err());
    }
}
