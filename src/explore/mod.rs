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

use crate::config::{Config, Params, RomStyle, SpecularModel};
use crate::datapath::Kind;
use crate::error::Error;
use crate::models::display::Display;
use crate::models::{blinn_fidelity, Model};
use crate::plan::Plan;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

mod choice;
pub use choice::*;
mod depth;
mod files;
mod sweep;
#[cfg(test)]
mod tests;

pub use depth::*;
pub use files::*;
pub use sweep::*;

/// specgen's and every tool's version, as each prints it, by name.
pub type Versions = BTreeMap<String, String>;

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
    /// also this many depths spread evenly up to the deepest (a calibration's grid), 0: none
    pub spread: u32,
    /// the display of the display metrics
    pub display: Display,
}

impl Space {
    /// The clocks of this space: the asked ones, else the family's.
    pub fn clocks(&self) -> Vec<f64> {
        match self.clocks.is_empty() {
            true => crate::family::of(self.base.target)
                .explore_clocks()
                .to_vec(),
            false => self.clocks.clone(),
        }
    }
}

/// How far a unit is from Blinn's `cos^n`, on its whole input space and in a picture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Accuracy {
    /// max |intensity − cos^n| over every (cos_g ≤ 1.0, n) at the unit's own codes (c =
    /// cos_g/2^F), full scale: the error for a cosine that already arrives at F bits
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
    /// the error at the pixel: the real cosine rounded to F bits counted (`models::Pixel`);
    /// None in an exploration written before it was measured (its pixel metrics then meet no
    /// bound until recomputed)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixel: Option<PixelAccuracy>,
    /// the error and the banding in codes of a display (`models::display`); None in an
    /// exploration written before it was measured
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub display: Option<DisplayAccuracy>,
}

/// [`Accuracy::display`]: on which display, and its figures in that display's codes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DisplayAccuracy {
    /// `srgb8`, `gamma2.2:10`, …
    pub display: String,
    pub max_codes: f64,
    pub banding_codes: f64,
    pub bound: bool,
}

/// [`Accuracy::pixel`]: max, mean and RMS of `|intensity − c^n|` over the real `c ∈ [0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PixelAccuracy {
    pub max: f64,
    pub mean: f64,
    pub rms: f64,
    /// true: `max` is a bound over a stride of codes (never below the exact figure)
    pub bound: bool,
}

/// The metric `--max-error` bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// the largest |intensity − c^n| over every real cosine c (rounded to F bits) and n
    Max,
    Mean,
    Rms,
    /// the same at the unit's own codes (c = cos_g/2^F exactly): a cosine that arrives at F bits
    CodeMax,
    CodeMean,
    CodeRms,
    /// the largest step between neighbouring pixels beyond the float image's
    Step,
    /// the largest error in codes of a display (after its transfer function), at the pixel
    DisplayMax,
    /// the largest jump in codes of a display between neighbouring cosine codes (1: no banding
    /// beyond the display's own)
    DisplayBanding,
}

impl Metric {
    pub const ALL: [Metric; 9] = [
        Metric::Max,
        Metric::Mean,
        Metric::Rms,
        Metric::CodeMax,
        Metric::CodeMean,
        Metric::CodeRms,
        Metric::Step,
        Metric::DisplayMax,
        Metric::DisplayBanding,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Metric::Max => "max",
            Metric::Mean => "mean",
            Metric::Rms => "rms",
            Metric::CodeMax => "code-max",
            Metric::CodeMean => "code-mean",
            Metric::CodeRms => "code-rms",
            Metric::Step => "step",
            Metric::DisplayMax => "display-max",
            Metric::DisplayBanding => "display-banding",
        }
    }
    /// The metric's figure; a pixel metric of an accuracy without pixel figures is infinite
    /// (it meets no bound).
    pub fn of(self, a: &Accuracy) -> f64 {
        let pixel = |f: fn(&PixelAccuracy) -> f64| a.pixel.as_ref().map_or(f64::INFINITY, f);
        match self {
            Metric::Max => pixel(|p| p.max),
            Metric::Mean => pixel(|p| p.mean),
            Metric::Rms => pixel(|p| p.rms),
            Metric::CodeMax => a.max,
            Metric::CodeMean => a.mean,
            Metric::CodeRms => a.rms,
            Metric::Step => a.max_step_excess,
            Metric::DisplayMax => a.display.as_ref().map_or(f64::INFINITY, |d| d.max_codes),
            Metric::DisplayBanding => a
                .display
                .as_ref()
                .map_or(f64::INFINITY, |d| d.banding_codes),
        }
    }
    /// Whether the figure needs the pixel's part of an accuracy.
    pub fn at_pixel(self) -> bool {
        matches!(
            self,
            Metric::Max | Metric::Mean | Metric::Rms | Metric::DisplayMax | Metric::DisplayBanding
        )
    }
    /// Whether the figure is in codes of a display (its bound is in codes, not full scale).
    pub fn in_display_codes(self) -> bool {
        matches!(self, Metric::DisplayMax | Metric::DisplayBanding)
    }
}

