//! The blinn datapath on the builder: normalise, log2 by table, times n, exp2 by table,
//! shift, round.

mod exp2;
use exp2::*;

use super::*;
use crate::datapath::{pad_operands, Delay, Sig, LUT_INPUTS};

/// A multiplier of at most this many bits is worth shift-adds rather than a DSP block.
const SHIFT_ADD_BITS: u32 = 5;

/// What every part of the datapath reads: the configuration, the widths and tables, and the
/// shape chosen once (each interpolation on a DSP block or not, the tables' indices).
#[derive(Clone, Copy)]
struct Shape<'a> {
    w: &'a BlinnWidths,
    t: &'a BlinnTables,
    f: u32,
    fi: u32,
    bb: u32,
    nb: u32,
    cb: u32,
    dsp: u32,
    /// the low bits of x (log) and of frac(y) (exp2) below each table's index
    rb: u32,
    re: u32,
    /// each interpolation on one DSP block
    log_dsp: bool,
    exp2_dsp: bool,
    log_pad: Option<OperandPad>,
    exp2_pad: Option<OperandPad>,
    /// the tables' indices in the builder
    lt: usize,
    et: usize,
}

/// The blinn datapath: normalise, log2 by table, times n, exp2 by table, shift, round.
pub fn datapath(cfg: &Config, w: &BlinnWidths, t: &BlinnTables, b: &mut Builder) {
    let (f, fi, bb, nb) = (cfg.f(), cfg.fi(), cfg.b(), cfg.n_bits());
    let cb = f + 1;
    // each interpolation on one DSP block where its operands fit (on the iCE40 with the
    // entry added inside it: the table word carries the operands at the block's width)
    let dsp = b.dsp_bits();
    let (rb, re) = (w.log_rest_bits(cfg), w.exp2_rest_bits());
    let (log_dsp, log_pad) = b.interpolation_on_block(w.log_delta_bits, rb, w.ghat_bits());
    let (exp2_dsp, exp2_pad) = b.interpolation_on_block(w.exp2_delta_bits, re, w.exp2_entry_bits);
    let lt = b.table(t.log_table(w, log_pad));
    // on a DSP block the entry is the multiply-add's addend, complemented: stored so
    let et = b.table(t.exp2_table(w, exp2_pad, exp2_dsp));

    let s = Shape {
        w,
        t,
        f,
        fi,
        bb,
        nb,
        cb,
        dsp,
        rb,
        re,
        log_dsp,
        exp2_dsp,
        log_pad,
        exp2_pad,
        lt,
        et,
    };
    normalise(&s, b);
    let ell_after = log2(&s, b);
    times_n(&s, b, ell_after);
    let complemented = exp2(&s, b);
    shift_and_round(&s, b, complemented);
}

