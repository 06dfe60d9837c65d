//! The unit's ports (SPEC §2) as one table, and the values that cross them.
//!
//! The table drives the Verilog port list and header, the manifest, the vector columns and
//! the harnesses; [`Inputs`] and [`Outputs`] are what the golden model takes and gives.
//! A leaf: imports nothing from the crate.

use serde::Serialize;

/// The three colour channels, in port order.
pub const CHANNELS: [&str; 3] = ["r", "g", "b"];

/// One input vector of the unit (port values as integers).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Inputs {
    /// UQ1.F; codes above 2^F are taken as 1.0.
    pub cos_g: u32,
    pub n: u32,
    /// `ks_r`, `ks_g`, `ks_b`: UNORM, all ones = 1.0.
    pub ks: [u32; 3],
}

/// The unit's outputs for one input vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Outputs {
    pub spec: [u32; 3],
    /// UQ1.FI
    pub intensity: u32,
    pub done: bool,
}

/// The widths the port table depends on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PortWidths {
    /// F of UQ1.F
    pub cos_frac_bits: u32,
    pub n_bits: u32,
    pub color_bits: u32,
    /// FI of UQ1.FI
    pub intensity_frac_bits: u32,
    /// a clock and reset (the unit has pipeline registers)
    pub clocked: bool,
}

/// One port of the generated module.
#[derive(Debug, Clone, Serialize, PartialEq, Eq)]
pub struct Port {
    pub name: &'static str,
    pub direction: &'static str,
    pub width: u32,
    /// its number format and meaning, for the Verilog comment
    #[serde(skip)]
    pub meaning: String,
    /// a data field of a vector (not a clock, reset or handshake)
    #[serde(skip)]
    pub data: bool,
}

/// Every name the port table can hold.
pub(crate) const NAMES: [&str; 14] =
    ["clk", "rst", "in_valid", "cos_g", "n", "ks_r", "ks_g", "ks_b", "out_valid", "spec_r", "spec_g", "spec_b", "intensity", "done"];

/// The port list in module order; `done_meaning` completes the `done` comment.
pub fn ports(w: PortWidths, done_meaning: &str) -> Vec<Port> {
    let (f, b, fi) = (w.cos_frac_bits, w.color_bits, w.intensity_frac_bits);
    let mut v = Vec::new();
    let mut port = |name, direction, width, meaning: String, data| v.push(Port { name, direction, width, meaning, data });
    if w.clocked {
        port("clk", "input", 1, String::new(), false);
        port("rst", "input", 1, "synchronous, active high: clears the valid pipeline".into(), false);
    }
    port("in_valid", "input", 1, String::new(), false);
    port("cos_g", "input", f + 1, format!("UQ1.{f}: cos(gamma) = N.H; codes above 1.0 read as 1.0"), true);
    port("n", "input", w.n_bits, "unsigned specular exponent".into(), true);
    for (name, ch) in ["ks_r", "ks_g", "ks_b"].into_iter().zip(["R", "G", "B"]) {
        port(name, "input", b, format!("UNORM{b}: Ks * {ch}"), true);
    }
    port("out_valid", "output", 1, String::new(), false);
    for name in ["spec_r", "spec_g", "spec_b"] {
        port(name, "output", b, format!("UNORM{b}: S * ks_{}", &name[5..]), true);
    }
    port("intensity", "output", fi + 1, format!("UQ1.{fi}: S"), true);
    port("done", "output", 1, done_meaning.to_string(), true);
    v
}

/// The data columns of a vector, inputs then outputs: the order of `specgen vectors`.
pub(crate) const VECTOR_COLUMNS: [&str; 10] = ["cos_g", "n", "ks_r", "ks_g", "ks_b", "intensity", "spec_r", "spec_g", "spec_b", "done"];

impl Inputs {
    /// The value on an input port of [`VECTOR_COLUMNS`].
    pub fn value(&self, port: &str) -> Option<u64> {
        Some(match port {
            "cos_g" => self.cos_g as u64,
            "n" => self.n as u64,
            "ks_r" => self.ks[0] as u64,
            "ks_g" => self.ks[1] as u64,
            "ks_b" => self.ks[2] as u64,
            _ => return None,
        })
    }
}

impl Outputs {
    /// The value on an output port of [`VECTOR_COLUMNS`].
    pub fn value(&self, port: &str) -> Option<u64> {
        Some(match port {
            "intensity" => self.intensity as u64,
            "spec_r" => self.spec[0] as u64,
            "spec_g" => self.spec[1] as u64,
            "spec_b" => self.spec[2] as u64,
            "done" => self.done as u64,
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_holds_every_name_once_and_every_column() {
        let w = PortWidths { cos_frac_bits: 15, n_bits: 10, color_bits: 8, intensity_frac_bits: 15, clocked: true };
        let p = ports(w, "");
        assert_eq!(p.iter().map(|p| p.name).collect::<Vec<_>>(), NAMES);
        for c in VECTOR_COLUMNS {
            assert!(p.iter().any(|p| p.name == c && p.data), "{c}");
            let (x, y) = (Inputs::default(), Outputs::default());
            assert!(x.value(c).is_some() != y.value(c).is_some(), "{c}");
        }
        assert_eq!(ports(PortWidths { clocked: false, ..w }, "").len(), 12);
    }
}
