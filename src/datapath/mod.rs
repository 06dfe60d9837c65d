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
    pub(crate) expr: String,
    pub(crate) comment: String,
}

impl Wire {
    /// Whether the wire only selects and concatenates bits (and constants): no logic, no delay.
    pub(crate) fn is_plain(&self) -> bool {
        self.expr.chars().all(|c| c.is_alphanumeric() || "_[]:{}, '".contains(c))
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
    /// Delay estimate (ns on a LUT4 + carry-chain fabric); only ratios matter.
    pub(crate) delay: f64,
    /// a product here is too small for the family's block and lands in LUTs
    /// ([`Builder::product_delay`]): the step is logic, never a hard block on its own
    pub(crate) soft_product: bool,
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
        let tokens = |e: &str| e.split(|c: char| !(c.is_alphanumeric() || c == '_')).map(str::to_string).collect::<Vec<_>>();
        let mut aliases = vec![format!("{name}_c{k}")];
        for s in &self.steps {
            for w in &s.wires {
                if w.is_plain() && tokens(&w.expr).iter().any(|t| aliases.contains(t)) {
                    aliases.push(format!("{}_s{}", w.name, s.index));
                }
            }
        }
        let reads = |w: &Wire| w.expr.contains(" * ") && tokens(&w.expr).iter().any(|t| aliases.contains(t));
        self.steps.iter().flat_map(|s| &s.wires).any(reads)
    }

