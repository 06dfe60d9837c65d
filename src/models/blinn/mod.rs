//! `--model blinn` (SPEC §6): Blinn's `c^n` itself, faithfully, from a log2 and an exp2
//! table with linear interpolation — the way GPUs raise to a power. Its home: the error budget
//! below and the widths it gives ([`BlinnWidths`]), the two tables (`tables.rs`), the golden
//! model (`golden.rs`) and the datapath (`datapath.rs`).
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
//!
//! # Its shape at 125 MHz on the UP5K
//!
//! At its deepest every step is at most two LUT levels, or one short carry chain, between
//! registers (a UP5K LUT level with its route is 2.5–3 ns of the 8 ns): `c = 0` and `n ≠ 0`
//! are ORed per 4 bits beside the clamp and finished in one LUT later; wide ORs and the
//! leading-zero pick keep their first LUT level (`(* keep *)`, [`Builder::wire_kept`]), which
//! yosys 0.70's ABC9 otherwise chains three deep; the exp2 table holds `~E` where the
//! interpolation's multiply-add takes it on the SB_MAC16, so the block RAM feeds the block
//! directly; the shift by `⌊y⌋` is one bit a step (a 2:1 mux); each colour product reads its
//! own copy of `c^n`'s field, registered a step after `c^n`, so the copy sits by its block.

use super::{
    check_cos_n, cosine, explain_ideal, scaled, Description, Inputs, Outputs, SpecularUnit,
};
use crate::bits::{bit_length, lit, mask};
use crate::config::Config;
use crate::datapath::{ex, Builder, Expr, Kind, Piece, LUT_DELAY};
use crate::table::Table;
use serde::Serialize;

mod datapath;
mod golden;
mod tables;

pub use crate::table::OperandPad;
pub use datapath::datapath;
pub use golden::{trace, BlinnTrace};
use tables::{exp2_values, log_values};
pub use tables::{tables, BlinnTables};

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
        self.log_table
            + self.ell_truncation
            + self.y_truncation
            + self.exp2_table
            + self.shift_truncation
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
        (w.out_bits as f64).exp2() * ln2 * eps / (std::f64::consts::E * (1.0 - eps * ln2))
            <= 1.0 / 12.0
            && eps * room <= 0.45
    }
    pub fn log_table(w: &BlinnWidths, cfg: &Config) -> bool {
        let b = w.budget(cfg);
        w.log_index_bits >= cfg.f() - 1 || (b.log_table <= 1.0 / 6.0 && b.monotone_ratio <= 0.9)
    }
    pub fn exp2_entries(w: &BlinnWidths, _cfg: &Config) -> bool {
        // the entries' rounding, the interpolation's floor and truncation #3
        (w.out_bits as f64).exp2() * (2.5 * (-(w.exp2_frac_bits as f64)).exp2() + (-50f64).exp2())
            <= 1.0 / 12.0
    }
    pub fn exp2_table(w: &BlinnWidths, cfg: &Config) -> bool {
        let b = w.budget(cfg);
        w.exp2_index_bits >= w.y_frac_bits || b.exp2_table + b.shift_truncation <= 5.0 / 32.0
    }
}

/// `max g''` on [0, 1/2]: g'' = (1/ln2)·Σ_{k≥2} k(k−1)/(k+1)·x^(k−2), rising in x.
fn g2_max() -> f64 {
    let s: f64 = (2..400)
        .map(|k| (k * (k - 1)) as f64 / (k + 1) as f64 * 0.5f64.powi(k - 2))
        .sum();
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
        p(-wg - 1)
            + p(-50)
            + if interpolates {
                g2_max() / 8.0 * p(-2 * (tg + 1)) + p(-wg)
            } else {
                0.0
            }
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
        let eps_e = p(-we - 1)
            + p(-50)
            + if interpolates_e {
                ln2 * ln2 / 8.0 * p(-2 * te) + p(-we)
            } else {
                0.0
            };
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
        assert!(
            b.holds(),
            "blinn budget does not close for {:?}: {b:?}",
            cfg.params
        );
        // WC: the colours see the same error scaled by ks/2^W < 2^(B−W), plus flooring V to
        // WC bits (< 2^(B−WC) in colour units): the smallest WC with a sum below 1/2
        let p = |k: i64| (k as f64).exp2();
        let tc = b.total() * p(cfg.b() as i64 - w as i64);
        bw.color_frac_bits = (1..=bw.exp2_frac_bits)
            .find(|&wc| tc + p(cfg.b() as i64 - wc as i64) < 0.5)
            .unwrap_or(bw.exp2_frac_bits);
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
        Blinn {
            cfg: cfg.clone(),
            widths,
            tables,
        }
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
