//! The plan of one command: a validated configuration, its model (fit or tables made), its
//! widths with the registers placed, and the datapath they give — built once, and taken by
//! everything downstream (the RTL, the tables, the golden model, the manifest).
//!
//! This is also where `--stages` is bounded: by the cut points of this configuration's own
//! datapath, which only exists once the model is made.

use crate::config::{Config, ConfigError, Params, SpecularModel};
use crate::datapath::{self, Datapath};
use crate::model::{Kind, Model};
use crate::widths::{balanced_cuts, Widths};

#[derive(Debug, Clone)]
pub struct Plan {
    pub cfg: Config,
    pub kind: Kind,
    pub widths: Widths,
    pub datapath: Datapath,
    /// the most `--stages` this configuration takes
    pub cut_points: u32,
}

impl Plan {
    pub fn new(cfg: Config) -> Result<Plan, ConfigError> {
        let kind = Kind::new(&cfg);
        let flat = Widths::derive_unpipelined(&cfg);
        let combinational = datapath::build_for(&cfg, &flat, &kind);
        let cut_points = combinational.steps.len() as u32;
        if cfg.stages() > cut_points {
            return Err(ConfigError {
                parameter: "stages",
                message: format!(
                    "{} is out of range; allowed 0..={cut_points} (the cut points of the {} datapath with these widths)",
                    cfg.stages(),
                    match cfg.model() {
                        SpecularModel::Quadratic => cfg.arch().name(),
                        other => other.name(),
                    }
                ),
            });
        }
        let widths = flat.with_cuts(balanced_cuts(&combinational.delays(), cfg.stages()));
        let datapath = if cfg.stages() == 0 { combinational } else { datapath::build_for(&cfg, &widths, &kind) };
        Ok(Plan { cfg, kind, widths, datapath, cut_points })
    }

    pub fn from_params(params: Params) -> Result<Plan, ConfigError> {
        Plan::new(Config::new(params)?)
    }

    /// The golden model of this plan.
    pub fn model(&self) -> Model {
        Model::from_parts(&self.cfg, self.widths.clone(), self.kind.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_builds_nothing_and_the_plan_bounds_stages() {
        // a configuration is valid without its datapath; the plan knows the cut points
        let cfg = Config::new(Params { stages: 99, ..Params::default() }).expect("stages are the plan's to check");
        let e = Plan::new(cfg).unwrap_err();
        assert_eq!(e.parameter, "stages");
        assert!(e.message.contains("allowed 0..=13"), "{}", e.message);
        for model in [SpecularModel::Quadratic, SpecularModel::Fitted, SpecularModel::Blinn, SpecularModel::BlinnPow] {
            let top = Plan::from_params(Params { model, stages: 0, n_bits: 6, ..Params::default() }).unwrap().cut_points;
            let plan = Plan::from_params(Params { model, stages: top, n_bits: 6, ..Params::default() }).unwrap();
            // every cut registered, and the same registers as the widths derived on their own
            assert_eq!(plan.widths.registered_cuts, (1..=top).collect::<Vec<_>>(), "{model:?}");
            assert_eq!(plan.widths, Widths::derive(&plan.cfg), "{model:?}");
            assert_eq!(plan.datapath.steps.len() as u32, top);
        }
    }
}
