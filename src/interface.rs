//! The unit's edge around its datapath (SPEC §7): the handshake, the tag beside each pixel,
//! the material registers of a static colour, and the `axis` names — rendered as the lines
//! `templates/unit.v` places around the steps. One place for all of them, so every model gets
//! every interface from the same text.
//!
//! - `valid`: the pipeline's `valid_line` takes `in_valid`; outputs are assigned from the last
//!   step. The default unit's text is exactly what it was before this module existed.
//! - `ready`/`axis`: the pipeline takes `in_take` (`in_valid && in_ready`) and its results go
//!   to `<top>_out_buffer` (`templates/out_buffer.v`): credits reserve a place there for every
//!   pixel taken, so the pipeline itself never stalls and its registers need no enable.
//! - a tag (`--tag-bits W`) is one delay line beside `valid_line`, into the buffer with its
//!   result.
//! - a static colour: three registers loaded by `ks_load`; the datapath reads them at every step
//!   (`datapath::Builder::hold`), so no cut carries a colour.

use crate::config::{Colour, Config, Interface, BUFFER_LATENCY};
use crate::datapath::{DelayLine, Waiting};
use crate::plan::Plan;
use crate::ports::{self, Field};

/// Places of the output buffer for a pipeline of `stages`: its latency + 7 (the buffer's three
/// cycles and the four of the credit loop: `took`, `taken`, `over_credits`, `in_ready`), so a stream at
/// full rate never finds `in_ready` low. Exactly as many as that: each place costs a bit of
/// the buffer's occupancy thermometer (`templates/out_buffer.v`).
pub fn places_for(stages: u32) -> u64 {
    (stages + BUFFER_LATENCY + 4) as u64
}

/// Address bits of the buffer's memory: its pointers step through the 2^bits - 1 states of a
/// linear feedback shift register ([`lfsr_taps`]), at least one per place.
pub fn buffer_depth_log2(stages: u32) -> u32 {
    (places_for(stages) + 1).next_power_of_two().trailing_zeros().max(3)
}

/// The taps of a maximal-length XNOR linear feedback shift register of `bits` bits (3..=16),
/// bit k - 1 for tap k, from Xilinx XAPP052 (table 3): shifting left with the XNOR of the taps
/// into bit 0, it goes through every state but all ones.
pub fn lfsr_taps(bits: u32) -> u32 {
    let taps: &[u32] = match bits {
        3 => &[3, 2],
        4 => &[4, 3],
        5 => &[5, 3],
        6 => &[6, 5],
        7 => &[7, 6],
        8 => &[8, 6, 5, 4],
        9 => &[9, 5],
        10 => &[10, 7],
        11 => &[11, 9],
        12 => &[12, 6, 4, 1],
        13 => &[13, 4, 3, 1],
        14 => &[14, 5, 3, 1],
        15 => &[15, 14],
        16 => &[16, 15, 13, 4],
        _ => panic!("no LFSR taps for {bits} bits"),
    };
    taps.iter().map(|t| 1 << (t - 1)).sum()
}

/// The places of the `ready`/`axis` output buffer (0 without a handshake).
pub fn buffer_places(cfg: &Config) -> u64 {
    if cfg.interface().handshake() {
        places_for(cfg.stages())
    } else {
        0
    }
}

/// The port checker's state as `specgen prove` hands it to a handshake unit's lemmas: the port
/// `f_ports` (only under `SPECGEN_LEMMAS`), its fields from bit 0 up: the pixels inside
/// (`count` bits), whether one is followed, its edges since taken (`age` bits, stopping at the
/// latency: in the buffer), the results to leave before it (`count`), its carried word (`word`:
/// tag and tlast, 1 bit without), the edges a result has been owed (8), the edges in_ready
/// has been low to a consumer ready at each (8), and with `prove --datapath` whether the
/// followed pixel's result is known and what it is (the `valid` twin's, `payload` bits:
/// {intensity, spec_r, spec_g, spec_b, done}; 0 without). The checker packs
/// it (`templates/prove_port_checker.v`), the unit unpacks it: both from this one layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CheckerState {
    pub count: u32,
    pub age: u32,
    pub word: u32,
    /// a result's bits, {intensity, spec_r, spec_g, spec_b, done}
    pub payload: u32,
}

impl CheckerState {
    pub fn of(cfg: &Config) -> CheckerState {
        let places = buffer_places(cfg);
        CheckerState {
            count: 64 - places.leading_zeros() + 1,
            age: (32 - cfg.latency().leading_zeros()).max(1),
            word: cfg.carried_tag_bits().max(1),
            payload: (cfg.fi() + 1) + 3 * cfg.b() + 1,
        }
    }

    /// Bits of `f_ports`.
    pub fn width(&self) -> u32 {
        2 * self.count + 1 + self.age + self.word + 24 + 1 + self.payload
    }

