//! What a command writes and reads as files: never a user's config, a manifest's copy or
//! what a later command reads; a planted build state or cache entry never runs; a killed build
//! leaves nothing.

use super::*;

/// Finding 3: outputs over inputs. `rom --config X -o X` replaced the manifest with a table;
/// `cosim --trace DIR/extra.v` wrote a VCD over a Verilog file the run compiled; `report --out`
/// replaced a hand-edited index.html (listed without a SHA-256). Each is refused now, the
/// input untouched.
#[test]
fn an_output_never_replaces_what_the_command_reads() {
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(tmp.path(), "u", &["--n-bits", "4", "--stages", "1"]);
    let manifest = unit.join("specular_unit.json");
    let before = std::fs::read(&manifest).unwrap();
    let o = specgen()
        .arg("rom")
        .arg("--config")
        .arg(&manifest)
        .arg("-o")
        .arg(&manifest)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("is the --config file this command reads"),
        "{}",
        text(&o)
    );
    assert_eq!(std::fs::read(&manifest).unwrap(), before);
    // a Verilog file of the user's beside the unit: compiled by cosim, so never its trace
    let extra = unit.join("extra.v");
    std::fs::write(&extra, "// the user's\n").unwrap();
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"))
        .args(["cosim", "--simulator", "icarus", "--rtl"])
        .arg(&unit)
        .arg("--trace")
        .arg(&extra)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    // refused as a file of the directory no tool may read in silence, or as the unit's own
    assert!(
        text(&o).contains("is the unit's own file")
            || text(&o).contains("extra.v is not a file of this unit"),
        "{}",
        text(&o)
    );
    assert_eq!(std::fs::read_to_string(&extra).unwrap(), "// the user's\n");
    // a report's page is listed with its SHA-256: edited, it is not replaced without --force
    let report = tmp.path().join("report");
    let args = ["report", "--n-bits", "4", "--cos-frac-bits", "8", "--out"];
    let o = specgen().args(args).arg(&report).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let page = report.join("index.html");
    let edited = std::fs::read_to_string(&page).unwrap() + "<!-- mine -->\n";
    std::fs::write(&page, &edited).unwrap();
    let o = specgen().args(args).arg(&report).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("index.html was changed since specgen wrote it"),
        "{}",
        text(&o)
    );
    assert_eq!(std::fs::read_to_string(&page).unwrap(), edited);
}

/// Finding 7: `vvp` kept running at 100 % CPU after SIGTERM/SIGINT to specgen, and `render
/// --models` left its temporary units. Children now die with specgen, and a signal removes
/// every temporary directory before specgen ends with 128 + the signal.
#[test]
fn children_and_temporaries_end_with_a_signalled_run() {
    require_tool("iverilog", "iverilog");
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(tmp.path(), "u", &["--stages", "4"]);
    for signal in [libc::SIGTERM, libc::SIGINT] {
        let mut run = specgen()
            .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"))
            .args([
                "cosim",
                "--simulator",
                "icarus",
                "--jobs",
                "1",
                "--vectors",
                "5000000",
                "--rtl",
            ])
            .arg(&unit)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let mut vvp = 0;
        wait_until("no vvp started", || {
            vvp = children(run.id())
                .into_iter()
                .find(|(_, c)| c == "vvp")
                .map_or(0, |(pid, _)| pid);
            vvp != 0
        });
        // SAFETY: a signal to our own child
        unsafe { libc::kill(run.id() as libc::pid_t, signal) };
        let status = run.wait().unwrap();
        assert_eq!(
            status.code(),
            Some(128 + signal),
            "specgen ends with 128 + the signal"
        );
        wait_until(
            &format!("vvp {vvp} outlived specgen (signal {signal})"),
            || ended(vvp),
        );
    }
    // render --models: its temporary units are gone after a signal
    let private = tmp.path().join("tmp");
    std::fs::create_dir(&private).unwrap();
    let mut run = specgen()
        .env("TMPDIR", &private)
        .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"))
        .args(["render", "--models", "quadratic,fitted,blinn", "--out"])
        .arg(tmp.path().join("r.png"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    wait_until("render made no temporary directory", || {
        std::fs::read_dir(&private).unwrap().count() > 0
    });
    // SAFETY: a signal to our own child
    unsafe { libc::kill(run.id() as libc::pid_t, libc::SIGINT) };
    let status = run.wait().unwrap();
    assert!(status.code() == Some(130) || status.success(), "{status:?}");
    let left: Vec<_> = std::fs::read_dir(&private)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "temporaries left: {left:?}");
}

/// Processes whose working directory is under `dir` (a killed build's `make`, `g++`, `cc1plus`).
fn working_under(dir: &Path) -> Vec<(u32, String)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(cwd) = std::fs::read_link(format!("/proc/{pid}/cwd")) else {
            continue;
        };
        if cwd.starts_with(dir) && !ended(pid) {
            let comm = std::fs::read_to_string(format!("/proc/{pid}/comm")).unwrap_or_default();
            out.push((pid, comm.trim().to_string()));
        }
    }
    out
}

