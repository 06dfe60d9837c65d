//! The delay model: what clock a depth of a unit reaches on a family, where no unit of that
//! configuration was measured on today's RTL. (Measured units come first, in
//! `explore::depth_for_clock`, the one depth search; this module is its fallback.)
//!
//! **The stretches.** Each datapath step counts the primitives it passes through (LUT levels,
//! carry chains and bits, hard multiplies, partial-product levels, register-only routes:
//! `datapath::Delay`); the family weighs them with its own primitive delays
//! (`family::PrimitiveDelays`, FloPoCo's way). `e` is the slowest stretch between registers,
//! `m` the mean one ([`stretches`]).
//!
//! **The rules, in order.**
//! 1. *Floors of these widths.* A calibration unit of this datapath, family and shape whose row
//!    names today's RTL digest (`Line::of_todays_rtl`) is a floor: a depth whose stretches are
//!    no longer than such a unit's is assured that unit's figure (`measured_floor`: its median
//!    over three seeds or more, else its slowest seed, `fit::row_figure`); between two of them,
//!    the longer one's (`bracketed`).
//! 2. *Between calibrated widths* (`Line::corner`): where calibrated shapes surround the
//!    configuration's (one no wider in every width, one no narrower; alike in rounding, ROM
//!    style, registers and whether a product is LUTs for its size: `Shape`), the depth is read at as
//!    many cuts from the deepest in each, and assured [`corner_margin`] of the least they
//!    measured there: a margin the fit computes by leaving each width out (`fit::corner_margin`),
//!    stored with the model and printed by `generate --explain`.
//! 3. *Otherwise an extrapolation*, said so: the line per datapath and family, fitted by least
//!    squares (`specgen calibrate`, `timing::fit`) to the calibration's medians,
//!    `period_ns = offset_ns + ns_per_unit·e + ns_per_mean_unit·m`, slopes and intercept
//!    non-negative, its R² stored; assured times its `margin` (the worst measured/predicted
//!    ratio of its data), and never above what calibrated widths no harder to clock (no wider,
//!    as many blocks or more) measured as deep or deeper (a ceiling: `Line::corner`).
//!
//! A depth that leaves a product to the synthesis tool where the family's unit instantiates its
//! blocks with their registers (the ECP5 and the GW1NR-9 at a shallow depth) is assured by rule 1
//! alone: neither the widths around it nor the line measured such paths (`line::inferred_blocks`).
//!
//! Every figure stays under the blocks' limits at speed grade 6 (`crate::family`) and, for a
//! `ready`/`axis` unit, under the most a unit with its output buffer was measured at.
//! [`pick_stages`] scans depths from the shallowest for the first whose assured figure reaches
//! the target; [`outside_calibration`] says which rule spoke. A figure of this module is never
//! called measured.

mod line;

use crate::config::Target;
use crate::error::Error;
use crate::plan::Plan;
use serde::Deserialize;
use shape::Shape;

/// What a depth between calibrated widths is assured, as a share of what the widths around it
/// measured ([`Line::corner`]): the worst ratio measured/read over the floors (today's RTL)
/// with each width left out in turn and read through the others, rounded down; computed by the
/// fit (`fit::corner_margin`) and stored with the model (`corner_margin`).
pub fn corner_margin() -> f64 {
    model_json()["corner_margin"].as_f64().unwrap_or(1.0)
}

/// The fitted lines, `specgen calibrate`'s output (`fit`).
const MODEL_JSON: &str = include_str!("../../data/delay_model.json");

