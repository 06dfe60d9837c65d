//! The outside checker at the unit's ports: its bounded search, its covers, its verdict.

use super::*;

/// How the port checker's runs ended.
pub(super) enum AtPorts {
    Checked(Ports),
    /// a property fails `frame` edges in; `how` names the search that found it
    Failed {
        frame: u32,
        vcd: Vec<u8>,
        how: String,
    },
    OutOfTime {
        reached: Option<u32>,
    },
    Unreached {
        covers: Vec<&'static str>,
        depth: u32,
    },
}

/// The covers of the port checker, each with its bit in `SPECGEN_COVER_MASK`; `tlast` and a
/// static colour's load only where the unit has them.
pub(super) fn covers(cfg: &crate::config::Config) -> Vec<(u32, &'static str)> {
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
pub(super) fn port_depth(cfg: &crate::config::Config) -> u32 {
    cfg.latency() + 8
}

/// The cover search's depth: every cover in one run, the unit filled and drained once.
pub(super) fn cover_depth(cfg: &crate::config::Config) -> u32 {
    cfg.latency() + 2 * crate::interface::buffer_places(cfg) as u32 + 12
}

/// Writes the port checker into the work directory `w`: `files` and it, for a script to read.
pub(super) fn with_port_checker(
    design: &Design,
    w: &Path,
    files: &[String],
) -> Result<Vec<String>, Error> {
    put(w, "port_checker.v", port_checker(design))?;
    let mut all = files.to_vec();
    all.push("port_checker.v".into());
    Ok(all)
}

/// The port checker's bounded search (its assertions only), then its covers, then (`lemmas`:
/// the unit states the assertions specgen writes) its properties for every edge.
pub(super) fn at_the_ports(
    design: &Design,
    tools: &Tools,
    w: &Path,
    script: &Script,
    lemmas: bool,
) -> Result<AtPorts, Error> {
    let cfg = &design.cfg;
    let files = with_port_checker(design, w, script.files)?;
    let checker = format!("{}_port_checker", cfg.top());
    let depth = port_depth(cfg);
    let ports = Script {
        bounded: Some(depth),
        files: &files,
        defines: vec!["SPECGEN_PORTS".into()],
        ports_only: Some(checker.clone()),
        ..script.clone()
    };
    // the first search keeps the unit's own assertions beside the checker's: a fault they see
    // is refuted here, within the depth, and named
    let first = Script {
        ports_only: None,
        ..ports.clone()
    };
    match search(design, tools, w, first, depth)? {
        Searched::Clear => {}
        Searched::Found { frame, vcd } => {
            // which failed: the checker's rules alone, searched again to the same depth
            let how = match search_with(design, &Tools { progress: None, ..tools.clone() }, w, ports.clone(), depth, false)? {
                Searched::Found { .. } => "a bounded search with ABC bmc3 over its assertions and the unit's own; a rule at the ports fails",
                _ => "a bounded search with ABC bmc3 over its assertions and the unit's own; the unit's own assertion fails, the rules at the ports hold to that depth",
            };
            return Ok(AtPorts::Failed {
                frame,
                vcd,
                how: how.into(),
            });
        }
        Searched::OutOfTime { reached } => return Ok(AtPorts::OutOfTime { reached }),
    }
    let all = covers(cfg);
    let reach = |mask: u32, depth: u32, replay: bool| -> Result<Searched, Error> {
        let defines = vec![
            "SPECGEN_PORTS".to_string(),
            "SPECGEN_COVERS".to_string(),
            format!("SPECGEN_COVER_MASK=7'd{mask}"),
        ];
        let covering = Script {
            bounded: Some(depth),
            files: &files,
            defines,
            ports_only: Some(checker.clone()),
            ..script.clone()
        };
        // (its depths are not "no failure": a cover not reached yet)
        search_with(
            design,
            &Tools {
                progress: None,
                ..tools.clone()
            },
            w,
            covering,
            depth,
            replay,
        )
    };
    let cdepth = cover_depth(cfg);
    let mask = all.iter().fold(0, |m, (bit, _)| m | 1 << bit);
    match reach(mask, cdepth, tools.cover_trace)? {
        Searched::Found { frame, vcd } => {
            let cover_vcd = tools.cover_trace.then_some(vcd);
            let unbounded = match lemmas.then(|| unbounded(design, tools, w, &ports, UNBOUNDED_STEPS)).transpose()? {
                None => Unbounded::NoLemmas,
                Some(Ok(u)) => u,
                Some(Err((frame, vcd))) => {
                    return Ok(AtPorts::Failed {
                        frame,
                        vcd,
                        how: "k-induction's base case with the unit's lemmas (a port property or a lemma), a search from power-up with yosys sat".into(),
                    })
                }
            };
            Ok(AtPorts::Checked(Ports {
                depth,
                properties: PORT_PROPERTIES.to_vec(),
                covers: all.iter().map(|c| c.1).collect(),
                covered_by: frame,
                cover_vcd,
                unbounded,
                bounded_only: Vec::new(),
            }))
        }
        Searched::OutOfTime { reached } => Ok(AtPorts::OutOfTime { reached }),
        Searched::Clear => {
            // not all in one run: which cannot be reached
            let mut unreached = Vec::new();
            for (bit, what) in &all {
                if matches!(reach(1 << bit, cdepth, false)?, Searched::Clear) {
                    unreached.push(*what);
                }
            }
            Ok(AtPorts::Unreached {
                covers: unreached,
                depth: cdepth,
            })
        }
    }
}

/// The edges the unbounded proof at the ports may unroll. The unit's lemmas tie every register
/// the checker keeps to the unit's own, so the induction closes within a few edges at any
/// depth (k = 3 on every unit measured, 0 to 13 stages); a deeper bound would only spend time
/// on a unit whose lemmas fall short, which is then undecided, never proved.
pub(super) const UNBOUNDED_STEPS: u32 = 6;

/// The edges the unbounded proof against the `valid` twin may unroll (`prove --datapath`, the
/// colour check): the port proof's, or enough to flush a pipeline of `stages` registers should
/// a stage of the unit's and the twin's stay unmerged (a value computed apart from its twin's
/// is known only from the inputs of its last `stages` edges); merged, they close at k = 3.
pub(super) fn twin_steps(cfg: &crate::config::Config) -> u32 {
    UNBOUNDED_STEPS.max(cfg.stages() + 4)
}

/// The port checker's properties proved unbounded: k-induction with yosys's `sat` over the
/// checker's assertions and the unit's own, its lemmas (`SPECGEN_LEMMAS`) reading the checker's
/// state through the port `f_ports`. The checker's assertions decide: a lemma is an assertion
/// too, so a false one fails the proof and a missing one leaves it undecided, and the checker
/// is written from the manifest, never read from the unit. A failure from power-up (the base
/// case) is `Err` with its edge and trace.
/// (`script`: the checker's search, whose files and defines it keeps; `steps`: the most edges.)
#[allow(clippy::type_complexity)]
pub(super) fn unbounded(
    design: &Design,
    tools: &Tools,
    w: &Path,
    script: &Script,
    steps: u32,
) -> Result<Result<Unbounded, (u32, Vec<u8>)>, Error> {
    let mut defines = script.defines.clone();
    defines.push("SPECGEN_LEMMAS".into());
    let lemmas = Script {
        bounded: None,
        induction: Some(steps),
        defines,
        ports_only: None,
        sat_search: None,
        replay: false,
        ..script.clone()
    };
    lemmas.write(w, "lemmas.ys")?;
    let _ = std::fs::remove_file(w.join("trace.vcd"));
    let said = match run_watched(
        &tools.yosys,
        &["-s".into(), "lemmas.ys".into()],
        w,
        tools.limit,
        tools.progress,
        sat_progress,
    ) {
        // an edited unit without the lemma port: the bounded search is what there is
        Err(e)
            if e.to_string()
                .contains("does not have a port named 'f_ports'") =>
        {
            return Ok(Ok(Unbounded::NoLemmas))
        }
        ran => ran?,
    };
    let k = said.text.matches("Induction step failed").count() as u32 + 1;
    Ok(
        match sat_verdict(
            &said,
            steps,
            tools,
            w,
            design,
            "the port checker's properties",
        )? {
            Verdict::Proved => Ok(Unbounded::Proved { k }),
            Verdict::Failed { frame, vcd } => Err((frame, vcd)),
            Verdict::Undecided { out_of_time, .. } => {
                Ok(Unbounded::Undecided { steps, out_of_time })
            }
            other => unreachable!("sat_verdict gives no {other:?}"),
        },
    )
}

/// The port checker's properties, in words (`templates/prove_port_checker.v`).
pub(super) const PORT_PROPERTIES: [&str; 6] = [
    "at the ports (from the manifest): a transfer is valid, ready, enabled and no reset; a reset leaves out_valid and in_ready low",
    "at the ports: a result not taken (out_ready low or the edge disabled) stays, every output field, the tag and tlast unchanged",
    "at the ports: never more pixels taken and not delivered than places, no result without one",
    "at the ports: in_ready high exactly when, three cycles before, fewer than places - 3 were inside (SPEC §7)",
    "at the ports: the n-th result delivered carries the n-th pixel's tag and tlast (a scoreboard)",
    "at the ports, bounded response: with the consumer ready a result owed leaves within latency + 2 edges, and in_ready rises within latency + places + 4",
];

/// How a bounded search ended.
pub(super) enum Searched {
    /// no assertion fails within the depth
    Clear,
    /// one fails `frame` edges in; the run's VCD
    Found { frame: u32, vcd: Vec<u8> },
    /// stopped at the time limit, `reached` frames searched
    OutOfTime { reached: Option<u32> },
}

/// A bounded search of `depth` edges from power-up of `script`'s model: yosys writes it as an
/// AIGER, ABC's bmc3 searches it, and a failure is simulated by yosys on the same model to a VCD.
pub(super) fn search(
    design: &Design,
    tools: &Tools,
    w: &Path,
    script: Script,
    depth: u32,
) -> Result<Searched, Error> {
    search_with(design, tools, w, script, depth, true)
}

/// [`search`], with the counterexample replayed to a VCD only when `replay` (a cover's trace
/// only when asked for: `--cover-trace`).
pub(super) fn search_with(
    design: &Design,
    tools: &Tools,
    w: &Path,
    script: Script,
    depth: u32,
    replay: bool,
) -> Result<Searched, Error> {
    script.write(w, "model.ys")?;
    run(
        &tools.yosys,
        &["-q".into(), "-s".into(), "model.ys".into()],
        w,
        tools.limit,
    )?
    .ok_or_else(|| {
        error::tool(
            &tools.yosys,
            format!(
                "yosys did not write the model within {} s (--time-limit)",
                tools.limit.as_secs()
            ),
        )
    })?;
    let _ = std::fs::remove_file(w.join("cex.aiw"));
    let abc_script =
        format!("read_aiger model.aig; fold; bmc3 -F {depth} -v; write_cex -a cex.aiw");
    let said = run_watched(
        &tools.abc,
        &["-c".into(), abc_script],
        w,
        tools.limit,
        tools.progress,
        bmc_progress,
    )?;
    if !said.ended {
        return Ok(Searched::OutOfTime {
            reached: bmc_reached(&said.text),
        });
    }
    match frame_asserted(&said.text) {
        Some(frame) if !replay => Ok(Searched::Found {
            frame,
            vcd: Vec::new(),
        }),
        Some(frame) => {
            yosys_witness(w)?;
            Script {
                replay: true,
                ..script.clone()
            }
            .write(w, "replay.ys")?;
            let _ = std::fs::remove_file(w.join("trace.vcd"));
            let replayed = run(
                &tools.yosys,
                &["-q".into(), "-s".into(), "replay.ys".into()],
                w,
                tools.limit,
            );
            if matches!(&replayed, Err(e) if without_sim(e)) {
                // YoWASP's yosys has no `sim`: its `sat` searches the failing run's edges again
                // (sat's first step is the state before the first edge: ABC's frame f is step f + 2)
                let steps = frame + 2;
                Script {
                    sat_search: Some(steps),
                    ..script
                }
                .write(w, "replay.ys")?;
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
                replayed?.ok_or_else(|| {
                    error::tool(
                        &tools.yosys,
                        format!(
                            "yosys did not replay the counterexample within {} s",
                            tools.limit.as_secs()
                        ),
                    )
                })?;
            }
            Ok(Searched::Found {
                frame,
                vcd: trace(&tools.yosys, w, design)?,
            })
        }
        None if said.text.contains("No output asserted") => Ok(Searched::Clear),
        None => Err(error::tool(
            &tools.abc,
            format!(
                "bmc3 neither found a failure nor finished its {depth} frames: {}",
                tail(&said.text)
            ),
        )),
    }
}
