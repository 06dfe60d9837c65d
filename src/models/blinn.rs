//! `--model blinn` (SPEC §6): Blinn's `c^n` itself, faithfully, from a log2 and an exp2
//! table with linear interpolation — the way GPUs raise to a power.
//!
//! # Datapath (all unsigned; W = max(FI, B))
//!
//! ```text
//! C     = min(cos_g, 2^F)                      UQ1.F      c = C/2^F; C = 0 → S = 0 (n ≥ 1)
//! e     = F − bitlen(C − 1)                    0..F       normalise: c = c'·2^−e, c' ∈ (1/2, 1]
//! X     = 2^F − (C << e)                       UQ0.F      x = 1 − c' ∈ [0, 1/2), exact
//! ĝ     = G[i] + ⌊ΔG[i]·r / 2^RB⌋              UQ2.WG     g(x) = −log2(1 − x)/x, i = top TG bits of 2x
//! L     = X·ĝ                                  UQ1.(F+WG) −log2 c' = x·g(x), exact product
//! ℓ     = ⌊(e + L)⌋ to WL fractional bits      −log2 c    truncation #1
//! y     = ⌊n·ℓ⌋ to WY fractional bits, ≤ W+2   −log2 c^n  truncation #2, saturated
//! Ê     = E[j] − ⌊ΔE[j]·r' / 2^RE⌋             UQ1.WE     2^−frac(y), j = top TE bits of frac(y)
//! V     = ⌊Ê / 2^⌊y⌋⌋                          UQ1.WE     truncation #3
//! out   = ⌊(V·2^FI + 2^(WE−1)) / 2^WE⌋; spec = ⌊(⌊V/2^(WE−WC)⌋·ks + 2^(WC−1)) / 2^WC⌋; done = (intensity == 0)
//! ```
//!
//! # Error budget (the argument [`BlinnWidths::derive`] applies)
//!
//! Write `y* = −n·log2 c` and `ŷ = y* + δ`. The sources of δ:
//! - the g table: entries rounded to nearest (≤ 2^−(WG+1), plus 2^−50 for the f64 they are
//!   computed in), linear interpolation between them (≤ h²/8·max g'', h = 2^−(TG+1); g'' grows
//!   on [0, 1/2], so its maximum is g''(1/2), summed from g's series), the floor of the
//!   interpolation product (< 2^−WG): together `εg`. It enters as `n·x·εg`, and since
//!   `c^n ≤ (1 − x)^n ≤ e^(−nx)`, `c^n·n·x·εg ≤ εg/e`: the relative form `x·g(x)` is what
//!   keeps this independent of n;
//! - truncation #1: `n·2^−WL < 2^(N−WL)`;   truncation #2: `< 2^−WY`.
//!
//! `|2^−ŷ − 2^−y*| ≤ 2^−y*·|δ|·ln2·2^|δ|`, and `c^n·|δ|·2^|δ|` is at most
//! `εg/(e·(1 − εg·ln2)) + (2^(N−WL) + 2^−WY)·1.01` (the 1.01 covers `2^|δ|` for the two small
//! terms, which the budget makes < 2^−W−3). The exp table adds `εE` (entries ≤ 2^−(WE+1) +
//! 2^−50, interpolation of the convex 2^−f ≤ ln²2/8·2^−2TE, the floor < 2^−WE), shrunk by the
//! shift, and truncation #3 adds < 2^−WE. In output units (`Mo ≤ 2^W`) the value fed to the
//! final rounding is within
//!
//! ```text
//! T = 2^W·[ ln2·(εg/(e(1−εg ln2)) + 1.01·(2^(N−WL) + 2^−WY)) + εE + 2^−WE ]
//! ```
//!
//! of `o*` (for the colours, `T·2^(B−W)` plus the floor of V to WC bits, `< 2^(B−WC)`).
//! [`BlinnWidths::derive`] gives each width a share of the 1/2 ([`Shares`]) and picks
//! the smallest width that keeps it; the
//! final round-half-up then gives `|o − o*| < 1`, and `o = o*` where `o*` is an integer.
//! Saturating y at `W + 2` only replaces outputs whose ideal is `< 2^−2·2^W/2^W·...` — below
//! 1/4 ulp — by 0, inside the same bound.
//!
//! Monotonicity: the tables are monotone (g rises, 2^−f falls; rounding keeps order), each
//! interpolation stays between its two entries, products, floors and the shift are monotone,
//! so ŷ never rises as `cos_g` grows within one exponent e. Across a power of two ŷ is
//! continuous from below only if `L ≤ 1` at the top of the range: the budget also requires
//! `εg/2 ≤ 0.9·(1 − L(1/2 − 2^−F))`, checked in [`BlinnWidths::derive`].

use super::{check_cos_n, cosine, explain_ideal, scaled, Description, Inputs, Outputs, SpecularUnit};
use crate::bits::{bit_length, lit, mask};
use crate::config::Config;
use crate::datapath::{Builder, Piece, LUT_DELAY};
use crate::table::Table;
use serde::Serialize;

/// Every width and table size of the blinn unit, from the error budget.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct BlinnWidths {
    /// W = max(FI, B).
    pub out_bits: u32,
    /// Bits of the exponent e ∈ [0, F].
    pub exp_bits: u32,
    /// TG: the log table has 2^TG entries.
    pub log_index_bits: u32,
    /// WG: fractional bits of g.
    pub log_frac_bits: u32,
    /// Bits of a G entry and of a ΔG entry.
    pub log_entry_bits: u32,
    pub log_delta_bits: u32,
    /// WL: fractional bits of ℓ = −log2 c.
    pub ell_frac_bits: u32,
    /// WY: fractional bits of y; YI its integer bits (saturated at W + 2).
    pub y_frac_bits: u32,
    pub y_int_bits: u32,
    /// TE: the exp table has 2^TE entries.
    pub exp2_index_bits: u32,
    /// WE: fractional bits of 2^−f.
    pub exp2_frac_bits: u32,
    pub exp2_entry_bits: u32,
    pub exp2_delta_bits: u32,
    /// WC: fractional bits of c^n fed to the colour multipliers (the colours' own budget).
    pub color_frac_bits: u32,
}

/// The budget terms in output units; their sum must be < 1/2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    pub(crate) log_table: f64,
    pub(crate) ell_truncation: f64,
    pub(crate) y_truncation: f64,
    pub(crate) exp2_table: f64,
    pub(crate) shift_truncation: f64,
    /// `εg/2` against the room `1 − L(1/2 − 2^−F)` below the next exponent (must be ≤ 0.9).
    pub(crate) monotone_ratio: f64,
}