/// `generate --config D/my.json --out D` deleted the user's file; any
/// specgen-looking `*.json` made its directory look like an earlier output. Now the command's own
/// input inside the output is refused, and a manifest vouches for its directory only when it is
/// one specgen wrote (its name, its fingerprint, every file it lists there and unchanged).
#[test]
fn a_users_config_or_a_copy_of_a_manifest_is_never_replaced() {
    let tmp = tempfile::tempdir().unwrap();
    let real = generate(tmp.path(), "real", &["--stages", "2"]);
    let manifest = std::fs::read_to_string(real.join("specular_unit.json")).unwrap();
    let edited = manifest.replace("\"stages\": 2", "\"stages\": 3");
    assert_ne!(edited, manifest);
    for (dir, file, text, as_config) in [
        ("own_input", "my.json", &edited, true),
        ("edited_copy", "my.json", &edited, false),
        ("unedited_copy", "my.json", &manifest, false),
        ("named_copy", "specular_unit.json", &manifest, false),
        ("named_edited", "specular_unit.json", &edited, false),
    ] {
        let d = tmp.path().join(dir);
        std::fs::create_dir(&d).unwrap();
        std::fs::write(d.join(file), text).unwrap();
        let mut cmd = specgen();
        cmd.arg("generate").arg("--out").arg(&d);
        if as_config {
            cmd.arg("--config").arg(d.join(file));
        }
        let o = cmd.output().unwrap();
        let said = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{dir}: {said}");
        assert_eq!(
            &std::fs::read_to_string(d.join(file)).unwrap(),
            text,
            "{dir}: the user's file is kept"
        );
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            1,
            "{dir}: nothing written"
        );
        if as_config {
            assert!(
                said.contains("--config") && said.contains("--out"),
                "{said}"
            );
        } else {
            assert!(said.contains(file), "{dir}: the stranger is named: {said}");
        }
    }
    // an output specgen wrote is still replaced
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&real)
        .args(["--stages", "3"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A `ccache.conf` planted where `CCACHE_DIR` points (a directory
/// others can write) never runs: ccache works in the simulator cache's own directory; a build
/// killed with SIGKILL leaves no process behind (`make`, `g++`, `cc1plus` die with specgen's
/// warden group) and its directories are swept by the next run, by their dead process id; a
/// cache under a directory others can write is refused.
#[test]
fn planted_build_state_never_runs_and_a_killed_build_leaves_nothing() {
    require_tool("verilator", "verilator");
    require_tool("ccache", "ccache");
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(
        tmp.path(),
        "u",
        &["--stages", "3", "--cos-frac-bits", "8", "--n-bits", "4"],
    );
    let evil = tmp.path().join("shared-ccache");
    std::fs::create_dir(&evil).unwrap();
    std::fs::set_permissions(&evil, std::fs::Permissions::from_mode(0o777)).unwrap();
    let pwned = tmp.path().join("pwned");
    std::fs::write(
        evil.join("ccache.conf"),
        format!("prefix_command = touch {}\n", pwned.display()),
    )
    .unwrap();
    let private = tmp.path().join("tmp");
    std::fs::create_dir(&private).unwrap();
    let cache = tmp.path().join("cache");
    let cosim = || {
        let mut c = specgen();
        c.env("SPECGEN_CACHE_DIR", &cache)
            .env("CCACHE_DIR", &evil)
            .env("TMPDIR", &private)
            .args([
                "cosim",
                "--simulator",
                "verilator",
                "--vectors",
                "2000",
                "--rtl",
            ])
            .arg(&unit);
        c
    };
    // killed while the harness compiles
    let mut run = cosim()
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    wait_until("no compiler started", || {
        working_under(&cache)
            .iter()
            .any(|(_, c)| c.contains("cc1plus") || c == "make" || c.contains("g++"))
    });
    let dead = run.id();
    // SAFETY: a signal to our own child
    unsafe { libc::kill(dead as libc::pid_t, libc::SIGKILL) };
    run.wait().unwrap();
    wait_until("the build's processes outlived specgen", || {
        working_under(&cache).is_empty()
    });
    let left = |dir: &Path| -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(&format!("-{dead}-")))
            .collect()
    };
    assert!(
        !left(&cache).is_empty() || !left(&private).is_empty(),
        "SIGKILL left the build's directories (else this test shows nothing)"
    );
    // the next run sweeps them, builds, and never runs the planted configuration
    let o = cosim().output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!pwned.exists(), "the planted ccache.conf ran");
    assert!(
        left(&cache).is_empty() && left(&private).is_empty(),
        "not swept: {:?} {:?}",
        left(&cache),
        left(&private)
    );
    assert!(
        cache.join("ccache").is_dir(),
        "ccache's directory is the cache's own"
    );
    // a cache below a directory others can write is refused, naming it
    let open = tmp.path().join("open");
    std::fs::create_dir(&open).unwrap();
    std::fs::set_permissions(&open, std::fs::Permissions::from_mode(0o777)).unwrap();
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", open.join("cache"))
        .args(["cosim", "--vectors", "10", "--rtl"])
        .arg(&unit)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success()
            && said.contains("writable by others")
            && said.contains(&open.display().to_string()),
        "{said}"
    );
}

