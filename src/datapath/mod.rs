//! Stage 3c: every model's datapath as a list of steps, from which the RTL is rendered —
//! one builder, one liveness pass, one delay model, one renderer (`templates/unit.v`).
//!
//! Every step is a set of wires. After step K comes cut K: a pipeline register where
//! the plan says, else nothing at all — a reference resolves to the last
//! register holding the signal, or to the wire (or port) that defines it ([`visible`]). The
//! [`Builder`] works out which signals are alive across each registered cut (only those get
//! registers), collects the bits nobody reads into one lint sink, holds the unit's tables
//! (ROMs) and keeps a delay estimate per step, from which `plan::balanced_cuts` places the
//! registers.
//!
//! The builder knows no model: each model (`crate::models`) describes its own datapath on it,
//! and `crate::plan` decides which cuts hold registers.

use crate::bits::{lit, mask};
use crate::config::Target;
pub use crate::ports::CHANNELS;
pub use crate::table::Table;
use std::collections::BTreeMap;

/// Width of a DSP block's multiplier operands (iCE40 SB_MAC16: 16×16), the split width of the
/// models' products.
pub(crate) use crate::family::ice40::MULTIPLIER_BITS as DSP_BITS;

/// The most low bits split off the bracket for the squarer: `lo²` then comes from a table of
/// 2^6 = 64 entries in LUTs, and `hi·lo` from one DSP (the bracket is at most UQ1.21 there).
pub(crate) const MAX_SQUARER_SPLIT: u32 = 6;

/// The most address bits one part of a table written as logic reads, where a model's table
/// is read with `Builder::rom_read_registered` under `--rom-style logic`: one LUT4 a bit (of 5
/// or 6, two LUT4 and a PFUMX that the placer may put apart: fitted's table at 239-241 MHz).
pub(crate) const LOGIC_PART_BITS: u32 = 4;

/// The inputs of a fabric LUT (iCE40 LUT4, ECP5 LUT4): a function of more takes two levels.
pub(crate) const LUT_INPUTS: u32 = 4;

/// Width of an ECP5 MULT18X18D's operands (`crate::family::ecp5`).
pub(crate) use crate::family::ecp5::MULTIPLIER_BITS as ECP5_DSP_BITS;

/// A product on an ECP5 MULT18X18D with its own registers: the input registers take the
/// operands at the cut before the product's step, the output register is the cut after it.
#[derive(Debug, Clone)]
pub struct Dsp {
    /// the product signal; its wire is `name_cK` (the DSP's output register is cut K)
    pub(crate) name: String,
    /// bits of the product kept (the rest of the 36-bit P goes to `unused_<name>_p`)
    pub(crate) width: u32,
    /// 18-bit operands, as seen in the step before (the input registers take them there)
    pub(crate) a: String,
    pub(crate) b: String,
    pub(crate) comment: String,
}

/// One wire of a step: `wire [width-1:0] name_sK = expr;   // comment`.
#[derive(Debug, Clone)]
pub struct Wire {
    pub(crate) name: String,
    pub(crate) width: u32,
    /// what it computes ([`Kind`]), typed when the builder made it
    pub(crate) kind: Kind,
    pub(crate) expr: Expr,
    pub(crate) comment: String,
    /// `(* keep *)`: a LUT boundary synthesis keeps ([`Builder::wire_kept`])
    pub(crate) keep: bool,
}

impl Wire {
    /// Whether the wire only selects and concatenates bits (and constants): no logic, no delay.
    pub(crate) fn is_plain(&self) -> bool {
        self.kind == Kind::Select
    }

    /// A product the family's synthesis maps: its operands' significant bits.
    pub(crate) fn product(&self) -> Option<(u32, u32)> {
        match self.kind {
            Kind::Product(a, b) => Some((a, b)),
            _ => None,
        }
    }
}

#[derive(Debug, Clone)]
pub struct Step {
    /// 1-based
    pub(crate) index: usize,
    pub(crate) title: String,
    pub(crate) wires: Vec<Wire>,
    /// products on ECP5 DSP blocks with their own registers (`Builder::product`)
    pub(crate) dsps: Vec<Dsp>,
    /// Delay estimate (ns on a LUT4 + carry-chain fabric, only ratios matter; and the
    /// primitives it counts)
    pub(crate) delay: Delay,
    /// a product here is too small for the family's block and lands in LUTs
    /// ([`Builder::product_delay`]): the step is logic, never a hard block on its own
    pub(crate) soft_product: bool,
    /// the product in LUTs has operands of two bits or more: a LUT multiplier (too small for
    /// the block, yosys's threshold on the iCE40), not an AND of a bit
    pub(crate) small_product: bool,
}

/// A signal alive across a cut, and the name it is taken from there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Live {
    pub(crate) name: String,
    pub(crate) width: u32,
    pub(crate) source: String,
}

