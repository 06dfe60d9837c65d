//! The quadratic unit of SPEC §3 on the datapath builder: `lean` (widths from the error
//! budget in `super`, short steps for a fully pipelined DSP design) and `paper` (the seed's
//! Fig. 5 literally). Every regrouping is exact, so the values are those of
//! [`super::Quadratic::trace`].
//!
//! `lean` is split into short steps so that a fully registered unit has at most one DSP
//! multiply-add, one ROM read, one LUT level or one ≤ [`crate::family::ice40::CHUNK_BITS`]-bit carry chain between
//! registers, and every carry chain takes its operands straight from registers (an inverter
//! or mux in front of an iCE40 carry chain costs a LUT level and a route). Wide adds go into
//! the DSPs' post-adders where the products are; the three left in the fabric are
//! carry-select: chunks added with carry-in 0 and 1 in one step, the carries rippled in the
//! next, each chunk's sum picked in the third. A register, not a LUT, drives every DSP input,
//! and no carry chain starts at a DSP output: the routes into and out of the iCE40's DSP
//! columns take 4–6 ns by themselves. Where `k_q` or `1 − cos` is wider than a DSP's 16 bits,
//! its high bits (a few) multiply by shift-adds in the fabric and the DSPs take the low 16:
//! the wide configuration keeps to the UP5K's 8 SB_MAC16. `paper` keeps the six coarse steps
//! of Fig. 5.

mod ecp5;
mod paper;
pub(crate) use ecp5::lean_ecp5;
pub use paper::paper;

use super::Widths;
use crate::bits::{bit_length, lit, mask};
use crate::config::Config;
use crate::datapath::*;

/// The cut-off ROM (10) read: `cos_sp`, addressed by n (`registered`: in block RAM with its
/// registers where the family has them, see [`Builder::rom_read_registered`]).
fn rom_read(cfg: &Config, b: &mut Builder, registered: bool) {
    let t = b.table(super::rom::cos_sp_rom(cfg));
    if registered {
        b.rom_read_registered("cos_sp", t, "n");
    } else {
        b.rom_read("cos_sp", t, "n");
    }
    b.delay(LUT_DELAY * cfg.n_bits().div_ceil(2) as f64);
}

/// `~cos`, clamped: one LUT level.
fn cos_complement(cfg: &Config, b: &mut Builder) {
    let f = cfg.f();
    let g = b.bits("cos_g", f, f);
    let x = b.bits("cos_g", f - 1, 0);
    b.wire(
        "cos_complement",
        f + 1,
        Kind::Logic,
        ex!("{{{}, ~{} | {{{}{{{}}}}}}}", g, x, f, g),
        &format!("UQ1.{f}: ~cos = 1 - 2^-{f} - cos; all ones when cos_g >= 1.0, so +1 wraps to 0 (the clamp)"),
    );
    b.delay(LUT_DELAY);
}

/// The comparator's add (12): `cos < cos_sp` is the carry out of `cos_sp + ~cos` over F+1
/// bits, an add of two registers. Returns (a, b, width, comment) for the family's adder.
fn cutoff_add(cfg: &Config) -> ([Piece; 1], [Piece; 2], u32, String) {
    let (f, cb) = (cfg.f(), cfg.f() + 1);
    (
        [Piece::sig("cos_sp", 0, cb)],
        [
            Piece::sig("cos_complement", 0, f),
            Piece::Const { value: 1, width: 1 },
        ],
        cb + 1,
        format!("cos_sp + ~cos over UQ1.{f}: bit {cb} (the carry) is cos < cos_sp"),
    )
}

/// `sig * c` (`c` a constant) as a sum of `sig` shifted to each set bit of `c`, mod 2^width:
/// fabric adds, for a product too narrow to spend a DSP block on.
fn shift_adds(b: &mut Builder, sig: &str, sig_width: u32, c: u128, width: u32) -> Expr {
    let mut terms: Vec<Expr> = Vec::new();
    for j in (0..128).filter(|j| c >> j & 1 == 1 && *j < width) {
        let pieces = if j == 0 {
            vec![Piece::sig(sig, 0, sig_width)]
        } else {
            vec![Piece::zeros(j), Piece::sig(sig, 0, sig_width)]
        };
        terms.push(b.pieces(&sub_pieces(&pieces, 0, width)));
    }
    if terms.is_empty() {
        Expr::constant(lit(width, 0))
    } else {
        Expr::join(&terms, "\n    + ")
    }
}

