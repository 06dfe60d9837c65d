//! The unit's module as its template reads it: the cuts, tables, reads, steps and blocks of the
//! plan, its ports and header lines.

use super::*;

/// A signal registered at one cut only: `reg x_cK; x_cK <= source`.
pub(crate) struct CutSignal {
    pub(crate) name: String,
    pub(crate) width: u32,
    /// a register a multiplier reads ([`datapath::Datapath::read_by_block`]): out of the DSP block
    pub(crate) keep: bool,
    /// a copy of a register ([`datapath::Datapath::copies`]): its flip-flop kept too (`(* keep *)`
    /// on the always block), which yosys's opt_merge honours where a kept name alone does not
    /// (the copies merged into one, and their readers shared their logic again)
    pub(crate) copy: bool,
    /// the expression the cut takes it from (`x_sK` computed in step K, a port, a block's output)
    pub(crate) source: String,
}

pub(crate) struct Cut {
    pub(crate) index: usize,
    pub(crate) registered: bool,
    pub(crate) signals: Vec<CutSignal>,
    /// the delay lines that start here
    pub(crate) lines: Vec<DelayLine>,
}

impl Cut {
    /// Every register that starts here: a single register with the always block that loads
    /// it, one line; or a delay line, its registers declared in one statement and loaded in
    /// one, each from the one before.
    pub fn lines(&self, top: &str) -> Vec<String> {
        let mut out = Vec::new();
        let range = |w: u32| {
            if w == 1 {
                "     ".to_string()
            } else {
                format!("[{}:0]", w - 1)
            }
        };
        for s in &self.signals {
            let reg = format!("{}_c{}", s.name, self.index);
            let keep = if s.keep { "(* keep *) " } else { "" };
            let cell = if s.copy { "(* keep *) " } else { "" };
            out.push(format!(
                "{keep}reg  {} {reg};   {cell}always @(posedge clk) {reg} <= {};",
                range(s.width),
                s.source
            ));
        }
        for l in &self.lines {
            out.extend(l.lines(top));
        }
        out
    }

    /// Whether anything is registered first here.
    pub fn is_empty(&self) -> bool {
        self.signals.is_empty() && self.lines.is_empty()
    }
}

pub(crate) struct RomEntry {
    pub(crate) index: String,
    pub(crate) value: String,
}

/// A table read with `$readmemh` (declared once at the top of the module).
pub(crate) struct TableView {
    pub(crate) name: String,
    pub(crate) param: String,
    pub(crate) file: String,
    pub(crate) what: String,
    pub(crate) width: u32,
    pub(crate) depth: usize,
    /// its last entry, and a value it cannot be (the short-file check)
    pub(crate) last: String,
    pub(crate) not_last: String,
    /// an entry as 64 bits (zero-extended or its low 64), `{i}` the index
    pub(crate) word64: String,
    /// [`Table::checksum`] as a Verilog literal
    pub(crate) checksum: String,
}

/// A table read inside a step: an index into a `$readmemh` memory or an inline `case`.
pub(crate) struct ReadView {
    pub(crate) signal: String,
    pub(crate) width: u32,
    pub(crate) table: String,
    pub(crate) addr: String,
    pub(crate) what: String,
    pub(crate) file: bool,
    pub(crate) zero: String,
    pub(crate) entries: Vec<RomEntry>,
    /// on ECP5 DP16KDs with their registers, one per 18 bits of the word ([`BlockSlice`]), the
    /// address zero-extended to 10 bits, the cut their address registers take
    pub(crate) block: bool,
    pub(crate) slices: Vec<BlockSlice>,
    pub(crate) input_cut: usize,
    /// two banks: the address's low 10 bits (to every DP16KD) and its bank bit
    pub(crate) banked: bool,
    pub(crate) addr_lo: String,
    pub(crate) addr_bank: String,
}

/// The DP16KDs of 18 bits of the word of a registered table read: its instance suffix (none
/// when it is the only one), each bank's contents as `INITVAL_XX` values (one bank per 1024
/// words; two: the address's bit 10 picks, after registers like the block's own), the bits of
/// the word it gives and its unread data bits.
pub(crate) struct BlockSlice {
    pub(crate) suffix: String,
    pub(crate) banks: Vec<Vec<(String, String)>>,
    pub(crate) bits: String,
    pub(crate) unused: u32,
    pub(crate) width: u32,
}