/// A read of a table in a step: `signal_sK = table[addr]`.
#[derive(Debug, Clone)]
pub struct RomRead {
    pub(crate) step: usize,
    pub(crate) signal: String,
    pub(crate) table: usize,
    /// the address as a Verilog expression of this step (of the step before, for a block read)
    pub(crate) addr: String,
    /// on an ECP5 DP16KD with its output register: the address register stands in for the cut
    /// before this step, the output register is the cut after it (`signal_cK`)
    pub(crate) block: bool,
    /// how many of its step's wires come before it (the RTL declares in definition order)
    pub(crate) position: usize,
}

/// Words and width an ECP5 DP16KD holds in its 1024 x 18 mode.
pub(crate) const DP16KD_WORDS: usize = 1024;
pub(crate) const DP16KD_BITS: u32 = 18;
/// A registered table read spreads its word over at most this many DP16KDs side by side.
pub(crate) const MAX_BLOCK_SLICES: u32 = 4;

#[derive(Debug, Clone)]
pub struct Datapath {
    pub tables: Vec<Table>,
    pub(crate) reads: Vec<RomRead>,
    pub steps: Vec<Step>,
    /// `live[K-1]`: the signals cut K carries, in definition order.
    pub(crate) live: Vec<Vec<Live>>,
    /// The bits no step reads, as Verilog selects (`x_c3[7:1]`), for the one lint sink.
    pub(crate) unused: Vec<String>,
    /// Each output port's source after the last step.
    pub outputs: Vec<(String, String)>,
    pub(crate) registered: Vec<u32>,
    /// Every name a step, an output or the lint sink reads, with the bits read: a delay line
    /// names only these words.
    pub(crate) read: BTreeMap<String, u128>,
    /// The signals a multiplier computes: their first register stays a register of its own,
    /// outside any delay line, so that synthesis can take it into the DSP block as its output
    /// register (yosys 0.23's ice40_dsp, given a product registered as the low word of a wider
    /// shift register, takes the whole register and changes the function).
    pub(crate) products: Vec<String>,
    /// every product, hard or in the fabric ([`ProductUse`])
    pub product_uses: Vec<ProductUse>,
    /// the products one of whose operands has constant zero low bits: yosys takes the shift
    /// out of the multiply, and the product's add and register with it, out of the block
    pub(crate) shifted_products: Vec<String>,
    /// copies of a register, each for its own readers: kept (`(* keep *)` on the register and
    /// its flip-flop), so that synthesis neither merges them nor shares logic between their
    /// readers (a table's address per part, [`Builder::rom_read_registered`]; the colour
    /// operand per block, [`Builder::colour_copies`])
    pub(crate) copies: Vec<String>,
}

impl Datapath {
    /// Whether a multiplier reads the register `name_cK`, directly or through wires that only
    /// select and concatenate its bits: such a register stays out of the DSP block (`(* keep *)`,
    /// which yosys's ice40_dsp honours). Two reasons:
    /// - correctness: when the register is a block's output (a product, or bits of one),
    ///   yosys 0.23's and 0.70's ice40_dsp would take that one flip-flop into both blocks, as
    ///   the first's output register and the second's input register, and leave the second
    ///   reading the first's unregistered output: the function changes (the colour products
    ///   of the 13-stage lean unit read `16'b000000xxxxxxxxxx` under 0.70). Synthesis sees one
    ///   flip-flop through wires that only slice it (`square_s11 = square_z_c10[30:14]`), so
    ///   those count as reads;
    /// - speed: yosys 0.70 takes an operand's register into the block as its input register,
    ///   and the logic before it, with the long route into the DSP tile, becomes the path
    ///   (fitted at 60 stages: 88 MHz; kept in the fabric: 100).
    pub(crate) fn read_by_block(&self, name: &str, k: usize) -> bool {
        let mut aliases = vec![format!("{name}_c{k}")];
        for s in &self.steps {
            for w in &s.wires {
                if w.is_plain() && w.expr.reads.iter().any(|r| aliases.contains(r)) {
                    aliases.push(format!("{}_s{}", w.name, s.index));
                }
            }
        }
        let reads =
            |w: &Wire| w.product().is_some() && w.expr.reads.iter().any(|r| aliases.contains(r));
        self.steps.iter().flat_map(|s| &s.wires).any(reads)
    }

    /// The products the family's synthesis maps (a `*`, or an instantiated block): those the
    /// budget leaves out of the fabric, small ones (LUTs by the tool's own rule) included.
    pub fn mapped_products(&self) -> usize {
        self.steps
            .iter()
            .map(|s| s.dsps.len() + s.wires.iter().filter(|w| w.product().is_some()).count())
            .sum()
    }