/// `<sig>_k_hi = sig * (k_code >> ks) mod 2^width` by shift-adds (the high part of a split k_q,
/// a few bits: the block's addend beside `sig * k_lo`); returns its delay.
fn k_hi_product(
    cfg: &Config,
    b: &mut Builder,
    sig: &str,
    sig_width: u32,
    ks: u32,
    width: u32,
) -> Delay {
    let k_hi = cfg.k_code as u128 >> ks;
    let e = shift_adds(b, sig, sig_width, k_hi, width);
    let what = format!(
        "{sig} * k_code[{}:{ks}] = {sig} * {k_hi} mod 2^{width}, by shift-adds",
        bit_length(cfg.k_code as u128) - 1
    );
    b.wire(&format!("{sig}_k_hi"), width, Kind::Sum, e, &what);
    add_delay(width) + LUT_DELAY * (k_hi.count_ones().max(2) - 1).ilog2() as f64
}

/// `done` from the comparator's carry (never when cos >= 1.0); `complemented`: the sum holds
/// the carry complemented ([`Builder::add_carry_complemented`]).
fn done(cfg: &Config, b: &mut Builder, sum: &Sig, complemented: bool) {
    let f = cfg.f();
    let (gg, c) = (b.bits("cos_g", f, f), b.bits(sum, f + 1, f + 1));
    let c = if complemented { ex!("~{}", c) } else { c };
    b.wire(
        "done",
        1,
        Kind::Logic,
        ex!("~{} & {}", gg, c),
        "comparator (12): cos(gamma) < cos_sp(n), beyond the highlight (never when cos >= 1.0)",
    );
}

/// 1 - deviation without an adder: with K = 2^(WB+s) + 2^s - 1 and K' = 2^m - 1 - K,
/// ~(P + K') = K - P (mod 2^m), and (K - P)[m-1:s] = 2^WB - floor(P / 2^s) (mod 2^(WB+1)).
/// Returns (m, K'): P is needed modulo 2^m only (m = WB+s+1); higher bits matter only beyond
/// the cut-off, where the key block zeroes the bracket.
fn deviation_offset(w: &Widths) -> (u32, u128) {
    let (wb, s) = (w.bracket_frac_bits, w.deviation_shift);
    let m = wb + s + 1;
    let k_big = (1u128 << (wb + s)) + (1u128 << s) - 1;
    (m, mask(m) - k_big)
}

/// The bracket step: `1 - deviation` (adder 9) as the complement of `P + K'`, truncation #1,
/// zeroed by the key block (13).
fn bracket(w: &Widths, b: &mut Builder) {
    let (wb, s) = (w.bracket_frac_bits, w.deviation_shift);
    let (m, _) = deviation_offset(w);
    b.step("bracket = 1 - deviation (adder 9), truncation #1, key block (13)");
    let (dn, q) = (b.r("done"), b.bits("deviation_sum", m - 1, s));
    b.wire(
        "bracket",
        wb + 1,
        Kind::Logic,
        ex!("{} ? {} : ~{}", dn, lit(wb + 1, 0), q),
        &format!("UQ1.{wb} in [0, 1]: 2^{wb} - floor(P/2^{s}) (truncation #1), zeroed beyond the cut-off (key block 13)"),
    );
    b.delay(LUT_DELAY);
}

/// Truncation #2 of the full square (`pieces`, LSB first) to `square`, and the colours' part of it.
fn square_and_color_square(w: &Widths, b: &mut Builder, full: &[Piece]) {
    let (ws, wsc) = (w.square_frac_bits, w.color_square_frac_bits);
    let sq = b.pieces(&sub_pieces(full, w.square_shift, ws + 1));
    b.wire(
        "square",
        ws + 1,
        Kind::Select,
        sq,
        &format!("UQ1.{ws}: S = bracket^2 floored to 2^-{ws} (truncation #2)"),
    );
    let csq = b.bits("square", ws, ws - wsc);
    b.wire(
        "color_square",
        wsc + 1,
        Kind::Select,
        csq,
        &if wsc < ws {
            format!(
                "UQ1.{wsc}: all the colours' budget needs (saves {} bits per colour multiplier)",
                ws - wsc
            )
        } else {
            format!("UQ1.{wsc}")
        },
    );
}

