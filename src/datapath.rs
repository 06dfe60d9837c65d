//! Stage 3c: the quadratic unit's datapath as a list of steps, from which the RTL is rendered.
//!
//! Every step is a set of wires computed from the previous cut (`x_cK`) or from wires of the
//! same step (`x_sK`); after step K comes cut K, a pipeline register or a pass-through as
//! [`Widths::registered_cuts`] says. The [`Builder`] resolves each reference to the right
//! version, works out which signals are alive across each cut (only those get registers),
//! marks the bits nobody reads (for a lint-clean `unused_*` wire) and keeps a delay estimate
//! per step, from which `widths::balanced_cuts` places the registers.
//!
//! `lean` is split into short steps so that a fully registered unit has at most one DSP
//! multiply-add, one ROM read, one LUT level or one ≤ [`CHUNK_BITS`]-bit carry chain between
//! registers, and every carry chain takes its operands straight from registers (an inverter
//! or mux in front of an iCE40 carry chain costs a LUT level and a route). Wide adds go into
//! the DSPs' post-adders where the products are; the three left in the fabric are
//! carry-select: chunks added with carry-in 0 and 1 in one step, the carries rippled in the
//! next, each chunk's sum picked in the third. Every regrouping is exact, so the values are
//! those of [`crate::model::Model::trace`].
//! `paper` keeps the six coarse steps of the seed's Fig. 5.

use crate::config::{Arch, Config};
use crate::widths::{bit_length, mask, Widths};

/// Longest carry chain of one lean step (bits). iCE40 UP5K post-route, operands and sum
/// straight from and to registers, carry-out registered too: 4 bits ~109 MHz, 6 bits
/// ~103 MHz, 8 bits ~92 MHz.
pub const CHUNK_BITS: u32 = 6;

/// Width of a DSP block's multiplier operands (iCE40 SB_MAC16: 16×16).
pub const DSP_BITS: u32 = 16;

/// One wire of a step: `wire [width-1:0] name_sK = expr;   // comment`.
#[derive(Debug, Clone)]
pub struct Wire {
    pub name: String,
    pub width: u32,
    pub expr: String,
    pub comment: String,
}

#[derive(Debug, Clone)]
pub struct Step {
    /// 1-based
    pub index: usize,
    pub title: String,
    pub wires: Vec<Wire>,
    /// Delay estimate (ns on a LUT4 + carry-chain fabric); only ratios matter.
    pub delay: f64,
}

/// A signal alive across a cut, and the name it is taken from there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Live {
    pub name: String,
    pub width: u32,
    pub source: String,
}

/// A constant table of the unit (a ROM): written as a `$readmemh` file or inlined as a `case`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Table {
    /// The memory's name in the Verilog.
    pub name: String,
    /// Its `$readmemh` file.
    pub file: String,
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
    pub fn address_bits(&self) -> u32 {
        bit_length(self.words.len() as u128 - 1).max(1)
    }
}

/// A read of a table in a step: `signal_sK = table[addr]`.
#[derive(Debug, Clone)]
pub struct RomRead {
    pub step: usize,
    pub signal: String,
    pub table: usize,
    /// the address as a Verilog expression of this step
    pub addr: String,
}

#[derive(Debug, Clone)]
pub struct Datapath {
    pub tables: Vec<Table>,
    pub reads: Vec<RomRead>,
    pub steps: Vec<Step>,
    /// `live[K-1]`: the signals cut K carries, in definition order.
    pub live: Vec<Vec<Live>>,
    /// The one lint sink: the XOR of every bit no step reads (None when there is none).
    pub unused: Option<String>,
    /// Each output port's source after the last step.
    pub outputs: Vec<(String, String)>,
    pub registered: Vec<u32>,
}

impl Datapath {
    pub fn delays(&self) -> Vec<f64> {
        self.steps.iter().map(|s| s.delay).collect()
    }
}

#[derive(Debug, Clone)]
struct Signal {
    name: String,
    width: u32,
    step: usize,
    /// (step, bits read) for every reference
    uses: Vec<(usize, u128)>,
}

/// A sized Verilog literal, `W'hX`.
pub fn lit(width: u32, value: u128) -> String {
    format!("{width}'h{value:x}")
}

/// Records the datapath step by step; see the module documentation.
pub struct Builder {
    steps: Vec<Step>,
    signals: Vec<Signal>,
    tables: Vec<Table>,
    reads: Vec<RomRead>,
    /// the cuts that hold a register (1-based)
    registered: Vec<u32>,
}

/// Bits `[lo, lo+width)` of a signal, optionally inverted; or a constant.
#[derive(Debug, Clone)]
pub enum Piece {
    Sig { name: String, lo: u32, width: u32, invert: bool },
    Const { value: u128, width: u32 },
}

