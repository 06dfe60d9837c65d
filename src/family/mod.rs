//! One home per FPGA family (issue: a family as one home, like a model): what `synth`, the
//! delay model and the block limits need to know of a family, behind one trait, with the one
//! exhaustive registry ([`of`]). A third family is a file here and an arm of [`of`].
//!
//! What lives here today: the family's name and part, its synthesis command and the primitive
//! library read beside the RTL, its place-and-route tools and device options, its second timer,
//! its speed grades, its hard blocks' own limits (the vendors' timing data, for what nextpnr
//! does not time), whether it has block RAM, and the name its delay-model calibration goes by.
//! The datapath's block shapes live here too: the multiplier's operand width, the carry chain a
//! step holds, which products yosys leaves in LUTs, the post-adder, blocks instantiated with
//! their own registers, the carry-save layers a step holds, distributed RAM, the constraint
//! file and FuseSoC's synthesis arch, the split of a wide square and the padding of a block's
//! operands. No file outside this home names a family (`tests::family_names_stay_home`).

pub mod blocks;
pub(crate) mod ecp5;
mod generic;
mod gowin;
pub(crate) mod ice40;

pub use ecp5::{ecp5_bram_model, ecp5_sim_model};

use crate::config::Target;
use std::path::{Path, PathBuf};

/// A block's minimum clock period on one part and speed grade, and where it comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockLimit {
    /// the primitive (`DP16KD`, `MULT18X18D`, `SB_MAC16`)
    pub(crate) block: &'static str,
    /// its minimum period, ns
    pub(crate) period_ns: f64,
    /// what the period is, in words, with the source
    pub(crate) what: String,
}

impl BlockLimit {
    /// Its clock, rounded down to 0.1 MHz (a limit is never rounded up).
    pub fn mhz(&self) -> f64 {
        (10_000.0 / self.period_ns).floor() / 10.0
    }
}

/// A family's primitive delays, ns (FloPoCo's way: what a LUT level, a carry chain and its
/// bits, a hard multiply, a level of a partial-product array and a register-only route cost on
/// the part, each with its route), from which the delay model reads a datapath's stretches
/// between registers on that family (`crate::timing`). Only the ratios and the order of the
/// stretches matter: the delay model's line per datapath scales them to the part's clock.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimitiveDelays {
    /// one LUT level and its route
    pub lut: f64,
    /// a carry chain's entry and exit (the LUT that brings its carry-out back excluded: counted
    /// as a LUT level)
    pub carry: f64,
    /// a carry chain, per bit
    pub carry_bit: f64,
    /// a hard multiply between registers in the fabric (into the block, through, out)
    pub dsp: f64,
    /// a level of a partial-product array past the block's operands
    pub array_level: f64,
    /// a route from one register to another with no logic
    pub route: f64,
}

impl PrimitiveDelays {
    /// In the order of `datapath::Delay`'s parts.
    pub(crate) fn as_array(&self) -> [f64; 6] {
        [
            self.lut,
            self.carry,
            self.carry_bit,
            self.dsp,
            self.array_level,
            self.route,
        ]
    }
}

/// A place-and-route tool of a family: the programs tried in order, how to install the first,
/// and the device options.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlaceAndRoute {
    pub tools: &'static [&'static str],
    pub install: &'static str,
    pub args: Vec<String>,
}

