//! The same properties for every model, through the one trait (`SpecularUnit` behind
//! `Model`), over random configurations across the width ranges: the model meets its own
//! contract (its exact reference), every output is non-decreasing in `cos_g`, `n = 0` and
//! `c = 1.0` give exactly full scale, no intensity where `done` or below `n`'s boundary, and the plan
//! builds its datapath at every depth. A new model in `SpecularModel::ALL` is covered here
//! without a line of this file changing; its own module adds the big-integer reference.

use proptest::prelude::*;
use specgen::config::{Config, SpecularModel};
use specgen::models::{Inputs, Model};
use specgen::plan::Plan;

fn any_model_config() -> impl Strategy<Value = Config> {
    proptest::sample::select(SpecularModel::ALL.to_vec()).prop_flat_map(crate::common::model_config)
}

/// An input of `cfg` from a seed: any `cos_g` port code (above 1.0 too), any n and colours.
fn input(cfg: &Config, seed: u64) -> Inputs {
    let r = specgen::bits::splitmix(seed);
    let r2 = specgen::bits::splitmix(r);
    let ks = |s: u32| ((r2 >> s) as u32) & ((1 << cfg.b()) - 1);
    Inputs {
        cos_g: (r as u32) & ((2u32 << cfg.f()) - 1),
        n: ((r >> 32) as u32) & ((1 << cfg.n_bits()) - 1),
        ks: [ks(0), ks(16), ks(32)],
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn every_model_meets_its_contract_and_is_monotone(cfg in any_model_config(), seeds in proptest::collection::vec(any::<u64>(), 24)) {
        let m = Model::new(&cfg);
        let one = 1u32 << cfg.f();
        for &seed in &seeds {
            let x = input(&cfg, seed);
            let o = m.eval(x);
            prop_assert!(m.check(x, o).is_ok(), "{:?} {x:?} {o:?}: {:?}", cfg.params, m.check(x, o));
            // one code further up never gives less, on any output
            let up = Inputs { cos_g: (x.cos_g + 1).min(2 * one - 1), ..x };
            let p = m.eval(up);
            prop_assert!(p.intensity >= o.intensity && (0..3).all(|i| p.spec[i] >= o.spec[i]), "{:?}: {x:?} {o:?} then {p:?}", cfg.params);
            // c = 1.0 (and every code above it) and n = 0 are full scale, exactly
            let full = |x: Inputs| m.eval(x);
            for y in [Inputs { cos_g: one + (seed as u32 % one), ..x }, Inputs { n: 0, ..x }] {
                let f = full(y);
                prop_assert_eq!(f.intensity, 1u32 << cfg.fi(), "{:?} {:?}", cfg.params, y);
                prop_assert_eq!(f.spec, y.ks);
                prop_assert!(!f.done);
            }
            // `done` is the end of the highlight: no intensity there (the cos^n models' colours,
            // wider than the intensity, may still round to a last glint)
            prop_assert!(!o.done || o.intensity == 0, "{:?} {x:?} {o:?}", cfg.params);
            // below n's boundary (the stored cut-off, or the first code with an intensity) the
            // intensity is 0 (a colour wider than the intensity may still show a last glint)
            let edge = m.boundary(x.n);
            if edge > 0 {
                let below = m.eval(Inputs { cos_g: edge - 1, ..x });
                prop_assert!(below.intensity == 0, "{:?} n={} boundary {}: {below:?}", cfg.params, x.n, edge);
            }
        }
    }

    #[test]
    fn every_model_plans_at_every_depth(cfg in any_model_config()) {
        let flat = Plan::new(cfg).unwrap();
        prop_assert!(flat.cut_points > 0);
        for stages in [1, flat.cut_points / 2, flat.cut_points] {
            let p = flat.with_stages(stages.max(1)).unwrap();
            prop_assert_eq!(p.registered_cuts.len() as u32, stages.max(1));
            prop_assert_eq!(p.datapath.steps.len() as u32, flat.cut_points);
            let outputs: Vec<&str> = p.datapath.outputs.iter().map(|(o, _)| o.as_str()).collect();
            prop_assert_eq!(outputs, specgen::plan::OUTPUT_SIGNALS.to_vec());
        }
    }
}
