//! The error a viewer sees: the unit's intensity and Blinn's `c^n` each through a display's
//! transfer function (sRGB, or a power law), in codes of that display.
//!
//! **What is measured.** For a display of `bits` bits and encoding `enc` (linear light to
//! signal in `[0, 1]`), a value `x` shows at `D(x) = enc(x)·(2^bits − 1)` codes (before the
//! display rounds it). The shader's real cosine `c` is rounded to the nearest F-bit code `q`
//! (SPEC §6, the error at the pixel), so `I(q)` is shown for every `c` of `q`'s interval
//! `[lo, hi]`:
//!
//! - `max_codes`: the worst `|D(I(q)) − D(c^n)|` over those `c` and every `n`: `D` and `c^n`
//!   are monotone, so an end of the interval is the worst.
//! - `banding_codes`: the largest jump between what neighbouring cosine codes show,
//!   `round(D(I(q+1))) − round(D(I(q)))`. Blinn's `c^n` shown on the display moves by one code
//!   at a time as `c` moves; a jump of more is a band the display would not have drawn. "No
//!   banding on an 8-bit display" is `banding_codes ≤ 1` with `--display srgb8`.
//!
//! Where the space exceeds the fidelity's 2^26 points only every `stride`-th code is visited:
//! then `max_codes` takes, for the codes between two visited ones `a < b`, the intensities
//! `[I(a), I(b)]` against the cosines `[lo(a), lo(b)]` (every model is monotone in `cos_g`),
//! and `banding_codes` the jump from `a` to `b` (at least any jump between): both bounds,
//! never below the true figures.

use super::Model;
use crate::error::Error;

/// A display: its bits and its transfer function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Display {
    pub bits: u32,
    /// None: sRGB's piecewise curve (IEC 61966-2-1); Some(g): `x^(1/g)`
    pub gamma: Option<f64>,
}

impl Display {
    /// An 8-bit sRGB display: what "no banding" means to most users.
    pub const SRGB8: Display = Display {
        bits: 8,
        gamma: None,
    };

    /// `srgbB` (B in 1..=16) or `gammaG:B` (G in [1, 4]), e.g. `srgb8`, `gamma2.2:10`.
    pub fn parse(s: &str) -> Result<Display, Error> {
        let bad = || {
            Error::Config {
            parameter: "display",
            message: format!("invalid --display: {s:?}; allowed srgbB (B bits, 1..=16, e.g. srgb8) or gammaG:B (G in [1, 4], e.g. gamma2.2:8)"),
        }
        };
        let bits = |b: &str| {
            b.parse::<u32>()
                .ok()
                .filter(|b| (1..=16).contains(b))
                .ok_or_else(bad)
        };
        if let Some(b) = s.strip_prefix("srgb") {
            return Ok(Display {
                bits: bits(b)?,
                gamma: None,
            });
        }
        let (g, b) = s
            .strip_prefix("gamma")
            .and_then(|r| r.split_once(':'))
            .ok_or_else(bad)?;
        let g: f64 = g
            .parse()
            .ok()
            .filter(|g: &f64| (1.0..=4.0).contains(g))
            .ok_or_else(bad)?;
        Ok(Display {
            bits: bits(b)?,
            gamma: Some(g),
        })
    }

    pub fn name(&self) -> String {
        match self.gamma {
            None => format!("srgb{}", self.bits),
            Some(g) => format!("gamma{g}:{}", self.bits),
        }
    }

    /// `D(x)`: linear light `x ∈ [0, 1]` in codes of this display, unrounded.
    pub fn codes(&self, x: f64) -> f64 {
        let x = x.clamp(0.0, 1.0);
        let e = match self.gamma {
            None if x <= 0.003_130_8 => 12.92 * x,
            None => 1.055 * x.powf(1.0 / 2.4) - 0.055,
            Some(g) => x.powf(1.0 / g),
        };
        e * ((1u64 << self.bits) - 1) as f64
    }
}

/// [`display_error`]'s figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DisplayError {
    pub max_codes: f64,
    pub banding_codes: f64,
    /// true: over a stride of codes, bounds (never below the exact figures)
    pub bound: bool,
}

