//! The models beyond the paper (SPEC §6): `fitted` and `blinn`, as the quadratic unit is
//! tested — properties over random configurations against exact references (big integers),
//! monotonicity, the error budgets, the fit's quality, and the fidelity figures.

use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use proptest::prelude::*;
use specgen::config::{Config, Params, SpecularModel};
use specgen::models::blinn::{BlinnWidths, Shares};
use specgen::models::{Inputs, Model};

/// blinn configurations over every width range.
fn blinn_config() -> impl Strategy<Value = Config> {
    crate::common::power_config(SpecularModel::Blinn)
}

/// fitted configurations over every width range (n_bits up to 9: each new fit well under a second).
fn fitted_config() -> impl Strategy<Value = Config> {
    crate::common::model_config(SpecularModel::Fitted)
}

/// A random input; one in three near 1.0 (where c^n is not tiny), one in three near the
/// last code with a non-zero output.
fn input(cfg: &Config, m: &Model, seed: u64) -> Inputs {
    let r = specgen::bits::splitmix(seed);
    let n = (r as u32) & ((1 << cfg.n_bits()) - 1);
    let one = 1u32 << cfg.f();
    let cos_g = match seed % 3 {
        0 => one.saturating_sub((r >> 40) as u32 % 64),
        1 => {
            let b = m.boundary(n) as i64;
            (b + ((r >> 40) % 5) as i64 - 2).clamp(0, (2 * one - 1) as i64) as u32
        }
        _ => ((r >> 12) as u32) & (2 * one - 1),
    };
    let r2 = specgen::bits::splitmix(r);
    let bm = (1u64 << cfg.b()) - 1;
    Inputs {
        cos_g,
        n,
        ks: [
            (r2 & bm) as u32,
            ((r2 >> 16) & bm) as u32,
            ((r2 >> 32) & bm) as u32,
        ],
    }
}

/// `|got − ideal/2^den| < 1`, and `got = ideal/2^den` where that is an integer.
fn faithful(got: u32, ideal: &BigInt, den_log2: u32) -> bool {
    let one = BigInt::from(1) << den_log2;
    let diff = ((BigInt::from(got) << den_log2) - ideal).abs();
    diff < one && (!(ideal % &one).is_zero() || diff.is_zero())
}

/// Every output of `m` for `x` within one unit of `c^n·M` (exact big integers).
fn faithful_to_power(cfg: &Config, x: Inputs, o: specgen::models::Outputs) -> Result<(), String> {
    let c = BigInt::from(x.cos_g.min(1 << cfg.f()));
    let den = cfg.f() * x.n;
    let pow = c.pow(x.n);
    if !faithful(o.intensity, &(&pow << cfg.fi()), den) {
        return Err(format!(
            "intensity {} vs c^n = {}",
            o.intensity,
            (x.cos_g.min(1 << cfg.f()) as f64 / (cfg.f() as f64).exp2()).powi(x.n as i32)
        ));
    }
    for ch in 0..3 {
        if !faithful(o.spec[ch], &(&pow * BigInt::from(x.ks[ch])), den) {
            return Err(format!("spec[{ch}] {} (ks {})", o.spec[ch], x.ks[ch]));
        }
    }
    if o.done != (o.intensity == 0) {
        return Err("done != (intensity == 0)".into());
    }
    Ok(())
}