/// The shapes the calibration measured `datapath` at on `target`'s family on today's RTL: each
/// the default parameters with a measured unit's `args` applied (the rows the floors come from;
/// a row of another RTL calibrates no shape); a unit whose args name another flag is left out
/// (it is not known to be any configuration's shape).
fn calibrated_shapes(plan: &Plan) -> Vec<Shape> {
    let mut shapes: Vec<Shape> = Vec::new();
    for args in line(plan.cfg.target(), plan.cfg.datapath_name())
        .map(|l| l.of_todays_rtl().measured_args)
        .unwrap_or_default()
    {
        if let Some(sh) = Shape::of_args(&args, &plan.cfg.params) {
            if !shapes.contains(&sh) {
                shapes.push(sh);
            }
        }
    }
    shapes
}

/// Why `plan`'s pick is not a calibrated configuration's, or None: no unit of its datapath was
/// placed and routed at its widths, rounding and ROM style on its family. "between calibrated
/// widths" when each of them lies within those of the grid (the line and its margin are
/// fitted over them all; no measured unit is a floor), "outside the calibration" otherwise (the
/// line's extrapolation, not assured: a narrow schlick asked for 55 MHz measured 49.2 before
/// the grid had narrow units). `generate --target-mhz` says it, with
/// the command that measures the unit.
pub fn outside_calibration(plan: &Plan) -> Option<String> {
    family(plan.cfg.target())?;
    let datapath = plan.cfg.datapath_name();
    let model = plan.cfg.model();
    let own = Shape::of_plan(plan);
    let shapes = calibrated_shapes(plan);
    if shapes.contains(&own) {
        return None;
    }
    let flags = |sh: &Shape| sh.flags(model);
    let measured = match shapes.len() {
        0 => "no unit of today's RTL".to_string(),
        _ => shapes.iter().map(flags).collect::<Vec<_>>().join("; "),
    };
    let (part, own_flags) = (part(plan.cfg.target()), flags(&own));
    if own.between(&shapes) {
        if let Some(l) = line_of(plan).ok().filter(|l| l.surrounded) {
            let around: Vec<String> = l.around.iter().map(flags).collect();
            return Some(format!(
                "between calibrated widths: the {datapath} datapath on the {part} was calibrated at {} widths; this configuration ({own_flags}) lies between the nearest of them, {}: a depth is assured {:.2} of the least that the widths around it measured as many cuts from their deepest (the nearest measured near that depth on either side, and those between them), where its slowest stretch is no longer than theirs, else the delay model's line with its margin; not a unit measured at these widths",
                shapes.len(),
                around.join("; "),
                corner_margin()
            ));
        }
        return Some(format!(
            "between calibrated widths: the {datapath} datapath on the {part} was calibrated at {} widths, none of them around this configuration ({own_flags}) in every width: the delay model's line with its margin, no more than they measured as deep; not a unit measured at these widths",
            shapes.len()
        ));
    }
    Some(format!(
        "outside the calibration: the {datapath} datapath on the {part} was calibrated at {measured}, not at this configuration ({own_flags}): the depth follows the delay model's line, an extrapolation, not a measured assurance"
    ))
}