/// Clamp c, then normalise it: c' = c*2^e in (1/2, 1] by its leading zeros, and x = 1 - c'.
fn normalise(s: &Shape, b: &mut Builder) {
    let Shape { w, f, nb, cb, .. } = *s;
    b.step("clamp c = min(cos, 1)");
    let (top, g) = (b.bits("cos_g", f, f), b.r("cos_g"));
    // cos_g >= 1.0 exactly when its integer bit is set: a mux, no comparator
    b.wire(
        "cos_clamped",
        cb,
        Kind::Logic,
        Builder::select_const(&top, 1u128 << f, cb, &g),
        &format!("UQ1.{f}: c"),
    );
    // beside it, the first LUT level of c = 0 (cos_g = 0: the clamp keeps 0) and of n != 0,
    // each an OR of up to 4 bits: the second is one LUT in a later step
    let bits = b.bit_list("cos_g", f, 0);
    let cos_any = b.or_groups("cos_nonzero", bits, "cos_g");
    let bits = b.bit_list("n", nb - 1, 0);
    let n_any = b.or_groups("n_nonzero", bits, "n");
    b.delay(LUT_DELAY);

    // c - 2^-F = c + (2^(F+1) - 1) mod 2^(F+1): a carry-select add of the all-ones word
    let title = "c - 1 for the normalisation";
    b.step(&format!("{title}; c = 0"));
    let p = b.add_start(
        "cos_minus_ulp",
        &[Piece::sig("cos_clamped", 0, cb)],
        &[Piece::Const {
            value: mask(cb),
            width: cb,
        }],
        false,
        cb,
        &format!("UQ1.{f}: c - 2^-{f} (its leading zeros give the exponent)"),
    );
    let terms: Vec<Expr> = cos_any.iter().map(|g| b.r(g)).collect();
    b.wire(
        "cos_zero",
        1,
        Kind::Logic,
        ex!("~({})", Expr::join(&terms, " | ")),
        "c = 0: c^n = 0 for n >= 1",
    );
    b.delay(2.0 * LUT_DELAY);
    b.resolve(p, title);

    // e = the leading zeros of c - 2^-F over its F fraction bits, in two LUT steps: per group
    // of 4 bits from the top, whether it has a one and where its first one is; then the
    // first group with a one
    let eb = w.exp_bits;
    b.step("normalise: the exponent e, per group of 4 bits of c - 2^-F");
    b.leading_zeros(
        "lead",
        "cos_minus_ulp",
        f,
        f,
        "exponent",
        w.exp_bits,
        &format!("c - 2^-{f}"),
        "normalise: e = the leading zeros of c - 2^-F",
        &format!("e = F - bitlength(C - 1) in 0..{f}: leading zeros of c - 2^-{f}"),
    );
    // beside it, the one case the tables do not cover, carried as one bit
    let terms: Vec<Expr> = n_any.iter().map(|g| b.r(g)).collect();
    let z = b.r("cos_zero");
    b.wire(
        "y_zero_power",
        1,
        Kind::Logic,
        ex!("{} & ({})", z, Expr::join(&terms, " | ")),
        "c = 0 with n >= 1: c^n = 0 (y saturates)",
    );
    b.delay(2.0 * LUT_DELAY);

    // c' = c*2^e, one bit of e a step from the top: a 2:1 mux level each, so the bit that
    // fans out over the whole word drives one LUT level; the last also inverts c' for
    // x = -c' = ~c' + 1
    let mut src = "cos_clamped".to_string();
    for k in (0..eb).rev() {
        let last = k == 0;
        let name = if last {
            "cos_norm".to_string()
        } else {
            format!("cos_norm_shift{k}")
        };
        b.step(&if last {
            "normalise: c' = c*2^e in (1/2, 1], its complement".to_string()
        } else {
            format!("normalise: c shifted by e's bit {k}")
        });
        // 2^k <= F < F + 1: bit k of e never shifts the whole word out
        let what = if last {
            format!("UQ1.{f}: c' = c*2^e in (1/2, 1]")
        } else {
            format!("UQ1.{f}: c*2^(e's bits from {k} up)")
        };
        b.shift_left_level(&name, &src, "exponent", k, cb, &what);
        if last {
            let cn = b.bits("cos_norm", f - 2, 0);
            b.wire(
                "cos_norm_inv",
                f - 1,
                Kind::Logic,
                ex!("~{}", cn),
                &format!("~c' over its low {} bits", f - 1),
            );
        }
        b.delay(LUT_DELAY);
        src = name;
    }
    // x = 1 - c' < 1/2: only the low F-1 bits of 2^F - c', i.e. of -c' = ~c' + 1
    let title = "x = 1 - c'";
    b.step(title);
    let p = b.add_start(
        "x",
        &[Piece::sig("cos_norm_inv", 0, f - 1)],
        &[],
        true,
        f - 1,
        &format!("UQ0.{f} (top bit 0): x = 1 - c' in [0, 1/2), exact"),
    );
    b.resolve(p, title);
}