    /// Each field's (name, lowest bit, width), from bit 0 up.
    pub fn fields(&self) -> [(&'static str, u32, u32); 10] {
        let (c, a, w) = (self.count, self.age, self.word);
        let word = 2 * c + 1 + a;
        let check = word + w + 24;
        [
            ("inside", 0, c),
            ("following", c, 1),
            ("age", c + 1, a),
            ("rank", c + 1 + a, c),
            ("word", word, w),
            ("owed", word + w, 8),
            ("refused", word + w + 8, 8),
            ("waiting", word + w + 16, 8),
            ("check", check, 1),
            ("expected", check + 1, self.payload),
        ]
    }

    /// The bounds of the port checker's bounded response, (RESPOND, RECOVER): with the consumer
    /// always ready, a result owed is delivered within RESPOND edges (a pixel taken into an
    /// empty unit leaves `latency` edges later, plus two for the buffer's queue to start), and
    /// in_ready rises again within RECOVER (the unit drains a full buffer, places results one an
    /// edge after the last pixel's latency, and in_ready follows the count three edges later).
    pub fn bounds(cfg: &Config) -> (u32, u64) {
        (cfg.latency() + 2, cfg.latency() as u64 + buffer_places(cfg) + 4)
    }
}

/// The lines around the datapath.
pub(crate) struct Edge {
    /// the header's `Latency:` line and the lines after it (each without its `// `)
    pub(crate) header: Vec<String>,
    /// declarations right after the port list: `axis` aliases, `in_take`, material registers
    pub(crate) prologue: Vec<String>,
    /// what `valid_line` takes: `in_valid`, or `in_take` behind a handshake
    pub(crate) valid_source: String,
    /// the tag's delay line (after the valid pipeline)
    pub(crate) tag: Vec<String>,
    /// the outputs: assigns, or the buffer and what it drives
    pub(crate) tail: Vec<String>,
    /// bits no logic reads (`tdata` padding), for the lint sink
    pub(crate) unused: Vec<String>,
}

fn range(width: u32) -> String {
    if width == 1 {
        "      ".into()
    } else {
        format!("{:<6}", format!("[{}:0]", width - 1))
    }
}

/// `{a, b, …}` or the one name.
fn concat(parts: &[String]) -> String {
    if parts.len() == 1 {
        parts[0].clone()
    } else {
        format!("{{{}}}", parts.join(", "))
    }
}

/// What every part of a unit's edge reads: the configuration and the ports it gives.
#[derive(Clone, Copy)]
struct Shape<'a> {
    cfg: &'a Config,
    depth: u32,
    interface: Interface,
    /// the bits carried beside each pixel, tlast above the tag
    tw: u32,
    colour: Colour,
    user: u32,
    tlast: bool,
    top: &'a str,
    /// the clock enable's port, if any
    enable: Option<&'static str>,
    /// what the buffer sees of in_valid and out_ready
    offer: &'static str,
    accept: &'static str,
}

/// The edge of the unit `plan` describes. `outputs`: each output port and the signal that
/// drives it (the datapath's last view of it).
pub(crate) fn edge(plan: &Plan, outputs: &[(String, String)]) -> Edge {
    let cfg = &plan.cfg;
    let depth = plan.registered_cuts.len() as u32;
    // tw: the bits carried beside each pixel, tlast above the tag
    let (interface, tw, colour) = (cfg.interface(), cfg.carried_tag_bits(), cfg.colour());
    let (user, tlast) = (cfg.tag_bits(), cfg.params.tlast);
    let top = cfg.top();
    // the clock enable's port, if any: it gates the handshake's inputs, so an edge with it low
    // is one without a transfer (the pipeline runs on; its results wait in the buffer)
    let enable = cfg.params.clock_enable.then_some(if interface == Interface::Axis { "aclken" } else { "clk_en" });
    // what the buffer sees of in_valid and out_ready
    let (offer, accept) = match (enable, interface) {
        (Some(_), Interface::Ready) => ("in_valid_enabled", "out_ready_enabled"),
        _ => ("in_valid", "out_ready"),
    };
    let s = Shape { cfg, depth, interface, tw, colour, user, tlast, top, enable, offer, accept };
    let mut e = Edge { header: Vec::new(), prologue: Vec::new(), valid_source: "in_valid".into(), tag: Vec::new(), tail: Vec::new(), unused: Vec::new() };
    header(&s, &mut e);
    prologue(&s, &mut e);
    let (tag_out, tag_shift) = tag(&s, plan, &mut e);
    tail(&s, outputs, tag_out, tag_shift, &mut e);
    e
}

