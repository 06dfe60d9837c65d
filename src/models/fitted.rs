//! `--model fitted` (SPEC §6): the paper's structure made accurate. For every n ≥ 1 the
//! generator fits `S = [1 − a_n·(1 − c)]^(2^m_n)`, `m_n ∈ {0, …, M}`, minimax against `c^n`
//! over the real interval `c ∈ [0, 1]`, quantises `a_n` to `KA = k_frac_bits` fractional
//! bits, and from then on the *quantised* `a_n` define the unit.
//!
//! # The fit
//!
//! For fixed m the approximant `max(0, 1 − a·t)^(2^m)` (t = 1 − c) falls everywhere as a
//! grows, so `max_t (approx − c^n)` falls and `max_t (c^n − approx)` rises with a: the
//! maximum error `E(a)` is quasi-convex and a golden-section search finds its minimum. The
//! inner maximum over t is taken on a grid of `t ∈ [0, min(1, 40/n)]` (past `40/n`,
//! `c^n < e^−40` and the approximant only falls, so the error there is at most its value at
//! the grid's end) and refined around the worst grid point. Every m is tried; the smallest
//! error wins (ties to the smaller m). Only `f64::powi` is used, so the fit is the same on
//! every run. n = 0 stores `a = 0, m = 0` (S = 1).
//!
//! # Datapath and error budget (all unsigned, W = max(FI, B) + M + 2)
//!
//! ```text
//! D       = 2^F − min(cos_g, 2^F)                 UQ1.F exact                 1 − cos
//! P       = a_code·D                              UQ(·).(KA+F) exact          a_n·(1 − c)
//! diff    = 2^(KA+F) − P                          signed; done = diff < 0     the bracket, exact
//! x_0     = done ? 0 : ⌊diff / 2^(KA+F−W)⌋        UQ1.W  truncation #1
//! x_j     = j ≤ m_n ? ⌊x_(j−1)² / 2^W⌋ : x_(j−1)  UQ1.W  truncation #(j+1), j = 1..M
//! out     = ⌊(x_M·Mo + 2^(W−1)) / 2^W⌋            Mo = 2^FI or ks_X, round half up
//! ```
//!
//! Every truncation rounds down, so every error is one-sided: the computed value never
//! exceeds the exact one. With `e_j = x_j(exact) − x_j ≥ 0`, `e_0 < 2^−W` and, as all values
//! are in [0, 1], `x² − (x − e)² ≤ 2e`, so `e_j < 2·e_(j−1) + 2^−W`, hence
//! `e_m < (2^(m+1) − 1)·2^−W < 2^(M+1−W)`. In output units (`Mo < 2^max(FI,B)`) the value fed
//! to the final rounding lies in `(o* − 2^(M+1−W+max(FI,B)), o*] = (o* − 1/2, o*]` for
//! `W = max(FI, B) + M + 2`; round half up then gives `|o − o*| < 1`, and `o = o*` where `o*`
//! is an integer. The colours need less: see [`color_frac_bits`]. Each step is monotone in `cos_g` (the mux depends on n only), so the
//! outputs never decrease as `cos_g` grows. (When `KA + F < W` the bracket is exact and
//! shifted left instead.)
//!
//! # Shape (what the steps are; the values above are exact, so the shape never changes them)
//!
//! Every add is the builder's carry-select add, cut into the family's chunks, and every sum
//! of more than two terms a carry-save sum closed by one (`Builder::sum_start`): `1 − c`,
//! `P` (a_lo·D on a DSP with a_hi·D's partial products beside it, when a_n is wider than a
//! DSP's operands), `diff` (from `~P`, complemented in the LUTs that pick P's chunks so the
//! add starts at a flip-flop), each squaring's `T = 2·hi·lo + ⌊lo²/2^r⌋` (partial products
//! and a table of lo², registered once more before its DSP, whose input registers would
//! otherwise take it from LUTs) and the intensity's rounding. The DSP's output meets only a
//! flip-flop before the bypass mux. On the iCE40 this makes about 65 cut points, each at most
//! a short carry chain or two LUTs; a shallower `--stages` picks among them by the delays.

use super::{
    cosine, explain_ideal, scaled, Description, Inputs, Outputs, SpecularUnit, SPEC_PORTS,
};
use crate::bits::{bit_length, exact_decimal, lit, mask};
use crate::config::Config;
use crate::datapath::{
    ex, Builder, Delay, Expr, Kind, Piece, LUT_DELAY, LUT_INPUTS, MAX_SQUARER_SPLIT,
};
use crate::table::Table;
use num_bigint::BigUint;
use serde::Serialize;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The fitted constants of one configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// `a_n` before quantisation (0 for n = 0).
    pub a: Vec<f64>,
    /// `round(a_n · 2^KA)`.
    pub a_code: Vec<u64>,
    /// `m_n`: the bracket is raised to `2^m_n`.
    pub m: Vec<u32>,
    /// The fit's own estimate of `max_c |S − c^n|` for each n (before quantisation).
    pub fit_error: Vec<f64>,
}