/// `--trace DIR/new.v` wrote a VCD among the unit's files, and every later
/// command then compiled it. An output inside the unit's directory under a name a later command
/// reads (`*.v`, `*.hex`, `*.json`, …) is refused, naming it, and nothing is written.
#[test]
fn an_output_among_the_units_files_is_refused_when_a_later_command_would_read_it() {
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(tmp.path(), "u", &["--stages", "2"]);
    let before = std::fs::read_dir(&d).unwrap().count();
    for (cmd, name) in [
        ("cosim", "new.v"),
        ("cosim", "x.hex"),
        ("prove", "t.json"),
        ("prove", "t.sv"),
    ] {
        let out = d.join(name);
        let o = specgen()
            .arg(cmd)
            .arg("--rtl")
            .arg(&d)
            .arg("--trace")
            .arg(&out)
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{cmd} --trace {name}: {said}");
        assert!(
            said.contains(name) && said.contains("later command"),
            "{said}"
        );
        assert!(!out.exists());
    }
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), before);
}

/// A cache entry whose program is a FIFO hung cosim, one linked to /dev/zero
/// read until memory ran out. Entries are read as every input is (a regular file, bounded, never
/// blocking): such an entry is damaged, built again, and the run passes.
#[test]
fn a_planted_cache_entry_is_rebuilt_never_read_forever() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(
        tmp.path(),
        "u",
        &["--stages", "1", "--cos-frac-bits", "7", "--n-bits", "4"],
    );
    let cache = tmp.path().join("cache");
    let cosim = || {
        let mut run = specgen()
            .env("SPECGEN_CACHE_DIR", &cache)
            .args([
                "cosim",
                "--simulator",
                "verilator",
                "--vectors",
                "500",
                "--rtl",
            ])
            .arg(&unit)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        finished_within_guard(&mut run, "cosim hung on a planted cache entry")
    };
    assert!(cosim().success());
    let entry = std::fs::read_dir(&cache)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("verilator-")
        })
        .unwrap();
    let harness = entry.join("harness");
    std::fs::remove_file(&harness).unwrap();
    assert!(Command::new("mkfifo")
        .arg(&harness)
        .status()
        .unwrap()
        .success());
    assert!(cosim().success(), "a FIFO for a program");
    std::fs::remove_file(&harness).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &harness).unwrap();
    assert!(cosim().success(), "a link to /dev/zero for a program");
    assert!(
        std::fs::symlink_metadata(&harness).unwrap().is_file(),
        "built again"
    );
}