proptest! {
    // 128 configurations a property: each draws a new fit or table (well under a second), so
    // configurations are what a case costs; every case checks many inputs
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// blinn: every output within one unit of the exact c^n·M, exact at integer ideals,
    /// done ⇔ intensity 0; the library's own check agrees.
    #[test]
    fn blinn_is_faithful_to_the_exact_power(cfg in blinn_config(), seeds in proptest::collection::vec(any::<u64>(), 24)) {
        let m = Model::new(&cfg);
        for &seed in &seeds {
            let x = input(&cfg, &m, seed);
            let o = m.eval(x);
            prop_assert!(faithful_to_power(&cfg, x, o).is_ok(), "{:?} {:?} {:?}: {:?}", cfg.params, x, o, faithful_to_power(&cfg, x, o));
            prop_assert!(m.check(x, o).is_ok(), "{:?}", m.check(x, o));
        }
    }

    /// blinn: each width of the budget is the smallest that keeps its share, the shares close
    /// the budget below 1/2, and taking one bit off any width breaks its share.
    #[test]
    fn blinn_budget_closes_and_every_bit_is_needed(cfg in blinn_config()) {
        let w = BlinnWidths::derive(&cfg);
        prop_assert!(w.budget(&cfg).holds(), "{:?}", w.budget(&cfg));
        type Share = fn(&BlinnWidths, &Config) -> bool;
        let knobs: [(&str, Share, BlinnWidths); 6] = [
            ("WY", Shares::y_truncation, BlinnWidths { y_frac_bits: w.y_frac_bits - 1, ..w.clone() }),
            ("WL", Shares::ell_truncation, BlinnWidths { ell_frac_bits: w.ell_frac_bits - 1, ..w.clone() }),
            ("WG", Shares::log_entries, BlinnWidths { log_frac_bits: w.log_frac_bits - 1, ..w.clone() }),
            ("TG", Shares::log_table, BlinnWidths { log_index_bits: w.log_index_bits - 1, ..w.clone() }),
            ("WE", Shares::exp2_entries, BlinnWidths { exp2_frac_bits: w.exp2_frac_bits - 1, ..w.clone() }),
            ("TE", Shares::exp2_table, BlinnWidths { exp2_index_bits: w.exp2_index_bits - 1, ..w.clone() }),
        ];
        for (name, share, less) in knobs {
            prop_assert!(share(&w, &cfg), "{name} breaks its own share");
            let floor = match name { "WY" | "WL" | "WG" | "TG" | "TE" => 1, _ => cfg.fi() + 1 };
            let at_floor = match name { "WY" => w.y_frac_bits, "WL" => w.ell_frac_bits, "WG" => w.log_frac_bits, "TG" => w.log_index_bits, "TE" => w.exp2_index_bits, _ => w.exp2_frac_bits } <= floor;
            prop_assert!(at_floor || !share(&less, &cfg), "{name} has a bit to spare: {:?}", cfg.params);
        }
    }

    /// fitted: outputs within one unit of S = [1 − a_n(1 − c)]^(2^m_n) with the stored a_n
    /// (exact big integers, independent of the library's check), exact at integer ideals,
    /// done ⇔ the bracket is negative, 0 beyond it.
    #[test]
    fn fitted_is_faithful_to_its_formula(cfg in fitted_config(), seeds in proptest::collection::vec(any::<u64>(), 24)) {
        let m = Model::new(&cfg);
        let fit = specgen::models::fitted::cached_fit(&cfg);
        for &seed in &seeds {
            let x = input(&cfg, &m, seed);
            let o = m.eval(x);
            let den = cfg.kf() + cfg.f();
            let d = BigInt::from((1u32 << cfg.f()) - x.cos_g.min(1 << cfg.f()));
            let base = (BigInt::from(1) << den) - BigInt::from(fit.a_code[x.n as usize]) * d;
            let negative = base.is_negative();
            prop_assert_eq!(o.done, negative, "{:?} {:?}", cfg.params, x);
            let e = 1u32 << fit.m[x.n as usize];
            let s = if negative { BigInt::from(0) } else { base.pow(e) };
            prop_assert!(faithful(o.intensity, &(&s << cfg.fi()), den * e), "{:?} {:?} {:?}", cfg.params, x, o);
            for ch in 0..3 {
                prop_assert!(faithful(o.spec[ch], &(&s * BigInt::from(x.ks[ch])), den * e), "{:?} {:?} {:?}", cfg.params, x, o);
            }
            prop_assert!(m.check(x, o).is_ok(), "{:?}", m.check(x, o));
        }
    }

    /// fitted and blinn: for fixed n and colours, every output is non-decreasing in cos_g.
    #[test]
    fn new_models_are_monotone_in_cos(blinn in blinn_config(), fitted in fitted_config(), seed in any::<u64>(), steps in proptest::collection::vec(1u32..200, 64)) {
        for cfg in [blinn, fitted] {
            let m = Model::new(&cfg);
            let x0 = input(&cfg, &m, seed);
            let mut prev = m.eval(Inputs { cos_g: 0, ..x0 });
            let mut cos_g = 0u32;
            for &s in &steps {
                cos_g = (cos_g + s).min((2 << cfg.f()) - 1);
                let o = m.eval(Inputs { cos_g, ..x0 });
                prop_assert!(o.intensity >= prev.intensity && (0..3).all(|c| o.spec[c] >= prev.spec[c]), "{:?} cos_g {}: {:?} after {:?}", cfg.params, cos_g, o, prev);
                prev = o;
            }
        }
    }
}

