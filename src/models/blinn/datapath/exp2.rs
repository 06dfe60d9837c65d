//! The end of Blinn's datapath: exp2 of the scaled log by its table and interpolation, then
//! the shift by the integer part and the rounding.

use super::*;

/// 2^-frac(y) by the exp2 table and linear interpolation. Returns the sum whose bits are its
/// complement when the interpolation took the DSP's multiply-add (complemented in the shift's LUTs).
pub(super) fn exp2(s: &Shape, b: &mut Builder) -> Option<Sig> {
    let Shape {
        w,
        t,
        re,
        exp2_dsp,
        exp2_pad,
        et,
        ..
    } = *s;
    let te = w.exp2_index_bits;
    let ji = b.bits("y", w.y_frac_bits - 1, re);
    b.wire(
        "exp2_index",
        te,
        Kind::Select,
        ji,
        "j: frac(y) to the table's resolution",
    );
    b.ecp5_register_step("exp2 table read: the address at the block RAM's address register");
    b.step(&format!(
        "exp2 table read: 2^-f at the top {te} bits of frac(y)"
    ));
    b.rom_read_registered("exp2_word", et, "exp2_index");
    b.ecp5_register_step("exp2 table read: the word at the multiplier's input registers");
    let implied = t.exp2_one_implied(w);
    if implied && exp2_dsp {
        // the table holds ~E: its integer bit complemented as well
        let ji = b.r("exp2_index");
        b.wire(
            "exp2_not_one",
            1,
            Kind::Logic,
            ex!("{} != {}", ji, lit(te, 0)),
            "~E's integer bit: 2^-f = 1.0 at j = 0 only",
        );
    } else if implied {
        let ji = b.r("exp2_index");
        b.wire(
            "exp2_one",
            1,
            Kind::Logic,
            ex!("{} == {}", ji, lit(te, 0)),
            "E's integer bit: 2^-f = 1.0 at j = 0 only",
        );
    }
    b.delay(LUT_DELAY * te.div_ceil(2) as f64);

    let we = w.exp2_frac_bits;
    let ee = w.exp2_entry_bits;
    let es = ee - implied as u32; // E's bits in the word
                                  // E's bits as read: complemented (~E) where the table holds them so
    let mut e_word = vec![Piece::sig("exp2_word", 0, es)];
    if implied {
        e_word.push(Piece::sig(
            if exp2_dsp { "exp2_not_one" } else { "exp2_one" },
            0,
            1,
        ));
    }
    let title = "2^-frac(y) by linear interpolation";
    let sw = ee + re;
    // set when E[j] - floor(dE[j]*r / 2^RE) is the complement of bits of exp2_sum
    let mut complemented = None;
    if exp2_dsp {
        // E[j]*2^RE + 2^RE - 1 - s = ~(s + ~(E[j]*2^RE + 2^RE - 1)) mod 2^sw for the step
        // s = dE[j]*r, and ~(E[j]*2^RE + 2^RE - 1) = {~E[j], RE zeros}: one DSP multiply-add,
        // the complemented entry its addend, read as the table stores it (the block RAM feeds
        // the block directly); the result's complement is taken in the LUTs of the shift that
        // follows (the DSP's output meets only a flip-flop)
        b.step(&format!("{title}: dE[j]*r + ~E[j]*2^{re} (multiplier)"));
        let mut addend = vec![Piece::zeros(re)];
        addend.extend(e_word.iter().cloned());
        let (de, r) = (
            Piece::sig("exp2_word", es, w.exp2_delta_bits),
            Piece::sig("y", 0, re),
        );
        let (a, r) = pad_operands(de, r, "exp2_word", exp2_pad);
        let what = format!("~(E[j]*2^{re} + 2^{re} - 1 - dE[j]*(frac(y) mod 2^-{te})), exact");
        complemented = Some(b.multiply_add("exp2_sum", &a, &r, &addend, sw, title, &what));
    } else if re > 0 {
        // E[j] - floor(s / 2^RE) = floor((E[j]*2^RE + 2^RE - 1 - s) / 2^RE) for the step
        // s = dE[j]*r, and -s = the sum of its complemented partial products plus their count:
        // one carry-save sum, one carry chain at its end
        b.step(&format!(
            "{title}: the partial products of dE[j]*r, complemented"
        ));
        let mut terms = b.partial_products(
            "exp2_sum",
            &Piece::sig("exp2_word", es, w.exp2_delta_bits),
            &Piece::sig("y", 0, re),
            0,
            sw,
            true,
        );
        let k = terms.len() as u128;
        let mut et = vec![Piece::zeros(re)];
        et.extend(e_word);
        terms.push(et);
        terms.push(vec![Piece::Const {
            value: (((1u128 << re) - 1) + k) & mask(sw),
            width: sw,
        }]);
        let p = b.sum_start(
            "exp2_sum",
            terms,
            sw,
            title,
            &format!("E[j]*2^{re} + 2^{re} - 1 - dE[j]*(frac(y) mod 2^-{te}), exact"),
        );
        let sum = b.resolve(p, title);
        let e = b.bits(&sum, sw - 1, re);
        b.wire(
            "exp2_frac",
            ee,
            Kind::Select,
            e,
            &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"),
        );
    } else {
        b.step(title);
        let e = b.pieces(&e_word);
        b.wire(
            "exp2_frac",
            ee,
            Kind::Select,
            e,
            &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"),
        );
    }

    complemented
}

