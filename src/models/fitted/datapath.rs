//! The fitted unit on the datapath builder: the bracket `1 - a_n*(1 - cos)` and its squarings,
//! each squaring bypassed where `m_n` asks fewer (the error budget in `super`).

use super::*;

/// The fitted datapath: ROM read and 1 − cos; a_n·(1 − cos); the bracket and the key block;
/// M squarings, each bypassed when j > m_n; colour multipliers and the roundings.
pub fn datapath(cfg: &Config, fit: &Fit, w: &FittedWidths, b: &mut Builder) {
    let (f, fi, bb, ka, wf) = (cfg.f(), cfg.fi(), cfg.b(), cfg.kf(), w.frac_bits);
    let cb = f + 1;
    let t = b.table(table(fit, w));

    // on the ECP5 the ROM is read a step later, from n's register, into block RAM with its
    // address and output registers (a read from the ports has no register before it)
    let ecp5 = b.instantiated_blocks();
    b.step(if ecp5 {
        "c = min(cos, 1)"
    } else {
        "per-n fit ROM read {m_n, a_n}; c = min(cos, 1)"
    });
    if !ecp5 {
        b.rom_read("fit", t, "n");
    }
    let (top, g) = (b.bits("cos_g", f, f), b.r("cos_g"));
    // cos_g >= 1.0 exactly when its integer bit is set: a mux, no comparator; complemented
    // here, in the mux's LUT, so that the add below takes it straight into its carry chain
    let not_one = Expr::constant(lit(cb, mask(cb) & !(1u128 << f)));
    b.wire(
        "cos_clamped_n",
        cb,
        Kind::Logic,
        Builder::select(&top, &not_one, &ex!("~{}", g), cb),
        &format!("~c, c = min(cos, 1) in UQ1.{f}"),
    );
    b.delay(LUT_DELAY * if ecp5 { 1 } else { cfg.n_bits().div_ceil(2) } as f64);

    // 1 - c = ~c + 2^F + 1 mod 2^(F+1) (c <= 1): a carry-select add of a constant
    let title = "1 - c (adder 6)";
    b.step(&if ecp5 {
        format!("{title}; per-n fit ROM read {{m_n, a_n}}")
    } else {
        title.to_string()
    });
    if ecp5 {
        b.rom_read_registered("fit", t, "n");
    }
    let p = b.add_start(
        "one_minus_cos",
        &[Piece::sig("cos_clamped_n", 0, cb)],
        &[Piece::Const {
            value: (1u128 << f) + 1,
            width: cb,
        }],
        false,
        cb,
        &format!("UQ1.{f}: 1 - c, exact"),
    );
    b.resolve(p, title);
    b.ecp5_register_step("per-n fit ROM read: the word at the multiplier's input registers");

    // a_n wider than a DSP's operands: a_n = a_hi*2^D + a_lo; a_lo*(1 - cos) on one DSP, then
    // the bits of P above D as a_hi*(1 - cos) (its few partial products) plus
    // a_lo*(1 - cos)/2^D in one carry-save sum: exact
    let dsp = b.dsp_bits();
    let pb = w.product_bits;
    // ~P, the add's first operand: a wire of the product's step, or (a product held in an
    // ECP5 block's output register, readable only after its step) complemented in the add
    let mut complement = Piece::sig("deviation_n", 0, pb);
    if w.a_bits > dsp && cb <= dsp {
        let t = "deviation a_n*(1 - cos) (multiplier 7)";
        b.step(&format!(
            "{t}: a_lo*(1 - cos) (one DSP); the partial products of a_hi*(1 - cos)"
        ));
        let lw = dsp + cb;
        b.product(
            "deviation_lo",
            &[Piece::sig("fit", 0, dsp)],
            &[Piece::sig("one_minus_cos", 0, cb)],
            lw,
            &format!("a_n[{}:0]*(1 - cos), exact", dsp - 1),
        );
        let hw = pb - dsp;
        let mut terms = b.partial_products(
            "deviation_hi",
            &Piece::sig("one_minus_cos", 0, cb),
            &Piece::sig("fit", dsp, w.a_bits - dsp),
            0,
            hw,
            false,
        );
        b.product_delay(dsp, cb, lw, Delay::ZERO);
        // (the block's output read by the carry-save layers from a flip-flop of its own: a
        // MULT18X18D's 1.5-1.8 ns route into two LUT levels held fitted at 246 MHz on the ECP5)
        b.fabric_register_step(&format!("{t}: a_lo*(1 - cos) registered in the fabric"));
        terms.push(vec![Piece::sig("deviation_lo", dsp, lw - dsp)]);
        let p = b.sum_start(
            "deviation_hi",
            terms,
            hw,
            t,
            &format!(
                "a_n[{}:{dsp}]*(1 - cos) + a_n[{}:0]*(1 - cos)/2^{dsp}, exact",
                w.a_bits - 1,
                dsp - 1
            ),
        );
        let hi = b.resolve(p, t);
        let (hv, lv) = (b.r(&hi), b.bits("deviation_lo", dsp - 1, 0));
        // complemented here, in the LUTs that pick the sum's chunks, so that the add below
        // takes it straight into its carry chain
        b.wire(
            "deviation_n",
            pb,
            Kind::Logic,
            ex!("~{{{}, {}}}", hv, lv),
            &format!(
                "~P, P = a_n*(1 - cos) in UQ{}.{}, exact",
                pb - ka - f,
                ka + f
            ),
        );
    } else {
        b.step("deviation a_n*(1 - cos) (multiplier 7)");
        b.product(
            "deviation",
            &[Piece::sig("fit", 0, w.a_bits)],
            &[Piece::sig("one_minus_cos", 0, cb)],
            pb,
            &format!("UQ{}.{}: a_n*(1 - cos), exact", pb - ka - f, ka + f),
        );
        if b.is_block_output_here("deviation") {
            complement = Piece::not("deviation", 0, pb);
        } else {
            let d = b.r("deviation");
            b.wire(
                "deviation_n",
                pb,
                Kind::Logic,
                ex!("~{}", d),
                &format!(
                    "~P, P = a_n*(1 - cos) in UQ{}.{}, exact",
                    pb - ka - f,
                    ka + f
                ),
            );
        }
    }

    // (with route registers, ~P once more in a flip-flop: from the pick that makes it, at the
    // middle of the die, a 3.6-4.9 ns route into the add's chains held fitted at 112-117 MHz on
    // the UP5K)
    b.route_register_step("bracket: ~P registered again, by the add");
    // 2^(KA+F) - P = ~P + 2^(KA+F) + 1 mod 2^DB (P zero-extended): a carry-select add
    let title = "bracket = 1 - deviation (adder 9); its sign is the cut-off (comparator 12)";
    b.step(title);
    let db = w.diff_bits;
    let p = b.add_start(
        "diff",
        &[
            complement,
            Piece::Const {
                value: mask(db - pb),
                width: db - pb,
            },
        ],
        &[Piece::Const {
            value: (1u128 << (ka + f)) + 1,
            width: db,
        }],
        false,
        db,
        &format!(
            "S{}.{}: 1 - a_n*(1 - cos), exact (two's complement)",
            db - ka - f,
            ka + f
        ),
    );
    b.resolve(p, title);

    b.step("key block (13) and truncation #1");
    let sign = b.bits("diff", db - 1, db - 1);
    b.wire(
        "done",
        1,
        Kind::Select,
        sign.clone(),
        "the bracket is negative: beyond the highlight",
    );
    let x0 = if ka + f >= wf {
        b.bits("diff", ka + f, ka + f - wf)
    } else {
        let d = b.bits("diff", ka + f, 0);
        ex!("{{{}, {}}}", d, lit(wf - ka - f, 0))
    };
    b.wire(
        "power0",
        wf + 1,
        Kind::Logic,
        Builder::gate(&ex!("~{}", sign), &x0, wf + 1),
        &format!("UQ1.{wf}: the bracket in [0, 1], floored; 0 beyond the cut-off"),
    );
    b.delay(LUT_DELAY);

    // a bracket wider than a DSP's operands: x = hi*2^r + lo with hi of D bits, and
    // x^2 = 2^r*(hi^2*2^r + T) + (lo^2 mod 2^r), T = 2*hi*lo + floor(lo^2/2^r) by partial
    // products and a table of lo^2 in one carry-save sum, Z = hi^2 + floor(T/2^r) =
    // floor(x^2/2^2r) on one DSP (the add inside it); then floor(x^2/2^W) = floor(Z/2^(W-2r)),
    // all floors exact (W >= 2r: W <= 2D - 2)
    let r = (wf + 1).saturating_sub(dsp);
    let sq_split = r > 0 && wf >= 2 * r && r <= MAX_SQUARER_SPLIT;
    let m_max = cfg.max_squarings();
    for j in 1..=m_max {
        squaring(w, b, j, m_max, r, sq_split);
    }

    let s = format!("power{m_max}");
    let wc = w.color_frac_bits;
    b.colour_copies(&s, wf - wc, wc, "S", false);
    b.step("colour multipliers (14-16)");
    b.colour_products(&s, wf - wc, wc, "S");
    b.product_delay(wc + 1, bb, wc + bb, Delay::ZERO);
    // round half up on the bits that matter: (S[W:W-FI-1] + 1) >> 1 = floor((S + 2^-(FI+1)) / 2^-FI)
    let title = "the intensity rounded half up";
    b.step(&format!("{title}: chunk sums"));
    let p = b.add_start_short(
        "intensity_sum",
        &[Piece::sig(&s, wf - fi - 1, fi + 2)],
        &[],
        true,
        fi + 2,
        &format!("UQ1.{}: S to 2^-{} plus one ulp = S + 2^-{} (round half up; S < 1 when it is not a whole 1.0)", fi + 1, fi + 1, fi + 1),
    );
    // (on the ECP5, the colours' rounding half after their products)
    b.colour_rounding(wc, "S");
    let sum = b.resolve(p, title);
    b.colour_results(wc, "S");
    let e = b.bits(&sum, fi + 1, 1);
    b.wire(
        "intensity",
        fi + 1,
        Kind::Select,
        e,
        &format!("UQ1.{fi}: S rounded half up"),
    );
}

