//! The log2 and exp2 tables, each word `{Δ, entry}`, and the operands their words pad.

use super::*;

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
