//! The searches behind a proof: the SAT verdict of a bounded search, and induction over the
//! unit's lemmas (with the colour check where a colour is per pixel).

use super::*;

/// The verdict of a k-induction by yosys's `sat` (`said`, its log) bounded by `steps`: proved
/// when the step closes; a failure of the base case (a search from power-up) with its trace;
/// undecided when it ran out of time or depth. `what` names the properties in an error.
pub(super) fn sat_verdict(
    said: &Said,
    steps: u32,
    tools: &Tools,
    w: &Path,
    design: &Design,
    what: &str,
) -> Result<Verdict, Error> {
    let text = &said.text;
    let reached = sat_reached(text);
    Ok(if !said.ended {
        Verdict::Undecided {
            bounded: reached,
            out_of_time: true,
            reached,
        }
    } else if text.contains("Induction step proven: SUCCESS") {
        Verdict::Proved
    } else if text.contains("model found for base case: FAIL") {
        // the base case of length N failed: a failure N edges from power-up, its whole trace
        // in trace.vcd
        let frame = reached.unwrap_or(0) + 1;
        Verdict::Failed {
            frame,
            vcd: trace(&tools.yosys, w, design)?,
        }
    } else if text.contains("Reached maximum number of time steps") {
        Verdict::Undecided {
            bounded: Some(steps),
            out_of_time: false,
            reached: Some(steps),
        }
    } else {
        return Err(error::tool(
            &tools.yosys,
            format!(
                "yosys's sat neither proved nor refuted {what}: {}",
                tail(text)
            ),
        ));
    })
}

