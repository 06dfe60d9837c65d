//! The widths of the reciprocal divider and its table: `r = 2/u` on `u ∈ [1, 2)` by linear
//! interpolation between rounded points, each word `{D_i, B_i}` (the argument is the module
//! doc's).

use super::*;
use crate::table::{interpolation_table, OperandPad, Table};

/// Every width of the schlick unit, from the error budget (the module doc).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchlickWidths {
    /// M = max(FI, B)
    pub(crate) m: u32,
    /// Z = M + 1: fractional bits of the reciprocal r̂ = 1 + z/2^Z
    pub(crate) recip_frac_bits: u32,
    /// W = M + 3: fractional bits of the quotient q
    pub(crate) quotient_frac_bits: u32,
    /// Wc = B + 3: fractional bits of the quotient the colours take
    pub(crate) colour_frac_bits: u32,
    /// U = Z + 4: the table's unit, 2^−U
    pub(crate) entry_frac_bits: u32,
    /// K = ⌈(Z + 2)/2⌉: the table's index, the top K fraction bits of u
    pub(crate) index_bits: u32,
    /// J = U − K: the interpolation fraction, the next J bits of u
    pub(crate) fraction_bits: u32,
    /// the denominator's bits, N + F + 2
    pub(crate) den_bits: u32,
    /// the bits of L, the denominator's leading zeros above 2^F (0..=N+1; N+2 when none)
    pub(crate) shift_bits: u32,
}

impl SchlickWidths {
    pub fn derive(cfg: &Config) -> SchlickWidths {
        let m = cfg.fi().max(cfg.b());
        let z = m + 1;
        let u = z + 4;
        let k = (z + 3) / 2;
        // L's groups of 4 (Builder::leading_zeros) need 2 bits above the group's index
        let groups = (cfg.n_bits() + 2).div_ceil(4);
        SchlickWidths {
            m,
            recip_frac_bits: z,
            quotient_frac_bits: m + 3,
            colour_frac_bits: cfg.b() + 3,
            entry_frac_bits: u,
            index_bits: k,
            fraction_bits: u - k,
            den_bits: cfg.n_bits() + cfg.f() + 2,
            shift_bits: bit_length(cfg.n_bits() as u128 + 2)
                .max(2 + bit_length(groups as u128 - 1)),
        }
    }

    /// The bits of a slope D_i: below 2^(U+1−K).
    pub(crate) fn slope_bits(&self) -> u32 {
        self.entry_frac_bits + 1 - self.index_bits
    }

    /// The interpolation's sum `B_i·2^J + D_i·t'`: below 2^(U+J).
    pub(crate) fn sum_bits(&self) -> u32 {
        self.entry_frac_bits + self.fraction_bits
    }
}

/// The table: `b[i] = B_i` (in units of 2^−U, 1.0 taken off), `d[i] = D_i` (the step over
/// interval i, in the same units).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReciprocalTable {
    pub(crate) b: Vec<u128>,
    pub(crate) d: Vec<u128>,
}

impl ReciprocalTable {
    /// The points `V_i = round(2/u_i·2^U)` at `u_i = 1 + i/2^K` (`V_0` lowered so that
    /// r̂ < 2), the slopes their differences, and `B_i = V_(i+1) + κ − 2^U` with one constant
    /// κ (the module doc), all in integers.
    pub fn new(w: &SchlickWidths) -> ReciprocalTable {
        let (k, j, u, z) = (
            w.index_bits,
            w.fraction_bits,
            w.entry_frac_bits,
            w.recip_frac_bits,
        );
        let count = 1u128 << k;
        let top = 1u128 << (k + 1 + u); // 2·2^K·2^U: V_i = top/(2^K + i)
        let mut v: Vec<u128> = (0..=count)
            .map(|i| (2 * top + count + i) / (2 * (count + i)))
            .collect();
        // κ·2^(J+2) = 2^(U−Z−1)·2^(J+2) + 2·D_max − 2^(U−2K−2)·2^(J+2): the rounding offset to Z
        // bits, the centring of t's truncation, and half the widest chord gap, rounded to a unit
        let dmax = v[0] - v[1];
        let scaled = (1i128 << (u - z - 1 + j + 2)) + 2 * dmax as i128
            - ((1i128 << (u + j + 2)) >> (2 * k + 2));
        let kappa = ((scaled + (1 << (j + 1))) >> (j + 2)) as u128;
        // r̂ < 2 on interval 0: B_0·2^J + D_0·(2^J − 1) < 2^(U+J)
        let b0 = v[1] + kappa - (1 << u);
        let room = ((1u128 << (u + j)) - 1 - (b0 << j)) / ((1 << j) - 1);
        v[0] = v[0].min(v[1] + room);
        ReciprocalTable {
            b: v[1..].iter().map(|&x| x + kappa - (1 << u)).collect(),
            d: v.windows(2).map(|p| p[0] - p[1]).collect(),
        }
    }

