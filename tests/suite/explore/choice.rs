//! What `generate --max-error` and `--target-mhz` choose from the explorations: measured units
//! within the error, the handshake's ceiling, a budget as a ceiling, the options not given, the
//! shipped rows of today's RTL.

use super::*;

/// `generate --max-error E --target-mhz F` picks a unit that meets its error, checked here
/// exhaustively with the golden model, and whose measured median Fmax (the built-in
/// exploration's, over its seeds) reaches F; refused with the nearest units when none does.
#[test]
fn generate_max_error_picks_a_measured_unit_within_its_error() {
    let tmp = tempfile::tempdir().unwrap();
    // at the pixel: 0.02 is met on both families; 1e-3 (F = 20) only slowly on the UP5K (with
    // --dsp-budget 8) and at the ECP5's deepest, below 100 MHz
    let cases: &[(&str, f64, &[&str])] = &[
        ("0.02", 100.0, &[]),
        ("0.001", 45.0, &[]),
        ("0.02", 200.0, &["--target", "ecp5"]),
    ];
    for (i, &(e, mhz, extra)) in cases.iter().enumerate() {
        let out = tmp.path().join(format!("u{i}"));
        let o = output_guarded(
            specgen()
                .args([
                    "generate",
                    "--max-error",
                    e,
                    "--target-mhz",
                    &mhz.to_string(),
                ])
                .args(extra)
                .arg("--out")
                .arg(&out),
            "generate --max-error",
        );
        assert!(
            o.status.success(),
            "{e} at {mhz}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let said = String::from_utf8_lossy(&o.stderr);
        assert!(
            said.contains("max-error: chose") && said.contains("median over nextpnr seeds"),
            "{said}"
        );
        let params =
            specgen::config::Params::from_json_file(&out.join("specular_unit.json")).unwrap();
        let cfg = specgen::config::Config::new(params).unwrap();
        // the error at the pixel, every code's interval and every n (above 2^26 points a bound,
        // never below the exact figure: SPEC §6)
        let f = specgen::models::blinn_fidelity(&specgen::models::Model::new(&cfg));
        assert!(
            f.pixel.max <= e.parse::<f64>().unwrap(),
            "{e}: the unit's error at the pixel is {}",
            f.pixel.max
        );
        // the clock: the measured median of the exploration's unit that was written (not the
        // figure printed), and no unit of the exploration meets both with fewer cells
        let family = if extra.is_empty() { "ice40" } else { "ecp5" };
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let explored: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(root.join(format!("data/explore/{family}.json"))).unwrap(),
        )
        .unwrap();
        let written: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        let points = explored["points"].as_array().unwrap();
        let same = |p: &&serde_json::Value| {
            p["params"].as_object().unwrap().iter().all(|(k, v)| {
                ["top", "clock_mhz"].contains(&k.as_str()) || written.get(k).is_none_or(|w| w == v)
            })
        };
        let row = points
            .iter()
            .find(same)
            .unwrap_or_else(|| panic!("the unit written is no unit of the exploration: {said}"));
        assert!(
            row["measured"]["fmax_mhz"].as_f64().unwrap() >= mhz,
            "{row}"
        );
        let meets = |p: &&serde_json::Value| {
            p["params"]["interface"] == "valid"
                && p["params"]["n_bits"] == 10
                && p["params"]["color_bits"] == 8
                && p["measured"]["fmax_mhz"].as_f64().is_some_and(|f| f >= mhz)
                && p["accuracy"]["pixel"]["max"]
                    .as_f64()
                    .is_some_and(|x| x <= e.parse::<f64>().unwrap())
        };
        let cheapest = points
            .iter()
            .filter(meets)
            .map(|p| p["measured"]["logic_cells"].as_u64().unwrap())
            .min()
            .unwrap();
        assert_eq!(
            row["measured"]["logic_cells"].as_u64().unwrap(),
            cheapest,
            "{said}"
        );
        // the constraints ask for the clock chosen for
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["clock_mhz"], serde_json::json!(mhz.to_string()));
    }
    // none meets both: refused (exit 2), naming the nearest, nothing written
    let out = tmp.path().join("none");
    let o = output_guarded(
        specgen()
            .args(["generate", "--max-error", "1e-9", "--target-mhz", "100"])
            .arg("--out")
            .arg(&out),
        "generate",
    );
    assert_eq!(o.status.code(), Some(2));
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(
        said.contains("--max-error")
            && said.contains("nearest: ")
            && said.contains("specgen explore --target ice40"),
        "{said}"
    );
    assert!(!out.exists());
}

