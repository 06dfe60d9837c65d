//! Stage 2: validated config → internal widths, derived from an error budget.
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

use crate::config::{Arch, Config, Rounding, SpecularModel, Target};
use serde::Serialize;

/// Every internal width and shift of the unit. All widths are bit counts of unsigned values.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Widths {
    /// `cos_g`, `cos_sp` and `d = 1 − cos`: F+1 bits, UQ1.F.
    pub cos_bits: u32,
    /// `kn = k_code·n`: bits of its largest value, UQ(·).KF.
    pub kn_bits: u32,
    /// `P = kn·d`, the exact deviation: UQ(·).(KF+F).
    pub deviation_bits: u32,
    /// Bits dropped from `P` (truncation #1): `s = KF + F − WB`.
    pub deviation_shift: u32,
    /// WB: fractional bits of the bracket; the bracket is UQ1.WB, WB+1 bits.
    pub bracket_frac_bits: u32,
    /// WS: fractional bits of the (truncated) square; UQ1.WS, WS+1 bits.
    pub square_frac_bits: u32,
    /// Bits dropped from the full square (truncation #2): `2·WB − WS`.
    pub square_shift: u32,
    /// WS_C: fractional bits of the square fed to the colour multipliers (≤ WS).
    pub color_square_frac_bits: u32,
    /// Low bits split off the bracket so the squarer's main product is ≤ 16×16 (0: one multiply).
    pub squarer_split: u32,
    /// `sq_C · ks_X` (+ the rounding half): WS_C+B bits, since `2^WS_C·(2^B−1) + 2^(WS_C−1) < 2^(WS_C+B)`.
    pub color_product_bits: u32,
    /// W of `--model blinn-pow`: fractional bits of every power and partial product, UQ1.W
    /// (0 for the quadratic model). See [`power_frac_bits`].
    pub power_frac_bits: u32,
    /// Registered cut points, 1-based step numbers (empty when combinational).
    pub registered_cuts: Vec<u32>,
}

/// The most low bits split off the bracket for the squarer: `lo²` then comes from a table of
/// 2^6 = 64 entries in LUTs, and `hi·lo` from one DSP (the bracket is at most UQ1.21 there).
pub const MAX_SQUARER_SPLIT: u32 = 6;

impl Widths {
    pub fn derive(cfg: &Config) -> Widths {
        Widths::derive_unpipelined(cfg).with_balanced_cuts(cfg)
    }

    /// Every width, no registers placed yet.
    pub fn derive_unpipelined(cfg: &Config) -> Widths {
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
        let squarer_split = match (cfg.arch(), cfg.target()) {
            (Arch::Lean, Target::Ice40) if wb + 1 > 16 && wb + 1 - 16 <= MAX_SQUARER_SPLIT => wb + 1 - 16,
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
            power_frac_bits: if cfg.model() == SpecularModel::BlinnPow { power_frac_bits(cfg) } else { 0 },
            registered_cuts: Vec::new(),
        }
    }

    fn with_balanced_cuts(self, cfg: &Config) -> Widths {
        let delays = step_delays(cfg, &self);
        self.with_cuts(balanced_cuts(&delays, cfg.stages()))
    }

    /// These widths with registers after the given steps.
    pub fn with_cuts(mut self, cuts: Vec<u32>) -> Widths {
        self.registered_cuts = cuts;
        self
    }

    pub fn bracket_bits(&self) -> u32 {
        self.bracket_frac_bits + 1
    }
    pub fn square_bits(&self) -> u32 {
        self.square_frac_bits + 1
    }
    pub fn full_square_bits(&self) -> u32 {
        2 * self.bracket_bits()
    }
    /// Width of `dev` after truncation #1, as kept in the datapath.
    pub fn truncated_deviation_bits(&self) -> u32 {
        self.deviation_bits - self.deviation_shift
    }
}

/// W for `--model blinn-pow` (square-and-multiply over the bits of n, LSB first, every
/// product truncated to W fractional bits, c taken exactly: W ≥ F).
///
/// Error budget: all truncations round down, so errors are one-sided. Powers `p_i = c^(2^i)`
/// are squared: with `p ≤ 1`, `x² − (x−e)² ≤ 2e`, so `e(p_i) ≤ (2^i − 1)·2^−W`. The result
/// `r ← r·p_i` (r, p ≤ 1) gains at most `e(r) + e(p_i) + 2^−W`; summed over the N bits,
/// `e(r_N) ≤ Σ_{i<N} 2^i·2^−W < 2^(N−W)`. In output units (`M = 2^FI` or `ks < 2^B`) this is
/// below 1/2 when `W ≥ max(FI, B) + N + 1`; the final round-half-up then gives a faithful
/// result, exact where the ideal is an integer, and monotone in cos_g.
pub fn power_frac_bits(cfg: &Config) -> u32 {
    (cfg.fi().max(cfg.b()) + cfg.n_bits() + 1).max(cfg.f())
}

/// Number of cut points of the configured datapath (the most `--stages` it takes).
pub fn cut_points(cfg: &Config) -> u32 {
    crate::datapath::build(cfg, &Widths::derive_unpipelined(cfg)).steps.len() as u32
}

/// The datapath's per-step delay estimates (the one delay model, in `datapath`).
pub fn step_delays(cfg: &Config, w: &Widths) -> Vec<f64> {
    crate::datapath::build(cfg, w).delays()
}