/// The header's lines from `Latency:` on: the timing, the handshake, the fields, the enable, the colour.
fn header(s: &Shape, e: &mut Edge) {
    let Shape { cfg, interface, colour, user, tlast, top, enable, .. } = *s;
    if interface.handshake() {
        let places = buffer_places(cfg);
        let (iv, ir, ov, or) = names(interface);
        let rst = reset_words(cfg);
        e.header.push(format!("Latency:    {} clock cycles from a transfer in to its result out while {or} is high;", cfg.stages() + BUFFER_LATENCY));
        e.header.push(format!("            one result a cycle; {rst} empties the unit."));
        e.header.push("Handshake:  AXI4-Stream rules: a transfer when valid and ready are both high at a rising clock edge.".into());
        e.header.push(format!("            {ov} and every output hold while {or} is low;"));
        e.header.push(format!("            {ov} never waits for {or}."));
        e.header.push(format!("            {ir} is a register: high in a cycle when, three cycles before, fewer than {} pixels", places - 3));
        e.header.push(format!("            were taken and not yet delivered ({top}_out_buffer holds {places} results), so the"));
        e.header.push("            pipeline never stalls;".into());
        e.header.push(format!("            {iv} may come and go freely: a pixel is taken only in a transfer."));
    } else {
        let latency = if cfg.stages() == 0 {
            "0 clock cycle(s) (combinational).".to_string()
        } else {
            format!("{} clock cycle(s), one result per cycle; {} clears only the valid pipeline.", cfg.stages(), reset_words(cfg))
        };
        e.header.push(format!("Latency:    {latency}"));
    }
    if interface == Interface::Axis {
        let w = cfg.port_widths();
        let (sf, _, mf, _) = ports::tdata_fields(w);
        let bits = |f: &Field| if f.width == 1 { format!("{}[{}]", f.name, f.lo) } else { format!("{}[{}:{}]", f.name, f.lo + f.width - 1, f.lo) };
        let layout = |fields: &[Field]| fields.iter().map(bits).collect::<Vec<_>>().join(" ");
        e.header.push(format!("tdata:      s_axis_tdata: {}", layout(&sf)));
        e.header.push(format!("            m_axis_tdata: {} (other bits 0)", layout(&mf)));
    }
    if user > 0 {
        let (inp, out) = if interface == Interface::Axis { ("s_axis_tuser", "m_axis_tuser") } else { ("in_tag", "out_tag") };
        e.header.push(format!("Tag:        {inp} ({user} bits) leaves on {out} with its own pixel's result."));
    }
    if tlast {
        e.header.push("Last:       s_axis_tlast leaves on m_axis_tlast with its own pixel's result (carried as tuser is).".into());
    }
    if let Some(en) = enable {
        e.header.push(format!("Enable:     {en}: a rising edge with {en} low transfers nothing and loads no colour; the"));
        e.header.push(format!("            pipeline runs on (a result waits in {top}_out_buffer), so no result depends on {en}."));
    }
    if colour == Colour::Static {
        e.header.push("Colour:     static: ks_load takes ks_r/g/b into the material registers at a rising edge; every".into());
        e.header.push("            pixel taken after that edge uses them. Load only while idle is high and with no pixel".into());
        e.header.push("            taken in the same cycle (a pixel inside the unit meanwhile would see either colour).".into());
    }
}

/// The declarations after the port list: the reset active high inside, axis aliases, the take,
/// the material registers.
fn prologue(s: &Shape, e: &mut Edge) {
    let Shape { cfg, depth, interface, tw, colour, user, tlast, top, enable, offer, accept } = *s;
    if interface != Interface::Axis && cfg.clocked() && cfg.port_widths().reset_low {
        e.prologue.push(format!("wire {} rst = ~rst_n;   // active high inside", range(1)));
    }
    if interface == Interface::Axis {
        let w = cfg.port_widths();
        let (sf, sw, _, _) = ports::tdata_fields(w);
        e.prologue.push("// ---- AXI4-Stream names: the logic below uses the plain ones ----".into());
        e.prologue.push(format!("wire {} clk       = aclk;", range(1)));
        let w = cfg.port_widths();
        let polarity = if w.reset_low { "~" } else { "" };
        e.prologue.push(format!("wire {} rst       = {polarity}{};   // active high inside", range(1), ports::reset_port(w)));
        let gate = if enable.is_some() { " & aclken;   // a transfer only at an enabled edge" } else { ";" };
        e.prologue.push(format!("wire {} in_valid  = s_axis_tvalid{gate}", range(1)));
        e.prologue.push(format!("wire {} out_ready = m_axis_tready{gate}", range(1)));
        e.prologue.push(format!("wire {} in_ready, out_valid;", range(1)));
        let mut covered = 0u128;
        for f in &sf {
            e.prologue.push(format!("wire {} {:<9} = s_axis_tdata[{}:{}];", range(f.width), f.name, f.lo + f.width - 1, f.lo));
            covered |= crate::bits::mask(f.width) << f.lo;
        }
        e.unused.extend(crate::datapath::bit_ranges("s_axis_tdata", sw, crate::bits::mask(sw) & !covered));
        if tw > 0 {
            let source = match (user, tlast) {
                (0, _) => "s_axis_tlast".to_string(),
                (_, true) => "{s_axis_tlast, s_axis_tuser}".to_string(),
                (_, false) => "s_axis_tuser".to_string(),
            };
            e.prologue.push(format!("wire {} in_tag    = {source};", range(tw)));
        }
        let b = cfg.b();
        e.prologue.push(format!("wire {} spec_r, spec_g, spec_b;", range(b)));
        e.prologue.push(format!("wire {} intensity;", range(cfg.fi() + 1)));
        e.prologue.push(format!("wire {} done;", range(1)));
        if tw > 0 {
            e.prologue.push(format!("wire {} out_tag;", range(tw)));
        }
        e.prologue.push("assign s_axis_tready = in_ready;".into());
        e.prologue.push("assign m_axis_tvalid = out_valid;".into());
    }
    if let (Some(en), Interface::Ready) = (enable, interface) {
        e.prologue.push(format!("wire {} {offer}  = in_valid & {en};    // a transfer only at an enabled edge", range(1)));
        e.prologue.push(format!("wire {} {accept} = out_ready & {en};", range(1)));
    }
    if interface.handshake() {
        e.prologue.push(format!("wire {} in_take;   // in_valid && in_ready: the pipeline takes a pixel ({top}_out_buffer)", range(1)));
        e.valid_source = "in_take".into();
    }
    if colour == Colour::Static {
        let b = cfg.b();
        e.prologue.push(String::new());
        e.prologue.push("// ---- the material registers: ks_load takes ks_r/g/b; every step reads them ----".into());
        // kept: yosys 0.70 takes a register a multiplier reads into the SB_MAC16 as its input
        // register, ks_load its hold, a 6.5 ns route into the DSP tile (blinn static 94.8 MHz)
        e.prologue.push(format!("(* keep *) reg  {} ks_r_material, ks_g_material, ks_b_material;   // UNORM{b}", range(b)));
        let load = enable.map_or("ks_load".to_string(), |en| format!("ks_load && {en}"));
        e.prologue.push(format!("always @(posedge clk) if ({load}) {{ks_r_material, ks_g_material, ks_b_material}} <= {{ks_r, ks_g, ks_b}};"));
        if depth == 0 && !interface.handshake() {
            // combinational: no valid pipeline for rst to clear (the port stays, as with every clock)
            e.unused.push("rst".into());
        }
    }
}

