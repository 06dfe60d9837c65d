//! One depth search for a clock, used by `generate --target-mhz`, by `explore` when it plans
//! the depths it measures, and by the choice among measured units alike.
//!
//! **Measured points first.** A unit of this very configuration (every parameter but the depth,
//! the interface and its edge included) measured on today's RTL (its jobs' fingerprints are
//! those of the unit specgen writes now: [`super::measured_today`]) whose median Fmax over its
//! seeds reaches the clock: the shallowest such depth, and the evidence says which unit, which
//! seeds, which RTL digest. A row of another RTL is never evidence.
//!
//! **Else the delay model** (`crate::timing`), with a policy: [`Policy::Assured`] scans for the
//! shallowest depth whose assured figure reaches the clock (what `generate` promises);
//! [`Policy::Predicted`] bisects on the predicted figure (what `explore` plans to measure, whose
//! verdict is the measurement). Its figure is labelled *interpolated* where the delay model
//! reads calibration units of these widths or of widths around them, *extrapolated* where it
//! follows its line outside them; neither is a measurement, and the pick says how to measure it.

use super::{measured_today, Exploration};
use crate::config::Params;
use crate::error::Error;
use crate::plan::Plan;

/// What figure a depth search compares with the clock where no measured unit answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Policy {
    /// the delay model's prediction (a guess to be measured: `explore`'s plan)
    Predicted,
    /// the delay model's assured figure (a promise: `generate --target-mhz`)
    Assured,
}

/// What a depth's clock rests on.
#[derive(Debug, Clone, PartialEq)]
pub enum ClockEvidence {
    /// a unit of this configuration measured on today's RTL
    Measured {
        /// the exploration point's id, and the part
        id: String,
        part: String,
        /// the median over the seeds, and the seeds
        median: f64,
        seeds: Vec<u32>,
        /// the SHA-256 of the RTL and tables measured (today's)
        digest: String,
    },
    /// the delay model's figure; `extrapolated`: outside every calibrated width (its line
    /// alone), else read from calibration units at or around these widths; `note`: how
    Modelled {
        figure: f64,
        predicted: f64,
        extrapolated: bool,
        note: Option<String>,
    },
}

impl std::fmt::Display for ClockEvidence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ClockEvidence::Measured { id, part, median, seeds, digest } => write!(
                f,
                "measured: {median:.1} MHz, median over nextpnr seeds {} of {id} on the {part}, today's RTL (sha256 {})",
                crate::synth::seed_list(seeds),
                &digest[..digest.len().min(16)]
            ),
            ClockEvidence::Modelled { figure, predicted, extrapolated, note } => {
                let kind = if *extrapolated { "extrapolated" } else { "interpolated" };
                write!(f, "{kind}: {figure:.1} MHz by the delay model (predicted {predicted:.1}), not a measurement of this unit")?;
                if let Some(n) = note {
                    write!(f, " ({n})")?;
                }
                Ok(())
            }
        }
    }
}

/// A depth chosen for a clock: the plan at that depth, and what its clock rests on.
#[derive(Debug, Clone)]
pub struct DepthPick {
    pub plan: Plan,
    pub evidence: ClockEvidence,
}

/// The built-in exploration of `target`'s family (what `generate --max-error` and
/// `--target-mhz` read), if one was measured: read once per process (`explore` asks for it at
/// every shape and clock it plans).
pub fn built_in(target: crate::config::Target) -> Result<Option<&'static Exploration>, Error> {
    use crate::config::Target;
    use std::sync::OnceLock;
    static BUILT: [OnceLock<Option<Exploration>>; Target::ALL.len()] =
        [const { OnceLock::new() }; Target::ALL.len()];
    let slot = &BUILT[Target::ALL
        .iter()
        .position(|t| *t == target)
        .expect("a target of ALL")];
    if let Some(e) = slot.get() {
        return Ok(e.as_ref());
    }
    let read = crate::family::of(target)
        .explored()
        .map(|text| Exploration::from_text(text, "the built-in exploration"))
        .transpose()?;
    Ok(slot.get_or_init(|| read).as_ref())
}