/// The hard blocks a family's unit instantiates (`Family::instantiated_blocks`): one product
/// module `<top>_mult18x18` (18×18 → 36, input and output registers) and one table module
/// `<top>_rom1k18` (1024 × 18, address and output registers), each written by the family around
/// its own primitive, with the primitive's simulation model beside.
pub struct Blocks {
    /// the vendor and the family as the unit's header names them (`Lattice`, `ECP5`)
    pub vendor: &'static str,
    pub family: &'static str,
    /// the product's and the table's primitive (`MULT18X18D`, `DP16KD`)
    pub dsp: &'static str,
    pub bram: &'static str,
    /// what each simulation model's file name adds to the top's, under `sim/`
    pub dsp_model_suffix: &'static str,
    pub bram_model_suffix: &'static str,
    /// the product module's and the table module's RTL for a top
    pub dsp_module: RenderFor,
    pub bram_module: RenderFor,
    /// the primitives' simulation models
    pub dsp_model: fn() -> String,
    pub bram_model: fn() -> String,
    /// the table module's contents parameters holding up to 1024 words of 18 bits
    pub bram_init: fn(&[u128]) -> Vec<(String, String)>,
    /// every multiplier primitive of the family a netlist may hold (the one instantiated, and
    /// those the synthesis tool infers), with its register parameters and what each registers:
    /// a value of none, `NONE` or zeros is no register
    pub dsp_registers: &'static [(&'static str, &'static [(&'static str, &'static str)])],
    /// black boxes of the primitives for a synthesis tool that lacks them, as an RTL file the
    /// unit brings (what its name adds to the top's, its text for a top); None: the tools know them
    pub boxes: Option<(&'static str, RenderFor)>,
}

/// A file's text for a unit's top.
pub type RenderFor = fn(&str) -> String;

/// A bitstream packer of a family: the programs tried in order, how to install the first, and
/// its arguments before `-o <file> <routed json>`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Packer {
    pub tools: &'static [&'static str],
    pub install: &'static str,
    pub args: &'static [&'static str],
}

/// What a cell of a family's netlist counts as in `synth`'s figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellKind {
    Lut,
    Carry,
    Dsp,
    FlipFlop,
    BlockRam,
}

