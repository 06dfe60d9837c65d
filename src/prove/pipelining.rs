//! `prove --pipelining` and `prove --datapath`: miters against a twin of the unit.

use super::*;

/// The pipelining proof's properties, in words.
pub(super) const PIPELINING_PROPERTIES: [&str; 2] = [
    "after a reset, out_valid is the depth-0 twin's fed the same inputs `latency` edges late",
    "while out_valid is high, every output and the tag are the twin's",
];

/// The delay RAM's contract, in words (`templates/prove_delay_ram.v`).
pub(super) const DELAY_RAM_PROPERTY: &str =
    "each <top>_delay_ram the unit uses, alone: from the CUTS-th edge after power-up on, whatever rst does, q is d of CUTS edges before, as CUTS flip-flops in a row (k-induction with yosys sat)";

/// Proves the contract of `<top>_delay_ram` at `width` and `cuts` (`templates/prove_delay_ram.v`)
/// by k-induction with yosys's `sat`, over the unit's staged `files` (the module as shipped, its
/// lemma under `SPECGEN_CONTRACT`). `None`: proved; else the verdict that stops the proof.
fn delay_ram_contract(
    design: &Design,
    tools: &Tools,
    w: &Path,
    files: &[String],
    unit_defines: &[String],
    width: u32,
    cuts: u32,
) -> Result<Option<Verdict>, Error> {
    let top = design.cfg.top();
    let name = format!("{top}_delay_ram_contract_w{width}_c{cuts}");
    let file = format!("{name}.v");
    let mut all = files.to_vec();
    all.push(file.clone());
    // the module's lemmas make it inductive in a step or two; the base case searches CUTS + 4
    // edges from power-up, past the first edge the contract speaks of (a module without its
    // lemmas: a failure found there, or no verdict)
    let steps = cuts + 4;
    let script = Script {
        induction: Some(steps),
        defines: vec!["SPECGEN_CONTRACT".into()],
        unit_defines: unit_defines.to_vec(),
        ..Script::model(&name, &all)
    };
    script.write(w, "contract.ys")?;
    let mut said = None;
    for lemmas in [true, false] {
        let text = DelayRamContract {
            name: &name,
            top,
            version: crate::names::VERSION,
            width,
            cuts,
            lemmas,
        }
        .render()
        .expect("the contract renders")
            + "\n";
        put(w, &file, text)?;
        let _ = std::fs::remove_file(w.join("trace.vcd"));
        match run_watched(
            &tools.yosys,
            &["-s".into(), "contract.ys".into()],
            w,
            tools.limit,
            None,
            sat_progress,
        ) {
            // an edited module without the lemma ports: its contract alone (deleting lemmas can
            // only make the proof harder)
            Err(e) if lemmas && e.to_string().contains("does not have a port named 'f_") => {
                continue
            }
            ran => {
                said = Some(ran?);
                break;
            }
        }
    }
    let said = said.expect("the contract ran");
    Ok(
        match sat_verdict(&said, steps, tools, w, design, "the delay RAM's contract")? {
            Verdict::Proved => None,
            verdict => Some(verdict),
        },
    )
}

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
    let t0 = Instant::now();
    let mut files = design.stage_sim_models(w)?;
    let unit = design.stage(w)?;
    files.extend(unit.iter().cloned());
    // a delay line's tail in RAM keeps words longer than the pipeline's K + 1 edges (the checks
    // from any state cannot flush a memory): its module's contract is proved alone, for each
    // width and length the unit uses, and the unit is then read with the contract's model in
    // its place, CUTS flip-flops in a row free at power-up (every run of the module is one of
    // theirs), which the checks flush like every other register
    let rams = crate::emit::delay_rams(&design.plan);
    let name = format!("{top}_prove_pipelining");
    let tools = &Tools {
        yosys: crate::synth::absolute_tool(&tools.yosys),
        abc: crate::synth::absolute_tool(&tools.abc),
        ..tools.clone()
    };
    // one design: every step reads the unit as the check shows synthesis builds it
    let unit_defines =
        match super::built::one_design(design, tools, w, &unit, false, !rams.is_empty(), &name)? {
            Ok(d) => d,
            Err(proof) => return Ok(proof),
        };
    let mut overrides = Vec::new();
    for &(width, cuts) in &rams {
        if let Some(verdict) =
            delay_ram_contract(design, tools, w, &files, &unit_defines, width, cuts)?
        {
            let engine = format!("k-induction with yosys sat over {top}_delay_ram (WIDTH = {width}, CUTS = {cuts}) alone");
            return Ok(Proof {
                name: name.clone(),
                properties: vec![DELAY_RAM_PROPERTY],
                verdict,
                seconds: t0.elapsed().as_secs_f64(),
                engine,
                ports: None,
            });
        }
    }
    if !rams.is_empty() {
        let ideal = DelayRamIdeal {
            top,
            version: crate::names::VERSION,
            proved: &rams,
        }
        .render()
        .expect("the model renders")
            + "\n";
        put(w, "delay_ram_proved.v", ideal)?;
        overrides.push("delay_ram_proved.v".to_string());
    }
    // the twin: the same parameters at depth 0, its files by its own names beside the unit's
    // (its simulation models, under sim/, are the unit's)
    let twin_params = crate::config::Params {
        stages: 0,
        top: twin_top.clone(),
        ..cfg.params.clone()
    };
    files.extend(stage_twin(design, w, twin_params)?);
    let file = format!("{top}_prove_ports.v");
    put(
        w,
        &file,
        crate::cosim::adapter::adapter_named(cfg, &format!("{top}_prove_ports")),
    )?;
    files.push(file);
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
        let text = PipeliningScript {
            version: crate::names::VERSION,
            harness: &name,
            files: &files,
            overrides: &overrides,
            replay_steps,
            replay_skip,
            environment: super::environment_of(&name),
            unit_defines: unit_defines.clone(),
        }
        .render()
        .expect("the script renders")
            + "\n";
        put(w, file, text)
    };
    script(None, "models.ys")?;
    let (yosys, abc) = (
        crate::synth::absolute_tool(&tools.yosys),
        crate::synth::absolute_tool(&tools.abc),
    );
    run(
        &yosys,
        &["-q".into(), "-s".into(), "models.ys".into()],
        w,
        Duration::from_secs(600),
    )?
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
                break 'checks Verdict::Undecided {
                    bounded: None,
                    out_of_time: true,
                    reached: None,
                };
            };
            if said.contains("UNSATISFIABLE") {
                continue;
            }
            if !said.contains("SATISFIABLE") {
                return Err(error::tool(
                    &abc,
                    format!("iprove neither proved nor refuted the miter: {said}"),
                ));
            }
            script(Some(replay), "replay.ys")?;
            let found = run_sat(&yosys, w, "replay.ys", tools.limit)? == Some(false);
            if replay.1 > 0 && !found {
                // no run reaches the failing state from the replay's: state kept beyond K + 1 edges
                let keeps = match rams.is_empty() {
                    false => "a delay line in block RAM, its pointers never flushed; generate it with fewer stages or narrower widths (no delay line in memory) to prove it".to_string(),
                    true => format!("state specgen's unit of these parameters does not have (it writes no delay line in memory at --stages {k}): a register or memory of this RTL keeps values longer than its {k} stages; find what does, or compare with a unit generated afresh"),
                };
                break 'checks Verdict::Incomplete {
                    bounded: frames,
                    keeps,
                };
            }
            break 'checks Verdict::Failed {
                frame: replay.0 - 1,
                vcd: trace(&yosys, w, design)?,
            };
        }
        Verdict::Proved
    };
    let mut properties = PIPELINING_PROPERTIES.to_vec();
    let mut engine = PIPELINING.to_string();
    if !rams.is_empty() {
        properties.push(DELAY_RAM_PROPERTY);
        let each: Vec<String> = rams
            .iter()
            .map(|(w, c)| format!("WIDTH = {w}, CUTS = {c}"))
            .collect();
        engine = format!(
            "{engine}, the delay RAM's contract proved alone ({}) and its model in its place",
            each.join("; ")
        );
    }
    Ok(Proof {
        name,
        properties,
        verdict,
        seconds: t0.elapsed().as_secs_f64(),
        engine,
        ports: None,
    })
}

