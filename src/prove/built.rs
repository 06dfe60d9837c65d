//! The design proved is the design built: one elaboration for every step of a proof, shown
//! equal at the ports to the RTL as synthesis reads it.
//!
//! Every step of a proof (the bounded search, the covers, the induction) reads the unit's files
//! with one set of macros (`FORMAL` and the flow's own, [`unit_defines`]), apart from specgen's
//! harness files, so no step proves a design another does not. Before any step, yosys
//! elaborates the unit twice — as synthesis reads it (`SYNTHESIS`, no `FORMAL`, no `SPECGEN_*`)
//! and as the proof reads it, with its formal cells (assert, assume, cover) and the logic only
//! they read removed — and proves the two equal at every port bit of the built one: its
//! registers matched by name, their first values compared, each signal then proved equal
//! alone or by induction (`equiv_simple`, `equiv_induct`). A formal-only port is removed, an
//! input among them left free, so a built result that reads one cannot be proved equal. A
//! unit whose formal regions change what is built (an `` `ifdef FORMAL `` or `` `else ``
//! branch that drives a built signal, a register whose first value differs) is refused with
//! the bits that differ: a proof of it would be a proof of a design nobody builds.

use super::*;
use std::collections::BTreeMap;

#[derive(Template)]
#[template(path = "prove_built.ys")]
struct BuiltScript<'a> {
    version: &'a str,
    /// "built", "formal" or "equiv"
    step: &'a str,
    top: &'a str,
    libs: &'a [String],
    unit: &'a [String],
    defines: &'a [String],
    formal_only: Vec<String>,
}

/// The macros every step of a proof reads the unit with, beyond `FORMAL` and `SYNTHESIS`:
/// `lemmas`, a handshake unit's lemma port (`SPECGEN_LEMMAS`); `contract`, the delay RAM's
/// lemmas (`SPECGEN_CONTRACT`, `prove --pipelining`).
pub(super) fn unit_defines(lemmas: bool, contract: bool) -> Vec<String> {
    let mut d = Vec::new();
    if lemmas {
        d.push("SPECGEN_LEMMAS".to_string());
    }
    if contract {
        d.push("SPECGEN_CONTRACT".to_string());
    }
    d
}

/// A module's ports and registers' first values, from yosys's RTLIL of it.
#[derive(Default, Debug, PartialEq)]
struct Elaboration {
    /// port name → "input"/"output"/"inout" and width
    ports: BTreeMap<String, (String, u32)>,
    /// wire name → its `init` attribute
    inits: BTreeMap<String, String>,
}

/// Reads the ports and `init` attributes of the module in RTLIL `text`.
fn elaboration(text: &str) -> Elaboration {
    let mut e = Elaboration::default();
    let mut init: Option<String> = None;
    for line in text.lines().map(str::trim) {
        if let Some(v) = line.strip_prefix("attribute \\init ") {
            init = Some(v.to_string());
            continue;
        }
        if let Some(rest) = line.strip_prefix("wire ") {
            let words: Vec<&str> = rest.split_whitespace().collect();
            let name = words
                .last()
                .copied()
                .unwrap_or("")
                .trim_start_matches('\\')
                .to_string();
            let width = words
                .iter()
                .position(|w| *w == "width")
                .and_then(|i| words.get(i + 1))
                .and_then(|w| w.parse().ok())
                .unwrap_or(1);
            if let Some(dir) = words
                .iter()
                .find(|w| matches!(**w, "input" | "output" | "inout"))
            {
                e.ports.insert(name.clone(), (dir.to_string(), width));
            }
            if let Some(v) = init.take() {
                e.inits.insert(name, v);
            }
            continue;
        }
        if !line.starts_with("attribute ") {
            init = None;
        }
    }
    e
}

/// What [`check`] found.
pub(super) struct Checked {
    /// what differs between the built design and the proved one, in words (none: equal)
    pub(super) differs: Option<String>,
    /// the formal elaboration has the lemma port `f_ports`
    pub(super) lemma_port: bool,
}

/// Proves that the unit of `design` as every step of its proof reads it (its `unit` files, as
/// staged in `w`, with `defines`) is the design synthesis builds.
pub(super) fn check(
    design: &Design,
    tools: &Tools,
    w: &Path,
    unit: &[String],
    defines: &[String],
) -> Result<Checked, Error> {
    let (differs, lemma_port) = differs_from_built(design, tools, w, unit, defines)?;
    Ok(Checked {
        differs,
        lemma_port,
    })
}

