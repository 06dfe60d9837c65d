//! `--model quadratic` (SPEC §3): the paper's formula (15), `[1 − k_q·n·(1 − c)]²` cut off at
//! `cos_sp(n)`. Its home: the error budget below and the widths it gives ([`Widths`]), the
//! cut-off ROM ([`rom`]), the golden model and exact reference ([`golden`]) and the datapath
//! ([`datapath`]: `lean` and `paper`).
//!
//! # The datapath (all quantities unsigned)
//!
//! ```text
//! d        = 2^F − min(cos_g, 2^F)          exact, UQ1.F            "1 − cos γ" (adder 6)
//! kn       = k_code · n                     exact, UQ(N).KF         (multipliers 34, 7)
//! P        = kn · d                         exact, UQ(N+1).(KF+F)   k_q·n·(1 − c)
//! dev      = ⌊P / 2^s⌋,  s = KF+F−WB        UQ(·).WB                truncation #1
//! bracket  = done ? 0 : 2^WB − dev          UQ1.WB                  (adder 9, key block 13)
//! sq       = ⌊bracket² / 2^(2WB−WS)⌋        UQ1.WS                  truncation #2 (squarer 11)
//! intensity= ⌊(sq·2^FI + 2^(WS−1)) / 2^WS⌋  UQ1.FI                  round half up
//! spec_X   = ⌊(sq·ks_X + 2^(WS−1)) / 2^WS⌋  B bits                  round half up (mult. 14–16)
//! ```
//!
//! # Error budget (the argument the widths below apply)
//!
//! Let `b = base ∈ [0, 1]` be the exact bracket when not `done`, `e = bracket/2^WB − b`.
//! Truncating `P` makes `dev` too small by less than one unit, so `0 ≤ e < 2^−WB`, and
//! `bracket ≤ 2^WB` (i.e. `b + e ≤ 1`). Squaring: `(b+e)² − b² = e(2b+e) ≤ 2e(b+e) ≤ 2e`,
//! so the square is high by less than `2^(1−WB)`. Truncation #2 makes it low by less than
//! `2^−WS`. Hence the value `y` fed to the final rounding satisfies, in units of the output,
//!
//! ```text
//!   −2^−WS · M  <  y − o*  <  2^(1−WB) · M,      M = 2^FI (intensity) or ks < 2^B (colours)
//! ```
//!
//! Both bounds are below `1/2` when `WS ≥ max(FI, B) + 1` and `WB ≥ max(FI, B) + 2`.
//! The final `o = ⌊y + 1/2⌋` is within `(−1/2, 1/2]` of `y`, so `|o − o*| < 1` (faithful),
//! and where `o*` is an integer `|y − o*| < 1/2` forces `o = o*`.
//! Every step is a monotone function of `cos_g` (truncation, squaring a non-negative value,
//! multiplying by `ks ≥ 0`, rounding), so outputs never decrease as `cos_g` grows.
//!
//! The colour outputs need only `WS_C = B + 1` fractional bits of the square (their own
//! budget: `WS_C ≥ B + 1`, `WB ≥ B + 2`), so the `lean` datapath multiplies the colours by the
//! square truncated further, `sq_C = ⌊sq / 2^(WS − WS_C)⌋` (floor of a floor is one floor, so
//! the bound above holds with WS_C in place of WS). The `paper` datapath keeps every bit
//! everywhere (the device of Fig. 5 has no error analysis): it is exact, hence also faithful.
//!
//! `exact` rounding needs the value itself, not an approximation (a tie can only be told
//! from a near-tie by every bit), so it uses `WB = KF+F` (no truncation #1) and `WS = 2·WB`
//! (no truncation #2): then `e = 0`, `y = o*`, and `⌊o* + 1/2⌋` is round-half-up, which for
//! non-negative values is "ties away from zero". The same caps apply in `faithful` mode
//! when the budget asks for more bits than the exact value has.

pub mod datapath;
pub mod golden;
pub mod rom;

use super::{explain_ideal, Description, Ideal, Inputs, Outputs, SpecularUnit};
use crate::bits::{bit_length, exact_decimal};
use crate::config::{Arch, Config, Rounding};
use crate::datapath::{Builder, MAX_SQUARER_SPLIT};
use serde::Serialize;

/// Every internal width and shift of the unit. All widths are bit counts of unsigned values.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Widths {
    /// `cos_g`, `cos_sp` and `d = 1 − cos`: F+1 bits, UQ1.F.
    pub(crate) cos_bits: u32,
    /// `kn = k_code·n`: bits of its largest value, UQ(·).KF.
    pub(crate) kn_bits: u32,
    /// `P = kn·d`, the exact deviation: UQ(·).(KF+F).
    pub(crate) deviation_bits: u32,
    /// Bits dropped from `P` (truncation #1): `s = KF + F − WB`.
    pub(crate) deviation_shift: u32,
    /// WB: fractional bits of the bracket; the bracket is UQ1.WB, WB+1 bits.
    pub(crate) bracket_frac_bits: u32,
    /// WS: fractional bits of the (truncated) square; UQ1.WS, WS+1 bits.
    pub(crate) square_frac_bits: u32,
    /// Bits dropped from the full square (truncation #2): `2·WB − WS`.
    pub(crate) square_shift: u32,
    /// WS_C: fractional bits of the square fed to the colour multipliers (≤ WS).
    pub(crate) color_square_frac_bits: u32,
    /// Low bits split off the bracket so the squarer's main product is ≤ 16×16 (0: one multiply).
    pub(crate) squarer_split: u32,
    /// `sq_C · ks_X` (+ the rounding half): WS_C+B bits, since `2^WS_C·(2^B−1) + 2^(WS_C−1) < 2^(WS_C+B)`.
    pub(crate) color_product_bits: u32,
}