/// The table blocks of a registered read of `t` into `signal`: 18 bits of the word each, low
/// first, each bank's contents as the family's block lays them out (`init`).
pub(super) fn block_slices(
    t: &crate::table::Table,
    signal: &str,
    init: fn(&[u128]) -> Vec<(String, String)>,
) -> Vec<BlockSlice> {
    let b = datapath::DP16KD_BITS;
    let n = t.width.div_ceil(b);
    (0..n)
        .map(|k| {
            let (lo, hi) = (k * b, ((k + 1) * b).min(t.width));
            let words: Vec<u128> = t.words.iter().map(|w| (w >> lo) & mask(hi - lo)).collect();
            let banks = words.chunks(datapath::DP16KD_WORDS).map(init).collect();
            let bits = if n == 1 {
                signal.to_string()
            } else if hi - lo == 1 {
                format!("{signal}[{lo}]")
            } else {
                format!("{signal}[{}:{lo}]", hi - 1)
            };
            BlockSlice {
                suffix: if n == 1 { String::new() } else { k.to_string() },
                banks,
                bits,
                unused: b - (hi - lo),
                width: hi - lo,
            }
        })
        .collect()
}

/// One step of the datapath as the template renders it: its reads and wires, then the cut after it.
pub(crate) struct StepView {
    pub(crate) index: usize,
    pub(crate) title: String,
    /// table reads and wires in definition order
    pub(crate) items: Vec<StepItem>,
    pub(crate) dsps: Vec<DspView>,
    pub(crate) cut: Cut,
}

/// A table read or a wire (its whole statement, comment included, as the RTL shows it).
pub(crate) struct StepItem {
    pub(crate) read: Option<ReadView>,
    pub(crate) wire: Option<String>,
}

/// A product on an ECP5 MULT18X18D with its registers (see `datapath::Builder::product`).
pub(crate) struct DspView {
    /// the product's signal name, and its wire (the DSP's output register: the cut after the step)
    pub(crate) name: String,
    pub(crate) wire: String,
    pub(crate) width: u32,
    /// bits of the 36-bit P above `width`, sent to `unused_<name>_p`
    pub(crate) unused: u32,
    pub(crate) a: String,
    pub(crate) b: String,
    pub(crate) comment: String,
    /// the cut whose place the input registers take
    pub(crate) input_cut: usize,
}

#[derive(Template)]
#[template(path = "unit.v")]
pub(crate) struct UnitTemplate<'a> {
    pub(crate) top: &'a str,
    pub(crate) version: &'a str,
    /// `Config::fingerprint`, repeated from the manifest
    pub(crate) fingerprint: String,
    pub(crate) model: &'a str,
    pub(crate) p: &'a Params,
    pub(crate) param_line: String,
    /// `interface=… tag_bits=… colour=…` when any is not the default
    pub(crate) interface_line: String,
    pub(crate) formula: Vec<String>,
    pub(crate) rounding_text: String,
    pub(crate) datapath_line: String,
    /// the port list (SPEC §2), one declaration a line
    pub(crate) port_lines: Vec<String>,
    pub(crate) cuts_text: String,
    pub(crate) file_tables: Vec<TableView>,
    pub(crate) steps: Vec<StepView>,
    /// registers in the valid pipeline (one a registered cut)
    pub(crate) valid_depth: u32,
    /// what the valid pipeline takes (`in_valid`, or `in_take` behind a handshake)
    pub(crate) valid_source: String,
    /// the header's latency and interface lines, the declarations after the ports, the tag's
    /// delay line, and the outputs (see [`crate::interface`])
    pub(crate) edge_header: Vec<String>,
    pub(crate) prologue: Vec<String>,
    pub(crate) tag_lines: Vec<String>,
    pub(crate) tail: Vec<String>,
    /// the one lint sink for bits no step reads, four a line
    pub(crate) unused: Vec<String>,
    /// products use the family's product module (`<top>_mult18x18`)
    pub(crate) dsp_module: bool,
    /// tables use the family's ROM module (`<top>_rom1k18`)
    pub(crate) bram_module: bool,
    /// the family's blocks as the header names them
    pub(crate) blk: BlockNames,
}

/// The family's hard blocks as the unit's header and comments name them (empty: none).
#[derive(Default)]
pub(crate) struct BlockNames {
    vendor: &'static str,
    family: &'static str,
    dsp: &'static str,
    bram: &'static str,
    dsp_model: &'static str,
    bram_model: &'static str,
    /// the contents parameters' common name (`INITVAL`, `INIT_RAM`)
    init: String,
}

