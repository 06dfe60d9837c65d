//! The lean quadratic unit on the ECP5: its products on MULT18X18D blocks with their own
//! registers, shaped for the family.

use super::*;

/// The lean datapath shaped for ECP5 (`--target ecp5`): the same values as [`lean`], in the
/// shape of the family. A MULT18X18D has 18×18 operands, no post-adder that yosys uses, and
/// its own input and output registers; the fabric's CCU2C carry chains add 32 bits in ~2 ns.
/// So every product is a step of its own on one DSP with its registers (see
/// [`Builder::product`]), every add a whole carry chain in the fabric step after it, and no
/// product reads another's output in the step right after it (an operand must be visible in
/// the step before the product, where the input registers take it).
///
/// Where it differs from [`lean`]:
/// - `k_q·n` is a product on a DSP (the constant as operand B);
/// - `P = kn·(1 − cos)` as `kn[17:0]·d + kn[hi:18]·d·2^18` (two DSPs), `P + K'` in two adds;
/// - a bracket of at most 18 bits is squared on one DSP; a wider one as hi² and hi·lo on a
///   DSP each (hi 18 bits), lo² by table, and two carry chains;
/// - the colours' rounding half is a fabric add after their products.
pub(crate) fn lean_ecp5(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, cb, bb) = (cfg.f(), w.cos_bits, cfg.b());
    let (wb, wsc) = (w.bracket_frac_bits, w.color_square_frac_bits);
    let dsp = ECP5_DSP_BITS;
    let (m, k_prime) = deviation_offset(w);

    b.step("cos complemented and clamped");
    cos_complement(cfg, b);

    let logic = cfg.params.rom_style == crate::config::RomStyle::Logic;
    let mut parts = None;
    if logic {
        // --rom-style logic: the table in LUTs, read in this step and the next, past the
        // DP16KD's clock limit
        b.step("cut-off ROM read (10, in LUTs): the entry in each group of words; 1 - cos (adder 6); k_q*n (a product)");
        let t = b.table(super::super::rom::cos_sp_rom(cfg));
        parts = Some((t, b.rom_parts("cos_sp", t, "n")));
    } else {
        b.step("cut-off ROM read (10, a block RAM); 1 - cos (adder 6); k_q*n (a product)");
        rom_read(cfg, b, true);
    }
    b.add(
        "one_minus_cos",
        &[Piece::sig("cos_complement", 0, cb)],
        &[],
        true,
        cb,
        &format!("UQ1.{f}: 1 - min(cos, 1) = ~cos + 1, exact"),
    );
    let (k, kb) = (cfg.k_code as u128, bit_length(cfg.k_code as u128));
    let what = format!(
        "UQ{}.{}: k_q*n, exact; one constant product replaces the paper's general multiplier 34",
        w.kn_bits - cfg.kf(),
        cfg.kf()
    );
    let nn = [Piece::sig("n", 0, cfg.n_bits())];
    if kb <= dsp {
        b.product(
            "kn",
            &nn,
            &[Piece::Const {
                value: k,
                width: kb,
            }],
            w.kn_bits,
            &what,
        );
    } else {
        // k_q wider than the block's operands: n*k[17:0] on one, n*k[hi:18] beside it, their
        // sum in the comparator's step
        b.product(
            "kn_lo",
            &nn,
            &[Piece::Const {
                value: k & mask(dsp),
                width: dsp,
            }],
            w.kn_bits.min(cfg.n_bits() + dsp),
            &format!("n*k_q[{}:0], exact", dsp - 1),
        );
        b.product(
            "kn_hi",
            &nn,
            &[Piece::Const {
                value: k >> dsp,
                width: kb - dsp,
            }],
            w.kn_bits - dsp,
            &format!("n*k_q[{}:{dsp}], exact", kb - 1),
        );
    }

    // a cut-off ROM of more than one DP16KD's words (one per n) is two banks of them, picked
    // after their output registers: a step that only registers the picked word before the
    // comparator's chain
    if let Some((t, (mut words, mut lo))) = parts {
        while words.len() > 1 {
            b.step(&format!(
                "cut-off ROM read (10, in LUTs): the entry picked by n's bits from {lo}"
            ));
            (words, lo) = b.rom_pick("cos_sp", t, "n", &words, lo);
        }
    } else if 1usize << cfg.n_bits() > DP16KD_WORDS {
        b.ecp5_register_step("cut-off ROM read: the bank's word registered");
    }
    b.step("comparator (12)");
    if kb > dsp {
        let lo_w = w.kn_bits.min(cfg.n_bits() + dsp);
        b.add(
            "kn",
            &[Piece::sig("kn_lo", 0, lo_w)],
            &[Piece::zeros(dsp), Piece::sig("kn_hi", 0, w.kn_bits - dsp)],
            false,
            w.kn_bits,
            &what,
        );
    }
    let (ca, cb2, cw, comment) = cutoff_add(cfg);
    let comment =
        format!("{comment}, kept complemented (a 1 above cos_sp): the chain's own output");
    let cmp = b.add_carry_complemented("cutoff_sum", &ca, &cb2, cw, &comment);

    // 1 - deviation without a subtractor, as in `lean`: ~(P + K') = K - P (mod 2^m)
    let split = w.kn_bits > dsp && m > dsp;
    b.step("deviation P = k_q*n*(1 - cos) (multiplier 7, products); comparator result");
    done(cfg, b, &cmp, true);
    // 1 - cos one bit wider than the block's operands (F = 18): its top bit is set only for
    // 1 - cos = 1.0, when the bits below are 0; the block takes those bits, and that one case
    // is kn*2^18, a mux after the products (the high product is 0 then)
    let top_alone = split && cb == dsp + 1;
    let dw = if top_alone { dsp } else { cb };
    let one_minus_cos = [Piece::sig("one_minus_cos", 0, dw)];
    if split {
        let hi_w = m - dsp;
        b.product(
            "deviation_lo",
            &[Piece::sig("kn", 0, dsp)],
            &one_minus_cos,
            m.min(dsp + dw),
            &format!("kn[{}:0] * (1 - cos), exact", dsp - 1),
        );
        b.product(
            "deviation_hi",
            &[Piece::sig("kn", dsp, w.kn_bits - dsp)],
            &one_minus_cos,
            hi_w,
            &format!(
                "kn[{}:{dsp}] * (1 - cos){}, mod 2^{hi_w}",
                w.kn_bits - 1,
                if top_alone {
                    format!("[{}:0]", dsp - 1)
                } else {
                    String::new()
                }
            ),
        );
        b.step("deviation: the high product plus K' (adder)");
        let hi = if top_alone {
            let (top, kn, h) = (
                b.bits("one_minus_cos", dsp, dsp),
                b.operand("kn", 0, w.kn_bits, hi_w),
                b.r("deviation_hi"),
            );
            b.wire(
                "deviation_top",
                hi_w,
                Kind::Logic,
                Builder::select(&top, &kn, &h, hi_w),
                &format!("kn * (1 - cos) / 2^{dsp}: kn when 1 - cos = 1.0, else the high product"),
            );
            "deviation_top"
        } else {
            "deviation_hi"
        };
        b.add(
            "deviation_hi_sum",
            &[Piece::sig(hi, 0, hi_w)],
            &[Piece::Const {
                value: k_prime >> dsp,
                width: hi_w,
            }],
            false,
            hi_w,
            &format!(
                "kn[{}:{dsp}] * (1 - cos) + K'[{}:{dsp}], mod 2^{hi_w}",
                w.kn_bits - 1,
                m - 1
            ),
        );
        b.step("deviation P plus K' (adder)");
        let lo_w = m.min(dsp + dw);
        b.add(
            "deviation_sum",
            &[Piece::sig("deviation_lo", 0, lo_w)],
            &[Piece::Const { value: k_prime & mask(dsp), width: dsp }, Piece::sig("deviation_hi_sum", 0, hi_w)],
            false,
            m,
            &format!("P + K' mod 2^{m}, P = k_q*n*(1 - cos) UQ.{} exact; its complement is K - P (no subtractor)", cfg.kf() + f),
        );
    } else {
        b.product(
            "deviation",
            &[Piece::sig("kn", 0, w.kn_bits)],
            &one_minus_cos,
            m,
            &format!("P = k_q*n*(1 - cos) mod 2^{m}, UQ.{} exact", cfg.kf() + f),
        );
        b.step("deviation P plus K' (adder)");
        b.add(
            "deviation_sum",
            &[Piece::sig("deviation", 0, m)],
            &[Piece::Const {
                value: k_prime,
                width: m,
            }],
            false,
            m,
            &format!("P + K' mod 2^{m}; its complement is K - P (no subtractor)"),
        );
    }

    bracket(w, b);

    let full_bits = w.full_square_bits();
    // a bracket more than MAX_SQUARER_SPLIT bits wider than the block's operands is squared as
    // one product the tool splits over its blocks: its low part's square by table would need
    // 2^r entries (4 M lines of Verilog at --rounding exact --k-frac-bits 24)
    let full = if wb < dsp || wb + 1 - dsp > MAX_SQUARER_SPLIT {
        b.step("square (squarer 11, a product)");
        let bracket_bits = [Piece::sig("bracket", 0, wb + 1)];
        b.product(
            "square_full",
            &bracket_bits,
            &bracket_bits,
            full_bits,
            &format!("UQ2.{}: bracket^2, exact (top bit always 0)", 2 * wb),
        );
        vec![Piece::sig("square_full", 0, full_bits)]
    } else {
        // a bracket wider than the MULT18X18D's operands: bracket = hi*2^r + lo with hi at 18
        // bits; hi^2 and hi*lo alone on a block each, lo^2 by table; then, as on the iCE40,
        // T = hi*lo + lo^2/2^(r+1) and Z = hi^2 + T/2^(r-1), each a carry chain of its own:
        // bracket^2 = {Z, T mod 2^(r-1), lo^2 mod 2^(r+1)}, every floor exact
        let r = wb + 1 - dsp;
        let (hi, lo) = (Piece::sig("bracket", r, dsp), Piece::sig("bracket", 0, r));
        let t = "square (squarer 11)";
        b.step(&format!(
            "{t}: hi^2 and hi*lo (a product each); lo^2 by table"
        ));
        b.product(
            "square_hh",
            std::slice::from_ref(&hi),
            std::slice::from_ref(&hi),
            2 * dsp,
            &format!("hi^2, bracket = hi*2^{r} + lo, exact"),
        );
        b.product(
            "square_hl",
            std::slice::from_ref(&hi),
            std::slice::from_ref(&lo),
            dsp + r,
            "hi*lo, exact",
        );
        b.square_table(
            "square_ll",
            "bracket",
            0,
            r,
            &format!("lo^2 by table, bracket = hi*2^{r} + lo"),
        );
        b.step(&format!("{t}: T = hi*lo + lo^2/2^{}", r + 1));
        let tw = dsp + r;
        let ll_hi: Vec<Piece> = if r > 1 {
            vec![Piece::sig("square_ll", r + 1, r - 1)]
        } else {
            vec![]
        };
        b.add(
            "square_t",
            &[Piece::sig("square_hl", 0, tw)],
            &ll_hi,
            false,
            tw,
            &format!("hi*lo + floor(lo^2 / 2^{}), exact", r + 1),
        );
        b.step(&format!("{t}: Z = hi^2 + T/2^{}", r - 1));
        b.add(
            "square_z",
            &[Piece::sig("square_hh", 0, 2 * dsp)],
            &[Piece::sig("square_t", r - 1, tw - (r - 1))],
            false,
            2 * dsp,
            &format!("floor(bracket^2 / 2^{}), exact", 2 * r),
        );
        let mut full = vec![Piece::sig("square_ll", 0, r + 1)];
        if r > 1 {
            full.push(Piece::sig("square_t", 0, r - 1));
        }
        full.push(Piece::sig("square_z", 0, 2 * dsp));
        full
    };

    b.step("truncation #2; intensity rounding (adder)");
    square_and_color_square(w, b, &full);
    if let Some((a, width, comment)) = intensity_add(cfg, w, b) {
        let sum = b.add("intensity_sum", &a, &[], true, width, &comment);
        intensity_from(cfg, b, &sum);
    }

    b.step("colour multipliers (14-16, products)");
    let cpb = w.color_product_bits;
    for ch in CHANNELS {
        b.product(
            &format!("color_prod_{ch}"),
            &[Piece::sig("color_square", 0, wsc + 1)],
            &[Piece::sig(&format!("ks_{ch}"), 0, bb)],
            cpb,
            &format!("UQ{bb}.{wsc}: S * ks_{ch}, exact"),
        );
    }

    b.step("colour rounding (adders)");
    for ch in CHANNELS {
        b.add(
            &format!("color_sum_{ch}"),
            &[Piece::sig(&format!("color_prod_{ch}"), 0, cpb)],
            &[Piece::Const {
                value: 1u128 << (wsc - 1),
                width: wsc,
            }],
            false,
            cpb,
            &format!("UQ{bb}.{wsc}: S * ks_{ch} + 1/2 colour ulp (round half up)"),
        );
    }
    b.colour_results(wsc, "S");
}