    /// The hard blocks the product `name` takes (0: LUTs; one where no use is recorded).
    pub(crate) fn product_blocks(&self, name: &str) -> u32 {
        self.product_uses
            .iter()
            .find(|u| u.name == name)
            .map_or(1, |u| u.blocks)
    }

    /// The products `--dsp-budget` put in the fabric, by name.
    pub fn fabric_products(&self) -> Vec<&str> {
        self.product_uses
            .iter()
            .filter(|u| u.fabric)
            .map(|u| u.name.as_str())
            .collect()
    }

    pub(crate) fn delays(&self) -> Vec<f64> {
        self.steps.iter().map(|s| s.delay.ns).collect()
    }

    /// Whether some product is an ECP5 MULT18X18D with its registers (`<top>_mult18x18`).
    pub(crate) fn has_dsp_blocks(&self) -> bool {
        self.steps.iter().any(|s| !s.dsps.is_empty())
    }

    /// Whether some table read is an ECP5 DP16KD with its registers (`<top>_rom1k18`).
    pub(crate) fn has_block_rams(&self) -> bool {
        self.reads.iter().any(|r| r.block)
    }
}

#[derive(Debug, Clone)]
struct Signal {
    name: String,
    width: u32,
    step: usize,
    /// (step, bits read) for every reference
    uses: Vec<(usize, u128)>,
    /// held by a DSP's output register at the cut after its step (no fabric register there)
    dsp_registered: bool,
    /// an input held in a register of its own for every pixel (a static colour): read under
    /// this name at every step, never carried across a cut
    held: Option<String>,
}

/// A product of the datapath, hard or not: what `--dsp-budget` counts and trades.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProductUse {
    pub name: String,
    /// the operands' significant bits, and the bits kept
    pub a: u32,
    pub b: u32,
    pub width: u32,
    /// the family's blocks it takes as a hard product (`Family::product_blocks`)
    pub blocks: u32,
    /// summed from partial products in the fabric, by the unit's `--dsp-budget`
    pub fabric: bool,
}

/// Records the datapath step by step; see the module documentation.
pub struct Builder {
    steps: Vec<Step>,
    signals: Vec<Signal>,
    tables: Vec<Table>,
    reads: Vec<RomRead>,
    /// the cuts that hold a register (1-based)
    registered: Vec<u32>,
    target: Target,
    /// while the operands of a registered DSP are written: the step whose view they take
    view: Option<usize>,
    /// a shorter carry-select chunk than the family's, while a carry-save sum is closed
    chunk_limit: u32,
    /// every register or wire name a step, an output or the lint sink reads, with the bits read
    read: BTreeMap<String, u128>,
    /// the signals a multiplier computes (a `*` in their expression)
    products: Vec<String>,
    /// every product, hard or in the fabric, in the order made
    product_uses: Vec<ProductUse>,
    /// the products `--dsp-budget` puts in the fabric
    fabric: std::collections::BTreeSet<String>,
    /// [`Datapath::shifted_products`]
    shifted_products: Vec<String>,
    /// [`Datapath::copies`]
    copies: Vec<String>,
    /// `--rom-style logic`: a table read with [`Builder::rom_read_registered`] is written as
    /// LUTs over steps of its own, never a memory (the plan's choice for the unit)
    logic_tables: bool,
    /// `--fabric-registers` (implied by `--rom-style logic`): [`Builder::fabric_register_step`]
    fabric_registers: bool,
}

/// A signal the builder defined, as the datapath's code holds it: its name and width. The
/// builder's readers take it (or a name, for the unit's inputs) so that a model keeps the
/// handles its wires returned instead of spelling their names (`rem{k}`) and widths again.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sig {
    name: String,
    width: u32,
}

impl Sig {
    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn width(&self) -> u32 {
        self.width
    }
    /// All of it, as a piece of an operand.
    pub(crate) fn all(&self) -> Piece {
        Piece::sig(&self.name, 0, self.width)
    }
    /// Bits `[lo, lo+width)` of it, as a piece of an operand.
    pub(crate) fn part(&self, lo: u32, width: u32) -> Piece {
        assert!(
            lo + width <= self.width,
            "datapath: bits [{lo}, {}) of the {}-bit {}",
            lo + width,
            self.width,
            self.name
        );
        Piece::sig(&self.name, lo, width)
    }
}

impl AsRef<str> for Sig {
    fn as_ref(&self) -> &str {
        &self.name
    }
}

/// Bits `[lo, lo+width)` of a signal, optionally inverted; or a constant.
#[derive(Debug, Clone)]
pub enum Piece {
    Sig {
        name: String,
        lo: u32,
        width: u32,
        invert: bool,
    },
    Const {
        value: u128,
        width: u32,
    },
}

