//! `--model schlick`: the paper's modified Schlick approximation, formula (11),
//! `S = c / (2n − 2n·c + c)` (Schlick's (7) with a = b = 2) — a rational function, no cut-off
//! table, no power — by a reciprocal from an interpolated table and one product. Its home: the
//! error budget below and the widths it gives ([`SchlickWidths`]), the table
//! (`reciprocal.rs`, [`ReciprocalTable`]), the golden model ([`Schlick::steps`]), the exact
//! reference and contract ([`check`]: big integers, no float), and the datapath
//! (`datapath.rs`) on the same builder as every model.
//!
//! # Datapath (all unsigned; M = max(FI, B), Z = M + 1, W = M + 3)
//!
//! ```text
//! c    = min(cos_g, 2^F)                       UQ1.F
//! den  = 2n·(2^F − c) + c                      N+F+2 bits, exact (one multiply-add: n·(2^F − c) + ⌊c/2⌋, doubled, c's low bit)
//! L    = leading zeros of den above 2^F        0..N+1     den = u·2^e, e = N+F+1 − L, u ∈ [1, 2)
//! u    = den << L                              UQ1.(N+F+1) exact
//! i, t = the next K, then J bits of u          the table's interval, the fraction in it (truncated)
//! z    = ⌊(B_i·2^J + D_i·(2^J − 1 − t)) / 2^(U+J−Z)⌋         r̂ = 1 + z/2^Z ≈ r = 2/u, r̂ ∈ [1, 2)
//! P    = c·(2^Z + z)                           UQ2.(F+Z): c·r̂, exact (one multiply-add)
//! q    = ⌊P·2^L / 2^(N+F)⌋ = ⌊⌊P/2^(F−1)⌋ / 2^(N+1−L)⌋        UQ1.W: S·(r̂/r) floored; 2^W at n = 0
//! out  = ⌊(q + 2^(W−FI−1)) / 2^(W−FI)⌋; spec = ⌊(⌊q/2^(W−Wc)⌋·ks + 2^(Wc−1)) / 2^Wc⌋, Wc = B + 3; done = (intensity == 0)
//! ```
//!
//! Why it is `S`: `den ≥ 2^F` for `n ≥ 1` (`2n·2^F − (2n − 1)·c ≥ 2^F` as `c ≤ 2^F`), so its
//! leading one is at `e ∈ [F, N+F+1]` and `den = u·2^e` exactly. Then `S = c/den = c·r/2^(e+1)`
//! with `r = 2/u ∈ (1, 2]`, and the unit computes `T = c·r̂/2^(e+1) = S·(r̂/r)`, floored to W
//! bits: `q = ⌊T·2^W⌋` is the formula above (`Z + e + 1 − W = N + F − L`). `T < 1` always
//! (`c ≤ 2^F`, `r̂ < 2`, `e ≥ F`), so q needs no saturation. `n = 0` is 1.0 by a select (its
//! `den = c` may be 0).
//!
//! # Error budget
//!
//! Write `δ = r̂/r − 1`. Then `q·2^−W − S ∈ (−S·|δ| − 2^−W, S·|δ|]`: the floor loses less
//! than `2^−W`. An output `o = round_half_up(x)` of `x = q·M·2^−W` (`M = 2^FI` for the
//! intensity) is within `(S·M − 1/2 − M·(|δ| + 2^−W), S·M + 1/2 + M·|δ|]`; the colours take
//! `⌊q/2^(W−Wc)⌋`, `Wc` fractional bits, and `M = ks ≤ 2^B − 1` with `2^−Wc` for `2^−W`.
//! With `|δ| ≤ 3·2^−(M+3)`:
//! - intensity: `2^FI·(3·2^−(M+3) + 2^−(M+3)) ≤ 1/2`, and `2^FI·|δ| ≤ 3/8`, so `|o − S·2^FI| < 1`;
//! - colours: `ks·(3·2^−(M+3) + 2^−(B+3)) < 2^B·4·2^−(B+3) = 1/2`, and `ks·|δ| < 3/8`.
//!
//! So the unit is faithful when `|r̂/r − 1| ≤ 3·2^−(M+3)` on every `u`. The reciprocal's part:
//! - **rounding to Z bits**: the table's words carry `2^−(Z+1)`, so the floor rounds the
//!   interpolation to nearest: `≤ 2^−(Z+1) = 2·2^−(M+3)`;
//! - **the interpolation**, `ε ≤ 3·2^−(Z+4)` before that rounding. `2^K` intervals of
//!   `h = 2^−K` (`K = ⌈(Z+2)/2⌉`); the points `V_i = round(2/u_i·2^U)` (`U = Z + 4`, each
//!   within `2^−(U+1)`), the line between two of them above the convex `r` by at most
//!   `h²/8·max r'' = 2^−(2K+1) ≤ 2^−(Z+3)`, so lowered by half of that (`≤ 2^−(Z+4)` either way);
//!   `t` truncated to J = U − K bits reads the line up to `D_max·2^−J` early, centred by half
//!   of it (`D_max < 2^(1−K)`: `≤ 2^−U`); the offsets summed into one constant κ rounded to
//!   a unit (`≤ 2^−(U+1)`). Together `2^−(Z+4)·(1 + 1/2 + 1 + 1/2) = 3·2^−(Z+4)`;
//! - **the top**: `V_0 = 2^(U+1)` is lowered until `r̂ < 2` on interval 0 (by at most
//!   κ + 1 units, fading over the interval); there `r ≈ 2`, so the relative error halves.
//!
//! `2^−(Z+1) + 3·2^−(Z+4) = 11·2^−(Z+4) < 12·2^−(Z+4) = 3·2^−(M+3)`, and `r ≥ 1` makes the
//! absolute bound a relative one. `reciprocal.rs`'s test checks the bound on every cell of
//! the table (every interval and fraction, both ends) at five configurations, and that it is
//! within a factor 2 of tight.
//!
//! # Monotone in `cos_g`
//!
//! For `n ≥ 1`, `den` falls as `c` rises. Within one exponent `u` falls, `t` and `i` with it,
//! and `r̂` never falls: each line is `B_i + D_i·(1 − t/2^J)` with `D_i ≥ 0`, and adjacent
//! lines meet (`B_i` is the next point `V_(i+1)` plus the same κ for every i; the start of
//! interval `i + 1` is `D·2^−J` below the end of interval i). So `c·r̂` rises. Where `e` drops,
//! `T` goes from `c·r̂/2^(e+1) < c/2^e` (`r̂ < 2`) to at least `(c + 1)/2^(e'+1) ≥ (c + 1)/2^e`
//! (`r̂ ≥ 1`, `e' < e`). Floors keep order. The cell test checks `r̂` never rises with `u`.
//!
//! # The divider this replaced
//!
//! The unit used to divide by a restoring divider, one quotient bit a step, each a
//! compare-subtract of N+F+3 bits on one carry chain: exact (`q = ⌊S·2^W⌋`), but its
//! deepest pipeline ran at 49 MHz on the UP5K, a chain in every step. A radix-2 SRT
//! divider (carry-save remainders) reached 85 MHz at three times the area. Here every step
//! is a mux level, a LUT level, a short carry-select chunk, a table read or a DSP block.

