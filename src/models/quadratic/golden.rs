//! The quadratic unit's golden model ([`Quadratic::trace`]: the RTL's arithmetic step for step,
//! the same widths and truncations in the same order) and its exact reference ([`reference`]:
//! SPEC §3 as exact dyadic rationals, with no knowledge of the internal widths), tied by
//! [`check`], the rounding contract.

use super::Quadratic;
use crate::bits::{mask, Word};
use crate::config::Config;
use crate::error::Error;
use crate::models::{check_value, Ideal, Inputs, Outputs, SPEC_PORTS};

/// Every intermediate value of the datapath, named as in the RTL.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Trace {
    pub(crate) cos_clamped: u64,
    pub(crate) one_minus_cos: u64,
    pub(crate) cos_sp: u64,
    pub(crate) done: bool,
    pub(crate) kn: u64,
    pub(crate) deviation_full: u128,
    pub(crate) deviation: u64,
    pub(crate) bracket: u64,
    pub(crate) square_full: u128,
    pub(crate) square: u128,
    pub(crate) color_prod: [u128; 3],
    pub(crate) intensity_sum: u128,
    pub(crate) outputs: Outputs,
}

impl Quadratic {
    /// Runs the quadratic datapath and returns every intermediate value.
    #[inline]
    pub fn trace(&self, x: Inputs) -> Trace {
        if self.widths.fits_u64(self.cfg.fi()) {
            self.trace_in::<u64>(x)
        } else {
            self.trace_in::<u128>(x)
        }
    }

    /// [`Quadratic::trace`] in the word `W`, which holds every value of the datapath.
    #[inline(always)]
    fn trace_in<W: Word>(&self, x: Inputs) -> Trace {
        let w = &self.widths;
        let f = self.cfg.f();
        let wb = w.bracket_frac_bits;
        let ws = w.square_frac_bits;
        let fi = self.cfg.fi();
        let b = self.cfg.b();
        let m = W::mask;
        let bit = |k: u32| W::from(1u32) << k;
        let wide = |v: W| -> u128 { v.into() };
        let one = bit(f);
        let cos_g = W::from(x.cos_g) & m(f + 1);
        let n = x.n & mask(self.cfg.n_bits()) as u32;
        let ks = x.ks.map(|k| W::from(k) & m(b));

        // step 1: clamp, 1 − cos (adder 6), ROM, comparator, k_code·n
        let cos_clamped = cos_g.min(one);
        let one_minus_cos = one - cos_clamped;
        let cos_sp = W::from(self.rom[n as usize]);
        let done = cos_clamped < cos_sp;
        let kn = W::low(self.cfg.k_code as u128) * W::from(n);
        // step 2: P = kn·d, truncation #1 to WB fractional bits (keep WB+1 bits)
        let deviation_full = kn * one_minus_cos;
        let deviation = (deviation_full >> w.deviation_shift) & m(wb + 1);
        // step 3: bracket = 1 − dev, zeroed by the key block beyond the cut-off (mod 2^(WB+1))
        let bracket = if done {
            W::from(0u32)
        } else {
            bit(wb).wrapping_sub(deviation) & m(wb + 1)
        };
        // step 4: square, truncation #2 to WS fractional bits
        let square_full = bracket * bracket;
        let square = (square_full >> w.square_shift) & m(ws + 1);
        // step 5: colour products (of the square cut to WS_C bits); intensity rounding add
        let wsc = w.color_square_frac_bits;
        let color_square = square >> (ws - wsc);
        let color_prod = ks.map(|k| color_square * k);
        let intensity_sum = if ws > fi {
            square + bit(ws - fi - 1)
        } else {
            square << (fi - ws)
        };
        // step 6: colour rounding add and the final slices
        let spec = color_prod.map(|p| wide((p + bit(wsc - 1)) >> wsc) as u32);
        let intensity = if ws > fi {
            wide(intensity_sum >> (ws - fi)) as u32
        } else {
            wide(intensity_sum) as u32
        };
        Trace {
            cos_clamped: wide(cos_clamped) as u64,
            one_minus_cos: wide(one_minus_cos) as u64,
            cos_sp: wide(cos_sp) as u64,
            done,
            kn: wide(kn) as u64,
            deviation_full: wide(deviation_full),
            deviation: wide(deviation) as u64,
            bracket: wide(bracket) as u64,
            square_full: wide(square_full),
            square: wide(square),
            color_prod: color_prod.map(wide),
            intensity_sum: wide(intensity_sum),
            outputs: Outputs {
                spec,
                intensity,
                done,
            },
        }
    }
}

