//! Signals that wait through several registered cuts: one shifted vector, its words named
//! where read, its long unread stretches in block RAM where the family has it.

use super::*;

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

/// A tail in LUT RAM spans at most this many cuts: its memory then holds 32 words (the read
/// register and the last flip-flop take two cuts, and a word is read one edge before it is
/// written over), two TRELLIS_DPR16X4 and one mux level (PFUMX) deep; 64 words are four and
/// two LUT levels, 4.9 ns from the read address (blinn's colours at 37 ECP5 stages held it
/// at 204 MHz). The cuts before it are flip-flops.
pub(crate) const DISTRIBUTED_TAIL_MAX_CUTS: usize = 33;

impl DelayLine {
    /// The bits of a word (every member's).
    pub(crate) fn word(&self) -> u32 {
        self.members.iter().map(|m| m.width).sum()
    }

    /// Where its unread tail starts and how long it is, when that tail waits in block RAM: the
    /// words after the last one read before the end (or all of them) are never named, so the
    /// last word is the word before the tail (or the sources) delayed by the tail's cuts, and
    /// `(shift words kept, tail cuts)` says how. `None`: every word is a register.
    pub fn memory_tail(&self) -> Option<(usize, usize)> {
        let d = self.cuts.len();
        let read_before_end = (0..d - 1)
            .rev()
            .find(|&k| self.members.iter().any(|m| m.read[k] != 0));
        let mut kept = read_before_end.map_or(0, |r| r + 1);
        if self.distributed && d - kept > DISTRIBUTED_TAIL_MAX_CUTS {
            kept = d - DISTRIBUTED_TAIL_MAX_CUTS;
        }
        let tail = d - kept;
        (self.memory
            && tail >= MEMORY_TAIL_MIN_CUTS
            && self.word() * tail as u32 >= MEMORY_TAIL_MIN_BITS)
            .then_some((kept, tail))
    }

    /// Its Verilog: the vector and the statement that shifts it, then the words read, named
    /// (one statement per width). A tail in block RAM ([`DelayLine::memory_tail`]) follows the
    /// vector: an instance of `<top>_delay_ram`, its output the line's last word.
    pub fn lines(&self, top: &str) -> Vec<String> {
        let word = self.word();
        let line = format!("{}_line", self.name);
        let sources: Vec<&str> = self
            .members
            .iter()
            .rev()
            .map(|m| m.source.as_str())
            .collect();
        let joined = if sources.len() == 1 {
            sources[0].to_string()
        } else {
            format!("{{{}}}", sources.join(", "))
        };
        let tail = self.memory_tail();
        // the words in the shift vector (none when the whole line waits in block RAM)
        let d = tail.map_or(self.cuts.len(), |(kept, _)| kept);
        let mut out = Vec::new();
        if d > 0 {
            let shifted = if d == 1 {
                joined.clone()
            } else {
                format!(
                    "{{{line}[{}:0], {}}}",
                    word * (d as u32 - 1) - 1,
                    sources.join(", ")
                )
            };
            out.push(format!(
                "reg  [{}:0] {line};   always @(posedge clk) {line} <= {shifted};",
                word * d as u32 - 1
            ));
        }
        if let Some((kept, cuts)) = tail {
            out.extend(self.memory_lines(top, &line, word, kept, cuts, &joined));
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
                // the last word of a tail in block RAM is `<line>_out`
                let (vector, lo) = if k >= d {
                    (format!("{line}_out"), offset)
                } else {
                    (line.clone(), word * k as u32 + offset)
                };
                let select = if m.width == 1 {
                    format!("[{lo}]")
                } else {
                    format!("[{}:{lo}]", lo + m.width - 1)
                };
                let tap = format!("{}_c{cut} = {vector}{select}", m.name);
                match by_width.iter_mut().find(|x| x.0 == m.width) {
                    Some(x) => x.1.push(tap),
                    None => by_width.push((m.width, vec![tap])),
                }
            }
            offset += m.width;
        }
        for (w, taps) in by_width {
            let range = if w == 1 {
                "     ".to_string()
            } else {
                format!("[{}:0]", w - 1)
            };
            out.push(format!("wire {range} {};", taps.join(", ")));
        }
        out
    }

    /// The tail in block RAM: `cuts` cycles from the word before it (`kept` words into the
    /// vector; none: the sources) to `<line>_out`, in an instance `<line>_ram` of
    /// `<top>_delay_ram` (`templates/delay_ram.v`: `cuts - 1` clocks in the memory with its read
    /// register, the last in a flip-flop, so the memory's output meets only a flip-flop).
    pub(super) fn memory_lines(
        &self,
        top: &str,
        line: &str,
        word: u32,
        kept: usize,
        cuts: usize,
        sources: &str,
    ) -> Vec<String> {
        let input = if kept == 0 {
            sources.to_string()
        } else {
            format!(
                "{line}[{}:{}]",
                word * kept as u32 - 1,
                word * (kept as u32 - 1)
            )
        };
        let names: Vec<&str> = self.members.iter().map(|m| m.name.as_str()).collect();
        let memory = memory_kind(self.distributed);
        vec![
            format!("// {} wait {cuts} more cuts: {} clocks in {memory} (with its read register), one in", names.join(", "), cuts - 1),
            format!("// a flip-flop after it ({top}_delay_ram), so the memory's output meets only a flip-flop"),
            format!("wire [{}:0] {line}_out;", word - 1),
            format!("{top}_delay_ram #(.WIDTH({word}), .CUTS({cuts})) {line}_ram (.clk(clk), .d({input}), .q({line}_out));"),
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
                    out.extend(bit_ranges(
                        &format!("{}_c{cut}", m.name),
                        m.width,
                        mask(m.width) & !m.read[k],
                    ));
                }
            }
        }
        out
    }
}

/// What a delay line's tail waits in, in words: LUT RAM where the family's delay lines are
/// distributed (the ECP5), else block RAM.
pub(crate) fn memory_kind(distributed: bool) -> &'static str {
    if distributed {
        "LUT RAM"
    } else {
        "block RAM"
    }
}

/// The name under which a signal defined in step `def` (0: an input port) is seen in step
/// `at`: its own wire in its own step, else the last register holding it, else its wire.
pub(crate) fn visible(registered: &[u32], name: &str, def: usize, at: usize) -> String {
    if def == at {
        return format!("{name}_s{at}");
    }
    match registered
        .iter()
        .copied()
        .filter(|&r| r as usize >= def && (r as usize) < at)
        .max()
    {
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
pub(super) fn chunks(width: u32, chunk_bits: u32) -> Vec<(u32, u32)> {
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
