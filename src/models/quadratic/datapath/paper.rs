//! The paper's device (the seed's Fig. 5) literally, on the datapath builder.

use super::*;

/// The seed's Fig. 5 taken literally: every bit kept, a general multiplier for k (34), a
/// separate n*(1 - cos) multiplier (7), a multiplier as squarer (11), three colour
/// multipliers (14-16); six coarse steps.
pub fn paper(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, cb, nb, bb, fi) = (cfg.f(), w.cos_bits, cfg.n_bits(), cfg.b(), cfg.fi());
    let (wb, ws) = (w.bracket_frac_bits, w.square_frac_bits);
    let one = lit(cb, 1u128 << f);

    b.step("clamp, 1 - cos (adder 6), cut-off ROM (10), comparator (12)");
    rom_read(cfg, b, false);
    let g = b.r("cos_g");
    b.wire(
        "cos_clamped",
        cb,
        Kind::Logic,
        ex!("({} > {}) ? {} : {}", g, one, one, g),
        &format!("UQ1.{f}, <= 1.0"),
    );
    let c = b.r("cos_clamped");
    b.wire(
        "one_minus_cos",
        cb,
        Kind::Sum,
        ex!("{} - {}", one, c),
        &format!("UQ1.{f}: 1 - cos(gamma), exact"),
    );
    let (c, sp) = (b.r("cos_clamped"), b.r("cos_sp"));
    b.wire(
        "done",
        1,
        Kind::Logic,
        ex!("({} < {})", c, sp),
        "comparator: bracket < 0",
    );
    b.delay(add_delay(cb) * 2.0);

    b.step("deviation n*(1 - cos) (multiplier 7) times k (general multiplier 34), truncation #1");
    let nd_bits = nb + cb;
    let constant_product = b.mul_delay(nd_bits, bit_length(cfg.k_code as u128));
    let (nn, d) = (
        [Piece::sig("n", 0, nb)],
        [Piece::sig("one_minus_cos", 0, cb)],
    );
    b.mul(
        "n_dev",
        nd_bits,
        (&nn, nb),
        (&d, cb),
        &[],
        constant_product,
        &format!("UQ{nb}.{f}: n*(1 - cos), exact (multiplier 7)"),
    );
    let nd = [Piece::sig("n_dev", 0, nd_bits)];
    let what = format!(
        "UQ.{}: k_q*n*(1 - cos), exact (general multiplier 34)",
        cfg.kf() + f
    );
    // in the same step as n_dev: its delay comes before this product's
    let after = b.mul_delay(nb, cb);
    // a k_q the synthesis tool mis-maps whole (`Builder::constant_split`: 0xC000 and more on
    // the iCE40): k_q = k_hi*2^s + k_lo, the product takes k_lo and n_dev*k_hi (a few bits of
    // k_hi, by shift-adds) as its addend
    // (a k_q only wider than the block is the tool's to split, as it always was)
    let (ks, k_bits) = (
        b.constant_split(cfg.k_code as u128),
        bit_length(cfg.k_code as u128),
    );
    if k_bits > ks && ks < b.dsp_bits() {
        let hw = w.deviation_bits - ks;
        let delay = k_hi_product(cfg, b, "n_dev", nd_bits, ks, hw);
        let k_lo = [Piece::Const {
            value: cfg.k_code as u128 & mask(ks),
            width: w.deviation_bits,
        }];
        let hi = [Piece::zeros(ks), Piece::sig("n_dev_k_hi", 0, hw)];
        let what = format!("{what}: n_dev*k_lo + n_dev*k_hi*2^{ks}");
        let after = after + delay;
        b.mul(
            "deviation_full",
            w.deviation_bits,
            (&nd, nd_bits),
            (&k_lo, ks),
            &hi,
            after,
            &what,
        );
    } else {
        let k = [Piece::Const {
            value: cfg.k_code as u128,
            width: w.deviation_bits,
        }];
        b.mul(
            "deviation_full",
            w.deviation_bits,
            (&nd, nd_bits),
            (&k, k_bits),
            &[],
            after,
            &what,
        );
    }
    let dev = b.pieces(&sub_pieces(
        &[Piece::sig("deviation_full", 0, w.deviation_bits)],
        w.deviation_shift,
        wb + 1,
    ));
    b.wire(
        "deviation",
        wb + 1,
        Kind::Select,
        dev,
        &format!("UQ1.{wb}: exact below the cut-off (< 2)"),
    );

    b.step("bracket = 1 - deviation (adder 9), zeroed beyond the cut-off (key block 13)");
    let (dn, dv) = (b.r("done"), b.r("deviation"));
    b.wire(
        "bracket",
        wb + 1,
        Kind::Logic,
        ex!(
            "{} ? {} : ({} - {})",
            dn,
            lit(wb + 1, 0),
            lit(wb + 1, 1u128 << wb),
            dv
        ),
        &format!("UQ1.{wb}, in [0, 1]"),
    );
    b.delay(add_delay(wb + 1) + LUT_DELAY);

    b.step("square (a general multiplier as squarer 11)");
    let fb = w.full_square_bits();
    let br = [Piece::sig("bracket", 0, wb + 1)];
    b.mul(
        "square_full",
        fb,
        (&br, wb + 1),
        (&br, wb + 1),
        &[],
        Delay::ZERO,
        &format!("UQ2.{}: exact (top bit always 0)", 2 * wb),
    );
    let sq = b.bits("square_full", 2 * wb, w.square_shift);
    b.wire("square", ws + 1, Kind::Select, sq, &format!("UQ1.{ws}: S"));

    b.step("colour multipliers (14-16); intensity rounding");
    let cpb = w.color_product_bits;
    let mut products = Vec::new();
    for ch in CHANNELS {
        let (cs, ks) = (
            [Piece::sig("square", 0, ws + 1)],
            [Piece::sig(&format!("ks_{ch}"), 0, bb)],
        );
        products.push(b.mul(
            &format!("color_prod_{ch}"),
            cpb,
            (&cs, ws + 1),
            (&ks, bb),
            &[],
            Delay::ZERO,
            &format!("UQ{bb}.{ws}: S * ks_{ch}, exact"),
        ));
    }
    if ws > fi {
        let sqr = b.r("square");
        b.wire(
            "intensity_sum",
            ws + 1,
            Kind::Sum,
            ex!("{} + {}", sqr, lit(ws + 1, 1u128 << (ws - fi - 1))),
            &format!("UQ1.{ws}: S + 2^-{} (round half up)", fi + 1),
        );
    }

    b.step("colour rounding, final slices");
    for (ch, product) in CHANNELS.iter().zip(&products) {
        let p = b.r(product);
        b.wire(
            &format!("color_sum_{ch}"),
            cpb,
            Kind::Sum,
            ex!("{} + {}", p, lit(cpb, 1u128 << (ws - 1))),
            "+ 1/2 colour ulp (round half up)",
        );
    }
    b.colour_results(ws, "S");
    let e = if ws > fi {
        b.bits("intensity_sum", ws, ws - fi)
    } else {
        let sqr = b.r("square");
        if fi > ws {
            ex!("{{{}, {}}}", sqr, lit(fi - ws, 0))
        } else {
            sqr
        }
    };
    b.wire("intensity", fi + 1, Kind::Select, e, &format!("UQ1.{fi}"));
    b.delay(add_delay(cpb));
}