/// The tag's delay line beside valid_line, where the unit has a tag and a pipeline.
pub(crate) fn tag_line(plan: &Plan) -> Option<DelayLine> {
    let cfg = &plan.cfg;
    let tw = cfg.carried_tag_bits();
    if tw == 0 || plan.registered_cuts.is_empty() {
        return None;
    }
    let cuts: Vec<usize> = plan.registered_cuts.iter().map(|&k| k as usize).collect();
    let read = vec![0; cuts.len()];
    let member = Waiting { name: "tag".into(), width: tw, source: "in_tag".into(), read };
    Some(DelayLine {
        name: "tag".into(),
        cuts,
        members: vec![member],
        memory: crate::family::of(cfg.target()).has_block_ram(),
        distributed: crate::family::of(cfg.target()).distributed_ram(),
    })
}

/// The tag: one delay line beside valid_line. Returns its last word, and whether the line is
/// all a shift register `tag_line` (no tail in block RAM: its formal block then follows it word
/// by word).
fn tag(s: &Shape, plan: &Plan, e: &mut Edge) -> (Option<String>, bool) {
    let Shape { depth, tw, top, .. } = *s;
    let mut tag_shift = false;
    let tag_out = if tw == 0 {
        None
    } else if depth == 0 {
        Some("in_tag".to_string())
    } else {
        let line = tag_line(plan).expect("a tag and a pipeline");
        let last = format!("tag_c{}", line.cuts[line.cuts.len() - 1]);
        e.tag.push(String::new());
        e.tag.extend(line.lines(top));
        tag_shift = line.memory_tail().is_none();
        Some(last)
    };

    (tag_out, tag_shift)
}

