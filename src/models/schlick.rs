//! `--model schlick`: the paper's modified Schlick approximation, formula (11),
//! `S = c / (2n − 2n·c + c)` (Schlick's (7) with a = b = 2), by a restoring divider — a rational function, no cut-off table,
//! no power. Its home: the error budget ([`quotient_frac_bits`]), the golden model
//! ([`Schlick::trace`], the divider step for step), the exact reference and contract
//! ([`check`]: big integers, no float), and the datapath on the same builder as every model.
//!
//! The division. With `c = min(cos_g, 2^F)` (a code, UQ1.F) the denominator in the same units
//! is `den = 2n·(2^F − c) + c`, an integer of at most `N + F + 2` bits, computed exactly as
//! `2·(n·(2^F − c) + ⌊c/2⌋) + (c mod 2)`: one multiply-add of `N`- and `(F+1)`-bit operands
//! whose sum fits `N + F + 1` bits, then the doubling and `c`'s low bit by wiring (an operand
//! `2n`, its low bit a constant 0, would have yosys take the shift, and the add and register
//! behind it, out of the SB_MAC16). `den ≥ c` (as `2n·(2^F − c) ≥ 0`), so `S = c/den ≤ 1`. A restoring divider
//! takes the quotient one bit a step, most significant first: the remainder starts at `c`, the
//! bit of weight 1 is `[r ≥ den]` (and `r −= den` when set), then each of the W fractional bits
//! doubles the remainder and compares again. The remainder stays below `den ≤ 2^(N+F+1)`, so
//! a doubled one has `N + F + 3` bits: one compare-subtract of that width a step, W + 1 steps.
//! The result is `q = floor(S·2^W)` exactly. `den = 0` only at `c = 0, n = 0`, where `S` is
//! taken as its limit 1 (cos^0 = 1): the quotient of `n = 0` is 1.0 by a select at the end
//! (for `c > 0` the divider gives 1.0 there too).
//!
//! Error budget. `q·2^−W` is within `[S − 2^−W, S]`. An output `o = round_half_up(q·M/2^W)`
//! (`M = 2^FI` for the intensity, `ks < 2^B` for a colour) is then within
//! `(S·M − 1/2 − M·2^−W, S·M + 1/2]` of the ideal `S·M`: faithful (`|o − S·M| < 1`) when
//! `M·2^−W ≤ 1/2`, that is `W ≥ max(FI, B) + 1` ([`quotient_frac_bits`]). The colours' bound
//! is tight: at `W = B` a colour near `2^B` loses up to one whole unit to the truncation and
//! half a unit more to the rounding (a test finds such an input). The intensity's alone would
//! allow `W = FI` with the quotient taken as it is (floor, within 1); one rounding step for
//! every output keeps `W > FI`. The colours take `q` floored to `Wc = min(B + 1, W)` bits,
//! `floor(q/2^(W−Wc)) = floor(S·2^Wc)` (floors compose), and the same bound with `Wc` for `W`
//! holds: `ks·2^−Wc < 2^B·2^−(B+1) = 1/2`. So a colour product's operand is `Wc + 1` bits, not
//! `W + 1`: one SB_MAC16 each while `B ≤ 14` (17 bits at the defaults took two, summed in the
//! fabric, with no register of their own). The property test `every_model` checks the contract on random
//! configurations, the exhaustive sweep at the defaults. `done = (intensity == 0)`, as for
//! the `cos^n` models.

use super::{explain_ideal, Description, Inputs, Outputs, SpecularUnit, SPEC_PORTS};
use crate::bits::{lit, mask};
use crate::config::Config;
use crate::datapath::{add_delay, ex, Builder, Kind, Sig, LUT_DELAY};
use crate::error::Error;

/// W: fractional bits of the quotient `q = floor(S·2^W)`, from the budget above.
pub(crate) fn quotient_frac_bits(cfg: &Config) -> u32 {
    cfg.fi().max(cfg.b()) + 1
}

/// Wc: the fractional bits of the quotient the colours take, from the budget above.
fn colour_frac_bits(cfg: &Config, w: u32) -> u32 {
    (cfg.b() + 1).min(w)
}

/// The schlick unit of one configuration.
#[derive(Debug, Clone)]
pub struct Schlick {
    pub(crate) cfg: Config,
    /// W: fractional bits of the quotient, UQ1.W.
    pub(crate) quotient_frac_bits: u32,
}

