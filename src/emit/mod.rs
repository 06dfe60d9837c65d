//! Stage 3b/4: config + widths → template context → emitted files, written atomically.
//!
//! Rust decides every width, literal and register placement here; `templates/unit.v`
//! holds only the Verilog's shape.

use crate::bits::{lit, mask};
use crate::config::{Params, RomStyle, Target};
use crate::datapath::{self, DelayLine, Waiting, Wire};
use crate::plan::Plan;
use crate::ports::Port;
use crate::rom::{self, RomFormat};
use askama::Template;
use serde::Serialize;

pub(crate) use crate::names::{SIM_DIR, VERSION};

mod cuts;
mod python;
#[cfg(test)]
mod tests;
mod text;

use cuts::*;
mod digest;
pub use digest::rtl_digest;
pub(crate) use text::*;

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
fn block_slices(
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
fn registered_cuts_text(cuts: &[u32]) -> String {
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
fn with_lemma_port(cfg: &crate::config::Config, mut lines: Vec<String>) -> Vec<String> {
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
fn fill_lines<'a>(
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
fn step_items(s: &datapath::Step, reads: Vec<(usize, ReadView)>) -> Vec<StepItem> {
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

#[derive(Template)]
#[template(path = "unit.core")]
struct CoreTemplate<'a> {
    top: &'a str,
    /// the sim targets' testbench, its module and the vectors it reads
    testbench: String,
    tb_top: String,
    tb_vectors: String,
    /// `<top>.sdc` (and `<top>.lpf` on ECP5)
    constraint_files: Vec<String>,
    clock_mhz: String,
    version: &'a str,
    name: String,
    params: String,
    description: String,
    table_files: Vec<String>,
    /// RTL files beside `<top>.v` (the ECP5 product module)
    rtl_files: Vec<String>,
    /// the simulation models of the ECP5 primitives, for lint and simulation only
    sim_models: Vec<String>,
    /// the family FuseSoC's `synth` target maps for (`ecp5`: yosys alone; else the icestorm flow)
    arch: &'a str,
    /// the FuseSoC flags under which a dependent core gets the simulation models
    sim_flags: Vec<&'static str>,
}

/// The FuseSoC flags under which a core that depends on a unit gets its simulation models: a
/// target named `sim`/`lint` (the flow API sets `target_<name>`), or a simulator as the tool.
const SIM_FLAGS: [&str; 7] = [
    "target_sim",
    "target_lint",
    "tool_icarus",
    "tool_verilator",
    "tool_modelsim",
    "tool_questa",
    "tool_xsim",
];

/// The clock constraint `<top>.sdc` (every unit) or `<top>.lpf` (ECP5).
#[derive(Template)]
#[template(path = "unit.sdc")]
struct SdcTemplate<'a> {
    top: &'a str,
    version: &'a str,
    params: String,
    /// the clock port (`clk`, `aclk`); none: a combinational unit
    clock: Option<&'a str>,
    mhz: String,
    /// ns, three decimals
    period: String,
}

#[derive(Template)]
#[template(path = "unit.lpf")]
struct LpfTemplate<'a> {
    top: &'a str,
    version: &'a str,
    params: String,
    clock: Option<&'a str>,
    mhz: String,
}

/// The clock port of a unit (none when combinational).
pub(crate) fn clock_port(cfg: &crate::config::Config) -> Option<&'static str> {
    cfg.ports("")
        .iter()
        .map(|p| p.name)
        .find(|n| *n == "clk" || *n == "aclk")
}

/// `<top>.sdc`, and `<top>.lpf` for ECP5, at the configuration's clock, on the clock port of
/// the user's top when given (`clock_port`), else on the unit's own.
fn constraint_files(cfg: &crate::config::Config) -> Vec<(String, String)> {
    let top = cfg.top();
    let mhz = crate::family::clock_mhz(cfg);
    let mhz_text = format!("{mhz}");
    let clock = clock_port(cfg).map(|own| cfg.params.clock_port.as_deref().unwrap_or(own));
    let sdc = SdcTemplate {
        top,
        version: VERSION,
        params: cfg.describe(),
        clock,
        mhz: mhz_text.clone(),
        period: format!("{:.3}", 1000.0 / mhz),
    };
    let mut files = vec![(
        format!("{top}.sdc"),
        sdc.render().expect("sdc renders") + "\n",
    )];
    if crate::family::of(cfg.target()).lpf_constraints() {
        let lpf = LpfTemplate {
            top,
            version: VERSION,
            params: cfg.describe(),
            clock,
            mhz: mhz_text,
        };
        files.push((
            format!("{top}.lpf"),
            lpf.render().expect("lpf renders") + "\n",
        ));
    }
    files.extend(crate::family::of(cfg.target()).constraint_files(top));
    files
}

