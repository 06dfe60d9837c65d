//! Careless and hostile inputs on the real binary (issue: nothing passes silently): each ends
//! in a clear message and the right exit code, and nothing is lost or half-written.

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
fn out_through_a_symlink_lands_where_it_points_and_keeps_the_link() {
    let tmp = tempfile::tempdir().unwrap();
    let target = tmp.path().join("target");
    std::fs::create_dir(&target).unwrap();
    let link = tmp.path().join("lnk");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    // the link as given, and with a trailing separator (`link/`)
    let slashed = format!("{}/", link.display());
    for (round, out) in [link.to_str().unwrap(), slashed.as_str()]
        .into_iter()
        .enumerate()
    {
        let o = specgen().args(["generate", "--out", out]).output().unwrap();
        assert!(o.status.success(), "round {round}: {}", text(&o));
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink(),
            "the link is gone"
        );
        assert!(
            target.join("specular_unit.v").is_file()
                && link.join("specular_unit_cos_sp_rom.hex").is_file()
        );
    }
    // a dangling link: refused, the link left alone
    let dangling = tmp.path().join("dangling");
    std::os::unix::fs::symlink(tmp.path().join("nowhere"), &dangling).unwrap();
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&dangling)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("dangling"));
    assert!(std::fs::symlink_metadata(&dangling)
        .unwrap()
        .file_type()
        .is_symlink());
}

#[test]
fn leftovers_of_an_interrupted_swap_are_cleaned_and_a_concurrent_writer_is_told() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let tag = specgen::output::tag(&out);
    // what a generate killed after its exchange leaves: the old output in the staging name,
    // beside a sibling output's staging directory, which is not ours to remove
    std::fs::create_dir_all(
        tmp.path()
            .join(format!(".specgen-new-{tag}-XyZ789"))
            .join("old"),
    )
    .unwrap();
    let sibling = tmp.path().join(format!(
        ".specgen-new-{}-AbC123",
        specgen::output::tag(&tmp.path().join("p"))
    ));
    std::fs::create_dir_all(&sibling).unwrap();
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let mut names: Vec<String> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            sibling.file_name().unwrap().to_string_lossy().into_owned(),
            "o".into()
        ],
        "leftovers remain"
    );
    // killed between the two renames of the fallback (no exchange): the name is missing and the
    // old copy waits in .specgen-old-…/old; the next run puts it back, never deletes it
    let before = std::fs::read(out.join("specular_unit.v")).unwrap();
    let saved = tmp.path().join(format!(".specgen-old-{tag}-Qq1234"));
    std::fs::create_dir(&saved).unwrap();
    std::fs::rename(&out, saved.join("old")).unwrap();
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(!saved.exists() && std::fs::read(out.join("specular_unit.v")).unwrap() == before);
    // another writer of the same output: a clear message, exit 1, the output untouched
    // (it waits a bounded time, then names the holder)
    let lock = std::fs::File::create(tmp.path().join(format!(".specgen-lock-{tag}"))).unwrap();
    lock.lock().unwrap();
    std::io::Write::write_all(&mut &lock, b"4242\n").unwrap();
    let o = specgen()
        .args(["generate", "--stages", "2", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("another specgen (process 4242) has been writing"),
        "{}",
        text(&o)
    );
    assert_eq!(std::fs::read(out.join("specular_unit.v")).unwrap(), before);
    // … while a sibling output is written at the same time (the lock is per output)
    let o = specgen()
        .args(["generate", "--out"])
        .arg(tmp.path().join("p"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    lock.unlock().unwrap();
}

#[test]
fn the_swap_keeps_mode_and_group_and_refuses_the_current_directory() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let mode = |p: &std::path::Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o7777;
    // a new output gets what mkdir gives under the caller's umask; a replaced one keeps its mode
    let o = with_umask(specgen().args(["generate", "--out"]).arg(&out), 0o027)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(mode(&out), 0o750);
    assert_eq!(mode(&out.join("specular_unit.v")), 0o640);
    for kept in [0o700, 0o2755] {
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(kept)).unwrap();
        let o = specgen()
            .args(["generate", "--stages", "2", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o));
        assert_eq!(mode(&out), kept, "the mode of the output directory changed");
    }
    // `--out .` and a directory holding the current one: one line of reason, exit 2, untouched
    let before = std::fs::read(out.join("specular_unit.v")).unwrap();
    for (cwd, arg) in [
        (out.clone(), "."),
        (out.clone(), out.to_str().unwrap()),
        (out.join("."), ".."),
    ] {
        let o = specgen()
            .current_dir(&cwd)
            .args(["generate", "--out", arg])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "--out {arg}: {}", text(&o));
        assert!(
            text(&o).contains("current directory"),
            "--out {arg}: {}",
            text(&o)
        );
    }
    assert_eq!(std::fs::read(out.join("specular_unit.v")).unwrap(), before);
    // a parent that cannot take the staging directory (sysfs: read-only even to root)
    let o = specgen()
        .args(["generate", "--out", "/sys/specgen-never"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("its parent /sys is not writable") && text(&o).lines().count() == 1,
        "{}",
        text(&o)
    );
}

