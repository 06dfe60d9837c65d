//! Runs that share a machine's temporary directory: a live run's files are never swept by
//! another, whoever sweeps, whatever its PID namespace.

use crate::common::*;

/// A `synth` stalled inside its yosys holds its work directories; a `cosim` started in another
/// PID namespace (`unshare --pid --fork`, as a container or a cluster node sharing the
/// temporary directory), which sweeps killed runs' leftovers first, sees no such pid and must
/// still leave them: the run holds a lock on each directory's marker for its life.
#[test]
fn a_live_runs_files_are_never_swept_from_another_pid_namespace() {
    require_tool("unshare", "util-linux");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let shared = tmp.path().join("shared-tmp");
    std::fs::create_dir(&shared).unwrap();
    let unit = generate(
        tmp.path(),
        "u",
        &[
            "--n-bits",
            "4",
            "--cos-frac-bits",
            "8",
            "--intensity-frac-bits",
            "8",
            "--color-bits",
            "4",
            "--stages",
            "2",
        ],
    );
    let started = tmp.path().join("started");
    let stall = tmp.path().join("yosys");
    std::fs::write(&stall, format!("#!/bin/bash\ncase \"$1\" in -V) exec yosys -V;; esac\ntouch {started:?}\nexec sleep {}\n", HANG_GUARD_SECS)).unwrap();
    std::fs::set_permissions(&stall, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let mut live = specgen()
        .args(["synth", "--rtl"])
        .arg(&unit)
        .arg("--yosys")
        .arg(&stall)
        .env("TMPDIR", &shared)
        .spawn()
        .unwrap();
    wait_until("the live synth's yosys", || started.exists());
    let pid = live.id();
    let ours = || -> Vec<String> {
        std::fs::read_dir(&shared)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(&format!("specgen-{pid}-")))
            .collect()
    };
    let before = ours();
    assert!(
        !before.is_empty(),
        "the live run's directories in {}",
        shared.display()
    );
    // outside the suite's job slots: the live run holds one, and the other may be the only
    // one left (the swept run's own tools would wait on it for ever)
    let o = output_guarded(
        std::process::Command::new("unshare")
            .args(["--pid", "--fork"])
            .arg(env!("CARGO_BIN_EXE_specgen"))
            .args(["cosim", "--simulator", "icarus", "--vectors", "10", "--rtl"])
            .arg(&unit)
            .env("TMPDIR", &shared)
            .env_remove("SPECGEN_JOBS"),
        "cosim in another PID namespace",
    );
    let after = ours();
    unsafe {
        libc::kill(pid as i32, libc::SIGTERM);
    }
    finished_within_guard(&mut live, "the stalled synth");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        after, before,
        "a live run's directories swept from another PID namespace"
    );
}

const NARROW_SPACE: &[&str] = &[
    "--models",
    "quadratic",
    "--cos-frac-bits",
    "8",
    "--intensity-frac-bits",
    "8",
    "--n-bits",
    "4",
    "--color-bits",
    "4",
    "--measure-all",
    "--seeds",
    "1",
];

fn executable(path: &std::path::Path, text: &str) {
    std::fs::write(path, text).unwrap();
    std::fs::set_permissions(path, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
}

/// One run of a job at a time: a second `measure` of a job that is running (a resumed sweep
/// beside a killed sweep's orphan) waits for it and takes its result; yosys runs once.
#[test]
fn a_job_never_runs_beside_itself() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let plan = tmp.path().join("plan");
    let o = output_guarded(
        specgen()
            .arg("explore")
            .arg("--out")
            .arg(&plan)
            .args(NARROW_SPACE),
        "explore",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let jobs: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(plan.join("jobs.json")).unwrap()).unwrap();
    let fp = jobs[0]["fingerprint"].as_str().unwrap();
    let (gate, runs, started) = (
        tmp.path().join("gate"),
        tmp.path().join("runs"),
        tmp.path().join("started"),
    );
    let yosys = tmp.path().join("yosys");
    executable(&yosys, &format!("#!/bin/bash\ncase \"$1\" in -V) exec yosys -V;; esac\necho run >> {runs:?}\ntouch {started:?}\nwhile [ ! -e {gate:?} ]; do sleep 0.1; done\nexec yosys \"$@\"\n"));
    let out = tmp.path().join(format!("{fp}.json"));
    let measure = || {
        specgen()
            .arg("measure")
            .arg("--jobs")
            .arg(plan.join("jobs.json"))
            .args(["--fingerprint", fp])
            .arg("--out")
            .arg(&out)
            .arg("--yosys")
            .arg(&yosys)
            .spawn()
            .unwrap()
    };
    let mut first = measure();
    wait_until("the first run's yosys", || started.exists());
    let mut second = measure();
    // the second waits on the first's lock; had it run beside the first, its own yosys runs
    // would be counted below (decided by the count, never by how long anything took)
    std::fs::write(&gate, "").unwrap();
    assert!(finished_within_guard(&mut first, "the first measure").success());
    assert!(finished_within_guard(&mut second, "the second measure").success());
    assert_eq!(
        std::fs::read_to_string(&runs).unwrap().lines().count(),
        2,
        "yosys runs of the job (its unit and its wrapped top, once)"
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(r["job"]["fingerprint"], fp);
}

/// A sweep's paths are data: a results directory named `res+1` and a plan under `run #2/`
/// sweep as any; a second sweep on a directory a sweep runs on is refused (the lock it holds,
/// no pattern of its name), never started beside it.
#[test]
fn a_sweeps_paths_are_data_and_one_sweep_runs_a_directory() {
    require_tool("snakemake", "snakemake (pip)");
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let plan = tmp.path().join("run #2");
    let o = output_guarded(
        specgen()
            .arg("explore")
            .arg("--out")
            .arg(&plan)
            .args(NARROW_SPACE),
        "explore",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let results = tmp.path().join("res+1");
    let sweep = |specgen_path: &std::path::Path| {
        let mut c = std::process::Command::new("bash");
        c.arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/sweep.sh"))
            .arg(plan.join("jobs.json"))
            .arg(&results)
            .args(["--cores", "1", "--quiet"]);
        c.env("SPECGEN", specgen_path).env("SPECGEN_JOBS", jobs());
        c.stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        c
    };
    // a first sweep whose jobs stall: the second is refused while it runs
    let started = tmp.path().join("started");
    let stalling = tmp.path().join("stalling-specgen");
    executable(
        &stalling,
        &format!("#!/bin/bash\ntouch {started:?}\nexec sleep {HANG_GUARD_SECS}\n"),
    );
    let mut first = {
        use std::os::unix::process::CommandExt;
        sweep(&stalling).process_group(0).spawn().unwrap()
    };
    wait_until("the first sweep's job", || started.exists());
    let o = output_guarded(
        &mut sweep(std::path::Path::new(env!("CARGO_BIN_EXE_specgen"))),
        "the second sweep",
    );
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("a sweep is running on"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    unsafe {
        libc::kill(-(first.id() as i32), libc::SIGKILL);
    }
    finished_within_guard(&mut first, "the killed sweep");
    // then a sweep runs, its paths whole
    let o = output_guarded(
        &mut sweep(std::path::Path::new(env!("CARGO_BIN_EXE_specgen"))),
        "the sweep",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let jobs_planned: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(plan.join("jobs.json")).unwrap()).unwrap();
    for j in &jobs_planned {
        assert!(results
            .join(format!("{}.json", j["fingerprint"].as_str().unwrap()))
            .is_file());
    }
}