/// Internal widths of the fitted unit.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct FittedWidths {
    /// KA: fractional bits of `a_n` (the `k_frac_bits` parameter).
    pub(crate) a_frac_bits: u32,
    /// Bits of the largest `a_code`.
    pub(crate) a_bits: u32,
    /// Bits of the `m_n` field of the ROM word (0 when M = 0).
    pub(crate) m_bits: u32,
    /// ROM word: `{m_n, a_code}`.
    pub(crate) rom_word_bits: u32,
    /// `P = a_code·D`.
    pub(crate) product_bits: u32,
    /// `diff = 2^(KA+F) − P` with its sign bit.
    pub(crate) diff_bits: u32,
    /// W: fractional bits of the bracket and of every square, UQ1.W.
    pub(crate) frac_bits: u32,
    /// WC: fractional bits of S fed to the colour multipliers (≤ W; see the module docs).
    pub(crate) color_frac_bits: u32,
}

/// WC: the colours' own budget. With `e < 2^(M+1−W)` from the squarings and `< 2^−WC` from
/// flooring S further to WC bits, the colour value is low by less than
/// `ks·(2^(M+1−W) + 2^−WC) < 2^(B+M+1−W) + 2^(B−WC)`; the smallest WC ≤ W keeping that
/// ≤ 1/2 (when FI > B there is room, and the colour multipliers shrink to B+2 or so bits).
pub(crate) fn color_frac_bits(cfg: &Config) -> u32 {
    let (b, m) = (cfg.b() as i64, cfg.max_squarings() as i64);
    let w = cfg.fi().max(cfg.b()) as i64 + m + 2;
    let p = |k: i64| (k as f64).exp2();
    (1..=w)
        .find(|&wc| p(b + m + 1 - w) + p(b - wc) <= 0.5)
        .unwrap_or(w) as u32
}