/// The intensity rounding's add, `S[WS:WS-FI-1] + 1` (its bits [FI+1:1] are S rounded half
/// up), as (a, width, comment); `None` when S has no bits to drop, and then `intensity` is
/// defined here as S itself.
fn intensity_add(cfg: &Config, w: &Widths, b: &mut Builder) -> Option<([Piece; 1], u32, String)> {
    let (ws, fi) = (w.square_frac_bits, cfg.fi());
    if ws > fi {
        // round half up: (S[WS:WS-FI-1] + 1) >> 1 = floor(S*2^FI + 1/2)
        Some((
            [Piece::sig("square", ws - fi - 1, fi + 2)],
            fi + 2,
            format!(
                "UQ1.{}: S to 2^-{} plus one ulp = S + 2^-{} (round half up)",
                fi + 1,
                fi + 1,
                fi + 1
            ),
        ))
    } else {
        let sqr = b.r("square");
        let e = if fi > ws {
            ex!("{{{}, {}}}", sqr, lit(fi - ws, 0))
        } else {
            sqr
        };
        b.wire(
            "intensity",
            fi + 1,
            Kind::Select,
            e,
            &format!("UQ1.{fi}: S exactly (no bits to drop)"),
        );
        None
    }
}

/// `intensity` from the rounding add's sum.
fn intensity_from(cfg: &Config, b: &mut Builder, sum: &Sig) {
    let fi = cfg.fi();
    let e = b.bits(sum, fi + 1, 1);
    b.wire(
        "intensity",
        fi + 1,
        Kind::Select,
        e,
        &format!("UQ1.{fi}: S rounded half up"),
    );
}