/// What a family is, for synthesis, place-and-route, block limits and the delay model.
pub trait Family: Sync {
    /// `generate --target`'s value for it.
    fn name(&self) -> &'static str;
    /// The part its figures are for (a family with none says so).
    fn part(&self) -> &'static str;
    /// The clocks `explore` measures its fronts at, MHz (from a slow unit to the blocks'
    /// limits): a depth is chosen per clock and the front is drawn per clock. Empty: no
    /// place-and-route to measure a clock with.
    fn explore_clocks(&self) -> &'static [f64];
    /// The clock the constraint files and `synth` ask for when the unit names none, MHz.
    fn default_clock_mhz(&self) -> f64 {
        100.0
    }
    /// Whether a table may be written as logic (`--rom-style logic`: kept out of block RAM
    /// where block RAM's own clock limit is below the rest of the unit's).
    fn writes_logic_tables(&self) -> bool {
        false
    }
    /// The hard multiplier blocks of the part its figures are for (None: no part): `explore`
    /// measures no unit that needs more.
    fn dsp_capacity(&self) -> Option<u64>;
    /// The logic cells of the part (its LUT4s; a slice holds two on the ECP5): no measurement
    /// counts more. None: no part.
    fn logic_capacity(&self) -> Option<u64> {
        None
    }
    /// No place-and-route of the part reports a clock above this (its fabric's and clock
    /// network's reach, with margin): a measurement above it is refused as not a measurement.
    fn fmax_ceiling_mhz(&self) -> f64 {
        1000.0
    }
    /// The exploration built in for `generate --max-error` (`specgen explore`'s points.json,
    /// measured by `scripts/explore.sh`), if one was measured for the family.
    fn explored(&self) -> Option<&'static str> {
        None
    }
    /// yosys's synthesis command for module `top` (`dsp`: hard multipliers allowed).
    fn synth_command(&self, dsp: bool, top: &str) -> String;
    /// What yosys reads before the RTL: the library of the primitives the RTL instantiates.
    fn primitives_lib(&self) -> &'static str {
        ""
    }
    /// Its place-and-route at speed grade `grade` (where the family has grades); None: none.
    fn place_and_route(&self, grade: u32) -> Option<PlaceAndRoute>;
    /// Whether the placed design is also written for IceStorm's `icetime` (`--asc`).
    fn icetime(&self) -> bool {
        false
    }
    /// The speed grades its block limits and place-and-route know; None: no grades.
    fn speed_grades(&self) -> Option<&'static [u32]> {
        None
    }
    /// The minimum periods of the hard blocks a unit uses (`dsp`, `bram`), on its part at
    /// `grade`, from the vendors' timing data (`crate::family::blocks` says why and from where).
    fn block_limits(&self, grade: u32, dsp: bool, bram: bool) -> Vec<BlockLimit>;
    /// Its primitive delays on the part its delay model is calibrated on (see
    /// [`PrimitiveDelays`]; a family without a delay model: the iCE40's, which place the
    /// registers everywhere).
    fn primitive_delays(&self) -> PrimitiveDelays {
        ice40::PRIMITIVE_DELAYS
    }
    /// Block RAM with a read register (a long delay line's tail can wait there).
    fn has_block_ram(&self) -> bool;
    /// The family `synth` maps this family's RTL on when none is named: its own, or (RTL of no
    /// family) one that has place-and-route.
    fn synthesized_on(&self) -> Target;
    /// Whether its netlist is yosys's generic gates, every cell of which counts as logic.
    fn generic_gates(&self) -> bool {
        false
    }
    /// The widest multiplier operand one of its hard multipliers takes (u32::MAX: whole-width
    /// products, the synthesis tool's to split).
    fn multiplier_bits(&self) -> u32;
    /// Whether a hard multiplier takes `value` (a constant of at most
    /// [`Family::multiplier_bits`] bits) as an operand whole: every value, unless the synthesis
    /// tool mis-maps some (a constant it refuses is split lower, its high part by shift-adds:
    /// [`crate::datapath::Builder::constant_split`]).
    fn takes_constant(&self, _value: u128) -> bool {
        true
    }
    /// The longest carry chain one pipeline step may hold (u32::MAX: no limit).
    fn carry_chunk_bits(&self) -> u32;
    /// Whether yosys leaves an a×b multiply kept to `y` bits in LUTs here: too small for its
    /// block.
    fn soft_product(&self, a: u32, b: u32, y: u32) -> bool;
    /// The blocks an a×b product kept to `y` bits takes: none when it is LUTs
    /// ([`Family::soft_product`]), else one per pair of operand slices of the block's width
    /// (generic: one, a multiplier the user's tool may map to one block).
    fn product_blocks(&self, a: u32, b: u32, y: u32) -> u32 {
        match self.soft_product(a, b, y) {
            true => 0,
            false => a.div_ceil(self.multiplier_bits()) * b.div_ceil(self.multiplier_bits()),
        }
    }
    /// Whether a multiply-add of `width` bits from an a×b product takes its add inside the
    /// block (a post-adder the synthesis tool uses).
    fn post_adder(&self, width: u32, wa: u32, wb: u32) -> bool;
    /// Whether yosys takes an inferred product's register into the block as its output
    /// register (ice40_dsp on the iCE40). Where it does not (the ECP5's inferred multipliers,
    /// which yosys maps without registers; generic RTL, which names no block), a unit
    /// promises registers only on the blocks it instantiates.
    fn registers_inferred_blocks(&self) -> bool {
        false
    }
    /// Whether products and table reads are instantiated blocks with their own input and
    /// output registers (where the cuts allow), rather than inferred by the synthesis tool;
    /// such a family has no post-adder, and its adds are one carry chain a step.
    fn instantiated_blocks(&self) -> bool {
        false
    }
    /// The carry-save layers a step holds in a sum of many terms.
    fn carry_save_layers_per_step(&self) -> usize {
        2
    }
    /// Whether a carry-save sum's two vectors are registered in a step of their own before
    /// their carry-select add.
    fn registers_carry_save_vectors(&self) -> bool {
        false
    }
    /// Whether a square wider than the multiplier is split `x = h·2^r + l` into one block
    /// product `h²` (and `h·l`) and a small table for `l²`, rather than left to the tool.
    fn splits_wide_squares(&self) -> bool {
        false
    }
    /// Whether a table word that feeds a multiply-add on the block carries its operands at the
    /// block's width (the iCE40's SB_MAC16 takes them whole, its post-adder the entry).
    fn pads_block_operands(&self) -> bool {
        false
    }
    /// Whether a table in LUTs (`--rom-style logic`) gives each of its parts a register copy of
    /// the address bits it reads, in a step of its own before them: ABC9 maps the parts,
    /// functions of the same four bits, through each other's LUTs where its timing model sees
    /// slack (fitted's table three and four LUT4 levels deep, n_c1 → part28 → part36 → part17,
    /// at 227 MHz on the ECP5); parts that read distinct registers share no logic.
    fn copies_table_address(&self) -> bool {
        false
    }
    /// Whether an operand several blocks read is registered once per block: the blocks sit
    /// apart (the UP5K's DSPs in two columns at the die's edges), and one register's route to
    /// the farthest is most of a clock (8.3 ns: blinn's colour products at 102.6 MHz).
    fn copies_block_operands(&self) -> bool {
        false
    }
    /// Whether a delay line may sit in distributed (LUT) RAM.
    fn distributed_ram(&self) -> bool {
        false
    }
    /// Whether its place-and-route reads the unit's clock from an `.lpf` (nextpnr-ecp5)
    /// beside the `.sdc` every unit has.
    fn lpf_constraints(&self) -> bool {
        false
    }
    /// The `arch` FuseSoC's `synth` target of the `.core` maps its RTL for (`ice40`, `ecp5`).
    fn fusesoc_arch(&self) -> &'static str {
        self.synthesized_on().name()
    }
    /// The hard blocks its units instantiate (None: it instantiates none).
    fn blocks(&self) -> Option<&'static Blocks> {
        None
    }
    /// The library of black boxes of the primitives its RTL instantiates that yosys ships, read
    /// before the RTL where no synthesis command does (`specgen prove`); None: the unit brings
    /// its own ([`Blocks::boxes`]), or there are none.
    fn primitive_boxes(&self) -> Option<&'static str> {
        None
    }
    /// What a cell of its netlist counts as (None: nothing of the family's; yosys's own
    /// internal cells are counted by `synth`).
    fn cell_kind(&self, _cell: &str) -> Option<CellKind> {
        None
    }
    /// Constraint files a unit brings beside its `.sdc` (and `.lpf`): (file name, text).
    fn constraint_files(&self, _top: &str) -> Vec<(String, String)> {
        Vec::new()
    }
    /// Files its place-and-route reads beside the synthesized wrapper (the `.cst` its
    /// arguments name): (file name, text).
    fn place_and_route_files(&self) -> Vec<(String, String)> {
        Vec::new()
    }
    /// Hard-block paths its place-and-route does not time and no limit of
    /// [`Family::block_limits`] covers, in words (None: every used block is timed or capped).
    fn untimed_blocks(&self, _dsp: bool, _bram: bool) -> Option<String> {
        None
    }
    /// Its bitstream packer (None: `synth --bitstream` is refused for it).
    fn packer(&self) -> Option<Packer> {
        None
    }
    /// The simulation models of its cells, for co-simulating a mapped netlist, as (file name,
    /// text), read from yosys's data directory `datdir` (`top`: the unit's own models' prefix).
    fn cell_models(
        &self,
        datdir: &Path,
        top: &str,
    ) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)>;
}

