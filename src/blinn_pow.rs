//! `--model blinn-pow`: Blinn's `c^n` by square-and-multiply over the bits of n, LSB first —
//! the costly exact baseline. Its error budget is `widths::power_frac_bits`; its golden model
//! is `Model::eval_blinn_pow`; this is its datapath, on the same builder as every model.

use crate::config::Config;
use crate::datapath::{lit, mul_delay, Builder, CHANNELS, LUT_DELAY};
use crate::widths::Widths;

/// Step 1 clamps and widens c; steps 2..N+1 take one bit of n each (multiply the running
/// product by the power when the bit is set, square the power); the last step rounds.
pub fn datapath(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, nb, bb, fi) = (cfg.f(), cfg.n_bits(), cfg.b(), cfg.fi());
    let pw = w.power_frac_bits;
    let full = 2 * pw + 2;

    b.step(&format!("clamp c = min(cos, 1), widen to UQ1.{pw}; the running product starts at 1.0"));
    let g = b.r("cos_g");
    let one = lit(f + 1, 1u128 << f);
    b.wire("cos_clamped", f + 1, format!("({g} > {one}) ? {one} : {g}"), &format!("UQ1.{f}: c"));
    let c = b.r("cos_clamped");
    let widened = if pw > f { format!("{{{c}, {}}}", lit(pw - f, 0)) } else { c };
    b.wire("power0", pw + 1, widened, &format!("UQ1.{pw}: c^(2^0), exact"));
    b.wire("result0", pw + 1, lit(pw + 1, 1u128 << pw), &format!("UQ1.{pw}: 1.0"));
    b.delay(crate::datapath::add_delay(f + 1));

    for i in 0..nb {
        let more = i + 1 < nb;
        b.step(&format!("bit {i} of n: multiply by c^(2^{i}) when it is set{}", if more { "; square the power" } else { "" }));
        let (r, p) = (format!("result{i}"), format!("power{i}"));
        let (re, pe) = (b.zext(&r, full), b.zext(&p, full));
        b.wire(&format!("result_prod{}", i + 1), full, format!("{re} * {pe}"), &format!("UQ2.{}: result*power, exact", 2 * pw));
        // the bits of n still to use travel on, shrinking, as n_rest (n itself for bit 0)
        let rest = if i == 0 { "n".to_string() } else { format!("n_rest{i}") };
        let bit = b.bits(&rest, 0, 0);
        let (hi, keep) = (b.bits(&format!("result_prod{}", i + 1), 2 * pw, pw), b.r(&r));
        b.wire(&format!("result{}", i + 1), pw + 1, format!("{bit} ? {hi} : {keep}"), &format!("UQ1.{pw}: floored product, or the product so far"));
        if more {
            let (p1, p2) = (b.zext(&p, full), b.zext(&p, full));
            b.wire(&format!("power_sq{}", i + 1), full, format!("{p1} * {p2}"), &format!("UQ2.{}: power^2, exact", 2 * pw));
            let sq = b.bits(&format!("power_sq{}", i + 1), 2 * pw, pw);
            b.wire(&format!("power{}", i + 1), pw + 1, sq, &format!("UQ1.{pw}: c^(2^{}), floored", i + 1));
            let upper = b.bits(&rest, nb - i - 1, 1);
            b.wire(&format!("n_rest{}", i + 1), nb - i - 1, upper, "the bits of n still to use");
        }
        b.delay(mul_delay(pw + 1, pw + 1) + LUT_DELAY);
    }

    b.step("round half up to the outputs");
    let r = format!("result{nb}");
    let rv = b.r(&r);
    b.wire("intensity_sum", pw + 1, format!("{rv} + {}", lit(pw + 1, 1u128 << (pw - fi - 1))), &format!("UQ1.{pw}: c^n + 2^-{}", fi + 1));
    let e = b.bits("intensity_sum", pw, pw - fi);
    b.wire("intensity", fi + 1, e, &format!("UQ1.{fi}: c^n rounded half up"));
    let cp = pw + bb;
    for ch in CHANNELS {
        let (sv, kv) = (b.zext(&r, cp), b.zext(&format!("ks_{ch}"), cp));
        b.wire(&format!("color_sum_{ch}"), cp, format!("{sv} * {kv} + {}", lit(cp, 1u128 << (pw - 1))), &format!("UQ{bb}.{pw}: c^n*ks_{ch} + 1/2 colour ulp"));
        let s = b.bits(&format!("color_sum_{ch}"), cp - 1, pw);
        b.wire(&format!("spec_{ch}"), bb, s, &format!("UNORM{bb}: c^n*ks_{ch} rounded half up"));
    }
    let iv = b.r("intensity");
    b.wire("done", 1, format!("{iv} == {}", lit(fi + 1, 0)), "the highlight is below the output's resolution");
    b.delay(mul_delay(pw + 1, bb) + crate::datapath::add_delay(cp));
}
