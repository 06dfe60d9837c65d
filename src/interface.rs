//! The unit's edge around its datapath (SPEC §7): the handshake, the tag beside each pixel,
//! the material registers of a static colour, and the `axis` names — rendered by the
//! templates `edge_header.txt`, `edge_prologue.v`, `edge_tail.v` and `edge_formal.v` (the
//! unit's formal block and lemmas) from the values computed here, as the lines
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
use askama::Template;

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
    (places_for(stages) + 1)
        .next_power_of_two()
        .trailing_zeros()
        .max(3)
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
        (
            cfg.latency() + 2,
            cfg.latency() as u64 + buffer_places(cfg) + 4,
        )
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
    let enable = cfg
        .params
        .clock_enable
        .then_some(if interface == Interface::Axis {
            "aclken"
        } else {
            "clk_en"
        });
    // what the buffer sees of in_valid and out_ready
    let (offer, accept) = match (enable, interface) {
        (Some(_), Interface::Ready) => ("in_valid_enabled", "out_ready_enabled"),
        _ => ("in_valid", "out_ready"),
    };
    let s = Shape {
        cfg,
        depth,
        interface,
        tw,
        colour,
        user,
        tlast,
        top,
        enable,
        offer,
        accept,
    };
    let mut e = Edge {
        header: Vec::new(),
        prologue: Vec::new(),
        valid_source: "in_valid".into(),
        tag: Vec::new(),
        tail: Vec::new(),
        unused: Vec::new(),
    };
    header(&s, &mut e);
    prologue(&s, &mut e);
    let (tag_out, tag_shift) = tag(&s, plan, &mut e);
    tail(&s, outputs, tag_out, tag_shift, &mut e);
    e
}

/// The lines a template renders: each of its lines starts after a newline (the templates
/// open with a comment, so the first line is preceded by one too), and a file's last newline
/// ends nothing.
fn lines_of(t: &impl Template) -> Vec<String> {
    let text = t.render().expect("an edge template renders");
    let text = text.strip_prefix('\n').unwrap_or(&text);
    let text = text.strip_suffix('\n').unwrap_or(text);
    if text.is_empty() {
        return Vec::new();
    }
    text.split('\n').map(String::from).collect()
}

/// The handshake's words in the header.
struct HandshakeWords {
    latency: u32,
    places: u64,
    in_valid: &'static str,
    in_ready: &'static str,
    out_valid: &'static str,
    out_ready: &'static str,
}

#[derive(Template)]
#[template(path = "edge_header.txt")]
struct HeaderView<'a> {
    handshake: Option<HandshakeWords>,
    stages: u32,
    reset: String,
    top: &'a str,
    /// the s_axis_tdata and m_axis_tdata layouts
    tdata: Option<(String, String)>,
    /// the tag's port in, port out and bits
    tag: Option<(&'static str, &'static str, u32)>,
    tlast: bool,
    enable: Option<&'static str>,
    static_colour: bool,
}

/// The header's lines from `Latency:` on: the timing, the handshake, the fields, the enable, the colour.
fn header(s: &Shape, e: &mut Edge) {
    let Shape {
        cfg,
        interface,
        colour,
        user,
        tlast,
        top,
        enable,
        ..
    } = *s;
    let handshake = interface.handshake().then(|| {
        let (in_valid, in_ready, out_valid, out_ready) = names(interface);
        HandshakeWords {
            latency: cfg.stages() + BUFFER_LATENCY,
            places: buffer_places(cfg),
            in_valid,
            in_ready,
            out_valid,
            out_ready,
        }
    });
    let tdata = (interface == Interface::Axis).then(|| {
        let (sf, _, mf, _) = ports::tdata_fields(cfg.port_widths());
        let bits = |f: &Field| {
            if f.width == 1 {
                format!("{}[{}]", f.name, f.lo)
            } else {
                format!("{}[{}:{}]", f.name, f.lo + f.width - 1, f.lo)
            }
        };
        let layout = |fields: &[Field]| fields.iter().map(bits).collect::<Vec<_>>().join(" ");
        (layout(&sf), layout(&mf))
    });
    let tag = (user > 0).then_some(match interface {
        Interface::Axis => ("s_axis_tuser", "m_axis_tuser", user),
        _ => ("in_tag", "out_tag", user),
    });
    let view = HeaderView {
        handshake,
        stages: cfg.stages(),
        reset: reset_words(cfg),
        top,
        tdata,
        tag,
        tlast,
        enable,
        static_colour: colour == Colour::Static,
    };
    e.header = lines_of(&view);
}