/// The outputs: assigns, or the output buffer and what it drives (the formal lines, axis packing).
fn tail(s: &Shape, outputs: &[(String, String)], tag_out: Option<String>, tag_shift: bool, e: &mut Edge) {
    let Shape { cfg, depth, interface, tw, colour, user, tlast, top, offer, accept, .. } = *s;
    let last_valid = if depth == 0 { e.valid_source.clone() } else { format!("valid_line[{}]", depth - 1) };
    if !interface.handshake() {
        e.tail.push(String::new());
        e.tail.push(format!("assign out_valid = {last_valid};"));
        for (port, src) in outputs {
            e.tail.push(format!("assign {port:<9} = {src};"));
        }
        if let Some(t) = &tag_out {
            e.tail.push(format!("assign {:<9} = {t};", "out_tag"));
        }
        if colour == Colour::Static {
            if depth == 0 {
                e.tail.push(format!("assign {:<9} = 1'b1;   // no pipeline: never a pixel inside", "idle"));
            } else {
                // registered, from what valid_line holds after this edge: idle leaves the unit
                // from a flip-flop, not through an OR of the whole valid pipeline
                e.tail.extend(idle_of_valid_line(depth));
                e.tail.push(format!("assign {:<9} = idle_q;", "idle"));
            }
        }
        return;
    }
    // the buffer: the tag, then the outputs in port order reversed (spec_r lowest)
    let mut fields: Vec<(String, String, u32)> = Vec::new();
    if let Some(t) = &tag_out {
        fields.push(("out_tag".into(), t.clone(), tw));
    }
    let logical = cfg.logical_ports();
    let widths = |p: &str| logical.iter().find(|x| x.name == p).map(|x| x.width).expect("an output port");
    for (port, src) in outputs.iter().rev() {
        fields.push((port.clone(), src.clone(), widths(port)));
    }
    let width: u32 = fields.iter().map(|f| f.2).sum();
    e.tail.push(String::new());
    e.tail.push("// ==== the output buffer: the handshake ====".into());
    e.tail.push(format!("// every pixel taken has a place reserved in {top}_out_buffer, so the pipeline never waits"));
    e.tail.push(format!("wire {} out_result = {};", range(width), concat(&fields.iter().map(|f| f.1.clone()).collect::<Vec<_>>())));
    e.tail.push(format!("wire {} out_held;", range(width)));
    let count_bits = buffer_depth_log2(depth) + 2;
    e.tail.push("`ifdef FORMAL".into());
    e.tail.push("// formal only: what the buffer tells the unit's own assertions (see its formal block)".into());
    e.tail.push(format!("wire {} f_buffer_outstanding, f_buffer_results, f_buffer_rank;", range(count_bits)));
    e.tail.push(format!("wire {} f_buffer_at_rank;", range(width)));
    e.tail.push("wire [7:0]  f_buffer_progress, f_buffer_recover;".into());
    e.tail.push(format!("wire [{}:0] f_buffer_takes;", cfg.stages()));
    e.tail.push("`endif".into());
    let bits = buffer_depth_log2(depth) as usize;
    e.tail.push(format!(
        "{top}_out_buffer #(.WIDTH({width}), .DEPTH_LOG2({bits}), .TAPS({bits}'b{:0bits$b}), .PLACES({}), .LATENCY({})) out_buffer (",
        lfsr_taps(bits as u32),
        places_for(depth),
        cfg.stages()
    ));
    e.tail.push(format!("    .clk(clk), .rst(rst), .in_valid({offer}), .in_ready(in_ready), .take(in_take),"));
    e.tail.push(format!("    .result_valid({last_valid}), .result(out_result),"));
    e.tail.push(format!("    .out_valid(out_valid), .out_ready({accept}), .out(out_held)"));
    e.tail.push("`ifdef FORMAL".into());
    e.tail.push("    , .f_outstanding(f_buffer_outstanding), .f_results(f_buffer_results), .f_rank(f_buffer_rank),".into());
    e.tail.push("    .f_at_rank(f_buffer_at_rank), .f_progress(f_buffer_progress), .f_recover(f_buffer_recover), .f_takes(f_buffer_takes)".into());
    e.tail.push("`endif".into());
    e.tail.push(");".into());
    if colour == Colour::Static {
        e.tail.extend(inside_count(places_for(depth), accept));
    }
    e.tail.push(format!("assign {} = out_held;", concat(&fields.iter().map(|f| f.0.clone()).collect::<Vec<_>>())));
    let tag_line = (depth > 0 && tw > 0).then(|| (tag_out.clone().expect("a tag"), tag_shift));
    // a result in the buffer's word as the port checker orders it: {intensity, spec_r, spec_g,
    // spec_b, done}
    let mut at = width;
    let mut bits = std::collections::BTreeMap::new();
    for (port, _, w) in &fields {
        bits.insert(port.as_str(), if *w == 1 { format!("f_buffer_at_rank[{}]", at - 1) } else { format!("f_buffer_at_rank[{}:{}]", at - 1, at - w) });
        at -= w;
    }
    let payload = format!("{{{}}}", ["intensity", "spec_r", "spec_g", "spec_b", "done"].map(|p| bits[p].clone()).join(", "));
    let lemmas = lemma_lines(depth, tw, width, &payload, CheckerState::of(cfg), CheckerState::bounds(cfg).1);
    e.tail.extend(formal_lines(depth, tw, tag_line, (colour == Colour::Static).then(|| places_for(depth)), lemmas));
    if interface == Interface::Axis {
        let (_, _, mf, mw) = ports::tdata_fields(cfg.port_widths());
        e.tail.push(format!("assign m_axis_tdata = {};", ports::packed_tdata(&mf, mw)));
        match (user, tlast) {
            (0, false) => {}
            (0, true) => e.tail.push("assign m_axis_tlast = out_tag;".into()),
            (_, false) => e.tail.push("assign m_axis_tuser = out_tag;".into()),
            (_, true) => e.tail.push(format!("assign {{m_axis_tlast, m_axis_tuser}} = out_tag;   // tlast above the tag ({user} bits)")),
        }
    }
}

