//! Lattice iCE40 UP5K: SB_MAC16 16×16 multipliers with post-adders, SB_RAM40_4K block RAM,
//! yosys's `synth_ice40`, nextpnr-ice40 (sg48 package) and IceStorm's `icetime`.

use super::{BlockLimit, Family, PlaceAndRoute};
use crate::config::Target;
use std::path::{Path, PathBuf};

/// Longest carry chain of one lean step (bits). iCE40 UP5K post-route, operands and sum
/// straight from and to registers, carry-out registered too: 4 bits ~109 MHz, 6 bits
/// ~103 MHz, 8 bits ~92 MHz.
pub(crate) const CHUNK_BITS: u32 = 6;

/// Width of an SB_MAC16's multiplier operands: 16×16.
pub(crate) const MULTIPLIER_BITS: u32 = 16;

/// yosys's `synth_ice40 -dsp` maps a product to an SB_MAC16 only when it has at least this
/// many bits (`DSP_Y_MINWIDTH`, after `wreduce`), and each operand at least 2.
const MIN_PRODUCT_BITS: u32 = 11;

pub(super) struct Ice40;

/// The iCE40 UP5K's primitive delays (post-route figures of nextpnr-ice40, each with its
/// route: a LUT4 ~1.2 ns in the cell library plus ~1.5 of route, a carry 0.3 ns a bit with its
/// SB_CARRY's entry and exit, an SB_MAC16 multiply ~5.5 ns): the figures the datapath's delay
/// estimates are written in (`datapath::Delay`), which place the registers on every family.
pub(crate) const PRIMITIVE_DELAYS: crate::family::PrimitiveDelays =
    crate::family::PrimitiveDelays {
        lut: 2.7,
        carry: 0.7,
        carry_bit: 0.3,
        dsp: 5.5,
        array_level: 1.5,
        route: 1.0,
    };

impl Family for Ice40 {
    fn name(&self) -> &'static str {
        "ice40"
    }
    fn part(&self) -> &'static str {
        "iCE40 UP5K"
    }
    fn fmax_ceiling_mhz(&self) -> f64 {
        400.0
    }
    fn logic_capacity(&self) -> Option<u64> {
        Some(5280)
    }
    fn dsp_capacity(&self) -> Option<u64> {
        Some(8)
    }
    fn explored(&self) -> Option<&'static str> {
        Some(include_str!("../../data/explore/ice40.json"))
    }
    fn explore_clocks(&self) -> &'static [f64] {
        &[50.0, 75.0, 100.0, 125.0]
    }
    fn synth_command(&self, dsp: bool, top: &str) -> String {
        format!("synth_ice40 -top {top}{}", if dsp { " -dsp" } else { "" })
    }
    fn place_and_route(&self, _grade: u32) -> Option<PlaceAndRoute> {
        Some(PlaceAndRoute {
            tools: &["nextpnr-ice40"],
            install: "apt-get install -y nextpnr-ice40",
            args: ["--up5k", "--package", "sg48", "--pcf-allow-unconstrained"]
                .map(String::from)
                .to_vec(),
        })
    }
    fn icetime(&self) -> bool {
        true
    }
    fn block_limits(&self, _grade: u32, dsp: bool, _bram: bool) -> Vec<BlockLimit> {
        // SB_RAM40_4K: IceStorm's data has no pulse width or period: no limit is known
        let mut out = Vec::new();
        if dsp {
            out.push(BlockLimit {
                block: "SB_MAC16",
                period_ns: 6.504,
                what:
                    "SB_MAC16 input to output register setup 6.504 ns, UP5K (IceStorm icefuzz/timings_up5k.txt, MAC_U_16X16_BYPASS); untimed by nextpnr-ice40"
                        .into(),
            });
        }
        out
    }
    fn has_block_ram(&self) -> bool {
        true
    }
    fn synthesized_on(&self) -> Target {
        Target::Ice40
    }
    fn multiplier_bits(&self) -> u32 {
        MULTIPLIER_BITS
    }
    /// Below 0xC000: yosys 0.23's `synth_ice40 -dsp` maps a multiply by a 16-bit constant of
    /// 0xC000 or more (its two top bits set) to an SB_MAC16 whose constant has lost its top bits
    /// (x·0xE5C9 read as x·0x25C9, x·0xF333 as x·0x1333, x·0xD555 as x·0x5555; 0xB333, 0x9999,
    /// 0x7FFF map right; yosys 0.70 maps them all right). Found on the lean unit at `--k` 0.8,
    /// 0.95 and 0.99 and at KF = 20 (k_lo = 0xE5C9), each netlist then refused by `synth`'s
    /// check. Such a constant is split at 15 bits instead (every constant below 0x8000 maps
    /// right), and no other: splitting k_q = 0xB333 (`--k 0.7`) too left 0.23 the add outside
    /// the block and its register unused, at default widths and 12 stages.
    fn takes_constant(&self, value: u128) -> bool {
        value < 0xc000
    }
    fn carry_chunk_bits(&self) -> u32 {
        CHUNK_BITS
    }
    fn soft_product(&self, a: u32, b: u32, y: u32) -> bool {
        a.min(b) < 2 || y.min(a + b) < MIN_PRODUCT_BITS
    }
    /// ice40_dsp takes a product's register into the SB_MAC16 (and its post-adder's)
    fn cell_kind(&self, cell: &str) -> Option<super::CellKind> {
        use super::CellKind::*;
        Some(match cell {
            "SB_LUT4" => Lut,
            "SB_CARRY" => Carry,
            "SB_MAC16" => Dsp,
            c if c.starts_with("SB_DFF") => FlipFlop,
            c if c.starts_with("SB_RAM40") => BlockRam,
            _ => return None,
        })
    }
    fn registers_inferred_blocks(&self) -> bool {
        true
    }
    /// yosys 0.23 leaves a sum wider than the product's operands together in the fabric, on
    /// the product's unregistered output.
    fn post_adder(&self, width: u32, wa: u32, wb: u32) -> bool {
        width <= wa + wb
    }
    /// one layer a step: yosys 0.70's ABC maps a layer of up to 9 registers to three LUT4
    /// levels
    fn carry_save_layers_per_step(&self) -> usize {
        1
    }
    /// each of their bits feeds two carry chains (carry-select), and a flip-flop with no logic
    /// before it is free to sit between them (from the carry-save layers' LUTs a bit crosses a
    /// 3 ns route)
    fn registers_carry_save_vectors(&self) -> bool {
        true
    }
    /// the SB_MAC16 multiplies 16×16: a wider bracket is split, squared with one block product
    fn splits_wide_squares(&self) -> bool {
        true
    }
    fn pads_block_operands(&self) -> bool {
        true
    }
    fn copies_block_operands(&self) -> bool {
        true
    }
    fn cell_models(
        &self,
        datdir: &Path,
        _top: &str,
    ) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)> {
        let text = super::read(&datdir.join("ice40/cells_sim.v"))?;
        // port default values are SystemVerilog; the netlist connects every port it uses
        Ok(vec![(
            "ice40_cells_sim.v".into(),
            format!("`define NO_ICE40_DEFAULT_ASSIGNMENTS\n{text}"),
        )])
    }
}