fn differs_from_built(
    design: &Design,
    tools: &Tools,
    w: &Path,
    unit: &[String],
    defines: &[String],
) -> Result<(Option<String>, bool), Error> {
    let top = design.cfg.top();
    let libs: Vec<String> = match crate::family::of(design.cfg.target())
        .primitive_boxes()
        .filter(|_| !design.sim_models.is_empty())
    {
        Some(lib) => vec![format!("-lib {lib}")],
        None => Vec::new(),
    };
    let script = |step: &str, formal_only: Vec<String>| -> Result<(), Error> {
        let text = BuiltScript {
            version: crate::names::VERSION,
            step,
            top,
            libs: &libs,
            unit,
            defines,
            formal_only,
        }
        .render()
        .expect("the script renders")
            + "\n";
        put(w, &format!("built_{step}.ys"), text)
    };
    let elaborate = |step: &str| -> Result<Elaboration, Error> {
        script(step, Vec::new())?;
        match run(
            &tools.yosys,
            &["-q".into(), "-s".into(), format!("built_{step}.ys")],
            w,
            tools.limit,
        ) {
            Err(e)
                if e.to_string().contains("select -assert-none")
                    || e.to_string().contains("selection is not empty") =>
            {
                // "Selection contains:\n<module>\n<module>/<wire>…": the modules named
                let text = e.to_string();
                let named: Vec<&str> = text
                    .split("Selection contains:")
                    .nth(1)
                    .unwrap_or("")
                    .split_whitespace()
                    .filter(|m| !m.contains('/'))
                    .take(4)
                    .collect();
                return Err(error::input(format!(
                    "{}: a module of the unit takes the name of one of specgen's proof modules ({top}_prove_*, {top}_port_checker, {top}_datapath*, {top}_depth0*, {top}_delay_ram_contract*){}: it would stand in for the harness; rename it",
                    design.dir.display(),
                    if named.is_empty() { String::new() } else { format!(": {}", named.join(", ")) }
                )));
            }
            ran => ran?.ok_or_else(|| {
                error::tool(
                    &tools.yosys,
                    format!(
                        "yosys did not elaborate the unit within {} s (--time-limit)",
                        tools.limit.as_secs()
                    ),
                )
            })?,
        };
        let text = crate::small_file::read(&w.join(format!("{step}.il")), 1 << 30)
            .map_err(|e| error::tool(&tools.yosys, format!("{step}.il: {e}")))?;
        Ok(elaboration(&text))
    };
    let built = elaborate("built")?;
    let formal = elaborate("formal")?;
    // what no proof is handed: an input the unit drives, a second clock, a latch (in the
    // design built and in the one the proof reads)
    let clock = crate::emit::clock_port(&design.cfg);
    let mut refused: Vec<String> = Vec::new();
    for step in ["built", "formal"] {
        let json = crate::small_file::read(&w.join(format!("{step}.json")), 1 << 30)
            .map_err(|e| error::tool(&tools.yosys, format!("{step}.json: {e}")))?;
        for why in super::netlist::refusals(&json, step, clock) {
            if !refused.contains(&why) {
                refused.push(why);
            }
        }
    }
    if !refused.is_empty() {
        let more = if refused.len() > 8 {
            format!("; and {} more", refused.len() - 8)
        } else {
            String::new()
        };
        return Err(error::input(format!(
            "{}: not a unit a proof can be handed: {}{more}",
            design.dir.display(),
            refused[..refused.len().min(8)].join("; ")
        )));
    }
    let lemma_port = formal.ports.contains_key("f_ports") && !built.ports.contains_key("f_ports");
    let mut differ = Vec::new();
    for (port, (dir, width)) in &built.ports {
        match formal.ports.get(port) {
            None => differ.push(format!("the port {port} is not in the formal elaboration")),
            Some((d, wd)) if d != dir || wd != width => differ.push(format!(
                "the port {port} is {dir} [{width}] built, {d} [{wd}] in the proof"
            )),
            Some(_) => {}
        }
    }
    for (reg, init) in &built.inits {
        match formal.inits.get(reg) {
            Some(i) if i != init => {
                differ.push(format!("{reg} starts at {init} built, at {i} in the proof"))
            }
            _ => {}
        }
    }
    for (reg, init) in &formal.inits {
        if !built.inits.contains_key(reg)
            && !built.ports.contains_key(reg)
            && text_has_wire(w, reg)?
        {
            differ.push(format!(
                "{reg} starts at {init} in the proof and has no first value built"
            ));
        }
    }
    if !differ.is_empty() {
        return Ok((Some(differ.join("; ")), lemma_port));
    }
    let formal_only: Vec<String> = formal
        .ports
        .keys()
        .filter(|p| !built.ports.contains_key(*p))
        .cloned()
        .collect();
    script("equiv", formal_only)?;
    let said = run_watched(
        &tools.yosys,
        &["-s".into(), "built_equiv.ys".into()],
        w,
        tools.limit,
        None,
        |_| None,
    );
    match said {
        Ok(s) if !s.ended => Err(error::tool(
            &tools.yosys,
            format!("the check that the proved design is the built one did not end within {} s (--time-limit)", tools.limit.as_secs()),
        )),
        Ok(_) => Ok((None, lemma_port)),
        Err(e) if e.to_string().contains("unproven $equiv") => {
            // "Unproven $equiv $auto$…: \m_axis_tdata_gold [0] \m_axis_tdata_gate [0]"
            let text = crate::small_file::read(&w.join("equiv_status.log"), 1 << 30).unwrap_or_else(|_| e.to_string());
            // the signals, each with its bits: the built unit's ports first
            let mut signals: BTreeMap<String, Vec<String>> = BTreeMap::new();
            for equal in text.lines().filter_map(|l| l.trim().strip_prefix("Unproven $equiv ")).filter_map(|l| l.split(": ").nth(1)) {
                let gold = equal.split(" \\").next().unwrap_or("").trim_start_matches('\\');
                let (signal, bit) = gold.split_once(' ').unwrap_or((gold, ""));
                let signal = signal.strip_suffix("_gold").unwrap_or(signal).to_string();
                signals.entry(signal).or_default().push(bit.trim_matches(|c| c == '[' || c == ']').to_string());
            }
            let (ports, inside): (Vec<_>, Vec<_>) = signals.into_iter().partition(|(s, _)| built.ports.contains_key(s));
            let say = |list: &[(String, Vec<String>)]| -> String {
                list.iter()
                    .take(8)
                    .map(|(s, bits)| if bits.iter().all(String::is_empty) { s.clone() } else { format!("{s} (bit {})", bits.join(", ")) })
                    .collect::<Vec<_>>()
                    .join("; ")
            };
            let what = if ports.is_empty() {
                format!(
                    "not proved equal at the signals {}{}",
                    say(&inside),
                    if inside.len() > 8 { format!(" and {} more", inside.len() - 8) } else { String::new() }
                )
            } else {
                format!(
                    "not proved equal at the ports {}{}",
                    say(&ports),
                    if inside.is_empty() { String::new() } else { format!(", and {} signals inside", inside.len()) }
                )
            };
            Ok((Some(what), lemma_port))
        }
        Err(e) => Err(e),
    }
}

