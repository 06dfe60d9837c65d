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
    pub(crate) cos_frac_bits: u32,
    pub(crate) n_bits: u32,
    pub(crate) color_bits: u32,
    /// FI of UQ1.FI
    pub(crate) intensity_frac_bits: u32,
    /// a clock and reset (the unit has registers)
    pub(crate) clocked: bool,
    /// `in_ready`/`out_ready` (the `ready` and `axis` interfaces)
    pub(crate) ready: bool,
    /// AXI4-Stream names, the fields packed into `tdata` (the `axis` interface)
    pub(crate) axis: bool,
    /// W of `in_tag`/`out_tag` (`tuser` under `axis`), 0 for none
    pub(crate) tag_bits: u32,
    /// `ks_r/g/b` are material registers loaded by `ks_load`, with an `idle` output
    pub(crate) static_colour: bool,
    /// the reset is active low (`rst_n`, `aresetn`), else active high (`rst`, `areset`)
    pub(crate) reset_low: bool,
    /// `s_axis_tlast`/`m_axis_tlast` (the `axis` interface)
    pub(crate) tlast: bool,
    /// a clock enable: `clk_en`, `aclken` under `axis` (the `ready` and `axis` interfaces)
    pub(crate) clock_enable: bool,
}

/// The reset port's name: `rst`/`rst_n`, or under `axis` `areset`/`aresetn`.
pub fn reset_port(w: PortWidths) -> &'static str {
    match (w.axis, w.reset_low) {
        (true, true) => "aresetn",
        (true, false) => "areset",
        (false, true) => "rst_n",
        (false, false) => "rst",
    }
}

/// One field of a packed `tdata` (the `axis` interface): a logical port's bits at `lo`.
#[derive(Debug, Clone, Serialize, PartialEq, Eq)]
pub struct Field {
    pub(crate) name: &'static str,
    pub(crate) lo: u32,
    pub(crate) width: u32,
}

/// A packed `tdata` of `width` bits as a Verilog concatenation, most significant first: the
/// fields' names with zero padding between them (the RTL's `m_axis_tdata`, the adapter's
/// `s_axis_tdata`).
pub(crate) fn packed_tdata(fields: &[Field], width: u32) -> String {
    let mut parts = Vec::new();
    let mut top = width;
    for f in fields.iter().rev() {
        if top > f.lo + f.width {
            parts.push(format!("{}'d0", top - f.lo - f.width));
        }
        parts.push(f.name.to_string());
        top = f.lo;
    }
    format!("{{{}}}", parts.join(", "))
}