/// The output buffer `<top>_out_buffer` of a `ready`/`axis` unit.
#[derive(Template)]
#[template(path = "out_buffer.v")]
struct OutBufferTemplate<'a> {
    top: &'a str,
    version: &'a str,
}

/// The delay line's memory module `<top>_delay_ram` (a word delayed CUTS clocks in RAM).
#[derive(Template)]
#[template(path = "delay_ram.v")]
struct DelayRamTemplate<'a> {
    top: &'a str,
    version: &'a str,
    /// what the memory is, in words
    memory: &'a str,
    /// the memory's attributes after `no_rw_check`
    ram_style: &'a str,
}

/// The (word bits, cuts) of every delay line's tail in RAM (`<top>_delay_ram`), the datapath's
/// and the tag's, each pair once, in order.
pub fn delay_rams(plan: &Plan) -> Vec<(u32, u32)> {
    let mut out: Vec<(u32, u32)> = Vec::new();
    for p in delay_ram_tails(plan) {
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

/// The (word bits, cuts) of every delay line's tail in RAM, one entry a tail (an instance of
/// `<top>_delay_ram` each), in order.
pub fn delay_ram_tails(plan: &Plan) -> Vec<(u32, u32)> {
    let lines = cut_list(&plan.datapath, plan.cfg.target())
        .into_iter()
        .flat_map(|c| c.lines)
        .chain(crate::interface::tag_line(plan));
    lines
        .filter_map(|l| l.memory_tail().map(|(_, cuts)| (l.word(), cuts as u32)))
        .collect()
}

/// The FuseSoC VLNV of a configuration: `specgen:specular:<top>-<digest>:<version>`, the digest
/// (8 hex digits of SHA-256) taken over every parameter that shapes the files, so two
/// configurations never replace each other in one cores-root, and one configuration always
/// gets the same name.
pub fn core_name(cfg: &crate::config::Config) -> String {
    let digest = sha256_hex(
        format!(
            "{} rom_style={} top={}",
            cfg.describe(),
            cfg.params.rom_style.name(),
            cfg.top()
        )
        .as_bytes(),
    );
    format!("specgen:specular:{}-{}:{VERSION}", cfg.top(), &digest[..8])
}

/// Where each field sits in the `axis` unit's `tdata`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Tdata {
    pub(crate) s_axis: Vec<crate::ports::Field>,
    pub(crate) m_axis: Vec<crate::ports::Field>,
}

#[derive(Debug, Clone, Serialize)]
pub(crate) struct FileEntry {
    pub(crate) name: String,
    pub(crate) sha256: String,
}

/// The manifest `<top>.json` (SPEC §4): parameters at top level under their SPEC names.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Manifest<'a> {
    pub(crate) generator: &'static str,
    pub(crate) version: &'static str,
    /// `Config::fingerprint`: the unit's header repeats it
    pub(crate) fingerprint: String,
    #[serde(flatten)]
    pub(crate) params: &'a Params,
    pub(crate) k_code: u64,
    pub(crate) latency: u32,
    pub(crate) ports: Vec<Port>,
    /// The fields packed into `s_axis_tdata` and `m_axis_tdata` (the `axis` interface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) tdata: Option<Tdata>,
    /// The model's own widths and table sizes.
    pub(crate) internal_widths: serde_json::Value,
    /// The cuts that hold a pipeline register (1-based step numbers).
    pub(crate) registered_cuts: &'a [u32],
    /// The hard products whose block has no output register (SPEC §7), each with why; empty:
    /// every block has it, and `synth` fails naming any that does not.
    pub(crate) unregistered_products: Vec<Unregistered>,
    /// `Plan::stage_delay`: the slowest stretch between registers, in the delay estimates'
    /// units (what `--target-mhz`'s delay model reads)
    pub(crate) stage_delay_estimate: f64,
    /// `Plan::stage_delay_mean`
    pub(crate) stage_delay_mean: f64,
    /// `timing::predicted_fmax`: the delay model's clock for this unit on its family's part
    /// (null for a datapath without calibration)
    pub(crate) predicted_fmax_mhz: Option<f64>,
    /// `max |intensity/2^FI − c^n|` over the inputs of `blinn_error_method` (SPEC §6).
    pub(crate) blinn_error_max: f64,
    pub(crate) blinn_error_mean: f64,
    pub(crate) blinn_error_method: String,
    /// the same at the pixel: over every real cosine in [0, 1], rounded to F bits before the
    /// unit reads it (SPEC §6)
    pub(crate) pixel_error_max: f64,
    pub(crate) pixel_error_mean: f64,
    pub(crate) pixel_error_rms: f64,
    pub(crate) pixel_error_method: String,
    pub(crate) files: Vec<FileEntry>,
}