/// Every intermediate value of the datapath, named as in the RTL.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Trace {
    /// `c`, UQ1.F
    pub(crate) cos_clamped: u128,
    /// `den = 2n·(2^F − c) + c`, in units of 2^−F
    pub(crate) den: u128,
    /// the remainder after each quotient bit (W + 1 of them)
    pub(crate) remainders: Vec<u128>,
    /// `q = floor(S·2^W)`, UQ1.W (1.0 at n = 0)
    pub(crate) quotient: u128,
    pub(crate) outputs: Outputs,
}

impl Schlick {
    pub fn new(cfg: &Config) -> Schlick {
        Schlick { cfg: cfg.clone(), quotient_frac_bits: quotient_frac_bits(cfg) }
    }

    /// The divider step for step, as the RTL computes it.
    pub fn trace(&self, x: Inputs) -> Trace {
        let mut remainders = Vec::with_capacity(self.quotient_frac_bits as usize + 1);
        let (cos_clamped, den, quotient, outputs) = self.divide(x, |r| remainders.push(r));
        Trace { cos_clamped, den, remainders, quotient, outputs }
    }

    /// The datapath: `(c, den, quotient, outputs)`, each remainder given to `remainder` as it
    /// is made.
    fn divide(&self, x: Inputs, mut remainder: impl FnMut(u128)) -> (u128, u128, u128, Outputs) {
        let (f, w) = (self.cfg.f(), self.quotient_frac_bits);
        // step 1: clamp, 1 − c
        let c = (x.cos_g as u128 & mask(f + 1)).min(1 << f);
        let n = x.n as u128 & mask(self.cfg.n_bits());
        let d = (1u128 << f) - c;
        // step 2: the denominator, exact
        let den = 2 * n * d + c;
        // steps 3..: one quotient bit a step, the weight-1 bit first
        let mut r = c;
        let mut q = 0u128;
        for k in 0..=w {
            if k > 0 {
                r <<= 1;
            }
            let bit = r >= den;
            if bit {
                r -= den;
            }
            q = q << 1 | bit as u128;
            remainder(r);
        }
        // last step: n = 0 is 1.0 (the limit at c = 0); round half up to the outputs
        let quotient = if n == 0 { 1 << w } else { q };
        (c, den, quotient, self.outputs(x, quotient))
    }

    /// The last step: the outputs of the quotient `q` (UQ1.W), rounded half up.
    fn outputs(&self, x: Inputs, quotient: u128) -> Outputs {
        let (w, fi, b) = (self.quotient_frac_bits, self.cfg.fi(), self.cfg.b());
        let intensity = ((quotient + (1 << (w - fi - 1))) >> (w - fi)) as u32;
        let wc = colour_frac_bits(&self.cfg, w);
        let qc = quotient >> (w - wc);
        let spec = x.ks.map(|k| ((qc * (k as u128 & mask(b)) + (1 << (wc - 1))) >> wc) as u32);
        Outputs { spec, intensity, done: intensity == 0 }
    }

    /// [`Schlick::divide`]'s outputs without its steps: the restoring divider's quotient is
    /// `floor(c·2^W/den)` (the module doc; `the_divider_gives_the_floor_of_the_quotient`
    /// checks it), one division here, in 64 bits: `c·2^W ≤ 2^(20+25)` and `den < 2^(12+20+2)`
    /// at every allowed width.
    fn quick(&self, x: Inputs) -> Outputs {
        let (f, w) = (self.cfg.f(), self.quotient_frac_bits);
        let c = (x.cos_g as u64 & mask(f + 1) as u64).min(1 << f);
        let n = x.n as u64 & mask(self.cfg.n_bits()) as u64;
        let quotient = if n == 0 { 1 << w } else { ((c << w) / (2 * n * ((1u64 << f) - c) + c)) as u128 };
        self.outputs(x, quotient)
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
        return Err(Error::breach("intensity", format!("got {}, S·2^FI = {}·2^{}/{den}", got.intensity, num, cfg.fi())));
    }
    for (i, name) in SPEC_PORTS.iter().enumerate() {
        if !within(got.spec[i], x.ks[i] as u128) {
            return Err(Error::breach(name, format!("got {}, S·ks = {}·{}/{den}", got.spec[i], num, x.ks[i])));
        }
    }
    if got.done != (got.intensity == 0) {
        return Err(Error::breach("done", format!("got {}, intensity {}", got.done, got.intensity)));
    }
    Ok(())
}