/// Largest and worst error of `max(0, 1 − a t)^(2^m)` against `(1 − t)^n` over `t ∈ [0, 1]`.
fn max_error(n: u32, m: u32, a: f64) -> f64 {
    const GRID: usize = 160;
    let e = 1i32 << m;
    let err = |t: f64| {
        let base = (1.0 - a * t).max(0.0);
        (base.powi(e) - (1.0 - t).powi(n as i32)).abs()
    };
    let t_end = (40.0 / n as f64).min(1.0);
    let (mut worst, mut at) = (err(1.0), GRID);
    for i in 0..=GRID {
        let v = err(t_end * i as f64 / GRID as f64);
        if v > worst {
            worst = v;
            at = i;
        }
    }
    if at < GRID || t_end < 1.0 {
        // golden-section refinement of the worst grid point's neighbourhood
        let h = t_end / GRID as f64;
        let (mut lo, mut hi) = ((at as f64 - 1.0) * h, (at as f64 + 1.0) * h);
        lo = lo.max(0.0);
        hi = hi.min(1.0);
        let r = 0.618_033_988_749_894_9;
        let (mut x1, mut x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
        let (mut f1, mut f2) = (err(x1), err(x2));
        for _ in 0..24 {
            if f1 > f2 {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - r * (hi - lo);
                f1 = err(x1);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + r * (hi - lo);
                f2 = err(x2);
            }
        }
        worst = worst.max(f1).max(f2);
    }
    worst
}

/// The minimax `a` for one (n, m): golden-section search on the quasi-convex `E(a)`.
fn fit_one(n: u32, m: u32) -> (f64, f64) {
    let centre = n as f64 / (1u32 << m) as f64;
    let (mut lo, mut hi) = (centre * 0.25, centre * 4.0);
    let r = 0.618_033_988_749_894_9;
    let (mut x1, mut x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut f1, mut f2) = (max_error(n, m, x1), max_error(n, m, x2));
    for _ in 0..48 {
        if f1 < f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - r * (hi - lo);
            f1 = max_error(n, m, x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + r * (hi - lo);
            f2 = max_error(n, m, x2);
        }
    }
    let a = 0.5 * (lo + hi);
    (a, max_error(n, m, a))
}

/// The best `(a, m, error)` for one n over `m ∈ 0..=max_m`.
pub(crate) fn fit_n(n: u32, max_m: u32) -> (f64, u32, f64) {
    let mut best = (0.0, 0, f64::INFINITY);
    for m in 0..=max_m {
        if (1u64 << m) > 4 * n as u64 {
            break; // raising to far more than n only widens the bell
        }
        let (a, e) = fit_one(n, m);
        if e < best.2 - 1e-12 {
            best = (a, m, e);
        }
    }
    best
}

/// Fits every n of the configuration (two threads) and quantises `a_n`.
pub fn fit(cfg: &Config) -> Fit {
    let count = 1usize << cfg.n_bits();
    let max_m = cfg.max_squarings();
    let threads = std::thread::available_parallelism()
        .map_or(1, |p| p.get())
        .clamp(1, 8);
    let mut rows: Vec<(f64, u32, f64)> = vec![(0.0, 0, 0.0); count];
    std::thread::scope(|s| {
        let chunk = count.div_ceil(threads);
        for (t, part) in rows.chunks_mut(chunk).enumerate() {
            s.spawn(move || {
                for (i, row) in part.iter_mut().enumerate() {
                    let n = (t * chunk + i) as u32;
                    if n > 0 {
                        *row = fit_n(n, max_m);
                    }
                }
            });
        }
    });
    let scale = (cfg.kf() as f64).exp2();
    let a_code = rows
        .iter()
        .enumerate()
        .map(|(n, r)| {
            if n == 0 {
                0
            } else {
                ((r.0 * scale).round() as u64).max(1)
            }
        })
        .collect();
    Fit {
        a: rows.iter().map(|r| r.0).collect(),
        a_code,
        m: rows.iter().map(|r| r.1).collect(),
        fit_error: rows.iter().map(|r| r.2).collect(),
    }
}

impl Fit {
    /// The ROM words `{m_n, a_code}`.
    pub(crate) fn rom_words(&self, w: &FittedWidths) -> Vec<u128> {
        self.a_code
            .iter()
            .zip(&self.m)
            .map(|(&a, &m)| ((m as u128) << w.a_bits) | a as u128)
            .collect()
    }
}

impl FittedWidths {
    pub fn derive(cfg: &Config, fit: &Fit) -> FittedWidths {
        let (f, ka) = (cfg.f(), cfg.kf());
        let a_bits = bit_length(*fit.a_code.iter().max().unwrap_or(&1) as u128).max(1);
        let m_bits = bit_length(cfg.max_squarings() as u128);
        let product_bits = a_bits + f + 1;
        FittedWidths {
            a_frac_bits: ka,
            a_bits,
            m_bits,
            rom_word_bits: a_bits + m_bits,
            product_bits,
            diff_bits: product_bits.max(ka + f + 1) + 1,
            frac_bits: cfg.fi().max(cfg.b()) + cfg.max_squarings() + 2,
            color_frac_bits: color_frac_bits(cfg),
        }
    }
}

/// Every intermediate value of the fitted datapath for one input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FittedTrace {
    pub(crate) a_code: u64,
    pub(crate) m: u32,
    pub(crate) one_minus_cos: u64,
    pub(crate) product: u128,
    pub(crate) done: bool,
    /// `x_0 … x_M` (only the first M+1 used)
    pub(crate) squares: [u128; 5],
}

/// The bit-exact golden model (what the RTL computes).
pub fn trace(cfg: &Config, fit: &Fit, w: &FittedWidths, x: Inputs) -> (FittedTrace, Outputs) {
    let (f, fi, b, ka, wf) = (cfg.f(), cfg.fi(), cfg.b(), cfg.kf(), w.frac_bits);
    let cos = (x.cos_g as u64 & mask(f + 1) as u64).min(1 << f);
    let n = (x.n as u64 & mask(cfg.n_bits()) as u64) as usize;
    let (a_code, m) = (fit.a_code[n], fit.m[n]);
    let d = (1u64 << f) - cos;
    let product = a_code as u128 * d as u128;
    let one = 1u128 << (ka + f);
    let done = product > one;
    let diff = if done { 0 } else { one - product };
    let x0 = if ka + f >= wf {
        diff >> (ka + f - wf)
    } else {
        diff << (wf - ka - f)
    };
    let mut squares = [0u128; 5];
    squares[0] = x0;
    for j in 1..=cfg.max_squarings() as usize {
        let prev = squares[j - 1];
        squares[j] = if j as u32 <= m {
            (prev * prev) >> wf
        } else {
            prev
        };
    }
    let s = squares[cfg.max_squarings() as usize];
    let intensity = ((s + (1u128 << (wf - fi - 1))) >> (wf - fi)) as u32;
    let wc = w.color_frac_bits;
    let sc = s >> (wf - wc);
    let spec =
        x.ks.map(|k| ((sc * (k as u128 & mask(b)) + (1u128 << (wc - 1))) >> wc) as u32);
    (
        FittedTrace {
            a_code,
            m,
            one_minus_cos: d,
            product,
            done,
            squares,
        },
        Outputs {
            spec,
            intensity,
            done,
        },
    )
}

