//! The log2 and exp2 tables, each word `{Δ, entry}`, and the operands their words pad.

use super::*;
use crate::table::interpolation_table;

/// `G_i = round(g(i/2^(TG+1))·2^WG)` for `i = 0..=2^TG` (the last only for ΔG).
pub(super) fn log_values(w: &BlinnWidths) -> Vec<u128> {
    let count = 1u32 << w.log_index_bits;
    (0..=count)
        .map(|i| {
            let x = i as f64 / (2 * count) as f64;
            (g(x) * (w.log_frac_bits as f64).exp2()).round() as u128
        })
        .collect()
}

/// `E_j = round(2^−(j/2^TE)·2^WE)` for `j = 0..=2^TE` (`E_0 = 2^WE`, the last `2^(WE−1)`).
pub(super) fn exp2_values(w: &BlinnWidths) -> Vec<u128> {
    let count = 1u32 << w.exp2_index_bits;
    (0..=count)
        .map(|j| {
            ((-(j as f64) / count as f64).exp2() * (w.exp2_frac_bits as f64).exp2()).round() as u128
        })
        .collect()
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

impl BlinnTables {
    pub fn log_table(&self, w: &BlinnWidths, pad: Option<OperandPad>) -> Table {
        let what = format!("{{dG, G}}: g(x) = -log2(1 - x)/x at x = i/2^{}, UQ2.{}, and the step to the next entry", w.log_index_bits + 1, w.log_frac_bits);
        interpolation_table(
            "log2",
            &self.g,
            &self.dg,
            (w.log_entry_bits, w.log_delta_bits),
            pad,
            what,
            ("g", "dg"),
        )
    }
    /// The exp2 table as stored: `E_0 = 1.0` is the only entry with its integer bit set when
    /// [`BlinnTables::exp2_one_implied`], and then that bit is not stored but read as `j == 0`
    /// (one word bit fewer: 2 block RAMs for 256 words instead of 3).
    ///
    /// `complemented`: each entry is stored complemented (`~E`, over its stored bits), the
    /// addend of the interpolation's multiply-add on a DSP block ([`super::datapath`]): the
    /// block RAM then feeds the block with no LUT between them (on the UP5K that LUT, and
    /// the route on to the DSP column, held blinn at 97.8–114.9 MHz).
    pub fn exp2_table(
        &self,
        w: &BlinnWidths,
        pad: Option<OperandPad>,
        complemented: bool,
    ) -> Table {
        let implied = self.exp2_one_implied(w);
        let stored_bits = w.exp2_entry_bits - implied as u32;
        let flip = if complemented { mask(stored_bits) } else { 0 };
        let entries: Vec<u128> = self
            .e
            .iter()
            .map(|&e| (e ^ flip) & mask(stored_bits))
            .collect();
        let (field, not) = if complemented { ("~E", "~") } else { ("E", "") };
        let what = if implied {
            format!(
                "{{dE, {field} mod 1}}: {not}2^-f at f = j/2^{}, UQ0.{} (its integer bit, set for j = 0 only, is j == 0), and the step down to the next entry",
                w.exp2_index_bits, w.exp2_frac_bits
            )
        } else {
            format!("{{dE, {field}}}: {not}2^-f at f = j/2^{}, UQ1.{}, and the step down to the next entry", w.exp2_index_bits, w.exp2_frac_bits)
        };
        let entry_field = if complemented { "not_e" } else { "e" };
        interpolation_table(
            "exp2",
            &entries,
            &self.de,
            (stored_bits, w.exp2_delta_bits),
            pad,
            what,
            (entry_field, "de"),
        )
    }

    /// Whether E_0 = 2^WE is the only exp2 entry at or above 1.0.
    pub(crate) fn exp2_one_implied(&self, w: &BlinnWidths) -> bool {
        w.exp2_entry_bits == w.exp2_frac_bits + 1
            && self.e[1..].iter().all(|&e| e < 1u128 << w.exp2_frac_bits)
    }
}