/// One `s_axis_tdata` field's alias.
struct FieldAlias {
    range: String,
    name: &'static str,
    hi: u32,
    lo: u32,
}

/// The `axis` unit's aliases of its ports.
struct AxisAliases {
    reset: String,
    gate: &'static str,
    fields: Vec<FieldAlias>,
    tag_source: Option<&'static str>,
    intensity_range: String,
}

#[derive(Template)]
#[template(path = "edge_prologue.v")]
struct PrologueView<'a> {
    reset_from_low: bool,
    axis: Option<AxisAliases>,
    /// (in_valid enabled, out_ready enabled, the enable) of a `ready` unit with one
    enabled_ready: Option<(&'static str, &'static str, &'static str)>,
    handshake: bool,
    top: &'a str,
    /// what loads the material registers, with a static colour
    material_load: Option<String>,
    colour_bits: u32,
    colour_range: String,
    tag_range: String,
}

/// The declarations after the port list: the reset active high inside, axis aliases, the take,
/// the material registers.
fn prologue(s: &Shape, e: &mut Edge) {
    let Shape {
        cfg,
        depth,
        interface,
        tw,
        colour,
        user,
        tlast,
        top,
        enable,
        offer,
        accept,
    } = *s;
    let w = cfg.port_widths();
    let axis = (interface == Interface::Axis).then(|| {
        let (sf, sw, _, _) = ports::tdata_fields(w);
        let covered = sf
            .iter()
            .fold(0u128, |c, f| c | crate::bits::mask(f.width) << f.lo);
        e.unused.extend(crate::datapath::bit_ranges(
            "s_axis_tdata",
            sw,
            crate::bits::mask(sw) & !covered,
        ));
        let fields = sf
            .iter()
            .map(|f| FieldAlias {
                range: range(f.width),
                name: f.name,
                hi: f.lo + f.width - 1,
                lo: f.lo,
            })
            .collect();
        let tag_source = (tw > 0).then_some(match (user, tlast) {
            (0, _) => "s_axis_tlast",
            (_, true) => "{s_axis_tlast, s_axis_tuser}",
            (_, false) => "s_axis_tuser",
        });
        let polarity = if w.reset_low { "~" } else { "" };
        AxisAliases {
            reset: format!("{polarity}{}", ports::reset_port(w)),
            gate: if enable.is_some() {
                " & aclken;   // a transfer only at an enabled edge"
            } else {
                ";"
            },
            fields,
            tag_source,
            intensity_range: range(cfg.fi() + 1),
        }
    });
    let enabled_ready = match (enable, interface) {
        (Some(en), Interface::Ready) => Some((offer, accept, en)),
        _ => None,
    };
    if interface.handshake() {
        e.valid_source = "in_take".into();
    }
    let material_load = (colour == Colour::Static)
        .then(|| enable.map_or("ks_load".to_string(), |en| format!("ks_load && {en}")));
    if colour == Colour::Static && depth == 0 && !interface.handshake() {
        // combinational: no valid pipeline for rst to clear (the port stays, as with every clock)
        e.unused.push("rst".into());
    }
    let view = PrologueView {
        reset_from_low: interface != Interface::Axis && cfg.clocked() && w.reset_low,
        axis,
        enabled_ready,
        handshake: interface.handshake(),
        top,
        material_load,
        colour_bits: cfg.b(),
        colour_range: range(cfg.b()),
        tag_range: range(tw),
    };
    e.prologue = lines_of(&view);
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
    let member = Waiting {
        name: "tag".into(),
        width: tw,
        source: "in_tag".into(),
        read,
    };
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

/// A handshake unit's output buffer, as `templates/edge_tail.v` instantiates it.
struct BufferView {
    width: u32,
    range: String,
    count_range: String,
    /// `{…}` of what enters the buffer, the tag on top
    results: String,
    /// `{…}` of the ports it drives
    ports: String,
    depth_log2: u32,
    taps: String,
    places: u64,
    offer: &'static str,
    accept: &'static str,
    tdata: Option<String>,
    /// what out_tag drives under `axis` (tlast above the tag: its bits)
    carried: Option<(&'static str, Option<u32>)>,
}

#[derive(Template)]
#[template(path = "edge_tail.v")]
struct TailView<'a> {
    top: &'a str,
    stages: u32,
    last_valid: String,
    static_colour: bool,
    buffer: Option<BufferView>,
    formal: Vec<String>,
    /// a `valid` unit: each output port and its source
    outputs: &'a [(String, String)],
    tag_out: Option<String>,
    /// a `valid` unit with material registers, 2+ stages: the flags' range, the top bit they
    /// cover, their count, and their next value
    valid_seen: Option<(String, u32, usize, String)>,
}

/// The outputs: assigns, or the output buffer and what it drives (the formal lines, axis packing).
fn tail(
    s: &Shape,
    outputs: &[(String, String)],
    tag_out: Option<String>,
    tag_shift: bool,
    e: &mut Edge,
) {
    let Shape {
        cfg,
        depth,
        interface,
        tw,
        colour,
        user,
        tlast,
        top,
        offer,
        accept,
        ..
    } = *s;
    let last_valid = if depth == 0 {
        e.valid_source.clone()
    } else {
        format!("valid_line[{}]", depth - 1)
    };
    let static_colour = colour == Colour::Static;
    let mut view = TailView {
        top,
        stages: cfg.stages(),
        last_valid,
        static_colour,
        buffer: None,
        formal: Vec::new(),
        outputs,
        tag_out: None,
        valid_seen: None,
    };
    if !interface.handshake() {
        view.tag_out = tag_out;
        view.valid_seen = (static_colour && depth > 1).then(|| valid_seen(depth));
        e.tail = lines_of(&view);
        return;
    }
    // the buffer: the tag, then the outputs in port order reversed (spec_r lowest)
    let mut fields: Vec<(String, String, u32)> = Vec::new();
    if let Some(t) = &tag_out {
        fields.push(("out_tag".into(), t.clone(), tw));
    }
    let logical = cfg.logical_ports();
    let widths = |p: &str| {
        logical
            .iter()
            .find(|x| x.name == p)
            .map(|x| x.width)
            .expect("an output port")
    };
    for (port, src) in outputs.iter().rev() {
        fields.push((port.clone(), src.clone(), widths(port)));
    }
    let width: u32 = fields.iter().map(|f| f.2).sum();
    let bits = buffer_depth_log2(depth);
    let tag_line = (depth > 0 && tw > 0).then(|| (tag_out.clone().expect("a tag"), tag_shift));
    // a result in the buffer's word as the port checker orders it: {intensity, spec_r, spec_g,
    // spec_b, done}
    let mut at = width;
    let mut at_rank = std::collections::BTreeMap::new();
    for (port, _, w) in &fields {
        at_rank.insert(
            port.as_str(),
            if *w == 1 {
                format!("f_buffer_at_rank[{}]", at - 1)
            } else {
                format!("f_buffer_at_rank[{}:{}]", at - 1, at - w)
            },
        );
        at -= w;
    }
    let payload = format!(
        "{{{}}}",
        ["intensity", "spec_r", "spec_g", "spec_b", "done"]
            .map(|p| at_rank[p].clone())
            .join(", ")
    );
    let state = CheckerState::of(cfg);
    view.formal = lines_of(&FormalView {
        depth,
        tw,
        tag: tag_line,
        places: static_colour.then(|| places_for(depth)),
        fields: state
            .fields()
            .iter()
            .map(|&(name, lo, w)| checker_field(name, lo, w))
            .collect(),
        tag_range: range(tw),
        width,
        payload,
        recover: CheckerState::bounds(cfg).1,
    });
    view.buffer = Some(BufferView {
        width,
        range: range(width),
        count_range: range(bits + 2),
        results: concat(&fields.iter().map(|f| f.1.clone()).collect::<Vec<_>>()),
        ports: concat(&fields.iter().map(|f| f.0.clone()).collect::<Vec<_>>()),
        depth_log2: bits,
        taps: format!("{bits}'b{:0w$b}", lfsr_taps(bits), w = bits as usize),
        places: places_for(depth),
        offer,
        accept,
        tdata: (interface == Interface::Axis).then(|| {
            let (_, _, mf, mw) = ports::tdata_fields(cfg.port_widths());
            ports::packed_tdata(&mf, mw)
        }),
        carried: match (interface, user, tlast) {
            (Interface::Axis, 0, true) => Some(("m_axis_tlast", None)),
            (Interface::Axis, u, false) if u > 0 => Some(("m_axis_tuser", None)),
            (Interface::Axis, u, true) => Some(("{m_axis_tlast, m_axis_tuser}", Some(u))),
            _ => None,
        },
    });
    e.tail = lines_of(&view);
}

/// `valid_seen` of a `valid` unit with material registers at `depth` >= 2 stages: flag j is
/// valid_line[4j+3:4j] (within 0..=depth-2) after the edge, from the bits one below; its
/// range, the top bit, the flags, their next value.
fn valid_seen(depth: u32) -> (String, u32, usize, String) {
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
    (
        range(groups as u32),
        top,
        groups,
        format!("{{{}}}", next.join(", ")),
    )
}

#[derive(Template)]
#[template(path = "edge_formal.v")]
struct FormalView {
    /// the latency
    depth: u32,
    /// the carried word's bits
    tw: u32,
    /// the tag line's last word, and whether the line is a plain shift register `tag_line`
    tag: Option<(String, bool)>,
    /// with material registers: the buffer's places
    places: Option<u64>,
    /// the port checker's fields: name, range, select of f_ports, what it holds
    fields: Vec<(&'static str, String, String, &'static str)>,
    tag_range: String,
    /// the buffer's word, the carried word on top
    width: u32,
    /// a result at the buffer's rank, in the checker's order
    payload: String,
    recover: u64,
}

/// One field of the port checker's state as the lemmas unpack it from `f_ports`.
fn checker_field(
    name: &'static str,
    lo: u32,
    w: u32,
) -> (&'static str, String, String, &'static str) {
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
    let select = if w == 1 {
        format!("f_ports[{lo}]")
    } else {
        format!("f_ports[{}:{lo}]", lo + w - 1)
    };
    (name, range(w), select, what)
}

/// The reset as the header names it: `rst`, `rst_n low`, `areset`, `aresetn low`.
fn reset_words(cfg: &crate::config::Config) -> String {
    let w = cfg.port_widths();
    format!(
        "{}{}",
        ports::reset_port(w),
        if w.reset_low { " low" } else { "" }
    )
}

/// The handshake's port names: in valid, in ready, out valid, out ready (the reset's:
/// [`reset_words`]).
fn names(interface: Interface) -> (&'static str, &'static str, &'static str, &'static str) {
    match interface {
        Interface::Axis => (
            "s_axis_tvalid",
            "s_axis_tready",
            "m_axis_tvalid",
            "m_axis_tready",
        ),
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
            assert!(
                !seen[mask as usize],
                "{bits} bits: all ones is the one state left out"
            );
        }
    }
}
