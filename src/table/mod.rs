//! A constant table of the unit (a ROM): its words, its width, the file it is written to.
//! Models make them, the datapath reads them (`datapath/tables.rs`), `emit` writes them, and
//! `formats` renders any of them in an export format (`specgen rom`). The type imports only the
//! fixed-point helpers; `formats` reads the configuration its header names.

pub mod formats;

use crate::bits::bit_length;

/// A constant table of the unit (a ROM): written as a `$readmemh` file or inlined as a `case`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Table {
    /// The memory's name in the Verilog, and the second half of its file's name.
    pub name: String,
    /// The Verilog parameter that names the file.
    pub(crate) param: String,
    pub(crate) width: u32,
    pub(crate) words: Vec<u128>,
    /// What an entry holds, for the comments.
    pub(crate) what: String,
    /// The fields of a word, LSB first: (name, bits), for the CSV export.
    pub(crate) fields: Vec<(String, u32)>,
    /// Each word is a cosine, UQ1.this: the CSV export gives its address as `n`, the cosine as
    /// a decimal and its angle (a cut-off table).
    pub(crate) cosines: Option<u32>,
}

impl Table {
    /// Its `$readmemh` file, `<top>_<name>.hex`: the unit's top in front, so two units in one
    /// design (one simulator run, one FuseSoC `copyto`, one yosys working directory) never
    /// read each other's tables.
    pub fn file(&self, top: &str) -> String {
        format!("{top}_{}.hex", self.name)
    }

    /// What the RTL's load check recomputes over every entry after `$readmemh`:
    /// `sum = sum·31 + word` (mod 2^64, each word's low 64 bits), from 0. A missing entry (X in
    /// Icarus) or a wrong one changes it, so a file that sets only some entries (`@3ff 7faa`)
    /// or another table's is caught in the user's own simulator, not only by `cosim`.
    pub fn checksum(&self) -> u64 {
        self.words
            .iter()
            .fold(0u64, |s, &w| s.wrapping_mul(31).wrapping_add(w as u64))
    }

    pub(crate) fn address_bits(&self) -> u32 {
        bit_length(self.words.len() as u128 - 1).max(1)
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
pub(crate) fn interpolation_table(
    name: &str,
    entries: &[u128],
    deltas: &[u128],
    bits: (u32, u32),
    pad: Option<OperandPad>,
    what: String,
    fields: (&str, &str),
) -> Table {
    let (entry_bits, delta_bits) = bits;
    let (delta_field, zeros) = pad.map_or((delta_bits, 0), |p| (p.a_bits, p.b_pad));
    let mut f = vec![
        (fields.0.into(), entry_bits),
        (fields.1.into(), delta_field),
    ];
    if zeros > 0 {
        f.push(("zero".into(), zeros));
    }
    Table {
        name: format!("{name}_rom"),
        param: format!("{}_ROM_FILE", name.to_uppercase()),
        width: delta_field + entry_bits + zeros,
        words: entries
            .iter()
            .zip(deltas)
            .map(|(&e, &d)| (d << entry_bits) | e)
            .collect(),
        what,
        fields: f,
        cosines: None,
    }
}