/// A product whose block has no output register, and why.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Unregistered {
    pub(crate) name: String,
    pub(crate) why: String,
}

/// The hard products of the plan's unit whose block has no output register, each with why
/// (empty: every block has it).
pub fn unregistered(plan: &Plan) -> Vec<(String, String)> {
    unregistered_products(
        &plan.datapath,
        &cut_list(&plan.datapath, plan.cfg.target()),
        plan.cfg.target(),
    )
}

fn sha256_hex(bytes: &[u8]) -> String {
    crate::bits::sha256_hex(bytes, 32)
}

/// A unit's sources: its Verilog (the top, then the modules it instantiates), the simulation
/// models of its family's blocks (under `sim/`) and its tables' files, by name.
pub struct Sources {
    pub top: (String, String),
    pub rtl: Vec<(String, String)>,
    pub sim_models: Vec<(String, String)>,
    pub tables: Vec<crate::table::Table>,
}

/// The unit's sources alone (no manifest, testbench or vectors): what its RTL digest covers.
pub fn sources(plan: &Plan) -> Sources {
    let cfg = &plan.cfg;
    let top = cfg.top();
    let mut verilog =
        fold_long_lines(&unit_template(plan).render().expect("unit template renders"));
    verilog.push('\n');
    let dp = &plan.datapath;
    let tables: Vec<_> = match cfg.params.rom_style {
        RomStyle::File => dp
            .tables
            .iter()
            .enumerate()
            .filter(|(i, _)| !block_table(dp, *i))
            .map(|(_, t)| t.clone())
            .collect(),
        RomStyle::Case | RomStyle::Logic => Vec::new(),
    };
    // the ECP5 primitives' wrappers (RTL) and their simulation models (never synthesized)
    let (mut rtl_files, mut sim_models) = (Vec::new(), Vec::new());
    if cfg.interface().handshake() {
        let text = OutBufferTemplate {
            top,
            version: VERSION,
        }
        .render()
        .expect("buffer template renders")
            + "\n";
        rtl_files.push((format!("{top}_out_buffer.v"), text));
    }
    let blocks = crate::family::of(cfg.target()).blocks();
    if let Some(b) = blocks.filter(|_| dp.has_dsp_blocks()) {
        rtl_files.push((format!("{top}_mult18x18.v"), (b.dsp_module)(top)));
        sim_models.push((
            format!("{SIM_DIR}/{top}{}", b.dsp_model_suffix),
            (b.dsp_model)(),
        ));
    }
    if !delay_rams(plan).is_empty() {
        let distributed = crate::family::of(cfg.target()).distributed_ram();
        let ram_style = if distributed {
            ", ram_style = \"distributed\""
        } else {
            ""
        };
        let memory = datapath::memory_kind(distributed);
        let text = DelayRamTemplate {
            top,
            version: VERSION,
            memory,
            ram_style,
        }
        .render()
        .expect("delay_ram template renders")
            + "\n";
        rtl_files.push((format!("{top}_delay_ram.v"), text));
    }
    if let Some(b) = blocks.filter(|_| dp.has_block_rams()) {
        rtl_files.push((format!("{top}_rom1k18.v"), (b.bram_module)(top)));
        sim_models.push((
            format!("{SIM_DIR}/{top}{}", b.bram_model_suffix),
            (b.bram_model)(),
        ));
    }
    // the primitives as black boxes, for a synthesis tool that lacks them
    if let Some((suffix, text)) = blocks
        .filter(|_| dp.has_dsp_blocks() || dp.has_block_rams())
        .and_then(|b| b.boxes)
    {
        rtl_files.push((format!("{top}{suffix}"), text(top)));
    }
    Sources {
        top: (format!("{top}.v"), verilog),
        rtl: rtl_files,
        sim_models,
        tables,
    }
}