impl Piece {
    pub fn sig(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig { name: name.into(), lo, width, invert: false }
    }
    pub fn not(name: &str, lo: u32, width: u32) -> Piece {
        Piece::Sig { name: name.into(), lo, width, invert: true }
    }
    pub fn zeros(width: u32) -> Piece {
        Piece::Const { value: 0, width }
    }
    fn width(&self) -> u32 {
        match self {
            Piece::Sig { width, .. } | Piece::Const { width, .. } => *width,
        }
    }
}

/// Bits `[lo, lo+width)` of the value the pieces (LSB first) make, zero above their top.
pub fn sub_pieces(pieces: &[Piece], lo: u32, width: u32) -> Vec<Piece> {
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

/// A wide add started by [`Builder::add_start`], finished by [`Builder::add_finish`].
pub struct PendingAdd {
    name: String,
    width: u32,
    chunks: Vec<(u32, u32)>,
    /// 1 when chunk 0 carries its carry-in as an extra low bit
    part0_offset: u32,
    comment: String,
}

/// The name under which a signal defined in step `def` (0: an input port) is seen in step
/// `at`: its own wire in its own step, else the last register holding it, else its wire.
pub fn visible(registered: &[u32], name: &str, def: usize, at: usize) -> String {
    if def == at {
        return format!("{name}_s{at}");
    }
    match registered.iter().copied().filter(|&r| r as usize >= def && (r as usize) < at).max() {
        Some(r) => format!("{name}_c{r}"),
        None if def == 0 => name.to_string(),
        None => format!("{name}_s{def}"),
    }
}

/// Chunk boundaries `(lo, width)` of a `width`-bit carry chain, each ≤ `CHUNK_BITS`.
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
pub const LUT_DELAY: f64 = 2.7;

/// A `w`-bit carry chain, carry-out included.
pub fn add_delay(w: u32) -> f64 {
    0.7 + 0.3 * w as f64 + LUT_DELAY
}

/// An a×b multiply: one DSP when both fit its operands, else an array of partial products.
pub fn mul_delay(a: u32, b: u32) -> f64 {
    if a.max(b) <= DSP_BITS {
        5.5
    } else {
        1.5 * ((a.min(b).max(1) as f64).log2().ceil() + 1.0) + 0.3 * (a + b) as f64
    }
}

impl Builder {
    /// `inputs`: the port signals, available from cut 0; `registered`: the cuts that hold a
    /// pipeline register (a reference resolves to the last of them before it, or to the
    /// defining wire when there is none: a combinational cut emits nothing).
    pub fn new(inputs: &[(&str, u32)], registered: &[u32]) -> Builder {
        Builder {
            steps: Vec::new(),
            signals: inputs.iter().map(|&(n, w)| Signal { name: n.into(), width: w, step: 0, uses: Vec::new() }).collect(),
            tables: Vec::new(),
            reads: Vec::new(),
            registered: registered.to_vec(),
        }
    }

    fn cur(&self) -> usize {
        self.steps.len()
    }

    /// Starts the next step.
    pub fn step(&mut self, title: &str) {
        let index = self.steps.len() + 1;
        self.steps.push(Step { index, title: title.into(), wires: Vec::new(), delay: 0.0 });
    }

    /// Raises the current step's delay estimate to at least `d`.
    pub fn delay(&mut self, d: f64) {
        let s = self.steps.last_mut().expect("a step");
        s.delay = s.delay.max(d);
    }

    fn signal(&mut self, name: &str) -> &mut Signal {
        self.signals.iter_mut().rev().find(|s| s.name == name).unwrap_or_else(|| panic!("datapath: {name} used before it is defined"))
    }

    /// The name of `name` as seen from the current step.
    fn version(&mut self, name: &str) -> String {
        let (cur, def) = (self.cur(), self.signal(name).step);
        visible(&self.registered, name, def, cur)
    }

    /// Bits `[hi:lo]` of a signal (the bare name when that is all of it).
    pub fn bits(&mut self, name: &str, hi: u32, lo: u32) -> String {
        let cur = self.cur();
        let s = self.signal(name);
        assert!(hi < s.width && lo <= hi, "datapath: {name}[{hi}:{lo}] of a {}-bit signal", s.width);
        s.uses.push((cur, mask(hi + 1) & !mask(lo)));
        let whole = lo == 0 && hi + 1 == s.width;
        let v = self.version(name);
        match (whole, hi == lo) {
            (true, _) => v,
            (false, true) => format!("{v}[{lo}]"),
            (false, false) => format!("{v}[{hi}:{lo}]"),
        }
    }

    /// All of a signal.
    pub fn r(&mut self, name: &str) -> String {
        let w = self.signal(name).width;
        self.bits(name, w - 1, 0)
    }

    /// Bits `[lo, lo+width)` of a signal as an operand of exactly `out` bits: cut to its low
    /// `out` bits (enough for a result taken modulo 2^out) or zero-extended.
    pub fn operand(&mut self, name: &str, lo: u32, width: u32, out: u32) -> String {
        self.pieces(&sub_pieces(&[Piece::sig(name, lo, width)], 0, out))
    }

    /// All of `name` zero-extended to `to` bits.
    pub fn zext(&mut self, name: &str, to: u32) -> String {
        let w = self.signal(name).width;
        assert!(to >= w, "zext {name} from {w} to {to}");
        self.operand(name, 0, w, to)
    }

    /// The Verilog for a list of pieces (LSB first), MSB first in a concatenation.
    pub fn pieces(&mut self, pieces: &[Piece]) -> String {
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
    pub fn wire(&mut self, name: &str, width: u32, expr: String, comment: &str) {
        assert!(self.signals.iter().all(|s| s.name != name), "datapath: {name} defined twice");
        let cur = self.cur();
        self.signals.push(Signal { name: name.into(), width, step: cur, uses: Vec::new() });
        self.steps.last_mut().expect("a step").wires.push(Wire { name: name.into(), width, expr, comment: comment.into() });
    }

    /// Adds a constant table to the unit; returns its index for [`Builder::rom_read`].
    pub fn table(&mut self, t: Table) -> usize {
        self.tables.push(t);
        self.tables.len() - 1
    }

    /// Defines `signal` in the current step as the entry of table `t` addressed by all of
    /// the signal `addr` (the template renders the memory and the read).
    pub fn rom_read(&mut self, signal: &str, t: usize, addr: &str) {
        let a = self.r(addr);
        let cur = self.cur();
        let width = self.tables[t].width;
        assert!(self.signals.iter().all(|s| s.name != signal), "datapath: {signal} defined twice");
        self.signals.push(Signal { name: signal.into(), width, step: cur, uses: Vec::new() });
        self.reads.push(RomRead { step: cur, signal: signal.into(), table: t, addr: a });
    }

    /// `name = (a + b + cin) mod 2^width`. One chunk: computed here. More: each chunk is added
    /// here with carry-in 0 and 1 (carry-select), and [`Builder::add_finish`] resolves the
    /// carries and picks in the next step.
    pub fn add_start(&mut self, name: &str, a: &[Piece], b: &[Piece], cin: bool, width: u32, comment: &str) -> PendingAdd {
        let parts = chunks(width, CHUNK_BITS);
        let n = parts.len();
        let max_chunk = parts.iter().map(|c| c.1).max().unwrap_or(1);
        self.delay(add_delay(max_chunk));
        if n == 1 {
            let ea = self.pieces(&sub_pieces(a, 0, width));
            let eb = self.addend(&sub_pieces(b, 0, width), |e| e);
            let plus = if cin { format!(" + {}", lit(width, 1)) } else { String::new() };
            self.wire(name, width, format!("{ea}{eb}{plus}"), comment);
        } else {
            for (i, &(lo, w)) in parts.iter().enumerate() {
                let top = i + 1 == n;
                let ww = if top { w } else { w + 1 };
                let ext = |e: String| if top { e } else { format!("{{1'b0, {e}}}") };
                // carry-in 1 as a 1 + 1 in an extra low bit: one adder that no synthesis tool
                // can share with the carry-in-0 sum (a shared "+ 1" would chain two adders)
                let ext1 = |e: String| if top { format!("{{{e}, 1'b1}}") } else { format!("{{1'b0, {e}, 1'b1}}") };
                let pa = sub_pieces(a, lo, w);
                let pb = sub_pieces(b, lo, w);
                let ea = self.pieces(&pa);
                let what = if top { format!("bits [{}:{lo}]", lo + w - 1) } else { format!("bits [{}:{lo}] and their carry", lo + w - 1) };
                let sum0 = {
                    let eb = self.addend(&pb, ext);
                    format!("{}{eb}", ext(ea.clone()))
                };
                let sum1 = {
                    let eb = self.addend(&pb, ext1);
                    let eb = if eb.is_empty() { format!(" + {}", lit(ww + 1, 1)) } else { eb };
                    format!("{}{eb}", ext1(ea))
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
        PendingAdd { name: name.into(), width, chunks: if n == 1 { Vec::new() } else { parts }, part0_offset: u32::from(cin), comment: comment.into() }
    }

    /// Second step of a carry-select add: the carry into each chunk from the third on
    /// (the first chunk's own carry-out is the carry into the second), rippled through the
    /// chunks' carry-outs. Nothing to do for one or two chunks.
    pub fn add_carries(&mut self, p: &PendingAdd) {
        let n = p.chunks.len();
        if n <= 2 {
            return;
        }
        self.delay(LUT_DELAY * (n - 2) as f64);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let mut carry = self.bits(&format!("{}_part0", p.name), w0 + o, w0 + o);
        for i in 1..n - 1 {
            let w = p.chunks[i].1;
            let (ca, cb) = (self.bits(&format!("{}_part{i}_plus1", p.name), w + 1, w + 1), self.bits(&format!("{}_part{i}", p.name), w, w));
            let cname = format!("{}_carry{}", p.name, i + 1);
            self.wire(&cname, 1, format!("{carry} ? {ca} : {cb}"), &format!("carry into bit {}", p.chunks[i + 1].0));
            carry = self.r(&cname);
        }
    }

    /// Last step of a carry-select add: each chunk picks its sum by its carry-in (one LUT
    /// level). Returns the name of the sum.
    pub fn add_finish(&mut self, p: PendingAdd) -> String {
        if p.chunks.is_empty() {
            return p.name;
        }
        self.delay(LUT_DELAY);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let mut words = vec![self.bits(&format!("{}_part0", p.name), w0 - 1 + o, o)];
        for (i, &(_, w)) in p.chunks.iter().enumerate().skip(1) {
            let carry = match i {
                1 => self.bits(&format!("{}_part0", p.name), w0 + o, w0 + o),
                _ => self.r(&format!("{}_carry{i}", p.name)),
            };
            let (plain, inc) = (format!("{}_part{i}", p.name), format!("{}_part{i}_plus1", p.name));
            let (a, b) = (self.bits(&inc, w, 1), self.bits(&plain, w - 1, 0));
            words.push(format!("({carry} ? {a} : {b})"));
        }
        words.reverse();
        let comment = p.comment.clone();
        self.wire(&p.name, p.width, format!("{{{}}}", words.join(", ")), &comment);
        p.name
    }

    /// Closes the datapath: `outputs` are read after the last step. Adds an `unused_*` wire
    /// for the bits of each signal that its last reader leaves unread, and lists the live
    /// signals of every cut.
    pub fn finish(mut self, outputs: &[&str]) -> Datapath {
        let last = self.cur();
        for o in outputs {
            let w = self.signal(o).width;
            self.signal(o).uses.push((last + 1, mask(w)));
        }
        // unused bits: read nowhere at the last step that reads the signal; one sink for all
        let mut parts: Vec<String> = Vec::new();
        for s in &self.signals {
            let last_use = s.uses.iter().map(|u| u.0).max().unwrap_or(s.step).max(s.step);
            if last_use > last {
                continue;
            }
            let read = s.uses.iter().filter(|u| u.0 == last_use).fold(0u128, |m, u| m | u.1);
            let unread = mask(s.width) & !read;
            if unread == 0 {
                continue;
            }
            let v = visible(&self.registered, &s.name, s.step, last_use);
            let mut b = s.width;
            while b > 0 {
                b -= 1;
                if unread >> b & 1 == 1 {
                    let hi = b;
                    while b > 0 && unread >> (b - 1) & 1 == 1 {
                        b -= 1;
                    }
                    parts.push(if s.width == 1 {
                        v.clone()
                    } else if hi == b {
                        format!("{v}[{b}]")
                    } else {
                        format!("{v}[{hi}:{b}]")
                    });
                }
            }
        }
        let unused = (!parts.is_empty()).then(|| format!("^{{{}}}", parts.join(", ")));
        let live = (1..=last)
            .map(|k| {
                self.signals
                    .iter()
                    .filter(|s| s.step <= k && s.uses.iter().any(|u| u.0 > k))
                    .map(|s| Live { name: s.name.clone(), width: s.width, source: visible(&self.registered, &s.name, s.step, k) })
                    .collect()
            })
            .collect();
        let outputs = outputs
            .iter()
            .map(|o| {
                (o.to_string(), {
                    let d = self.signals.iter().rev().find(|s| s.name == *o).expect("output defined").step;
                    visible(&self.registered, o, d, last + 1)
                })
            })
            .collect();
        Datapath { tables: self.tables, reads: self.reads, steps: self.steps, live, unused, outputs, registered: self.registered }
    }
}

/// The datapath of the configured model: the one description every RTL is rendered from.
pub fn build(cfg: &Config, w: &Widths) -> Datapath {
    let inputs = [("cos_g", w.cos_bits), ("n", cfg.n_bits()), ("ks_r", cfg.b()), ("ks_g", cfg.b()), ("ks_b", cfg.b())];
    let mut b = Builder::new(&inputs, &w.registered_cuts);
    match (crate::model::Kind::new(cfg), cfg.arch()) {
        (crate::model::Kind::Fitted { fit, widths }, _) => crate::fitted::datapath(cfg, &fit, &widths, &mut b),
        (crate::model::Kind::Blinn { widths, tables }, _) => crate::blinn::datapath(cfg, &widths, &tables, &mut b),
        (crate::model::Kind::BlinnPow, _) => crate::blinn_pow::datapath(cfg, w, &mut b),
        (_, Arch::Lean) => lean(cfg, w, &mut b),
        (_, Arch::Paper) => paper(cfg, w, &mut b),
    }
    b.finish(&["spec_r", "spec_g", "spec_b", "intensity", "done"])
}

pub const CHANNELS: [&str; 3] = ["r", "g", "b"];

/// The cut-off ROM (10) read: `cos_sp`, addressed by n.
fn rom_read(cfg: &Config, w: &Widths, b: &mut Builder) {
    let t = b.table(Table {
        name: "cos_sp_rom".into(),
        file: crate::emit::ROM_FILE.into(),
        param: "ROM_FILE".into(),
        width: w.cos_bits,
        words: crate::rom::cos_sp_table(cfg).into_iter().map(u128::from).collect(),
        what: format!("cut-off ROM cos_sp(n), UQ1.{}, address = n", cfg.f()),
        fields: vec![("cos_sp".into(), w.cos_bits)],
    });
    b.rom_read("cos_sp", t, "n");
    b.delay(LUT_DELAY * cfg.n_bits().div_ceil(2) as f64);
}

/// The lean datapath: short steps, every decomposition exact (see the module docs).
///
/// Where it saves against `paper` (each also said in the RTL comments):
/// - `k_q·n` is one constant multiply: no general multiplier by k (34);
/// - the deviation and `1 − deviation` come out of DSP multiply-adds (`P + K'`, then an
///   inversion folded into the key block's LUTs): no fabric adder for adder 9;
/// - the bracket is squared as `hi²` and `hi·lo` with a 16-bit `hi`, the adds inside the
///   DSPs: two 16-bit DSP products instead of a 3-DSP 18×18 one;
/// - widths cut to the error budget (bracket UQ1.(max(FI,B)+2), colours fed UQ1.(B+1));
/// - the colour rounding half is the colour DSPs' addend: no rounding adders.
fn lean(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, cb, bb, fi) = (cfg.f(), w.cos_bits, cfg.b(), cfg.fi());
    let (wb, ws, wsc, s) = (w.bracket_frac_bits, w.square_frac_bits, w.color_square_frac_bits, w.deviation_shift);
    // P is needed modulo 2^m only: dev = P[m-1:s] (m = KF+F+1); higher bits matter only
    // beyond the cut-off, where the key block zeroes the bracket.
    let m = wb + s + 1;

    b.step("cut-off ROM read (10); cos complemented and clamped");
    rom_read(cfg, w, b);
    let g = b.bits("cos_g", f, f);
    let x = b.bits("cos_g", f - 1, 0);
    b.wire(
        "cos_complement",
        cb,
        format!("{{{g}, ~{x} | {{{f}{{{g}}}}}}}"),
        &format!("UQ1.{f}: ~cos = 1 - 2^-{f} - cos; all ones when cos_g >= 1.0, so +1 wraps to 0 (the clamp)"),
    );
    b.delay(LUT_DELAY);

    b.step("1 - cos (adder 6): chunk sums");
    let d = b.add_start("one_minus_cos", &[Piece::sig("cos_complement", 0, cb)], &[], true, cb, &format!("UQ1.{f}: 1 - min(cos, 1) = ~cos + 1, exact"));

    b.step("1 - cos: carries; comparator (12): chunk sums");
    b.add_carries(&d);
    // cos < cos_sp  <=>  cos_sp + ~cos (over F+1 bits) carries out: an add of two registers
    let cmp = b.add_start(
        "cutoff_sum",
        &[Piece::sig("cos_sp", 0, cb)],
        &[Piece::sig("cos_complement", 0, f), Piece::Const { value: 1, width: 1 }],
        false,
        cb + 1,
        &format!("cos_sp + ~cos over UQ1.{f}: bit {cb} (the carry) is cos < cos_sp"),
    );

    b.step("1 - cos: select; comparator: carries; k_q*n (constant multiply)");
    b.add_finish(d);
    b.add_carries(&cmp);
    let nn = b.operand("n", 0, cfg.n_bits(), w.kn_bits);
    b.wire(
        "kn",
        w.kn_bits,
        format!("{nn} * {}", lit(w.kn_bits, cfg.k_code as u128)),
        &format!("UQ{}.{}: k_q*n, exact; one constant multiply replaces the paper's general multiplier 34", w.kn_bits - cfg.kf(), cfg.kf()),
    );
    b.delay(mul_delay(cfg.n_bits(), bit_length(cfg.k_code as u128)));

    // 1 - deviation without an adder: with K = 2^(WB+s) + 2^s - 1 and K' = 2^m - 1 - K,
    // ~(P + K') = K - P (mod 2^m), and (K - P)[m-1:s] = 2^WB - floor(P / 2^s) (mod 2^(WB+1)).
    let k_big = (1u128 << (wb + s)) + (1u128 << s) - 1;
    let k_prime = mask(m) - k_big;
    b.step("comparator: select; deviation, high partial product (multiply-add)");
    let sum = b.add_finish(cmp);
    let (gg, c) = (b.bits("cos_g", f, f), b.bits(&sum, cb, cb));
    b.wire("done", 1, format!("~{gg} & {c}"), "comparator (12): cos(gamma) < cos_sp(n), beyond the highlight (never when cos >= 1.0)");
    // kn = kn_hi*2^16 + kn_lo: two products with <= 16-bit operands instead of one that
    // would take 3 DSP blocks; the hi product is needed only modulo 2^(m-16)
    let split = w.kn_bits > DSP_BITS && m > DSP_BITS;
    if split {
        let hi_w = m - DSP_BITS;
        let (kh, d2) = (b.operand("kn", DSP_BITS, w.kn_bits - DSP_BITS, hi_w), b.operand("one_minus_cos", 0, cb, hi_w));
        b.wire(
            "deviation_hi",
            hi_w,
            format!("{kh} * {d2} + {}", lit(hi_w, k_prime >> DSP_BITS)),
            &format!("kn[{}:{DSP_BITS}] * (1 - cos) + K'[{}:{DSP_BITS}], mod 2^{hi_w} (one DSP, the add inside it)", w.kn_bits - 1, m - 1),
        );
        b.delay(mul_delay(w.kn_bits - DSP_BITS, cb));
    }

    b.step("deviation P = k_q*n*(1 - cos) (multiplier 7) plus K' (multiply-add)");
    let expr = if split {
        let (kl, d1) = (b.operand("kn", 0, DSP_BITS, m), b.operand("one_minus_cos", 0, cb, m));
        let c = b.pieces(&[Piece::Const { value: k_prime & mask(DSP_BITS), width: DSP_BITS }, Piece::sig("deviation_hi", 0, m - DSP_BITS)]);
        format!("{kl} * {d1} + {c}")
    } else {
        let (kn, d1) = (b.operand("kn", 0, w.kn_bits, m), b.operand("one_minus_cos", 0, cb, m));
        format!("{kn} * {d1} + {}", lit(m, k_prime))
    };
    b.wire("deviation_sum", m, expr, &format!("P + K' mod 2^{m}, P = k_q*n*(1 - cos) UQ.{} exact; its complement is K - P (no subtractor)", cfg.kf() + f));
    b.delay(mul_delay(DSP_BITS, cb));

    b.step("bracket = 1 - deviation (adder 9), truncation #1, key block (13)");
    let (dn, q) = (b.r("done"), b.bits("deviation_sum", m - 1, s));
    b.wire(
        "bracket",
        wb + 1,
        format!("{dn} ? {} : ~{q}", lit(wb + 1, 0)),
        &format!("UQ1.{wb} in [0, 1]: 2^{wb} - floor(P/2^{s}) (truncation #1), zeroed beyond the cut-off (key block 13)"),
    );
    b.delay(LUT_DELAY);

    let r = w.squarer_split;
    let full_bits = w.full_square_bits();
    let full: Vec<Piece> = if r > 0 {
        // bracket = hi*2^r + lo; bracket^2 = hi^2*2^2r + hi*lo*2^(r+1) + lo^2 regrouped, all
        // floors exact: T = hi*lo + lo^2/2^(r+1), Z = hi^2 + T/2^(r-1), and
        // bracket^2 = {Z, T mod 2^(r-1), lo^2 mod 2^(r+1)}: two multiply-adds, no fabric adder
        let hw = wb + 1 - r;
        b.step("square (squarer 11): lo^2");
        // a table of 2^r entries: LUTs, no carry chain in front of the next DSP
        let lo = b.bits("bracket", r - 1, 0);
        let table = (0..(1u128 << r)).rev().fold(String::new(), |acc, v| match acc.is_empty() {
            true => lit(2 * r, v * v),
            false => format!("({lo} == {}) ? {} : {acc}", lit(r, v), lit(2 * r, v * v)),
        });
        b.wire("square_ll", 2 * r, table, &format!("lo^2 by table, bracket = hi*2^{r} + lo"));
        b.delay(LUT_DELAY);
        b.step("square: T = hi*lo + lo^2/2^(r+1) (multiply-add)");
        let tw = hw + r;
        let (hi, lo) = (b.operand("bracket", r, hw, tw), b.operand("bracket", 0, r, tw));
        let plus = if 2 * r > r + 1 { format!(" + {}", b.operand("square_ll", r + 1, r - 1, tw)) } else { String::new() };
        b.wire("square_t", tw, format!("{hi} * {lo}{plus}"), "hi*lo + floor(lo^2 / 2^(r+1)), exact (one DSP, the add inside it)");
        b.delay(mul_delay(hw, r));
        b.step("square: Z = hi^2 + T/2^(r-1) (multiply-add)");
        let (h1, h2) = (b.operand("bracket", r, hw, 2 * hw), b.operand("bracket", r, hw, 2 * hw));
        let th = b.operand("square_t", r - 1, tw - (r - 1), 2 * hw);
        b.wire(
            "square_z",
            2 * hw,
            format!("{h1} * {h2} + {th}"),
            &format!("floor(bracket^2 / 2^{}), exact: a {hw}x{hw} multiply-add (one DSP) instead of {}x{}", 2 * r, wb + 1, wb + 1),
        );
        b.delay(mul_delay(hw, hw));
        let mut full = vec![Piece::sig("square_ll", 0, r + 1)];
        if r > 1 {
            full.push(Piece::sig("square_t", 0, r - 1));
        }
        full.push(Piece::sig("square_z", 0, 2 * hw));
        full
    } else {
        b.step("square (squarer 11)");
        let (a1, a2) = (b.operand("bracket", 0, wb + 1, full_bits), b.operand("bracket", 0, wb + 1, full_bits));
        b.wire("square_full", full_bits, format!("{a1} * {a2}"), &format!("UQ2.{}: bracket^2, exact (top bit always 0)", 2 * wb));
        b.delay(mul_delay(wb + 1, wb + 1));
        vec![Piece::sig("square_full", 0, full_bits)]
    };

    b.step("truncation #2; colour multipliers (14-16) with the rounding half (multiply-add); intensity rounding: chunk sums");
    let sq = b.pieces(&sub_pieces(&full, w.square_shift, ws + 1));
    b.wire("square", ws + 1, sq, &format!("UQ1.{ws}: S = bracket^2 floored to 2^-{ws} (truncation #2)"));
    let csq = b.bits("square", ws, ws - wsc);
    b.wire(
        "color_square",
        wsc + 1,
        csq,
        &if wsc < ws { format!("UQ1.{wsc}: all the colours' budget needs (saves {} bits per colour multiplier)", ws - wsc) } else { format!("UQ1.{wsc}") },
    );
    let cpb = w.color_product_bits;
    for ch in CHANNELS {
        let (cs, ks) = (b.zext("color_square", cpb), b.zext(&format!("ks_{ch}"), cpb));
        b.wire(
            &format!("color_sum_{ch}"),
            cpb,
            format!("{cs} * {ks} + {}", lit(cpb, 1u128 << (wsc - 1))),
            &format!("UQ{bb}.{wsc}: S * ks_{ch} + 1/2 colour ulp (round half up; the add inside the DSP)"),
        );
    }
    b.delay(mul_delay(wsc + 1, bb));
    let intensity_add = if ws > fi {
        // round half up: (S[WS:WS-FI-1] + 1) >> 1 = floor(S*2^FI + 1/2)
        Some(b.add_start(
            "intensity_sum",
            &[Piece::sig("square", ws - fi - 1, fi + 2)],
            &[],
            true,
            fi + 2,
            &format!("UQ1.{}: S to 2^-{} plus one ulp = S + 2^-{} (round half up)", fi + 1, fi + 1, fi + 1),
        ))
    } else {
        let sqr = b.r("square");
        let e = if fi > ws { format!("{{{sqr}, {}}}", lit(fi - ws, 0)) } else { sqr };
        b.wire("intensity", fi + 1, e, &format!("UQ1.{fi}: S exactly (no bits to drop)"));
        None
    };

    b.step("colour results; intensity rounding: carries");
    for ch in CHANNELS {
        let e = b.bits(&format!("color_sum_{ch}"), cpb - 1, wsc);
        b.wire(&format!("spec_{ch}"), bb, e, &format!("UNORM{bb}: S * ks_{ch} rounded half up"));
    }
    b.delay(0.0);
    if let Some(p) = intensity_add {
        b.add_carries(&p);
        if !p.chunks.is_empty() {
            b.step("intensity rounding: select");
        }
        let sum = b.add_finish(p);
        let e = b.bits(&sum, fi + 1, 1);
        b.wire("intensity", fi + 1, e, &format!("UQ1.{fi}: S rounded half up"));
    }
}

/// The seed's Fig. 5 taken literally: every bit kept, a general multiplier for k (34), a
/// separate n*(1 - cos) multiplier (7), a multiplier as squarer (11), three colour
/// multipliers (14-16); six coarse steps.
fn paper(cfg: &Config, w: &Widths, b: &mut Builder) {
    let (f, cb, nb, bb, fi) = (cfg.f(), w.cos_bits, cfg.n_bits(), cfg.b(), cfg.fi());
    let (wb, ws) = (w.bracket_frac_bits, w.square_frac_bits);
    let one = lit(cb, 1u128 << f);

    b.step("clamp, 1 - cos (adder 6), cut-off ROM (10), comparator (12)");
    rom_read(cfg, w, b);
    let g = b.r("cos_g");
    b.wire("cos_clamped", cb, format!("({g} > {one}) ? {one} : {g}"), &format!("UQ1.{f}, <= 1.0"));
    let c = b.r("cos_clamped");
    b.wire("one_minus_cos", cb, format!("{one} - {c}"), &format!("UQ1.{f}: 1 - cos(gamma), exact"));
    let (c, sp) = (b.r("cos_clamped"), b.r("cos_sp"));
    b.wire("done", 1, format!("({c} < {sp})"), "comparator: bracket < 0");
    b.delay(add_delay(cb) * 2.0);

    b.step("deviation n*(1 - cos) (multiplier 7) times k (general multiplier 34), truncation #1");
    let nd_bits = nb + cb;
    let (nn, d) = (b.zext("n", nd_bits), b.zext("one_minus_cos", nd_bits));
    b.wire("n_dev", nd_bits, format!("{nn} * {d}"), &format!("UQ{nb}.{f}: n*(1 - cos), exact (multiplier 7)"));
    let nd = b.zext("n_dev", w.deviation_bits);
    b.wire(
        "deviation_full",
        w.deviation_bits,
        format!("{nd} * {}", lit(w.deviation_bits, cfg.k_code as u128)),
        &format!("UQ.{}: k_q*n*(1 - cos), exact (general multiplier 34)", cfg.kf() + f),
    );
    let dev = b.pieces(&sub_pieces(&[Piece::sig("deviation_full", 0, w.deviation_bits)], w.deviation_shift, wb + 1));
    b.wire("deviation", wb + 1, dev, &format!("UQ1.{wb}: exact below the cut-off (< 2)"));
    b.delay(mul_delay(nb, cb) + mul_delay(nd_bits, bit_length(cfg.k_code as u128)));

    b.step("bracket = 1 - deviation (adder 9), zeroed beyond the cut-off (key block 13)");
    let (dn, dv) = (b.r("done"), b.r("deviation"));
    b.wire("bracket", wb + 1, format!("{dn} ? {} : ({} - {dv})", lit(wb + 1, 0), lit(wb + 1, 1u128 << wb)), &format!("UQ1.{wb}, in [0, 1]"));
    b.delay(add_delay(wb + 1) + LUT_DELAY);

    b.step("square (a general multiplier as squarer 11)");
    let fb = w.full_square_bits();
    let (a1, a2) = (b.zext("bracket", fb), b.zext("bracket", fb));
    b.wire("square_full", fb, format!("{a1} * {a2}"), &format!("UQ2.{}: exact (top bit always 0)", 2 * wb));
    let sq = b.bits("square_full", 2 * wb, w.square_shift);
    b.wire("square", ws + 1, sq, &format!("UQ1.{ws}: S"));
    b.delay(mul_delay(wb + 1, wb + 1));

    b.step("colour multipliers (14-16); intensity rounding");
    let cpb = w.color_product_bits;
    for ch in CHANNELS {
        let (cs, ks) = (b.zext("square", cpb), b.zext(&format!("ks_{ch}"), cpb));
        b.wire(&format!("color_prod_{ch}"), cpb, format!("{cs} * {ks}"), &format!("UQ{bb}.{ws}: S * ks_{ch}, exact"));
    }
    if ws > fi {
        let sqr = b.r("square");
        b.wire("intensity_sum", ws + 1, format!("{sqr} + {}", lit(ws + 1, 1u128 << (ws - fi - 1))), &format!("UQ1.{ws}: S + 2^-{} (round half up)", fi + 1));
    }
    b.delay(mul_delay(ws + 1, bb));

    b.step("colour rounding, final slices");
    for ch in CHANNELS {
        let p = b.r(&format!("color_prod_{ch}"));
        b.wire(&format!("color_sum_{ch}"), cpb, format!("{p} + {}", lit(cpb, 1u128 << (ws - 1))), "+ 1/2 colour ulp (round half up)");
        let s = b.bits(&format!("color_sum_{ch}"), cpb - 1, ws);
        b.wire(&format!("spec_{ch}"), bb, s, &format!("UNORM{bb}"));
    }
    let e = if ws > fi {
        b.bits("intensity_sum", ws, ws - fi)
    } else {
        let sqr = b.r("square");
        if fi > ws {
            format!("{{{sqr}, {}}}", lit(fi - ws, 0))
        } else {
            sqr
        }
    };
    b.wire("intensity", fi + 1, e, &format!("UQ1.{fi}"));
    b.delay(add_delay(cpb));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_cover_the_width_in_balanced_pieces() {
        for w in 1..80 {
            let c = chunks(w, CHUNK_BITS);
            assert_eq!(c.iter().map(|x| x.1).sum::<u32>(), w);
            assert!(c.iter().all(|x| x.1 <= CHUNK_BITS && x.1 >= 1));
            assert!(c.windows(2).all(|p| p[0].0 + p[0].1 == p[1].0));
            assert_eq!(c.len() as u32, w.div_ceil(CHUNK_BITS));
        }
    }

    #[test]
    fn sub_pieces_pads_with_zeros() {
        let p = [Piece::sig("a", 2, 3), Piece::Const { value: 0b101, width: 3 }];
        let s = sub_pieces(&p, 1, 7);
        let mut b = Builder::new(&[("a", 8)], &[]);
        b.step("t");
        assert_eq!(b.pieces(&s), "{2'h0, 3'h5, a[4:3]}");
    }

    #[test]
    fn liveness_and_unused_bits() {
        let mut b = Builder::new(&[("x", 8)], &[1]);
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
        assert_eq!(d.unused.as_deref(), Some("^{x_c1[7:1]}"));
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