/// Squaring `j` of `m_max` (squarer 11): power_j = power_(j-1)^2 floored, or power_(j-1) when
/// m_n < j. `r`: the low bits split off a bracket wider than a DSP's operands (`sq_split`: the
/// square is then hi^2*2^2r + T*2^r + lo^2 with T by partial products and a table, above).
pub(super) fn squaring(
    w: &FittedWidths,
    b: &mut Builder,
    j: u32,
    m_max: u32,
    r: u32,
    sq_split: bool,
) {
    let (wf, dsp) = (w.frac_bits, b.dsp_bits());
    let prev = format!("power{}", j - 1);
    let hi_bits = if sq_split {
        let t = format!("squaring {j} of {m_max}: T = 2*hi*lo + lo^2/2^{r}");
        b.step(&format!(
            "{t}: the partial products of 2*hi*lo; lo^2 by a table"
        ));
        let tw = dsp + r + 2;
        let (ll, tn) = (format!("square{j}_ll"), format!("square{j}_t"));
        let terms = if r > LUT_INPUTS {
            // lo = t*2^(r-1) + l' (t its top bit): lo^2 = t*2^(2r-2) + t*l'*2^r + l'^2, so
            // T = 2*hi*l' + t*(hi*2^r + l') + t*2^(r-2) + floor(l'^2/2^r), every floor exact
            // (the first two terms of lo^2 are multiples of 2^r) and l'^2 < 2^(2r-2) leaves
            // bit r-2 of its floor clear for t: a table of r-1 bits, one LUT level, not two
            let l = r - 1;
            b.square_table(
                &ll,
                &prev,
                0,
                l,
                &format!("l'^2 by table, power{} = hi*2^{r} + t*2^{l} + l'", j - 1),
            );
            let mut terms = b.partial_products(
                &tn,
                &Piece::sig(&prev, r, dsp),
                &Piece::sig(&prev, 0, l),
                1,
                tw,
                false,
            );
            let t_bit = b.bits(&prev, l, l);
            // (its r + dsp significant bits a wire, the zeros above it pieces the sum sees)
            let hl = b.pieces(&[
                Piece::sig(&prev, 0, l),
                Piece::zeros(1),
                Piece::sig(&prev, r, dsp),
            ]);
            let top = format!("{tn}_top");
            b.wire(
                &top,
                dsp + r,
                Kind::Logic,
                Builder::gate(&t_bit, &hl, dsp + r),
                "t*(hi*2^r + l'): the partial product of lo's top bit",
            );
            terms.push(vec![
                Piece::sig(&top, 0, dsp + r),
                Piece::zeros(tw - dsp - r),
            ]);
            terms.push(vec![Piece::sig(&ll, r, r - 2), Piece::sig(&prev, l, 1)]);
            terms
        } else {
            b.square_table(
                &ll,
                &prev,
                0,
                r,
                &format!("lo^2 by table, power{} = hi*2^{r} + lo", j - 1),
            );
            let mut terms = b.partial_products(
                &tn,
                &Piece::sig(&prev, r, dsp),
                &Piece::sig(&prev, 0, r),
                1,
                tw,
                false,
            );
            terms.push(vec![Piece::sig(&ll, r, r)]);
            terms
        };
        let p = b.sum_start(&tn, terms, tw, &t, "2*hi*lo + floor(lo^2 / 2^r), exact");
        let tn = b.resolve(p, &t);
        let zw = 2 * dsp;
        let what = format!("floor(power{}^2 / 2^{}), exact", j - 1, 2 * r);
        let square = if b.instantiated_blocks() {
            // the MULT18X18D has no adder: hi^2 alone on it (with its own registers where
            // the cuts allow), T added after it on a carry chain
            b.step(&format!(
                "squaring {j} of {m_max} (squarer 11): hi^2 (one DSP)"
            ));
            let hh = format!("square{j}_hh");
            b.product(
                &hh,
                &[Piece::sig(&prev, r, dsp)],
                &[Piece::sig(&prev, r, dsp)],
                zw,
                &format!("hi^2, power{} = hi*2^{r} + lo, exact", j - 1),
            );
            b.fabric_register_step(&format!(
                "squaring {j} of {m_max}: hi^2 registered in the fabric"
            ));
            b.step(&format!("squaring {j} of {m_max}: Z = hi^2 + T/2^{r}"));
            b.add(
                &format!("square{j}"),
                &[Piece::sig(&hh, 0, zw)],
                &[tn.part(r, tw - r)],
                false,
                zw,
                &what,
            )
        } else {
            // a step that only registers T: the DSP's input registers take their operands
            // from a flip-flop (a route to the DSP column), not from the LUTs that picked
            // T's chunks
            b.register_only_step(&format!("{t}: registered for the DSP"));
            b.step(&format!(
                "squaring {j} of {m_max} (squarer 11): Z = hi^2 + T/2^{r} (multiply-add)"
            ));
            let (h, th) = (
                [Piece::sig(&prev, r, dsp)],
                [Piece::sig(tn.as_ref(), r, tw - r)],
            );
            let what = format!(
                "{what}: a {dsp}x{dsp} multiply-add (one DSP) instead of {}x{}",
                wf + 1,
                wf + 1
            );
            b.mul(
                &format!("square{j}"),
                zw,
                (&h, dsp),
                (&h, dsp),
                &th,
                Delay::ZERO,
                &what,
            )
        };
        // the bypass in a step of its own: the DSP's output meets only a flip-flop
        b.step(&format!("squaring {j} of {m_max}: bypassed when m_n < {j}"));
        b.delay(LUT_DELAY);
        b.bits(&square, 2 * wf - 2 * r, wf - 2 * r)
    } else {
        b.step(&format!(
            "squaring {j} of {m_max} (squarer 11): the product alone"
        ));
        let sq = 2 * wf + 2;
        let p = [Piece::sig(&prev, 0, wf + 1)];
        let (square, what) = (
            format!("square{j}"),
            format!("UQ2.{}: power{}^2, exact", 2 * wf, j - 1),
        );
        if b.instantiated_blocks() {
            // a MULT18X18D with its own registers where the cuts allow
            b.product(&square, &p, &p, sq, &what);
        } else {
            let wp = (wf + 1).min(dsp);
            b.mul(&square, sq, (&p, wp), (&p, wp), &[], Delay::ZERO, &what);
        }
        // the bypass in a step of its own: the block's output meets only its register
        b.step(&format!("squaring {j} of {m_max}: bypassed when m_n < {j}"));
        b.delay(LUT_DELAY);
        b.bits(&square, 2 * wf, wf)
    };
    let keep = b.r(&prev);
    let mf = b.bits("fit", w.rom_word_bits - 1, w.a_bits);
    let m_test = ex!("({} >= {})", mf, lit(w.m_bits, j as u128));
    b.wire(
        &format!("power{j}"),
        wf + 1,
        Kind::Logic,
        ex!("{} ? {} : {}", m_test, hi_bits, keep),
        &format!(
            "UQ1.{wf}: bracket^(2^{j}) floored (truncation #{}), or power{} when m_n < {j}",
            j + 1,
            j - 1
        ),
    );
}