/// One family's line (see the module doc).
#[derive(Debug, Clone, Deserialize)]
pub struct Line {
    pub(crate) offset_ns: f64,
    pub(crate) ns_per_unit: f64,
    pub(crate) ns_per_mean_unit: f64,
    pub(crate) cap_mhz: f64,
    /// the largest `e` among the calibration units that reached the cap (-1: none did)
    pub(crate) cap_up_to: f64,
    pub margin: f64,
    /// the share of the calibration's variance (of the period) the line explains
    #[serde(default)]
    pub(crate) r2: f64,
    /// the calibration units of this datapath on this family, `[e, m, median Fmax]`: a unit
    /// whose stretches are no longer than one measured reaches at least its Fmax (the line
    /// misses the jump of the last cuts, where the long stretches go at once)
    #[serde(default)]
    pub(crate) measured: Vec<[f64; 3]>,
    /// each measured unit's generate flags beyond the model (its widths; empty: the defaults),
    /// in the order of `measured`
    #[serde(default)]
    pub(crate) measured_args: Vec<String>,
    /// each measured unit's depth, in the order of `measured`
    #[serde(default)]
    pub(crate) measured_stages: Vec<u32>,
    /// each measured unit's RTL digest (SHA-256 of its Verilog and tables, `emit::rtl_digest`;
    /// empty: the row names none), in the order of `measured`: a unit is a floor only where it
    /// is the RTL specgen writes today ([`Line::of_todays_rtl`])
    #[serde(default)]
    pub(crate) measured_digest: Vec<String>,
    /// at widths no unit was measured at: the calibrated widths it is read against
    /// ([`Line::corner`]): the nearest on either side of its own where there are such, else
    /// every one
    #[serde(skip)]
    pub(crate) corners: Vec<Corner>,
    /// the configuration's deepest `--stages`: a corner's units are read at as many cuts from
    /// their own deepest as the configuration's depth is from this
    #[serde(skip)]
    pub(crate) deepest: u32,
    /// whether `corners` surround the configuration's widths: some no wider in every width and
    /// some no narrower, the other flags alike
    #[serde(skip)]
    pub(crate) surrounded: bool,
    /// where surrounded: the nearest calibrated widths below and above
    #[serde(skip)]
    pub(crate) around: Vec<Shape>,
    /// at widths never measured: the configuration's shape
    #[serde(skip)]
    pub(crate) own: Option<Shape>,
}

/// The nearest of `shapes` no wider than `own` in every width (none between them and it), and
/// the nearest no narrower.
fn nearest_around<'a>(
    own: &Shape,
    shapes: impl Iterator<Item = &'a Shape> + Clone,
) -> (Vec<&'a Shape>, Vec<&'a Shape>) {
    let below: Vec<&Shape> = shapes.clone().filter(|sh| sh.no_wider(own)).collect();
    let above: Vec<&Shape> = shapes.filter(|sh| own.no_wider(sh)).collect();
    let nearest_below = below
        .iter()
        .filter(|a| !below.iter().any(|b| b != *a && a.no_wider(b)))
        .copied()
        .collect();
    let nearest_above = above
        .iter()
        .filter(|a| !above.iter().any(|b| b != *a && b.no_wider(a)))
        .copied()
        .collect();
    (nearest_below, nearest_above)
}

/// A calibrated width's units, read for a configuration at widths no unit was measured at.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Corner {
    /// its generate flags beyond the defaults (empty: the defaults)
    pub(crate) args: String,
    /// its deepest `--stages` (its plan's cut points)
    pub(crate) deepest: u32,
    /// its units: `(stages, slowest stretch e, median Fmax)`
    pub(crate) units: Vec<(u32, f64, f64)>,
    /// its shape
    pub(crate) shape: Shape,
}

impl Corner {
    /// Its unit read for a depth `from_deepest` cuts from the configuration's deepest: the
    /// deepest at as many cuts from its own deepest or more, where its units span that depth
    /// (one as deep or deeper too) or that unit is within [`BETWEEN_WINDOW`] cuts of it; else
    /// none (a width measured at a few shallow depths says nothing of a deep one).
    fn unit_at(&self, from_deepest: u32) -> Option<&(u32, f64, f64)> {
        let at = self.deepest.saturating_sub(from_deepest);
        let spans = self.units.iter().any(|u| u.0 >= at);
        self.units
            .iter()
            .filter(|u| u.0 <= at && (spans || u.0 + BETWEEN_WINDOW >= at))
            .max_by_key(|u| u.0)
    }

    /// Its shallowest unit at `from_deepest` cuts from its own deepest or fewer (a ceiling for a
    /// depth that far from the configuration's deepest).
    fn unit_at_or_deeper(&self, from_deepest: u32) -> Option<&(u32, f64, f64)> {
        let at = self.deepest.saturating_sub(from_deepest);
        self.units.iter().filter(|u| u.0 >= at).min_by_key(|u| u.0)
    }
}