/// `--interface ready --target-mhz 120` on the UP5K is refused
/// beforehand, naming the output buffer's own paths and the most a handshake unit measured,
/// where it used to pick 13 stages at "129.8 MHz predicted" for a unit that measures 101.7.
#[test]
fn a_handshake_unit_is_not_promised_what_its_buffer_cannot_do() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--interface",
                "ready",
                "--target-mhz",
                "120",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    assert_eq!(o.status.code(), Some(2));
    let said = String::from_utf8_lossy(&o.stderr);
    // the ceiling is the measured unit's, as the delay model's fit keeps it (its calibration's
    // `ready`/`axis` rows of today's RTL)
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("data/delay_model.json")).unwrap())
            .unwrap();
    let cap = model["handshake"]["ice40"]["lean"]["mhz"]
        .as_f64()
        .expect("a lean handshake unit measured on the UP5K");
    assert!(cap < 120.0 && cap > 95.0, "{cap}");
    assert!(
        said.contains("interface's output buffer has paths of its own")
            && said.contains(&format!("{cap:.1} MHz"))
            && said.contains("on today's RTL"),
        "{said}"
    );
    assert!(!out.exists());
    // a part where no unit with the buffer was measured on today's RTL: refused, saying how to measure one
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "gowin",
                "--interface",
                "ready",
                "--target-mhz",
                "50",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        model["handshake"]["gowin"].is_null(),
        "a ready unit of the GW1NR-9 measured: this refusal no longer holds"
    );
    assert!(
        said.contains("no ready unit was measured on the GW1NR-9")
            && said.contains("specgen explore --target gowin --interface ready"),
        "{said}"
    );
    assert!(!out.exists());
    // below the buffer's measured clock it is picked, and its prediction never above it
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--interface",
                "ready",
                "--target-mhz",
                "95",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
            .unwrap();
    assert!(
        m["predicted_fmax_mhz"].as_f64().unwrap() <= cap,
        "{}",
        m["predicted_fmax_mhz"]
    );
    // the interface is part of the question: an axis unit measured as axis answers, and the
    // evidence printed is of that unit (its interface, its depth)
    for (args, interface) in [
        (&["--max-error", "0.02", "--target-mhz", "90"][..], "axis"),
        (&["--model", "blinn", "--target-mhz", "90"][..], "axis"),
    ] {
        let out = tmp.path().join(format!("edge-{}", args.len()));
        let o = output_guarded(
            specgen()
                .arg("generate")
                .args(args)
                .args(["--interface", interface, "--out"])
                .arg(&out),
            "generate",
        );
        let said = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{said}");
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["interface"], interface, "{m}");
        let id = format!(
            "{}-f{}-fi{}-s{}-n10-c8-",
            m["model"].as_str().unwrap(),
            m["cos_frac_bits"],
            m["intensity_frac_bits"],
            m["stages"]
        );
        assert!(
            said.contains(&id) && said.contains("today's RTL (sha256 "),
            "{id}: {said}"
        );
    }
}