/// SPEC §3's ideal outputs for one input, as exact rationals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reference {
    /// `base · 2^(KF+F)` (may be negative).
    pub base_num: i128,
    pub(crate) base_den_log2: u32,
    pub done: bool,
    pub intensity: Ideal,
    pub spec: [Ideal; 3],
}

/// The exact reference: `c = min(cos_g, 2^F)/2^F`, `base = 1 − k_q·n·(1 − c)`,
/// `S = base²` (0 when `base < 0`), `intensity* = S·2^FI`, `spec_X* = S·ks_X`.
pub fn reference(cfg: &Config, x: Inputs) -> Reference {
    let (f, kf, fi) = (cfg.f(), cfg.kf(), cfg.fi());
    let c = (x.cos_g as i128).min(1i128 << f);
    let base_den_log2 = kf + f;
    let base_num = (1i128 << base_den_log2) - cfg.k_code as i128 * x.n as i128 * ((1i128 << f) - c);
    let done = base_num < 0;
    let s_num: u128 = if done {
        0
    } else {
        (base_num * base_num) as u128
    };
    let den_log2 = 2 * base_den_log2;
    Reference {
        base_num,
        base_den_log2,
        done,
        intensity: Ideal {
            num: s_num << fi,
            den_log2,
        },
        spec: x.ks.map(|k| Ideal {
            num: s_num * k as u128,
            den_log2,
        }),
    }
}

/// Checks a full output vector against SPEC §3 for one input.
pub fn check(cfg: &Config, x: Inputs, got: Outputs) -> Result<(), Error> {
    let r = reference(cfg, x);
    if got.done != r.done {
        return Err(Error::breach(
            "done",
            format!("got {}, reference {}", got.done, r.done),
        ));
    }
    check_value("intensity", cfg.rounding(), got.intensity, r.intensity)?;
    for (i, name) in SPEC_PORTS.iter().enumerate() {
        check_value(name, cfg.rounding(), got.spec[i], r.spec[i])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::Model;

    #[test]
    fn full_cosine_gives_full_colour() {
        let m = Model::new(&Config::defaults());
        let o = m.eval(Inputs {
            cos_g: 1 << 15,
            n: 500,
            ks: [255, 7, 0],
        });
        assert_eq!(
            o,
            Outputs {
                spec: [255, 7, 0],
                intensity: 1 << 15,
                done: false
            }
        );
    }

    #[test]
    fn the_u64_and_u128_datapaths_agree() {
        // the default unit computes in u64; the same steps in u128 must give every value
        let m = super::super::Quadratic::new(&Config::defaults());
        assert!(m.widths.fits_u64(15));
        for n in [0, 1, 2, 40, 500, 1023] {
            for cos_g in (0..=(1u32 << 16) - 1)
                .step_by(97)
                .chain([1 << 15, (1 << 15) + 1])
            {
                let x = Inputs {
                    cos_g,
                    n,
                    ks: [cos_g & 255, (n * 7) & 255, 255],
                };
                assert_eq!(m.trace_in::<u64>(x), m.trace_in::<u128>(x), "{x:?}");
            }
        }
    }

    #[test]
    fn check_rejects_off_by_one() {
        let cfg = Config::defaults();
        let x = Inputs {
            cos_g: 32000,
            n: 40,
            ks: [200, 100, 50],
        };
        let mut o = Model::new(&cfg).eval(x);
        assert!(check(&cfg, x, o).is_ok());
        o.spec[1] += 1;
        assert!(check(&cfg, x, o).is_err());
    }

    #[test]
    fn default_faithful_widths_follow_the_budget() {
        let w = super::super::Widths::derive(&Config::defaults());
        assert_eq!(w.bracket_frac_bits, 15 + 2);
        assert_eq!(w.square_frac_bits, 15 + 1);
        assert_eq!(w.deviation_shift, 16 + 15 - 17);
    }
}