/// The fields of `s_axis_tdata` and `m_axis_tdata`, each starting on a byte boundary, and
/// the two widths (whole bytes).
pub fn tdata_fields(w: PortWidths) -> (Vec<Field>, u32, Vec<Field>, u32) {
    let pack = |fields: &[(&'static str, u32)]| {
        let mut lo = 0;
        let v: Vec<Field> = fields
            .iter()
            .map(|&(name, width)| {
                let f = Field { name, lo, width };
                lo += width.div_ceil(8) * 8;
                f
            })
            .collect();
        (v, lo)
    };
    let (f, b, fi) = (w.cos_frac_bits, w.color_bits, w.intensity_frac_bits);
    let mut s: Vec<(&'static str, u32)> = vec![("cos_g", f + 1), ("n", w.n_bits)];
    if !w.static_colour {
        s.extend([("ks_r", b), ("ks_g", b), ("ks_b", b)]);
    }
    let m = [
        ("intensity", fi + 1),
        ("spec_r", b),
        ("spec_g", b),
        ("spec_b", b),
        ("done", 1),
    ];
    let (sf, sw) = pack(&s);
    let (mf, mw) = pack(&m);
    (sf, sw, mf, mw)
}

/// One port of the generated module.
#[derive(Debug, Clone, Serialize, PartialEq, Eq)]
pub struct Port {
    pub(crate) name: &'static str,
    pub(crate) direction: &'static str,
    pub(crate) width: u32,
    /// its number format and meaning, for the Verilog comment
    #[serde(skip)]
    pub(crate) meaning: String,
    /// a data field of a vector (not a clock, reset or handshake)
    #[serde(skip)]
    pub(crate) data: bool,
}

/// Every name the port table can hold, and the logical names of the `axis` unit's fields.
pub(crate) const NAMES: [&str; 36] = [
    "clk",
    "rst",
    "in_valid",
    "in_ready",
    "cos_g",
    "n",
    "ks_r",
    "ks_g",
    "ks_b",
    "ks_load",
    "in_tag",
    "out_valid",
    "out_ready",
    "spec_r",
    "spec_g",
    "spec_b",
    "intensity",
    "done",
    "out_tag",
    "idle",
    "aclk",
    "aresetn",
    "s_axis_tvalid",
    "s_axis_tready",
    "s_axis_tdata",
    "s_axis_tuser",
    "m_axis_tvalid",
    "m_axis_tready",
    "m_axis_tdata",
    "m_axis_tuser",
    "rst_n",
    "areset",
    "s_axis_tlast",
    "m_axis_tlast",
    "clk_en",
    "aclken",
];

/// The port list in module order; `done_meaning` completes the `done` comment.
pub fn ports(w: PortWidths, done_meaning: &str) -> Vec<Port> {
    let (f, b, fi, tw) = (
        w.cos_frac_bits,
        w.color_bits,
        w.intensity_frac_bits,
        w.tag_bits,
    );
    let mut v = Vec::new();
    let mut port = |name, direction, width, meaning: String, data| {
        v.push(Port {
            name,
            direction,
            width,
            meaning,
            data,
        })
    };
    let static_colour = |port: &mut dyn FnMut(&'static str, &'static str, u32, String, bool)| {
        for (name, ch) in ["ks_r", "ks_g", "ks_b"].into_iter().zip(["R", "G", "B"]) {
            port(
                name,
                "input",
                b,
                format!("UNORM{b}: Ks * {ch}, taken by ks_load"),
                false,
            );
        }
        port(
            "ks_load",
            "input",
            1,
            "loads ks_r/g/b into the material registers; only while idle".into(),
            false,
        );
    };
    if w.axis {
        let (sf, sw, mf, mw) = tdata_fields(w);
        let layout = |fields: &[Field]| {
            fields
                .iter()
                .map(|x| format!("{}@{}", x.name, x.lo))
                .collect::<Vec<_>>()
                .join(" ")
        };
        port("aclk", "input", 1, String::new(), false);
        let level = if w.reset_low { "low" } else { "high" };
        port(
            reset_port(w),
            "input",
            1,
            format!("synchronous, active {level}: empties the unit"),
            false,
        );
        if w.clock_enable {
            port(
                "aclken",
                "input",
                1,
                "clock enable: an edge with it low transfers nothing".into(),
                false,
            );
        }
        port("s_axis_tvalid", "input", 1, String::new(), false);
        port("s_axis_tready", "output", 1, String::new(), false);
        port("s_axis_tdata", "input", sw, layout(&sf), true);
        if tw > 0 {
            port("s_axis_tuser", "input", tw, "the pixel's tag".into(), true);
        }
        if w.tlast {
            port(
                "s_axis_tlast",
                "input",
                1,
                "the pixel's last flag, carried with it as tuser is".into(),
                true,
            );
        }
        port("m_axis_tvalid", "output", 1, String::new(), false);
        port("m_axis_tready", "input", 1, String::new(), false);
        port("m_axis_tdata", "output", mw, layout(&mf), true);
        if tw > 0 {
            port(
                "m_axis_tuser",
                "output",
                tw,
                "the tag of the pixel out".into(),
                true,
            );
        }
        if w.tlast {
            port(
                "m_axis_tlast",
                "output",
                1,
                "the last flag of the pixel out".into(),
                true,
            );
        }
        if w.static_colour {
            static_colour(&mut port);
            port(
                "idle",
                "output",
                1,
                "no pixel inside the unit".into(),
                false,
            );
        }
        return v;
    }
    if w.clocked {
        port("clk", "input", 1, String::new(), false);
        let what = if w.ready {
            "empties the unit"
        } else {
            "clears the valid pipeline"
        };
        let level = if w.reset_low { "low" } else { "high" };
        port(
            reset_port(w),
            "input",
            1,
            format!("synchronous, active {level}: {what}"),
            false,
        );
        if w.clock_enable {
            port(
                "clk_en",
                "input",
                1,
                "clock enable: an edge with it low transfers nothing".into(),
                false,
            );
        }
    }
    port("in_valid", "input", 1, String::new(), false);
    if w.ready {
        port("in_ready", "output", 1, String::new(), false);
    }
    port(
        "cos_g",
        "input",
        f + 1,
        format!("UQ1.{f}: cos(gamma) = N.H; codes above 1.0 read as 1.0"),
        true,
    );
    port(
        "n",
        "input",
        w.n_bits,
        "unsigned specular exponent".into(),
        true,
    );
    if w.static_colour {
        static_colour(&mut port);
    } else {
        for (name, ch) in ["ks_r", "ks_g", "ks_b"].into_iter().zip(["R", "G", "B"]) {
            port(name, "input", b, format!("UNORM{b}: Ks * {ch}"), true);
        }
    }
    if tw > 0 {
        port(
            "in_tag",
            "input",
            tw,
            "carried beside the pixel to out_tag".into(),
            true,
        );
    }
    port("out_valid", "output", 1, String::new(), false);
    if w.ready {
        port("out_ready", "input", 1, String::new(), false);
    }
    for name in ["spec_r", "spec_g", "spec_b"] {
        port(
            name,
            "output",
            b,
            format!("UNORM{b}: S * ks_{}", &name[5..]),
            true,
        );
    }
    port("intensity", "output", fi + 1, format!("UQ1.{fi}: S"), true);
    port("done", "output", 1, done_meaning.to_string(), true);
    if tw > 0 {
        port(
            "out_tag",
            "output",
            tw,
            "in_tag of the pixel out".into(),
            true,
        );
    }
    if w.static_colour {
        port(
            "idle",
            "output",
            1,
            "no pixel inside the unit".into(),
            false,
        );
    }
    v
}

/// The data columns of a vector, inputs then outputs: the order of `specgen vectors`.
pub(crate) const VECTOR_COLUMNS: [&str; 10] = [
    "cos_g",
    "n",
    "ks_r",
    "ks_g",
    "ks_b",
    "intensity",
    "spec_r",
    "spec_g",
    "spec_b",
    "done",
];

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
        let w = default_widths();
        let p = ports(w, "");
        let names = |w| ports(w, "").iter().map(|p| p.name).collect::<Vec<_>>();
        let mut all: Vec<&str> = names(PortWidths {
            ready: true,
            tag_bits: 4,
            static_colour: true,
            ..w
        });
        all.extend(
            names(PortWidths {
                axis: true,
                tag_bits: 4,
                static_colour: true,
                reset_low: true,
                ..w
            })
            .into_iter()
            .filter(|n| n.contains("axis") || n.starts_with('a')),
        );
        all.extend(
            names(PortWidths {
                reset_low: true,
                ..w
            })
            .into_iter()
            .filter(|n| *n == "rst_n"),
        );
        all.extend(
            names(PortWidths { axis: true, ..w })
                .into_iter()
                .filter(|n| *n == "areset"),
        );
        all.extend(
            names(PortWidths {
                axis: true,
                tlast: true,
                ..w
            })
            .into_iter()
            .filter(|n| n.ends_with("tlast")),
        );
        all.extend(
            names(PortWidths {
                ready: true,
                clock_enable: true,
                ..w
            })
            .into_iter()
            .filter(|n| *n == "clk_en"),
        );
        all.extend(
            names(PortWidths {
                axis: true,
                clock_enable: true,
                ..w
            })
            .into_iter()
            .filter(|n| *n == "aclken"),
        );
        assert_eq!(all, NAMES);
        for c in VECTOR_COLUMNS {
            assert!(p.iter().any(|p| p.name == c && p.data), "{c}");
            let (x, y) = (Inputs::default(), Outputs::default());
            assert!(x.value(c).is_some() != y.value(c).is_some(), "{c}");
        }
        assert_eq!(
            ports(
                PortWidths {
                    clocked: false,
                    ..w
                },
                ""
            )
            .len(),
            12
        );
    }
}