/// "after steps [..]" for the Verilog header: runs of consecutive steps as `a-b`.
pub(super) fn registered_cuts_text(cuts: &[u32]) -> String {
    if cuts.is_empty() {
        return "none".into();
    }
    let mut runs: Vec<(u32, u32)> = Vec::new();
    for &c in cuts {
        match runs.last_mut() {
            Some(r) if r.1 + 1 == c => r.1 = c,
            _ => runs.push((c, c)),
        }
    }
    runs.iter()
        .map(|&(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}-{b}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The module's port declarations, one a line, the comments in one column.
pub(crate) fn port_lines(ports: &[Port]) -> Vec<String> {
    ports
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let range = if p.width == 1 {
                String::new()
            } else {
                format!("[{}:0]", p.width - 1)
            };
            let decl = format!(
                "    {:<6} wire {range:<6} {}{}",
                p.direction,
                p.name,
                if i + 1 < ports.len() { "," } else { "" }
            );
            if p.meaning.is_empty() {
                decl
            } else {
                format!("{decl:<36} // {}", p.meaning)
            }
        })
        .collect()
}

/// A handshake unit's port list with, under `SPECGEN_LEMMAS`, the port checker's state for its
/// lemmas (`specgen prove`; [`crate::interface::CheckerState`]): no flow but the proof sees it.
pub(super) fn with_lemma_port(cfg: &crate::config::Config, mut lines: Vec<String>) -> Vec<String> {
    if cfg.interface().handshake() {
        let w = crate::interface::CheckerState::of(cfg).width();
        lines.push("`ifdef SPECGEN_LEMMAS".into());
        lines.push("    ,".into());
        lines.push("    // formal only (`specgen prove` at the ports): the port checker's state, for the lemmas below".into());
        lines.push(format!("    input  wire [{}:0] f_ports", w - 1));
        lines.push("`endif".into());
    }
    lines
}

/// Joins `items` with `sep` into as few lines as keep each at most `width` characters (an item
/// longer than that has a line of its own): an expression's operands, the lint sink's selects.
pub(super) fn fill_lines<'a>(
    items: impl IntoIterator<Item = &'a str>,
    sep: &str,
    width: usize,
) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for item in items {
        match lines.last_mut() {
            Some(l) if l.chars().count() + sep.chars().count() + item.chars().count() <= width => {
                l.push_str(sep);
                l.push_str(item);
            }
            _ => lines.push(item.to_string()),
        }
    }
    lines
}