mod datapath;
mod reciprocal;
pub use reciprocal::{ReciprocalTable, SchlickWidths};

use super::{explain_ideal, Description, Inputs, Outputs, SpecularUnit, SPEC_PORTS};
use crate::bits::{bit_length, mask};
use crate::config::Config;
use crate::datapath::Builder;
use crate::error::Error;

/// The schlick unit of one configuration.
#[derive(Debug, Clone)]
pub struct Schlick {
    pub(crate) cfg: Config,
    pub(crate) w: SchlickWidths,
    pub(crate) t: ReciprocalTable,
}

/// Every intermediate value of the datapath, named as in the RTL.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Trace {
    /// `c`, UQ1.F
    pub(crate) cos_clamped: u128,
    /// `den = 2n·(2^F − c) + c`, in units of 2^−F
    pub(crate) den: u128,
    /// L: den's leading zeros above 2^F (N + 2 when den < 2^F, at n = 0)
    pub(crate) lead_zeros: u32,
    /// the table's interval i and the fraction t
    pub(crate) index: usize,
    pub(crate) fraction: u128,
    /// `z`: r̂ = 1 + z/2^Z
    pub(crate) recip: u128,
    /// `P = c·(2^Z + z)`
    pub(crate) product: u128,
    /// `q`, UQ1.W (1.0 at n = 0)
    pub(crate) quotient: u128,
    pub(crate) outputs: Outputs,
}