/// `cmd` run under `mask` as its umask.
fn with_umask(cmd: &mut Command, mask: u32) -> &mut Command {
    use std::os::unix::process::CommandExt;
    // SAFETY: umask is async-signal-safe and touches no memory
    unsafe {
        cmd.pre_exec(move || {
            libc::umask(mask as libc::mode_t);
            Ok(())
        })
    }
}

#[test]
fn single_file_outputs_go_through_links_into_fifos_and_keep_modes() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().unwrap();
    let mode = |p: &std::path::Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o7777;
    // a new file under umask 077; a replaced file keeps its mode
    let f = tmp.path().join("rom.hex");
    let o = with_umask(specgen().args(["rom", "-o"]).arg(&f), 0o077)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(mode(&f), 0o600);
    std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o640)).unwrap();
    let o = specgen().args(["rom", "-o"]).arg(&f).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(mode(&f), 0o640);
    // through a symbolic link: the target is written, the link stays
    let link = tmp.path().join("lnk.hex");
    std::os::unix::fs::symlink("rom.hex", &link).unwrap();
    std::fs::write(&f, "").unwrap();
    let o = specgen().args(["rom", "-o"]).arg(&link).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink(),
        "the link was replaced"
    );
    assert!(
        std::fs::read(&f).unwrap().len() > 100,
        "nothing written through the link"
    );
    // a FIFO gets the stream: its reader receives the table, and it stays a FIFO
    let fifo = tmp.path().join("fifo");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let o = specgen().args(["rom", "-o"]).arg(&fifo).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(reader.join().unwrap(), std::fs::read(&f).unwrap());
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    // what a run killed mid-write left is removed by the next run writing that file; the
    // temporary file of a run still going (this test's own process) is not touched
    let tag = specgen::output::tag(&f);
    let orphan = tmp.path().join(format!(".specgen-{tag}-4194305-AbC123"));
    let live = tmp
        .path()
        .join(format!(".specgen-{tag}-{}-XyZ789", std::process::id()));
    std::fs::write(&orphan, "half").unwrap();
    std::fs::write(&live, "busy").unwrap();
    let o = specgen().args(["rom", "-o"]).arg(&f).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        !orphan.exists() && live.exists(),
        "orphan removed, live kept"
    );
    std::fs::remove_file(&live).unwrap();
    // a directory is refused and left alone
    let o = specgen()
        .args(["rom", "-o"])
        .arg(tmp.path())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("it is a directory"), "{}", text(&o));
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

#[test]
fn a_manifest_that_disagrees_with_the_rtl_is_reported_as_such() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "u", &[]);
    let m = dir.join("specular_unit.json");
    std::fs::write(
        &m,
        std::fs::read_to_string(&m)
            .unwrap()
            .replace("\"color_bits\": 8", "\"color_bits\": 10"),
    )
    .unwrap();
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["cosim", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("its parameters are not the ones specgen wrote it with (fingerprint"),
        "{}",
        text(&o)
    );
    // without fingerprints (the files of an older specgen): the ports are compared
    let drop_line = |path: &std::path::Path, key: &str| {
        let t = std::fs::read_to_string(path).unwrap();
        let line = t.lines().find(|l| l.contains(key)).unwrap().to_string();
        std::fs::write(path, t.replace(&format!("{line}\n"), "")).unwrap();
    };
    drop_line(&m, "\"fingerprint\"");
    drop_line(&dir.join("specular_unit.v"), "// Fingerprint: ");
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["cosim", "--edited", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("disagree with the manifest")
            && text(&o).contains(
                "spec_r is output of 8 bits in the RTL, output of 10 bits by the manifest"
            ),
        "{}",
        text(&o)
    );
}

