//! `specgen info --json`: what this specgen offers, for scripts.

use super::{outln, Failure, ParamArgs, RtlArgs};
use specgen::plan::Plan;

/// The version, models, targets and the deepest depth of the configuration the flags give.
pub fn run(params: &ParamArgs, rtl: RtlArgs) -> Result<(), Failure> {
    let cfg = params.to_config(Some(&RtlArgs {
        stages: Some(0),
        ..rtl
    }))?;
    let plan = Plan::new(cfg)?;
    let targets: Vec<serde_json::Value> = specgen::config::Target::ALL
        .iter()
        .map(|&t| {
            serde_json::json!({
                "name": t.name(),
                "part": specgen::timing::part(t),
                "target_mhz": specgen::timing::calibrated(t),
                "explored": specgen::family::of(t).explored().is_some(),
            })
        })
        .collect();
    let info = serde_json::json!({
        "generator": "specgen",
        "version": specgen::names::VERSION,
        "models": specgen::config::SpecularModel::ALL.iter().map(|m| m.name()).collect::<Vec<_>>(),
        "targets": targets,
        "configuration": { "model": plan.cfg.model().name(), "target": plan.cfg.target().name(), "deepest_stages": plan.cut_points },
    });
    outln!(
        "{}",
        serde_json::to_string_pretty(&info).expect("serialises")
    )?;
    Ok(())
}