impl Budget {
    pub(crate) fn total(&self) -> f64 {
        self.log_table + self.ell_truncation + self.y_truncation + self.exp2_table + self.shift_truncation
    }
    pub fn holds(&self) -> bool {
        self.total() < 0.5 && self.monotone_ratio <= 0.9
    }
}

/// The budget's shares, each a condition on one width (all together: `T ≤ 0.448 < 1/2`):
/// WY: truncation #2 ≤ 1/16; WL: truncation #1 ≤ 1/16; WG: the log entries' own rounding
/// (table as fine as X, no interpolation) ≤ 1/12 and ≤ 0.45 of the monotone room; TG: the
/// whole log term ≤ 1/6 and ≤ 0.9 of the room; WE: the exp entries' rounding (no
/// interpolation) plus truncation #3 ≤ 1/12; TE: the whole exp term plus truncation #3 ≤ 5/32.
pub struct Shares;

impl Shares {
    pub fn y_truncation(w: &BlinnWidths, cfg: &Config) -> bool {
        w.budget(cfg).y_truncation <= 1.0 / 16.0
    }
    pub fn ell_truncation(w: &BlinnWidths, cfg: &Config) -> bool {
        w.budget(cfg).ell_truncation <= 1.0 / 16.0
    }
    pub fn log_entries(w: &BlinnWidths, cfg: &Config) -> bool {
        // the entries' rounding and the interpolation's floor, without the interpolation error
        let eps = 1.5 * (-(w.log_frac_bits as f64)).exp2() + (-50f64).exp2();
        let b = w.budget(cfg);
        let room = b.monotone_ratio / w.eps_g(cfg);
        let ln2 = std::f64::consts::LN_2;
        (w.out_bits as f64).exp2() * ln2 * eps / (std::f64::consts::E * (1.0 - eps * ln2)) <= 1.0 / 12.0 && eps * room <= 0.45
    }
    pub fn log_table(w: &BlinnWidths, cfg: &Config) -> bool {
        let b = w.budget(cfg);
        w.log_index_bits >= cfg.f() - 1 || (b.log_table <= 1.0 / 6.0 && b.monotone_ratio <= 0.9)
    }
    pub fn exp2_entries(w: &BlinnWidths, _cfg: &Config) -> bool {
        // the entries' rounding, the interpolation's floor and truncation #3
        (w.out_bits as f64).exp2() * (2.5 * (-(w.exp2_frac_bits as f64)).exp2() + (-50f64).exp2()) <= 1.0 / 12.0
    }
    pub fn exp2_table(w: &BlinnWidths, cfg: &Config) -> bool {
        let b = w.budget(cfg);
        w.exp2_index_bits >= w.y_frac_bits || b.exp2_table + b.shift_truncation <= 5.0 / 32.0
    }
}

/// `max g''` on [0, 1/2]: g'' = (1/ln2)·Σ_{k≥2} k(k−1)/(k+1)·x^(k−2), rising in x.
fn g2_max() -> f64 {
    let s: f64 = (2..400).map(|k| (k * (k - 1)) as f64 / (k + 1) as f64 * 0.5f64.powi(k - 2)).sum();
    s / std::f64::consts::LN_2 * 1.001
}

/// `g(x) = −log2(1 − x)/x`, `g(0) = 1/ln2`.
pub fn g(x: f64) -> f64 {
    if x == 0.0 {
        1.0 / std::f64::consts::LN_2
    } else {
        -(-x).ln_1p() / (x * std::f64::consts::LN_2)
    }
}

impl BlinnWidths {
    /// `εg`: the g table's error (entries, interpolation, its floor).
    pub(crate) fn eps_g(&self, cfg: &Config) -> f64 {
        let p = |k: i64| (k as f64).exp2();
        let (tg, wg) = (self.log_index_bits as i64, self.log_frac_bits as i64);
        let interpolates = tg < cfg.f() as i64 - 1;
        p(-wg - 1) + p(-50) + if interpolates { g2_max() / 8.0 * p(-2 * (tg + 1)) + p(-wg) } else { 0.0 }
    }

    /// The error budget for a choice of widths (see the module documentation).
    pub fn budget(&self, cfg: &Config) -> Budget {
        let ln2 = std::f64::consts::LN_2;
        let p = |k: i64| (k as f64).exp2();
        let (w, n, f) = (self.out_bits as i64, cfg.n_bits() as i64, cfg.f() as i64);
        let (wl, wy) = (self.ell_frac_bits as i64, self.y_frac_bits as i64);
        let (te, we) = (self.exp2_index_bits as i64, self.exp2_frac_bits as i64);
        let eps_g = self.eps_g(cfg);
        let interpolates_e = te < wy;
        let eps_e = p(-we - 1) + p(-50) + if interpolates_e { ln2 * ln2 / 8.0 * p(-2 * te) + p(-we) } else { 0.0 };
        let l_top = -(0.5 + p(-f)).log2();
        Budget {
            log_table: p(w) * ln2 * eps_g / (std::f64::consts::E * (1.0 - eps_g * ln2)),
            ell_truncation: p(w) * ln2 * 1.01 * p(n - wl),
            y_truncation: p(w) * ln2 * 1.01 * p(-wy),
            exp2_table: p(w) * eps_e,
            shift_truncation: p(w) * p(-we),
            monotone_ratio: eps_g / 2.0 / (1.0 - l_top),
        }
    }

    /// The shares of the budget's `1/2`, one per width: each width is the smallest that keeps
    /// its share, so removing any one bit breaks the budget as written (see [`Shares`]).
    pub fn derive(cfg: &Config) -> BlinnWidths {
        let f = cfg.f();
        let w = cfg.fi().max(cfg.b());
        let mut bw = BlinnWidths {
            out_bits: w,
            exp_bits: bit_length(f as u128),
            log_index_bits: 1,
            log_frac_bits: 1,
            log_entry_bits: 0,
            log_delta_bits: 0,
            ell_frac_bits: 1,
            y_frac_bits: 1,
            y_int_bits: bit_length((w + 2) as u128),
            exp2_index_bits: 1,
            exp2_frac_bits: cfg.fi() + 1,
            exp2_entry_bits: 0,
            exp2_delta_bits: 0,
            color_frac_bits: 0,
        };
        while !Shares::y_truncation(&bw, cfg) {
            bw.y_frac_bits += 1;
        }
        bw.ell_frac_bits = bw.y_frac_bits;
        while !Shares::ell_truncation(&bw, cfg) {
            bw.ell_frac_bits += 1;
        }
        while !Shares::log_entries(&bw, cfg) {
            bw.log_frac_bits += 1;
        }
        while !Shares::log_table(&bw, cfg) {
            bw.log_index_bits += 1;
        }
        while !Shares::exp2_entries(&bw, cfg) {
            bw.exp2_frac_bits += 1;
        }
        while !Shares::exp2_table(&bw, cfg) {
            bw.exp2_index_bits += 1;
        }
        let b = bw.budget(cfg);
        assert!(b.holds(), "blinn budget does not close for {:?}: {b:?}", cfg.params);
        // WC: the colours see the same error scaled by ks/2^W < 2^(B−W), plus flooring V to
        // WC bits (< 2^(B−WC) in colour units): the smallest WC with a sum below 1/2
        let p = |k: i64| (k as f64).exp2();
        let tc = b.total() * p(cfg.b() as i64 - w as i64);
        bw.color_frac_bits = (1..=bw.exp2_frac_bits).find(|&wc| tc + p(cfg.b() as i64 - wc as i64) < 0.5).unwrap_or(bw.exp2_frac_bits);
        let (lt, et) = (log_values(&bw), exp2_values(&bw));
        bw.log_entry_bits = bit_length(*lt.iter().max().unwrap());
        bw.log_delta_bits = bit_length(lt.windows(2).map(|p| p[1] - p[0]).max().unwrap()).max(1);
        bw.exp2_entry_bits = bit_length(et[0]);
        bw.exp2_delta_bits = bit_length(et.windows(2).map(|p| p[0] - p[1]).max().unwrap()).max(1);
        bw
    }