/// The unit's header repeats the manifest's fingerprint, and the manifest lists each file's
/// SHA-256: a unit of another configuration beside the manifest, or a file changed since
/// specgen wrote it, is named before anything is simulated (exit 2); `--edited` accepts a
/// changed RTL on purpose.
#[test]
fn files_that_are_not_what_the_manifest_lists_are_named() {
    let tmp = tempfile::tempdir().unwrap();
    let fitted = generate(tmp.path(), "fitted", &["--model", "fitted"]);
    let blinn = generate(tmp.path(), "blinn", &["--model", "blinn"]);
    std::fs::copy(
        blinn.join("specular_unit.v"),
        fitted.join("specular_unit.v"),
    )
    .unwrap();
    for cmd in [
        &["cosim"][..],
        &["vectors", "--count", "10", "--out", "/dev/null"][..],
        &["synth", "--no-pnr", "--verify"][..],
    ] {
        let o = specgen()
            .env("SPECGEN_CACHE_DIR", cache_dir())
            .args(cmd)
            .arg("--rtl")
            .arg(&fitted)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {}", text(&o));
        assert!(
            text(&o).contains("was generated for another configuration (fingerprint"),
            "{cmd:?}: {}",
            text(&o)
        );
    }
    // one changed line in the unit: refused, named; accepted with --edited (and then right)
    let dir = generate(tmp.path(), "u", &["--stages", "2"]);
    let v = dir.join("specular_unit.v");
    std::fs::write(
        &v,
        std::fs::read_to_string(&v)
            .unwrap()
            .replacen("// Formula:", "// formula, reworded:", 1),
    )
    .unwrap();
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["cosim", "--vectors", "100", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit.v is not the file specgen wrote")
            && text(&o).contains("--edited"),
        "{}",
        text(&o)
    );
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["cosim", "--edited", "--vectors", "100", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
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

/// A closed pipe ends the output quietly (exit 0, as `head` expects), a full device
/// is an error naming standard output (exit 1) — never a panic (101).
#[test]
fn a_closed_or_full_stdout_is_not_a_panic() {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = specgen()
        .args(["rom", "--format", "hex"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 4];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    if std::path::Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = specgen()
            .args(["eval", "--cos", "0.9", "--n", "10"])
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1));
        assert!(String::from_utf8_lossy(&o.stderr).contains("standard output"));
    }
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

/// An output flag naming one of the unit's own files is refused before any work (exit 2),
/// and the file is left as it was.
#[test]
fn outputs_never_replace_the_commands_inputs() {
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(tmp.path(), "u", &[]);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "cosim".into(),
                "--trace".into(),
                d.join("specular_unit.v").display().to_string(),
            ],
            "specular_unit.v",
        ),
        (
            vec![
                "cosim".into(),
                "--trace".into(),
                d.join("specular_unit.json").display().to_string(),
            ],
            "specular_unit.json",
        ),
        (
            vec![
                "render".into(),
                "--model-only".into(),
                "--out".into(),
                d.join("specular_unit.v").display().to_string(),
            ],
            "specular_unit.v",
        ),
        (
            vec![
                "vectors".into(),
                "--out".into(),
                d.join("specular_unit_cos_sp_rom.hex").display().to_string(),
            ],
            "specular_unit_cos_sp_rom.hex",
        ),
        (
            vec![
                "synth".into(),
                "--no-pnr".into(),
                "--json".into(),
                d.join("specular_unit.v").display().to_string(),
            ],
            "specular_unit.v",
        ),
        (
            vec![
                "synth".into(),
                "--no-pnr".into(),
                "--pnr-log".into(),
                d.join("specular_unit.core").display().to_string(),
            ],
            "specular_unit.core",
        ),
    ];
    for (args, file) in cases {
        let before = std::fs::read(d.join(file)).unwrap();
        let o = specgen().args(&args).arg("--rtl").arg(&d).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(
            text(&o).contains("the unit's own file"),
            "{args:?}: {}",
            text(&o)
        );
        assert_eq!(
            std::fs::read(d.join(file)).unwrap(),
            before,
            "{args:?} changed {file}"
        );
    }
}

