//! The schlick datapath on the builder: clamp, the denominator, normalise, the reciprocal by
//! table and interpolation, the product, the shift back, round.

use super::*;
use crate::bits::{lit, mask};
use crate::datapath::{ex, pad_operands, Delay, Kind, Piece, LUT_DELAY};

/// Step 1 clamps c and forms 1 − c; the denominator is one multiply-add; its leading zeros
/// take two LUT steps and its normalising shift one mux level a step; then the table read, the
/// interpolation and the product on DSP blocks, the shift back one mux level a step, the
/// select of n = 0 and the rounding.
pub(super) fn datapath(cfg: &Config, w: &SchlickWidths, t: &ReciprocalTable, b: &mut Builder) {
    let (f, nb, bb, fi) = (cfg.f(), cfg.n_bits(), cfg.b(), cfg.fi());
    let (dw, k, j, z, u) = (
        w.den_bits,
        w.index_bits,
        w.fraction_bits,
        w.recip_frac_bits,
        w.entry_frac_bits,
    );
    let (wq, wc, lb) = (w.quotient_frac_bits, w.colour_frac_bits, w.shift_bits);
    // the interpolation on one DSP block, its post-adder adding B, where the operands fit (on
    // the iCE40 the table word carries them at the block's width)
    let (_, pad) = b.interpolation_on_block(w.slope_bits(), j, u);
    let rt = b.table(t.table(w, pad));

    b.step("the operand of 1 - c = 1 - min(cos, 1); n = 0 picks S = 1 at the end");
    // cos_g >= 1.0 exactly when its integer bit is set: a mux, no comparator
    // 1 − c = ~c + 1 over F + 1 bits with c's integer bit 0, and 0 (all ones + 1) at c = 1
    let (top, low) = (b.bits("cos_g", f, f), b.bits("cos_g", f - 1, 0));
    let comp = Builder::select_const(&top, mask(f + 1), f + 1, &ex!("{{1'b0, ~{}}}", low));
    b.wire(
        "cos_comp",
        f + 1,
        Kind::Logic,
        comp,
        &format!(
            "2^{} - 1 - c over {} bits (all ones at c = 1): 1 - c = this + 2^-{f}",
            f + 1,
            f + 1
        ),
    );
    let n = b.sig("n");
    let nv = b.r(&n);
    b.wire(
        "n_zero",
        1,
        Kind::Logic,
        ex!("{} == {}", nv, lit(nb, 0)),
        "n = 0: S = 1 (cos^0), the limit at c = 0 too",
    );
    b.delay(LUT_DELAY);
    let title = "1 - c";
    b.step(&format!("{title}; clamp c = min(cos, 1)"));
    // (the clamp a step after the operand of 1 - c, from the next register of cos_g: its
    // integer bit, which selects both, then drives half as many LUTs from each flip-flop, and
    // no synthesis tool can share c's LUTs with ~c's, whose flip-flops would then take them
    // over a route of their own: schlick held at 117.1 MHz on the UP5K)
    let (top, g) = (b.bits("cos_g", f, f), b.r("cos_g"));
    let cos = b.wire(
        "cos_clamped",
        f + 1,
        Kind::Logic,
        Builder::select_const(&top, 1u128 << f, f + 1, &g),
        &format!("UQ1.{f}: c"),
    );
    let p = b.add_start(
        "one_minus_cos",
        &[Piece::sig("cos_comp", 0, f + 1)],
        &[],
        true,
        f + 1,
        &format!("UQ1.{f}: 1 - c, exact"),
    );
    let one_minus_cos = b.resolve(p, title);

    // 2n·(1 − c) + c = 2·(n·(1 − c) + ⌊c/2⌋) + c[0]: one multiply-add (on the iCE40 the
    // SB_MAC16's post-adder, its register the block's; on the ECP5 a MULT18X18D, then a carry
    // chain), the doubling and c[0] by wiring
    // (past the block RAM's limit: 1 - c from a flip-flop of the fabric's into the block)
    b.fabric_register_step("1 - c registered for the DSP");
    b.step("the denominator den = 2n*(1 - c) + c, exact: half of it, n*(1 - c) + floor(c/2)");
    let comment = format!(
        "UQ{}.{}: n*(1 - c) + floor(c/2), exact: den = 2*den_half + c[0]",
        nb + 1,
        f
    );
    let half = b.multiply_add(
        "den_half",
        &[n.all()],
        &[one_minus_cos.all()],
        &[cos.part(1, f)],
        dw - 1,
        "the denominator",
        &comment,
    );

    // L = den's leading zeros over its bits [N+F+1:F] (den >= 2^F for n >= 1)
    b.step("normalise: den's leading zeros, per group of 4 bits above 2^F");
    let (hv, c0) = (b.r(&half), b.bits(&cos, 0, 0));
    b.wire(
        "den",
        dw,
        Kind::Select,
        ex!("{{{}, {}}}", hv, c0),
        &format!(
            "UQ{}.{f}: den = 2n*(1 - c) + c = {{den_half, c[0]}}",
            nb + 2
        ),
    );
    b.leading_zeros(
        "den_lead",
        "den",
        dw,
        nb + 2,
        "den_zeros",
        lb,
        "den",
        "normalise: L = den's leading zeros above 2^F",
        &format!(
            "L in 0..{}: den = u*2^({} - L), u in [1, 2) ({} at n = 0, where den < 2^F)",
            nb + 1,
            dw - 1,
            nb + 2
        ),
    );
    b.delay(2.0 * LUT_DELAY);

    // u = den·2^L, one bit of L a step from the top (a 2:1 mux level each); the last also
    // takes the table's index and the fraction, complemented
    let kj = k + j;
    let mut src = "den".to_string();
    for s in (0..lb).rev() {
        let last = s == 0;
        let name = if last {
            "den_norm".to_string()
        } else {
            format!("den_norm_shift{s}")
        };
        b.step(&if last {
            "normalise: u = den*2^L, the table's index and fraction".to_string()
        } else {
            format!("normalise: den shifted by L's bit {s}")
        });
        let what = if last {
            format!("UQ1.{}: u = den*2^L in [1, 2) (n >= 1)", dw - 1)
        } else {
            format!("den*2^(L's bits from {s} up)")
        };
        b.shift_left_level(&name, &src, "den_zeros", s, dw, &what);
        if last {
            // u's next K + J fraction bits (zeros below u's last bit)
            let field = if dw > kj {
                b.bits("den_norm", dw - 2, dw - 1 - kj)
            } else {
                let v = b.bits("den_norm", dw - 2, 0);
                ex!("{{{}, {}}}", v, lit(kj - (dw - 1), 0))
            };
            b.wire(
                "den_field",
                kj,
                Kind::Select,
                field,
                &format!("u's {kj} fraction bits from the top: i, then t"),
            );
            let idx = b.bits("den_field", kj - 1, j);
            b.wire(
                "recip_index",
                k,
                Kind::Select,
                idx,
                &format!("i: u's top {k} fraction bits, the table's interval"),
            );
            let frac = b.bits("den_field", j - 1, 0);
            let t = ex!("~{}", frac);
            b.wire("recip_frac", j, Kind::Logic, t, &format!("~t: the next {j} bits of u, complemented (the line is read from the interval's end)"));
        }
        b.delay(LUT_DELAY);
        src = name;
    }

    b.ecp5_register_step("reciprocal table read: the address at the block RAM's address register");
    b.step(&format!(
        "reciprocal table read: {{D, B}} of interval i (2^{k} words)"
    ));
    b.rom_read_registered("recip_word", rt, "recip_index");
    b.delay(LUT_DELAY * k.div_ceil(2) as f64);
    b.ecp5_register_step("reciprocal table read: the word at the multiplier's input registers");

    // z = ⌊(B·2^J + D·~t) / 2^(U+J−Z)⌋: one multiply-add, the entry its addend
    let title = "r^ by linear interpolation";
    b.step(&format!("{title}: D*~t + B*2^{j}"));
    let sw = w.sum_bits();
    let (d, tf, bw) = (
        Piece::sig("recip_word", u, w.slope_bits()),
        Piece::sig("recip_frac", 0, j),
        Piece::sig("recip_word", 0, u),
    );
    let (d, tf) = pad_operands(d, tf, "recip_word", pad);
    let comment = format!(
        "B*2^{j} + D*~t, exact; z = bits [{}:{}]: r^ = 1 + z/2^{z} ~ 2/u",
        sw - 1,
        sw - z
    );
    let sum = b.multiply_add(
        "recip_sum",
        &d,
        &tf,
        &[Piece::zeros(j), bw],
        sw,
        title,
        &comment,
    );
    let recip = if b.instantiated_blocks() {
        let e = b.bits(&sum, sw - 1, sw - z);
        b.wire(
            "recip",
            z,
            Kind::Select,
            e,
            &format!("UQ0.{z}: z, r^ = 1 + z/2^{z} (rounded to nearest)"),
        );
        Piece::sig("recip", 0, z)
    } else {
        // read as bits of the sum: the cut registers the block's whole output (the DSP's
        // own output register)
        Piece::sig(sum.name(), sw - z, z)
    };

    // P = c·r̂·2^Z = c·z + c·2^Z: one multiply-add, exact
    let pw = f + 1 + z;
    // (past the block RAM's limit: r^ from a flip-flop of the fabric's into the block's input
    // register, not from the carry chain's last LUT)
    b.fabric_register_step("r^ registered for the DSP");
    b.step("the product P = c*r^ = c*z + c*2^Z");
    let comment = format!("UQ2.{}: c*r^, exact", f + z);
    let product = b.multiply_add(
        "quot_prod",
        &[cos.all()],
        &[recip],
        &[Piece::zeros(z), cos.all()],
        pw,
        "the product",
        &comment,
    );

    // q = ⌊P·2^L / 2^(N+F)⌋: ⌊P/2^(F−1)⌋ (W bits) shifted left by L, one bit a step, its bits
    // from N+1 up
    let xw = wq + nb + 1;
    let mut src = "quot_floor".to_string();
    for s in (0..lb).rev() {
        let last = s == 0;
        let name = if last {
            "quot_shifted".to_string()
        } else {
            format!("quot_shift{s}")
        };
        b.step(&format!(
            "shift back: floor(P/2^{})*2^L by L's bit {s}",
            f - 1
        ));
        if s + 1 == lb {
            let e = b.bits(&product, f + z, f - 1);
            b.wire(
                "quot_floor",
                wq,
                Kind::Select,
                e,
                &format!(
                    "floor(P/2^{}), {wq} bits: c*r^*2^(Z - F + 1) floored",
                    f - 1
                ),
            );
        }
        let what = if last {
            format!("floor(P/2^{})*2^L: q = bits [{}:{}]", f - 1, xw - 1, nb + 1)
        } else {
            format!("floor(P/2^{})*2^(L's bits from {s} up)", f - 1)
        };
        b.shift_left_level(&name, &src, "den_zeros", s, xw, &what);
        b.delay(LUT_DELAY);
        src = name;
    }

    b.step("S = 1 at n = 0");
    let (nz, q) = (b.r("n_zero"), b.bits("quot_shifted", xw - 1, nb + 1));
    let quotient = b.wire(
        "quotient",
        wq + 1,
        Kind::Logic,
        Builder::select_const(&nz, 1u128 << wq, wq + 1, &ex!("{{1'b0, {}}}", q)),
        &format!("UQ1.{wq}: c*r^/2^(e+1) floored, 1.0 at n = 0"),
    );
    b.delay(LUT_DELAY);

    // the colours take q floored to Wc bits (the module doc): one block each, its product
    // alone in its step, read after its register
    b.step("colour multipliers (14-16)");
    b.colour_products(quotient.name(), wq - wc, wc, "S");
    b.product_delay(wc + 1, bb, wc + bb, Delay::ZERO);

    b.round_intensity("quotient", wq, fi, wc, "S");
}