/// Writes the twin `params` describe (its own top, its files by their own names) into `w`,
/// beside the unit's, with its co-simulation adapter `<top>_prove_ports`: the Verilog to read.
/// Its simulation models (under `sim/`) are the unit's, staged with them.
pub(super) fn stage_twin(
    design: &Design,
    w: &Path,
    params: crate::config::Params,
) -> Result<Vec<String>, Error> {
    let top = params.top.clone();
    let twin = crate::plan::Plan::from_params(params)
        .map_err(|e| error::input(format!("the twin {top} of {}: {e}", design.dir.display())))?;
    let mut files = Vec::new();
    for (name, bytes) in crate::emit::generate_files(&twin)
        .into_iter()
        .filter(|(name, _)| !name.contains('/'))
    {
        put(w, &name, bytes)?;
        if name.ends_with(".v") {
            files.push(name);
        }
    }
    let file = format!("{top}_prove_ports.v");
    put(
        w,
        &file,
        crate::cosim::adapter::adapter_named(&twin.cfg, &format!("{top}_prove_ports")),
    )?;
    files.push(file);
    Ok(files)
}

/// The module name of `top`'s datapath twin (`prove --datapath`).
pub(super) fn datapath_twin_name(top: &str) -> String {
    format!("{top}_datapath")
}