/// A `--dsp-budget` given beside `--max-error` is a ceiling: the choice is the cheapest measured
/// unit taking at most that many blocks, whatever budget (or none) it was measured with, and the
/// unit is written as it was measured (its RTL the measurement's), saying the budget is met.
#[test]
fn a_dsp_budget_beside_max_error_is_a_ceiling() {
    let tmp = tempfile::tempdir().unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let e: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("data/explore/ice40.json")).unwrap(),
    )
    .unwrap();
    let (bound, mhz, budget) = (0.3, 100.0, 6u64);
    // the cheapest by the file's figures, at the default edge and widths N, B
    let meets = |p: &&serde_json::Value| {
        let m = &p["measured"];
        p["params"]["interface"] == "valid"
            && p["params"]["n_bits"] == 10
            && p["params"]["color_bits"] == 8
            && m["fmax_mhz"].as_f64().is_some_and(|f| f >= mhz)
            && m["dsp_blocks"].as_u64().is_some_and(|d| d <= budget)
            && p["accuracy"]["pixel"]["max"]
                .as_f64()
                .is_some_and(|x| x <= bound)
    };
    let cheapest = e["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(meets)
        .map(|p| p["measured"]["logic_cells"].as_u64().unwrap())
        .min();
    let cheapest = cheapest.expect(
        "the built-in exploration holds a unit of at most 6 DSP blocks at 100 MHz within 0.3",
    );
    let out = tmp.path().join("u");
    let args = [
        "--max-error",
        "0.3",
        "--target-mhz",
        "100",
        "--dsp-budget",
        "6",
    ];
    let o = output_guarded(
        specgen().arg("generate").args(args).arg("--out").arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    let cells: u64 = said
        .split(" logic cells")
        .next()
        .unwrap()
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{said}"));
    let blocks: u64 = said
        .split(" DSP blocks")
        .next()
        .unwrap()
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{said}"));
    assert!(
        blocks <= budget && cells == cheapest,
        "{cells} cells, {blocks} blocks; the cheapest meeting both: {cheapest}: {said}"
    );
    assert!(said.contains("--dsp-budget 6 is met"), "{said}");
}

/// The exploration issue's two refusals: a budgeted blinn at 100 MHz on the UP5K and lean's
/// table as logic at 250 MHz on the ECP5 are picked: from measured units of exactly that
/// configuration (median over seeds at or above the clock) where the delay model alone refuses,
/// or by the delay model at a shape it was calibrated at (the budgets 3 and 5 on the UP5K).
#[test]
fn the_refused_cases_are_picked_from_measured_units() {
    let tmp = tempfile::tempdir().unwrap();
    for (i, (args, mhz)) in [
        (&["--model", "blinn", "--dsp-budget", "5"][..], 100.0),
        (&["--target", "ecp5", "--rom-style", "logic"][..], 250.0),
    ]
    .into_iter()
    .enumerate()
    {
        let out = tmp.path().join(format!("u{i}"));
        let o = output_guarded(
            specgen()
                .arg("generate")
                .args(args)
                .args(["--target-mhz", &mhz.to_string(), "--out"])
                .arg(&out),
            "generate",
        );
        let said = String::from_utf8_lossy(&o.stderr);
        if !o.status.success() {
            // refused only where no unit measured on today's RTL reaches it: said so, with the
            // nearest measured unit (or that none is) and the command that would measure it
            assert_eq!(o.status.code(), Some(2), "{args:?}: {said}");
            assert!(
                said.contains("is not assured on the")
                    && said.contains(
                        "no unit of this configuration measured on today's RTL reaches it"
                    ),
                "{said}"
            );
            assert!(
                said.contains("to measure this configuration: specgen generate --stages"),
                "{said}"
            );
            assert!(!out.exists());
            continue;
        }
        // "chose --stages N on the PART: measured: F MHz, …" (a unit of the built-in exploration
        // measured on today's RTL) or "…: interpolated: F MHz by the delay model" at a calibrated
        // shape (the budget is one); never an extrapolation
        let chose = said
            .split("chose --stages ")
            .nth(1)
            .unwrap_or_else(|| panic!("{said}"));
        let (kind, rest) = chose.split_once(": ").unwrap().1.split_once(": ").unwrap();
        let figure: f64 = rest
            .split(' ')
            .next()
            .unwrap()
            .trim_end_matches(',')
            .parse()
            .unwrap_or_else(|_| panic!("{said}"));
        assert!(figure >= mhz, "{said}");
        assert!(kind == "measured" || kind == "interpolated", "{said}");
        let stages: u32 = chose.split(' ').next().unwrap().parse().unwrap();
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["stages"], stages);
    }
}