impl Widths {
    /// Whether every value of the datapath fits a u64 (the golden model then computes in one):
    /// the exact deviation, the full square, the colour products with their rounding half, and
    /// the intensity sum.
    pub fn fits_u64(&self, intensity_frac_bits: u32) -> bool {
        let square_full = 2 * (self.bracket_frac_bits + 1);
        let intensity_sum = self.square_frac_bits.max(intensity_frac_bits) + 2;
        [
            self.deviation_bits,
            square_full,
            self.color_product_bits + 1,
            intensity_sum,
        ]
        .into_iter()
        .max()
        .unwrap_or(0)
            <= 64
    }

    /// Every width, from the budget above.
    pub fn derive(cfg: &Config) -> Widths {
        let (f, kf, fi, b) = (cfg.f(), cfg.kf(), cfg.fi(), cfg.b());
        let exact_bracket_frac = kf + f;
        let (wb, ws) = match (cfg.rounding(), cfg.arch()) {
            (_, Arch::Paper) | (Rounding::Exact, _) => (exact_bracket_frac, 2 * exact_bracket_frac),
            (Rounding::Faithful, Arch::Lean) => {
                let need = fi.max(b);
                let wb = (need + 2).min(exact_bracket_frac);
                (wb, (need + 1).min(2 * wb))
            }
        };
        let wsc = match (cfg.rounding(), cfg.arch()) {
            (Rounding::Faithful, Arch::Lean) => (b + 1).min(ws),
            _ => ws,
        };
        // An iCE40 DSP block multiplies 16×16 (SB_MAC16); a wider bracket is split x = h·2^r + l
        // and squared as h²·2^2r + 2hl·2^r + l², the same exact value with one 16×16 product.
        // (ECP5 squares an 18-bit bracket in one MULT18X18D; generic leaves it to the tool.)
        let family = crate::family::of(cfg.target());
        let dsp = family.multiplier_bits();
        let squarer_split = match cfg.arch() {
            Arch::Lean
                if family.splits_wide_squares()
                    && wb + 1 > dsp
                    && wb + 1 - dsp <= MAX_SQUARER_SPLIT =>
            {
                wb + 1 - dsp
            }
            _ => 0,
        };
        let n_max = (1u64 << cfg.n_bits()) - 1;
        let kn_bits = bit_length(cfg.k_code as u128 * n_max as u128).max(1);
        Widths {
            cos_bits: f + 1,
            kn_bits,
            deviation_bits: kn_bits + f + 1,
            deviation_shift: exact_bracket_frac - wb,
            bracket_frac_bits: wb,
            square_frac_bits: ws,
            square_shift: 2 * wb - ws,
            color_square_frac_bits: wsc,
            squarer_split,
            color_product_bits: wsc + b,
        }
    }

    pub(crate) fn bracket_bits(&self) -> u32 {
        self.bracket_frac_bits + 1
    }
    pub(crate) fn full_square_bits(&self) -> u32 {
        2 * self.bracket_bits()
    }
}

/// The quadratic unit of one configuration: its widths and its cut-off ROM.
#[derive(Debug, Clone)]
pub struct Quadratic {
    pub(crate) cfg: Config,
    pub(crate) widths: Widths,
    /// The cut-off ROM `cos_sp(n)`, n = 0 .. 2^N − 1.
    pub(crate) rom: Vec<u32>,
}

impl Quadratic {
    pub fn new(cfg: &Config) -> Quadratic {
        Quadratic {
            cfg: cfg.clone(),
            widths: Widths::derive(cfg),
            rom: rom::cos_sp_table(cfg),
        }
    }

    /// `k` as given (`--k`), a float.
    fn k_real(&self) -> f64 {
        self.cfg.params.k.trim().parse().unwrap_or(f64::NAN)
    }

    /// `k_q = k_code / 2^KF`, the constant the unit uses.
    fn k_q(&self) -> f64 {
        self.cfg.k_code as f64 / (self.cfg.kf() as f64).exp2()
    }
}

/// Formula (15) in floats: `[1 - k·n·(1 - c)]²`, 0 where the bracket is negative.
fn formula15(k: f64, n: u32, c: f64) -> f64 {
    let b = 1.0 - k * n as f64 * (1.0 - c);
    if b < 0.0 {
        0.0
    } else {
        b * b
    }
}