/// The datapath proof's property, in words.
pub(super) const DATAPATH_PROPERTY: &str =
    "the datapath: the n-th result delivered (every output field) is what the unit's `valid` twin computes for the n-th pixel taken (with a static colour: the colour loaded at an enabled edge before it was taken)";
/// The datapath proof's cover, in words.
pub(super) const DATAPATH_COVER: &str = "a delivered result compared with the twin's";

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
/// set aside and every port rule of the checker kept; its cover, a result compared, must be
/// reached. Then, without `--depth`, the same for every edge: k-induction with the unit's
/// assertions as lemmas, the checker handing them the twin's result for the followed pixel,
/// which the unit's lemma finds at the pixel's rank in the buffer (at most `stages` + 4 edges:
/// where the two pipelines are not merged, a value is known from its last `stages` inputs).
/// That the twin is right is the co-simulation's and `--pipelining`'s (the twin against its
/// depth-0 twin).
pub fn prove_datapath(design: &Design, tools: &Tools) -> Result<Proof, Error> {
    if let Some(why) = datapath_refused(design) {
        return Err(error::input(format!("prove --datapath: {why}")));
    }
    let t0 = Instant::now();
    let depth = tools.depth.unwrap_or_else(|| port_depth(&design.cfg));
    let twin = datapath_twin_name(design.cfg.top());
    let then = if tools.depth.is_none() {
        format!(", then for every edge: k-induction with yosys sat (at most {} edges), the unit's assertions its lemmas", twin_steps(&design.cfg))
    } else {
        String::new()
    };
    let engine = format!(
        "the port checker (from the manifest) with the datapath twin {twin}, a bounded search of {depth} edges from power-up with ABC bmc3, the unit's own assertions set aside{then}"
    );
    // one design: every step reads the unit as the check shows synthesis builds it
    let unit_defines = {
        let work = crate::process::temp_dir().map_err(|e| error::tool("prove", e.to_string()))?;
        let unit = design.stage(work.path())?;
        let tools = &Tools {
            yosys: crate::synth::absolute_tool(&tools.yosys),
            ..tools.clone()
        };
        let lemmas = states_its_own_assertions(design)?;
        match super::built::one_design(
            design,
            tools,
            work.path(),
            &unit,
            lemmas,
            false,
            &harness_name(design.cfg.top()),
        )? {
            Ok(d) => d,
            Err(proof) => return Ok(proof),
        }
    };
    let (verdict, ports) = against_the_twin(design, tools, depth, false, &unit_defines)?;
    let mut properties = vec![DATAPATH_PROPERTY];
    if matches!(verdict, Verdict::Failed { .. }) {
        properties.extend(PORT_PROPERTIES);
    }
    Ok(Proof {
        name: harness_name(design.cfg.top()),
        properties,
        verdict,
        seconds: t0.elapsed().as_secs_f64(),
        engine,
        ports,
    })
}

/// The value check's property, in words (the default proof of a per-pixel colour).
pub(super) const VALUE_PROPERTY: &str =
    "the values at cos_g = 1.0 and n = 1: a result delivered carries the datapath twin's, every bit of the intensity and of each colour in its place";
/// The colour check's property, in words (the default proof of a static colour).
pub(super) const COLOUR_PROPERTY: &str =
    "with a static colour: a result delivered for a pixel at cos_g = 1.0 is the one computed with the colour loaded at an enabled edge before it was taken (the datapath twin's)";