/// Parameters with what does not change which unit is measured cleared: its depth, the clock
/// its constraints name, its names.
pub fn measured_shape(p: &Params) -> Params {
    Params {
        stages: 0,
        clock_mhz: None,
        top: Params::default().top,
        clock_port: None,
        ..p.clone()
    }
}

/// The shallowest depth of `plan`'s configuration whose clock reaches `mhz`: a unit measured on
/// today's RTL in `explored` (the family's built-in exploration when None) first, else the
/// delay model under `policy`. `progress(depth, deepest)` hears each depth the model plans.
/// Err: no depth reaches it (the delay model's reason, which names the best depth).
pub fn depth_for_clock(
    plan: &Plan,
    mhz: f64,
    policy: Policy,
    explored: Option<&Exploration>,
    progress: impl Fn(u32, u32),
) -> Result<DepthPick, Error> {
    depth_and_options_for_clock(plan, mhz, policy, explored, &[], progress)
}

/// [`depth_for_clock`], where the options named in `free` (`rom_style`, `fabric_registers`: the
/// ones the user did not give) may be chosen too, from measured units only: where no measured
/// unit with this configuration's own options reaches `mhz`, the unit of the fewest logic cells
/// (then the shallowest) among those measured on today's RTL with other options that does.
/// The delay model, where it speaks, keeps the configuration's options.
pub fn depth_and_options_for_clock(
    plan: &Plan,
    mhz: f64,
    policy: Policy,
    explored: Option<&Exploration>,
    free: &[&str],
    progress: impl Fn(u32, u32),
) -> Result<DepthPick, Error> {
    if let Some(pick) = measured_depth(plan, mhz, explored, free)? {
        return Ok(pick);
    }
    let (chosen, predicted, figure) = match policy {
        Policy::Assured => {
            let (p, f) = crate::timing::pick_stages_reporting(plan, mhz, progress)?;
            let assured = crate::timing::assured_fmax(&p).unwrap_or(f);
            (p, f, assured)
        }
        Policy::Predicted => {
            let p = predicted_depth(plan, mhz)?;
            let f = crate::timing::predicted_fmax(&p).unwrap_or(0.0);
            (p, f, f)
        }
    };
    // extrapolated where the line spoke, not a unit of today's RTL at or around these widths
    let extrapolated = crate::timing::assured_reading(&chosen)
        .is_none_or(|(_, rule)| rule == crate::timing::Rule::Line);
    let note = crate::timing::outside_calibration(&chosen).or_else(|| {
        extrapolated.then(|| "the delay model's line times its margin: no unit of these widths measured on today's RTL bounds this depth".to_string())
    });
    Ok(DepthPick {
        plan: chosen,
        evidence: ClockEvidence::Modelled {
            figure,
            predicted,
            extrapolated,
            note,
        },
    })
}

/// The measured step of [`depth_for_clock`]: None where no unit of this configuration measured
/// on today's RTL reaches `mhz`.
fn measured_depth(
    plan: &Plan,
    mhz: f64,
    explored: Option<&Exploration>,
    free: &[&str],
) -> Result<Option<DepthPick>, Error> {
    let e = match explored {
        Some(e) => e,
        None => match built_in(plan.cfg.target())? {
            Some(b) => b,
            None => return Ok(None),
        },
    };
    // the shape a measured unit must have: this configuration's, the free options aside
    let loose = |p: &Params| {
        let mut s = measured_shape(p);
        if free.contains(&"rom_style") {
            s.rom_style = Params::default().rom_style;
        }
        if free.contains(&"fabric_registers") {
            s.fabric_registers = false;
        }
        s
    };
    let want = loose(&plan.cfg.params);
    let mut reaching: Vec<&super::Point> = e
        .points
        .iter()
        .filter(|p| loose(&p.params) == want)
        .filter(|p| {
            p.measured
                .as_ref()
                .and_then(|m| m.fmax_mhz)
                .is_some_and(|f| f >= mhz)
        })
        .collect();
    // this configuration's own options first, the shallowest that reaches it; else the
    // cheapest unit of other options that does
    let other = |p: &super::Point| measured_shape(&p.params) != measured_shape(&plan.cfg.params);
    reaching.sort_by_key(|p| (other(p), if other(p) { p.cells() } else { 0 }, p.stages));
    for p in reaching {
        // a row of another RTL is never evidence
        let Some(digest) = measured_today(p)? else {
            continue;
        };
        let m = p.measured.as_ref().expect("measured");
        let evidence = ClockEvidence::Measured {
            id: p.id.clone(),
            part: e.part.clone(),
            median: m.fmax_mhz.unwrap_or(0.0),
            seeds: m.seeds.clone(),
            digest,
        };
        let params = Params {
            stages: p.stages,
            rom_style: p.params.rom_style,
            fabric_registers: p.params.fabric_registers,
            ..plan.cfg.params.clone()
        };
        let chosen = match measured_shape(&params) == measured_shape(&plan.cfg.params) {
            true => plan.with_stages(p.stages)?,
            false => Plan::new(crate::config::Config::new(params)?)?,
        };
        return Ok(Some(DepthPick {
            plan: chosen,
            evidence,
        }));
    }
    Ok(None)
}

