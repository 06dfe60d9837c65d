//! `specgen vectors`: golden vectors for other testbenches, and the cocotb testbench in
//! `tb/cocotb/` that reads them (run under Icarus and Verilator; a wrong vector must fail it).

use crate::common::*;
use specgen::config::Params;
use specgen::models::{Inputs, Model, Outputs};
use std::path::Path;
use std::process::Command;

fn vectors(rtl: &Path, out: &Path, args: &[&str]) -> std::process::Output {
    specgen()
        .args(["vectors", "--rtl"])
        .arg(rtl)
        .arg("--out")
        .arg(out)
        .args(args)
        .output()
        .unwrap()
}

fn model_of(rtl: &Path) -> Model {
    let text = std::fs::read_to_string(rtl.join("specular_unit.json")).unwrap();
    specgen::plan::Plan::from_params(Params::from_json(&text).unwrap())
        .unwrap()
        .model()
}

/// The data lines of a vectors file (no comments, no blank lines).
fn data_lines(text: &str, comment: &str) -> Vec<String> {
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with(comment))
        .map(str::to_string)
        .collect()
}

#[test]
fn csv_rows_are_the_golden_model_and_the_header_names_the_ports() {
    let tmp = tempfile::tempdir().unwrap();
    for args in [
        &["--model", "blinn", "--stages", "3"][..],
        &["--cos-frac-bits", "9", "--n-bits", "5", "--color-bits", "6"][..],
    ] {
        let rtl = generate(tmp.path(), "u", args);
        let file = tmp.path().join("v.csv");
        let out = vectors(&rtl, &file, &["--count", "300", "--seed", "7"]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = std::fs::read_to_string(&file).unwrap();
        let model = model_of(&rtl);
        let stages = model.cfg.stages();
        assert!(
            text.contains(&format!("latency {stages}")),
            "the header states the latency:\n{}",
            &text[..600]
        );
        let lines = data_lines(&text, "#");
        assert_eq!(
            lines[0],
            "cos_g,n,ks_r,ks_g,ks_b,intensity,spec_r,spec_g,spec_b,done"
        );
        let corners = specgen::cosim::corner_vectors(&model).len();
        assert_eq!(lines.len() - 1, corners + 300);
        let mut random_rows = 0;
        for (i, line) in lines[1..].iter().enumerate() {
            let v: Vec<u32> = line.split(',').map(|x| x.parse().unwrap()).collect();
            let x = Inputs {
                cos_g: v[0],
                n: v[1],
                ks: [v[2], v[3], v[4]],
            };
            let y = Outputs {
                intensity: v[5],
                spec: [v[6], v[7], v[8]],
                done: v[9] == 1,
            };
            assert_eq!(model.eval(x), y, "row {i}");
            model.check(x, y).unwrap();
            if i >= corners {
                assert_eq!(
                    x,
                    specgen::cosim::random_vector(&model.cfg, 7, (i - corners) as u64)
                );
                random_rows += 1;
            }
        }
        assert_eq!(random_rows, 300);
    }
}

#[test]
fn hex_words_pack_the_fields_the_header_lists() {
    let tmp = tempfile::tempdir().unwrap();
    let rtl = generate(tmp.path(), "u", &["--model", "fitted", "--n-bits", "6"]);
    let file = tmp.path().join("v.hex");
    let out = vectors(&rtl, &file, &["--count", "50"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&file).unwrap();
    let model = model_of(&rtl);
    // the field list: name[hi:lo] ... most significant first
    let fields_line = text.lines().find(|l| l.contains("cos_g[")).unwrap();
    let fields: Vec<(String, u32, u32)> = fields_line
        .trim_start_matches("//")
        .split_whitespace()
        .map(|f| {
            let (name, range) = f.split_once('[').unwrap();
            let (hi, lo) = range.trim_end_matches(']').split_once(':').unwrap();
            (name.to_string(), hi.parse().unwrap(), lo.parse().unwrap())
        })
        .collect();
    let words = data_lines(&text, "//");
    assert_eq!(
        words.len(),
        specgen::cosim::corner_vectors(&model).len() + 50
    );
    assert!(text.contains(&format!("vectors [0:{}]", words.len() - 1)));
    for w in &words {
        let word = u128::from_str_radix(w, 16).unwrap();
        let get = |name: &str| {
            let (_, hi, lo) = fields.iter().find(|f| f.0 == name).unwrap();
            ((word >> lo) & ((1u128 << (hi - lo + 1)) - 1)) as u32
        };
        let x = Inputs {
            cos_g: get("cos_g"),
            n: get("n"),
            ks: [get("ks_r"), get("ks_g"), get("ks_b")],
        };
        let y = Outputs {
            intensity: get("intensity"),
            spec: [get("spec_r"), get("spec_g"), get("spec_b")],
            done: get("done") == 1,
        };
        assert_eq!(model.eval(x), y);
    }
}

#[test]
fn exhaustive_covers_every_cos_and_n() {
    let tmp = tempfile::tempdir().unwrap();
    let rtl = generate(
        tmp.path(),
        "u",
        &["--cos-frac-bits", "6", "--n-bits", "3", "--color-bits", "4"],
    );
    let file = tmp.path().join("all.csv");
    let out = vectors(&rtl, &file, &["--exhaustive"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines = data_lines(&std::fs::read_to_string(&file).unwrap(), "#");
    let mut seen = std::collections::BTreeSet::new();
    for l in &lines[1..] {
        let v: Vec<u32> = l.split(',').map(|x| x.parse().unwrap()).collect();
        seen.insert((v[0], v[1]));
    }
    assert_eq!(seen.len(), 8 * 65, "every (cos_g <= 1.0, n)");
    assert_eq!(
        lines.len() - 1,
        8 * 65 + 16,
        "and every colour code at full intensity"
    );
}

#[test]
fn an_unwritable_file_is_an_error_and_nothing_is_left() {
    let tmp = tempfile::tempdir().unwrap();
    let rtl = generate(tmp.path(), "u", &["--n-bits", "4"]);
    let out = vectors(&rtl, &tmp.path().join("missing/v.csv"), &[]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing/v.csv"));
    let out = vectors(&tmp.path().join("nothing"), &tmp.path().join("v.csv"), &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!tmp.path().join("v.csv").exists());
    let out = vectors(
        &rtl,
        &tmp.path().join("v.csv"),
        &["--exhaustive", "--count", "3"],
    );
    assert_eq!(
        out.status.code(),
        Some(2),
        "--exhaustive and --count conflict"
    );
}

/// Runs the cocotb testbench of `tb/cocotb` in a scratch directory; returns (success, log).
fn cocotb(rtl: &Path, vectors: &Path, sim: &str, work: &Path) -> (bool, String) {
    require_tool("cocotb-config", "cocotb (pip install cocotb==1.9.2)");
    let makefile = Path::new(env!("CARGO_MANIFEST_DIR")).join("tb/cocotb/Makefile");
    std::fs::create_dir_all(work).unwrap();
    let out = Command::new("make")
        .current_dir(work)
        .arg("-f")
        .arg(&makefile)
        .arg(format!("SPECGEN_RTL={}", rtl.display()))
        .arg(format!("SPECGEN_VECTORS={}", vectors.display()))
        .arg(format!("SIM={sim}"))
        .output()
        .unwrap();
    (
        out.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn cocotb_checks_the_unit_under_icarus_and_verilator_and_fails_on_a_wrong_vector() {
    require_tool("iverilog", "iverilog");
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    // pipelined (latency checked to the cycle) under both simulators, with a table file
    let rtl = generate(tmp.path(), "piped", &["--stages", "5"]);
    let file = tmp.path().join("piped.csv");
    assert!(vectors(&rtl, &file, &["--count", "500"]).status.success());
    for sim in ["icarus", "verilator"] {
        let (ok, log) = cocotb(&rtl, &file, sim, &tmp.path().join(format!("run-{sim}")));
        assert!(
            ok && log.contains("PASS: 1 cocotb test"),
            "cocotb under {sim}:\n{log}"
        );
    }
    // combinational, another model
    let comb = generate(tmp.path(), "comb", &["--model", "blinn", "--n-bits", "6"]);
    let comb_file = tmp.path().join("comb.csv");
    assert!(vectors(&comb, &comb_file, &["--count", "200"])
        .status
        .success());
    let (ok, log) = cocotb(&comb, &comb_file, "icarus", &tmp.path().join("run-comb"));
    assert!(
        ok && log.contains("0 mismatches"),
        "cocotb, combinational:\n{log}"
    );
    // one expected value off by one: the make run must fail, naming the row
    let text = std::fs::read_to_string(&file).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let i = lines
        .iter()
        .position(|l| l.starts_with(|c: char| c.is_ascii_digit()) && !l.contains(",0,0,0,0,"))
        .unwrap()
        + 40;
    let mut v: Vec<u64> = lines[i].split(',').map(|x| x.parse().unwrap()).collect();
    v[5] ^= 1;
    lines[i] = v.iter().map(u64::to_string).collect::<Vec<_>>().join(",");
    let bad = tmp.path().join("bad.csv");
    std::fs::write(&bad, lines.join("\n") + "\n").unwrap();
    let (ok, log) = cocotb(&rtl, &bad, "icarus", &tmp.path().join("run-bad"));
    assert!(!ok, "a wrong vector must fail the run:\n{log}");
    assert!(
        log.contains("FAIL: 1 of 1 cocotb tests failed") && log.contains("intensity ="),
        "{log}"
    );
}

/// The cocotb testbench drives `ready` and `axis` units (fields at the manifest's
/// tdata offsets) with random backpressure and a static colour, and a wrong vector fails it.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn cocotb_drives_handshake_units_with_backpressure() {
    require_tool("iverilog", "iverilog");
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str], &str); 2] = [
        (
            "axis",
            &["--interface", "axis", "--stages", "4", "--tag-bits", "12"],
            "verilator",
        ),
        (
            "ready",
            &[
                "--interface",
                "ready",
                "--stages",
                "2",
                "--colour",
                "static",
                "--tag-bits",
                "3",
                "--n-bits",
                "6",
            ],
            "icarus",
        ),
    ];
    for (name, args, sim) in cases {
        let rtl = generate(tmp.path(), name, args);
        let file = tmp.path().join(format!("{name}.csv"));
        assert!(vectors(&rtl, &file, &["--count", "300"]).status.success());
        let (ok, log) = cocotb(&rtl, &file, sim, &tmp.path().join(format!("run-{name}")));
        assert!(
            ok && log.contains("under backpressure: 0 mismatches"),
            "cocotb {name} under {sim}:\n{log}"
        );
    }
    // a wrong expected value in the stream: the run fails
    let rtl = tmp.path().join("axis");
    let text = std::fs::read_to_string(tmp.path().join("axis.csv")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let i = lines
        .iter()
        .position(|l| l.starts_with(|c: char| c.is_ascii_digit()))
        .unwrap()
        + 7;
    let mut v: Vec<u64> = lines[i].split(',').map(|x| x.parse().unwrap()).collect();
    v[5] ^= 1;
    lines[i] = v.iter().map(u64::to_string).collect::<Vec<_>>().join(",");
    let bad = tmp.path().join("bad-axis.csv");
    std::fs::write(&bad, lines.join("\n") + "\n").unwrap();
    let (ok, log) = cocotb(&rtl, &bad, "icarus", &tmp.path().join("run-bad-axis"));
    assert!(
        !ok && log.contains("FAIL: 1 of 1 cocotb tests failed"),
        "a wrong vector must fail the stream run:\n{log}"
    );
}

/// The cocotb testbench's own check (run by its Makefile before simulating, and by the test
/// module): the directory's files against the manifest's SHA-256s, the unit's header and the
/// vectors' header against its fingerprint; the first difference is named (exit 1).
#[test]
fn the_cocotb_check_names_files_of_another_configuration() {
    let tmp = tempfile::tempdir().unwrap();
    let fitted = generate(tmp.path(), "fitted", &["--model", "fitted"]);
    let blinn = generate(tmp.path(), "blinn", &["--model", "blinn"]);
    let vectors = |dir: &std::path::Path, name: &str| {
        let out = tmp.path().join(name);
        let o = specgen()
            .args(["vectors", "--count", "20", "--rtl"])
            .arg(dir)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out
    };
    let (own, other) = (vectors(&fitted, "fitted.csv"), vectors(&blinn, "blinn.csv"));
    let script =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tb/cocotb/specgen_manifest.py");
    let check = |dir: &std::path::Path, v: &std::path::Path| {
        std::process::Command::new("python3")
            .arg(&script)
            .arg("--check")
            .arg(dir)
            .arg(v)
            .output()
            .unwrap()
    };
    let say = |o: &std::process::Output| {
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    };
    let o = check(&fitted, &own);
    assert!(o.status.success(), "{}", say(&o));
    let o = check(&fitted, &other);
    assert_eq!(o.status.code(), Some(1), "{}", say(&o));
    assert!(
        say(&o).contains("holds vectors of another configuration"),
        "{}",
        say(&o)
    );
    std::fs::copy(
        blinn.join("specular_unit.v"),
        fitted.join("specular_unit.v"),
    )
    .unwrap();
    let o = check(&fitted, &own);
    assert_eq!(o.status.code(), Some(1), "{}", say(&o));
    assert!(
        say(&o).contains("specular_unit.v is not the file specgen wrote"),
        "{}",
        say(&o)
    );
}