    /// RB: the interpolation fraction of the log table (bits of X below its index).
    pub(crate) fn log_rest_bits(&self, cfg: &Config) -> u32 {
        cfg.f() - 1 - self.log_index_bits
    }
    /// RE: the interpolation fraction of the exp table.
    pub(crate) fn exp2_rest_bits(&self) -> u32 {
        self.y_frac_bits - self.exp2_index_bits
    }
    /// Bits of ĝ and of L = X·ĝ.
    pub(crate) fn ghat_bits(&self) -> u32 {
        self.log_entry_bits.max(self.log_frac_bits + 1) + 1
    }
    /// ℓ = e + L < F + 1 ≤ 2^exp_bits (e ≤ F, L < 1): exp_bits integer bits hold it.
    pub(crate) fn ell_bits(&self) -> u32 {
        self.exp_bits + self.ell_frac_bits
    }
    pub(crate) fn y_bits(&self) -> u32 {
        self.y_int_bits + self.y_frac_bits
    }
    /// The saturation value of y, `(W + 2)·2^WY`.
    pub(crate) fn y_sat(&self) -> u128 {
        ((self.out_bits + 2) as u128) << self.y_frac_bits
    }
}

/// `G_i = round(g(i/2^(TG+1))·2^WG)` for `i = 0..=2^TG` (the last only for ΔG).
fn log_values(w: &BlinnWidths) -> Vec<u128> {
    let count = 1u32 << w.log_index_bits;
    (0..=count)
        .map(|i| {
            let x = i as f64 / (2 * count) as f64;
            (g(x) * (w.log_frac_bits as f64).exp2()).round() as u128
        })
        .collect()
}

/// `E_j = round(2^−(j/2^TE)·2^WE)` for `j = 0..=2^TE` (`E_0 = 2^WE`, the last `2^(WE−1)`).
fn exp2_values(w: &BlinnWidths) -> Vec<u128> {
    let count = 1u32 << w.exp2_index_bits;
    (0..=count).map(|j| ((-(j as f64) / count as f64).exp2() * (w.exp2_frac_bits as f64).exp2()).round() as u128).collect()
}

/// The two tables of the unit, each word `{Δ, entry}`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BlinnTables {
    pub(crate) g: Vec<u128>,
    pub(crate) dg: Vec<u128>,
    pub(crate) e: Vec<u128>,
    pub(crate) de: Vec<u128>,
}

pub fn tables(w: &BlinnWidths) -> BlinnTables {
    let (lv, ev) = (log_values(w), exp2_values(w));
    BlinnTables {
        g: lv[..lv.len() - 1].to_vec(),
        dg: lv.windows(2).map(|p| p[1] - p[0]).collect(),
        e: ev[..ev.len() - 1].to_vec(),
        de: ev.windows(2).map(|p| p[0] - p[1]).collect(),
    }
}

/// How an interpolation table's word carries its step for a DSP block whose post-adder adds
/// the entry: the step in a field `a_bits` wide, and above it `b_pad` zero bits that widen the
/// other operand (the interpolation fraction) to the block's width. yosys 0.23 puts an add in
/// the iCE40's SB_MAC16 only when the sum is no wider than the operands it sees, and an
/// operand's zero bits from a table are bits it sees (constant ones it strips); the block RAM
/// then drops the constant bits again, so they cost nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OperandPad {
    pub(crate) a_bits: u32,
    pub(crate) b_pad: u32,
}

/// An interpolation table: word i = `{Δ_i, entry_i}` (the entry in the low bits; with `pad`,
/// `{0, Δ_i, entry_i}`, the step in its field and the zero bits above it), one name for the
/// memory, its file and its `FILE` parameter.
fn interpolation_table(name: &str, entries: &[u128], deltas: &[u128], bits: (u32, u32), pad: Option<OperandPad>, what: String, fields: (&str, &str)) -> Table {
    let (entry_bits, delta_bits) = bits;
    let (delta_field, zeros) = pad.map_or((delta_bits, 0), |p| (p.a_bits, p.b_pad));
    let mut f = vec![(fields.0.into(), entry_bits), (fields.1.into(), delta_field)];
    if zeros > 0 {
        f.push(("zero".into(), zeros));
    }
    Table {
        name: format!("{name}_rom"),
        param: format!("{}_ROM_FILE", name.to_uppercase()),
        width: delta_field + entry_bits + zeros,
        words: entries.iter().zip(deltas).map(|(&e, &d)| (d << entry_bits) | e).collect(),
        what,
        fields: f,
        cosines: None,
    }
}

impl BlinnTables {
    pub fn log_table(&self, w: &BlinnWidths, pad: Option<OperandPad>) -> Table {
        let what = format!("{{dG, G}}: g(x) = -log2(1 - x)/x at x = i/2^{}, UQ2.{}, and the step to the next entry", w.log_index_bits + 1, w.log_frac_bits);
        interpolation_table("log2", &self.g, &self.dg, (w.log_entry_bits, w.log_delta_bits), pad, what, ("g", "dg"))
    }
    /// The exp2 table as stored: `E_0 = 1.0` is the only entry with its integer bit set when
    /// [`BlinnTables::exp2_one_implied`], and then that bit is not stored but read as `j == 0`
    /// (one word bit fewer: 2 block RAMs for 256 words instead of 3).
    pub fn exp2_table(&self, w: &BlinnWidths, pad: Option<OperandPad>) -> Table {
        let implied = self.exp2_one_implied(w);
        let stored_bits = w.exp2_entry_bits - implied as u32;
        let entries: Vec<u128> = self.e.iter().map(|&e| e & mask(stored_bits)).collect();
        let what = if implied {
            format!(
                "{{dE, E mod 1}}: 2^-f at f = j/2^{}, UQ0.{} (its integer bit, set for j = 0 only, is j == 0), and the step down to the next entry",
                w.exp2_index_bits, w.exp2_frac_bits
            )
        } else {
            format!("{{dE, E}}: 2^-f at f = j/2^{}, UQ1.{}, and the step down to the next entry", w.exp2_index_bits, w.exp2_frac_bits)
        };
        interpolation_table("exp2", &entries, &self.de, (stored_bits, w.exp2_delta_bits), pad, what, ("e", "de"))
    }