/// How many cuts shallower than the depth read a calibrated width's deepest unit may be and
/// still speak for it: widths of the explorations were measured at a few depths each (their
/// fronts), and a unit far shallower says nothing of the depth read.
pub const BETWEEN_WINDOW: u32 = 2;

/// A calibration unit's configuration at depth 0: `params`'s model, architecture and target,
/// every other parameter the default (as `scripts/calibrate_delay.sh` generates it: no
/// `--dsp-budget`, `--interface valid`), with the row's `args` applied; None when they name a
/// flag that is not a width, the rounding or the ROM style.
pub(crate) fn params_with_args(
    params: &crate::config::Params,
    args: &str,
) -> Option<crate::config::Params> {
    use crate::config::{Interface, RomStyle, Rounding};
    let mut p = crate::config::Params {
        model: params.model,
        arch: params.arch,
        target: params.target,
        ..Default::default()
    };
    let words: Vec<&str> = args.split_whitespace().collect();
    if !words.len().is_multiple_of(2) {
        return None;
    }
    for pair in words.chunks(2) {
        let n = || pair[1].parse::<u32>().ok();
        match pair[0] {
            "--cos-frac-bits" => p.cos_frac_bits = n()?,
            "--n-bits" => p.n_bits = n()?,
            "--color-bits" => p.color_bits = n()?,
            "--intensity-frac-bits" => p.intensity_frac_bits = n()?,
            "--k-frac-bits" => p.k_frac_bits = n()?,
            "--max-squarings" => p.max_squarings = n()?,
            "--rounding" => {
                p.rounding = [Rounding::Faithful, Rounding::Exact]
                    .into_iter()
                    .find(|r| r.name() == pair[1])?
            }
            "--rom-style" => {
                p.rom_style = [RomStyle::File, RomStyle::Case, RomStyle::Logic]
                    .into_iter()
                    .find(|r| r.name() == pair[1])?
            }
            "--fabric-registers" => p.fabric_registers = pair[1].parse().ok()?,
            "--dsp-budget" => p.dsp_budget = Some(n()?),
            "--interface" => {
                p.interface = [Interface::Valid, Interface::Ready, Interface::Axis]
                    .into_iter()
                    .find(|i| i.name() == pair[1])?
            }
            _ => return None,
        }
    }
    Some(p)
}

/// The deepest `--stages` of `params` (its plan's cut points) and its slowest stretch there
/// (the longest step no register splits), planned once per process for each configuration (a
/// pick reads the same corners at every depth it tries).
fn deepest_of(params: &crate::config::Params) -> Option<(u32, f64)> {
    use std::collections::BTreeMap;
    use std::sync::Mutex;
    static DEEPEST: Mutex<BTreeMap<String, (u32, f64)>> = Mutex::new(BTreeMap::new());
    let key = serde_json::to_string(params).ok()?;
    if let Some(d) = DEEPEST.lock().ok()?.get(&key) {
        return Some(*d);
    }
    let plan = Plan::from_params(params.clone()).ok()?;
    let d = (plan.cut_points, plan.longest_step());
    DEEPEST.lock().ok()?.insert(key, d);
    Some(d)
}

/// Keeps the items of `v` whose flag in `keep` is set (one flag an item, in order; an item
/// past the flags goes).
pub(crate) fn retain_flagged<T>(v: &mut Vec<T>, keep: &[bool]) {
    let mut k = keep.iter();
    v.retain(|_| k.next().copied().unwrap_or(false));
}

impl Line {}

/// Which rule of the module doc gave an assured figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// a calibration unit of these widths on today's RTL (rule 1)
    Floor,
    /// the calibrated widths around these, with the corner margin (rule 2)
    Between,
    /// the fitted line with its margin: an extrapolation (rule 3)
    Line,
}