impl Schlick {
    pub fn new(cfg: &Config) -> Schlick {
        let w = SchlickWidths::derive(cfg);
        let t = ReciprocalTable::new(&w);
        Schlick {
            cfg: cfg.clone(),
            w,
            t,
        }
    }

    /// The datapath step for step, as the RTL computes it.
    pub fn steps(&self, x: Inputs) -> Trace {
        let (f, nb, w) = (self.cfg.f(), self.cfg.n_bits(), &self.w);
        let (dw, k, j) = (w.den_bits, w.index_bits, w.fraction_bits);
        // clamp; the denominator, exact
        let c = (x.cos_g as u128 & mask(f + 1)).min(1 << f);
        let n = x.n as u128 & mask(nb);
        let den = 2 * n * ((1u128 << f) - c) + c;
        // normalise: L, u = den·2^L with its top bit set (for n ≥ 1)
        let bl = bit_length(den);
        let lead_zeros = if bl > f { dw - bl } else { nb + 2 };
        let u = (den << lead_zeros) & mask(dw);
        // the table's interval and fraction: u's next K + J bits (zeros below u's last)
        let frac = u & mask(dw - 1);
        let it = if dw > k + j {
            frac >> (dw - 1 - k - j)
        } else {
            frac << (k + j - (dw - 1))
        };
        let (index, fraction) = ((it >> j) as usize, it & mask(j));
        let recip = self.t.recip(w, index, fraction);
        // c·r̂, exact; shifted by L and floored to W bits
        let product = c * ((1u128 << w.recip_frac_bits) + recip);
        let wq = w.quotient_frac_bits;
        let xw = wq + nb + 1;
        let shifted = ((product >> (f - 1)) << lead_zeros) & mask(xw);
        let quotient = if n == 0 { 1 << wq } else { shifted >> (nb + 1) };
        Trace {
            cos_clamped: c,
            den,
            lead_zeros,
            index,
            fraction,
            recip,
            product,
            quotient,
            outputs: self.outputs(x, quotient),
        }
    }

    /// The last step: the outputs of the quotient `q` (UQ1.W), rounded half up.
    fn outputs(&self, x: Inputs, quotient: u128) -> Outputs {
        let (w, fi, b) = (self.w.quotient_frac_bits, self.cfg.fi(), self.cfg.b());
        let intensity = ((quotient + (1 << (w - fi - 1))) >> (w - fi)) as u32;
        let wc = self.w.colour_frac_bits;
        let qc = quotient >> (w - wc);
        let spec =
            x.ks.map(|k| ((qc * (k as u128 & mask(b)) + (1 << (wc - 1))) >> wc) as u32);
        Outputs {
            spec,
            intensity,
            done: intensity == 0,
        }
    }
}

/// `S = c/den` as an exact fraction `(num, den)` of codes: `(1, 1)` where `den = 0`.
fn ratio(cfg: &Config, x: Inputs) -> (u128, u128) {
    let c = (x.cos_g as u128).min(1 << cfg.f());
    let n = x.n as u128;
    match 2 * n * ((1u128 << cfg.f()) - c) + c {
        0 => (1, 1),
        den => (c, den),
    }
}