/// Checks one output vector against the exact rational `S = base^(2^m)`,
/// `base = 1 − a_code·D/2^(KA+F)`, with the faithful contract; `done ⇔ base < 0`.
pub fn check(cfg: &Config, fit: &Fit, x: Inputs, got: Outputs) -> Result<(), crate::error::Error> {
    let (f, ka) = (cfg.f(), cfg.kf());
    let cos = (x.cos_g as u64).min(1 << f);
    let n = x.n as usize;
    let one = 1u128 << (ka + f);
    let p = fit.a_code[n] as u128 * ((1u64 << f) - cos) as u128;
    let done = p > one;
    if got.done != done {
        return Err(crate::error::Error::breach(
            "done",
            format!("got {}, reference {done}", got.done),
        ));
    }
    let e = 1u32 << fit.m[n];
    let den_log2 = (ka + f) * e;
    // A float screen first, rigorous: `base = (one − p)/2^(KA+F)` is exact in f64 (< 2^32
    // over a power of two); each of the m ≤ 4 squarings and the final product by M < 2^25
    // adds a relative error of at most 2^−53, so `S·M` is within (2^m + 1)·2^−53·2^25 < 2^−23
    // of its exact value. An output farther than 2^−20 inside the unit interval around it is
    // faithful; only outputs near the edge go to exact big integers.
    let base = if done {
        0.0
    } else {
        (one - p) as f64 / ((ka + f) as f64).exp2()
    };
    let s = (0..fit.m[n]).fold(base, |v, _| v * v);
    let screened = |o: u32, mult: u128| (o as f64 - s * mult as f64).abs() < 1.0 - (-20f64).exp2();
    let s_num = std::cell::OnceCell::new();
    let s_num = || {
        s_num.get_or_init(|| {
            if done {
                BigUint::from(0u32)
            } else {
                BigUint::from(one - p).pow(e)
            }
        })
    };
    let within = |o: u32, mult: u128| -> bool {
        if screened(o, mult) {
            return true;
        }
        let ideal = s_num() * BigUint::from(mult);
        let scaled = BigUint::from(o) << den_log2;
        let diff = if scaled > ideal {
            scaled - &ideal
        } else {
            &ideal - scaled
        };
        diff < (BigUint::from(1u32) << den_log2)
    };
    if !within(got.intensity, 1u128 << cfg.fi()) {
        return Err(crate::error::Error::breach(
            "intensity",
            format!(
                "got {}, ideal S·2^FI = {:.6}",
                got.intensity,
                ratio(s_num(), den_log2) * (cfg.fi() as f64).exp2()
            ),
        ));
    }
    for (i, name) in SPEC_PORTS.iter().enumerate() {
        if !within(got.spec[i], x.ks[i] as u128) {
            return Err(crate::error::Error::breach(
                name,
                format!(
                    "got {}, ideal S·ks = {:.6}",
                    got.spec[i],
                    ratio(s_num(), den_log2) * x.ks[i] as f64
                ),
            ));
        }
    }
    Ok(())
}

/// `num / 2^den_log2` as a float.
fn ratio(num: &BigUint, den_log2: u32) -> f64 {
    let bits = num.bits() as u32;
    let keep = bits.min(60);
    let top = (num >> (bits - keep)).iter_u64_digits().next().unwrap_or(0) as f64;
    top * ((bits - keep) as f64 - den_log2 as f64).exp2()
}