/// The figure [`assured_fmax`] gives `plan`, and the rule that gave it. None for a datapath
/// without calibration.
pub fn assured_reading(plan: &Plan) -> Option<(f64, Rule)> {
    let (f, rule) = line_of(plan).ok()?.assured_by_rule(plan);
    Some((under_caps(plan, f), rule))
}

/// The slowest and the mean stretch of logic between registers of `plan` (`Plan::stage_delay`,
/// `Plan::stage_delay_mean`) weighed with its family's primitive delays
/// (`family::PrimitiveDelays`): what the lines are fitted in and read at.
pub(crate) fn stretches(plan: &Plan) -> (f64, f64) {
    let w = crate::family::of(plan.cfg.target()).primitive_delays();
    (plan.stage_delay_on(&w), plan.stage_delay_mean_on(&w))
}

/// The family the model speaks of for `target`: its name where `data/delay_model.json` holds
/// its lines (the data says which families are calibrated, so a family is never read through
/// another's); none for `generic`, whose RTL names no family: its clock is the device's it is
/// mapped to, which no calibration here knows.
fn family(target: Target) -> Option<&'static str> {
    let name = target.name();
    model_json()
        .get(name)
        .is_some_and(|v| v.is_object())
        .then_some(name)
}

/// Whether the delay model speaks for `target` (`--target-mhz` is refused where it does not).
pub fn calibrated(target: Target) -> bool {
    family(target).is_some()
}

/// The part a family's figures are for (`generic`: none, said so).
pub fn part(target: Target) -> &'static str {
    crate::family::of(target).part()
}

/// The fitted line of `target`'s family for the datapath `datapath` (`lean`, `paper`, or a
/// model's name): its own when calibrated, the family's (`all`) where the data says so
/// by name. A datapath the data does not name is an error: a new model is calibrated
/// (`scripts/calibrate_delay.sh`), never estimated by another's line in silence.
pub fn line(target: Target, datapath: &str) -> Result<Line, Error> {
    let Some(family) = family(target) else {
        let calibrated: Vec<String> = Target::ALL
            .into_iter()
            .filter(|t| calibrated(*t))
            .map(|t| format!("--target {}", t.name()))
            .collect();
        let why = match crate::family::of(target).place_and_route(6) {
            None => "its RTL names no family, so its clock is the one of the device it is mapped to, which specgen is not calibrated on".to_string(),
            Some(_) => format!("specgen is not calibrated on the {} yet (`FAMILIES={} scripts/calibrate_delay.sh` measures it and fits the model)", part(target), target.name()),
        };
        return Err(Error::Config {
            parameter: "target_mhz",
            message: format!(
                "the {} target has no delay model: {why}; allowed: {} with --target-mhz, or --stages N with --target {} (the README lists each target's depths)",
                target.name(),
                calibrated.join(" or "),
                target.name()
            ),
        });
    };
    let lines = &model_json()[family];
    let chosen = match &lines[datapath] {
        serde_json::Value::Object(_) => &lines[datapath],
        serde_json::Value::String(s) if s == "all" => &lines["all"],
        _ => {
            return Err(Error::Config {
                parameter: "target_mhz",
                message: format!(
                    "the {datapath} datapath has no delay calibration on the {}: `FAMILIES={} scripts/calibrate_delay.sh` measures it and fits the model (or give --stages)",
                    part(target),
                    target.name()
                ),
            })
        }
    };
    Ok(
        serde_json::from_value(chosen.clone())
            .expect("data/delay_model.json has a line per family"),
    )
}

/// Every datapath's own line on `target`'s family, by the datapath's name (a datapath that
/// reads the family's line is not listed); none for a family without a delay model.
pub(crate) fn lines(target: Target) -> Vec<(String, Line)> {
    let Some(family) = family(target) else {
        return Vec::new();
    };
    let all: serde_json::Value =
        serde_json::from_str(MODEL_JSON).expect("data/delay_model.json is JSON");
    all[family]
        .as_object()
        .into_iter()
        .flatten()
        .filter_map(|(name, v)| {
            Some((
                name.clone(),
                serde_json::from_value::<Line>(v.clone()).ok()?,
            ))
        })
        .collect()
}