impl SpecularUnit for Schlick {
    fn eval(&self, x: Inputs) -> Outputs {
        self.quick(x)
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), Error> {
        check(&self.cfg, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        let (num, den) = ratio(&self.cfg, x);
        let s = num as f64 / den as f64;
        (s * (self.cfg.fi() as f64).exp2(), x.ks.map(|k| s * k as f64))
    }

    fn reference_words(&self) -> &'static str {
        "the exact quotient S = c/(2n - 2n*c + c) in integers"
    }

    fn datapath(&self, b: &mut Builder) {
        datapath(&self.cfg, self.quotient_frac_bits, b)
    }

    fn describe(&self) -> Description {
        let p = &self.cfg.params;
        Description {
            param_line: String::new(),
            formula: vec![
                "S = c / (2n - 2n*c + c), c = min(cos_g, 1.0) (the paper's modified Schlick, formula (11)); S = 1 at n = 0;".into(),
                format!("intensity = S (UQ1.{}), spec_X = S * ks_X; done = (intensity == 0).", p.intensity_frac_bits),
            ],
            rounding: "faithful: every output within 1 ulp of the exact quotient (|o - o*| < 1)".into(),
            datapath: format!(
                "den = 2n*(1 - c) + c exact, a restoring divider of one quotient bit a step to UQ1.{} (error budget in specgen's models/schlick.rs)",
                self.quotient_frac_bits
            ),
            done_meaning: "intensity == 0: the highlight is below the output's resolution",
            summary: "Fixed-point modified-Schlick specular unit, c/(2n - 2n*c + c) by a restoring divider",
            computes: "modified Schlick (11) by division",
        }
    }

    fn widths(&self) -> serde_json::Value {
        let (f, nb) = (self.cfg.f(), self.cfg.n_bits());
        serde_json::json!({ "quotient_frac_bits": self.quotient_frac_bits, "denominator_bits": nb + f + 2, "remainder_bits": nb + f + 3 })
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        let t = self.trace(x);
        vec![
            format!("den        2n*(1 - c) + c = {} (units of 2^-{})", t.den, self.cfg.f()),
            format!(
                "quotient   floor(S*2^{}) = {} (UQ1.{}: {:.9})",
                self.quotient_frac_bits,
                t.quotient,
                self.quotient_frac_bits,
                t.quotient as f64 / (self.quotient_frac_bits as f64).exp2()
            ),
            explain_ideal(self.ideal(x), "(c/(2n - 2n*c + c))"),
        ]
    }
}

