//! A constant table of the unit (a ROM): its words, its width, the file it is written to.
//! Models make them, the datapath reads them, `emit` and `rom` write them. A leaf: it imports
//! only the fixed-point helpers.

use crate::bits::bit_length;

/// A constant table of the unit (a ROM): written as a `$readmemh` file or inlined as a `case`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Table {
    /// The memory's name in the Verilog, and the second half of its file's name.
    pub name: String,
    /// The Verilog parameter that names the file.
    pub param: String,
    pub width: u32,
    pub words: Vec<u128>,
    /// What an entry holds, for the comments.
    pub what: String,
    /// The fields of a word, LSB first: (name, bits), for the CSV export.
    pub fields: Vec<(String, u32)>,
}

impl Table {
    /// Its `$readmemh` file, `<top>_<name>.hex`: the unit's top in front, so two units in one
    /// design (one simulator run, one FuseSoC `copyto`, one yosys working directory) never
    /// read each other's tables.
    pub fn file(&self, top: &str) -> String {
        format!("{top}_{}.hex", self.name)
    }

    pub(crate) fn address_bits(&self) -> u32 {
        bit_length(self.words.len() as u128 - 1).max(1)
    }
}