/// The exponents of the picture figures: `render`'s defaults that the exponent's width holds.
fn picture_exponents(n_bits: u32) -> Vec<u32> {
    [1u32, 4, 16, 128]
        .into_iter()
        .filter(|&n| n < 1 << n_bits)
        .collect()
}

/// The accuracy of a model (every depth of it computes the same function), its display
/// figures on an 8-bit sRGB display.
pub fn accuracy(model: &Model) -> Accuracy {
    accuracy_on(model, Display::SRGB8)
}

/// [`accuracy`] with the display figures on `display`.
pub fn accuracy_on(model: &Model, display: Display) -> Accuracy {
    let f = blinn_fidelity(model);
    let d = crate::models::display::display_error(model, display);
    let img = crate::render::image_figures(model, &picture_exponents(model.cfg.n_bits()), 128);
    Accuracy {
        max: f.max,
        mean: f.mean,
        rms: f.rms,
        points: f.points,
        stride: f.stride,
        psnr_db: img.psnr_db,
        max_step_excess: img.max_step_excess,
        pixel: Some(PixelAccuracy {
            max: f.pixel.max,
            mean: f.pixel.mean,
            rms: f.pixel.rms,
            bound: f.pixel.bound,
        }),
        display: Some(DisplayAccuracy {
            display: display.name(),
            max_codes: d.max_codes,
            banding_codes: d.banding_codes,
            bound: d.bound,
        }),
    }
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

/// The cost estimate of a plan, as `synth` measures it (the unit inside its serial wrapper,
/// [`crate::synth::wrapper_cost`]): each wire by its kind (a sum or logic a LUT a bit, a table
/// in LUTs two, a product the family leaves in LUTs half its partial-product bits, a product
/// on a block none), every registered cut's live bits a flip-flop each, but those a delay line
/// keeps in RAM (`crate::emit::delay_ram_tails`). Over the built-in explorations' measured
/// points its median is within 10 % of synth's and most points are (a test holds both).
pub fn estimate(plan: &Plan) -> Estimate {
    let dp = &plan.datapath;
    let family = crate::family::of(plan.cfg.target());
    let mut luts = 0u64;
    for w in dp.steps.iter().flat_map(|s| &s.wires) {
        luts += match w.kind {
            Kind::Select => 0,
            Kind::Sum | Kind::Logic => w.width as u64,
            Kind::Table => 2 * w.width as u64,
            Kind::Product(a, b) if family.product_blocks(a, b, w.width) == 0 => {
                (a as u64 * b as u64).div_ceil(2)
            }
            Kind::Product(..) => 0,
        };
    }
    let mut flip_flops: u64 = dp
        .registered
        .iter()
        .filter_map(|&k| dp.live.get(k as usize - 1))
        .flatten()
        .map(|l| l.width as u64)
        .sum();
    let dsp_blocks = dp
        .product_uses
        .iter()
        .filter(|u| !u.fabric)
        .map(|u| u.blocks as u64)
        .sum();
    let mut block_rams = dp
        .reads
        .iter()
        .filter(|r| r.block)
        .map(|r| r.table)
        .collect::<BTreeSet<_>>()
        .len() as u64;
    // a delay line's tail in RAM: its words leave the flip-flops for the memory, which costs a
    // read register of the word, two address counters (a carry a bit) and, in block RAM, a
    // block per 16 bits of the word (256 words deep: every tail is shorter); in LUT RAM, a
    // 16-word, 4-bit TRELLIS_DPR16X4 (two LUTs' room) per 4 bits and 16 words
    for (word, cuts) in crate::emit::delay_ram_tails(plan) {
        let (word, cuts) = (word as u64, cuts as u64);
        let address = 64 - (cuts.max(2) - 1).leading_zeros() as u64;
        flip_flops = flip_flops.saturating_sub(word * cuts) + word + 2 * address;
        luts += 2 * address;
        if family.distributed_ram() {
            luts += 2 * word.div_ceil(4) * cuts.div_ceil(16);
        } else {
            block_rams += word.div_ceil(16);
        }
    }
    // the figures are compared with synth's, which are of the unit inside its serial wrapper
    let (wrapper_luts, wrapper_flip_flops) = crate::synth::wrapper_cost(&plan.cfg);
    let (luts, flip_flops) = (luts + wrapper_luts, flip_flops + wrapper_flip_flops);
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
    pub tools: Versions,
}

/// One configuration of the space.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// `<model>-f<F>-fi<FI>-s<stages>[-b<budget>][-<rom style>][-<interface>]`
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
        self.measured
            .as_ref()
            .and_then(|m| m.logic_cells)
            .unwrap_or(self.estimate.logic_cells)
    }
}