    pub(crate) fn delays(&self) -> Vec<f64> {
        self.steps.iter().map(|s| s.delay).collect()
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
        assert!(lo + width <= self.width, "datapath: bits [{lo}, {}) of the {}-bit {}", lo + width, self.width, self.name);
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
    Sig { name: String, lo: u32, width: u32, invert: bool },
    Const { value: u128, width: u32 },
}

impl Piece {
    pub(crate) fn sig(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig { name: name.into(), lo, width, invert: false }
    }
    pub fn not(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig { name: name.into(), lo, width, invert: true }
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

/// Bits `[lo, lo+width)` of the value the pieces (LSB first) make, zero above their top.
pub(crate) fn sub_pieces(pieces: &[Piece], lo: u32, width: u32) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut base = 0;
    for p in pieces {
        let (a, b) = (base.max(lo), (base + p.width()).min(lo + width));
        if a < b {
            out.push(match p {
                Piece::Sig { name, lo: plo, invert, .. } => Piece::Sig { name: name.clone(), lo: plo + a - base, width: b - a, invert: *invert },
                Piece::Const { value, .. } => Piece::Const { value: (value >> (a - base)) & mask(b - a), width: b - a },
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

/// Whether bit `bit` of `pieces` (LSB first) is a constant 0.
fn zero_bit(pieces: &[Piece], bit: u32) -> bool {
    let mut base = 0;
    for p in pieces {
        if bit < base + p.width() {
            return matches!(p, Piece::Const { value, .. } if (value >> (bit - base)) & 1 == 0);
        }
        base += p.width();
    }
    false
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

/// Signals that wait through the same registered cuts (two or more): one vector, declared at
/// the first cut and shifted a word each clock, a word holding every member (a cut's waiting
/// signals, and the tag beside the valid pipeline). Only the words something past the line
/// reads get a name, `x_cK`, as wires declared together.
pub(crate) struct DelayLine {
    /// the vector is `<name>_line`
    pub(crate) name: String,
    /// the registered cuts it spans, in order
    pub(crate) cuts: Vec<usize>,
    /// the signals of a word, the first in its low bits
    pub(crate) members: Vec<Waiting>,
    /// the target has block RAM: a long unread tail may wait there ([`DelayLine::memory_tail`])
    pub(crate) memory: bool,
    /// that memory is LUT RAM (ECP5: a DP16KD read without its output register, 5.8 ns from
    /// the clock, would set the unit's clock; TRELLIS_DPR16X4 reads in under 5 ns)
    pub(crate) distributed: bool,
}

/// A delay line's tail waits in block RAM when it spans at least this many cuts...
pub(crate) const MEMORY_TAIL_MIN_CUTS: usize = 8;
/// ...and holds at least this many bits (a UP5K block RAM holds 4096). The memory costs two
/// address counters of log2(depth) bits and a read register of two words: for 160 bits in
/// 8 to 32 cuts, at most 2·20 + 2·5 flip-flops and 10 carry cells, less than a third of what it
/// saves. Below that the flip-flops cost less.
pub(crate) const MEMORY_TAIL_MIN_BITS: u32 = 160;

impl DelayLine {
    /// The bits of a word (every member's).
    fn word(&self) -> u32 {
        self.members.iter().map(|m| m.width).sum()
    }

    /// Where its unread tail starts and how long it is, when that tail waits in block RAM: the
    /// words after the last one read before the end (or all of them) are never named, so the
    /// last word is the word before the tail (or the sources) delayed by the tail's cuts, and
    /// `(shift words kept, tail cuts)` says how. `None`: every word is a register.
    pub fn memory_tail(&self) -> Option<(usize, usize)> {
        let d = self.cuts.len();
        let read_before_end = (0..d - 1).rev().find(|&k| self.members.iter().any(|m| m.read[k] != 0));
        let kept = read_before_end.map_or(0, |r| r + 1);
        let tail = d - kept;
        (self.memory && tail >= MEMORY_TAIL_MIN_CUTS && self.word() * tail as u32 >= MEMORY_TAIL_MIN_BITS).then_some((kept, tail))
    }

    /// Its Verilog: the vector and the statement that shifts it, then the words read, named
    /// (one statement per width). A tail in block RAM ([`DelayLine::memory_tail`]) follows the
    /// vector: the memory, its two address counters, and its read register with the last word.
    pub fn lines(&self) -> Vec<String> {
        let word = self.word();
        let line = format!("{}_line", self.name);
        let sources: Vec<&str> = self.members.iter().rev().map(|m| m.source.as_str()).collect();
        let joined = if sources.len() == 1 { sources[0].to_string() } else { format!("{{{}}}", sources.join(", ")) };
        let tail = self.memory_tail();
        // the words in the shift vector (none when the whole line waits in block RAM)
        let d = tail.map_or(self.cuts.len(), |(kept, _)| kept);
        let mut out = Vec::new();
        if d > 0 {
            let shifted = if d == 1 { joined.clone() } else { format!("{{{line}[{}:0], {}}}", word * (d as u32 - 1) - 1, sources.join(", ")) };
            out.push(format!("reg  [{}:0] {line};   always @(posedge clk) {line} <= {shifted};", word * d as u32 - 1));
        }
        if let Some((kept, cuts)) = tail {
            out.extend(self.memory_lines(&line, word, kept, cuts, &joined));
        }
        // the named words, grouped by width in order of first appearance
        let mut by_width: Vec<(u32, Vec<String>)> = Vec::new();
        let mut offset = 0;
        let last = self.cuts.len() - 1;
        for m in &self.members {
            for (k, cut) in self.cuts.iter().enumerate() {
                if m.read[k] == 0 && k < last {
                    continue;
                }
                // the last word of a tail in block RAM is the high word of `<line>_out`
                let (vector, lo) = if k >= d { (format!("{line}_out"), word + offset) } else { (line.clone(), word * k as u32 + offset) };
                let select = if m.width == 1 { format!("[{lo}]") } else { format!("[{}:{lo}]", lo + m.width - 1) };
                let tap = format!("{}_c{cut} = {vector}{select}", m.name);
                match by_width.iter_mut().find(|x| x.0 == m.width) {
                    Some(x) => x.1.push(tap),
                    None => by_width.push((m.width, vec![tap])),
                }
            }
            offset += m.width;
        }
        for (w, taps) in by_width {
            let range = if w == 1 { "     ".to_string() } else { format!("[{}:0]", w - 1) };
            out.push(format!("wire {range} {};", taps.join(", ")));
        }
        out
    }

    /// The tail in block RAM: `cuts` cycles from the word before it (`kept` words into the
    /// vector; none: the sources) to the high word of `<line>_out`. The memory and its read
    /// register (the low word) wait `cuts - 1` of them (a word written at one clock is read
    /// `cuts - 2` clocks later), the high word the last, so the memory's output meets only a
    /// flip-flop.
    fn memory_lines(&self, line: &str, word: u32, kept: usize, cuts: usize, sources: &str) -> Vec<String> {
        let wait = cuts - 1; // the memory with its read register
        let bits = (wait as u64).next_power_of_two().trailing_zeros().max(1);
        let depth = 1u64 << bits;
        let input = if kept == 0 { sources.to_string() } else { format!("{line}[{}:{}]", word * kept as u32 - 1, word * (kept as u32 - 1)) };
        // the read address trails the write address by wait - 1 places: what was written
        // wait - 1 clocks before, never what is being written
        let from_reset = (depth - (wait as u64 - 1)) % depth;
        let w = word - 1;
        let a = bits - 1;
        let names: Vec<&str> = self.members.iter().map(|m| m.name.as_str()).collect();
        vec![
            format!("// {} wait {cuts} more cuts: {wait} clocks in block RAM (with its read register), one in", names.join(", ")),
            format!("// the high word of {line}_out: the memory's output meets only a flip-flop"),
            if self.distributed { "(* no_rw_check, ram_style = \"distributed\" *)".to_string() } else { "(* no_rw_check *)".to_string() },
            format!("reg  [{w}:0] {line}_ram [0:{}];", depth - 1),
            format!("reg  [{a}:0] {line}_at, {line}_from;   // write and read addresses: the read trails by {}", wait - 1),
            format!("reg  [{}:0] {line}_out;   // the memory's read register (low word), then the last word", 2 * word - 1),
            "always @(posedge clk) begin".to_string(),
            format!("    {line}_ram[{line}_at] <= {input};"),
            format!("    {line}_out <= {{{line}_out[{w}:0], {line}_ram[{line}_from]}};"),
            "end".to_string(),
            "always @(posedge clk) begin".to_string(),
            format!("    {line}_at <= rst ? {bits}'d0 : {line}_at + 1'b1;"),
            format!("    {line}_from <= rst ? {bits}'d{from_reset} : {line}_from + 1'b1;"),
            "end".to_string(),
        ]
    }

    /// The bits of its named words before the last that nothing reads, as selects, for the lint
    /// sink (the last word's are the datapath's own `unused`).
    pub fn unread(&self) -> Vec<String> {
        let last = self.cuts.len() - 1;
        let mut out = Vec::new();
        for m in &self.members {
            for (k, cut) in self.cuts[..last].iter().enumerate() {
                if m.read[k] != 0 {
                    out.extend(bit_ranges(&format!("{}_c{cut}", m.name), m.width, mask(m.width) & !m.read[k]));
                }
            }
        }
        out
    }
}

/// The name under which a signal defined in step `def` (0: an input port) is seen in step
/// `at`: its own wire in its own step, else the last register holding it, else its wire.
pub(crate) fn visible(registered: &[u32], name: &str, def: usize, at: usize) -> String {
    if def == at {
        return format!("{name}_s{at}");
    }
    match registered.iter().copied().filter(|&r| r as usize >= def && (r as usize) < at).max() {
        Some(r) => format!("{name}_c{r}"),
        None if def == 0 => name.to_string(),
        None => format!("{name}_s{def}"),
    }
}

/// The runs of set bits of `unread` in a `width`-bit signal seen as `v`, MSB first, as selects.
pub(crate) fn bit_ranges(v: &str, width: u32, unread: u128) -> Vec<String> {
    let mut parts = Vec::new();
    let mut b = width;
    while b > 0 {
        b -= 1;
        if unread >> b & 1 == 1 {
            let hi = b;
            while b > 0 && unread >> (b - 1) & 1 == 1 {
                b -= 1;
            }
            parts.push(if width == 1 {
                v.to_string()
            } else if hi == b {
                format!("{v}[{b}]")
            } else {
                format!("{v}[{hi}:{b}]")
            });
        }
    }
    parts
}

/// Chunk boundaries `(lo, width)` of a `width`-bit carry chain, each ≤ `chunk_bits`.
fn chunks(width: u32, chunk_bits: u32) -> Vec<(u32, u32)> {
    let n = width.div_ceil(chunk_bits).max(1);
    let (base, extra) = (width / n, width % n);
    let mut lo = 0;
    (0..n)
        .map(|i| {
            let w = base + u32::from(i < extra);
            let c = (lo, w);
            lo += w;
            c
        })
        .collect()
}

// Delay estimates in ns, after iCE40 UP5K post-route figures (logic and routing, without the
// clock-to-out and setup every register adds once): one LUT level with its route ~2.7, a
// carry chain ~0.7 + 0.3/bit plus the LUT that brings its carry-out back to the fabric, a
// DSP multiply(-add) of <= 16-bit operands ~5.5, an asynchronous 2^N-word ROM in LUTs about
// one LUT level per 2 address bits. Only the ratios matter: they place the registers.

/// One LUT level and its route.
pub(crate) const LUT_DELAY: f64 = 2.7;

/// Chunk bits of the carry-select add closing a carry-save sum ([`Builder::sum_start`]).
pub(crate) const SUM_CHUNK_BITS: u32 = 4;

/// A step that only registers its signals (a route, no logic).
pub(crate) const REGISTER_ONLY_DELAY: f64 = 1.0;

/// A carry-select sum of more chunks than this spreads over so many tiles that a carry
/// crosses a long route: [`Builder::resolve`] ripples its carries one a step.
pub(crate) const WIDE_SUM_CHUNKS: usize = 4;

/// A `w`-bit carry chain, carry-out included.
pub(crate) fn add_delay(w: u32) -> f64 {
    0.7 + 0.3 * w as f64 + LUT_DELAY
}

/// An a×b multiply: one DSP when both fit its operands, else an array of partial products.
/// (The family's own rule, small products in LUTs: [`Builder::mul_delay`].)
fn dsp_or_array_delay(a: u32, b: u32) -> f64 {
    if a.max(b) <= DSP_BITS {
        5.5
    } else {
        1.5 * ((a.min(b).max(1) as f64).log2().ceil() + 1.0) + 0.3 * (a + b) as f64
    }
}

/// A product yosys leaves in LUTs (too small for the family's block): partial products summed
/// by a tree of LUT levels, then a carry chain over the product.
fn soft_mul_delay(a: u32, b: u32) -> f64 {
    LUT_DELAY * ((a.min(b).max(1) as f64).log2().ceil() + 1.0) + add_delay(a + b)
}

impl Builder {
    /// The delay estimate of an a×b multiply as this target's synthesis maps it: a product too
    /// small for the block (on the iCE40 fewer than 11 bits, on
    /// either family an operand of one bit) is LUTs, slower than the block (a narrow lean's
    /// 5×4 colour product set its clock at 52 MHz while the estimate had it as one DSP); else
    /// one DSP, or an array past the block's operands.
    pub(crate) fn mul_delay(&self, a: u32, b: u32) -> f64 {
        self.product_estimate(a, b, a + b).0
    }

    /// An a×b multiply kept to `y` bits: its delay estimate, and whether yosys leaves it in
    /// LUTs on this family (too small for its block: `Family::soft_product`).
    fn product_estimate(&self, a: u32, b: u32, y: u32) -> (f64, bool) {
        match self.family().soft_product(a, b, y) {
            true => (soft_mul_delay(a, b), true),
            false => (dsp_or_array_delay(a, b), false),
        }
    }

    /// Raises the current step's delay to an a×b multiply's, kept to `y` bits, plus `after`
    /// (the logic behind it in the same step), and marks the step when the product is LUTs,
    /// not a block ([`Step::soft_product`]).
    pub(crate) fn product_delay(&mut self, a: u32, b: u32, y: u32, after: f64) {
        let (d, soft) = self.product_estimate(a, b, y);
        self.delay(d + after);
        let s = self.steps.last_mut().expect("a step");
        s.soft_product |= soft;
    }

    /// The family the datapath is shaped for.
    pub(crate) fn family(&self) -> &'static dyn crate::family::Family {
        crate::family::of(self.target)
    }

    /// Whether the family's products and table reads are blocks instantiated with their own
    /// registers (no post-adder; one carry chain a step): `Family::instantiated_blocks`.
    pub(crate) fn instantiated_blocks(&self) -> bool {
        self.family().instantiated_blocks()
    }

    /// `inputs`: the port signals, available from cut 0; `registered`: the cuts that hold a
    /// pipeline register (a reference resolves to the last of them before it, or to the
    /// defining wire when there is none: a combinational cut emits nothing).
    pub fn new(inputs: &[(&str, u32)], registered: &[u32], target: Target) -> Builder {
        Builder {
            steps: Vec::new(),
            signals: inputs.iter().map(|&(n, w)| Signal { name: n.into(), width: w, step: 0, uses: Vec::new(), dsp_registered: false, held: None }).collect(),
            tables: Vec::new(),
            reads: Vec::new(),
            registered: registered.to_vec(),
            target,
            view: None,
            chunk_limit: u32::MAX,
            read: BTreeMap::new(),
            products: Vec::new(),
        }
    }

    /// Makes the input `name` one held in the register `register` for every pixel (a static
    /// colour): every step reads that register, and no cut carries it.
    pub fn hold(&mut self, name: &str, register: &str) {
        let s = self.signal(name);
        assert_eq!(s.step, 0, "datapath: only an input can be held");
        s.held = Some(register.to_string());
    }

    /// The step references are made from: the current one, or the one before a registered
    /// DSP while its operands are written.
    fn cur(&self) -> usize {
        self.view.unwrap_or(self.steps.len())
    }

    pub fn target(&self) -> Target {
        self.target
    }

    /// The widest multiplier operand one DSP block takes on the target (generic: no limit).
    pub(crate) fn dsp_bits(&self) -> u32 {
        self.family().multiplier_bits()
    }

    /// The longest carry chain one step holds on the target (generic: no limit).
    pub(crate) fn chunk_bits(&self) -> u32 {
        self.family().carry_chunk_bits()
    }

    fn is_registered(&self, cut: usize) -> bool {
        self.registered.contains(&(cut as u32))
    }

    /// Whether the current step can be one ECP5 block (DSP or block RAM) with its registers:
    /// the cuts on both sides registered, the one before being a cut (not the input ports).
    fn block_registers_here(&self) -> bool {
        let k = self.steps.len();
        self.family().instantiated_blocks() && k >= 2 && self.is_registered(k - 1) && self.is_registered(k)
    }

    /// Runs `f` with references taken as the step before sees them, where a block's input
    /// registers take its inputs; each of `inputs` must be visible there (defined before it,
    /// and not another block's output registered at its end).
    fn seen_from_step_before<T>(&mut self, inputs: &[&str], what: &str, f: impl FnOnce(&mut Self) -> T) -> T {
        let k = self.steps.len();
        for n in inputs {
            assert!(self.visible_before(n), "datapath: {n} is not visible in step {} for {what}", k - 1);
        }
        self.view = Some(k - 1);
        let out = f(self);
        self.view = None;
        out
    }

    /// Whether `name` is visible in the step before the current one, where a block's input
    /// registers take their operands: defined before the current step, and not another block's
    /// output registered at the cut between the two.
    fn visible_before(&mut self, name: &str) -> bool {
        let k = self.steps.len();
        let s = self.signal(name);
        s.step < k && !(s.dsp_registered && s.step + 1 == k)
    }

    /// Records a new signal defined in `step` (`dsp_registered`: held by a block's output
    /// register at the cut after it).
    fn define(&mut self, name: &str, width: u32, step: usize, dsp_registered: bool) {
        assert!(self.signals.iter().all(|s| s.name != name), "datapath: {name} defined twice");
        self.signals.push(Signal { name: name.into(), width, step, uses: Vec::new(), dsp_registered, held: None });
    }

    /// `name = a·b mod 2^width` (operands zero-extended; `width` at most their two widths
    /// summed keeps it exact). On ECP5, when both operands fit 18 bits and the cuts on both
    /// sides of this step are registered, one MULT18X18D with its own registers: its input
    /// registers are the cut before (they take the operands as the step before sees them, so
    /// no fabric register holds them), its output register is the cut after (the product is
    /// `name_cK` from there). Anywhere else, a `*` the synthesis tool maps.
    pub fn product(&mut self, name: &str, a: &[Piece], b: &[Piece], width: u32, comment: &str) {
        let (wa, wb) = (a.iter().map(Piece::width).sum::<u32>(), b.iter().map(Piece::width).sum::<u32>());
        let inputs: Vec<String> = a.iter().chain(b).filter_map(|p| if let Piece::Sig { name, .. } = p { Some(name.clone()) } else { None }).collect();
        // an operand that is another block's output registered at the cut before cannot also
        // be this block's input register: then a `*` the tool maps
        let visible = inputs.iter().all(|n| self.visible_before(n));
        let on_dsp = visible && self.block_registers_here() && wa.max(wb) <= ECP5_DSP_BITS && width <= 2 * ECP5_DSP_BITS;
        self.product_delay(wa, wb, width, 0.0);
        if !on_dsp {
            let (ea, eb) = (self.pieces(&sub_pieces(a, 0, width)), self.pieces(&sub_pieces(b, 0, width)));
            self.wire(name, width, format!("{ea} * {eb}"), comment);
            return;
        }
        let inputs: Vec<&str> = inputs.iter().map(String::as_str).collect();
        let (ea, eb) = self.seen_from_step_before(&inputs, &format!("the DSP of {name}"), |s| {
            (s.pieces(&sub_pieces(a, 0, ECP5_DSP_BITS)), s.pieces(&sub_pieces(b, 0, ECP5_DSP_BITS)))
        });
        self.define(name, width, self.steps.len(), true);
        self.steps.last_mut().expect("a step").dsps.push(Dsp { name: name.into(), width, a: ea, b: eb, comment: comment.into() });
    }

    /// `name = a·b + addend mod 2^width` (operands zero-extended), starting in this step.
    /// Where the DSP block's post-adder takes it, one multiply-add (the add inside the block):
    /// generic, and the iCE40's SB_MAC16 when the sum is no wider than the product's operands
    /// together (yosys 0.23 leaves a wider add in the fabric, on the product's unregistered
    /// output). Elsewhere (and always on the ECP5, whose MULT18X18D has no adder) the product
    /// `name_prod` alone here ([`Builder::product`]: on a block with its own registers where
    /// the cuts allow), then the add over the bits above the addend's low zeros in steps of its
    /// own, titled `title`: one carry chain on the ECP5, a carry-select add on the iCE40.
    /// Returns the name of the sum.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn multiply_add(&mut self, name: &str, a: &[Piece], b: &[Piece], addend: &[Piece], width: u32, title: &str, comment: &str) -> Sig {
        let (wa, wb) = (a.iter().map(Piece::width).sum::<u32>(), b.iter().map(Piece::width).sum::<u32>());
        let post_adder = self.family().post_adder(width, wa, wb);
        if post_adder {
            self.product_delay(wa, wb, width, 0.0);
            let (ea, eb) = (self.pieces(&sub_pieces(a, 0, width)), self.pieces(&sub_pieces(b, 0, width)));
            let ec = self.addend(&sub_pieces(addend, 0, width), |e| e);
            return self.wire(name, width, format!("{ea} * {eb}{ec}"), &format!("{comment} (one DSP, the add inside it)"));
        }
        let product = format!("{name}_prod");
        let pw = width.min(wa + wb);
        self.product(&product, a, b, pw, &format!("the product alone (one DSP), exact: {pw} bits"));
        // the addend's low zero bits: the sum there is the product's
        let mut z = 0;
        for p in addend {
            match p {
                Piece::Const { value: 0, width } => z += width,
                _ => break,
            }
        }
        let z = z.min(pw);
        let hi = if z == 0 { name.to_string() } else { format!("{name}_hi") };
        let mut pb = sub_pieces(addend, z, width - z);
        if pb.iter().any(|p| matches!(p, Piece::Sig { invert: true, .. })) {
            // a complemented addend is formed here, beside the product: a carry chain's
            // operand takes no inverter, which would be a LUT level before it
            let e = self.pieces(&pb);
            let (aname, aw) = (format!("{name}_addend"), width - z);
            self.wire(&aname, aw, e, &format!("bits [{}:{z}] of the addend of {name}", width - 1));
            pb = vec![Piece::sig(&aname, 0, aw)];
        }
        let pa = [Piece::sig(&product, z, pw - z)];
        self.step(&format!("{title}: the add after the product"));
        let what = if z == 0 { comment.to_string() } else { format!("bits [{}:{z}] of {name}", width - 1) };
        if self.family().instantiated_blocks() {
            self.add(&hi, &pa, &pb, false, width - z, &what);
        } else {
            let p = self.add_start(&hi, &pa, &pb, false, width - z, &what);
            self.resolve(p, title);
        }
        if z > 0 {
            let (h, l) = (self.r(&hi), self.bits(&product, z - 1, 0));
            self.wire(name, width, format!("{{{h}, {l}}}"), comment);
        }
        self.sig(name)
    }

    /// On the ECP5 only, a step titled `title` that only registers, where one flip-flop cannot
    /// serve two blocks or a long route needs a flip-flop at its start: before a DP16KD's
    /// address register when a carry chain or mux computes the address (blinn's log table
    /// address set the clock at 186–208 MHz over 5 seeds without it), and after a block RAM's
    /// output register when a MULT18X18D's input registers take the word next. The step is
    /// there whatever the cuts, so the datapath's shape does not depend on them.
    pub(crate) fn ecp5_register_step(&mut self, title: &str) {
        if self.family().instantiated_blocks() {
            self.step(title);
            self.delay(REGISTER_ONLY_DELAY);
        }
    }

    /// Starts the next step.
    pub(crate) fn step(&mut self, title: &str) {
        let index = self.steps.len() + 1;
        self.steps.push(Step { index, title: title.into(), wires: Vec::new(), dsps: Vec::new(), delay: 0.0, soft_product: false });
    }

    /// Raises the current step's delay estimate to at least `d`.
    pub(crate) fn delay(&mut self, d: f64) {
        let s = self.steps.last_mut().expect("a step");
        s.delay = s.delay.max(d);
    }

    fn signal(&mut self, name: &str) -> &mut Signal {
        self.signals.iter_mut().rev().find(|s| s.name == name).unwrap_or_else(|| panic!("datapath: {name} used before it is defined"))
    }

    /// Whether `name` is held in a block's output register defined in the current step (so
    /// it can be read only from the next step on).
    pub(crate) fn is_block_output_here(&mut self, name: &(impl AsRef<str> + ?Sized)) -> bool {
        let name = name.as_ref();
        let cur = self.cur();
        let s = self.signal(name);
        s.dsp_registered && s.step == cur
    }

    /// The name of `name` as seen from the current step.
    fn version(&mut self, name: &str) -> String {
        let (cur, def, dsp) = (self.cur(), self.signal(name).step, self.signal(name).dsp_registered);
        assert!(!(dsp && def == cur), "datapath: {name} is a DSP's registered output, read only after its step");
        if let Some(held) = &self.signal(name).held {
            return held.clone();
        }
        visible(&self.registered, name, def, cur)
    }

    /// Bits `[hi:lo]` of a signal (the bare name when that is all of it).
    pub fn bits(&mut self, name: &(impl AsRef<str> + ?Sized), hi: u32, lo: u32) -> String {
        let name = name.as_ref();
        let cur = self.cur();
        let s = self.signal(name);
        assert!(hi < s.width && lo <= hi, "datapath: {name}[{hi}:{lo}] of a {}-bit signal", s.width);
        s.uses.push((cur, mask(hi + 1) & !mask(lo)));
        let whole = lo == 0 && hi + 1 == s.width;
        let v = self.version(name);
        *self.read.entry(v.clone()).or_default() |= mask(hi + 1) & !mask(lo);
        match (whole, hi == lo) {
            (true, _) => v,
            (false, true) => format!("{v}[{lo}]"),
            (false, false) => format!("{v}[{hi}:{lo}]"),
        }
    }

    /// All of a signal.
    pub fn r(&mut self, name: &(impl AsRef<str> + ?Sized)) -> String {
        let name = name.as_ref();
        let w = self.signal(name).width;
        self.bits(name, w - 1, 0)
    }

    /// Bits `[lo, lo+width)` of a signal as an operand of exactly `out` bits: cut to its low
    /// `out` bits (enough for a result taken modulo 2^out) or zero-extended.
    pub fn operand(&mut self, name: &(impl AsRef<str> + ?Sized), lo: u32, width: u32, out: u32) -> String {
        let name = name.as_ref();
        self.pieces(&sub_pieces(&[Piece::sig(name, lo, width)], 0, out))
    }

    /// All of `name` zero-extended to `to` bits.
    pub(crate) fn zext(&mut self, name: &(impl AsRef<str> + ?Sized), to: u32) -> String {
        let name = name.as_ref();
        let w = self.signal(name).width;
        assert!(to >= w, "zext {name} from {w} to {to}");
        self.operand(name, 0, w, to)
    }

    /// `cond ? a : b` over `width` bits written as an AND-OR, for a mux where `a` or `b` has
    /// constant bits: yosys makes a `?:` of a constant before a register the register's
    /// synchronous set/reset (iCE40 SB_DFFSR/SS), and a set/reset driven by logic costs
    /// placement (the 8 flip-flops of a tile share one) and ~3.5 ns of route into the pin,
    /// or a global buffer ~6 ns away when it drives more than 15 flip-flops.
    pub fn select(cond: &str, a: &str, b: &str, width: u32) -> String {
        // one side a line
        format!("({{{width}{{{cond}}}}} & {a})\n    | (~{{{width}{{{cond}}}}} & {b})")
    }

    /// `cond ? value : other` for a constant `value` of `width` bits ([`Builder::select`]).
    pub(crate) fn select_const(cond: &str, value: u128, width: u32, other: &str) -> String {
        Builder::select(cond, &lit(width, value), other, width)
    }

    /// `cond ? a : 0` over `width` bits as an AND ([`Builder::select`]).
    pub(crate) fn gate(cond: &str, a: &str, width: u32) -> String {
        format!("({{{width}{{{cond}}}}} & {a})")
    }

    /// The Verilog for a list of pieces (LSB first), MSB first in a concatenation.
    pub(crate) fn pieces(&mut self, pieces: &[Piece]) -> String {
        let parts: Vec<String> = pieces
            .iter()
            .rev()
            .map(|p| match p {
                Piece::Sig { name, lo, width, invert } => {
                    let b = self.bits(name, lo + width - 1, *lo);
                    if *invert {
                        format!("~{b}")
                    } else {
                        b
                    }
                }
                Piece::Const { value, width } => lit(*width, *value),
            })
            .collect();
        match parts.len() {
            1 => parts.into_iter().next().unwrap(),
            _ => format!("{{{}}}", parts.join(", ")),
        }
    }

    /// The terms of `a·r·2^shift` mod 2^out: `a` shifted to each bit `k` of `r` (by `k + shift`)
    /// where that bit is set, for a sum with more addends (constants, a table's value).
    pub(crate) fn shift_add_terms(&mut self, a: &Piece, r: &Piece, shift: u32, out: u32) -> Vec<String> {
        let (Piece::Sig { name: rn, lo: rlo, width: rw, .. }, Piece::Sig { name: an, lo: alo, width: aw, .. }) = (r, a) else {
            panic!("shift_add takes signal pieces")
        };
        let mut terms = Vec::new();
        for k in (0..*rw).filter(|k| k + shift < out) {
            let bit = self.bits(rn, rlo + k, rlo + k);
            let s = k + shift;
            let av = self.operand(an, *alo, *aw, out - s);
            let shifted = if s == 0 { av } else { format!("{{{av}, {}}}", lit(s, 0)) };
            terms.push(Builder::gate(&bit, &shifted, out));
        }
        terms
    }

    /// ` + b` for an addend (`ext` applied), or nothing when it is constant zero.
    fn addend(&mut self, pieces: &[Piece], ext: impl Fn(String) -> String) -> String {
        if pieces.iter().all(|p| matches!(p, Piece::Const { value: 0, .. })) {
            String::new()
        } else {
            let e = self.pieces(pieces);
            format!(" + {}", ext(e))
        }
    }

    /// Defines a wire of the current step.
    pub fn wire(&mut self, name: &str, width: u32, expr: String, comment: &str) -> Sig {
        let cur = self.cur();
        if expr.contains(" * ") {
            self.products.push(name.to_string());
        }
        self.define(name, width, cur, false);
        self.steps.last_mut().expect("a step").wires.push(Wire { name: name.into(), width, expr, comment: comment.into() });
        Sig { name: name.into(), width }
    }

    /// The handle of a signal defined before (a unit input, or a wire a helper defined).
    pub(crate) fn sig(&mut self, name: &str) -> Sig {
        let width = self.signal(name).width;
        Sig { name: name.into(), width }
    }

    /// The colour multipliers (14–16) with the colours' rounding half as their addend, one
    /// multiply-add each (on a DSP block, the add is its post-adder):
    /// `color_sum_X = v·ks_X + 2^(wc−1)`, `B + wc` bits, for the `wc + 1`-bit UQ1.wc signal `v`
    /// (`what` names the value in the comments). [`Builder::colour_results`] takes the outputs.
    pub(crate) fn colour_sums(&mut self, v: &str, wc: u32, what: &str) {
        let bb = self.colour_bits();
        let cp = wc + bb;
        for ch in CHANNELS {
            let (sv, kv) = (self.zext(v, cp), self.zext(&format!("ks_{ch}"), cp));
            let comment = format!("UQ{bb}.{wc}: {what}*ks_{ch} + 1/2 colour ulp");
            self.wire(&format!("color_sum_{ch}"), cp, format!("{sv} * {kv} + {}", lit(cp, 1u128 << (wc - 1))), &comment);
        }
    }

    /// The colour multipliers (14–16) in this step, for the `wc + 1`-bit UQ1.wc field of `src`
    /// from bit `lo` (`what` names the value). Where the DSP block has a post-adder (iCE40,
    /// generic) one multiply-add each with the colours' rounding half as its addend
    /// (`color_power`, then [`Builder::colour_sums`]); on the ECP5, whose MULT18X18D has none,
    /// the products alone (`color_prod_X`, on blocks with their own registers where the cuts
    /// allow), and [`Builder::colour_rounding`] adds the half in a later step.
    pub(crate) fn colour_products(&mut self, src: &str, lo: u32, wc: u32, what: &str) {
        if !self.family().instantiated_blocks() {
            let cs = self.bits(src, lo + wc, lo);
            self.wire("color_power", wc + 1, cs, &format!("UQ1.{wc}: {what} floored to what the colours' budget needs"));
            self.colour_sums("color_power", wc, what);
            return;
        }
        let bb = self.colour_bits();
        for ch in CHANNELS {
            let (v, k) = (Piece::sig(src, lo, wc + 1), Piece::sig(&format!("ks_{ch}"), 0, bb));
            self.product(
                &format!("color_prod_{ch}"),
                &[v],
                &[k],
                wc + bb,
                &format!("UQ{bb}.{wc}: {what}*ks_{ch}, {what} floored to what the colours' budget needs, exact"),
            );
        }
    }

    /// The ECP5's colour rounding after [`Builder::colour_products`], in this step:
    /// `color_sum_X = color_prod_X + 2^(wc−1)` on carry chains (elsewhere nothing: the half was
    /// the multiply-add's addend).
    pub(crate) fn colour_rounding(&mut self, wc: u32, what: &str) {
        if !self.family().instantiated_blocks() {
            return;
        }
        let cp = wc + self.colour_bits();
        for ch in CHANNELS {
            let half = Piece::Const { value: 1u128 << (wc - 1), width: wc };
            let comment = format!("UQ{}.{wc}: {what}*ks_{ch} + 1/2 colour ulp", cp - wc);
            self.add(&format!("color_sum_{ch}"), &[Piece::sig(&format!("color_prod_{ch}"), 0, cp)], &[half], false, cp, &comment);
        }
    }

    /// The colour outputs `spec_X` from `color_sum_X` (`B + wc` bits, the rounding half in it):
    /// its top B bits, the colour rounded half up.
    pub(crate) fn colour_results(&mut self, wc: u32, what: &str) {
        let bb = self.colour_bits();
        for ch in CHANNELS {
            let e = self.bits(&format!("color_sum_{ch}"), wc + bb - 1, wc);
            self.wire(&format!("spec_{ch}"), bb, e, &format!("UNORM{bb}: {what}*ks_{ch} rounded half up"));
        }
    }

    /// B: the width of the colour ports.
    fn colour_bits(&self) -> u32 {
        self.signals.iter().find(|s| s.name == "ks_r").expect("the colour ports are inputs").width
    }

    /// `name = v²` for the `r`-bit field `v = sig[lo..lo+r)`, by a table of 2^r entries in
    /// LUTs (no multiply, no carry chain): one LUT level up to [`LUT_INPUTS`] bits, two above.
    /// Written as an OR of the entries, each gated by its match: a `?:` chain of constants
    /// before a register would become the register's synchronous set/reset
    /// ([`Builder::select`]).
    pub(crate) fn square_table(&mut self, name: &str, sig: &str, lo: u32, r: u32, comment: &str) {
        let v = self.bits(sig, lo + r - 1, lo);
        // one entry a line; v = 0 squares to 0 and adds nothing
        let entries: Vec<String> = (1..1u128 << r).map(|x| Builder::gate(&format!("{v} == {}", lit(r, x)), &lit(2 * r, x * x), 2 * r)).collect();
        self.wire(name, 2 * r, entries.join("\n    | "), comment);
        // a function of more inputs than a LUT has: two levels
        self.delay(if r > LUT_INPUTS { 2.0 * LUT_DELAY } else { LUT_DELAY });
    }

    /// Adds a constant table to the unit; returns its index for [`Builder::rom_read`].
    pub fn table(&mut self, t: Table) -> usize {
        self.tables.push(t);
        self.tables.len() - 1
    }

    /// Defines `signal` in the current step as the entry of table `t` addressed by all of
    /// the signal `addr` (the template renders the memory and the read).
    pub(crate) fn rom_read(&mut self, signal: &str, t: usize, addr: &str) {
        let a = self.r(addr);
        let cur = self.cur();
        self.define(signal, self.tables[t].width, cur, false);
        let position = self.steps.last().expect("a step").wires.len();
        self.reads.push(RomRead { step: cur, signal: signal.into(), table: t, addr: a, block: false, position });
    }

    /// [`Builder::rom_read`], on ECP5 block RAM with its registers when the table has at most
    /// 1024 words of at most [`MAX_BLOCK_SLICES`]·18 bits (one DP16KD, 1024 x 18, per 18 bits
    /// of the word) and the cuts on both sides of this step are registered: the address
    /// registers take the address as the step before sees it, the output registers are the cut
    /// after this step (the read's clock-to-out, 5.6 ns without them on LFE5U-25F grade 6,
    /// then never limits Fmax). Anywhere else, an asynchronous read in this step.
    pub(crate) fn rom_read_registered(&mut self, signal: &str, t: usize, addr: &str) {
        // up to 1024 words, or two banks of them addressed by a whole 11-bit signal
        let words = self.tables[t].words.len();
        let banks = words > DP16KD_WORDS && words <= 2 * DP16KD_WORDS && self.signal(addr).width == 11;
        let fits = (words <= DP16KD_WORDS || banks) && self.tables[t].width <= MAX_BLOCK_SLICES * DP16KD_BITS;
        if !(fits && self.block_registers_here()) {
            return self.rom_read(signal, t, addr);
        }
        let a = self.seen_from_step_before(&[addr], &format!("the block read of {signal}"), |s| s.r(addr));
        let k = self.steps.len();
        self.define(signal, self.tables[t].width, k, true);
        let position = self.steps.last().expect("a step").wires.len();
        self.reads.push(RomRead { step: k, signal: signal.into(), table: t, addr: a, block: true, position });
    }

    /// `name = (a + b + cin) mod 2^width` as one carry chain in this step, whatever its width
    /// (the ECP5's CCU2C chains are fast; the iCE40 shape uses [`Builder::add_start`]).
    pub(crate) fn add(&mut self, name: &str, a: &[Piece], b: &[Piece], cin: bool, width: u32, comment: &str) -> Sig {
        self.delay(add_delay(width.min(self.chunk_bits())));
        let ea = self.pieces(&sub_pieces(a, 0, width));
        let eb = self.addend(&sub_pieces(b, 0, width), |e| e);
        let plus = if cin { format!(" + {}", lit(width, 1)) } else { String::new() };
        self.wire(name, width, format!("{ea}{eb}{plus}"), comment)
    }

    /// `name = (a + b + cin) mod 2^width`. One chunk: computed here. More: each chunk is added
    /// here with carry-in 0 and 1 (carry-select), and [`Builder::add_finish`] resolves the
    /// carries and picks in the next step.
    pub(crate) fn add_start(&mut self, name: &str, a: &[Piece], b: &[Piece], cin: bool, width: u32, comment: &str) -> PendingAdd {
        let parts = chunks(width, self.chunk_bits().min(self.chunk_limit));
        let n = parts.len();
        let no_carry_out = parts.iter().map(|&(lo, w)| sub_pieces(b, lo, w).iter().all(|p| matches!(p, Piece::Const { value: 0, .. }))).collect();
        let max_chunk = parts.iter().map(|c| c.1).max().unwrap_or(1);
        self.delay(add_delay(max_chunk));
        let mut top_inverted = false;
        if n == 1 {
            let ea = self.pieces(&sub_pieces(a, 0, width));
            let eb = self.addend(&sub_pieces(b, 0, width), |e| e);
            let plus = if cin { format!(" + {}", lit(width, 1)) } else { String::new() };
            self.wire(name, width, format!("{ea}{eb}{plus}"), comment);
        } else {
            for (i, &(lo, w)) in parts.iter().enumerate() {
                let top = i + 1 == n;
                let ww = if top { w } else { w + 1 };
                let pa = sub_pieces(a, lo, w);
                let pb = sub_pieces(b, lo, w);
                // the top chunk's top bit a carry-out (0 above both operands): a 1 above the
                // first makes it a sum bit, the carry's complement, as below
                let pa = if top && zero_bit(&pa, w - 1) && zero_bit(&pb, w - 1) {
                    top_inverted = true;
                    let mut v = sub_pieces(&pa, 0, w - 1);
                    v.push(Piece::Const { value: 1, width: 1 });
                    v
                } else {
                    pa
                };
                // below the top chunk, the carry-out is kept complemented, as the sum bit of a
                // 1 above the first operand and a 0 above the second (1 + 0 + carry = ~carry
                // mod 2): the chain computes it in a LUT of its own that packs with its
                // flip-flop. A plain carry-out (0 above both, or 1 above both, which synthesis
                // folds to the same) is the chain's CO, which leaves an iCE40 chain through an
                // extra LUT placed apart from the flip-flop: 2-3 ns of routing more.
                // [`Builder::carry_out`] reads it back.
                let ext_a = |e: String| if top { e } else { format!("{{1'b1, {e}}}") };
                let ext_b = |e: String| if top { e } else { format!("{{1'b0, {e}}}") };
                // carry-in 1 as a 1 + 1 in an extra low bit: one adder that no synthesis tool
                // can share with the carry-in-0 sum (a shared "+ 1" would chain two adders)
                let ext1_a = |e: String| if top { format!("{{{e}, 1'b1}}") } else { format!("{{1'b1, {e}, 1'b1}}") };
                let ext1_b = |e: String| if top { format!("{{{e}, 1'b1}}") } else { format!("{{1'b0, {e}, 1'b1}}") };
                let ea = self.pieces(&pa);
                let what = if top { format!("bits [{}:{lo}]", lo + w - 1) } else { format!("bits [{}:{lo}] and their carry (complemented)", lo + w - 1) };
                let sum0 = {
                    let eb = self.addend(&pb, ext_b);
                    format!("{}{eb}", ext_a(ea.clone()))
                };
                let sum1 = {
                    let eb = self.addend(&pb, ext1_b);
                    let eb = if eb.is_empty() { format!(" + {}", lit(ww + 1, 1)) } else { eb };
                    format!("{}{eb}", ext1_a(ea))
                };
                if i == 0 && cin {
                    self.wire(&format!("{name}_part0"), ww + 1, sum1, &format!("{what} above bit 0, carry-in 1"));
                } else if i == 0 {
                    self.wire(&format!("{name}_part0"), ww, sum0, &format!("{what}, carry-in 0"));
                } else {
                    self.wire(&format!("{name}_part{i}"), ww, sum0, &format!("{what}, carry-in 0"));
                    self.wire(&format!("{name}_part{i}_plus1"), ww + 1, sum1, &format!("{what} above bit 0, carry-in 1 (carry-select)"));
                }
            }
        }
        PendingAdd {
            name: name.into(),
            width,
            chunks: if n == 1 { Vec::new() } else { parts },
            part0_offset: u32::from(cin),
            no_carry_out,
            top_inverted,
            comment: comment.into(),
        }
    }

    /// `sig[hi:lo] >= c` as AND/OR of its bits, most significant first (a bit of `c` set: that
    /// bit and the rest; clear: that bit or the rest; none left set: true): a few LUTs that
    /// synthesis maps as logic, where `>=` becomes a carry chain whose carry-out leaves it
    /// through an extra LUT placed apart (iCE40).
    pub(crate) fn at_least(&mut self, sig: &str, hi: u32, lo: u32, c: u128) -> String {
        let width = hi - lo + 1;
        if c == 0 {
            return "1'b1".into();
        }
        let mut expr = String::new();
        // x[i:0] >= c[i:0], from the lowest set bit of c up (below it, c's bits are 0: true)
        let low = c.trailing_zeros();
        for i in low..width {
            let bit = self.bits(sig, lo + i, lo + i);
            expr = if i == low {
                bit
            } else if (c >> i) & 1 == 1 {
                format!("{bit} & ({expr})")
            } else {
                format!("{bit} | ({expr})")
            };
        }
        expr
    }

    /// The carry out of a chunk of [`Builder::add_start`]: its bit `bit`, kept complemented.
    fn carry_out(&mut self, part: &str, bit: u32) -> String {
        format!("~{}", self.bits(part, bit, bit))
    }

    /// Second step of a carry-select add: the carry into each chunk from the third on
    /// (the first chunk's own carry-out is the carry into the second), rippled through the
    /// chunks' carry-outs. Nothing to do for one or two chunks.
    pub(crate) fn add_carries(&mut self, p: &PendingAdd) {
        let n = p.chunks.len();
        if n > 2 {
            self.add_carries_range(p, 1, n - 1);
        }
    }

    /// The carries into chunks `from + 1 ..= to` (one LUT level each, rippled).
    fn add_carries_range(&mut self, p: &PendingAdd, from: usize, to: usize) {
        self.delay(LUT_DELAY * (to - from) as f64);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let mut carry = match from {
            1 => self.carry_out(&format!("{}_part0", p.name), w0 + o),
            _ => self.r(&format!("{}_carry{from}", p.name)),
        };
        for i in from..to {
            let w = p.chunks[i].1;
            let ca = self.carry_out(&format!("{}_part{i}_plus1", p.name), w + 1);
            let cname = format!("{}_carry{}", p.name, i + 1);
            let expr = if p.no_carry_out[i] {
                // an AND, not a ?: of 0 ([`Builder::select`])
                format!("{carry} & {ca}")
            } else {
                let cb = self.carry_out(&format!("{}_part{i}", p.name), w);
                format!("{carry} ? {ca} : {cb}")
            };
            self.wire(&cname, 1, expr, &format!("carry into bit {}", p.chunks[i + 1].0));
            carry = self.r(&cname);
        }
    }

    /// The partial products of `a·r·2^shift` mod 2^width as wires `{name}_pp{k}` (one LUT
    /// level: `a` shifted to bit `k` of `r` where it is set, else 0; each complemented when
    /// `invert`, for a difference), as terms for [`Builder::sum_start`].
    pub(crate) fn partial_products(&mut self, name: &str, a: &Piece, r: &Piece, shift: u32, width: u32, invert: bool) -> Vec<Vec<Piece>> {
        let terms = self.shift_add_terms(a, r, shift, width);
        let mut out = Vec::new();
        for (k, t) in terms.into_iter().enumerate() {
            let pp = format!("{name}_pp{k}");
            let (e, what) = if invert { (format!("~{t}"), "complemented") } else { (t, "") };
            self.wire(&pp, width, e, &format!("partial product {k}{}", if invert { format!(", {what}") } else { String::new() }));
            out.push(vec![Piece::sig(&pp, 0, width)]);
        }
        self.delay(LUT_DELAY);
        out
    }

    /// `name = Σ terms mod 2^width` (each term pieces, LSB first) without a carry chain until
    /// the end: 3:2 carry-save layers (sum `a ^ b ^ c`, carry the majority shifted up: one LUT
    /// level each, from this step on; one a step on the iCE40, where two in a row are a function
    /// of up to 9 registers that yosys 0.70's ABC maps to three LUT4 levels, two a step
    /// elsewhere), then (iCE40: after a step that only
    /// registers them) the two vectors left into [`Builder::add_start`] in a step of its own.
    /// [`Builder::resolve`] finishes it.
    pub(crate) fn sum_start(&mut self, name: &str, mut terms: Vec<Vec<Piece>>, width: u32, title: &str, comment: &str) -> PendingAdd {
        let mut layer = 0;
        let per_step = self.family().carry_save_layers_per_step();
        while terms.len() > 2 {
            if layer % per_step == 0 {
                if per_step == 1 {
                    self.step(&format!("{title}: carry-save layer {}", layer + 1));
                } else {
                    self.step(&format!("{title}: carry-save layers {} and {}", layer + 1, layer + 2));
                }
                self.delay(per_step as f64 * LUT_DELAY);
            }
            layer += 1;
            let mut next = Vec::new();
            let mut rest = terms.into_iter();
            let mut i = 0;
            loop {
                let group: Vec<Vec<Piece>> = rest.by_ref().take(3).collect();
                if group.len() < 3 {
                    next.extend(group);
                    break;
                }
                let e: Vec<String> = group.iter().map(|t| self.pieces(&sub_pieces(t, 0, width))).collect();
                let (sn, cn) = (format!("{name}_csa{layer}_s{i}"), format!("{name}_csa{layer}_c{i}"));
                // one operand (or pair) a line
                self.wire(&sn, width, format!("{}\n    ^ {}\n    ^ {}", e[0], e[1], e[2]), &format!("carry-save layer {layer}: the sum bits"));
                self.wire(
                    &cn,
                    width,
                    format!("({0} & {1})\n    | ({0} & {2})\n    | ({1} & {2})", e[0], e[1], e[2]),
                    &format!("carry-save layer {layer}: the carries (worth twice)"),
                );
                next.push(vec![Piece::sig(&sn, 0, width)]);
                next.push(vec![Piece::zeros(1), Piece::sig(&cn, 0, width - 1)]);
                i += 1;
            }
            terms = next;
        }
        if self.family().registers_carry_save_vectors() {
            // a step that only registers the two vectors (`Family::registers_carry_save_vectors`)
            self.step(&format!("{title}: the two vectors registered"));
            self.delay(REGISTER_ONLY_DELAY);
        }
        self.step(&format!("{title}: chunk sums"));
        let zero = vec![Piece::zeros(width)];
        let (a, b) = (terms.first().unwrap_or(&zero).clone(), terms.get(1).unwrap_or(&zero).clone());
        // short chunks: the vectors come from registers spread over a wide sum
        self.add_start_short(name, &a, &b, false, width, comment)
    }

    /// [`Builder::add_start`] in chunks of at most [`SUM_CHUNK_BITS`]: for a sum whose
    /// operands come from registers spread over the fabric, or whose result fans out far.
    pub(crate) fn add_start_short(&mut self, name: &str, a: &[Piece], b: &[Piece], cin: bool, width: u32, comment: &str) -> PendingAdd {
        self.chunk_limit = SUM_CHUNK_BITS;
        let p = self.add_start(name, a, b, cin, width, comment);
        self.chunk_limit = u32::MAX;
        p
    }

    /// Finishes a carry-select add in the steps it needs, at most two LUT levels a step: none
    /// for one chunk; the chunk carries rippled two a step (one for a sum of more than
    /// [`WIDE_SUM_CHUNKS`] chunks), the last with each chunk's pick. Returns the name of the sum.
    pub(crate) fn resolve(&mut self, p: PendingAdd, title: &str) -> Sig {
        if !p.chunks.is_empty() {
            // the carries into chunks from+1..=to (chunk 1's is part0's), `per_step` levels a
            // step, then the pick with the last of them
            let to = p.chunks.len().saturating_sub(1).max(1);
            let per_step = if p.chunks.len() > WIDE_SUM_CHUNKS { 1 } else { 2 };
            let mut from = 1;
            while to - from > 1 {
                self.step(&format!("{title}: carries"));
                self.add_carries_range(&p, from, from + per_step);
                from += per_step;
            }
            let rest = from < to;
            self.step(&format!("{title}: {}select", if rest { "carries and " } else { "" }));
            if rest {
                self.add_carries_range(&p, from, to);
            }
        }
        self.add_finish(p)
    }

    /// Last step of a carry-select add: each chunk picks its sum by its carry-in (one LUT
    /// level). Returns the name of the sum.
    pub(crate) fn add_finish(&mut self, p: PendingAdd) -> Sig {
        if p.chunks.is_empty() {
            return self.sig(&p.name);
        }
        self.delay(LUT_DELAY);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let mut words = vec![self.bits(&format!("{}_part0", p.name), w0 - 1 + o, o)];
        for (i, &(lo, w)) in p.chunks.iter().enumerate().skip(1) {
            let carry = match i {
                1 => self.carry_out(&format!("{}_part0", p.name), w0 + o),
                _ => self.r(&format!("{}_carry{i}", p.name)),
            };
            let (plain, inc) = (format!("{}_part{i}", p.name), format!("{}_part{i}_plus1", p.name));
            let (a, b) = if p.top_inverted && i + 1 == p.chunks.len() {
                // the carry-out above the top chunk's sum, complemented back
                let (na, nb) = (format!("~{}", self.bits(&inc, w, w)), format!("~{}", self.bits(&plain, w - 1, w - 1)));
                if w == 1 {
                    (na, nb)
                } else {
                    (format!("{{{na}, {}}}", self.bits(&inc, w - 1, 1)), format!("{{{nb}, {}}}", self.bits(&plain, w - 2, 0)))
                }
            } else {
                (self.bits(&inc, w, 1), self.bits(&plain, w - 1, 0))
            };
            // each chunk's pick on its own line; the sum is then a plain concatenation
            let chunk = format!("{}_chunk{i}", p.name);
            self.wire(&chunk, w, format!("{carry} ? {a} : {b}"), &format!("bits [{}:{lo}]: the sum with the carry into bit {lo}", lo + w - 1));
            words.push(self.r(&chunk));
        }
        words.reverse();
        let comment = p.comment.clone();
        // many chunks: one a line
        let sep = if words.len() > 4 { ",\n    " } else { ", " };
        self.wire(&p.name, p.width, format!("{{{}}}", words.join(sep)), &comment)
    }

    /// Closes the datapath: `outputs` are read after the last step. Adds an `unused_*` wire
    /// for the bits of each signal that its last reader leaves unread, and lists the live
    /// signals of every cut.
    pub(crate) fn finish(mut self, outputs: &[&str]) -> Datapath {
        // a step with logic and no delay estimate would count 0 ns, and `--target-mhz` would
        // place its cuts on a wrong sum: every step's logic states its delay (Builder::delay)
        for s in &self.steps {
            let logic = s.wires.iter().any(|w| !w.is_plain()) || !s.dsps.is_empty();
            assert!(!logic || s.delay > 0.0, "datapath: step {} ({}) has logic but no delay estimate: call Builder::delay in it", s.index, s.title);
        }
        let last = self.cur();
        for o in outputs {
            let w = self.signal(o).width;
            self.signal(o).uses.push((last + 1, mask(w)));
        }
        // unused bits: read nowhere at the last step that reads the signal; one sink for all
        let mut unused: Vec<String> = Vec::new();
        for s in &self.signals {
            let last_use = s.uses.iter().map(|u| u.0).max().unwrap_or(s.step).max(s.step);
            if last_use > last {
                continue;
            }
            let read = s.uses.iter().filter(|u| u.0 == last_use).fold(0u128, |m, u| m | u.1);
            let seen = s.held.clone().unwrap_or_else(|| visible(&self.registered, &s.name, s.step, last_use));
            self.read.insert(seen.clone(), mask(s.width));
            unused.extend(bit_ranges(&seen, s.width, mask(s.width) & !read));
        }
        let live = (1..=last)
            .map(|k| {
                self.signals
                    .iter()
                    // a DSP's output register is the cut after its step: nothing to add there
                    .filter(|s| s.step <= k && s.uses.iter().any(|u| u.0 > k) && !(s.dsp_registered && s.step == k) && s.held.is_none())
                    .map(|s| Live { name: s.name.clone(), width: s.width, source: visible(&self.registered, &s.name, s.step, k) })
                    .collect()
            })
            .collect();
        let outputs: Vec<(String, String)> = outputs
            .iter()
            .map(|o| {
                (o.to_string(), {
                    let d = self.signals.iter().rev().find(|s| s.name == *o).expect("output defined").step;
                    visible(&self.registered, o, d, last + 1)
                })
            })
            .collect();
        for (o, seen) in &outputs {
            let w = self.signal(o).width;
            self.read.insert(seen.clone(), mask(w));
        }
        Datapath {
            tables: self.tables,
            reads: self.reads,
            steps: self.steps,
            live,
            unused,
            outputs,
            registered: self.registered,
            read: self.read,
            products: self.products,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_cover_the_width_in_balanced_pieces() {
        for w in 1..80 {
            use crate::family::ice40::CHUNK_BITS;
            let c = chunks(w, CHUNK_BITS);
            assert_eq!(c.iter().map(|x| x.1).sum::<u32>(), w);
            assert!(c.iter().all(|x| x.1 <= CHUNK_BITS && x.1 >= 1));
            assert!(c.windows(2).all(|p| p[0].0 + p[0].1 == p[1].0));
            assert_eq!(c.len() as u32, w.div_ceil(CHUNK_BITS));
        }
    }

    /// The post-adder takes an add no wider than the operands (yosys 0.23's rule on the
    /// iCE40; always in generic RTL); a wider one is the product, then a carry-select add over
    /// the bits above the addend's low zeros (a complemented addend formed beside the product);
    /// on the ECP5 always the product, then one carry chain.
    #[test]
    fn multiply_add_uses_the_post_adder_only_where_the_tool_takes_it() {
        let expr = |b: &Builder, name: &str| b.steps.iter().flat_map(|s| &s.wires).find(|w| w.name == name).map(|w| w.expr.clone());
        let (a, r) = ([Piece::sig("a", 0, 11)], [Piece::sig("r", 0, 7)]);
        let inputs = [("a", 11), ("r", 7), ("g", 20)];
        // 18 bits from 11 x 7: inside the block
        for target in [Target::Ice40, Target::Generic] {
            let mut b = Builder::new(&inputs, &[], target);
            b.step("t");
            b.multiply_add("s", &a, &r, &[Piece::sig("g", 0, 18)], 18, "t", "");
            assert_eq!(b.steps.len(), 1, "{target:?}");
            assert!(expr(&b, "s").unwrap().contains(" * ") && expr(&b, "s").unwrap().contains(" + "), "{target:?}");
        }
        // 28 bits (the entry above 7 zero bits): in the generic RTL still one expression ...
        let addend = [Piece::zeros(7), Piece::not("g", 0, 20)];
        let mut b = Builder::new(&inputs, &[], Target::Generic);
        b.step("t");
        b.multiply_add("s", &a, &r, &addend, 28, "t", "");
        assert_eq!(b.steps.len(), 1);
        // ... on the iCE40 the product alone, the addend complemented beside it, then the add
        // of bits [27:7] in carry-select chunks, and the sum with the product's low bits
        let mut b = Builder::new(&inputs, &[], Target::Ice40);
        b.step("t");
        b.multiply_add("s", &a, &r, &addend, 28, "t", "");
        assert_eq!(expr(&b, "s_prod").unwrap(), "{7'h0, a} * {11'h0, r}");
        assert_eq!(expr(&b, "s_addend").unwrap(), "{1'h0, ~g}");
        assert!(b.steps.len() >= 3, "chunk sums and their select after the product");
        assert!(expr(&b, "s_hi_part1_plus1").is_some());
        assert!(expr(&b, "s").unwrap().ends_with("s_prod_s1[6:0]}"), "{:?}", expr(&b, "s"));
        // on the ECP5 one carry chain after the product
        let mut b = Builder::new(&inputs, &[], Target::Ecp5);
        b.step("t");
        b.multiply_add("s", &a, &r, &addend, 28, "t", "");
        assert_eq!(b.steps.len(), 2);
        assert!(expr(&b, "s_hi").unwrap().contains("s_prod_s1[17:7]"), "{:?}", expr(&b, "s_hi"));
    }

    /// A register a multiplier reads (bits of a product, an input) is named for `(* keep *)`;
    /// one only the fabric reads is not.
    #[test]
    fn a_register_read_by_a_block_is_kept() {
        let mut b = Builder::new(&[("a", 8), ("c", 8)], &[1, 2], Target::Ice40);
        b.step("p");
        b.wire("p", 16, "a * c".into(), "");
        b.delay(5.5);
        let e = b.bits("p", 15, 8);
        b.wire("hi", 8, e, "");
        b.step("q");
        let (hv, cv) = (b.r("hi"), b.r("c"));
        b.wire("q", 16, format!("{hv} * {cv}"), "");
        let e = b.bits("p", 7, 0);
        b.wire("lo", 8, format!("~{e}"), "");
        b.delay(5.5);
        let d = b.finish(&["q", "lo"]);
        assert!(d.read_by_block("hi", 1), "bits of a product, read by a multiplier");
        assert!(!d.read_by_block("p", 1), "the product itself is read only by the fabric");
        assert!(d.read_by_block("c", 1), "an input's register a multiplier reads");
    }

    /// Issue 35: a multiplier reads a block's output register also through wires that only
    /// slice it (yosys 0.70 took such a register into both blocks): it is kept too.
    #[test]
    fn a_block_output_register_read_through_slices_is_kept() {
        let mut b = Builder::new(&[("a", 8), ("c", 8)], &[1], Target::Ice40);
        b.step("p");
        b.wire("p", 16, "a * c".into(), "");
        b.delay(5.5);
        b.step("q");
        b.delay(5.5);
        let e = b.bits("p", 15, 4);
        b.wire("s", 12, e, "a slice of the registered product");
        let e = b.bits("s", 11, 4);
        b.wire("t", 8, e, "a slice of the slice");
        let (t, c) = (b.r("t"), b.r("c"));
        b.wire("q", 16, format!("{t} * {c}"), "");
        let d = b.finish(&["q"]);
        assert!(d.read_by_block("p", 1), "read by a multiplier through two slices");
    }

    /// Issue 36: no carry-out leaves a chain as the chain's own CO. Each chunk's carry is a sum
    /// bit of its chunk, complemented (1 above the first operand, 0 above the second), and so
    /// is the top chunk's when the add's top bit is a carry-out; the select reads them back
    /// complemented.
    #[test]
    fn carries_are_sum_bits_kept_complemented() {
        let mut b = Builder::new(&[("x", 16), ("y", 15)], &[1, 2], Target::Ice40);
        b.step("add");
        b.chunk_limit = 6;
        // 17 bits of two 16/15-bit operands: the top bit is the carry-out
        let p = b.add_start("s", &[Piece::sig("x", 0, 16)], &[Piece::sig("y", 0, 15)], false, 17, "");
        let expr = |b: &Builder, name: &str| b.steps.iter().flat_map(|s| &s.wires).find(|w| w.name == name).map(|w| w.expr.clone()).unwrap();
        assert_eq!(expr(&b, "s_part0"), "{1'b1, x[5:0]} + {1'b0, y[5:0]}");
        assert_eq!(expr(&b, "s_part1"), "{1'b1, x[11:6]} + {1'b0, y[11:6]}");
        assert_eq!(expr(&b, "s_part1_plus1"), "{1'b1, x[11:6], 1'b1} + {1'b0, y[11:6], 1'b1}");
        assert!(expr(&b, "s_part2").starts_with("{1'h1, x[15:12]}"), "{}", expr(&b, "s_part2"));
        b.step("carries");
        b.add_carries(&p);
        assert!(expr(&b, "s_carry2").starts_with("~s_part0_c1[6] ?"), "{}", expr(&b, "s_carry2"));
        b.step("select");
        b.add_finish(p);
        assert!(expr(&b, "s_chunk2").contains("{~s_part2_plus1_c2[5], s_part2_plus1_c2[4:1]}"), "{}", expr(&b, "s_chunk2"));
    }

    /// Issue 37: a step with logic and no delay estimate is a build error (it would count 0 ns
    /// and `--target-mhz` would place its cuts on a wrong sum); a step that only selects bits
    /// needs none.
    #[test]
    #[should_panic(expected = "has logic but no delay estimate")]
    fn a_step_without_a_delay_estimate_is_refused() {
        let mut b = Builder::new(&[("x", 8)], &[1], Target::Ice40);
        b.step("slices only");
        let e = b.bits("x", 7, 4);
        b.wire("hi", 4, e, "");
        b.step("logic, no delay");
        let h = b.r("hi");
        b.wire("y", 4, format!("~{h}"), "");
        b.finish(&["y"]);
    }

    /// `at_least` is `>=` on every value of a 6-bit signal for every constant: its AND/OR
    /// expression, evaluated here, agrees with the integer comparison.
    #[test]
    fn at_least_is_the_comparison() {
        // a tiny evaluator of the expressions at_least writes: x[i], 1'b1, &, |, parentheses
        fn eval(e: &[u8], at: &mut usize, x: u32) -> bool {
            let mut v = term(e, at, x);
            while *at < e.len() && e[*at] != b')' {
                let op = e[*at];
                *at += 1;
                let r = term(e, at, x);
                v = if op == b'&' { v & r } else { v | r };
            }
            v
        }
        fn term(e: &[u8], at: &mut usize, x: u32) -> bool {
            match e[*at] {
                b'(' => {
                    *at += 1;
                    let v = eval(e, at, x);
                    *at += 1;
                    v
                }
                b'1' => {
                    *at += 4;
                    true
                }
                _ => {
                    let end = e[*at..].iter().position(|&c| c == b']').unwrap() + *at;
                    let bit: u32 = std::str::from_utf8(&e[*at + 2..end]).unwrap().parse().unwrap();
                    *at = end + 1;
                    (x >> bit) & 1 == 1
                }
            }
        }
        let mut b = Builder::new(&[("x", 6)], &[], Target::Ice40);
        b.step("t");
        for c in 0..64u128 {
            let expr = b.at_least("x", 5, 0, c).replace(' ', "");
            for x in 0..64u32 {
                assert_eq!(eval(expr.as_bytes(), &mut 0, x), x as u128 >= c, "x = {x}, c = {c}: {expr}");
            }
        }
    }

    #[test]
    fn sub_pieces_pads_with_zeros() {
        let p = [Piece::sig("a", 2, 3), Piece::Const { value: 0b101, width: 3 }];
        let s = sub_pieces(&p, 1, 7);
        let mut b = Builder::new(&[("a", 8)], &[], Target::Ice40);
        b.step("t");
        assert_eq!(b.pieces(&s), "{2'h0, 3'h5, a[4:3]}");
    }

    #[test]
    fn liveness_and_unused_bits() {
        let mut b = Builder::new(&[("x", 8)], &[1], Target::Ice40);
        b.step("one");
        let e = b.bits("x", 7, 4);
        b.wire("y", 4, e, "");
        b.step("two");
        let e = b.bits("x", 0, 0);
        let y = b.r("y");
        b.wire("z", 5, format!("{{{y}, {e}}}"), "");
        let d = b.finish(&["z"]);
        // cut 1 carries x (read again in step 2) and y
        assert_eq!(d.live[0].iter().map(|l| (l.name.as_str(), l.source.as_str())).collect::<Vec<_>>(), [("x", "x"), ("y", "y_s1")]);
        assert_eq!(d.live[1].iter().map(|l| l.name.as_str()).collect::<Vec<_>>(), ["z"]);
        // step 2 reads x through the register of cut 1; bits 7:1 are left for the sink
        assert_eq!(d.unused, ["x_c1[7:1]"]);
        assert_eq!(d.outputs, [("z".to_string(), "z_s2".to_string())]);
    }

    #[test]
    fn a_combinational_cut_is_no_name() {
        // nothing registered: every reference goes straight to the defining wire or port
        assert_eq!(visible(&[], "x", 0, 3), "x");
        assert_eq!(visible(&[], "y", 1, 3), "y_s1");
        assert_eq!(visible(&[2], "y", 1, 3), "y_c2");
        assert_eq!(visible(&[2], "y", 1, 2), "y_s1");
        assert_eq!(visible(&[1, 2], "y", 2, 2), "y_s2");
    }
}