    /// Whether E_0 = 2^WE is the only exp2 entry at or above 1.0.
    pub(crate) fn exp2_one_implied(&self, w: &BlinnWidths) -> bool {
        w.exp2_entry_bits == w.exp2_frac_bits + 1 && self.e[1..].iter().all(|&e| e < 1u128 << w.exp2_frac_bits)
    }
}

/// Every intermediate value of the blinn datapath for one input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BlinnTrace {
    pub(crate) cos_clamped: u64,
    pub(crate) exponent: u32,
    pub(crate) x: u64,
    pub(crate) ghat: u128,
    pub(crate) ell: u128,
    pub(crate) y: u128,
    pub(crate) ehat: u128,
    pub(crate) v: u128,
}

/// The bit-exact golden model.
pub fn trace(cfg: &Config, w: &BlinnWidths, t: &BlinnTables, x: Inputs) -> (BlinnTrace, Outputs) {
    let (f, fi, b) = (cfg.f(), cfg.fi(), cfg.b());
    let c = (x.cos_g as u64 & mask(f + 1) as u64).min(1 << f);
    let n = x.n as u128 & mask(cfg.n_bits());
    let zero = c == 0;
    let cm1 = c.wrapping_sub(1) & mask(f) as u64;
    let e = f - bit_length(cm1 as u128);
    let cn = (c << e) & mask(f + 1) as u64;
    let xx = ((1u64 << f).wrapping_sub(cn)) & mask(f - 1) as u64;
    let rb = w.log_rest_bits(cfg);
    let (i, r) = ((xx >> rb) as usize, xx as u128 & mask(rb));
    let ghat = t.g[i] + ((t.dg[i] * r) >> rb);
    let l = xx as u128 * ghat; // frac F + WG
    let lf = f + w.log_frac_bits;
    let full = ((e as u128) << lf) + l;
    let ell = if lf >= w.ell_frac_bits { full >> (lf - w.ell_frac_bits) } else { full << (w.ell_frac_bits - lf) };
    let y_full = (n * ell) >> (w.ell_frac_bits - w.y_frac_bits);
    let y = if (zero && n != 0) || y_full >= w.y_sat() { w.y_sat() } else { y_full };
    let (yint, yfrac) = ((y >> w.y_frac_bits) as u32, y & mask(w.y_frac_bits));
    let re = w.exp2_rest_bits();
    let (j, rr) = ((yfrac >> re) as usize, yfrac & mask(re));
    let ehat = t.e[j] - ((t.de[j] * rr) >> re);
    let v = ehat >> yint;
    let we = w.exp2_frac_bits;
    let intensity = ((v + (1u128 << (we - fi - 1))) >> (we - fi)) as u32;
    let wc = w.color_frac_bits;
    let vc = v >> (we - wc);
    let spec = x.ks.map(|k| ((vc * (k as u128 & mask(b)) + (1u128 << (wc - 1))) >> wc) as u32);
    (BlinnTrace { cos_clamped: c, exponent: e, x: xx, ghat, ell, y, ehat, v }, Outputs { spec, intensity, done: intensity == 0 })
}

/// The operands of an interpolation's DSP block: the step `delta` and the fraction `r`, each
/// at the block's width when the table word carries them so (`pad`: the step's field, and the
/// zero bits above it that widen `r`).
fn operands(delta: Piece, r: Piece, word: &str, pad: Option<OperandPad>) -> (Vec<Piece>, Vec<Piece>) {
    match (pad, &delta) {
        (Some(p), Piece::Sig { lo, .. }) => (vec![Piece::sig(word, *lo, p.a_bits)], vec![r, Piece::sig(word, lo + p.a_bits, p.b_pad)]),
        _ => (vec![delta], vec![r]),
    }
}

/// A multiplier of at most this many bits is worth shift-adds rather than a DSP block.
const SHIFT_ADD_BITS: u32 = 5;