impl SpecularUnit for Quadratic {
    /// The paper's literal datapath is never calibrated alone (the lean one is).
    fn reads_family_delay_line(&self) -> bool {
        self.cfg.params.arch == crate::config::Arch::Paper
    }
    fn premise_role(&self) -> Option<crate::models::PremiseRole> {
        Some(crate::models::PremiseRole::Paper)
    }

    fn eval(&self, x: Inputs) -> Outputs {
        self.trace(x).outputs
    }

    fn check(&self, x: Inputs, got: Outputs) -> Result<(), crate::error::Error> {
        golden::check(&self.cfg, x, got)
    }

    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        let r = golden::reference(&self.cfg, x);
        (r.intensity.to_f64(), r.spec.map(Ideal::to_f64))
    }

    fn cut_off(&self, n: u32) -> Option<u32> {
        Some(self.rom[n as usize])
    }

    fn datapath(&self, b: &mut Builder) {
        let (cfg, w) = (&self.cfg, &self.widths);
        match cfg.arch() {
            Arch::Lean if b.instantiated_blocks() => datapath::lean_ecp5(cfg, w, b),
            Arch::Lean => datapath::lean(cfg, w, b),
            Arch::Paper => datapath::paper(cfg, w, b),
        }
    }

    fn describe(&self) -> Description {
        let (cfg, w) = (&self.cfg, &self.widths);
        let p = &cfg.params;
        Description {
            param_line: format!(
                "k={} k_frac_bits={} (k_code={}, k_q={})",
                p.k,
                p.k_frac_bits,
                cfg.k_code,
                exact_decimal(cfg.k_code, cfg.kf())
            ),
            formula: vec![
                "S = [1 - k_q*n*(1 - cos_g)]^2, cut to 0 where the bracket is negative (done);"
                    .into(),
                format!(
                    "intensity = S (UQ1.{}), spec_X = S * ks_X.",
                    p.intensity_frac_bits
                ),
            ],
            rounding: match p.rounding {
                Rounding::Faithful => {
                    "faithful: every output within 1 ulp of the exact value (|o - o*| < 1)".into()
                }
                Rounding::Exact => {
                    "exact: every output is the exact value rounded to nearest, ties away from zero"
                        .into()
                }
            },
            datapath: format!(
                "{}{}; bracket UQ1.{}, square UQ1.{} (colours UQ1.{})",
                cfg.arch().name(),
                if cfg.arch() == Arch::Paper {
                    " (the paper's Fig. 5 literally, every bit kept)"
                } else {
                    " (widths from the error budget)"
                },
                w.bracket_frac_bits,
                w.square_frac_bits,
                w.color_square_frac_bits
            ),
            done_meaning: "cos(gamma) < cos_sp(n): beyond the highlight",
            summary:
                "Fixed-point specular highlight unit, [1 - k*n*(1 - cos)]^2 cut off at cos_sp(n)",
            computes: "formula (15), the paper: [1 - k n (1 - c)]^2",
        }
    }

    fn widths(&self) -> serde_json::Value {
        serde_json::to_value(&self.widths).expect("widths serialise")
    }

    fn reference_words(&self) -> &'static str {
        "formula (15) in exact arithmetic with the quantised k_q and the cut-off at cos_sp(n)"
    }

    fn quantisation_error(&self, x: Inputs) -> Option<f64> {
        let c = crate::models::cosine(&self.cfg, x.cos_g);
        Some((formula15(self.k_q(), x.n, c) - formula15(self.k_real(), x.n, c)).abs())
    }

    fn ideal_cut_off(&self, n: u32) -> Option<f64> {
        Some((1.0 - 1.0 / (self.k_q() * n as f64)).max(0.0))
    }

    fn fidelity_note(&self, x: Inputs) -> Option<String> {
        let c = crate::models::cosine(&self.cfg, x.cos_g);
        Some(format!(
            "formula (15) in real arithmetic with k = {}: {:.9}",
            self.k_real(),
            formula15(self.k_real(), x.n, c)
        ))
    }

    fn explain(&self, x: Inputs) -> Vec<String> {
        let (cfg, w) = (&self.cfg, &self.widths);
        let t = self.trace(x);
        let r = golden::reference(cfg, x);
        let (wb, ws) = (w.bracket_frac_bits, w.square_frac_bits);
        vec![
            format!(
                "constant   k = {} -> k_code = {} (k_q = {})",
                cfg.params.k,
                cfg.k_code,
                exact_decimal(cfg.k_code, cfg.kf())
            ),
            format!(
                "datapath   cos_clamped = {}  one_minus_cos = {}  cos_sp[n] = {}  done = {}",
                t.cos_clamped, t.one_minus_cos, t.cos_sp, t.done
            ),
            format!(
                "           kn = {}  deviation = {} (UQ1.{wb})  bracket = {} (UQ1.{wb} = {:.9})",
                t.kn,
                t.deviation,
                t.bracket,
                t.bracket as f64 / (wb as f64).exp2()
            ),
            format!(
                "           square = {} (UQ1.{ws} = {:.9})",
                t.square,
                t.square as f64 / (ws as f64).exp2()
            ),
            explain_ideal(
                self.ideal(x),
                &format!("done = {}  (SPEC §3 with k_q)", r.done),
            ),
        ]
    }
}