/// `idle_q` of a `valid` unit with material registers: `~|valid_line` one edge ahead. After
/// the edge valid_line holds `in_valid` and its bits `0 ..= depth - 2`; those bits are
/// `valid_seen`, one flag for each four, registered one edge ahead too (each a LUT of four
/// bits, as they shift in), so idle_q's input is an OR of `in_valid` and the flags: two LUT
/// levels at any depth, not an OR of the whole pipeline (three levels from 17 stages on).
fn idle_of_valid_line(depth: u32) -> Vec<String> {
    let mut out = vec!["reg  idle_q;   // no pixel in the pipeline: ~|valid_line, one edge ahead".to_string()];
    if depth == 1 {
        out.push("always @(posedge clk) idle_q <= rst | ~(in_valid);".into());
        return out;
    }
    // flag j: valid_line[4j+3:4j] (within 0..=depth-2) after the edge, from the bits one below
    let top = depth - 2;
    let groups = (top / 4 + 1) as usize;
    let next: Vec<String> = (0..groups as u32)
        .rev()
        .map(|j| {
            let (lo, hi) = (4 * j, (4 * j + 3).min(top));
            match (lo, hi) {
                (0, 0) => "in_valid".to_string(),
                (0, h) => format!("(|{{valid_line[{}:0], in_valid}})", h - 1),
                (l, h) if l == h => format!("valid_line[{}]", l - 1),
                (l, h) => format!("(|valid_line[{}:{}])", h - 1, l - 1),
            }
        })
        .collect();
    out.push(format!("reg  {} valid_seen;   // bit j: a pixel in valid_line[4j+3:4j] (bits 0..={top}), one edge ahead", range(groups as u32)));
    out.push("always @(posedge clk) begin".into());
    out.push(format!("    if (rst) valid_seen <= {groups}'h0;"));
    out.push(format!("    else     valid_seen <= {{{}}};", next.join(", ")));
    out.push("end".into());
    out.push("always @(posedge clk) idle_q <= rst | ~(in_valid | (|valid_seen));".into());
    out
}

/// `idle` of a handshake unit with material registers, from a flip-flop: a thermometer of the
/// pixels inside (taken, not yet delivered: 0..=`places`), bit k set while k or more are.
/// Two LUT levels from the handshake, no carry chain and no OR over the pipeline: first each
/// bit as it would be after the take alone (`in_take ? bit k-1 : bit k`, kept), then the
/// delivery picks it or its neighbour above (a delivery moves every bit down one).
fn inside_count(places: u64, accept: &str) -> Vec<String> {
    let p = places;
    let given = format!("out_valid && {accept}");
    vec![
        String::new(),
        "// ---- idle: a thermometer of the pixels inside (taken, not yet delivered) ----".into(),
        format!("reg  [{p}:1] inside_at_least;   // bit k: k or more pixels inside"),
        format!("wire [{}:0] inside_level = {{1'b0, inside_at_least, 1'b1}};   // with its two ends", p + 1),
        "// bit k after the take alone (k = 1 ..= places + 1): one LUT of in_take and two bits".into(),
        "// (AND-OR, not ?: a hold would become a flip-flop enable that the handshake and rst reach)".into(),
        format!("(* keep *) wire [{}:1] inside_taken;", p + 1),
        format!("assign inside_taken = ({{{}{{in_take}}}} & inside_level[{p}:0]) | ({{{}{{!in_take}}}} & inside_level[{}:1]);", p + 1, p + 1, p + 1),
        format!("wire        inside_given = {given};   // a delivery"),
        "reg  idle_q;   // none inside: bit 1 clear, a flip-flop of its own".into(),
        "always @(posedge clk) begin".into(),
        "    if (rst) begin".into(),
        format!("        inside_at_least <= {p}'h0;"),
        "        idle_q          <= 1'b1;".into(),
        "    end else begin".into(),
        "        // a delivery moves every bit down one".into(),
        format!("        inside_at_least <= ({{{p}{{inside_given}}}} & inside_taken[{}:2]) | ({{{p}{{!inside_given}}}} & inside_taken[{p}:1]);", p + 1),
        "        idle_q          <= !((inside_given & inside_taken[2]) | (!inside_given & inside_taken[1]));".into(),
        "    end".into(),
        "end".into(),
        format!("assign {:<9} = idle_q;   // no pixel in the pipeline or the buffer", "idle"),
    ]
}