/// The blinn datapath: normalise, log2 by table, times n, exp2 by table, shift, round.
pub fn datapath(cfg: &Config, w: &BlinnWidths, t: &BlinnTables, b: &mut Builder) {
    let (f, fi, bb, nb) = (cfg.f(), cfg.fi(), cfg.b(), cfg.n_bits());
    let cb = f + 1;
    // each interpolation on one DSP block where its operands fit (on the iCE40 with the
    // entry added inside it: the table word carries the operands at the block's width)
    let dsp = b.dsp_bits();
    let (rb, re) = (w.log_rest_bits(cfg), w.exp2_rest_bits());
    let (log_dsp, exp2_dsp) = (
        rb > 0 && w.log_delta_bits.max(rb) <= dsp && w.ghat_bits() + rb <= 2 * dsp,
        re > 0 && w.exp2_delta_bits.max(re) <= dsp && w.exp2_entry_bits + re <= 2 * dsp,
    );
    let pad = |on: bool, rest: u32| (on && b.family().pads_block_operands()).then_some(OperandPad { a_bits: dsp, b_pad: dsp - rest });
    let (log_pad, exp2_pad) = (pad(log_dsp, rb), pad(exp2_dsp, re));
    let lt = b.table(t.log_table(w, log_pad));
    let et = b.table(t.exp2_table(w, exp2_pad));

    b.step("clamp c = min(cos, 1)");
    let (top, g) = (b.bits("cos_g", f, f), b.r("cos_g"));
    // cos_g >= 1.0 exactly when its integer bit is set: a mux, no comparator
    b.wire("cos_clamped", cb, Builder::select_const(&top, 1u128 << f, cb, &g), &format!("UQ1.{f}: c"));
    b.delay(LUT_DELAY);

    // c - 2^-F = c + (2^(F+1) - 1) mod 2^(F+1): a carry-select add of the all-ones word
    let title = "c - 1 for the normalisation";
    b.step(&format!("{title}; c = 0"));
    let p = b.add_start(
        "cos_minus_ulp",
        &[Piece::sig("cos_clamped", 0, cb)],
        &[Piece::Const { value: mask(cb), width: cb }],
        false,
        cb,
        &format!("UQ1.{f}: c - 2^-{f} (its leading zeros give the exponent)"),
    );
    let zc = b.r("cos_clamped");
    b.wire("cos_zero", 1, format!("{zc} == {}", lit(cb, 0)), "c = 0: c^n = 0 for n >= 1");
    b.delay(2.0 * LUT_DELAY);
    b.resolve(p, title);

    // e = the leading zeros of c - 2^-F over its F fraction bits, in two LUT steps: per group
    // of 4 bits from the top, whether it has a one and where its first one is; then the
    // first group with a one
    let eb = w.exp_bits;
    let groups: Vec<(u32, u32)> = (0..f.div_ceil(4)).map(|k| (f - 4 * k, (f - 4 * k).min(4))).collect(); // (top + 1, width)
    b.step("normalise: the exponent e, per group of 4 bits of c - 2^-F");
    // each group's (has a one, leading zeros)
    let mut leads = Vec::new();
    for (k, &(hi, gw)) in groups.iter().enumerate() {
        let bits = b.bits("cos_minus_ulp", hi - 1, hi - gw);
        let any = b.wire(&format!("lead_any{k}"), 1, format!("|{bits}"), &format!("bits [{}:{}] of c - 2^-{f} have a one", hi - 1, hi - gw));
        // its first one at j from the top: bits above it 0, bit j 1 (the last j: when the
        // group has a one, it is there if nowhere above); each bit of j an OR of those
        // conditions, no ?: of constants ([`Builder::select`])
        let bit = |b: &mut Builder, j: u32| b.bits("cos_minus_ulp", hi - 1 - j, hi - 1 - j);
        let first_at: Vec<String> = (0..gw)
            .map(|j| {
                let mut terms: Vec<String> = (0..j).map(|i| format!("~{}", bit(b, i))).collect();
                if j + 1 < gw {
                    terms.push(bit(b, j));
                }
                if terms.is_empty() {
                    "1'b1".to_string()
                } else {
                    format!("({})", terms.join(" & "))
                }
            })
            .collect();
        let lz_bit = |v: u32| {
            let ors: Vec<&str> = (0..gw).filter(|j| j >> v & 1 == 1).map(|j| first_at[j as usize].as_str()).collect();
            if ors.is_empty() {
                "1'b0".to_string()
            } else {
                ors.join(" | ")
            }
        };
        let (b1, b0) = (lz_bit(1), lz_bit(0));
        leads.push((any, b.wire(&format!("lead_zeros{k}"), 2, format!("{{{b1},\n    {b0}}}"), "its leading zeros (when it has a one)")));
    }
    b.delay(LUT_DELAY);
    b.step("normalise: e = the leading zeros of c - 2^-F");
    let mut cases = Vec::new();
    for (k, (any, lz)) in leads.iter().enumerate() {
        let (any, lz) = (b.r(any), b.r(lz));
        cases.push(format!("{any} ? {{{}, {lz}}}", lit(eb - 2, k as u128)));
    }
    cases.push(lit(eb, f as u128));
    b.wire("exponent", eb, cases.join("\n    : "), &format!("e = F - bitlength(C - 1) in 0..{f}: leading zeros of c - 2^-{f}"));
    // beside it, the one case the tables do not cover, carried as one bit
    let (z, nn) = (b.r("cos_zero"), b.r("n"));
    b.wire("y_zero_power", 1, format!("{z} && ({nn} != {})", lit(nb, 0)), "c = 0 with n >= 1: c^n = 0 (y saturates)");
    b.delay(2.0 * LUT_DELAY);

    // c' = c*2^e, one bit of e a step from the top: a 2:1 mux level each, so the bit that
    // fans out over the whole word drives one LUT level; the last also inverts c' for
    // x = -c' = ~c' + 1
    let mut src = "cos_clamped".to_string();
    for k in (0..eb).rev() {
        let last = k == 0;
        let name = if last { "cos_norm".to_string() } else { format!("cos_norm_shift{k}") };
        b.step(&if last { "normalise: c' = c*2^e in (1/2, 1], its complement".to_string() } else { format!("normalise: c shifted by e's bit {k}") });
        let (c, ek) = (b.r(&src), b.bits("exponent", k, k));
        // 2^k <= F < F + 1: bit k of e never shifts the whole word out
        let shifted = format!("{{{}, {}}}", b.bits(&src, cb - 1 - (1 << k), 0), lit(1 << k, 0));
        let what = if last { format!("UQ1.{f}: c' = c*2^e in (1/2, 1]") } else { format!("UQ1.{f}: c*2^(e's bits from {k} up)") };
        b.wire(&name, cb, Builder::select(&ek, &shifted, &c, cb), &what);
        if last {
            let cn = b.bits("cos_norm", f - 2, 0);
            b.wire("cos_norm_inv", f - 1, format!("~{cn}"), &format!("~c' over its low {} bits", f - 1));
        }
        b.delay(LUT_DELAY);
        src = name;
    }
    // x = 1 - c' < 1/2: only the low F-1 bits of 2^F - c', i.e. of -c' = ~c' + 1
    let title = "x = 1 - c'";
    b.step(title);
    let p = b.add_start("x", &[Piece::sig("cos_norm_inv", 0, f - 1)], &[], true, f - 1, &format!("UQ0.{f} (top bit 0): x = 1 - c' in [0, 1/2), exact"));
    b.resolve(p, title);
    // the table's address beside x (on ECP5 the block RAM's address register takes it)
    let tg = w.log_index_bits;
    let idx = b.bits("x", f - 2, rb);
    b.wire("log_index", tg, idx, &format!("i: 2x to {tg} bits"));

    b.ecp5_register_step("log2 table read: the address at the block RAM's address register");
    b.step(&format!("log2 table read: g(x) = -log2(1 - x)/x at the top {tg} bits of 2x"));
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
        let (dg, r, g) = (Piece::sig("log_word", ge, w.log_delta_bits), Piece::sig("x", 0, rb), Piece::sig("log_word", 0, ge));
        let (a, r) = operands(dg, r, "log_word", log_pad);
        let comment = format!("G[i]*2^{rb} + dG[i]*(x mod 2^-{}), exact; g^ = bits [{}:{rb}], UQ2.{}", tg + 1, sw - 1, w.log_frac_bits);
        let sum = b.multiply_add("ghat_sum", &a, &r, &[Piece::zeros(rb), g], sw, title, &comment);
        if b.instantiated_blocks() {
            let e = b.bits(&sum, sw - 1, rb);
            b.wire("ghat", gb, e, &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits));
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
        let mut terms = b.partial_products("ghat_sum", &Piece::sig("log_word", ge, w.log_delta_bits), &Piece::sig("x", 0, rb), 0, sw, false);
        terms.push(vec![Piece::zeros(rb), Piece::sig("log_word", 0, ge)]);
        let p = b.sum_start("ghat_sum", terms, sw, title, &format!("G[i]*2^{rb} + dG[i]*(x mod 2^-{}), exact", tg + 1));
        let sum = b.resolve(p, title);
        let e = b.bits(&sum, sw - 1, rb);
        b.wire("ghat", gb, e, &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits));
    } else {
        b.step(title);
        let e = b.operand("log_word", 0, ge, gb);
        b.wire("ghat", gb, e, &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits));
    }

    let lf = f + w.log_frac_bits;
    let eb2 = w.ell_bits();
    let lb = f - 1 + gb;
    // g wider than a DSP's operands: g = g_hi*2^D + g_lo; x*g_lo on one DSP, then the bits of
    // L above D as x*g_hi (its few partial products) plus x*g_lo/2^D in one carry-save sum
    if f - 1 <= dsp && gb > dsp && gb - dsp <= SHIFT_ADD_BITS {
        b.step("-log2 c' = x*g(x): x*g_lo (multiplier); the partial products of x*g_hi");
        let lw = f - 1 + dsp;
        b.product("log_frac_lo", &[Piece::sig("x", 0, f - 1)], &[Piece::sig(&ghat.0, ghat.1, dsp)], lw, &format!("x*ghat[{}:0], exact", dsp - 1));
        // beside the DSP (they do not wait for it), x*g_hi's partial products
        let t = "-log2 c' = x*g(x)";
        let hw = lb - dsp;
        let mut terms = b.partial_products("log_frac_hi", &Piece::sig("x", 0, f - 1), &Piece::sig(&ghat.0, ghat.1 + dsp, gb - dsp), 0, hw, false);
        b.product_delay(f - 1, dsp, lw, 0.0);
        terms.push(vec![Piece::sig("log_frac_lo", dsp, lw - dsp)]);
        let p = b.sum_start("log_frac_hi", terms, hw, t, &format!("x*ghat[{}:{dsp}] + x*ghat[{}:0]/2^{dsp}, exact", gb - 1, dsp - 1));
        let hi = b.resolve(p, t);
        let (hv, lv) = (b.r(&hi), b.bits("log_frac_lo", dsp - 1, 0));
        b.wire("log_frac", lb, format!("{{{hv}, {lv}}}"), &format!("UQ1.{lf}: L = x*g(x) = -log2 c', exact"));
    } else {
        b.step("-log2 c' = x*g(x)");
        if ghat.0 != "ghat" {
            let e = b.bits(&ghat.0, ghat.1 + gb - 1, ghat.1);
            b.wire("ghat", gb, e, &format!("UQ2.{}: g(x) within the budget's eps_g", w.log_frac_bits));
        }
        let (xv, gv) = (b.zext("x", lb), b.zext("ghat", lb));
        b.wire("log_frac", lb, format!("{xv} * {gv}"), &format!("UQ1.{lf}: L = x*g(x) = -log2 c', exact"));
        b.product_delay(f - 1, gb, lb, 0.0);
    }
    // L = x*g < 1 (x < 1/2, g^ < 2: each interpolation stays below the next entry, and the
    // last is g(1/2) = 2), so e + L is a concatenation: e above L's fraction bits
    let e = b.r("exponent");
    let lbits = if lf >= w.ell_frac_bits {
        b.bits("log_frac", lf - 1, lf - w.ell_frac_bits)
    } else {
        let v = b.bits("log_frac", lf - 1, 0);
        format!("{{{v}, {}}}", lit(w.ell_frac_bits - lf, 0))
    };
    b.wire("ell", eb2, format!("{{{e}, {lbits}}}"), &format!("UQ{}.{}: e + L floored (truncation #1); L < 1", eb2 - w.ell_frac_bits, w.ell_frac_bits));

    // n*l from the bottom up, l in D-bit chunks: P_0 = n*l[D-1:0], and P_k = n*l[chunk k] +
    // floor(P_(k-1) / 2^D) on one DSP each (the add inside it); then n*l = {P_top, P_(top-1)
    // mod 2^D, .., P_0 mod 2^D}. A top chunk of a few bits is partial products instead.
    let yb = w.y_bits();
    let pb = nb + eb2;
    let chunks: Vec<(u32, u32)> = (0..eb2.div_ceil(dsp.min(eb2))).map(|i| (i * dsp, (eb2 - i * dsp).min(dsp))).collect();
    if nb <= dsp && chunks.len() > 1 {
        let mut low_words: Vec<String> = Vec::new();
        let last = chunks.len() - 1;
        for (k, &(lo, cw)) in chunks.iter().enumerate() {
            let width = nb + cw;
            let name = format!("y_part{k}");
            let what = format!("floor(n*l[{}:0] / 2^{lo}), exact", lo + cw - 1);
            if k == last && k > 0 && cw <= SHIFT_ADD_BITS {
                let t = "y = n*(-log2 c): the top bits of l";
                b.step(&format!("{t}: partial products"));
                let mut terms = b.partial_products(&name, &Piece::sig("n", 0, nb), &Piece::sig("ell", lo, cw), 0, width, false);
                let below = format!("y_part{}", k - 1);
                let bw = nb + chunks[k - 1].1;
                terms.push(vec![Piece::sig(&below, dsp, bw - dsp)]);
                let p = b.sum_start(&name, terms, width, t, &what);
                b.resolve(p, t);
            } else {
                // one DSP each, the chunk below added inside it (on the ECP5, after it)
                let t = format!("y = n*(-log2 c) (multiplier 7): n*l[{}:{lo}]", lo + cw - 1);
                b.step(&format!("{t} (one DSP)"));
                let (nn, l) = ([Piece::sig("n", 0, nb)], [Piece::sig("ell", lo, cw)]);
                if k == 0 {
                    b.product(&name, &nn, &l, width, &format!("{what} (one DSP)"));
                } else {
                    let below = Piece::sig(&format!("y_part{}", k - 1), dsp, nb + chunks[k - 1].1 - dsp);
                    b.multiply_add(&name, &nn, &l, &[below], width, &t, &format!("{what}: n*l[{}:{lo}] plus the chunk below", lo + cw - 1));
                }
            }
        }
        // each P_k's low D bits, read here (in the step of the last: a register holds the others)
        for k in (0..chunks.len()).rev() {
            let name = format!("y_part{k}");
            low_words.push(if k == last { b.r(&name) } else { b.bits(&name, dsp - 1, 0) });
        }
        b.wire("y_full", pb, format!("{{{}}}", low_words.join(", ")), &format!("UQ{}.{}: n*(-log2 c), exact", pb - w.ell_frac_bits, w.ell_frac_bits));
    } else {
        b.step("y = n*(-log2 c) (multiplier 7)");
        let (nv, lv) = (b.zext("n", pb), b.zext("ell", pb));
        b.wire("y_full", pb, format!("{nv} * {lv}"), &format!("UQ{}.{}: n*(-log2 c), exact", pb - w.ell_frac_bits, w.ell_frac_bits));
        b.product_delay(nb, eb2, pb, 0.0);
    }

    b.step("y truncated; its saturation");
    let drop = w.ell_frac_bits - w.y_frac_bits;
    let top = b.bits("y_full", pb - 1, drop);
    let ytw = pb - drop;
    b.wire("y_trunc", ytw, top, &format!("UQ{}.{}: truncation #2", ytw - w.y_frac_bits, w.y_frac_bits));
    // y >= (W + 2)*2^WY on its integer bits alone (the saturation value has no fraction):
    // some high bit set, or the low ones at least W + 2
    let sat_int = (w.out_bits + 2) as u128;
    let yiw = ytw - w.y_frac_bits;
    let mut flags = vec!["y_zero_power"];
    if sat_int < 1u128 << yiw {
        let k = bit_length(sat_int);
        let ge = b.at_least("y_trunc", w.y_frac_bits + k - 1, w.y_frac_bits, sat_int);
        b.wire("y_over_low", 1, ge, &format!("floor(y)'s low {k} bits reach {sat_int}"));
        flags.push("y_over_low");
        if yiw > k {
            let high = b.bits("y_trunc", ytw - 1, w.y_frac_bits + k);
            b.wire("y_over_high", 1, format!("|{high}"), &format!("floor(y) has a bit set above its low {k}"));
            flags.push("y_over_high");
        }
    } // else y_trunc cannot reach the saturation value
    b.delay(2.0 * LUT_DELAY);
    b.step("y saturated");
    let flags: Vec<String> = flags.iter().map(|f| b.r(f)).collect();
    b.wire("y_saturate", 1, flags.join(" || "), &format!("y reaches {} (or c = 0 with n >= 1)", w.out_bits + 2));
    let (sat, yt2) = (b.r("y_saturate"), b.operand("y_trunc", 0, ytw, yb));
    b.wire(
        "y",
        yb,
        Builder::select_const(&sat, w.y_sat(), yb, &yt2),
        &format!("UQ{}.{}: y, saturated at {} (every output is 0 from there on)", w.y_int_bits, w.y_frac_bits, w.out_bits + 2),
    );
    b.delay(LUT_DELAY);

    let te = w.exp2_index_bits;
    let ji = b.bits("y", w.y_frac_bits - 1, re);
    b.wire("exp2_index", te, ji, "j: frac(y) to the table's resolution");
    b.ecp5_register_step("exp2 table read: the address at the block RAM's address register");
    b.step(&format!("exp2 table read: 2^-f at the top {te} bits of frac(y)"));
    b.rom_read_registered("exp2_word", et, "exp2_index");
    b.ecp5_register_step("exp2 table read: the word at the multiplier's input registers");
    let implied = t.exp2_one_implied(w);
    if implied {
        let ji = b.r("exp2_index");
        b.wire("exp2_one", 1, format!("{ji} == {}", lit(te, 0)), "E's integer bit: 2^-f = 1.0 at j = 0 only");
    }
    b.delay(LUT_DELAY * te.div_ceil(2) as f64);

    let we = w.exp2_frac_bits;
    let ee = w.exp2_entry_bits;
    let es = ee - implied as u32; // E's bits in the word
    let mut e_word = vec![Piece::sig("exp2_word", 0, es)];
    if implied {
        e_word.push(Piece::sig("exp2_one", 0, 1));
    }
    let title = "2^-frac(y) by linear interpolation";
    let sw = ee + re;
    // set when E[j] - floor(dE[j]*r / 2^RE) is the complement of bits of exp2_sum
    let mut complemented = None;
    if exp2_dsp {
        // E[j]*2^RE + 2^RE - 1 - s = ~(s + ~(E[j]*2^RE + 2^RE - 1)) mod 2^sw for the step
        // s = dE[j]*r, and ~(E[j]*2^RE + 2^RE - 1) = {~E[j], RE zeros}: one DSP multiply-add,
        // the complemented entry its addend; the result's complement is taken in the LUTs of
        // the shift that follows (the DSP's output meets only a flip-flop)
        b.step(&format!("{title}: dE[j]*r + ~E[j]*2^{re} (multiplier)"));
        let mut addend = vec![Piece::zeros(re)];
        addend.extend(e_word.iter().map(|p| match p {
            Piece::Sig { name, lo, width, .. } => Piece::not(name, *lo, *width),
            Piece::Const { .. } => unreachable!("the entry is read from the table"),
        }));
        let (de, r) = (Piece::sig("exp2_word", es, w.exp2_delta_bits), Piece::sig("y", 0, re));
        let (a, r) = operands(de, r, "exp2_word", exp2_pad);
        let what = format!("~(E[j]*2^{re} + 2^{re} - 1 - dE[j]*(frac(y) mod 2^-{te})), exact");
        complemented = Some(b.multiply_add("exp2_sum", &a, &r, &addend, sw, title, &what));
    } else if re > 0 {
        // E[j] - floor(s / 2^RE) = floor((E[j]*2^RE + 2^RE - 1 - s) / 2^RE) for the step
        // s = dE[j]*r, and -s = the sum of its complemented partial products plus their count:
        // one carry-save sum, one carry chain at its end
        b.step(&format!("{title}: the partial products of dE[j]*r, complemented"));
        let mut terms = b.partial_products("exp2_sum", &Piece::sig("exp2_word", es, w.exp2_delta_bits), &Piece::sig("y", 0, re), 0, sw, true);
        let k = terms.len() as u128;
        let mut et = vec![Piece::zeros(re)];
        et.extend(e_word);
        terms.push(et);
        terms.push(vec![Piece::Const { value: (((1u128 << re) - 1) + k) & mask(sw), width: sw }]);
        let p = b.sum_start("exp2_sum", terms, sw, title, &format!("E[j]*2^{re} + 2^{re} - 1 - dE[j]*(frac(y) mod 2^-{te}), exact"));
        let sum = b.resolve(p, title);
        let e = b.bits(&sum, sw - 1, re);
        b.wire("exp2_frac", ee, e, &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"));
    } else {
        b.step(title);
        let e = b.pieces(&e_word);
        b.wire("exp2_frac", ee, e, &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"));
    }

    // the shift by the integer part of y, two of its bits a step (a 4:1 mux level each)
    let yib = w.y_int_bits;
    let mut src = "exp2_frac".to_string();
    let mut hi = yib;
    while hi > 0 {
        let lo = hi.saturating_sub(2);
        b.step(&format!("shift by the integer part of y: its bits [{}:{lo}]{}", hi - 1, if lo == 0 { " (truncation #3)" } else { "" }));
        if let Some(sum) = complemented.take() {
            let e = b.bits(&sum, sw - 1, re);
            b.wire("exp2_frac", ee, format!("~{e}"), &format!("UQ1.{we}: 2^-frac(y) within the budget's eps_E"));
        }
        let (sv, yi) = (b.r(&src), b.bits("y", w.y_frac_bits + hi - 1, w.y_frac_bits + lo));
        let name = if lo == 0 { "power".to_string() } else { format!("power_shift{lo}") };
        let comment = if lo == 0 { format!("UQ1.{we}: c^n before rounding") } else { format!("2^-frac(y) shifted by floor(y)'s bits above {lo}") };
        // a 4:1 mux as an AND-OR of the shifted words ([`Builder::select`])
        let terms: Vec<String> = (0..1u32 << (hi - lo))
            .filter(|v| v << lo < ee)
            .map(|v| {
                let shifted = if v == 0 { sv.clone() } else { format!("({sv} >> {})", v << lo) };
                Builder::gate(&format!("({yi} == {})", lit(hi - lo, v as u128)), &shifted, ee)
            })
            .collect();
        b.wire(&name, ee, terms.join("\n    | "), &comment);
        b.delay(2.0 * LUT_DELAY);
        src = name;
        hi = lo;
    }

    b.step("colour multipliers (14-16)");
    let wc = w.color_frac_bits;
    b.colour_products("power", we - wc, wc, "c^n");
    b.product_delay(wc + 1, bb, wc + bb, 0.0);
    // a step of its own, from a copy of c^n of its own: the register that feeds the colour
    // multipliers sits by the DSP column
    b.step("the intensity rounding: chunk sums; done");
    // round half up on the bits that matter: (power[WE:WE-FI-1] + 1) >> 1
    let p = b.add_start(
        "intensity_sum",
        &[Piece::sig("power", we - fi - 1, fi + 2)],
        &[],
        true,
        fi + 2,
        &format!("UQ1.{}: c^n to 2^-{} plus one ulp = c^n + 2^-{} (round half up)", fi + 1, fi + 1, fi + 1),
    );
    // the intensity is 0 exactly when c^n < 2^-(FI+1): its bits from 2^-(FI+1) up are all 0
    // (whether each group of 4 of them is 0 here, all of them in the last step)
    let (lo, hi) = (we - fi - 1, ee);
    let mut groups = Vec::new();
    for (k, g) in (lo..hi).step_by(4).enumerate() {
        let gh = (g + 4).min(hi);
        let bits = b.bits("power", gh - 1, g);
        let name = format!("done_zero{k}");
        b.wire(&name, 1, format!("~|{bits}"), &format!("bits [{}:{g}] of c^n are 0", gh - 1));
        groups.push(name);
    }
    // (on the ECP5, the colours' rounding half after their products)
    b.colour_rounding(wc, "c^n");
    let sum = b.resolve(p, "the intensity rounded half up");
    let zeros: Vec<String> = groups.iter().map(|g| b.r(g)).collect();
    b.wire("done", 1, zeros.join(" & "), "the highlight is below the output's resolution (the intensity rounds to 0)");
    b.colour_results(wc, "c^n");
    let e = b.bits(&sum, fi + 1, 1);
    b.wire("intensity", fi + 1, e, &format!("UQ1.{fi}: c^n rounded half up"));
}

/// The blinn unit of one configuration: its widths and its two tables.
#[derive(Debug, Clone)]
pub struct Blinn {
    pub(crate) cfg: Config,
    pub(crate) widths: BlinnWidths,
    pub(crate) tables: BlinnTables,
}

impl Blinn {
    pub fn new(cfg: &Config) -> Blinn {
        let widths = BlinnWidths::derive(cfg);
        let tables = tables(&widths);
        Blinn { cfg: cfg.clone(), widths, tables }
    }
}

impl SpecularUnit for Blinn {
    fn premise_role(&self) -> Option<crate::models::PremiseRole> {
        Some(crate::models::PremiseRole::Tables)
    }

    fn eval(&self, x: Inputs) -> Outputs {
        trace(&self.cfg, &self.widths, &self.tables, x).1
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), crate::error::Error> {
        check_cos_n(&self.cfg, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        scaled(&self.cfg, cosine(&self.cfg, x.cos_g).powi(x.n as i32), x)
    }

    fn datapath(&self, b: &mut Builder) {
        datapath(&self.cfg, &self.widths, &self.tables, b)
    }

    fn describe(&self) -> Description {
        let (p, bw) = (&self.cfg.params, &self.widths);
        Description {
            param_line: String::new(),
            formula: vec![
                "S = c^n, c = min(cos_g, 1.0), as 2^-(n*(e + x*g(x))) with c = (1 - x)*2^-e, x in [0, 1/2);".into(),
                format!(
                    "g from a {}-entry log2 table, 2^-f from a {}-entry exp2 table, both interpolated;",
                    1u32 << bw.log_index_bits,
                    1u32 << bw.exp2_index_bits
                ),
                format!("intensity = S (UQ1.{}), spec_X = S * ks_X; done = (intensity == 0).", p.intensity_frac_bits),
            ],
            rounding: "faithful: every output within 1 ulp of the exact c^n value (|o - o*| < 1)".into(),
            datapath: format!(
                "-log2 c UQ.{}, y UQ{}.{}, 2^-f UQ1.{} (error budget in specgen's models/blinn.rs)",
                bw.ell_frac_bits, bw.y_int_bits, bw.y_frac_bits, bw.exp2_frac_bits
            ),
            done_meaning: "intensity == 0: the highlight is below the output's resolution",
            summary: "Fixed-point Blinn specular unit, cos^n from log2/exp2 tables",
            computes: "c^n from log2/exp2 tables",
        }
    }

    fn widths(&self) -> serde_json::Value {
        serde_json::to_value(&self.widths).expect("widths serialise")
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        let (t, _) = trace(&self.cfg, &self.widths, &self.tables, x);
        let (w, f) = (&self.widths, self.cfg.f());
        vec![
            format!("datapath   c = {}  e = {}  x = {} (UQ0.{f})  g^ = {} (UQ2.{})", t.cos_clamped, t.exponent, t.x, t.ghat, w.log_frac_bits),
            format!(
                "           -log2 c = {} (= {:.9})  y = {} (UQ{}.{} = {:.9})  2^-frac(y) = {} (UQ1.{})  power = {}",
                t.ell,
                t.ell as f64 / (w.ell_frac_bits as f64).exp2(),
                t.y,
                w.y_int_bits,
                w.y_frac_bits,
                t.y as f64 / (w.y_frac_bits as f64).exp2(),
                t.ehat,
                w.exp2_frac_bits,
                t.v
            ),
            explain_ideal(self.ideal(x), "(c^n)"),
        ]
    }
}