/// Builds the template context of the RTL for one configuration (every model).
pub(crate) fn unit_template(plan: &Plan) -> UnitTemplate<'_> {
    let cfg = &plan.cfg;
    let p = &cfg.params;
    let dp = &plan.datapath;
    let blocks = crate::family::of(cfg.target()).blocks();
    let cuts = cut_list(dp, cfg.target());
    let edge = crate::interface::edge(plan, &dp.outputs);
    let line_unread: Vec<String> = cuts
        .iter()
        .flat_map(|c| c.lines.iter().flat_map(DelayLine::unread))
        .collect();
    // each line indented 4 and ended by a comma
    let unused = fill_lines(
        dp.unused
            .iter()
            .chain(&line_unread)
            .chain(&edge.unused)
            .map(String::as_str),
        ", ",
        MAX_LINE - 5,
    );
    let file = p.rom_style == RomStyle::File;
    let file_tables = if file {
        dp.tables
            .iter()
            .enumerate()
            .filter(|(i, _)| !block_table(dp, *i))
            .map(|(_, t)| {
                let last_word = *t.words.last().expect("a table has words");
                TableView {
                    name: t.name.clone(),
                    param: t.param.clone(),
                    file: t.file(cfg.top()),
                    what: t.what.clone(),
                    width: t.width,
                    depth: t.words.len(),
                    last: lit(t.width, last_word),
                    not_last: lit(t.width, !last_word & mask(t.width)),
                    word64: match t.width {
                        w if w < 64 => format!("{{{}, {}[{}_i]}}", lit(64 - w, 0), t.name, t.name),
                        64 => format!("{}[{}_i]", t.name, t.name),
                        _ => format!("{}[{}_i][63:0]", t.name, t.name),
                    },
                    checksum: lit(64, t.checksum() as u128),
                }
            })
            .collect()
    } else {
        Vec::new()
    };
    let mut reads: Vec<Vec<(usize, ReadView)>> = (0..dp.steps.len()).map(|_| Vec::new()).collect();
    for r in &dp.reads {
        let t = &dp.tables[r.table];
        let ab = t.address_bits();
        reads[r.step - 1].push((
            r.position,
            ReadView {
                signal: format!("{}_{}{}", r.signal, if r.block { "c" } else { "s" }, r.step),
                width: t.width,
                table: t.name.clone(),
                addr: if r.block && ab < 10 {
                    format!("{{{}, {}}}", lit(10 - ab, 0), r.addr)
                } else {
                    r.addr.clone()
                },
                what: t.what.clone(),
                file,
                zero: lit(t.width, 0),
                block: r.block,
                slices: match blocks.filter(|_| r.block) {
                    Some(b) => block_slices(t, &format!("{}_c{}", r.signal, r.step), b.bram_init),
                    None => Vec::new(),
                },
                banked: r.block && t.words.len() > datapath::DP16KD_WORDS,
                addr_lo: format!("{}[9:0]", r.addr),
                addr_bank: format!("{}[10]", r.addr),
                input_cut: r.step - 1,
                entries: if file || r.block {
                    Vec::new()
                } else {
                    t.words
                        .iter()
                        .enumerate()
                        .map(|(i, &v)| RomEntry {
                            index: format!("{ab}'d{i}"),
                            value: lit(t.width, v),
                        })
                        .collect()
                },
            },
        ));
    }
    let d = plan.model.unit().describe();
    let mut param_line = format!(
        "{}{}stages={} rounding={}",
        d.param_line,
        if d.param_line.is_empty() { "" } else { " " },
        p.stages,
        p.rounding.name()
    );
    if !dp.tables.is_empty() {
        param_line.push_str(&format!(" rom_style={}", p.rom_style.name()));
    }
    if p.fabric_registers {
        param_line.push_str(" fabric_registers");
    }
    let interface_line = cfg.interface_words().trim_start().to_string();
    let ports = cfg.ports(d.done_meaning);
    UnitTemplate {
        top: cfg.top(),
        version: VERSION,
        fingerprint: cfg.fingerprint(),
        model: cfg.model().name(),
        p,
        param_line,
        interface_line,
        formula: d.formula,
        rounding_text: d.rounding,
        datapath_line: d.datapath,
        port_lines: with_lemma_port(cfg, port_lines(&ports)),
        cuts_text: registered_cuts_text(&plan.registered_cuts),
        file_tables,
        valid_depth: plan.registered_cuts.len() as u32,
        valid_source: edge.valid_source,
        edge_header: edge.header,
        prologue: edge.prologue,
        tag_lines: edge.tag,
        tail: edge.tail,
        unused,
        steps: dp
            .steps
            .iter()
            .zip(cuts)
            .zip(reads)
            .map(|((s, cut), reads)| StepView {
                index: s.index,
                title: s.title.clone(),
                items: step_items(s, reads),
                dsps: s
                    .dsps
                    .iter()
                    .map(|d| DspView {
                        name: d.name.clone(),
                        wire: format!("{}_c{}", d.name, s.index),
                        width: d.width,
                        unused: 2 * datapath::ECP5_DSP_BITS - d.width,
                        a: d.a.clone(),
                        b: d.b.clone(),
                        comment: d.comment.clone(),
                        input_cut: s.index - 1,
                    })
                    .collect(),
                cut,
            })
            .collect(),
        dsp_module: dp.has_dsp_blocks(),
        bram_module: dp.has_block_rams(),
        blk: blocks.map_or_else(BlockNames::default, |b| BlockNames {
            vendor: b.vendor,
            family: b.family,
            dsp: b.dsp,
            bram: b.bram,
            dsp_model: b.dsp_model_suffix,
            bram_model: b.bram_model_suffix,
            init: (b.bram_init)(&[]).first().map_or(String::new(), |(k, _)| {
                k.trim_end_matches(|c: char| c.is_ascii_hexdigit())
                    .trim_end_matches('_')
                    .to_string()
            }),
        }),
    }
}

/// A step's reads and wires in definition order (each read where its position says).
pub(super) fn step_items(s: &datapath::Step, reads: Vec<(usize, ReadView)>) -> Vec<StepItem> {
    let mut reads = reads.into_iter().peekable();
    let mut items = Vec::new();
    for (i, x) in s.wires.iter().enumerate() {
        while let Some((_, r)) = reads.next_if(|(at, _)| *at <= i) {
            items.push(StepItem {
                read: Some(r),
                wire: None,
            });
        }
        items.push(StepItem {
            read: None,
            wire: Some(wire_statement(x, s.index)),
        });
    }
    items.extend(reads.map(|(_, r)| StepItem {
        read: Some(r),
        wire: None,
    }));
    items
}
