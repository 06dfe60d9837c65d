//! What the binary writes under hostile conditions: through links, after an interrupted swap,
//! beside a concurrent writer, with modes and groups kept; never over its inputs or over what is
//! not its own.

use super::*;

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