/// The contract: every output within 1 of its ideal `S·M` (`|o·den − c·M| < den`, in integers),
/// `done` ⇔ the intensity is 0.
pub fn check(cfg: &Config, x: Inputs, got: Outputs) -> Result<(), Error> {
    let (num, den) = ratio(cfg, x);
    let within = |o: u32, m: u128| (o as u128 * den).abs_diff(num * m) < den;
    let one = 1u128 << cfg.fi();
    if !within(got.intensity, one) {
        return Err(Error::breach(
            "intensity",
            format!(
                "got {}, S·2^FI = {}·2^{}/{den}",
                got.intensity,
                num,
                cfg.fi()
            ),
        ));
    }
    for (i, name) in SPEC_PORTS.iter().enumerate() {
        if !within(got.spec[i], x.ks[i] as u128) {
            return Err(Error::breach(
                name,
                format!("got {}, S·ks = {}·{}/{den}", got.spec[i], num, x.ks[i]),
            ));
        }
    }
    if got.done != (got.intensity == 0) {
        return Err(Error::breach(
            "done",
            format!("got {}, intensity {}", got.done, got.intensity),
        ));
    }
    Ok(())
}

impl SpecularUnit for Schlick {
    fn eval(&self, x: Inputs) -> Outputs {
        self.steps(x).outputs
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), Error> {
        check(&self.cfg, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        let (num, den) = ratio(&self.cfg, x);
        let s = num as f64 / den as f64;
        (
            s * (self.cfg.fi() as f64).exp2(),
            x.ks.map(|k| s * k as f64),
        )
    }

    fn reference_words(&self) -> &'static str {
        "the exact quotient S = c/(2n - 2n*c + c) in integers"
    }

    fn datapath(&self, b: &mut Builder) {
        datapath::datapath(&self.cfg, &self.w, &self.t, b)
    }

    fn describe(&self) -> Description {
        let p = &self.cfg.params;
        let w = &self.w;
        Description {
            param_line: String::new(),
            formula: vec![
                "S = c / (2n - 2n*c + c), c = min(cos_g, 1.0) (the paper's modified Schlick, formula (11)); S = 1 at n = 0;".into(),
                format!("intensity = S (UQ1.{}), spec_X = S * ks_X; done = (intensity == 0).", p.intensity_frac_bits),
            ],
            rounding: "faithful: every output within 1 ulp of the exact quotient (|o - o*| < 1)".into(),
            datapath: format!(
                "den = 2n*(1 - c) + c exact, normalised to u in [1, 2); r = 2/u from a table of 2^{} intervals with linear interpolation to UQ1.{}; c*r shifted back to UQ1.{} (error budget in specgen's models/schlick)",
                w.index_bits, w.recip_frac_bits, w.quotient_frac_bits
            ),
            done_meaning: "intensity == 0: the highlight is below the output's resolution",
            summary: "Fixed-point modified-Schlick specular unit, c/(2n - 2n*c + c) by an interpolated reciprocal",
            computes: "modified Schlick (11) by a reciprocal",
        }
    }