/// Reads `path`, its error naming it.
pub(crate) fn read(path: &Path) -> Result<String, (PathBuf, std::io::Error)> {
    std::fs::read_to_string(path).map_err(|e| (path.to_path_buf(), e))
}

/// The family of `target`: the one registry, exhaustive over the targets.
/// The clock the unit's constraints and `synth` ask for: its `clock_mhz`, else its family's
/// default.
pub fn clock_mhz(cfg: &crate::config::Config) -> f64 {
    cfg.explicit_clock_mhz()
        .unwrap_or_else(|| of(cfg.target()).default_clock_mhz())
}

pub fn of(target: Target) -> &'static dyn Family {
    match target {
        Target::Ice40 => &ice40::Ice40,
        Target::Ecp5 => &ecp5::Ecp5,
        Target::Generic => &generic::Generic,
        Target::Gowin => &gowin::Gowin,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The registry answers for every target by its own name.
    #[test]
    fn every_target_has_its_home() {
        for t in Target::ALL {
            assert_eq!(of(t).name(), t.name());
            // a family copied from another brings none of its data: its exploration is its own
            if let Some(json) = of(t).explored() {
                let explored: serde_json::Value = serde_json::from_str(json).unwrap();
                assert_eq!(
                    explored["target"],
                    t.name(),
                    "{}'s built-in exploration",
                    t.name()
                );
            }
        }
        assert!(of(Target::Generic).place_and_route(6).is_none());
        assert!(of(Target::Ecp5)
            .place_and_route(6)
            .unwrap()
            .args
            .contains(&"6".to_string()));
    }

    /// A family named outside its home: every `Target::Ice40`, `Target::Ecp5` or
    /// `Target::Generic` in the code (not the unit tests) of `src/` outside `src/family/` and
    /// the enum's own files (`config/kinds.rs`, and `config/mod.rs` for the default). There is none: a comparison elsewhere would give a new family
    /// another's behaviour in silence.
    #[test]
    fn family_names_stay_home() {
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = vec![src.clone()];
        while let Some(p) = files.pop() {
            for e in std::fs::read_dir(&p).unwrap() {
                let path = e.unwrap().path();
                if path.is_dir() {
                    files.push(path);
                } else if path.extension().is_some_and(|x| x == "rs") {
                    let rel = path
                        .strip_prefix(&src)
                        .unwrap()
                        .to_string_lossy()
                        .replace('\\', "/");
                    // a `tests.rs` is a module of unit tests as a whole
                    if rel.starts_with("family/")
                        || rel == "config/kinds.rs"
                        || rel == "config/mod.rs"
                        || rel.ends_with("tests.rs")
                    {
                        continue;
                    }
                    let text = std::fs::read_to_string(&path).unwrap();
                    let code = text.split("#[cfg(test)]").next().unwrap_or("");
                    let n = ["Target::Ice40", "Target::Ecp5", "Target::Generic"]
                        .iter()
                        .map(|t| code.matches(t).count())
                        .sum::<usize>();
                    assert!(n == 0, "src/{rel} names a family {n} times (at most 0): ask crate::family::of(target) instead");
                }
            }
        }
    }

    /// The block limits SPEC states are the ones `synth` applies: each limit's minimum period
    /// and its clock, on every grade, stand in the SPEC's row of that block, and `synth
    /// --speed`'s help names the DP16KD's clock at each grade (a changed figure in a family's
    /// home fails here until the words follow).
    #[test]
    fn the_spec_states_the_block_limits_the_families_apply() {
        let help = include_str!("../cli/synth.rs");
        let dp = |grade| {
            of(crate::config::Target::Ecp5)
                .block_limits(grade, true, true)
                .into_iter()
                .find(|l| l.block == "DP16KD")
                .unwrap()
                .mhz()
        };
        let said = format!(
            "(DP16KD: {:.1} MHz at 6, {:.1} at 7, {:.1} at 8)",
            dp(6),
            dp(7),
            dp(8)
        );
        assert!(
            help.contains(&said),
            "synth --speed's help does not say {said}"
        );
        let spec = include_str!("../../docs/SPEC.md");
        for target in crate::config::Target::ALL {
            for grade in [6, 7, 8] {
                for limit in of(target).block_limits(grade, true, true) {
                    let row = spec
                        .lines()
                        .find(|l| l.starts_with(&format!("| {} |", limit.block)))
                        .unwrap_or_else(|| panic!("SPEC has no row for {}", limit.block));
                    // a period of two pulse widths is stated as the pulse
                    let (period, pulse) = (
                        format!("{}", limit.period_ns),
                        format!("{}", (limit.period_ns / 2.0 * 1e3).round() / 1e3),
                    );
                    let mhz = format!("{:.1}", limit.mhz());
                    assert!(
                        (row.contains(&period) || row.contains(&format!("2 × {pulse}")) || row.contains(&format!("/ {pulse}")))
                            && row.contains(&mhz),
                        "{target:?} grade {grade}: {} {period} ns / {mhz} MHz not in SPEC's row: {row}",
                        limit.block
                    );
                }
            }
        }
    }
}