/// Places `stages` registers after steps (1-based) so that the slowest stretch of logic
/// between registers (inputs and outputs count as registered outside) is as short as
/// possible; ties go to the placement closest to the outputs. Exact: the least bound any
/// placement reaches (over the segment sums), then each cut as late as the bound allows.
pub fn balanced_cuts(delays: &[f64], stages: u32) -> Vec<u32> {
    const TIE: f64 = 1e-9;
    let c = delays.len();
    let s = (stages as usize).min(c);
    if s == 0 {
        return Vec::new();
    }
    let seg = |a: usize, b: usize| delays[a..b].iter().sum::<f64>();
    // the fewest cuts after an edge at `v` that keep every segment up to the end within `w`
    // (greedy: each segment as long as it may be); None when one step alone exceeds `w`
    let need = |v: usize, w: f64| -> Option<usize> {
        let (mut count, mut start) = (0, v);
        while seg(start, c) > w + TIE {
            let mut e = start;
            while e < c && seg(start, e + 1) <= w + TIE {
                e += 1;
            }
            if e == start {
                return None;
            }
            count += 1;
            start = e;
        }
        Some(count)
    };
    // the least worst step: the smallest segment sum that s cuts can keep every segment within
    let mut sums: Vec<f64> = (0..c).flat_map(|a| (a + 1..=c).map(move |b| (a, b))).map(|(a, b)| seg(a, b)).collect();
    sums.push(0.0);
    sums.sort_by(f64::total_cmp);
    let best = *sums.iter().find(|&&w| need(0, w).is_some_and(|m| m <= s)).expect("c cuts always do");
    // among the cuts that reach it, the latest first, then the latest second, ...
    let (mut cuts, mut prev) = (Vec::with_capacity(s), 0usize);
    for i in 0..s {
        let after = s - i - 1;
        let v = (prev + 1..=c - after)
            .rev()
            .find(|&v| seg(prev, v) <= best + TIE && need(v, best).is_some_and(|m| m <= after))
            .expect("a cut that keeps the bound exists");
        cuts.push(v as u32);
        prev = v;
    }
    cuts
}

/// The low `bits` bits set (all 128 when `bits >= 128`).
pub fn mask(bits: u32) -> u128 {
    if bits >= 128 {
        u128::MAX
    } else {
        (1u128 << bits) - 1
    }
}

/// Number of bits needed to hold `v` (0 for 0).
pub fn bit_length(v: u128) -> u32 {
    128 - v.leading_zeros()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuts_are_distinct_increasing_and_in_range() {
        let cfg = Config::defaults();
        let delays = step_delays(&cfg, &Widths::derive(&cfg));
        let c = cut_points(&cfg);
        assert_eq!(delays.len(), c as usize);
        for s in 0..=c {
            let cuts = balanced_cuts(&delays, s);
            assert_eq!(cuts.len(), s as usize);
            assert!(cuts.windows(2).all(|w| w[0] < w[1]), "{cuts:?}");
            assert!(cuts.iter().all(|&x| (1..=c).contains(&x)));
        }
        assert_eq!(balanced_cuts(&delays, c), (1..=c).collect::<Vec<_>>());
    }

    #[test]
    fn balancing_splits_the_heaviest_step_off() {
        // one heavy step in the middle: a single register goes right next to it
        let d = [1.0, 1.0, 10.0, 1.0, 1.0];
        assert_eq!(balanced_cuts(&d, 1), vec![3]);
        assert_eq!(balanced_cuts(&d, 2), vec![2, 3]);
        // uniform steps: registers evenly spaced
        assert_eq!(balanced_cuts(&[1.0; 6], 2), vec![2, 4]);
    }

    /// Every placement tried: the slowest stretch, least; ties to the latest cuts.
    fn balanced_cuts_by_search(delays: &[f64], s: usize) -> Vec<u32> {
        let c = delays.len();
        let worst = |cuts: &[usize]| {
            let mut edges = vec![0usize];
            edges.extend(cuts.iter().copied());
            edges.push(c);
            edges.windows(2).map(|e| delays[e[0]..e[1]].iter().sum::<f64>()).fold(0.0f64, f64::max)
        };
        let mut best: Option<(f64, Vec<usize>)> = None;
        for mask in 0u32..(1 << c) {
            if mask.count_ones() as usize != s {
                continue;
            }
            let pick: Vec<usize> = (0..c).filter(|i| mask >> i & 1 == 1).map(|i| i + 1).collect();
            let w = worst(&pick);
            let better = match &best {
                None => true,
                Some((bw, bc)) => w < *bw - 1e-9 || ((w - *bw).abs() <= 1e-9 && pick > *bc),
            };
            if better {
                best = Some((w, pick));
            }
        }
        best.map(|(_, p)| p.into_iter().map(|x| x as u32).collect()).unwrap_or_default()
    }

    #[test]
    fn balancing_equals_the_search_over_every_placement() {
        let mut r = 7u64;
        for _ in 0..300 {
            r = crate::cosim::splitmix(r);
            let c = 1 + (r % 11) as usize;
            let delays: Vec<f64> = (0..c)
                .map(|i| {
                    let v = crate::cosim::splitmix(r ^ i as u64);
                    // a few distinct values, so ties happen
                    [0.0, 2.7, 3.4, 5.5, 8.1][(v % 5) as usize]
                })
                .collect();
            for s in 0..=c {
                assert_eq!(balanced_cuts(&delays, s as u32), balanced_cuts_by_search(&delays, s), "{delays:?} with {s} cuts");
            }
        }
        // and a long datapath in no time (the search would take 2^43 placements)
        assert_eq!(balanced_cuts(&[2.7; 43], 43).len(), 43);
    }

    #[test]
    fn default_faithful_widths_follow_the_budget() {
        let w = Widths::derive(&Config::defaults());
        assert_eq!(w.bracket_frac_bits, 15 + 2);
        assert_eq!(w.square_frac_bits, 15 + 1);
        assert_eq!(w.deviation_shift, 16 + 15 - 17);
    }
}