/// The shift by the integer part of y (truncation #3), the colour multipliers and the rounding.
pub(super) fn shift_and_round(s: &Shape, b: &mut Builder, mut complemented: Option<Sig>) {
    let Shape { w, fi, bb, re, .. } = *s;
    let (we, ee) = (w.exp2_frac_bits, w.exp2_entry_bits);
    let sw = ee + re;
    // the shift by the integer part of y, one of its bits a step from the top: a 2:1 mux, one
    // LUT level (a 4:1 mux is two, after a select bit that fans out over the word: yosys
    // 0.70's netlist of blinn then stopped at 106 MHz on the UP5K)
    let yib = w.y_int_bits;
    let mut src = "exp2_frac".to_string();
    let mut hi = yib;
    while hi > 0 {
        let lo = hi - 1;
        b.step(&format!(
            "shift by the integer part of y: its bit {lo}{}",
            if lo == 0 { " (truncation #3)" } else { "" }
        ));
        if let Some(sum) = complemented.take() {
            let e = b.bits(&sum, sw - 1, re);
            b.wire(
                "exp2_frac",
                ee,
                Kind::Logic,
                ex!("~{}", e),
                &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"),
            );
        }
        let (sv, yi) = (
            b.r(&src),
            b.bits("y", w.y_frac_bits + hi - 1, w.y_frac_bits + lo),
        );
        let name = if lo == 0 {
            "power".to_string()
        } else {
            format!("power_shift{lo}")
        };
        let comment = if lo == 0 {
            format!("UQ1.{we}: c^n before rounding")
        } else {
            format!("2^-frac(y) shifted by floor(y)'s bits above {lo}")
        };
        // a 2:1 mux as an AND-OR of the shifted words ([`Builder::select`])
        let terms: Vec<Expr> = (0..1u32 << (hi - lo))
            .filter(|v| v << lo < ee)
            .map(|v| {
                let shifted = if v == 0 {
                    sv.clone()
                } else {
                    ex!("({} >> {})", sv, v << lo)
                };
                Builder::gate(
                    &ex!("({} == {})", yi, lit(hi - lo, v as u128)),
                    &shifted,
                    ee,
                )
            })
            .collect();
        b.wire(
            &name,
            ee,
            Kind::Logic,
            Expr::join(&terms, "\n    | "),
            &comment,
        );
        b.delay(LUT_DELAY);
        src = name;
        hi = lo;
    }
    let wc = w.color_frac_bits;
    // c^n's colour field once per colour product's block (iCE40)
    b.colour_copies("power", we - wc, wc, "c^n", true);

    b.step("colour multipliers (14-16)");
    b.colour_products("power", we - wc, wc, "c^n");
    b.product_delay(wc + 1, bb, wc + bb, Delay::ZERO);
    // a step of its own, from a copy of c^n of its own: the register that feeds the colour
    // multipliers sits by the DSP column
    b.round_intensity("power", we, fi, wc, "c^n");
}
