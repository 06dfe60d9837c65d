use super::*;

#[test]
fn a_row_of_powers_is_powi_bit_for_bit() {
    let cs: Vec<f64> = (0..=4096u32)
        .map(|c| c as f64 / 4096.0)
        .chain([0.3, 0.7, 1e-3, 0.999_999])
        .collect();
    let (mut out, mut sq) = (Vec::new(), Vec::new());
    for n in (0..=1100).chain([4095, 65535]) {
        powi_row(&cs, n, &mut out, &mut sq);
        for (c, p) in cs.iter().zip(&out) {
            assert_eq!(p.to_bits(), c.powi(n as i32).to_bits(), "{c}^{n}");
        }
    }
}

/// The pixel's figures against a dense sampling of the real cosine: the max is never
/// below any sample's error and within a sample's spacing of the densest; mean and RMS
/// agree with the sampled integrals; with a stride the max is a bound above the exact one.
#[test]
fn the_error_at_the_pixel_is_the_real_cosines() {
    for model in [SpecularModel::Quadratic, SpecularModel::Blinn] {
        let cfg = Config::new(crate::config::Params {
            model,
            n_bits: 4,
            cos_frac_bits: 6,
            intensity_frac_bits: 8,
            ..Default::default()
        })
        .unwrap();
        let m = Model::new(&cfg);
        let f = blinn_fidelity(&m);
        assert_eq!(f.stride, 1);
        assert!(!f.pixel.bound);
        let (samples, one) = (200_000u32, 64.0);
        let (mut max, mut sum, mut squares) = (0.0f64, 0.0f64, 0.0f64);
        for n in 0..16u32 {
            for s in 0..=samples {
                let c = s as f64 / samples as f64;
                let q = (c * one).round() as u32;
                let i = m
                    .eval(Inputs {
                        cos_g: q,
                        n,
                        ks: [0; 3],
                    })
                    .intensity as f64
                    / 256.0;
                let e = (i - c.powi(n as i32)).abs();
                max = max.max(e);
                sum += e;
                squares += e * e;
            }
        }
        let count = 16.0 * (samples + 1) as f64;
        assert!(
            f.pixel.max >= max && f.pixel.max <= max + 16.0 / samples as f64,
            "{model:?}: {} vs sampled {max}",
            f.pixel.max
        );
        assert!(
            (f.pixel.mean - sum / count).abs() < 1e-4,
            "{model:?}: mean {} vs {}",
            f.pixel.mean,
            sum / count
        );
        assert!(
            (f.pixel.rms - (squares / count).sqrt()).abs() < 1e-4,
            "{model:?}: rms {} vs {}",
            f.pixel.rms,
            (squares / count).sqrt()
        );
        // the rounding's own cost is in it: never below the error at the codes
        assert!(f.pixel.max >= f.max);
        let strided = fidelity_within(&m, 200);
        assert!(strided.stride > 1 && strided.pixel.bound);
        assert!(
            strided.pixel.max >= f.pixel.max,
            "a stride's bound {} below the exact {}",
            strided.pixel.max,
            f.pixel.max
        );
        if let Some(b) = faithful_pixel_bound(&cfg) {
            assert!(
                b >= f.pixel.max && b <= f.pixel.max + 2.0 / 256.0,
                "{model:?}: the faithful bound {b} against the exact {}",
                f.pixel.max
            );
        }
    }
}

#[test]
fn every_model_is_in_the_registry() {
    for model in SpecularModel::ALL {
        let cfg = Config::new(crate::config::Params {
            model,
            n_bits: 4,
            ..Default::default()
        })
        .unwrap();
        let m = Model::new(&cfg);
        // n = 0 gives 1 in every model; c = 1.0 gives full scale
        let o = m.eval(Inputs {
            cos_g: 3,
            n: 0,
            ks: [255, 1, 0],
        });
        assert_eq!(
            o,
            Outputs {
                spec: [255, 1, 0],
                intensity: 1 << 15,
                done: false
            },
            "{model:?}"
        );
        assert!(m
            .check(
                Inputs {
                    cos_g: 3,
                    n: 0,
                    ks: [255, 1, 0]
                },
                o
            )
            .is_ok());
        assert!(!m.unit().describe().formula.is_empty());
    }
}