impl Piece {
    pub(crate) fn sig(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig {
            name: name.into(),
            lo,
            width,
            invert: false,
        }
    }
    pub fn not(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig {
            name: name.into(),
            lo,
            width,
            invert: true,
        }
    }
    pub(crate) fn zeros(width: u32) -> Piece {
        Piece::Const { value: 0, width }
    }
    fn width(&self) -> u32 {
        match self {
            Piece::Sig { width, .. } | Piece::Const { width, .. } => *width,
        }
    }
}

/// Whether `pieces` are all constant zeros (an addend that adds nothing).
pub(crate) fn all_zero(pieces: &[Piece]) -> bool {
    pieces
        .iter()
        .all(|p| matches!(p, Piece::Const { value: 0, .. }))
}

/// Bits `[lo, lo+width)` of the value the pieces (LSB first) make, zero above their top.
pub(crate) fn sub_pieces(pieces: &[Piece], lo: u32, width: u32) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut base = 0;
    for p in pieces {
        let (a, b) = (base.max(lo), (base + p.width()).min(lo + width));
        if a < b {
            out.push(match p {
                Piece::Sig {
                    name,
                    lo: plo,
                    invert,
                    ..
                } => Piece::Sig {
                    name: name.clone(),
                    lo: plo + a - base,
                    width: b - a,
                    invert: *invert,
                },
                Piece::Const { value, .. } => Piece::Const {
                    value: (value >> (a - base)) & mask(b - a),
                    width: b - a,
                },
            });
        }
        base += p.width();
    }
    let have: u32 = out.iter().map(Piece::width).sum();
    if have < width {
        out.push(Piece::zeros(width - have));
    }
    out
}

/// The kind of a wire that only writes `pieces`: a select, or logic when one is complemented.
pub(crate) fn pieces_kind(pieces: &[Piece]) -> Kind {
    match pieces
        .iter()
        .any(|p| matches!(p, Piece::Sig { invert: true, .. }))
    {
        true => Kind::Logic,
        false => Kind::Select,
    }
}

/// The bits of `pieces` (LSB first) below `width` that can be set: up to the last one that is
/// not a constant 0.
pub(crate) fn significant_bits(pieces: &[Piece], width: u32) -> u32 {
    let pieces = sub_pieces(pieces, 0, width);
    (0..width)
        .rev()
        .find(|&b| !zero_bit(&pieces, b))
        .map_or(0, |b| b + 1)
}

/// Bit `bit` of `pieces` (LSB first) where it is a constant; `None` where a signal holds it (or
/// beyond the pieces).
fn const_bit(pieces: &[Piece], bit: u32) -> Option<bool> {
    let mut base = 0;
    for p in pieces {
        if bit < base + p.width() {
            return match p {
                Piece::Const { value, .. } => Some((value >> (bit - base)) & 1 == 1),
                Piece::Sig { .. } => None,
            };
        }
        base += p.width();
    }
    None
}

/// Whether bit `bit` of `pieces` (LSB first) is a constant 0.
fn zero_bit(pieces: &[Piece], bit: u32) -> bool {
    const_bit(pieces, bit) == Some(false)
}

/// A wide add started by [`Builder::add_start`], finished by [`Builder::add_finish`].
pub(crate) struct PendingAdd {
    name: String,
    width: u32,
    /// the chunks `(lo, width)` of a carry-select add (empty: one chain, done)
    pub(crate) chunks: Vec<(u32, u32)>,
    /// 1 when chunk 0 carries its carry-in as an extra low bit
    part0_offset: u32,
    /// per chunk: the second addend is 0 there, so its carry-in-0 sum has no carry-out
    no_carry_out: Vec<bool>,
    /// the top chunk's top bit is the add's carry-out (both operands 0 there), held
    /// complemented as the other chunks' carries are; [`Builder::add_finish`] restores it
    top_inverted: bool,
    /// per chunk, per bit: the value of its carry-in-0 sum there where that is a constant (the
    /// second addend 0 over the chunk and the first a constant bit), as the pick reads it
    plain_consts: Vec<Vec<Option<bool>>>,
    comment: String,
}

/// A signal that waits in a [`DelayLine`]: its word after cut K is `x_cK`.
pub(crate) struct Waiting {
    pub(crate) name: String,
    pub(crate) width: u32,
    /// what its first word takes (`x_sK`, a port, a block's output)
    pub(crate) source: String,
    /// per cut of the line: the bits something past the line reads (0: none; the last word is
    /// always named)
    pub(crate) read: Vec<u128>,
}

mod builder;
mod carry_select;
mod colour;
mod delay;
mod delay_line;
pub(crate) mod expr;
mod normalise;
pub(crate) use expr::{ex, Expr, Kind};
mod products;
mod reduce;
pub(crate) use products::{pad_operands, MulItem};
mod sums;
mod tables;
#[cfg(test)]
mod tests;

pub(crate) use delay::*;
pub(crate) use delay_line::*;