    fn widths(&self) -> serde_json::Value {
        let w = &self.w;
        serde_json::json!({
            "quotient_frac_bits": w.quotient_frac_bits,
            "colour_frac_bits": w.colour_frac_bits,
            "denominator_bits": w.den_bits,
            "reciprocal_frac_bits": w.recip_frac_bits,
            "reciprocal_index_bits": w.index_bits,
            "reciprocal_fraction_bits": w.fraction_bits,
            "reciprocal_entry_frac_bits": w.entry_frac_bits,
        })
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        let t = self.steps(x);
        let (w, z) = (self.w.quotient_frac_bits, self.w.recip_frac_bits);
        vec![
            format!(
                "den        2n*(1 - c) + c = {} (units of 2^-{}), L = {}",
                t.den,
                self.cfg.f(),
                t.lead_zeros
            ),
            format!(
                "recip      r^ = 1 + {}/2^{z} ~ 2/u (interval {}, fraction {})",
                t.recip, t.index, t.fraction
            ),
            format!("product    c*r^ = {} (UQ2.{})", t.product, self.cfg.f() + z),
            format!(
                "quotient   q = {} (UQ1.{w}: {:.9})",
                t.quotient,
                t.quotient as f64 / (w as f64).exp2()
            ),
            explain_ideal(self.ideal(x), "(c/(2n - 2n*c + c))"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Params, SpecularModel};

    fn cfg(p: Params) -> Config {
        Config::new(Params {
            model: SpecularModel::Schlick,
            ..p
        })
        .unwrap()
    }

    #[test]
    fn the_quotient_is_within_its_budget_of_the_exact_one() {
        // q·2^−W against S = c/den in integers: within (−S·δ − 2^−W, S·δ], δ = 3·2^−(M+3)
        for p in [
            Params::default(),
            Params {
                cos_frac_bits: 20,
                n_bits: 12,
                color_bits: 16,
                intensity_frac_bits: 24,
                ..Params::default()
            },
        ] {
            let s = Schlick::new(&cfg(p.clone()));
            let (w, m) = (s.w.quotient_frac_bits, s.w.m);
            for n in [1u32, 2, 7, 100, (1 << p.n_bits) - 1] {
                for cos_g in (0..=1u32 << p.cos_frac_bits).step_by(331) {
                    let t = s.steps(Inputs {
                        cos_g,
                        n,
                        ks: [0; 3],
                    });
                    // in units of 2^−(W+M+3)/den: q·den·2^(M+3) − c·2^(W+M+3)
                    let got = (t.quotient * t.den) as i128 * (1 << (m + 3));
                    let exact = (t.cos_clamped as i128) << (w + m + 3);
                    let sd = (3 * t.cos_clamped as i128) << w; // S·δ·den·2^(W+M+3)
                    assert!(
                        got - exact <= sd && got - exact > -sd - ((t.den as i128) << (m + 3)),
                        "n={n} cos_g={cos_g}: {t:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn zero_over_zero_is_one() {
        let s = Schlick::new(&cfg(Params::default()));
        let o = s.eval(Inputs {
            cos_g: 0,
            n: 0,
            ks: [255, 3, 0],
        });
        assert_eq!(
            o,
            Outputs {
                spec: [255, 3, 0],
                intensity: 1 << 15,
                done: false
            }
        );
        assert_eq!(
            s.eval(Inputs {
                cos_g: 0,
                n: 5,
                ks: [255; 3]
            })
            .intensity,
            0
        );
        // c = 1: S = 1 for every n, r̂ one step below 2
        let t = s.steps(Inputs {
            cos_g: 1 << 15,
            n: 1000,
            ks: [255; 3],
        });
        assert_eq!(
            (t.recip, t.outputs.intensity, t.outputs.spec),
            ((1 << 16) - 1, 1 << 15, [255; 3])
        );
    }

    #[test]
    fn the_colours_floor_is_not_loose() {
        // colours wider than the intensity: with Wc = B + 1 some colour near 2^B breaks the
        // contract; the budget's B + 3 meets it on the same inputs (B + 2 happens to meet it
        // here too, but the budget cannot show it: its δ bound takes 3/8 of the unit)
        let c = cfg(Params {
            cos_frac_bits: 10,
            n_bits: 6,
            color_bits: 12,
            intensity_frac_bits: 6,
            ..Params::default()
        });
        let s = Schlick::new(&c);
        let mut narrow = s.clone();
        narrow.w.colour_frac_bits -= 2;
        let mut broken = false;
        for n in 0..64u32 {
            for cos_g in 0..=1u32 << 10 {
                let x = Inputs {
                    cos_g,
                    n,
                    ks: [4095, 4094, 1],
                };
                broken |= check(&c, x, narrow.eval(x)).is_err();
                assert!(check(&c, x, s.eval(x)).is_ok(), "{x:?}");
            }
        }
        assert!(broken, "Wc = B + 1 is enough: the colours' floor is loose");
    }
}