    /// `z`: r̂ = 1 + z/2^Z at interval `i`, fraction `t` (J bits).
    pub(crate) fn recip(&self, w: &SchlickWidths, i: usize, t: u128) -> u128 {
        let j = w.fraction_bits;
        let t_inv = mask(j) - t;
        ((self.b[i] << j) + self.d[i] * t_inv) >> (w.sum_bits() - w.recip_frac_bits)
    }

    /// The table as the unit stores it: word i = `{D_i, B_i}` (with `pad`, D in a field of
    /// the DSP block's width and zero bits above it that widen ~t: the block's post-adder then
    /// adds B).
    pub fn table(&self, w: &SchlickWidths, pad: Option<OperandPad>) -> Table {
        let what = format!(
            "{{D, B}}: r = 2/u on u in [1 + i/2^{k}, 1 + (i+1)/2^{k}): r^ = 1 + floor((B*2^{j} + D*~t)/2^{s})/2^{z}, units of 2^-{u}",
            k = w.index_bits,
            j = w.fraction_bits,
            s = w.sum_bits() - w.recip_frac_bits,
            z = w.recip_frac_bits,
            u = w.entry_frac_bits,
        );
        interpolation_table(
            "recip",
            &self.b,
            &self.d,
            (w.entry_frac_bits, w.slope_bits()),
            pad,
            what,
            ("b", "d"),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Params, SpecularModel};

    /// Every cell of the table (interval i, fraction t: the u in
    /// `[u_lo, u_lo + 2^−(K+J))`): r̂ within `3·2^−(M+3)` of r relatively at both ends (r̂ is
    /// constant on the cell, r monotone), r̂ in [1, 2), and r̂ never rising with u. The whole
    /// budget of the reciprocal, checked on every cell rather than argued.
    fn every_cell_is_within_the_budget(w: &SchlickWidths) {
        let t = ReciprocalTable::new(w);
        let (k, j, z, m) = (w.index_bits, w.fraction_bits, w.recip_frac_bits, w.m);
        let cells = 1u128 << (k + j);
        let one = 1i128 << (z + k + j + 1 + m + 3); // 1.0 in the scale of r̂·u·2^(M+3)/2
        let bound = 3i128 << (z + k + j + 1);
        let mut prev = u128::MAX;
        let mut worst = 0i128;
        for i in 0..1usize << k {
            for f in 0..1u128 << j {
                let r = t.recip(w, i, f);
                assert!(r < 1 << z, "r^ reaches 2 at i={i} t={f}");
                assert!(r <= prev, "r^ rises at i={i} t={f}");
                prev = r;
                let lo = cells + ((i as u128) << j) + f;
                for ucode in [lo, lo + 1] {
                    let e = (((1i128 << z) + r as i128) * ucode as i128) << (m + 3);
                    let err = (e - one).abs();
                    worst = worst.max(err);
                    assert!(err <= bound, "|r^/r - 1| > 3*2^-{} at i={i} t={f}", m + 3);
                }
            }
        }
        // the bound is not loose by more than a factor 2: the argument is the right one
        assert!(
            2 * worst > bound,
            "the reciprocal is well inside its budget: {worst} of {bound}"
        );
    }

    #[test]
    fn the_reciprocal_meets_its_budget_on_every_cell() {
        for p in [
            Params::default(),
            Params {
                cos_frac_bits: 8,
                n_bits: 6,
                color_bits: 4,
                intensity_frac_bits: 8,
                ..Params::default()
            },
            Params {
                cos_frac_bits: 12,
                n_bits: 8,
                color_bits: 10,
                intensity_frac_bits: 6,
                ..Params::default()
            },
            Params {
                intensity_frac_bits: 16,
                ..Params::default()
            },
            Params {
                intensity_frac_bits: 17,
                ..Params::default()
            },
        ] {
            let cfg = Config::new(Params {
                model: SpecularModel::Schlick,
                ..p
            })
            .unwrap();
            every_cell_is_within_the_budget(&SchlickWidths::derive(&cfg));
        }
    }
}