/// The line for `plan`'s family and datapath, with the measured units of its widths.
fn line_of(plan: &Plan) -> Result<Line, Error> {
    Ok(line(plan.cfg.target(), plan.cfg.datapath_name())?.at_widths_of(plan))
}

/// The Fmax the delay model predicts for `plan` on its family's part, in MHz.
/// None for a datapath without calibration.
pub fn predicted_fmax(plan: &Plan) -> Option<f64> {
    Some(under_caps(plan, line_of(plan).ok()?.fmax_of(plan)))
}

/// `mhz` under the limits of the blocks `plan` uses and a handshake unit's measured ceiling.
fn under_caps(plan: &Plan, mhz: f64) -> f64 {
    mhz.min(block_cap(plan).map_or(f64::INFINITY, |l| l.mhz()))
        .min(handshake_cap(plan).map_or(f64::INFINITY, |c| c.0))
}

/// The Fmax the delay model assures for `plan` (what `--target-mhz` compares with its target:
/// [`Line::assured_of`] under the blocks' limits and a handshake's ceiling), in MHz. None for a
/// datapath without calibration.
pub fn assured_fmax(plan: &Plan) -> Option<f64> {
    Some(under_caps(plan, line_of(plan).ok()?.assured_of(plan)))
}

/// A `ready`/`axis` unit's ceiling on its family: the most a unit with the output buffer was
/// measured at on today's RTL (its own paths, which no calibration unit of the line has), the
/// fit's `handshake` entry (`fit`): its datapath's, else the least any datapath's; with the unit
/// that was. None: no such unit measured on the part.
fn handshake_cap(plan: &Plan) -> Option<(f64, String)> {
    if !plan.cfg.interface().handshake() {
        return None;
    }
    let all: &serde_json::Value = model_json();
    let caps = all["handshake"][family(plan.cfg.target())?].as_object()?;
    let cap = |v: &serde_json::Value| Some((v["mhz"].as_f64()?, v["unit"].as_str()?.to_string()));
    match caps.get(plan.cfg.datapath_name()).and_then(cap) {
        Some(c) => Some(c),
        None => caps
            .values()
            .filter_map(cap)
            .min_by(|a, b| a.0.total_cmp(&b.0)),
    }
}

/// The units the handshake ceilings of `target`'s family rest on: (datapath, stages, flags,
/// RTL digest), for `specgen stale`.
pub fn handshake_units(target: Target) -> Vec<(String, u32, String, String)> {
    let Some(family) = family(target) else {
        return Vec::new();
    };
    let text = |v: &serde_json::Value| v.as_str().unwrap_or_default().to_string();
    model_json()["handshake"][family]
        .as_object()
        .into_iter()
        .flatten()
        .map(|(name, c)| {
            (
                name.clone(),
                c["stages"].as_u64().unwrap_or(0) as u32,
                text(&c["args"]),
                text(&c["digest"]),
            )
        })
        .collect()
}

/// `data/delay_model.json`, parsed once.
fn model_json() -> &'static serde_json::Value {
    static MODEL: std::sync::OnceLock<serde_json::Value> = std::sync::OnceLock::new();
    MODEL.get_or_init(|| serde_json::from_str(MODEL_JSON).expect("data/delay_model.json is JSON"))
}

/// The slowest limit of the blocks with their own registers that `plan` instantiates (the
/// ECP5's MULT18X18D and DP16KD) at speed grade 6, the part the delay model is calibrated on
/// (`crate::family`): no prediction and no pick passes it. None for a unit without them (an
/// iCE40 unit's products are yosys's to map, and the delay model's figures there are already
/// below the SB_MAC16's).
fn block_cap(plan: &Plan) -> Option<crate::family::blocks::BlockLimit> {
    let dp = &plan.datapath;
    crate::family::blocks::slowest(&crate::family::of(plan.cfg.target()).block_limits(
        6,
        dp.has_dsp_blocks(),
        dp.has_block_rams(),
    ))
    .cloned()
}