/// The lean datapath: short steps, every decomposition exact (see the module docs).
///
/// Where it saves against `paper` (each also said in the RTL comments):
/// - `k_q·n` is one constant multiply: no general multiplier by k (34);
/// - the deviation and `1 − deviation` come out of DSP multiply-adds (`P + K'`, then an
///   inversion folded into the key block's LUTs): no fabric adder for adder 9;
/// - the bracket is squared as `hi²` and `hi·lo` with a 16-bit `hi`, the adds inside the
///   DSPs: two 16-bit DSP products instead of a 3-DSP 18×18 one;
/// - widths cut to the error budget (bracket UQ1.(max(FI,B)+2), colours fed UQ1.(B+1));
/// - the colour rounding half is the colour DSPs' addend: no rounding adders.
pub fn lean(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, cb) = (cfg.f(), w.cos_bits);
    let (wb, wsc) = (w.bracket_frac_bits, w.color_square_frac_bits);
    let (m, k_prime) = deviation_offset(w);

    b.step("cut-off ROM read (10); cos complemented and clamped");
    rom_read(cfg, b, false);
    cos_complement(cfg, b);

    b.step("1 - cos (adder 6): chunk sums");
    let d = b.add_start(
        "one_minus_cos",
        &[Piece::sig("cos_complement", 0, cb)],
        &[],
        true,
        cb,
        &format!("UQ1.{f}: 1 - min(cos, 1) = ~cos + 1, exact"),
    );

    // 1 - cos is resolved a step before the DSP that reads it: its cut register there is the
    // DSP's input register, and a register, not a LUT, drives the long route into the DSP column
    b.step("1 - cos: carries and select; comparator (12): chunk sums");
    b.add_carries(&d);
    b.add_finish(d);
    let (ca, cb2, cw, comment) = cutoff_add(cfg);
    let cmp = b.add_start("cutoff_sum", &ca, &cb2, false, cw, &comment);
    // a k_q wider than the DSP's operands, or one the synthesis tool mis-maps whole
    // (`Builder::constant_split`: 0xC000 and more on the iCE40): k_q = k_hi*2^s + k_lo, and
    // n*k_hi (a few bits of k_hi) in shift-adds here, the DSP's addend in the next step: one
    // DSP for k_q*n, not two
    let dsp = b.dsp_bits();
    let ks = b.constant_split(cfg.k_code as u128);
    let k_bits = bit_length(cfg.k_code as u128);
    let k_split = k_bits > ks;
    if k_split {
        let delay = k_hi_product(cfg, b, "n", cfg.n_bits(), ks, (w.kn_bits - ks).max(1));
        b.delay(delay);
    }

    b.step("comparator: carries; k_q*n (constant multiply)");
    b.add_carries(&cmp);
    let nn = [Piece::sig("n", 0, cfg.n_bits())];
    let kq = (cfg.n_bits(), k_bits.min(ks));
    if k_split {
        let (k_lo, hi) = (
            [Piece::Const {
                value: cfg.k_code as u128 & mask(ks),
                width: w.kn_bits,
            }],
            [Piece::zeros(ks), Piece::sig("n_k_hi", 0, w.kn_bits - ks)],
        );
        let what = format!(
            "UQ{}.{}: k_q*n = n*k_lo + n*k_hi*2^{ks}, exact (one DSP, the add inside it)",
            w.kn_bits - cfg.kf(),
            cfg.kf()
        );
        b.mul(
            "kn",
            w.kn_bits,
            (&nn, kq.0),
            (&k_lo, kq.1),
            &hi,
            Delay::ZERO,
            &what,
        );
    } else {
        let k = [Piece::Const {
            value: cfg.k_code as u128,
            width: w.kn_bits,
        }];
        let what = format!("UQ{}.{}: k_q*n, exact; one constant multiply replaces the paper's general multiplier 34", w.kn_bits - cfg.kf(), cfg.kf());
        b.mul(
            "kn",
            w.kn_bits,
            (&nn, kq.0),
            (&k, kq.1),
            &[],
            Delay::ZERO,
            &what,
        );
    }

    b.step("comparator: select; deviation, high partial product (multiply-add)");
    let sum = b.add_finish(cmp);
    done(cfg, b, &sum, false);
    // done: one LUT (a one-chunk comparator's add_finish has no select to count)
    b.delay(LUT_DELAY);
    // 1 - cos wider than the DSP's operands: d = d_hi*2^16 + d_lo, and kn*d_hi (a few bits of
    // d_hi) in shift-adds with K'[m-1:16], the products then take d_lo alone: kn*d + K' =
    // kn*d_lo + 2^16*(kn*d_hi + K'_hi) + K'_lo, every term exact mod 2^m
    let d_split = cb > dsp;
    let dw = cb.min(dsp);
    if d_split {
        let xw = m - dsp;
        let mut terms = b.shift_add_terms(
            &Piece::sig("kn", 0, w.kn_bits),
            &Piece::sig("one_minus_cos", dsp, cb - dsp),
            0,
            xw,
        );
        terms.push(Expr::constant(lit(xw, k_prime >> dsp)));
        b.wire(
            "deviation_top",
            xw,
            Kind::Sum,
            Expr::join(&terms, "\n    + "),
            &format!(
                "kn * (1 - cos)[{}:{dsp}] + K'[{}:{dsp}] mod 2^{xw}, by shift-adds",
                cb - 1,
                m - 1
            ),
        );
        b.delay(add_delay(xw) + LUT_DELAY * ((cb - dsp + 1) as f64).log2().ceil());
        b.step("deviation, high partial product (multiply-add)");
    }
    // kn = kn_hi*2^16 + kn_lo: two products with <= 16-bit operands instead of one that
    // would take 3 DSP blocks; the hi product is needed only modulo 2^(m-16)
    let split = w.kn_bits > dsp && m > dsp;
    if split {
        let hi_w = m - dsp;
        let (kh, d2) = (
            [Piece::sig("kn", dsp, w.kn_bits - dsp)],
            [Piece::sig("one_minus_cos", 0, dw)],
        );
        // the addend of the 2^16 part: K'_hi, or with kn*d_hi
        let c = if d_split {
            Piece::sig("deviation_top", 0, m - dsp)
        } else {
            Piece::Const {
                value: k_prime >> dsp,
                width: hi_w,
            }
        };
        let what = if d_split {
            format!("(1 - cos)[{}:0] + kn*(1 - cos)[{}:{dsp}]", dsp - 1, cb - 1)
        } else {
            "(1 - cos)".into()
        };
        let what = format!(
            "kn[{}:{dsp}] * {what} + K'[{}:{dsp}], mod 2^{hi_w} (one DSP, the add inside it)",
            w.kn_bits - 1,
            m - 1
        );
        b.mul(
            "deviation_hi",
            hi_w,
            (&kh, w.kn_bits - dsp),
            (&d2, dw),
            &[c],
            Delay::ZERO,
            &what,
        );
    }

    b.step("deviation P = k_q*n*(1 - cos) (multiplier 7) plus K' (multiply-add)");
    let (kn, d1, c) = if split {
        let c = vec![
            Piece::Const {
                value: k_prime & mask(dsp),
                width: dsp,
            },
            Piece::sig("deviation_hi", 0, m - dsp),
        ];
        (
            Piece::sig("kn", 0, dsp),
            Piece::sig("one_minus_cos", 0, dw),
            c,
        )
    } else if d_split {
        let c = vec![
            Piece::Const {
                value: k_prime & mask(dsp),
                width: dsp,
            },
            Piece::sig("deviation_top", 0, m - dsp),
        ];
        (
            Piece::sig("kn", 0, w.kn_bits),
            Piece::sig("one_minus_cos", 0, dw),
            c,
        )
    } else {
        (
            Piece::sig("kn", 0, w.kn_bits),
            Piece::sig("one_minus_cos", 0, cb),
            vec![Piece::Const {
                value: k_prime,
                width: m,
            }],
        )
    };
    let what = format!("P + K' mod 2^{m}, P = k_q*n*(1 - cos) UQ.{} exact; its complement is K - P (no subtractor)", cfg.kf() + f);
    b.mul(
        "deviation_sum",
        m,
        (&[kn], dsp.min(w.kn_bits)),
        (&[d1], dw),
        &c,
        Delay::ZERO,
        &what,
    );

    bracket(w, b);

    let r = w.squarer_split;
    let full_bits = w.full_square_bits();
    let full: Vec<Piece> = if r > 0 {
        // bracket = hi*2^r + lo; bracket^2 = hi^2*2^2r + hi*lo*2^(r+1) + lo^2 regrouped, all
        // floors exact: T = hi*lo + lo^2/2^(r+1), Z = hi^2 + T/2^(r-1), and
        // bracket^2 = {Z, T mod 2^(r-1), lo^2 mod 2^(r+1)}: two multiply-adds, no fabric adder
        let hw = wb + 1 - r;
        b.step("square (squarer 11): lo^2");
        // a table of 2^r entries: LUTs, no carry chain in front of the next DSP
        b.square_table(
            "square_ll",
            "bracket",
            0,
            r,
            &format!("lo^2 by table, bracket = hi*2^{r} + lo"),
        );
        b.step("square: T = hi*lo + lo^2/2^(r+1) (multiply-add)");
        let tw = hw + r;
        let (hi, lo) = (
            [Piece::sig("bracket", r, hw)],
            [Piece::sig("bracket", 0, r)],
        );
        let plus = if 2 * r > r + 1 {
            vec![Piece::sig("square_ll", r + 1, r - 1)]
        } else {
            Vec::new()
        };
        b.mul(
            "square_t",
            tw,
            (&hi, hw),
            (&lo, r),
            &plus,
            Delay::ZERO,
            "hi*lo + floor(lo^2 / 2^(r+1)), exact (one DSP, the add inside it)",
        );
        b.step("square: Z = hi^2 + T/2^(r-1) (multiply-add)");
        let h = [Piece::sig("bracket", r, hw)];
        let th = [Piece::sig("square_t", r - 1, tw - (r - 1))];
        let what = format!(
            "floor(bracket^2 / 2^{}), exact: a {hw}x{hw} multiply-add (one DSP) instead of {}x{}",
            2 * r,
            wb + 1,
            wb + 1
        );
        b.mul(
            "square_z",
            2 * hw,
            (&h, hw),
            (&h, hw),
            &th,
            Delay::ZERO,
            &what,
        );
        let mut full = vec![Piece::sig("square_ll", 0, r + 1)];
        if r > 1 {
            full.push(Piece::sig("square_t", 0, r - 1));
        }
        full.push(Piece::sig("square_z", 0, 2 * hw));
        full
    } else {
        b.step("square (squarer 11)");
        let br = [Piece::sig("bracket", 0, wb + 1)];
        b.mul(
            "square_full",
            full_bits,
            (&br, wb + 1),
            (&br, wb + 1),
            &[],
            Delay::ZERO,
            &format!("UQ2.{}: bracket^2, exact (top bit always 0)", 2 * wb),
        );
        vec![Piece::sig("square_full", 0, full_bits)]
    };

    b.step("truncation #2; colour multipliers (14-16) with the rounding half (multiply-add)");
    square_and_color_square(w, b, &full);
    b.colour_sums("color_square", wsc, "S", Delay::ZERO);
    // the intensity rounding starts a step after the squarer's DSP: its output register
    // drives a fabric register across the long route out of the DSP column, not a carry chain
    let intensity_add = intensity_add(cfg, w, b);

    b.step("colour results; intensity rounding: chunk sums");
    b.colour_results(wsc, "S");
    b.delay(Delay::ZERO);
    if let Some((a, width, comment)) = intensity_add {
        let p = b.add_start("intensity_sum", &a, &[], true, width, &comment);
        if !p.chunks.is_empty() {
            b.step("intensity rounding: carries and select");
            b.add_carries(&p);
        }
        let sum = b.add_finish(p);
        intensity_from(cfg, b, &sum);
    }
}