/// The shallowest depth predicted to reach `mhz` (a bisection: the prediction grows with
/// depth), or the deepest where none is; Err without a delay model.
fn predicted_depth(plan: &Plan, mhz: f64) -> Result<Plan, Error> {
    let predicted = |d: u32| -> Result<Option<f64>, Error> {
        Ok(crate::timing::predicted_fmax(&plan.with_stages(d)?))
    };
    let deepest = plan.cut_points;
    match predicted(deepest)? {
        None => {
            return Err(
                crate::timing::line(plan.cfg.target(), plan.cfg.datapath_name())
                    .err()
                    .unwrap_or_else(|| crate::error::input("no delay model")),
            )
        }
        Some(f) if f < mhz => return plan.with_stages(deepest),
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
    plan.with_stages(lo)
}

/// What `specgen stale` finds of the delay model's calibration on one family.
#[derive(Debug, Clone, Default)]
pub struct CalibrationEvidence {
    /// floors (rows naming an RTL digest) whose digest is today's for their unit
    pub today: usize,
    /// floors whose digest is not today's: `<datapath> <args> --stages N`
    pub stale: Vec<String>,
    /// rows that name no digest: the fit's data, never a floor
    pub fit_only: usize,
}

/// The delay model's calibration units on `target`'s family, each floor's RTL digest checked
/// against the unit specgen writes today (each unit generated once: seconds).
pub fn calibration_evidence(target: crate::config::Target) -> Result<CalibrationEvidence, Error> {
    let mut ev = CalibrationEvidence::default();
    // a calibration unit is generated as scripts/calibrate_delay.sh does: the default
    // parameters but the datapath's model and architecture, the row's flags and depth
    let today = |datapath: &str, args: &str, stages: u32| {
        crate::config::datapaths(target)
            .into_iter()
            .find(|(n, _)| *n == datapath)
            .and_then(|(_, base)| crate::timing::params_with_args(&base, args))
            .and_then(|p| Plan::from_params(Params { stages, ..p }).ok())
            .map(|plan| crate::emit::rtl_digest(&plan))
    };
    // the units the handshake ceilings rest on: each a floor of its own
    for (name, stages, args, digest) in crate::timing::handshake_units(target) {
        match today(&name, &args, stages) == Some(digest) {
            true => ev.today += 1,
            false => ev.stale.push(format!(
                "{name} {args} --stages {stages} (a handshake's ceiling)"
            )),
        }
    }
    for (name, l) in crate::timing::lines(target) {
        for i in 0..l.measured.len() {
            let digest = l.measured_digest.get(i).map_or("", String::as_str);
            let (args, stages) = (
                l.measured_args.get(i).map_or("", String::as_str),
                l.measured_stages.get(i).copied().unwrap_or(0),
            );
            if digest.is_empty() {
                ev.fit_only += 1;
                continue;
            }
            match today(&name, args, stages).as_deref() == Some(digest) {
                true => ev.today += 1,
                false => ev
                    .stale
                    .push(format!("{name} {args} --stages {stages}").replace("  ", " ")),
            }
        }
    }
    Ok(ev)
}