/// The engine of the check, in words.
pub(super) const ENGINE: &str =
    "yosys equiv: the RTL as synthesis reads it (no FORMAL, no SPECGEN_*) against the elaboration every step of the proof reads, its formal cells and formal-only ports removed, registers matched by name and their first values compared";

/// The macros every step of the proof of `design` reads its `unit` files with (`lemmas`: a
/// handshake unit's lemma port, where the unit has one; `contract`: the delay RAM's lemmas),
/// once that elaboration is shown to be the built design; else the proof that ends here,
/// `name` its harness.
pub(super) fn one_design(
    design: &Design,
    tools: &Tools,
    w: &Path,
    unit: &[String],
    lemmas: bool,
    contract: bool,
    name: &str,
) -> Result<Result<Vec<String>, Proof>, Error> {
    let t0 = Instant::now();
    let mut defines = unit_defines(lemmas, contract);
    let mut checked = check(design, tools, w, unit, &defines)?;
    if lemmas && !checked.lemma_port {
        // an edited unit without the lemma port: the elaboration without it, in every step
        defines = unit_defines(false, contract);
        checked = check(design, tools, w, unit, &defines)?;
    }
    match checked.differs {
        None => Ok(Ok(defines)),
        Some(differs) => Ok(Err(Proof {
            name: name.to_string(),
            properties: vec![BUILT_PROPERTY],
            verdict: Verdict::NotBuilt { differs },
            seconds: t0.elapsed().as_secs_f64(),
            engine: ENGINE.to_string(),
            ports: None,
        })),
    }
}

/// The check's property, in words.
pub(super) const BUILT_PROPERTY: &str =
    "the design proved is the one built: the unit as every step reads it equals, at every port bit, the RTL as synthesis reads it";

/// Whether the formal elaboration's `wire` named `reg` is a register the built one has under
/// another first value or none (a wire of the formal elaboration only is no difference).
fn text_has_wire(w: &Path, reg: &str) -> Result<bool, Error> {
    let built = crate::small_file::read(&w.join("built.il"), 1 << 30)
        .map_err(|e| error::tool("yosys", format!("built.il: {e}")))?;
    Ok(built
        .lines()
        .any(|l| l.trim().starts_with("wire ") && l.trim().ends_with(&format!("\\{reg}"))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rtlil_reader_finds_ports_and_first_values() {
        let il = "module \\built\n  attribute \\init 1'0\n  wire \\fz\n  wire width 48 output 3 \\m_axis_tdata\n  wire input 1 \\clk\n  attribute \\src \"x\"\n  wire \\plain\nend\n";
        let e = elaboration(il);
        assert_eq!(
            e.ports.get("m_axis_tdata"),
            Some(&("output".to_string(), 48))
        );
        assert_eq!(e.ports.get("clk"), Some(&("input".to_string(), 1)));
        assert_eq!(e.inits.get("fz").map(String::as_str), Some("1'0"));
        assert!(!e.inits.contains_key("plain"));
    }
}
