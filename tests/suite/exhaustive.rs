//! Exhaustive sweep of the golden model against the exact reference for the default
//! configuration (both rounding modes, and every model): every (cos_g, n) over the whole cos_g port
//! (including codes above 1.0), colours varied so every channel sees every code.

use specgen::config::{Config, Params, Rounding, SpecularModel};
use specgen::models::{self, Inputs, Model};

fn sweep(cfg: &Config) {
    let m = Model::new(cfg);
    let f = cfg.f();
    let bm = (1u32 << cfg.b()) - 1;
    let n_count = 1u32 << cfg.n_bits();
    let bad = std::thread::scope(|s| {
        let parts: Vec<_> = (0..2u32)
            .map(|part| {
                let m = &m;
                s.spawn(move || {
                    let mut bad = 0u64;
                    for n in (part * n_count / 2)..((part + 1) * n_count / 2) {
                        let mut prev: Option<models::Outputs> = None;
                        for cos_g in 0..(2u32 << f) {
                            let ks = [
                                (cos_g + n) & bm,
                                (cos_g + 3 * n + 85) & bm,
                                (cos_g + 7 * n + 170) & bm,
                            ];
                            let x = Inputs { cos_g, n, ks };
                            let o = m.eval(x);
                            if let Err(e) = m.check(x, o) {
                                if bad == 0 {
                                    eprintln!("{x:?}: {e}");
                                }
                                bad += 1;
                            }
                            if cfg.model() == SpecularModel::Quadratic {
                                let rom_done = cos_g.min(1 << f)
                                    < m.unit()
                                        .cut_off(n)
                                        .expect("the quadratic unit stores its cut-off");
                                assert_eq!(o.done, rom_done, "{x:?}");
                            }
                            // monotonic in cos_g for fixed n: check intensity (colours vary along the row)
                            if let Some(p) = prev {
                                assert!(o.intensity >= p.intensity, "{x:?}");
                            }
                            prev = Some(o);
                        }
                    }
                    bad
                })
            })
            .collect();
        parts.into_iter().map(|p| p.join().unwrap()).sum::<u64>()
    });
    assert_eq!(
        bad,
        0,
        "{bad} outputs break the {} contract",
        cfg.rounding().name()
    );
}

#[test]
fn default_faithful_whole_input_space() {
    sweep(&Config::defaults());
}

#[test]
fn default_exact_whole_input_space() {
    sweep(
        &Config::new(Params {
            rounding: Rounding::Exact,
            ..Params::default()
        })
        .unwrap(),
    );
}

/// Every model of the registry at narrow widths (F = FI = 8, N = 6, B = 4; a model added to
/// `SpecularModel::ALL` is swept here with no line changing); at default widths in
/// `every_model_default_whole_input_space`, outside the suite's budget.
#[test]
fn every_model_narrow_whole_input_space() {
    for model in SpecularModel::ALL {
        sweep(
            &Config::new(Params {
                model,
                cos_frac_bits: 8,
                intensity_frac_bits: 8,
                n_bits: 6,
                color_bits: 4,
                ..Params::default()
            })
            .unwrap(),
        );
    }
}

/// Every other model of the registry at its defaults (a model added to `SpecularModel::ALL` is
/// swept here with no line changing).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn every_model_default_whole_input_space() {
    for model in SpecularModel::ALL
        .into_iter()
        .filter(|&m| m != Params::default().model)
    {
        sweep(
            &Config::new(Params {
                model,
                ..Params::default()
            })
            .unwrap(),
        );
    }
}