/// What `specgen prove`'s port checker asserts of an output port (every output port has one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PortRule {
    /// `in_ready`: SPEC §7's credit rule, low after a reset, high again within a bound
    Ready,
    /// `out_valid`: low after a reset, held until taken, never waiting for `out_ready`, a
    /// result owed shown within a bound
    Valid,
    /// a result's bits (and the tag, tlast): every bit held while shown and not taken, the
    /// n-th delivered carries the n-th pixel's tag, padding zero while shown
    Data,
    /// `idle`: high exactly while no pixel is taken and not delivered
    Idle,
}

/// The port checker's rule of the output port `name`; none for a name no rule speaks of (a
/// port added without one, which `prove` refuses).
pub fn port_rule(name: &str) -> Option<PortRule> {
    Some(match name {
        "in_ready" | "s_axis_tready" => PortRule::Ready,
        "out_valid" | "m_axis_tvalid" => PortRule::Valid,
        "m_axis_tdata" | "m_axis_tuser" | "m_axis_tlast" | "spec_r" | "spec_g" | "spec_b"
        | "intensity" | "done" | "out_tag" => PortRule::Data,
        "idle" => PortRule::Idle,
        _ => return None,
    })
}

/// The bits of output port `name` that carry no field (`m_axis_tdata`'s padding between its
/// fields, which the unit's header states are 0), as (highest, lowest) ranges.
pub fn padding(w: PortWidths, name: &str) -> Vec<(u32, u32)> {
    if name != "m_axis_tdata" || !w.axis {
        return Vec::new();
    }
    let (_, _, mf, mw) = tdata_fields(w);
    let mut ranges = Vec::new();
    let mut at = 0;
    for f in mf.iter().map(|f| (f.lo, f.lo + f.width)).chain([(mw, mw)]) {
        if f.0 > at {
            ranges.push((f.0 - 1, at));
        }
        at = f.1;
    }
    ranges
}