/// The shallowest depth of `plan`'s configuration whose predicted Fmax (with the fit's margin)
/// reaches `mhz`, and that prediction. Err: no depth does (the best one is named).
pub fn pick_stages(plan: &Plan, mhz: f64) -> Result<(u32, f64), Error> {
    pick_stages_reporting(plan, mhz, |_, _| {}).map(|(p, f)| (p.cfg.stages(), f))
}

/// [`pick_stages`], telling `progress(depth, deepest)` before each depth it plans (a wide
/// configuration takes a while: the caller shows that it works). Returns the plan chosen (not
/// planned again) and its prediction.
pub fn pick_stages_reporting(
    plan: &Plan,
    mhz: f64,
    progress: impl Fn(u32, u32),
) -> Result<(Plan, f64), Error> {
    let l = line_of(plan)?;
    // a ready/axis unit on a part where no unit with the output buffer was measured: its own
    // paths have no shape in the delay model and no ceiling measured, so no pick is assured
    if plan.cfg.interface().handshake() && handshake_cap(plan).is_none() {
        return Err(Error::Config {
            parameter: "target_mhz",
            message: format!(
                "no {} unit was measured on the {} on today's RTL: its output buffer's own paths are outside the delay model, so no depth is assured; allowed: --interface valid with --target-mhz, or --stages N; to measure some: specgen explore --target {} --interface {} --out DIR --results RESULTS --run, then specgen stale --explored DIR/points.json --write-calibration ROWS and specgen calibrate",
                plan.cfg.interface().name(),
                part(plan.cfg.target()),
                plan.cfg.target().name(),
                plan.cfg.interface().name()
            ),
        });
    }
    let mut best = (0, 0.0f64, 0.0f64, Rule::Line);
    // a depth whose blocks cannot run at mhz is no pick, whatever its routes (the first seen)
    let mut capped: Option<(u32, crate::family::blocks::BlockLimit)> = None;
    for stages in 0..=plan.cut_points {
        progress(stages, plan.cut_points);
        let p = plan.with_stages(stages)?;
        let (f, (assured, rule)) = (l.fmax_of(&p), l.assured_by_rule(&p));
        let cap = block_cap(&p);
        if let Some(c) = cap.as_ref().filter(|c| c.mhz() < mhz && assured >= mhz) {
            capped.get_or_insert((stages, c.clone()));
        }
        let (f, assured) = cap
            .as_ref()
            .map_or((f, assured), |c| (f.min(c.mhz()), assured.min(c.mhz())));
        let (f, assured) =
            handshake_cap(&p).map_or((f, assured), |(c, _)| (f.min(c), assured.min(c)));
        if assured >= mhz {
            return Ok((p, f));
        }
        if assured > best.2 {
            best = (stages, f, assured, rule);
        }
    }
    if let Some((stages, c)) = capped {
        // the same block's limit at the faster grades, from the family (one home)
        let at = |grade: u32| {
            crate::family::of(plan.cfg.target())
                .block_limits(grade, true, true)
                .into_iter()
                .find(|l| l.block == c.block)
                .map_or("?".to_string(), |l| format!("{:.1}", l.mhz()))
        };
        return Err(Error::Config {
            parameter: "target_mhz",
            message: format!(
                "{mhz} MHz is above what the blocks allow on the {}: at --stages {stages} the routes would reach it, but the {} (at most {:.1} MHz); allowed: at most {:.1} MHz here (--stages {}), or a faster speed grade (specgen synth --speed 7 or 8 measures one: {} {} or {} MHz; this delay model is calibrated on grade 6)",
                part(plan.cfg.target()),
                c.what,
                c.mhz(),
                best.2,
                best.0,
                c.block,
                at(7),
                at(8)
            ),
        });
    }
    let how = match (best.3, outside_calibration(plan)) {
        (Rule::Floor, _) => "a unit of these widths measured on today's RTL",
        (Rule::Between, _) => "read from the calibrated widths around these, not measured at them",
        (Rule::Line, Some(n)) if n.starts_with("outside") => "extrapolated: these widths are outside the calibration",
        (Rule::Line, _) => "extrapolated by the delay model's line: no unit of today's RTL at or around these widths bounds it",
    };
    let handshake = match handshake_cap(plan) {
        Some((c, _)) if c < mhz => {
            format!("; the {} interface's output buffer has paths of its own, measured at most {c:.1} MHz here on today's RTL", plan.cfg.interface().name())
        }
        _ => String::new(),
    };
    Err(Error::Config {
        parameter: "target_mhz",
        message: format!(
            "{mhz} MHz is not assured on the {}: no unit of this configuration measured on today's RTL reaches it, and the delay model assures at most {:.1} MHz, at --stages {} ({how}){handshake}",
            part(plan.cfg.target()),
            best.2,
            best.0
        ),
    })
}