/// The handshake's proof: k-induction with yosys's `sat` over the unit's own assertions (its
/// buffer's stream rules and the invariants that make them inductive, `ifdef FORMAL` in the
/// RTL). The base case searches from the first reset, so a failure there is a real trace; the
/// step proves, from any state where every assertion held for k edges, that they hold at the
/// next. The depth is enough for a pixel to pass the pipeline and a full buffer (the correct
/// unit is proved at about its latency plus one; a fault may need the buffer filled to show).
pub(super) fn induction(
    design: &Design,
    tools: &Tools,
    w: &Path,
    files: &[String],
    unit_defines: &[String],
    name: &str,
    t0: Instant,
) -> Result<Proof, Error> {
    let cfg = &design.cfg;
    let steps = tools
        .depth
        .unwrap_or_else(|| cfg.latency() + crate::interface::buffer_places(cfg) as u32 + 4);
    let script = Script {
        bounded: tools.depth,
        induction: Some(steps),
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
        unit_defines: unit_defines.to_vec(),
        ..Script::model(name, files)
    };
    let mut properties = properties(design);
    let name = name.to_string();
    if let Some(depth) = tools.depth {
        // the port checker (written from the manifest, apart from the unit) joins the search:
        // deleting or weakening the unit's own assertions cannot hide a fault at its ports
        let port_files = with_port_checker(design, w, files)?;
        let at_ports = Script {
            bounded: Some(depth),
            files: &port_files,
            defines: vec!["SPECGEN_PORTS".into()],
            ..script.clone()
        };
        properties.extend(PORT_PROPERTIES);
        // the bounded search: the unit's assertions and the port checker's, to `depth` edges
        let mut engine = format!("a bounded search of {depth} edges from power-up, ABC bmc3 on the model with the datapath cut");
        let mut verdict = match search(design, tools, w, at_ports, depth)? {
            Searched::Clear => Verdict::Bounded { depth },
            Searched::Found { frame, vcd } => Verdict::Failed { frame, vcd },
            Searched::OutOfTime { reached } => Verdict::Undecided {
                bounded: reached,
                out_of_time: true,
                reached,
            },
        };
        if verdict == (Verdict::Bounded { depth }) {
            // the colour check to the same depth (as in the default proof); a depth too short
            // to compare a result says nothing of the colour: not listed
            match colour_check(design, tools, depth, unit_defines)? {
                None | Some((Verdict::Unreached { .. }, _)) => {}
                Some((Verdict::Bounded { .. }, _)) => properties.push(colour_property(cfg)),
                Some((colour, how)) => {
                    properties.push(colour_property(cfg));
                    (verdict, engine) = (colour, how);
                }
            }
        }
        return Ok(Proof {
            name,
            properties,
            verdict,
            seconds: t0.elapsed().as_secs_f64(),
            engine,
            ports: None,
        });
    }
    // a unit that states the assertions specgen writes is proved in one induction with the
    // port checker (its assertions the lemmas); one that states fewer has its own proved first
    // (the RTL's word), and its ports only searched
    let own = states_its_own_assertions(design)?;
    // the unit's own assertions by themselves: the engine in words, or the proof that ends here
    // (the unit read with its lemma port: the checker drives it, its assertions joining the unit's)
    let lemma_files = with_port_checker(design, w, files)?;
    let own_script = if unit_defines.iter().any(|d| d == "SPECGEN_LEMMAS") {
        Script {
            files: &lemma_files,
            defines: vec!["SPECGEN_PORTS".into()],
            ..script.clone()
        }
    } else {
        script.clone()
    };
    let own_induction = || -> Result<Result<String, Proof>, Error> {
        own_script.write(w, "induction.ys")?;
        let _ = std::fs::remove_file(w.join("trace.vcd"));
        let ran = run_watched(
            &tools.yosys,
            &["-s".into(), "induction.ys".into()],
            w,
            tools.limit,
            tools.progress,
            sat_progress,
        );
        let seconds = t0.elapsed().as_secs_f64();
        let said = ran?;
        let text = &said.text;
        let k = text.matches("Induction step failed").count() + 1;
        let engine = if text.contains("model found for base case: FAIL") {
            "k-induction's base case, a search from power-up with yosys sat".to_string()
        } else {
            format!("k-induction with yosys sat over the unit's own assertions, k = {k} of at most {steps}")
        };
        let verdict = sat_verdict(&said, steps, tools, w, design, "the properties")?;
        if verdict != Verdict::Proved {
            return Ok(Err(Proof {
                name: name.clone(),
                properties: properties.clone(),
                verdict,
                seconds,
                engine,
                ports: None,
            }));
        }
        Ok(Ok(engine))
    };
    if !own {
        if let Err(proof) = own_induction()? {
            return Ok(proof);
        }
    }
    // the verdict is the port checker's, written from the manifest apart from the RTL: its
    // bounded search with the unit's assertions set aside, its covers, then its properties
    // for every edge by induction with the unit's assertions as lemmas (deleting them can
    // only lose the unbounded part, never pass a broken unit)
    let ports = at_the_ports(design, tools, w, &script, own)?;
    let ports = match ports {
        AtPorts::Checked(p) => p,
        AtPorts::Failed { frame, vcd, how } => {
            let mut all = PORT_PROPERTIES.to_vec();
            all.extend(properties.iter().copied());
            let engine = format!("the port checker (from the manifest), {how}");
            return Ok(Proof {
                name,
                properties: all,
                verdict: Verdict::Failed { frame, vcd },
                seconds: t0.elapsed().as_secs_f64(),
                engine,
                ports: None,
            });
        }
        AtPorts::OutOfTime { reached } => {
            let engine = "the port checker's bounded search".to_string();
            let verdict = Verdict::Undecided {
                bounded: reached,
                out_of_time: true,
                reached,
            };
            return Ok(Proof {
                name,
                properties: PORT_PROPERTIES.to_vec(),
                verdict,
                seconds: t0.elapsed().as_secs_f64(),
                engine,
                ports: None,
            });
        }
        AtPorts::Unreached { covers, depth } => {
            let verdict = Verdict::Unreached { covers, depth };
            let engine = "the port checker's covers, a bounded search with ABC bmc3".to_string();
            return Ok(Proof {
                name,
                properties: PORT_PROPERTIES.to_vec(),
                verdict,
                seconds: t0.elapsed().as_secs_f64(),
                engine,
                ports: None,
            });
        }
    };
    let mut ports = ports;
    match colour_check(design, tools, port_depth(cfg), unit_defines)? {
        None => {}
        Some((Verdict::Proved, _)) => ports.properties.push(colour_property(cfg)),
        Some((Verdict::Bounded { .. }, _)) => ports.bounded_only.push(colour_property(cfg)),
        Some((verdict, engine)) => {
            let seconds = t0.elapsed().as_secs_f64();
            return Ok(Proof {
                name,
                properties: vec![colour_property(cfg)],
                verdict,
                seconds,
                engine,
                ports: None,
            });
        }
    }
    let seconds = t0.elapsed().as_secs_f64();
    if !own {
        // the unit does not state what specgen writes: the bounded search at the ports is all
        // that can be said
        let engine = format!(
            "the unit states no assertions of its own or fewer than specgen writes, so nothing is proved unbounded; the port checker, ABC bmc3 to {} edges",
            ports.depth
        );
        let depth = ports.depth;
        return Ok(Proof {
            name,
            properties: Vec::new(),
            verdict: Verdict::Bounded { depth },
            seconds,
            engine,
            ports: Some(ports),
        });
    }
    match ports.unbounded {
        Unbounded::Undecided { steps, out_of_time } => {
            // the unit states its lemmas, yet the induction at the ports did not close: not proved
            let engine = format!("the port checker's k-induction with the unit's assertions as lemmas (yosys sat, at most {steps} edges)");
            let verdict = Verdict::Undecided {
                bounded: Some(ports.depth),
                out_of_time,
                reached: None,
            };
            let mut all = PORT_PROPERTIES.to_vec();
            all.extend(properties.iter().copied());
            Ok(Proof {
                name,
                properties: all,
                verdict,
                seconds,
                engine,
                ports: None,
            })
        }
        Unbounded::Proved { k } => {
            let engine = format!(
                "k-induction with yosys sat over the port checker's properties and the unit's own assertions, its lemmas, k = {k} of at most {UNBOUNDED_STEPS}"
            );
            Ok(Proof {
                name,
                properties,
                verdict: Verdict::Proved,
                seconds,
                engine,
                ports: Some(ports),
            })
        }
        Unbounded::NoLemmas | Unbounded::NotTried => {
            // assertions enough but no lemma port (an edited unit): its own assertions proved by
            // themselves are its word; the verdict at the ports stays a bounded search
            match own_induction()? {
                Ok(how) => {
                    let depth = ports.depth;
                    let engine = format!(
                        "the port checker, ABC bmc3 to {depth} edges; the unit has no lemma port f_ports, so its own assertions were proved by themselves ({how}), the RTL's word, and its ports only searched"
                    );
                    Ok(Proof {
                        name,
                        properties,
                        verdict: Verdict::Bounded { depth },
                        seconds: t0.elapsed().as_secs_f64(),
                        engine,
                        ports: Some(ports),
                    })
                }
                Err(proof) => Ok(proof),
            }
        }
    }
}

/// A static colour's colour check to `depth` edges (none for another colour): which colour each
/// result was computed with, against the datapath twin at cos_g = 1.0 (the only value a port
/// rule cannot see without the datapath); its verdict, and how it was reached in words.
pub(super) fn colour_check(
    design: &Design,
    tools: &Tools,
    depth: u32,
    unit_defines: &[String],
) -> Result<Option<(Verdict, String)>, Error> {
    // every ready/axis unit: with a per-pixel colour too, the values at cos_g = 1.0 (an
    // intensity bit or a colour bit out of place at the ports is seen)
    let (verdict, _) = against_the_twin(design, tools, depth, true, unit_defines)?;
    let engine = format!(
        "the value check: the port checker (from the manifest) with the datapath twin, every pixel at cos_g = 1.0 and n = 1, a bounded search of {depth} edges with ABC bmc3, the unit's own assertions set aside"
    );
    Ok(Some((verdict, engine)))
}

/// The value check's property for `cfg`, in words.
pub(super) fn colour_property(cfg: &crate::config::Config) -> &'static str {
    if cfg.colour() == crate::config::Colour::Static {
        COLOUR_PROPERTY
    } else {
        VALUE_PROPERTY
    }
}