/// The default widths, the `valid` interface (the tests' port table).
#[cfg(test)]
fn default_widths() -> PortWidths {
    PortWidths {
        cos_frac_bits: 15,
        n_bits: 10,
        color_bits: 8,
        intensity_frac_bits: 15,
        clocked: true,
        ready: false,
        axis: false,
        tag_bits: 0,
        static_colour: false,
        reset_low: false,
        tlast: false,
        clock_enable: false,
    }
}

#[cfg(test)]
mod port_rule_tests {
    use super::*;

    /// Every output port of every port table has a rule of the port
    /// checker (a port added without one fails here).
    #[test]
    fn every_output_port_has_a_rule_of_the_port_checker() {
        for axis in [false, true] {
            for ready in [false, true] {
                for static_colour in [false, true] {
                    for (tag_bits, tlast) in [(0, false), (3, false), (0, true), (2, true)] {
                        for (clocked, clock_enable, reset_low) in [
                            (false, false, false),
                            (true, false, false),
                            (true, true, true),
                        ] {
                            let w = PortWidths {
                                axis,
                                ready: ready || axis,
                                static_colour,
                                tag_bits,
                                tlast: tlast && axis,
                                clocked: clocked || axis || ready,
                                clock_enable: clock_enable && (axis || ready),
                                reset_low,
                                ..default_widths()
                            };
                            for p in ports(w, "").iter().filter(|p| p.direction == "output") {
                                assert!(
                                    port_rule(p.name).is_some(),
                                    "{} has no rule of the port checker ({w:?})",
                                    p.name
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_padding_of_tdata_is_every_bit_between_its_fields() {
        let w = PortWidths {
            axis: true,
            ready: true,
            ..default_widths()
        };
        // intensity@0 (16 bits), spec_r@16, spec_g@24, spec_b@32 (8 each), done@40, 48 bits
        assert_eq!(padding(w, "m_axis_tdata"), vec![(47, 41)]);
        let narrow = PortWidths {
            axis: true,
            ready: true,
            color_bits: 4,
            intensity_frac_bits: 6,
            ..default_widths()
        };
        // intensity 7 bits @0, spec_r 4 @8, spec_g 4 @16, spec_b 4 @24, done @32, 40 bits
        assert_eq!(
            padding(narrow, "m_axis_tdata"),
            vec![(39, 33), (31, 28), (23, 20), (15, 12), (7, 7)]
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
        );
        assert!(padding(w, "m_axis_tuser").is_empty());
    }
}