/// Every measured row the tool ships (the built-in explorations `generate --max-error` chooses
/// from) is of the RTL this specgen writes: `specgen stale` finds none of an older RTL.
#[test]
fn the_shipped_explorations_are_of_todays_rtl() {
    let o = output_guarded(specgen().arg("stale"), "specgen stale");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.status.success(), "{text}");
    assert!(text.contains("of today's RTL, 0 of an older RTL"), "{text}");
    // the delay model's floors too: each names today's RTL (a row naming none is no floor)
    for part in ["iCE40 UP5K", "ECP5-25 grade 6"] {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("the delay model's calibration on the {part}:")))
            .unwrap_or_else(|| panic!("{text}"));
        assert!(
            line.contains(" 0 of an older RTL") && !line.contains(": 0 floors"),
            "{line}"
        );
    }
    // the library agrees, family by family
    for t in specgen::config::Target::ALL {
        let ev = specgen::explore::calibration_evidence(t).unwrap();
        assert!(ev.stale.is_empty(), "{t:?}: stale floors {:?}", ev.stale);
    }
}

/// `specgen stale` says which rows of an exploration are of an older RTL, and exits 1.
#[test]
fn a_stale_row_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let mut e: serde_json::Value =
        serde_json::from_str(include_str!("../../../data/explore/ice40.json")).unwrap();
    let p = &mut e["points"][0];
    let id = p["id"].as_str().unwrap().to_string();
    p["measured"]["jobs"][0] = serde_json::json!("00000000000000000000");
    let file = tmp.path().join("e.json");
    std::fs::write(&file, e.to_string()).unwrap();
    let o = output_guarded(
        specgen().arg("stale").arg("--explored").arg(&file),
        "specgen stale",
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{text}");
    assert!(
        text.contains(&format!("  stale: {id}")) && text.contains("1 of an older RTL"),
        "{text}"
    );
}

/// `--target-mhz` chooses the options the user did not give as it chooses the depth, from
/// units measured on today's RTL: the ECP5 blinn reaches 250 MHz only with its tables in logic,
/// so without `--rom-style` it is chosen (and said), and with `--rom-style file` the request is
/// refused, naming the measured unit that reaches it.
#[test]
fn target_mhz_chooses_the_options_not_given_from_measured_units() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("free");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "ecp5",
                "--model",
                "blinn",
                "--target-mhz",
                "250",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    assert!(
        said.contains("--rom-style logic on the ECP5-25 grade 6: measured: ")
            && said.contains("today's RTL (sha256 "),
        "{said}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
            .unwrap();
    assert_eq!(m["rom_style"], "logic", "{m}");
    // the figure printed is the measured median of the unit written: its stages are the unit's
    let figure: f64 = said
        .split("measured: ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(figure >= 250.0, "{said}");
    let stages = m["stages"].as_u64().unwrap();
    assert!(
        said.contains(&format!("blinn-f15-fi15-s{stages}-logic")),
        "{said}"
    );
    // the user's own option kept: refused, naming the measured unit that reaches it
    let out = tmp.path().join("kept");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "ecp5",
                "--model",
                "blinn",
                "--rom-style",
                "file",
                "--target-mhz",
                "250",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("is not assured on the ECP5-25") && said.contains("--rom-style logic"),
        "{said}"
    );
    assert!(!out.exists());
}