/// `report --hw` takes only synthesis results: a manifest, `{}`, an unknown model, a FIFO or
/// a device are refused (exit 2) without hanging; a FIFO named `*.json` in an RTL directory is
/// never opened.
#[test]
fn hw_results_and_manifests_are_read_only_when_they_are_what_they_claim() {
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--n-bits",
            "4",
            "--cos-frac-bits",
            "8",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
        ],
    );
    let fifo = tmp.path().join("pipe.json");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let write = |name: &str, text: &str| {
        let p = tmp.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let cases = [
        (d.join("specular_unit.json"), "manifest"),
        (write("empty.json", "{}"), "no \"model\""),
        (
            write(
                "odd.json",
                r#"{"model": "phong", "target": "ice40", "luts": 1, "dsp_blocks": 0}"#,
            ),
            "unknown model",
        ),
        (fifo.clone(), "regular file"),
        (PathBuf::from("/dev/zero"), "regular file"),
    ];
    for (hw, why) in cases {
        let out = tmp.path().join("rep");
        let o = output_guarded(
            specgen()
                .args(["report", "--n-bits", "4", "--cos-frac-bits", "8", "--out"])
                .arg(&out)
                .arg("--hw")
                .arg(&hw),
            "report blocks on --hw",
        );
        assert_eq!(o.status.code(), Some(2), "{}: {}", hw.display(), text(&o));
        assert!(
            text(&o).contains("--hw") && text(&o).contains(why),
            "{}: {}",
            hw.display(),
            text(&o)
        );
        assert!(!out.exists());
    }
    // a FIFO among the unit's files is skipped, not opened (which would block)
    assert!(Command::new("mkfifo")
        .arg(d.join("zz.json"))
        .status()
        .unwrap()
        .success());
    let o = specgen()
        .args(["vectors", "--count", "3", "--rtl"])
        .arg(&d)
        .arg("--out")
        .arg(tmp.path().join("v.csv"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
}

/// `synth` asked for Fmax without the place-and-route tool fails (exit 1) and says how to get
/// area figures alone; it never exits 0 with no Fmax.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn synth_without_nextpnr_fails_when_fmax_is_asked_for() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--n-bits",
            "4",
            "--cos-frac-bits",
            "8",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
        ],
    );
    // the PATH's tools without nextpnr
    let bin = tmp.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    for dir in std::env::split_paths(&std::env::var_os("PATH").unwrap()) {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let name = entry.file_name();
            if !name.to_string_lossy().starts_with("nextpnr") && !bin.join(&name).exists() {
                std::os::unix::fs::symlink(entry.path(), bin.join(&name)).unwrap();
            }
        }
    }
    let o = specgen()
        .env("PATH", &bin)
        .args(["synth", "--target", "ice40", "--seeds", "1", "--rtl"])
        .arg(&d)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("nextpnr-ice40 not found") && text(&o).contains("--no-pnr"),
        "{}",
        text(&o)
    );
    let o = specgen()
        .env("PATH", &bin)
        .args(["synth", "--target", "ice40", "--no-pnr", "--rtl"])
        .arg(&d)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
}

/// `generate` and `report` never replace each other's output, and a file of a previous output
/// edited by hand is refused (naming it) unless `--force`.
#[test]
fn outputs_of_another_kind_or_edited_by_hand_are_not_replaced() {
    let tmp = tempfile::tempdir().unwrap();
    let small = ["--n-bits", "4", "--cos-frac-bits", "8"];
    let unit = generate(tmp.path(), "unit", &small);
    let rep = tmp.path().join("rep");
    let o = specgen()
        .args(["report", "--out"])
        .arg(&rep)
        .args(small)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    // each refuses the other's directory, which stays as it was
    let o = specgen()
        .args(["report", "--out"])
        .arg(&unit)
        .args(small)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("not a report") && unit.join("specular_unit.v").exists(),
        "{}",
        text(&o)
    );
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&rep)
        .args(small)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("not a unit") && rep.join("index.html").exists(),
        "{}",
        text(&o)
    );
    // an unedited previous output is replaced; an edited one only with --force
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&unit)
        .args(small)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let v = unit.join("specular_unit.v");
    let mut edited = std::fs::read_to_string(&v).unwrap();
    edited.push_str("// my change\n");
    std::fs::write(&v, &edited).unwrap();
    let o = specgen()
        .args(["generate", "--out"])
        .arg(&unit)
        .args(small)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit.v was changed") && text(&o).contains("--force"),
        "{}",
        text(&o)
    );
    assert_eq!(
        std::fs::read_to_string(&v).unwrap(),
        edited,
        "the edited file must stay"
    );
    let o = specgen()
        .args(["generate", "--force", "--out"])
        .arg(&unit)
        .args(small)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(!std::fs::read_to_string(&v).unwrap().contains("my change"));
}