/// The fit stores n = 0 as S = 1, is exact where cos^n is its own form (n = 1, 2, 4, 8),
/// and each a_n is the minimax choice: a 0.1 % change either way is no better.
#[test]
fn fit_is_exact_where_it_can_be_and_locally_minimax() {
    let cfg = Config::new(Params {
        model: SpecularModel::Fitted,
        n_bits: 6,
        ..Params::default()
    })
    .unwrap();
    let fit = specgen::models::fitted::cached_fit(&cfg);
    assert_eq!((fit.a_code[0], fit.m[0]), (0, 0));
    for (n, m) in [(1usize, 0u32), (2, 1), (4, 2), (8, 3)] {
        assert_eq!(fit.m[n], m, "n = {n}");
        assert_eq!(fit.a_code[n], 1 << cfg.kf(), "n = {n}");
        assert!(fit.fit_error[n] < 1e-9, "n = {n}: {}", fit.fit_error[n]);
    }
    // the error of (a, m) against cos^n on a dense grid of c
    let err = |n: u32, m: u32, a: f64| {
        (0..=20000)
            .map(|i| i as f64 / 20000.0)
            .map(|c: f64| ((1.0 - a * (1.0 - c)).max(0.0).powi(1 << m) - c.powi(n as i32)).abs())
            .fold(0.0, f64::max)
    };
    for n in [3u32, 5, 17, 40, 63] {
        let (a, m) = (fit.a[n as usize], fit.m[n as usize]);
        let e = err(n, m, a);
        assert!(
            err(n, m, a * 1.001) >= e * 0.999 && err(n, m, a * 0.999) >= e * 0.999,
            "n = {n}: a = {a} is not a local minimum"
        );
        assert!(
            (e - fit.fit_error[n as usize]).abs() < 2e-4,
            "n = {n}: fit says {}, grid {e}",
            fit.fit_error[n as usize]
        );
    }
}

/// SPEC §6 fidelity at defaults: fitted within 0.0165 of cos^n over every input, blinn within
/// one unit (2^-15), the quadratic unit about 0.40 off; every manifest states it and its method.
#[test]
fn fidelity_figures_at_defaults() {
    let fid = |model| {
        specgen::models::blinn_fidelity(&Model::new(
            &Config::new(Params {
                model,
                ..Params::default()
            })
            .unwrap(),
        ))
    };
    let (q, f, b) = (
        fid(SpecularModel::Quadratic),
        fid(SpecularModel::Fitted),
        fid(SpecularModel::Blinn),
    );
    for x in [&q, &f, &b] {
        assert_eq!((x.points, x.stride), (32769 * 1024, 1));
        assert!(x.mean > 0.0 && x.mean <= x.max);
    }
    assert!((0.39..0.41).contains(&q.max), "quadratic {q:?}");
    assert!(f.max <= 0.0165, "fitted {f:?}");
    assert!(b.max < 1.0 / 32768.0, "blinn {b:?}");
    assert!(f.max < q.max / 20.0 && b.max < f.max / 100.0);
}
