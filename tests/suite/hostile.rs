//! Careless and hostile inputs on the real binary (issue: nothing passes silently): each ends
//! in a clear message and the right exit code, and nothing is lost or half-written. Arguments
//! and names here; what is written (`outputs`) and what is read as evidence (`evidence`) in
//! their own files.

mod evidence;
mod outputs;

use crate::common::*;
use specgen::config::SpecularModel;
use std::path::PathBuf;
use std::process::{Command, Output};

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[test]
fn config_must_be_a_small_regular_file() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let big = tmp.path().join("big.json");
    std::fs::write(&big, vec![b' '; (1 << 20) + 1]).unwrap();
    for (cfg, why) in [
        ("/dev/zero", "not a regular file"),
        (big.to_str().unwrap(), "at most 1 MiB"),
        (tmp.path().to_str().unwrap(), "not a regular file"),
    ] {
        let o = specgen()
            .args(["generate", "--config", cfg, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{cfg}: {}", text(&o));
        assert!(
            text(&o).contains("--config") && text(&o).contains(why),
            "{cfg}: {}",
            text(&o)
        );
        assert!(!out.exists());
    }
}

#[test]
fn top_may_not_be_a_port_or_an_internal_name() {
    let tmp = tempfile::tempdir().unwrap();
    for bad in [
        "cos_g",
        "done",
        "clk",
        "valid_c0",
        "bracket_s7",
        "cos_sp_rom",
        "unused_x",
        "cos_sp_rom_fd",
        "ROM_FILE",
        "valid_line",
    ] {
        let out = tmp.path().join(bad);
        let o = specgen()
            .args(["generate", "--top", bad, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", text(&o));
        assert!(
            text(&o).contains("--top") && text(&o).contains("internal"),
            "{bad}: {}",
            text(&o)
        );
        assert!(!out.exists());
    }
    // the rule covers every name the generated units declare
    for args in
        specgen::config::SpecularModel::ALL.map(|m| crate::common::model_configs(m)[0].clone())
    {
        let dir = generate(tmp.path(), "ok", &args);
        let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        for line in v.lines().map(str::trim) {
            let decl = ["wire ", "reg ", "integer "]
                .iter()
                .find_map(|k| line.strip_prefix(k));
            let Some(rest) = decl else { continue };
            let name = rest
                .trim_start()
                .trim_start_matches(|c: char| {
                    c == '[' || c.is_ascii_digit() || c == ':' || c == ']'
                })
                .trim_start();
            let name: String = name
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                assert!(
                    specgen::config::is_internal_name(&name),
                    "{args:?}: internal name {name:?} would be accepted as --top"
                );
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn errors_name_the_users_paths_and_negative_numbers_get_ranges() {
    let o = specgen()
        .args(["rom", "-o", "/missing/dir/f.hex"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(
        text(&o).contains("/missing/dir/f.hex") && !text(&o).contains(".specgen-"),
        "{}",
        text(&o)
    );
    let cases: &[(&[&str], &str)] = &[
        (
            &["eval", "--cos", "-0.1", "--n", "3"],
            "out of range; allowed a decimal in [0, 2)",
        ),
        (&["eval", "--cos", "0.5", "--n", "-3"], "-3 is out of range"),
        (
            &["generate", "--out", "/tmp/specgen-never", "--n-bits", "-3"],
            "-3 is out of range; allowed 1..=12",
        ),
        (
            &["generate", "--out", "/tmp/specgen-never", "--k", "-0.5"],
            "negative, out of range",
        ),
        (
            &["generate", "--out", "/tmp/specgen-never", "--stages", "-1"],
            "-1 is out of range",
        ),
    ];
    for (args, want) in cases {
        let o = specgen().args(*args).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(text(&o).contains(want), "{args:?}: {}", text(&o));
    }
    assert!(!std::path::Path::new("/tmp/specgen-never").exists());
}

/// No shell. A file name in `--rtl` and the `--yosys` path are data: a file
/// named like a yosys command sequence runs nothing, a directory with a space works, and a
/// "tool" that is a shell command line is not found rather than run.
#[test]
fn file_names_and_tool_paths_never_reach_a_shell() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let parent = tmp.path().join("my dir");
    // (narrow widths: the names are the subject, and the netlist's check takes half as long)
    let dir = generate(
        &parent,
        "u",
        &[
            "--stages",
            "2",
            "--cos-frac-bits",
            "8",
            "--n-bits",
            "4",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let mark = tmp.path().join("PWNED");
    std::fs::write(dir.join("evil.ys"), format!("! touch {}\n", mark.display())).unwrap();
    std::fs::write(
        dir.join("a.v; script evil.ys; #.v"),
        "module stray; endmodule\n",
    )
    .unwrap();
    let o = specgen()
        .args(["synth", "--no-pnr", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    // a Verilog file the manifest does not list is named and refused, its name data
    assert_eq!(o.status.code(), Some(2), "{text}");
    assert!(
        text.contains("a.v; script evil.ys; #.v is not a file of this unit"),
        "{text}"
    );
    assert!(!mark.exists(), "a file name ran a command");
    std::fs::remove_file(dir.join("a.v; script evil.ys; #.v")).unwrap();
    // without it, the unit in a directory whose name has a space synthesizes
    let o = specgen()
        .args(["synth", "--no-pnr", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(o.status.code(), Some(0), "{text}");
    assert!(text.contains("flip-flops"), "{text}");
    assert!(!mark.exists(), "a file name ran a yosys script");
    let touched = tmp.path().join("X");
    let cmd = format!("yosys; touch {}; false", touched.display());
    let o = specgen()
        .args(["synth", "--no-pnr", "--yosys", &cmd, "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    // a tool not found is the tool's error (exit 1), with no Debian hint for a name that is none
    assert_eq!(o.status.code(), Some(1));
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("apt-get"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!touched.exists(), "--yosys ran a shell command");
}

/// Names the tools already use, SystemVerilog keywords and text that would break a
/// file header are refused up front, naming the flag (exit 2, nothing written); vector files
/// take their format from the extension in any case; `render --size` states its own range.
#[test]
fn reserved_names_and_header_breaking_text_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let cases: &[(&[&str], &str)] = &[
        (&["--top", "always_ff"], "--top"),
        (&["--top", "logic"], "--top"),
        (&["--top", "MULT18X18D", "--target", "ecp5"], "--top"),
        (&["--top", "specgen_synth_top"], "--top"),
        (&["--top", "SB_MAC16"], "--top"),
        (&["--k", "\n0.3686"], "--k"),
        (&["--k", "0.3686\r"], "--k"),
        (&["--clock-mhz", "100\n"], "--clock-mhz"),
    ];
    for (args, flag) in cases {
        let o = specgen()
            .args(["generate", "--out"])
            .arg(&out)
            .args(*args)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(flag),
            "{args:?}: {}",
            text(&o)
        );
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    let rtl = generate(tmp.path(), "u", &[]);
    let upper = tmp.path().join("v.HEX");
    assert!(specgen()
        .args(["vectors", "--count", "2", "--rtl"])
        .arg(&rtl)
        .arg("--out")
        .arg(&upper)
        .status()
        .unwrap()
        .success());
    let body = std::fs::read_to_string(&upper).unwrap();
    assert!(
        body.contains("$readmemh") && !body.contains("cos_g,n,"),
        "x.HEX is hex:\n{body}"
    );
    let o = specgen()
        .args(["render", "--size", "5", "--out"])
        .arg(tmp.path().join("p.png"))
        .arg("--rtl")
        .arg(&rtl)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("16..=1024"), "{}", text(&o));
    // the stage limits are the real ones: --help states none per model (a number there would
    // go stale with the next datapath), and a --stages above them names the plan's cut points
    let help = String::from_utf8_lossy(
        &specgen()
            .args(["generate", "--help"])
            .output()
            .unwrap()
            .stdout,
    )
    .to_string();
    assert!(
        help.contains("a value above them is refused with the range"),
        "{help}"
    );
    for model in SpecularModel::ALL {
        let cuts = default_cut_points(model);
        let o = specgen()
            .args([
                "generate",
                "--model",
                model.name(),
                "--stages",
                "100000",
                "--out",
            ])
            .arg(tmp.path().join("deep"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(
            text(&o).contains(&format!("allowed 0..={cuts}")),
            "{}: {}",
            model.name(),
            text(&o)
        );
    }
}

/// Every count is bounded — a huge `--vectors`, `--jobs`, `--count` or
/// `--verify-vectors` is a usage error naming the flag and its range (exit 2), not a panic,
/// an abort or gigabytes of memory.
#[test]
fn counts_are_bounded() {
    let tmp = tempfile::tempdir().unwrap();
    let rtl = generate(tmp.path(), "u", &[]);
    let cases: &[(&[&str], &str)] = &[
        (
            &["cosim", "--vectors", "18446744073709551615"],
            "0..=10000000",
        ),
        (&["cosim", "--vectors", "400000000"], "0..=10000000"),
        (&["cosim", "--jobs", "1000000"], "1..=64"),
        (
            &[
                "vectors",
                "--count",
                "18446744073709551615",
                "--out",
                "/tmp/specgen-never.csv",
            ],
            "0..=100000000",
        ),
        (
            &["synth", "--verify-vectors", "99999999999"],
            "0..=10000000",
        ),
    ];
    for (args, range) in cases {
        let o = specgen()
            .args(*args)
            .arg("--rtl")
            .arg(&rtl)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(
            text(&o).contains(args[1]) && text(&o).contains(range),
            "{args:?}: {}",
            text(&o)
        );
    }
    assert!(!std::path::Path::new("/tmp/specgen-never.csv").exists());
}

/// No panic, by fuzzing. Argument vectors are built from the flags each
/// subcommand's `--help` lists and hostile values (huge and negative numbers, whitespace and
/// line breaks, Verilog keywords, a FIFO, a dangling link, /dev/zero, the unit's own files as
/// outputs); every run must end with exit 0, 1 or 2, never by a signal (a panic is 101, an
/// abort a signal); the hang guard only stops a run that never ends, as a failure of its own. Deterministic: a fixed seed, so CI runs the same cases.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fuzzed_argument_vectors_exit_0_1_or_2() {
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(tmp.path(), "unit", &["--stages", "2"]);
    let cwd = tmp.path().join("a").join("b");
    std::fs::create_dir_all(&cwd).unwrap();
    let fifo = tmp.path().join("fifo");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let dangling = tmp.path().join("dangling");
    std::os::unix::fs::symlink(tmp.path().join("nowhere"), &dangling).unwrap();
    let values: Vec<String> = [
        "",
        " ",
        "0",
        "1",
        "2",
        "3",
        "-1",
        "0.5",
        "1.0",
        "0.3686",
        "64",
        "1000",
        "4294967295",
        "4294967296",
        "18446744073709551615",
        "18446744073709551616",
        "99999999999999999999999",
        "1e9",
        "nan",
        "-0",
        "\n0.3686",
        "0.36\r86",
        "always_ff",
        "logic",
        "SB_MAC16",
        "specular_unit",
        "é",
        "x y",
        "a;b",
        "--out",
        "ice40",
        "ecp5",
        "blinn",
        "fitted",
        "ready",
        "axis",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain(
        [
            fifo.clone(),
            dangling.clone(),
            "/dev/zero".into(),
            "/dev/null".into(),
            unit.clone(),
            unit.join("specular_unit.v"),
            unit.join("specular_unit.json"),
            unit.join("specular_unit_cos_sp_rom.hex"),
            tmp.path().join("fresh"),
            "..".into(),
            ".".into(),
        ]
        .into_iter()
        .map(|p| p.display().to_string()),
    )
    .collect();
    let subcommands = [
        "generate", "rom", "eval", "cosim", "vectors", "synth", "render", "report",
    ];
    let flags: Vec<Vec<(String, bool)>> = subcommands
        .iter()
        .map(|sub| {
            let help = String::from_utf8(specgen().args([sub, "--help"]).output().unwrap().stdout)
                .unwrap();
            help.lines()
                .filter_map(|l| {
                    let t = l.trim_start();
                    let t = t
                        .strip_prefix("-o, ")
                        .or_else(|| t.strip_prefix("-h, "))
                        .unwrap_or(t);
                    let name = t.strip_prefix("--")?.split([' ', '=']).next()?.to_string();
                    (name != "help" && name != "jobs")
                        .then(|| (format!("--{name}"), t.contains('<')))
                })
                .collect()
        })
        .collect();
    for (sub, f) in subcommands.iter().zip(&flags) {
        assert!(f.len() >= 3, "{sub}: flags read from --help: {f:?}");
    }
    let case = (
        0..subcommands.len(),
        proptest::collection::vec((0..64usize, 0..values.len()), 0..3),
    );
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let started = std::time::Instant::now();
    let cases = 24;
    let mut codes = [0u32; 4];
    for i in 0..cases {
        let (s, picks) = case.new_tree(&mut runner).unwrap().current();
        // a working command line first (so the hostile flags reach past argument parsing),
        // then the hostile flags that do not repeat one of it
        let fresh = |name: &str| tmp.path().join(format!("{name}{i}")).display().to_string();
        let unit_dir = unit.display().to_string();
        let base: Vec<String> = match subcommands[s] {
            "generate" => vec!["--out".into(), fresh("g")],
            "eval" => vec!["--cos".into(), "0.5".into(), "--n".into(), "3".into()],
            "cosim" => vec!["--rtl".into(), unit_dir, "--vectors".into(), "300".into()],
            "vectors" => vec![
                "--rtl".into(),
                unit_dir,
                "--count".into(),
                "50".into(),
                "--out".into(),
                fresh("v"),
            ],
            "synth" => vec!["--rtl".into(), unit_dir, "--no-pnr".into()],
            "render" => vec![
                "--rtl".into(),
                unit_dir,
                "--model-only".into(),
                "--size".into(),
                "16".into(),
                "--out".into(),
                fresh("r"),
            ],
            "report" => vec!["--out".into(), fresh("rep")],
            _ => vec![],
        };
        let mut argv = vec![subcommands[s].to_string()];
        argv.extend(base.iter().cloned());
        for (f, v) in picks {
            let (flag, takes_value) = &flags[s][f % flags[s].len()];
            if base.contains(flag) && i % 4 != 0 {
                continue; // a repeated flag is a usage error; keep a quarter of them
            }
            argv.push(flag.clone());
            if *takes_value {
                argv.push(values[v].clone());
            }
        }
        let mut child = specgen()
            .args(&argv)
            .current_dir(&cwd)
            .env("SPECGEN_CACHE_DIR", cache_dir())
            .env("SPECGEN_SIM_TIMEOUT", "20")
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let mut pipe = child.stderr.take().unwrap();
        let drain = std::thread::spawn(move || {
            let mut err = String::new();
            let _ = std::io::Read::read_to_string(&mut pipe, &mut err);
            err
        });
        let status = finished_within_guard(
            &mut child,
            &format!("case {i}: specgen {argv:?} never ended"),
        );
        let err = drain.join().unwrap();
        codes[status.code().unwrap_or(3).clamp(0, 3) as usize] += 1;
        assert!(
            matches!(status.code(), Some(0..=2)),
            "case {i}: specgen {argv:?} ended with {status}:\n{err}"
        );
        assert!(
            !err.contains("panicked"),
            "case {i}: specgen {argv:?} panicked:\n{err}"
        );
    }
    eprintln!(
        "fuzz: {cases} argument vectors in {:.1} s, exit codes 0/1/2: {codes:?}",
        started.elapsed().as_secs_f64()
    );
}
