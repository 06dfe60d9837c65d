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

mod datapath;
pub use datapath::datapath;

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