/// Why [`pick_stages`] refused `mhz` for `plan`, at length (`generate --explain`): the best
/// depth's figures, the rule that gave them (which calibrated widths, which unit holds the
/// figure down, the margins) and the handshake's ceiling.
pub fn explain_refusal(plan: &Plan, mhz: f64) -> Result<Vec<String>, Error> {
    let l = line_of(plan)?;
    let mut best: Option<(Plan, f64)> = None;
    for stages in 0..=plan.cut_points {
        let p = plan.with_stages(stages)?;
        let a = under_caps(&p, l.assured_of(&p));
        if best.as_ref().is_none_or(|b| a > b.1) {
            best = Some((p, a));
        }
    }
    let Some((p, assured)) = best else {
        return Ok(Vec::new());
    };
    let (e, m) = stretches(&p);
    let mut lines = vec![format!(
        "the best depth for {mhz} MHz, --stages {}: assured {assured:.1} MHz, predicted {:.1} (the line: {:.2} ns + {:.3} ns a unit of the slowest stretch {:.1} + {:.3} a unit of the mean {:.1}; margin {:.2}; R² {:.2})",
        p.cfg.stages(),
        predicted_fmax(&p).unwrap_or(0.0),
        l.offset_ns,
        l.ns_per_unit,
        e,
        l.ns_per_mean_unit,
        m,
        l.margin,
        l.r2
    )];
    if let Some(b) = block_cap(&p) {
        lines.push(format!(
            "the blocks' limit: {} (at most {:.1} MHz)",
            b.what,
            b.mhz()
        ));
    }
    if let Some(n) = outside_calibration(&p) {
        lines.push(n);
    }
    if let Some((args, stages, f, floor)) = l.nearest_unit(p.cfg.stages(), e) {
        let widths = if args.is_empty() {
            "the default widths"
        } else {
            args
        };
        lines.push(match floor {
            true => {
                format!("the calibrated unit that holds it: {widths} at --stages {stages}, {f:.1} MHz measured, times the corner margin {:.2}", corner_margin())
            }
            false => format!("the calibrated unit that caps it: {widths} at --stages {stages}, {f:.1} MHz measured"),
        });
    }
    if let Some((c, which)) = handshake_cap(plan) {
        lines.push(format!(
            "the {} interface's output buffer has paths of its own, which no calibration unit has: the most a unit with one was measured at on this part is {c:.1} MHz ({which}, on today's RTL)",
            plan.cfg.interface().name()
        ));
    }
    Ok(lines)
}

#[cfg(test)]
mod data_tests;
mod shape;
#[cfg(test)]
mod tests;

pub mod fit;