/// -log2 c' = x*g(x), g by the log2 table and linear interpolation; then l = e + L (truncation #1).
/// Returns whether `ell` is left to the next step ([`ell`]): after a product alone in its step.
fn log2(s: &Shape, b: &mut Builder) -> bool {
    let Shape {
        w,
        f,
        dsp,
        rb,
        log_dsp,
        log_pad,
        lt,
        ..
    } = *s;
    // the table's address beside x (on ECP5 the block RAM's address register takes it)
    let tg = w.log_index_bits;
    let idx = b.bits("x", f - 2, rb);
    b.wire(
        "log_index",
        tg,
        Kind::Select,
        idx,
        &format!("i: 2x to {tg} bits"),
    );

    b.ecp5_register_step("log2 table read: the address at the block RAM's address register");
    b.step(&format!(
        "log2 table read: g(x) = -log2(1 - x)/x at the top {tg} bits of 2x"
    ));
    b.rom_read_registered("log_word", lt, "log_index");
    b.delay(LUT_DELAY * tg.div_ceil(2) as f64);
    b.ecp5_register_step("log2 table read: the word at the multiplier's input registers");

    let gb = w.ghat_bits();
    let ge = w.log_entry_bits;
    let title = "g by linear interpolation";
    // where g^ is read from: a signal and its lowest bit
    let mut ghat = ("ghat".to_string(), 0);
    if log_dsp {
        // g^ = G[i] + floor(dG[i]*r / 2^RB) = floor((G[i]*2^RB + dG[i]*r) / 2^RB): one DSP
        // multiply-add, the entry its addend
        b.step(&format!("{title}: dG[i]*r + G[i]*2^{rb} (multiplier)"));
        let sw = gb + rb;
        let (dg, r, g) = (
            Piece::sig("log_word", ge, w.log_delta_bits),
            Piece::sig("x", 0, rb),
            Piece::sig("log_word", 0, ge),
        );
        let (a, r) = pad_operands(dg, r, "log_word", log_pad);
        let comment = format!(
            "G[i]*2^{rb} + dG[i]*(x mod 2^-{}), exact; g^ = bits [{}:{rb}], UQ2.{}",
            tg + 1,
            sw - 1,
            w.log_frac_bits
        );
        let sum = b.multiply_add(
            "ghat_sum",
            &a,
            &r,
            &[Piece::zeros(rb), g],
            sw,
            title,
            &comment,
        );
        if b.instantiated_blocks() {
            let e = b.bits(&sum, sw - 1, rb);
            b.wire(
                "ghat",
                gb,
                Kind::Select,
                e,
                &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits),
            );
        } else {
            // the next steps read g^ as bits of the sum: the cut registers the DSP's whole
            // output, which yosys takes into the block as its output register (a register of
            // some of its bits stays in the fabric, and leaves the SB_MAC16 without a clock:
            // nextpnr-ice40 then does not time the path through it)
            ghat = (sum.name().to_string(), rb);
        }
    } else if rb > 0 {
        // g^ = G[i] + floor(dG[i]*r / 2^RB) = floor((G[i]*2^RB + dG[i]*r) / 2^RB): the entry and
        // the step's partial products in one carry-save sum, one carry chain at its end
        b.step(&format!("{title}: the partial products of dG[i]*r"));
        let sw = gb + rb;
        let mut terms = b.partial_products(
            "ghat_sum",
            &Piece::sig("log_word", ge, w.log_delta_bits),
            &Piece::sig("x", 0, rb),
            0,
            sw,
            false,
        );
        terms.push(vec![Piece::zeros(rb), Piece::sig("log_word", 0, ge)]);
        let p = b.sum_start(
            "ghat_sum",
            terms,
            sw,
            title,
            &format!("G[i]*2^{rb} + dG[i]*(x mod 2^-{}), exact", tg + 1),
        );
        let sum = b.resolve(p, title);
        let e = b.bits(&sum, sw - 1, rb);
        b.wire(
            "ghat",
            gb,
            Kind::Select,
            e,
            &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits),
        );
    } else {
        b.step(title);
        let e = b.operand("log_word", 0, ge, gb);
        b.wire(
            "ghat",
            gb,
            Kind::Select,
            e,
            &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits),
        );
    }

    let lf = f + w.log_frac_bits;
    let lb = f - 1 + gb;
    // (past the block RAM's limit: g^ from a flip-flop of the fabric's into the block's input
    // register, not from the carry chain's last LUT)
    b.fabric_register_step("g^ registered for the DSP");
    // g wider than a DSP's operands: g = g_hi*2^D + g_lo; x*g_lo on one DSP, then the bits of
    // L above D as x*g_hi (its few partial products) plus x*g_lo/2^D in one carry-save sum
    if f - 1 <= dsp && gb > dsp && gb - dsp <= SHIFT_ADD_BITS {
        b.step("-log2 c' = x*g(x): x*g_lo (multiplier); the partial products of x*g_hi");
        let lw = f - 1 + dsp;
        b.product(
            "log_frac_lo",
            &[Piece::sig("x", 0, f - 1)],
            &[Piece::sig(&ghat.0, ghat.1, dsp)],
            lw,
            &format!("x*ghat[{}:0], exact", dsp - 1),
        );
        // beside the DSP (they do not wait for it), x*g_hi's partial products
        let t = "-log2 c' = x*g(x)";
        let hw = lb - dsp;
        let mut terms = b.partial_products(
            "log_frac_hi",
            &Piece::sig("x", 0, f - 1),
            &Piece::sig(&ghat.0, ghat.1 + dsp, gb - dsp),
            0,
            hw,
            false,
        );
        b.product_delay(f - 1, dsp, lw, Delay::ZERO);
        terms.push(vec![Piece::sig("log_frac_lo", dsp, lw - dsp)]);
        let p = b.sum_start(
            "log_frac_hi",
            terms,
            hw,
            t,
            &format!(
                "x*ghat[{}:{dsp}] + x*ghat[{}:0]/2^{dsp}, exact",
                gb - 1,
                dsp - 1
            ),
        );
        let hi = b.resolve(p, t);
        let (hv, lv) = (b.r(&hi), b.bits("log_frac_lo", dsp - 1, 0));
        b.wire(
            "log_frac",
            lb,
            Kind::Select,
            ex!("{{{}, {}}}", hv, lv),
            &format!("UQ1.{lf}: L = x*g(x) = -log2 c', exact"),
        );
    } else {
        b.step("-log2 c' = x*g(x)");
        let what = format!("UQ1.{lf}: L = x*g(x) = -log2 c', exact");
        if b.instantiated_blocks() {
            // a MULT18X18D with its own registers where the cuts allow; e + L after a step
            // that registers L (the block's output is read only after its step)
            b.product(
                "log_frac",
                &[Piece::sig("x", 0, f - 1)],
                &[Piece::sig(&ghat.0, ghat.1, gb)],
                lb,
                &what,
            );
            b.ecp5_register_step("e + L: the product registered");
            ell(s, b);
            return false;
        }
        if ghat.0 != "ghat" {
            let e = b.bits(&ghat.0, ghat.1 + gb - 1, ghat.1);
            b.wire(
                "ghat",
                gb,
                Kind::Select,
                e,
                &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits),
            );
        }
        let (xs, gs) = ([Piece::sig("x", 0, f - 1)], [Piece::sig("ghat", 0, gb)]);
        b.mul(
            "log_frac",
            lb,
            (&xs, f - 1),
            (&gs, gb),
            &[],
            Delay::ZERO,
            &what,
        );
        // e + L in the next step: the block's output meets only its register
        return true;
    }
    ell(s, b);
    false
}