/// The files [`sources`] names, in the order `generate` lists them: the top, the RTL modules,
/// the simulation models, the tables.
pub fn source_files(plan: &Plan) -> Vec<(String, Vec<u8>)> {
    let s = sources(plan);
    let mut files = vec![(s.top.0, s.top.1.into_bytes())];
    files.extend(
        s.rtl
            .into_iter()
            .chain(s.sim_models)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    for t in &s.tables {
        files.push((
            t.file(plan.cfg.top()),
            rom::render_table(&plan.cfg, t, RomFormat::Hex).into_bytes(),
        ));
    }
    files
}

/// Every file of a `generate` run, in memory: (file name, contents).
pub fn generate_files(plan: &Plan) -> Vec<(String, Vec<u8>)> {
    let cfg = &plan.cfg;
    let top = cfg.top();
    let unit = plan.model.unit();
    let Sources {
        top: (top_name, verilog),
        rtl: rtl_files,
        sim_models,
        tables,
    } = sources(plan);
    let description = unit.describe().summary;
    let mut files = vec![(top_name, verilog.into_bytes())];
    let constraints = constraint_files(cfg);
    let testbench = crate::vectors::testbench_files(&plan.model);
    let core = CoreTemplate {
        testbench: testbench[0].0.clone(),
        tb_top: format!("{top}_tb"),
        tb_vectors: testbench[1].0.clone(),
        top,
        constraint_files: constraints.iter().map(|(n, _)| n.clone()).collect(),
        clock_mhz: format!("{}", crate::family::clock_mhz(cfg)),
        version: VERSION,
        name: core_name(cfg),
        params: cfg.describe(),
        description: format!("{description}, {}-cycle latency", cfg.latency()),
        table_files: tables.iter().map(|t| t.file(top)).collect(),
        rtl_files: rtl_files.iter().map(|(n, _)| n.clone()).collect(),
        sim_models: sim_models.iter().map(|(n, _)| n.clone()).collect(),
        arch: crate::family::of(cfg.target()).fusesoc_arch(),
        sim_flags: if sim_models.is_empty() {
            Vec::new()
        } else {
            SIM_FLAGS.to_vec()
        },
    }
    .render()
    .expect("core template renders")
        + "\n";
    files.extend(
        rtl_files
            .into_iter()
            .chain(sim_models)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    for t in &tables {
        files.push((
            t.file(top),
            rom::render_table(cfg, t, RomFormat::Hex).into_bytes(),
        ));
    }
    files.extend(
        constraints
            .into_iter()
            .chain(testbench)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    files.push((format!("{top}.core"), core.into_bytes()));
    // the unit in the Python HDLs (Amaranth, LiteX): what they add to a build is its RTL and
    // tables, never the simulation models or the testbench
    let synthesized: Vec<String> = files
        .iter()
        .map(|(n, _)| n.clone())
        .filter(|n| {
            (n.ends_with(".v") || n.ends_with(".hex"))
                && !n.starts_with(SIM_DIR)
                && !n.ends_with("_vectors.hex")
        })
        .collect();
    files.extend(
        python::python_files(plan, synthesized)
            .into_iter()
            .map(|(n, t)| (n, t.into_bytes())),
    );
    let fidelity = plan.model.fidelity();
    let manifest = Manifest {
        generator: "specgen",
        version: VERSION,
        fingerprint: cfg.fingerprint(),
        // the reset's polarity stated always, the interface's own included
        params: &Params {
            reset: Some(cfg.reset()),
            ..cfg.params.clone()
        },
        k_code: cfg.k_code,
        latency: cfg.latency(),
        ports: cfg.ports(""),
        tdata: (cfg.interface() == crate::config::Interface::Axis).then(|| {
            let (s_axis, _, m_axis, _) = crate::ports::tdata_fields(cfg.port_widths());
            Tdata { s_axis, m_axis }
        }),
        internal_widths: unit.widths(),
        registered_cuts: &plan.registered_cuts,
        unregistered_products: unregistered(plan)
            .into_iter()
            .map(|(name, why)| Unregistered { name, why })
            .collect(),
        stage_delay_estimate: (plan.stage_delay() * 100.0).round() / 100.0,
        stage_delay_mean: (plan.stage_delay_mean() * 100.0).round() / 100.0,
        predicted_fmax_mhz: crate::timing::predicted_fmax(plan).map(|f| (f * 10.0).round() / 10.0),
        blinn_error_max: fidelity.max,
        blinn_error_mean: fidelity.mean,
        blinn_error_method: fidelity.method(),
        pixel_error_max: fidelity.pixel.max,
        pixel_error_mean: fidelity.pixel.mean,
        pixel_error_rms: fidelity.pixel.rms,
        pixel_error_method: fidelity.pixel_method(),
        files: files
            .iter()
            .map(|(name, bytes)| FileEntry {
                name: name.clone(),
                sha256: sha256_hex(bytes),
            })
            .collect(),
    };
    // only the model's own parameters (MODEL_KEYS): a reader branches on `model`
    let mut value = serde_json::to_value(&manifest).expect("manifest serialises");
    cfg.model().keep_own_keys(&mut value);
    let mut json = serde_json::to_string_pretty(&value).expect("manifest serialises");
    json.push('\n');
    files.push((format!("{top}.json"), json.into_bytes()));
    files
}