/// The ROM `{m_n, a_n}` as a table of the datapath.
pub fn table(fit: &Fit, w: &FittedWidths) -> Table {
    Table {
        name: "fit_rom".into(),
        param: "FIT_ROM_FILE".into(),
        width: w.rom_word_bits,
        words: fit.rom_words(w),
        what: format!(
            "per-n fit: {{m_n ({} bits), a_n (UQ{}.{})}}",
            w.m_bits,
            w.a_bits.saturating_sub(w.a_frac_bits),
            w.a_frac_bits
        ),
        fields: vec![("a_code".into(), w.a_bits), ("m".into(), w.m_bits)],
        cosines: None,
    }
}

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
fn squaring(w: &FittedWidths, b: &mut Builder, j: u32, m_max: u32, r: u32, sq_split: bool) {
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

/// The fit of a configuration, computed once per process for each (N, M, KA).
pub fn cached_fit(cfg: &Config) -> Arc<Fit> {
    type Cache = Mutex<HashMap<(u32, u32, u32), Arc<Fit>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let key = (cfg.n_bits(), cfg.max_squarings(), cfg.kf());
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(f) = cache.lock().expect("fit cache").get(&key) {
        return f.clone();
    }
    let fit = Arc::new(fit(cfg));
    cache
        .lock()
        .expect("fit cache")
        .entry(key)
        .or_insert(fit)
        .clone()
}

/// The fitted unit of one configuration: its fit and its widths.
#[derive(Debug, Clone)]
pub struct Fitted {
    pub(crate) cfg: Config,
    pub(crate) fit: Arc<Fit>,
    pub(crate) widths: FittedWidths,
}

impl Fitted {
    pub fn new(cfg: &Config) -> Fitted {
        let fit = cached_fit(cfg);
        let widths = FittedWidths::derive(cfg, &fit);
        Fitted {
            cfg: cfg.clone(),
            fit,
            widths,
        }
    }

    /// `S` with the stored `a_n`, in floating point.
    fn s(&self, x: Inputs) -> f64 {
        let n = x.n as usize;
        let a = self.fit.a_code[n] as f64 / (self.cfg.kf() as f64).exp2();
        let base = 1.0 - a * (1.0 - cosine(&self.cfg, x.cos_g));
        if base < 0.0 {
            0.0
        } else {
            base.powi(1 << self.fit.m[n])
        }
    }
}

impl SpecularUnit for Fitted {
    fn premise_role(&self) -> Option<crate::models::PremiseRole> {
        Some(crate::models::PremiseRole::Fit)
    }

    fn eval(&self, x: Inputs) -> Outputs {
        trace(&self.cfg, &self.fit, &self.widths, x).1
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), crate::error::Error> {
        check(&self.cfg, &self.fit, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        scaled(&self.cfg, self.s(x), x)
    }

    fn datapath(&self, b: &mut Builder) {
        datapath(&self.cfg, &self.fit, &self.widths, b)
    }

    fn describe(&self) -> Description {
        let p = &self.cfg.params;
        let (fi, m) = (p.intensity_frac_bits, p.max_squarings);
        Description {
            param_line: format!("k_frac_bits={} (fractional bits of a_n) max_squarings={m}", p.k_frac_bits),
            formula: vec![
                format!("S = [1 - a_n*(1 - cos_g)]^(2^m_n), m_n <= {m}, a_n and m_n per n from a minimax fit to cos^n"),
                "(quantised a_n in the fit ROM define the unit); S = 0 where the bracket is negative (done);".into(),
                format!("intensity = S (UQ1.{fi}), spec_X = S * ks_X."),
            ],
            rounding: "faithful: every output within 1 ulp of S with the stored a_n (|o - o*| < 1)".into(),
            datapath: format!("bracket and every square UQ1.{} (error budget in specgen's models/fitted.rs)", self.widths.frac_bits),
            done_meaning: "the bracket is negative: beyond the highlight",
            summary: "Fixed-point specular highlight unit, [1 - a_n*(1 - cos)]^(2^m_n) fitted per n to cos^n",
            computes: "[1 - a_n (1 - c)]^(2^m_n), minimax per n",
        }
    }

    fn widths(&self) -> serde_json::Value {
        serde_json::to_value(&self.widths).expect("widths serialise")
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        let cfg = &self.cfg;
        let (t, _) = trace(cfg, &self.fit, &self.widths, x);
        let wf = self.widths.frac_bits;
        let mut lines = vec![
            format!(
                "constant   a_n = {} (fit {:.9}) -> a_code = {}, m_n = {} (exponent 2^m_n = {})",
                exact_decimal(t.a_code, cfg.kf()),
                self.fit.a[x.n as usize],
                t.a_code,
                t.m,
                1u32 << t.m
            ),
            format!(
                "datapath   one_minus_cos = {}  a_n*(1 - cos) = {}  done = {}",
                t.one_minus_cos, t.product, t.done
            ),
        ];
        for j in 0..=cfg.max_squarings() as usize {
            lines.push(format!(
                "           power{j} = {} (UQ1.{wf} = {:.9})",
                t.squares[j],
                t.squares[j] as f64 / (wf as f64).exp2()
            ));
        }
        lines.push(explain_ideal(
            self.ideal(x),
            "(the fitted formula with the stored a_n)",
        ));
        lines
    }
}
