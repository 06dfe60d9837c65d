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
    let unit = generate(tmp.path(), "u", &["--n-bits", "4", "--cos-frac-bits", "8", "--intensity-frac-bits", "8", "--color-bits", "4", "--stages", "2"]);
    let started = tmp.path().join("started");
    let stall = tmp.path().join("yosys");
    std::fs::write(&stall, format!("#!/bin/bash\ncase \"$1\" in -V) exec yosys -V;; esac\ntouch {started:?}\nexec sleep {}\n", HANG_GUARD_SECS)).unwrap();
    std::fs::set_permissions(&stall, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let mut live = specgen().args(["synth", "--rtl"]).arg(&unit).arg("--yosys").arg(&stall).env("TMPDIR", &shared).spawn().unwrap();
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
    assert!(!before.is_empty(), "the live run's directories in {}", shared.display());
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
    assert_eq!(after, before, "a live run's directories swept from another PID namespace");
}