/// The error and the banding of `m` on `display`, at the pixel, over every n (module doc).
pub fn display_error(m: &Model, display: Display) -> DisplayError {
    let cfg = &m.cfg;
    let one = 1u32 << cfg.f();
    let n_count = 1u32 << cfg.n_bits();
    let full = (one as u64 + 1) * n_count as u64;
    let stride = full.div_ceil(super::FIDELITY_POINTS).max(1) as u32;
    let scale = (cfg.fi() as f64).exp2();
    let mut codes: Vec<u32> = (0..one).step_by(stride as usize).collect();
    codes.push(one);
    let end = |x: f64| (x / one as f64).clamp(0.0, 1.0);
    let los: Vec<f64> = codes.iter().map(|&q| end(q as f64 - 0.5)).collect();
    let his: Vec<f64> = codes.iter().map(|&q| end(q as f64 + 0.5)).collect();
    let threads = 8u32;
    let (codes, los, his) = (&codes, &los, &his);
    let parts: Vec<(f64, f64)> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    let (mut max, mut band) = (0.0f64, 0.0f64);
                    let mut got = Vec::with_capacity(codes.len());
                    for n in (t..n_count).step_by(threads as usize) {
                        got.clear();
                        m.unit().intensity_row(n, codes, &mut got);
                        let shown: Vec<f64> = got
                            .iter()
                            .map(|&g| display.codes(g as f64 / scale))
                            .collect();
                        let last = codes.len() - 1;
                        for j in 0..codes.len() {
                            let (lo, hi) = (
                                display.codes(los[j].powi(n as i32)),
                                display.codes(his[j].powi(n as i32)),
                            );
                            let worst = if stride == 1 {
                                (shown[j] - lo).abs().max((shown[j] - hi).abs())
                            } else {
                                let (top, top_c) = if j < last {
                                    (shown[j + 1], display.codes(los[j + 1].powi(n as i32)))
                                } else {
                                    (shown[j], hi)
                                };
                                (top - lo).max(top_c - shown[j])
                            };
                            max = max.max(worst);
                            if j < last {
                                band = band.max(shown[j + 1].round() - shown[j].round());
                            }
                        }
                    }
                    (max, band)
                })
            })
            .collect();
        hs.into_iter()
            .map(|h| h.join().expect("display thread"))
            .collect()
    });
    let (max_codes, banding_codes) = parts
        .into_iter()
        .fold((0.0f64, 0.0f64), |(a, b), (x, y)| (a.max(x), b.max(y)));
    DisplayError {
        max_codes,
        banding_codes,
        bound: stride > 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Config, Params, SpecularModel};
    use crate::models::Inputs;

    #[test]
    fn a_display_is_parsed_and_refused_by_name() {
        assert_eq!(Display::parse("srgb8").unwrap(), Display::SRGB8);
        assert_eq!(
            Display::parse("gamma2.2:10").unwrap(),
            Display {
                bits: 10,
                gamma: Some(2.2)
            }
        );
        for bad in [
            "srgb0",
            "srgb17",
            "gamma0.5:8",
            "gamma2.2",
            "rgb8",
            "gamma2.2:x",
        ] {
            let e = Display::parse(bad).unwrap_err();
            assert_eq!(e.parameter(), Some("display"), "{bad}");
        }
        assert!((Display::SRGB8.codes(1.0) - 255.0).abs() < 1e-9);
        assert_eq!(Display::SRGB8.codes(0.0), 0.0);
        assert!((Display::SRGB8.codes(0.5) - 187.5).abs() < 0.5);
    }

    /// Against a dense sampling of the real cosine: the max is never below a sample's and
    /// within the sampling's reach of it; banding is at least one code wherever the intensity
    /// moves, and a coarse input width bands where a fine one does not.
    #[test]
    fn the_display_error_is_the_real_cosines_in_display_codes() {
        let cfg = Config::new(Params {
            model: SpecularModel::Blinn,
            n_bits: 4,
            cos_frac_bits: 6,
            intensity_frac_bits: 10,
            ..Default::default()
        })
        .unwrap();
        let m = Model::new(&cfg);
        let d = display_error(&m, Display::SRGB8);
        assert!(!d.bound);
        let (samples, mut max) = (100_000u32, 0.0f64);
        for n in 0..16u32 {
            for s in 0..=samples {
                let c = s as f64 / samples as f64;
                let q = (c * 64.0).round() as u32;
                let i = m
                    .eval(Inputs {
                        cos_g: q,
                        n,
                        ks: [0; 3],
                    })
                    .intensity as f64
                    / 1024.0;
                max = max
                    .max((Display::SRGB8.codes(i) - Display::SRGB8.codes(c.powi(n as i32))).abs());
            }
        }
        assert!(
            d.max_codes >= max && d.max_codes <= max + 1.0,
            "{} vs sampled {max}",
            d.max_codes
        );
        // 64 cosine codes cannot draw 256 display codes smoothly: bands
        assert!(d.banding_codes > 1.0, "{d:?}");
        let fine = Config::new(Params {
            model: SpecularModel::Blinn,
            n_bits: 2,
            cos_frac_bits: 14,
            intensity_frac_bits: 12,
            ..Default::default()
        })
        .unwrap();
        let f = display_error(&Model::new(&fine), Display::SRGB8);
        assert!(f.banding_codes <= 1.0, "{f:?}");
        assert!(f.max_codes < d.max_codes);
    }
}
