//! `--model blinn-pow`: Blinn's `c^n` by square-and-multiply over the bits of n, LSB first —
//! the costly exact baseline. Its home: the error budget ([`power_frac_bits`]), the golden
//! model ([`BlinnPow`]'s `eval`), the datapath, on the same builder as every model. Its
//! contract is the rigorous `c^n` check every `c^n` model shares ([`check_cos_n`]).

use super::{
    check_cos_n, cosine, explain_ideal, scaled, Description, Inputs, Outputs, SpecularUnit,
};
use crate::bits::{lit, mask};
use crate::config::Config;
use crate::datapath::{add_delay, ex, Builder, Delay, Expr, Kind, Piece, LUT_DELAY};

/// W for `--model blinn-pow` (square-and-multiply over the bits of n, LSB first, every
/// product truncated to W fractional bits, c taken exactly: W ≥ F).
///
/// Error budget: all truncations round down, so errors are one-sided. Powers `p_i = c^(2^i)`
/// are squared: with `p ≤ 1`, `x² − (x−e)² ≤ 2e`, so `e(p_i) ≤ (2^i − 1)·2^−W`. The result
/// `r ← r·p_i` (r, p ≤ 1) gains at most `e(r) + e(p_i) + 2^−W`; summed over the N bits,
/// `e(r_N) ≤ Σ_{i<N} 2^i·2^−W < 2^(N−W)`. In output units (`M = 2^FI` or `ks < 2^B`) this is
/// below 1/2 when `W ≥ max(FI, B) + N + 1`; the final round-half-up then gives a faithful
/// result, exact where the ideal is an integer, and monotone in cos_g.
pub(crate) fn power_frac_bits(cfg: &Config) -> u32 {
    (cfg.fi().max(cfg.b()) + cfg.n_bits() + 1).max(cfg.f())
}

/// The blinn-pow unit of one configuration.
#[derive(Debug, Clone)]
pub struct BlinnPow {
    pub(crate) cfg: Config,
    /// W: fractional bits of every power and partial product, UQ1.W.
    pub(crate) power_frac_bits: u32,
}

impl BlinnPow {
    pub fn new(cfg: &Config) -> BlinnPow {
        BlinnPow {
            cfg: cfg.clone(),
            power_frac_bits: power_frac_bits(cfg),
        }
    }
}

impl SpecularUnit for BlinnPow {
    /// It fits neither part at default widths, so no unit of it is calibrated.
    fn reads_family_delay_line(&self) -> bool {
        true
    }
    fn premise_role(&self) -> Option<crate::models::PremiseRole> {
        Some(crate::models::PremiseRole::SquareAndMultiply)
    }