/// Every simulation has a time limit: RTL with a zero-delay loop (two processes that wake each
/// other at time 0) hangs vvp forever; cosim stops it and says why (exit 1).
#[test]
fn a_zero_delay_loop_is_stopped_by_the_time_limit() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "loop", &["--stages", "2"]);
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let looped = "reg zero_delay_a = 1'b0, zero_delay_b = 1'b0;\nalways @(zero_delay_a) zero_delay_b = ~zero_delay_a;\n\
                  always @(zero_delay_b) zero_delay_a = zero_delay_b;\nendmodule";
    std::fs::write(&v, src.replacen("endmodule", looped, 1)).unwrap();
    let o = output_guarded(
        specgen()
            .args([
                "cosim",
                "--edited",
                "--simulator",
                "icarus",
                "--vectors",
                "50",
                "--rtl",
            ])
            .arg(&dir)
            .env("SPECGEN_SIM_TIMEOUT", "2")
            .env("SPECGEN_CACHE_DIR", tmp.path().join("cache")),
        "the simulation's limit did not stop a zero-delay loop",
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("did not finish within 2 s"),
        "{}",
        text(&o)
    );
}

/// `synth --verify` checks the RTL against the golden model before the netlist: a faulty RTL
/// (here with a manifest that lists it, as a faulty generator would write) is named as such,
/// and yosys is not blamed.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn verify_blames_a_faulty_rtl_not_yosys() {
    require_tool("yosys", "yosys");
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "u", &["--stages", "2"]);
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let line = src
        .lines()
        .find(|l| l.starts_with("assign intensity"))
        .expect("the intensity output")
        .to_string();
    rewrite_sealed(
        &dir,
        "specular_unit.v",
        &src.replace(&line, &line.replace("= ", "= 16'h1 ^ ")),
    );
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args([
            "synth",
            "--no-pnr",
            "--verify",
            "--verify-vectors",
            "300",
            "--rtl",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("itself differs from the golden model")
            && !text(&o).contains("synthesis tool changed"),
        "{}",
        text(&o)
    );
}

/// A directory swapped by `generate` while `cosim` reads it: the run says the directory
/// changed (exit 1) instead of reporting the new unit's outputs as mismatches of the old.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn cosim_says_when_its_directory_changed_during_the_run() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "race", &["--stages", "2"]);
    let run = specgen()
        .env("SPECGEN_CACHE_DIR", tmp.path().join("cache"))
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "200000",
            "--jobs",
            "1",
            "--rtl",
        ])
        .arg(&dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // the swap lands while the simulator runs, whatever the machine's speed: the simulator is
    // held stopped (SIGSTOP) until it is done
    let mut vvp = 0;
    wait_until("no vvp started", || {
        vvp = children(run.id())
            .into_iter()
            .find(|(_, c)| c == "vvp")
            .map_or(0, |(pid, _)| pid);
        vvp != 0
    });
    // SAFETY: signals to a process of this test's
    unsafe { libc::kill(vvp as libc::pid_t, libc::SIGSTOP) };
    let o = specgen()
        .args(["generate", "--stages", "3", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    unsafe { libc::kill(vvp as libc::pid_t, libc::SIGCONT) };
    assert!(o.status.success(), "{}", text(&o));
    let o = run.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("changed during the run") && !text(&o).contains("first mismatch"),
        "{}",
        text(&o)
    );
}

/// A damaged entry of the simulator cache (its program truncated) is built again, not run.
#[test]
fn a_damaged_cache_entry_is_rebuilt() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "u", &["--stages", "1"]);
    let cache = tmp.path().join("cache");
    let run = || {
        specgen()
            .env("SPECGEN_CACHE_DIR", &cache)
            .args([
                "cosim",
                "--simulator",
                "icarus",
                "--vectors",
                "200",
                "--rtl",
            ])
            .arg(&dir)
            .output()
            .unwrap()
    };
    let o = run();
    assert!(
        o.status.success() && !text(&o).contains("(cached)"),
        "{}",
        text(&o)
    );
    let entry = std::fs::read_dir(&cache)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.join("sim.vvp").is_file())
        .expect("a cache entry");
    std::fs::write(entry.join("sim.vvp"), b"").unwrap();
    let o = run();
    assert!(
        o.status.success() && !text(&o).contains("(cached)"),
        "the damaged entry was used: {}",
        text(&o)
    );
    let o = run();
    assert!(
        o.status.success() && text(&o).contains("(cached)"),
        "{}",
        text(&o)
    );
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