/// The unit's own formal block (read only with `yosys -formal`, as `specgen prove` does; see
/// `templates/out_buffer.v` for the buffer's): with a tag (`tag`: the last word's name, and
/// whether the line is a plain shift register `tag_line`), the tag entering the buffer with a
/// result is in_tag of the pixel `depth` edges before; with material registers (`places`),
/// idle is high exactly while no pixel is inside. Each is an assertion `prove` proves, with the
/// invariants that make it inductive within a few edges.
fn formal_lines(depth: u32, tw: u32, tag: Option<(String, bool)>, places: Option<u64>, lemmas: Vec<String>) -> Vec<String> {
    let mut out = vec![
        String::new(),
        "`ifdef FORMAL".into(),
        "// ==== formal (read with yosys -formal, as `specgen prove` does; synthesis and simulation never read it) ====".into(),
        "reg  f_started = 1'b0;   // the first edge (a reset: the buffer's assumption) has passed".into(),
        "always @(posedge clk) f_started <= 1'b1;".into(),
    ];
    if let Some((last, shift)) = tag {
        let (l, t) = (depth, tw);
        out.push(format!("// in_tag of the last {l} edges (word j: j + 1 edges before), and how many edges have passed (bit j: more than j)"));
        out.push(format!("reg  [{}:0] f_tags;", l * t - 1));
        out.push(format!("reg  [{}:0] f_age = {l}'h0;", l - 1));
        if l == 1 {
            out.push("always @(posedge clk) begin f_tags <= in_tag; f_age <= 1'b1; end".into());
        } else {
            out.push(format!("always @(posedge clk) begin f_tags <= {{f_tags[{}:0], in_tag}}; f_age <= {{f_age[{}:0], 1'b1}}; end", (l - 1) * t - 1, l - 2));
        }
        out.push("always @(*) if (f_started) begin".into());
        out.push(format!("    // the tag that enters the buffer with a result is its pixel's: in_tag {l} edges before"));
        out.push(format!("    if (valid_line[{}]) assert({last} == f_tags[{}:{}]);", l - 1, l * t - 1, (l - 1) * t));
        out.push("    // (a pixel in the pipeline was taken after power-up)".into());
        out.push("    assert((valid_line & ~f_age) == 0);".into());
        if shift {
            out.push("    // the line is a shift register: each word is in_tag j + 1 edges before, once that many have passed".into());
            for j in 0..l {
                out.push(format!("    if (f_age[{j}]) assert(tag_line[{} +: {t}] == f_tags[{} +: {t}]);", j * t, j * t));
            }
        }
        out.push("end".into());
    }
    if let Some(p) = places {
        out.push("integer f_k, f_count;".into());
        out.push("always @(*) begin".into());
        out.push("    f_count = 0;".into());
        out.push(format!("    for (f_k = 1; f_k <= {p}; f_k = f_k + 1) f_count = f_count + inside_at_least[f_k];"));
        out.push("    if (f_started) begin".into());
        out.push("        // idle is high exactly while no pixel is inside (the buffer counts them)".into());
        out.push("        assert(idle_q == (f_buffer_outstanding == 0));".into());
        out.push("        // the thermometer is one, and counts them".into());
        out.push(format!("        for (f_k = 1; f_k < {p}; f_k = f_k + 1) if (inside_at_least[f_k + 1]) assert(inside_at_least[f_k]);"));
        out.push("        assert(f_count == f_buffer_outstanding);".into());
        out.push("    end".into());
        out.push("end".into());
    }
    out.extend(lemmas);
    out.push("`endif".into());
    out
}