/// The search of [`prove_datapath`] in a work directory of its own, to `depth` edges: the
/// verdict, and the ports' figures when every property holds and the compare is reached. With
/// `colour_only`, the harness holds every pixel at cos_g = 1.0 and n = 1 (`SPECGEN_COLOUR`): the
/// intensity folds to a constant in the unit and its twin alike, so what is left to compare is
/// the colour each result was computed with (a material register loaded at a disabled edge),
/// cheap at any width.
pub(super) fn against_the_twin(
    design: &Design,
    tools: &Tools,
    depth: u32,
    colour_only: bool,
    unit_defines: &[String],
) -> Result<(Verdict, Option<Ports>), Error> {
    // the colour check stays a bounded search: its induction closes (k = 3 at 11 stages, narrow
    // widths) but takes minutes there, unmeasured at default widths
    let for_every_edge = tools.depth.is_none() && !colour_only;
    let cfg = &design.cfg;
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
    put(
        w,
        "ports.v",
        crate::cosim::adapter::adapter_named(cfg, &format!("{top}_prove_ports")),
    )?;
    put(w, "harness.v", harness(design))?;
    files.push("ports.v".into());
    files.push("harness.v".into());
    let files = with_port_checker(design, w, &files)?;
    let (yosys, abc) = (
        crate::synth::absolute_tool(&tools.yosys),
        crate::synth::absolute_tool(&tools.abc),
    );
    let tools = &Tools {
        yosys,
        abc,
        ..tools.clone()
    };
    let name = harness_name(top);
    let mut defines = vec!["SPECGEN_PORTS".to_string(), "SPECGEN_DATAPATH".to_string()];
    if colour_only {
        defines.push("SPECGEN_COLOUR".into());
    }
    let script = Script {
        bounded: Some(depth),
        induction: Some(depth),
        defines,
        ports_only: Some(format!("{top}_port_checker")),
        share: true,
        merge_passes: cfg.stages() + 2,
        unit_defines: unit_defines.to_vec(),
        ..Script::model(&name, &files)
    };
    Ok(match search(design, tools, w, script.clone(), depth)? {
        Searched::Found { frame, vcd } => (Verdict::Failed { frame, vcd }, None),
        Searched::OutOfTime { reached } => (
            Verdict::Undecided {
                bounded: reached,
                out_of_time: true,
                reached,
            },
            None,
        ),
        Searched::Clear => {
            let mut defines = script.defines.clone();
            defines.extend([
                "SPECGEN_COVERS".to_string(),
                format!("SPECGEN_COVER_MASK=7'd{}", 1 << 6),
            ]);
            let covering = Script {
                defines,
                ..script.clone()
            };
            match search_with(
                design,
                &Tools {
                    progress: None,
                    ..tools.clone()
                },
                w,
                covering,
                depth,
                tools.cover_trace,
            )? {
                Searched::Found { frame, vcd } => {
                    let cover_vcd = tools.cover_trace.then_some(vcd);
                    // then for every edge, unless a bounded search was asked for (--depth): the
                    // unit's lemmas place the followed pixel's result in the buffer, the twin's
                    let unbounded = if !for_every_edge {
                        Unbounded::NotTried
                    } else {
                        match unbounded(design, tools, w, &script, twin_steps(cfg))? {
                            Ok(u) => u,
                            Err((frame, vcd)) => return Ok((Verdict::Failed { frame, vcd }, None)),
                        }
                    };
                    let verdict = match unbounded {
                        Unbounded::Proved { .. } => Verdict::Proved,
                        Unbounded::Undecided { out_of_time, .. } => Verdict::Undecided {
                            bounded: Some(depth),
                            out_of_time,
                            reached: None,
                        },
                        Unbounded::NoLemmas | Unbounded::NotTried => Verdict::Bounded { depth },
                    };
                    let ports = Ports {
                        depth,
                        properties: PORT_PROPERTIES.to_vec(),
                        covers: vec![DATAPATH_COVER],
                        covered_by: frame,
                        cover_vcd,
                        unbounded,
                        bounded_only: Vec::new(),
                    };
                    (verdict, Some(ports))
                }
                Searched::Clear => (
                    Verdict::Unreached {
                        covers: vec![DATAPATH_COVER],
                        depth,
                    },
                    None,
                ),
                Searched::OutOfTime { reached } => (
                    Verdict::Undecided {
                        bounded: Some(depth),
                        out_of_time: true,
                        reached,
                    },
                    None,
                ),
            }
        }
    })
}