/// `ell = e + L`, in this step.
fn ell(s: &Shape, b: &mut Builder) {
    let Shape { w, f, .. } = *s;
    let lf = f + w.log_frac_bits;
    let eb2 = w.ell_bits();
    // L = x*g < 1 (x < 1/2, g^ < 2: each interpolation stays below the next entry, and the
    // last is g(1/2) = 2), so e + L is a concatenation: e above L's fraction bits
    let e = b.r("exponent");
    let lbits = if lf >= w.ell_frac_bits {
        b.bits("log_frac", lf - 1, lf - w.ell_frac_bits)
    } else {
        let v = b.bits("log_frac", lf - 1, 0);
        ex!("{{{}, {}}}", v, lit(w.ell_frac_bits - lf, 0))
    };
    b.wire(
        "ell",
        eb2,
        Kind::Select,
        ex!("{{{}, {}}}", e, lbits),
        &format!(
            "UQ{}.{}: e + L floored (truncation #1); L < 1",
            eb2 - w.ell_frac_bits,
            w.ell_frac_bits
        ),
    );
}

/// y = n*l (multiplier 7), truncated (#2) and saturated.
/// `ell_here`: `ell` is made in the first step here (after `log_frac` alone in its step).
fn times_n(s: &Shape, b: &mut Builder, ell_here: bool) {
    let Shape { w, nb, dsp, .. } = *s;
    // the first step of n*l, and `ell` in it where log2 left it
    let first_step = |b: &mut Builder, title: &str| {
        b.step(title);
        if ell_here {
            ell(s, b);
        }
    };
    let eb2 = w.ell_bits();
    // n*l from the bottom up, l in D-bit chunks: P_0 = n*l[D-1:0], and P_k = n*l[chunk k] +
    // floor(P_(k-1) / 2^D) on one DSP each (the add inside it); then n*l = {P_top, P_(top-1)
    // mod 2^D, .., P_0 mod 2^D}. A top chunk of a few bits is partial products instead.
    let yb = w.y_bits();
    let pb = nb + eb2;
    let chunks: Vec<(u32, u32)> = (0..eb2.div_ceil(dsp.min(eb2)))
        .map(|i| (i * dsp, (eb2 - i * dsp).min(dsp)))
        .collect();
    let chunked = nb <= dsp && chunks.len() > 1;
    let last = chunks.len() - 1;
    if chunked {
        for (k, &(lo, cw)) in chunks.iter().enumerate() {
            let width = nb + cw;
            let name = format!("y_part{k}");
            let what = format!("floor(n*l[{}:0] / 2^{lo}), exact", lo + cw - 1);
            if k == last && k > 0 && cw <= SHIFT_ADD_BITS {
                let t = "y = n*(-log2 c): the top bits of l";
                b.step(&format!("{t}: partial products"));
                let mut terms = b.partial_products(
                    &name,
                    &Piece::sig("n", 0, nb),
                    &Piece::sig("ell", lo, cw),
                    0,
                    width,
                    false,
                );
                let below = format!("y_part{}", k - 1);
                let bw = nb + chunks[k - 1].1;
                terms.push(vec![Piece::sig(&below, dsp, bw - dsp)]);
                let p = b.sum_start(&name, terms, width, t, &what);
                b.resolve(p, t);
            } else {
                // one DSP each, the chunk below added inside it (on the ECP5, after it)
                let t = format!("y = n*(-log2 c) (multiplier 7): n*l[{}:{lo}]", lo + cw - 1);
                match k {
                    0 => first_step(b, &format!("{t} (one DSP)")),
                    _ => b.step(&format!("{t} (one DSP)")),
                }
                let (nn, l) = ([Piece::sig("n", 0, nb)], [Piece::sig("ell", lo, cw)]);
                if k == 0 {
                    b.product(&name, &nn, &l, width, &format!("{what} (one DSP)"));
                } else {
                    let below =
                        Piece::sig(&format!("y_part{}", k - 1), dsp, nb + chunks[k - 1].1 - dsp);
                    b.multiply_add(
                        &name,
                        &nn,
                        &l,
                        &[below],
                        width,
                        &t,
                        &format!("{what}: n*l[{}:{lo}] plus the chunk below", lo + cw - 1),
                    );
                }
            }
        }
    } else {
        first_step(b, "y = n*(-log2 c) (multiplier 7)");
        let (ns, ls) = ([Piece::sig("n", 0, nb)], [Piece::sig("ell", 0, eb2)]);
        b.mul(
            "y_full",
            pb,
            (&ns, nb),
            (&ls, eb2),
            &[],
            Delay::ZERO,
            &format!(
                "UQ{}.{}: n*(-log2 c), exact",
                pb - w.ell_frac_bits,
                w.ell_frac_bits
            ),
        );
    }

    b.step("y truncated; its saturation");
    if chunked {
        // each P_k's low D bits, read here (after the last one's step: the block's output
        // meets only its register)
        let mut low_words: Vec<Expr> = Vec::new();
        for k in (0..chunks.len()).rev() {
            let name = format!("y_part{k}");
            low_words.push(if k == last {
                b.r(&name)
            } else {
                b.bits(&name, dsp - 1, 0)
            });
        }
        b.wire(
            "y_full",
            pb,
            Kind::Select,
            ex!("{{{}}}", Expr::join(&low_words, ", ")),
            &format!(
                "UQ{}.{}: n*(-log2 c), exact",
                pb - w.ell_frac_bits,
                w.ell_frac_bits
            ),
        );
    }
    let drop = w.ell_frac_bits - w.y_frac_bits;
    let top = b.bits("y_full", pb - 1, drop);
    let ytw = pb - drop;
    b.wire(
        "y_trunc",
        ytw,
        Kind::Select,
        top,
        &format!("UQ{}.{}: truncation #2", ytw - w.y_frac_bits, w.y_frac_bits),
    );
    // y >= (W + 2)*2^WY on its integer bits alone (the saturation value has no fraction):
    // some high bit set, or the low ones at least W + 2
    let sat_int = (w.out_bits + 2) as u128;
    let yiw = ytw - w.y_frac_bits;
    let mut flags = vec!["y_zero_power"];
    if sat_int < 1u128 << yiw {
        let k = bit_length(sat_int);
        let ge = b.at_least("y_trunc", w.y_frac_bits + k - 1, w.y_frac_bits, sat_int);
        b.wire(
            "y_over_low",
            1,
            Kind::Logic,
            ge,
            &format!("floor(y)'s low {k} bits reach {sat_int}"),
        );
        flags.push("y_over_low");
        if yiw > k {
            let bits = b.bit_list("y_trunc", ytw - 1, w.y_frac_bits + k);
            let terms = b.or_terms(
                "y_over_high",
                bits,
                LUT_INPUTS,
                "floor(y) above its low bits",
            );
            b.wire(
                "y_over_high",
                1,
                Kind::Logic,
                Expr::join(&terms, " | "),
                &format!("floor(y) has a bit set above its low {k}"),
            );
            flags.push("y_over_high");
        }
    } // else y_trunc cannot reach the saturation value
    b.delay(2.0 * LUT_DELAY);
    b.step("y saturated");
    let flags: Vec<Expr> = flags.iter().map(|f| b.r(f)).collect();
    b.wire(
        "y_saturate",
        1,
        Kind::Logic,
        Expr::join(&flags, " || "),
        &format!("y reaches {} (or c = 0 with n >= 1)", w.out_bits + 2),
    );
    let (sat, yt2) = (b.r("y_saturate"), b.operand("y_trunc", 0, ytw, yb));
    b.wire(
        "y",
        yb,
        Kind::Logic,
        Builder::select_const(&sat, w.y_sat(), yb, &yt2),
        &format!(
            "UQ{}.{}: y, saturated at {} (every output is 0 from there on)",
            w.y_int_bits,
            w.y_frac_bits,
            w.out_bits + 2
        ),
    );
    b.delay(LUT_DELAY);
}