    /// Square-and-multiply over the bits of n, LSB first, each product truncated to W
    /// fractional bits ([`power_frac_bits`]), as the RTL does it.
    fn eval(&self, x: Inputs) -> Outputs {
        let w = self.power_frac_bits;
        let (f, fi, b, nb) = (self.cfg.f(), self.cfg.fi(), self.cfg.b(), self.cfg.n_bits());
        let cos_g = x.cos_g as u128 & mask(f + 1);
        let n = x.n as u128 & mask(nb);
        // step 1: clamp to 1.0, widen UQ1.F → UQ1.W; r = 1.0
        let mut power = cos_g.min(1 << f) << (w - f);
        let mut result = 1u128 << w;
        // steps 2..N+1: one bit of n each
        for i in 0..nb {
            if (n >> i) & 1 == 1 {
                result = (result * power) >> w;
            }
            if i + 1 < nb {
                power = (power * power) >> w;
            }
        }
        // last step: round half up to the outputs
        let intensity = ((result + (1u128 << (w - fi - 1))) >> (w - fi)) as u32;
        let spec =
            x.ks.map(|k| (((result * (k as u128 & mask(b))) + (1u128 << (w - 1))) >> w) as u32);
        Outputs {
            spec,
            intensity,
            done: intensity == 0,
        }
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), crate::error::Error> {
        check_cos_n(&self.cfg, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        scaled(&self.cfg, cosine(&self.cfg, x.cos_g).powi(x.n as i32), x)
    }

    fn datapath(&self, b: &mut Builder) {
        datapath(&self.cfg, self.power_frac_bits, b)
    }

    fn describe(&self) -> Description {
        let p = &self.cfg.params;
        Description {
            param_line: String::new(),
            formula: vec![
                "S = c^n, c = min(cos_g, 1.0), by square-and-multiply over the bits of n, LSB first;".into(),
                format!("intensity = S (UQ1.{}), spec_X = S * ks_X; done = (intensity == 0).", p.intensity_frac_bits),
            ],
            rounding: "faithful: every output within 1 ulp of the exact c^n value (|o - o*| < 1)".into(),
            datapath: format!(
                "powers c^(2^i) and the running product UQ1.{}, each product floored (error budget in specgen's models/blinn_pow.rs)",
                self.power_frac_bits
            ),
            done_meaning: "intensity == 0: the highlight is below the output's resolution",
            summary: "Fixed-point Blinn specular unit, cos^n by square-and-multiply",
            computes: "c^n by square-and-multiply",
        }
    }

    fn widths(&self) -> serde_json::Value {
        serde_json::json!({ "power_frac_bits": self.power_frac_bits })
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        vec![
            format!(
                "datapath   square-and-multiply over the bits of n, UQ1.{}",
                self.power_frac_bits
            ),
            explain_ideal(self.ideal(x), "(c^n)"),
        ]
    }
}

/// Step 1 clamps and widens c; steps 2..N+1 take one bit of n each (multiply the running
/// product by the power when the bit is set, square the power); the last step rounds.
fn datapath(cfg: &Config, pw: u32, b: &mut Builder) {
    let (f, nb, fi) = (cfg.f(), cfg.n_bits(), cfg.fi());
    let full = 2 * pw + 2;

    b.step(&format!(
        "clamp c = min(cos, 1), widen to UQ1.{pw}; the running product starts at 1.0"
    ));
    let g = b.r("cos_g");
    let one = lit(f + 1, 1u128 << f);
    b.wire(
        "cos_clamped",
        f + 1,
        Kind::Logic,
        ex!("({} > {}) ? {} : {}", g, one, one, g),
        &format!("UQ1.{f}: c"),
    );
    let c = b.r("cos_clamped");
    let widened = if pw > f {
        ex!("{{{}, {}}}", c, lit(pw - f, 0))
    } else {
        c
    };
    b.wire(
        "power0",
        pw + 1,
        Kind::Select,
        widened,
        &format!("UQ1.{pw}: c^(2^0), exact"),
    );
    b.wire(
        "result0",
        pw + 1,
        Kind::Select,
        Expr::constant(lit(pw + 1, 1u128 << pw)),
        &format!("UQ1.{pw}: 1.0"),
    );
    b.delay(add_delay(f + 1));

    // on the ECP5 each choice takes a step of its own, so that the MULT18X18Ds' input
    // registers take the chosen operands (and a block's output is read after its step), when
    // the operands fit one block
    let own_step = b.instantiated_blocks() && pw < crate::datapath::ECP5_DSP_BITS;
    for i in 0..nb {
        let more = i + 1 < nb;
        if i > 0 && own_step {
            b.step(&format!("bit {} of n: the choice", i - 1));
            chosen(b, nb, pw, i);
            b.delay(LUT_DELAY);
        }
        b.step(&format!(
            "bit {i} of n: multiply by c^(2^{i}) when it is set{}",
            if more { "; square the power" } else { "" }
        ));
        // the last bit's choice, here: a product's block meets only its register
        if i > 0 && !own_step {
            chosen(b, nb, pw, i);
        }
        let (r, p) = (format!("result{i}"), format!("power{i}"));
        let (rp, pp) = ([Piece::sig(&r, 0, pw + 1)], [Piece::sig(&p, 0, pw + 1)]);
        // on the ECP5 a MULT18X18D with its own registers where the cuts allow; elsewhere a
        // product inferred after the choice's LUT
        let product = |b: &mut Builder, name: String, a: &[Piece], what: String| match own_step {
            true => b.product(&name, a, &pp, full, &what),
            false => {
                _ = b.mul(
                    &name,
                    full,
                    (a, pw + 1),
                    (&pp, pw + 1),
                    &[],
                    LUT_DELAY,
                    &what,
                )
            }
        };
        product(
            b,
            format!("result_prod{}", i + 1),
            &rp,
            format!("UQ2.{}: result*power, exact", 2 * pw),
        );
        if more {
            product(
                b,
                format!("power_sq{}", i + 1),
                &pp,
                format!("UQ2.{}: power^2, exact", 2 * pw),
            );
        }
    }

    if own_step {
        b.step(&format!("bit {} of n: the choice", nb - 1));
        chosen(b, nb, pw, nb);
        b.delay(LUT_DELAY);
    }
    b.step("colour multipliers (14-16)");
    if !own_step {
        chosen(b, nb, pw, nb);
    }
    let r = format!("result{nb}");
    match b.instantiated_blocks() {
        // the products alone (MULT18X18Ds where they fit), the rounding half after them
        true => b.colour_products(&r, 0, pw, "c^n"),
        false => b.colour_sums(&r, pw, "c^n", Delay::ZERO),
    }
    // (on the iCE40 after the choice's LUT)
    b.product_delay(
        pw + 1,
        cfg.b(),
        pw + cfg.b(),
        if own_step { Delay::ZERO } else { LUT_DELAY },
    );

    // the colours after their blocks' registers
    b.step("round half up to the outputs");
    let rv = b.r(&r);
    b.wire(
        "intensity_sum",
        pw + 1,
        Kind::Sum,
        ex!("{} + {}", rv, lit(pw + 1, 1u128 << (pw - fi - 1))),
        &format!("UQ1.{pw}: c^n + 2^-{}", fi + 1),
    );
    let e = b.bits("intensity_sum", pw, pw - fi);
    b.wire(
        "intensity",
        fi + 1,
        Kind::Select,
        e,
        &format!("UQ1.{fi}: c^n rounded half up"),
    );
    // (on the ECP5, the colours' rounding half after their products)
    b.colour_rounding(pw, "c^n");
    b.colour_results(pw, "c^n");
    let iv = b.r("intensity");
    b.wire(
        "done",
        1,
        Kind::Logic,
        ex!("{} == {}", iv, lit(fi + 1, 0)),
        "the highlight is below the output's resolution",
    );
    b.delay(add_delay(pw + 1) + LUT_DELAY);
}

/// After bit `i - 1` of n: `result{i}` (the floored product when the bit is set, else the
/// product so far), and below the last bit the power `power{i}` (the floored square) and the
/// bits of n still to use, `n_rest{i}`.
fn chosen(b: &mut Builder, nb: u32, pw: u32, i: u32) {
    // the bits of n still to use travel on, shrinking, as n_rest (n itself for bit 0)
    let rest = if i == 1 {
        "n".to_string()
    } else {
        format!("n_rest{}", i - 1)
    };
    let bit = b.bits(&rest, 0, 0);
    let (hi, keep) = (
        b.bits(&format!("result_prod{i}"), 2 * pw, pw),
        b.r(&format!("result{}", i - 1)),
    );
    b.wire(
        &format!("result{i}"),
        pw + 1,
        Kind::Logic,
        ex!("{} ? {} : {}", bit, hi, keep),
        &format!("UQ1.{pw}: floored product, or the product so far"),
    );
    if i < nb {
        let sq = b.bits(&format!("power_sq{i}"), 2 * pw, pw);
        b.wire(
            &format!("power{i}"),
            pw + 1,
            Kind::Select,
            sq,
            &format!("UQ1.{pw}: c^(2^{i}), floored"),
        );
        let upper = b.bits(&rest, nb - i, 1);
        b.wire(
            &format!("n_rest{i}"),
            nb - i,
            Kind::Select,
            upper,
            "the bits of n still to use",
        );
    }
}