fn point_id(p: &Params) -> String {
    let mut id = format!(
        "{}-f{}-fi{}-s{}",
        p.model.name(),
        p.cos_frac_bits,
        p.intensity_frac_bits,
        p.stages
    );
    if let Some(b) = p.dsp_budget {
        id.push_str(&format!("-b{b}"));
    }
    if p.rom_style != RomStyle::File {
        id.push_str(&format!("-{}", p.rom_style.name()));
    }
    // a unit of another interface is another point (its edge is measured with it)
    if p.interface != crate::config::Interface::Valid {
        id.push_str(&format!("-{}", p.interface.name()));
    }
    id
}

/// The depth `explore` plans for `mhz`: [`depth_for_clock`] under [`Policy::Predicted`] (a
/// unit measured on today's RTL first), or the deepest where none reaches it; None without a
/// delay model.
fn depth_for(plan: &Plan, mhz: f64) -> Result<Option<u32>, Error> {
    if crate::timing::predicted_fmax(plan).is_none() {
        return Ok(None);
    }
    Ok(Some(
        depth_for_clock(plan, mhz, Policy::Predicted, None, |_, _| {})?
            .plan
            .cfg
            .stages(),
    ))
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
        let base = Params {
            model,
            cos_frac_bits: f,
            intensity_frac_bits: fi,
            stages: 0,
            ..space.base.clone()
        };
        let cfg = Config::new(base.clone())?;
        let golden = Model::new(&cfg);
        let acc = accuracy_on(&golden, space.display);
        for &rom in &space.rom_styles {
            // the ROM style shapes the model's own datapath (its tables' steps): a model of its
            // own per style (every style computes the same function: one accuracy); a budget is
            // the plan's, so the model is shared across budgets
            let styled = match Config::new(Params {
                rom_style: rom,
                ..base.clone()
            }) {
                Ok(c) if rom != base.rom_style => Model::new(&c),
                Ok(_) => golden.clone(),
                // a style the model does not take: not in the space
                Err(_) => continue,
            };
            for &budget in &space.dsp_budgets {
                let params = Params {
                    dsp_budget: budget,
                    rom_style: rom,
                    ..base.clone()
                };
                let cfg = match Config::new(params) {
                    Ok(c) => c,
                    // a budget out of range: not in the space
                    Err(_) => continue,
                };
                let plan = match Plan::for_model(styled.with_config(cfg)) {
                    Ok(p) => p,
                    // a style the family does not write: not in the space
                    Err(e) if e.parameter() == Some("rom_style") => continue,
                    Err(e) => return Err(e),
                };
                let mut depths: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
                let mut modelled = false;
                for &mhz in &clocks {
                    if let Some(d) = depth_for(&plan, mhz)? {
                        depths.entry(d).or_default().push(mhz);
                        modelled = true;
                    }
                }
                depths.entry(plan.cut_points).or_default();
                // a calibration's grid: `spread` depths from a `spread`-th of the cuts to all
                for k in 1..=space.spread {
                    depths
                        .entry((plan.cut_points * k).div_ceil(space.spread).max(1))
                        .or_default();
                }
                if clocks.is_empty() || !modelled {
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
                        accuracy: acc.clone(),
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

/// The points of units given whole (a bench's: `explore --unit DIR`), instead of a space:
/// each its own parameters, accuracy and estimate, measured as any point is. The same unit
/// twice is one point; the id adds N, B and the parameters' fingerprint to the space's form, so
/// units that differ elsewhere are apart. Every unit is of one family (the exploration's).
pub fn unit_points(units: &[Params]) -> Result<Vec<Point>, Error> {
    let mut out: Vec<Point> = Vec::new();
    let mut accuracies: BTreeMap<String, Accuracy> = BTreeMap::new();
    for params in units {
        let plan = Plan::new(Config::new(params.clone())?)?;
        let p = &plan.cfg.params;
        let id = format!(
            "{}-n{}-c{}-{}",
            point_id(p),
            p.n_bits,
            p.color_bits,
            &plan.cfg.fingerprint()[..8]
        );
        if out.iter().any(|q| q.id == id) {
            continue;
        }
        // the function a unit computes is its configuration's at depth 0 (any depth computes it)
        let shape = Config::new(Params {
            stages: 0,
            ..p.clone()
        })?
        .fingerprint();
        let acc = accuracies
            .entry(shape)
            .or_insert_with(|| accuracy(&plan.model()))
            .clone();
        out.push(Point {
            id,
            model: p.model.name().to_string(),
            cos_frac_bits: p.cos_frac_bits,
            intensity_frac_bits: p.intensity_frac_bits,
            stages: p.stages,
            dsp_budget: p.dsp_budget,
            rom_style: p.rom_style.name().to_string(),
            chosen_for: Vec::new(),
            params: p.clone(),
            accuracy: acc,
            estimate: estimate(&plan),
            measured: None,
            front: Vec::new(),
        });
    }
    Ok(out)
}

/// The front at `mhz` by `metric`: the ids of the points reaching the clock that no other point
/// beats on both error and logic cells (ties kept). Where any point is measured, only measured
/// points stand on it: an estimate never pushes a measurement off the front.
pub fn front_at(points: &[Point], metric: Metric, mhz: f64) -> Vec<String> {
    let any_measured = points
        .iter()
        .any(|p| p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some()));
    let mut reach: Vec<&Point> = points
        .iter()
        .filter(|p| !any_measured || p.measured.is_some())
        .filter(|p| p.fmax().is_some_and(|f| f >= mhz))
        .collect();
    reach.sort_by(|a, b| {
        a.cells()
            .cmp(&b.cells())
            .then(metric.of(&a.accuracy).total_cmp(&metric.of(&b.accuracy)))
            .then(a.id.cmp(&b.id))
    });
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
pub fn candidates(
    points: &[Point],
    metric: Metric,
    clocks: &[f64],
    near: f64,
    slack: f64,
) -> Vec<String> {
    let mut ids = BTreeSet::new();
    // a unit that needs more hard multipliers than the part has does not fit: not measured
    let fits = |p: &&Point| {
        crate::family::of(p.params.target)
            .dsp_capacity()
            .is_none_or(|c| p.estimate.dsp_blocks <= c)
    };
    let estimated: Vec<Point> = points
        .iter()
        .filter(fits)
        .map(|p| Point {
            measured: None,
            ..p.clone()
        })
        .collect();
    for &mhz in clocks {
        let reach: Vec<&Point> = estimated
            .iter()
            .filter(|p| p.estimate.fmax_mhz.is_none_or(|f| f >= mhz * slack))
            .collect();
        let owned: Vec<Point> = reach
            .iter()
            .map(|&p| Point {
                estimate: Estimate {
                    fmax_mhz: Some(mhz),
                    ..p.estimate
                },
                ..p.clone()
            })
            .collect();
        let front: Vec<&Point> = front_at(&owned, metric, mhz)
            .iter()
            .filter_map(|id| owned.iter().find(|p| &p.id == id))
            .collect();
        for p in &owned {
            let e = metric.of(&p.accuracy);
            let cheapest = front
                .iter()
                .filter(|q| metric.of(&q.accuracy) <= e)
                .map(|q| q.cells())
                .min();
            if cheapest.is_some_and(|c| p.cells() as f64 <= (1.0 + near) * c as f64) {
                ids.insert(p.id.clone());
            }
        }
    }
    points
        .iter()
        .filter(|p| ids.contains(&p.id))
        .map(|p| p.id.clone())
        .collect()
}