/// The unit's lemmas for `specgen prove` at its ports (under `SPECGEN_LEMMAS`, with the port
/// `f_ports`): the port checker's state, written from the manifest apart from the unit, tied to
/// the unit's own, so the checker's stream rules close by induction. The pixels inside are the
/// buffer's count; a result owed has waited no longer than the unit's progress toward one
/// (`f_progress` of the buffer); the pixel followed is, by its age, at its stage of the pipeline
/// (its tag there, the pixels inside less those at or behind its stage ahead of it) or in the
/// buffer at its rank with its tag. Each is an assertion: a false one fails the proof, and
/// without them the induction may not close, but no lemma can pass a unit that breaks a rule.
/// With `prove --datapath`, the followed pixel's result in the buffer is the one the `valid`
/// twin computed for it. (`depth`: the latency; `tw`: the carried word's bits; `width`: the
/// buffer's word, the carried word on top; `payload`: a result at the buffer's rank, in the
/// checker's order.)
fn lemma_lines(depth: u32, tw: u32, width: u32, payload: &str, state: CheckerState, recover: u64) -> Vec<String> {
    let mut out = vec![
        "`ifdef SPECGEN_LEMMAS".into(),
        "// ---- lemmas (`specgen prove` at the ports): the port checker's state, f_ports, tied to the unit's ----".into(),
    ];
    for (name, lo, w) in state.fields() {
        let what = match name {
            "inside" => "pixels taken and not delivered",
            "following" => "a pixel followed",
            "age" => "its edges since taken (the latency and more: in the buffer)",
            "rank" => "results to leave before it",
            "word" => "its tag (and tlast)",
            "owed" => "edges a result has been owed to a consumer ready at each",
            "refused" => "edges in_ready has been low to a consumer ready at each",
            "waiting" => "edges a result has been owed and not shown, whatever the consumer does",
            "check" => "prove --datapath: its result is known",
            _ => "prove --datapath: its result, {intensity, spec_r, spec_g, spec_b, done}",
        };
        let sel = if w == 1 { format!("f_ports[{lo}]") } else { format!("f_ports[{}:{lo}]", lo + w - 1) };
        out.push(format!("wire {} f_ports_{name:<9} = {sel};   // {what}", range(w)));
    }
    out.push("assign f_buffer_rank = f_ports_rank;".into());
    if depth > 0 {
        out.push("integer f_p, f_behind;".into());
        if tw > 0 {
            out.push(format!("reg  {} f_tag_at_age;   // in_tag of the edge the followed pixel was taken", range(tw)));
        }
    }
    out.push("always @(*) begin".into());
    if depth > 0 {
        out.push("    f_behind = 0;   // pixels in the pipeline at the followed one's stage or behind it".into());
        out.push(format!("    for (f_p = 0; f_p < {depth}; f_p = f_p + 1) if (f_p <= f_ports_age) f_behind = f_behind + valid_line[f_p];"));
        if tw > 0 {
            // (a constant part-select in a loop: yosys 0.23 reads `f_tags[f_ports_age * T +: T]` wrongly)
            out.push(format!("    f_tag_at_age = {tw}'h0;"));
            out.push(format!("    for (f_p = 0; f_p < {depth}; f_p = f_p + 1) if (f_p == f_ports_age) f_tag_at_age = f_tags[f_p * {tw} +: {tw}];"));
        }
    }
    out.push("    if (f_started) begin".into());
    if depth > 0 {
        out.push("        // the pipeline's valid bits are the pixels the buffer saw taken".into());
        out.push(format!("        assert(valid_line == f_buffer_takes[{}:0]);", depth - 1));
    }
    out.push("        // the checker counts the pixels inside as the buffer does".into());
    out.push("        assert(f_ports_inside == f_buffer_outstanding);".into());
    out.push("        // a result owed has waited no longer than the unit's progress toward delivering one".into());
    out.push("        assert(f_ports_owed <= f_buffer_progress);".into());
    out.push("        // and one owed and not shown: out_valid never waits for out_ready".into());
    out.push("        assert(f_ports_waiting <= f_buffer_progress);".into());
    out.push("        // in_ready low: the edges it has been low to a ready consumer and those it stays low".into());
    out.push(format!("        // are {recover} at most (the checker's bound: latency + places + 4)"));
    out.push(format!("        if (!in_ready) assert(f_ports_refused + f_buffer_recover <= {recover});"));
    if depth > 0 {
        out.push(format!("        if (f_ports_following && f_ports_age < {depth}) begin"));
        out.push("            // in the pipeline, at the stage of its age: a pixel there, its tag with it, those inside".into());
        out.push("            // less those at its stage or behind it ahead of it".into());
        out.push("            assert(valid_line[f_ports_age]);".into());
        if tw > 0 {
            out.push("            assert(f_tag_at_age == f_ports_word);".into());
        }
        out.push("            assert(f_ports_rank == f_ports_inside - f_behind);".into());
        out.push("        end".into());
    }
    out.push(format!("        if (f_ports_following && f_ports_age >= {depth}) begin"));
    out.push("            // in the buffer, at its rank, with its tag".into());
    out.push("            assert(f_ports_rank < f_buffer_results);".into());
    if tw > 0 {
        out.push(format!("            assert(f_buffer_at_rank[{}:{}] == f_ports_word);", width - 1, width - tw));
    }
    out.push("            // (prove --datapath) with the result the twin computed for it".into());
    out.push(format!("            if (f_ports_check) assert({payload} == f_ports_expected);"));
    out.push("        end".into());
    out.push("    end".into());
    out.push("end".into());
    out.push("`else".into());
    out.push("assign f_buffer_rank = 0;".into());
    out.push("`endif".into());
    out
}

/// The reset as the header names it: `rst`, `rst_n low`, `areset`, `aresetn low`.
fn reset_words(cfg: &crate::config::Config) -> String {
    let w = cfg.port_widths();
    format!("{}{}", ports::reset_port(w), if w.reset_low { " low" } else { "" })
}

/// The handshake's port names: in valid, in ready, out valid, out ready (the reset's:
/// [`reset_words`]).
fn names(interface: Interface) -> (&'static str, &'static str, &'static str, &'static str) {
    match interface {
        Interface::Axis => ("s_axis_tvalid", "s_axis_tready", "m_axis_tvalid", "m_axis_tready"),
        _ => ("in_valid", "in_ready", "out_valid", "out_ready"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every tap set gives a register that goes through all 2^bits - 1 states but all ones
    /// from 0, as the buffer's pointers need (a shorter cycle would reuse a place too early).
    #[test]
    fn lfsr_taps_are_maximal() {
        for bits in 3..=16u32 {
            let (taps, mask) = (lfsr_taps(bits), (1u32 << bits) - 1);
            let mut at = 0u32;
            let mut seen = vec![false; 1 << bits];
            for _ in 0..mask {
                assert!(!seen[at as usize], "{bits} bits: state {at} again");
                seen[at as usize] = true;
                at = ((at << 1) | (!(at & taps).count_ones() & 1)) & mask;
            }
            assert_eq!(at, 0, "{bits} bits: back at 0 after 2^{bits} - 1 steps");
            assert!(!seen[mask as usize], "{bits} bits: all ones is the one state left out");
        }
    }
}