/// Step 1 clamps c and forms 1 − c; then the denominator (a multiply-add) and its complement;
/// then one quotient bit a step (a compare-subtract of the doubled remainder on one carry
/// chain, and a select); the last step picks 1.0 at n = 0 and rounds to the outputs.
fn datapath(cfg: &Config, w: u32, b: &mut Builder) {
    let (f, nb, bb, fi) = (cfg.f(), cfg.n_bits(), cfg.b(), cfg.fi());
    let dw = nb + f + 2; // den, and the remainder
    let rw = dw + 1; // a doubled remainder

    b.step("clamp c = min(cos, 1); d = 1 - c; n = 0 picks S = 1 at the end");
    let g = b.r("cos_g");
    let one = lit(f + 1, 1u128 << f);
    let cos = b.wire("cos_clamped", f + 1, Kind::Logic, ex!("({} > {}) ? {} : {}", g, one, one, g), &format!("UQ1.{f}: c"));
    let c = b.r(&cos);
    let one_minus_cos = b.wire("one_minus_cos", f + 1, Kind::Sum, ex!("{} - {}", one, c), &format!("UQ1.{f}: 1 - c, exact"));
    let n = b.sig("n");
    let nv = b.r(&n);
    let n_zero = b.wire("n_zero", 1, Kind::Logic, ex!("{} == {}", nv, lit(nb, 0)), "n = 0: S = 1 (cos^0), the limit at c = 0 too");
    b.delay(2.0 * add_delay(f + 1));

    // 2n·(1 − c) + c = 2·(n·(1 − c) + ⌊c/2⌋) + c[0]: one multiply-add (on the iCE40 the
    // SB_MAC16's post-adder, its register the block's; on the ECP5 a MULT18X18D, then a carry
    // chain), the doubling and c[0] by wiring
    b.step("the denominator den = 2n*(1 - c) + c, exact: half of it, n*(1 - c) + floor(c/2)");
    let comment = format!("UQ{}.{}: n*(1 - c) + floor(c/2), exact: den = 2*den_half + c[0]", nb + 1, f);
    let half = b.multiply_add("den_half", &[n.all()], &[one_minus_cos.all()], &[cos.part(1, f)], dw - 1, "the denominator", &comment);

    // −den − 1 = ~den over the trial's width, once: each compare-subtract is then a plain add
    // with carry-in 1 (a carry chain's operand takes no inverter)
    b.step("~den for the compare-subtracts");
    let (hv, c0) = (b.r(&half), b.bits(&cos, 0, 0));
    let den_inv = b.wire(
        "den_inv",
        rw + 1,
        Kind::Logic,
        ex!("~{{{}, {}, {}}}", lit(rw + 1 - dw, 0), hv, c0),
        &format!("~den over {} bits, den = 2n*(1 - c) + c = {{den_half, c[0]}}: 2r + ~den + 1 = 2r - den", rw + 1),
    );
    b.delay(LUT_DELAY);

    // one quotient bit a step (the weight-1 bit first): the trial `shifted - den` on one carry
    // chain (a carry-select add would cut a bit over several steps, and its registers, a
    // remainder's and den's a cut, overflow the UP5K), its carry-out the bit, then the select;
    // `rem` and `quot` are the last step's remainder and quotient bits so far
    let (mut rem, mut quot): (Option<Sig>, Option<Sig>) = (None, None);
    for k in 0..=w {
        let title = if k == 0 { "quotient bit of weight 1: c >= den".to_string() } else { format!("quotient bit of weight 2^-{k}: 2r >= den") };
        b.step(&title);
        let (prev, what) = match &rem {
            None => (b.zext(&cos, rw), "c".to_string()),
            Some(r) => (ex!("{{{}, 1'b0}}", b.r(r)), format!("2*r{}", k - 1)),
        };
        let shifted = b.wire(&format!("shifted{k}"), rw, Kind::Select, prev, &format!("UQ{}.{f}: {what}", nb + 3));
        let (sv, dv) = (b.zext(&shifted, rw + 1), b.r(&den_inv));
        let trial = b.wire(
            &format!("trial{k}"),
            rw + 1,
            Kind::Sum,
            ex!("{} + {} + {}", sv, dv, lit(rw + 1, 1)),
            &format!("{what} - den mod 2^{}: its top bit a borrow", rw + 1),
        );
        let borrow = b.bits(&trial, rw, rw);
        let qbit = b.wire(&format!("qbit{k}"), 1, Kind::Logic, ex!("~{}", borrow), &format!("quotient bit of weight 2^-{k}: {what} >= den"));
        let (bit, t, s) = (b.r(&qbit), b.bits(&trial, dw - 1, 0), b.bits(&shifted, dw - 1, 0));
        rem = Some(b.wire(&format!("rem{k}"), dw, Kind::Logic, Builder::select(&bit, &t, &s, dw), &format!("r{k}: the remainder, below den")));
        // the quotient's bits so far (from the second on: the first is qbit0 itself)
        quot = Some(match quot {
            None => qbit,
            Some(above) => {
                let bits = ex!("{{{}, {}}}", b.r(&above), bit);
                b.wire(&format!("quot{k}"), k + 1, Kind::Select, bits, &format!("the quotient's top {} bits", k + 1))
            }
        });
        // the chain, its carry-out through a LUT, the remainder's select
        b.delay(add_delay(rw + 1) + LUT_DELAY);
    }
    let quot = quot.expect("at least one quotient bit");

    b.step("S = 1 at n = 0");
    let (nz, q) = (b.r(&n_zero), b.r(&quot));
    let quotient = b.wire("quotient", w + 1, Kind::Logic, Builder::select_const(&nz, 1u128 << w, w + 1, &q), &format!("UQ1.{w}: floor(S*2^{w}), 1.0 at n = 0"));
    b.delay(LUT_DELAY);

    // the colours take S floored to Wc bits (the module doc): one block each, its product
    // alone in its step, read after its register
    let wc = colour_frac_bits(cfg, w);
    b.step("colour multipliers (14-16)");
    b.colour_products(quotient.name(), w - wc, wc, "S");
    b.product_delay(wc + 1, bb, wc + bb, 0.0);

    b.step("round half up to the outputs");
    let qv = b.r(&quotient);
    let sum = b.wire("intensity_sum", w + 1, Kind::Sum, ex!("{} + {}", qv, lit(w + 1, 1u128 << (w - fi - 1))), &format!("UQ1.{w}: S + 2^-{}", fi + 1));
    let e = b.bits(&sum, w, w - fi);
    let intensity = b.wire("intensity", fi + 1, Kind::Select, e, &format!("UQ1.{fi}: S rounded half up"));
    // (on the ECP5, the colours' rounding half after their products)
    b.colour_rounding(wc, "S");
    b.colour_results(wc, "S");
    let iv = b.r(&intensity);
    b.wire("done", 1, Kind::Logic, ex!("{} == {}", iv, lit(fi + 1, 0)), "the highlight is below the output's resolution");
    b.delay(add_delay(w + 1) + LUT_DELAY);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Params, SpecularModel};

    fn cfg(p: Params) -> Config {
        Config::new(Params { model: SpecularModel::Schlick, ..p }).unwrap()
    }

    #[test]
    fn the_divider_gives_the_floor_of_the_quotient() {
        let s = Schlick::new(&cfg(Params::default()));
        let w = s.quotient_frac_bits;
        for n in [1u32, 2, 7, 100, 1023] {
            for cos_g in (0..=1u32 << 15).step_by(331) {
                let t = s.trace(Inputs { cos_g, n, ks: [0; 3] });
                assert_eq!(t.quotient, ((cos_g as u128) << w) / t.den, "n={n} cos_g={cos_g}");
                assert!(t.remainders.iter().all(|&r| r < t.den));
                // and eval, one division, is the divider step for step
                let x = Inputs { cos_g, n, ks: [cos_g & 255, n & 255, 255] };
                assert_eq!(s.eval(x), s.trace(x).outputs, "{x:?}");
            }
        }
    }

    #[test]
    fn eval_is_the_divider_step_for_step_on_a_whole_input_space() {
        // every input of a narrow unit, and a sample of the widest
        for p in [
            Params { cos_frac_bits: 9, n_bits: 5, color_bits: 4, intensity_frac_bits: 7, ..Params::default() },
            Params { cos_frac_bits: 20, n_bits: 12, color_bits: 16, intensity_frac_bits: 24, ..Params::default() },
        ] {
            let s = Schlick::new(&cfg(p.clone()));
            let step = if p.cos_frac_bits > 9 { 77_777 } else { 1 };
            for n in 0..1u32 << p.n_bits {
                for cos_g in (0..2u32 << p.cos_frac_bits).step_by(step) {
                    let x = Inputs { cos_g, n, ks: [cos_g & mask(p.color_bits) as u32, n, (1 << p.color_bits) - 1] };
                    assert_eq!(s.eval(x), s.divide(x, |_| {}).3, "{x:?}");
                }
            }
        }
    }

    #[test]
    fn the_colours_bound_is_tight() {
        // colours wider than the intensity: one quotient bit fewer than the budget (W = B)
        // breaks the contract on a colour near 2^B; the budget's W meets it everywhere
        let c = cfg(Params { cos_frac_bits: 10, n_bits: 6, color_bits: 12, intensity_frac_bits: 6, ..Params::default() });
        let (narrow, s) = (Schlick { cfg: c.clone(), quotient_frac_bits: quotient_frac_bits(&c) - 1 }, Schlick::new(&c));
        let mut broken = false;
        for n in 0..64u32 {
            for cos_g in 0..=1u32 << 10 {
                let x = Inputs { cos_g, n, ks: [4095, 4094, 1] };
                broken |= check(&c, x, narrow.eval(x)).is_err();
                assert!(check(&c, x, s.eval(x)).is_ok(), "{x:?}");
            }
        }
        assert!(broken, "W = B is enough: the colours' bound is not tight");
    }

    #[test]
    fn zero_over_zero_is_one() {
        let s = Schlick::new(&cfg(Params::default()));
        let o = s.eval(Inputs { cos_g: 0, n: 0, ks: [255, 3, 0] });
        assert_eq!(o, Outputs { spec: [255, 3, 0], intensity: 1 << 15, done: false });
        assert_eq!(s.eval(Inputs { cos_g: 0, n: 5, ks: [255; 3] }).intensity, 0);
    }
}
