//! `generate --target ice40|ecp5|generic`: one datapath description shaped per family, every
//! shape computing the golden model's values. ECP5 puts its products on MULT18X18D blocks and
//! its cut-off ROM on a DP16KD, each with its own registers, and reaches 200 MHz.
//! Tables and operands as the netlist keeps them: `tables`.

mod tables;

use crate::common::*;
use std::path::Path;
use std::process::{Command, Output};

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn cosim(dir: &Path, args: &[&str]) -> Output {
    // --edited: the fault tests change the RTL on purpose
    specgen()
        .arg("cosim")
        .arg("--edited")
        .arg("--rtl")
        .arg(dir)
        .args(args)
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .output()
        .unwrap()
}

/// Every `*.v` of a generated directory, then the simulation models of its `sim/`.
fn verilog_files(dir: &Path) -> Vec<String> {
    let names = |d: &Path| -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .map(|r| {
                r.flatten()
                    .map(|e| e.file_name().to_string_lossy().to_string())
                    .filter(|n| n.ends_with(".v"))
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    };
    let mut v = names(dir);
    v.extend(
        names(&dir.join("sim"))
            .into_iter()
            .map(|n| format!("sim/{n}")),
    );
    v
}

/// Whether the Verilog multiplies anywhere (a `*` in code, not in a comment).
fn has_multiply(verilog: &str) -> bool {
    verilog
        .lines()
        .any(|l| l.split("//").next().unwrap().contains(" * "))
}

/// The ECP5 unit at its deepest pipeline: products on MULT18X18D through the product module,
/// the ROM on a DP16KD with its contents as INITVAL parameters, the primitives' simulation
/// models in `sim/` (so `read_verilog *.v; synth_ecp5` of the directory works); lint-clean under `verilator -Wall` with them, compiled by Icarus, and
/// equal to the golden model on every input under Verilator.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn ecp5_unit_is_right_everywhere_and_lint_clean() {
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let stages = deepest(&["--target", "ecp5"]);
    let dir = generate(
        tmp.path(),
        "ecp5",
        &["--target", "ecp5", "--stages", &stages],
    );
    let files = verilog_files(&dir);
    assert_eq!(
        files,
        [
            "specular_unit.v",
            "specular_unit_delay_ram.v",
            "specular_unit_mult18x18.v",
            "specular_unit_rom1k18.v",
            "sim/specular_unit_ecp5_dp16kd_sim.v",
            "sim/specular_unit_ecp5_mult18x18d_sim.v"
        ]
    );
    assert!(
        !dir.join("specular_unit_cos_sp_rom.hex").exists(),
        "the ROM's contents are the DP16KD's INITVAL parameters"
    );
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    assert_eq!(
        unit.matches("specular_unit_mult18x18 ").count(),
        7,
        "kn, two deviation products, the square, three colours"
    );
    assert_eq!(unit.matches("specular_unit_rom1k18 #(").count(), 1);
    assert!(
        !has_multiply(&unit),
        "every product on a DSP at the deepest pipeline"
    );
    let core = std::fs::read_to_string(dir.join("specular_unit.core")).unwrap();
    assert!(
        core.contains("tool: yosys")
            && core.contains("arch: ecp5")
            && core.contains("sim_models:")
            && core.contains("- sim/specular_unit_ecp5_mult18x18d_sim.v"),
        "{core}"
    );
    // a user's flow: every *.v of the directory into yosys, no list kept by hand
    let rtl: Vec<&String> = files.iter().filter(|f| !f.contains('/')).collect();
    // (synth_ecp5's first pass reads the family's cell library: a simulation model among the
    // RTL would redefine its primitives there)
    let script = format!(
        "read_verilog {}; synth_ecp5 -top specular_unit -run begin:coarse",
        rtl.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(" ")
    );
    let o = Command::new("yosys")
        .current_dir(&dir)
        .args(["-q", "-p", &script])
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "read_verilog *.v; synth_ecp5:\n{}",
        text(&o)
    );
    let o = Command::new("verilator")
        .current_dir(&dir)
        .args(["--lint-only", "-Wall"])
        .args(&files)
        .output()
        .unwrap();
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "verilator -Wall:\n{}",
        text(&o)
    );
    let o = Command::new("iverilog")
        .current_dir(&dir)
        .args(["-g2005", "-o", "/dev/null"])
        .args(&files)
        .output()
        .unwrap();
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "iverilog:\n{}",
        text(&o)
    );
    let o = cosim(&dir, &["--exhaustive"]);
    assert!(
        text(&o).contains(&format!(" {} results, 0 mismatches", 32769u64 * 1024 + 256)),
        "{}",
        text(&o)
    );
    let o = cosim(&dir, &["--simulator", "icarus", "--vectors", "1500"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // a shallower pipeline keeps the products the cuts do not surround as plain multiplies
    let some = generate(tmp.path(), "ecp5_4", &["--target", "ecp5", "--stages", "4"]);
    let unit = std::fs::read_to_string(some.join("specular_unit.v")).unwrap();
    assert!(has_multiply(&unit), "{unit}");
    let o = cosim(&some, &["--vectors", "30000"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

/// The primitives' registers are part of the arithmetic's timing: a product module without its
/// output register, or a ROM without its output register, is a cycle early and the
/// co-simulation says so.
/// Fitted and blinn shaped for the ECP5 at their deepest pipelines put every product
/// on a MULT18X18D with its own registers (products alone on the block, which has no adder:
/// fitted's squarings' hi², blinn's n·ℓ chunks, both models' colours; the adds follow on carry
/// chains), and are the golden model's under both simulators.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fitted_blinn_and_wide_lean_on_the_ecp5_keep_every_product_in_a_registered_block_and_are_right() {
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    // fitted: a_lo*(1 - cos), three squarings' hi^2, three colours; blinn: the two
    // interpolations' steps, x*g_lo, two n*l chunks, three colours; the wide lean: k_q*n and
    // kn*(1 - cos) in two halves each, the bracket's hi^2 and hi*lo, three colours (and its
    // 2048-word cut-off ROM in two banks of DP16KDs, 19 bits: 2 x 2)
    let wide = [
        "--cos-frac-bits",
        "18",
        "--n-bits",
        "11",
        "--color-bits",
        "10",
        "--intensity-frac-bits",
        "18",
        "--k-frac-bits",
        "20",
    ];
    let cases: [(&str, Vec<&str>, usize); 3] = [
        ("fitted", vec!["--model", "fitted"], 7),
        ("blinn", vec!["--model", "blinn"], 8),
        ("lean_wide", wide.to_vec(), 9),
    ];
    for (model, margs, blocks) in cases {
        let args = [&margs[..], &["--target", "ecp5"]].concat();
        let stages = deepest(&args);
        let dir = generate(
            tmp.path(),
            model,
            &[&args[..], &["--stages", &stages]].concat(),
        );
        let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        assert!(
            !has_multiply(&unit),
            "{model}: every product on a registered block:\n{unit}"
        );
        assert_eq!(
            unit.matches("specular_unit_mult18x18 ").count(),
            blocks,
            "{model}"
        );
        if model == "lean_wide" {
            assert_eq!(
                unit.matches("specular_unit_rom1k18 #(").count(),
                4,
                "two banks of two DP16KDs"
            );
        }
        let o = cosim(&dir, &["--vectors", "200000"]);
        assert_eq!(o.status.code(), Some(0), "{model}: {}", text(&o));
        let o = cosim(&dir, &["--simulator", "icarus", "--vectors", "2000"]);
        assert_eq!(o.status.code(), Some(0), "{model}: {}", text(&o));
    }
}

#[test]
fn ecp5_register_faults_are_caught() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let stages = deepest(&["--target", "ecp5"]);
    for (name, file, from, to) in [
        (
            "dsp",
            "specular_unit_mult18x18.v",
            ".REG_OUTPUT_CLK(\"CLK0\")",
            ".REG_OUTPUT_CLK(\"NONE\")",
        ),
        (
            "bram",
            "specular_unit_rom1k18.v",
            ".REGMODE_A(\"OUTREG\")",
            ".REGMODE_A(\"NOREG\")",
        ),
    ] {
        let dir = generate(tmp.path(), name, &["--target", "ecp5", "--stages", &stages]);
        let path = dir.join(file);
        let v = std::fs::read_to_string(&path).unwrap();
        assert!(v.contains(from), "{name}: {from}");
        std::fs::write(&path, v.replace(from, to)).unwrap();
        let o = cosim(&dir, &["--vectors", "20000"]);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
        assert!(text(&o).contains("mismatch"), "{name}: {}", text(&o));
    }
}

/// ECP5 place-and-route: yosys keeps the registers in the MULT18X18D and DP16KD blocks, the
/// mapped netlist passes `synth --verify`, and nextpnr-ecp5 (seed 1, LFE5U-25F grade 6)
/// reaches 200 MHz. RTL with ECP5 primitives is refused for another family.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn ecp5_unit_keeps_its_registers_in_the_blocks_and_reaches_200_mhz() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let stages = deepest(&["--target", "ecp5"]);
    let dir = generate(
        tmp.path(),
        "ecp5",
        &["--target", "ecp5", "--stages", &stages],
    );
    let json = tmp.path().join("synth.json");
    // no --target: the one the RTL was generated for
    let o = specgen()
        .args([
            "synth",
            "--dsp",
            "--seeds",
            "1",
            "--verify",
            "--verify-vectors",
            "3000",
            "--rtl",
        ])
        .arg(&dir)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(
        text(&o).matches(", 0 mismatches").count(),
        2,
        "Verilator and Icarus on the netlist\n{}",
        text(&o)
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(r["target"], "ecp5");
    let cells: std::collections::HashMap<String, u64> =
        serde_json::from_value(serde_json::Value::Object(
            r["cells"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| (c[0].as_str().unwrap().to_string(), c[1].clone()))
                .collect(),
        ))
        .unwrap();
    assert_eq!(cells.get("MULT18X18D"), Some(&7), "{r}");
    assert_eq!(cells.get("DP16KD"), Some(&1), "{r}");
    // the registers the blocks hold are not in the fabric: far fewer flip-flops than the
    // ice40-shaped unit's pipeline (734 at 13 stages)
    assert!(r["flip_flops"].as_u64().unwrap() < 500, "{r}");
    let fmax = r["fmax_mhz"].as_f64().unwrap();
    assert!(fmax >= 200.0, "{fmax} MHz: {r}");
    // never above a block's limit (nextpnr skips the DP16KD's pulse widths): at
    // grade 6 the DP16KD allows 211.9 MHz, nextpnr's own figure is kept beside it
    let route = r["fmax_route_mhz"].as_f64().unwrap();
    assert!(fmax <= 211.9 && route >= fmax, "{r}");
    if route > 211.9 {
        assert!(
            r["fmax_limited_by"]
                .as_str()
                .unwrap()
                .starts_with("DP16KD clock pulse ≥ 2.359 ns"),
            "{r}"
        );
    }
    assert!(
        r["block_limits"]
            .as_array()
            .unwrap()
            .iter()
            .any(|l| l[0] == "DP16KD" && l[1] == 211.9),
        "{r}"
    );
    let o = specgen()
        .args(["synth", "--no-pnr", "--target", "ice40", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("invalid --target: ice40") && text(&o).contains("allowed: ecp5"),
        "{}",
        text(&o)
    );
}

/// The generic shape: whole-width products and adds (no DSP-sized splits, no carry-select
/// chunks), the same values. `generic` is its own target: `--target-mhz`
/// is refused naming it, never with another family's figure, and a depth beyond its cut points
/// is refused naming the target.
#[test]
fn generic_target_has_whole_width_arithmetic_and_the_same_values() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    for model in ["quadratic", "blinn", "schlick"] {
        let o = specgen()
            .args([
                "generate",
                "--target",
                "generic",
                "--target-mhz",
                "50",
                "--model",
                model,
                "--out",
            ])
            .arg(tmp.path().join("no"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(
            text(&o).contains("the generic target has no delay model")
                && !text(&o).contains("UP5K")
                && !text(&o).contains("ECP5"),
            "{}",
            text(&o)
        );
        assert!(!tmp.path().join("no").exists());
    }
    let stages = deepest(&["--target", "generic"]);
    let o = specgen()
        .args(["generate", "--target", "generic", "--stages", "99", "--out"])
        .arg(tmp.path().join("no"))
        .output()
        .unwrap();
    assert!(text(&o).contains(&format!("allowed 0..={stages} (the cut points of the lean datapath with these widths on the generic target)")), "{}", text(&o));
    let dir = generate(
        tmp.path(),
        "generic",
        &["--target", "generic", "--stages", &stages],
    );
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    for split in ["_part1", "deviation_hi", "square_t"] {
        assert!(!unit.contains(split), "generic has no {split}");
    }
    let ice40 = std::fs::read_to_string(
        generate(tmp.path(), "ice40", &["--stages", &stages]).join("specular_unit.v"),
    )
    .unwrap();
    for split in ["_part1", "deviation_hi", "square_t"] {
        assert!(
            ice40.contains(split),
            "ice40 splits for its DSPs and carry chains: {split}"
        );
    }
    let o = Command::new("verilator")
        .current_dir(&dir)
        .args(["--lint-only", "-Wall", "specular_unit.v"])
        .output()
        .unwrap();
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "verilator -Wall:\n{}",
        text(&o)
    );
    let o = cosim(&dir, &["--vectors", "200000"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

/// The wide ECP5 configuration.
const WIDE: &[&str] = &[
    "--cos-frac-bits",
    "18",
    "--n-bits",
    "11",
    "--color-bits",
    "10",
    "--intensity-frac-bits",
    "18",
    "--k-frac-bits",
    "20",
];

/// The wide configuration fits the UP5K's 8 SB_MAC16 at its deepest pipeline and places
/// there: `k_q` and `1 − cos` wider than a DSP's 16 bits are split, their narrow high parts
/// multiplied by shift-adds, and the 21-bit bracket squared as `hi²` and `hi·lo`. The unit is
/// the golden model's, pipelined and combinational, lint-clean.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn wide_config_fits_the_up5k_dsps_and_is_right() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let stages = deepest(WIDE);
    let dir = generate(tmp.path(), "wide", &[WIDE, &["--stages", &stages]].concat());
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    for split in [
        "n_k_hi",
        "deviation_top",
        "deviation_hi",
        "square_t",
        "square_z",
    ] {
        assert!(
            unit.contains(split),
            "the wide unit splits for the DSPs: {split}"
        );
    }
    let json = tmp.path().join("synth.json");
    let o = specgen()
        .args([
            "synth", "--target", "ice40", "--dsp", "--seeds", "1", "--rtl",
        ])
        .arg(&dir)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let dsp = r["dsp_blocks"].as_u64().unwrap();
    assert!(
        (1..=8).contains(&dsp),
        "{dsp} SB_MAC16 (the UP5K has 8): {r}"
    );
    assert!(
        r["fmax_mhz"].as_f64().is_some(),
        "placed and routed on the UP5K: {r}"
    );
    let o = Command::new("verilator")
        .current_dir(&dir)
        .args(["--lint-only", "-Wall", "specular_unit.v"])
        .output()
        .unwrap();
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "verilator -Wall:\n{}",
        text(&o)
    );
    let o = cosim(&dir, &["--vectors", "200000"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let comb = generate(tmp.path(), "wide0", WIDE);
    let o = cosim(&comb, &["--vectors", "20000", "--simulator", "icarus"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

/// Random iCE40 configurations where `1 − cos` (F ≥ 16), `k_q` (KF ≥ 16) or the bracket are
/// wider than a DSP's operands, of every model, at random depths: every one equals the
/// golden model under Icarus (a few thousand vectors each, corner cases first).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn dsp_splits_are_right_over_random_wide_configs() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let mut r = 0x5eed_u64;
    let mut draw = |lo: u64, hi: u64| {
        r = specgen::cosim::splitmix(r);
        (lo + r % (hi - lo + 1)).to_string()
    };
    for i in 0..12 {
        let k = format!("0.{}", draw(100, 999));
        let args: Vec<String> = [
            "--cos-frac-bits",
            &draw(14, 20),
            "--n-bits",
            // 6 bits at most for fitted: one minimax fit per n, each well under a second
            &draw(1, if i % 4 == 3 { 6 } else { 12 }),
            "--color-bits",
            &draw(1, 16),
            "--intensity-frac-bits",
            &draw(8, 24),
            "--k-frac-bits",
            &draw(14, 24),
            "--k",
            &k,
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let mut args: Vec<&str> = args.iter().map(String::as_str).collect();
        // every model's shape: its splits, carry-save sums and cuts
        match i % 4 {
            1 => args.extend(["--model", "blinn"]),
            3 => args.extend(["--model", "fitted"]),
            _ => {}
        }
        let depth: u64 = deepest(&args).parse().unwrap();
        let stages = draw(0, depth);
        let dir = generate(
            tmp.path(),
            &format!("w{i}"),
            &[&args[..], &["--stages", &stages]].concat(),
        );
        let o = cosim(
            &dir,
            &[
                "--vectors",
                "3000",
                "--simulator",
                "icarus",
                "--seed",
                &i.to_string(),
            ],
        );
        assert_eq!(
            o.status.code(),
            Some(0),
            "{args:?} --stages {stages}: {}",
            text(&o)
        );
    }
}
