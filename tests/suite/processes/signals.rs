//! What specgen runs, waited for and signalled: a job slot waited for with a bound, a stop and
//! a continue passed to the tool, a full disk named, a depth search bounded.

use super::*;

/// A malformed `SPECGEN_JOBS` (not a directory, or one without a slot
/// file) or `SPECGEN_JOBS_WAIT` is refused before anything runs, naming it (exit 2); a tool that
/// waits for a slot says so after 10 s and gives up at the bound, saying so (exit 1), instead of
/// waiting silently for ever.
#[test]
fn a_job_slot_is_waited_for_with_a_message_and_a_bound() {
    require_tool("iverilog", "iverilog");
    require_tool("flock", "util-linux");
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
    let empty = tmp.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let slots = tmp.path().join("slots");
    std::fs::create_dir(&slots).unwrap();
    let slot = slots.join("0");
    std::fs::write(&slot, "").unwrap();
    for (jobs, wait, names) in [
        (tmp.path().join("none"), "", "SPECGEN_JOBS="),
        (empty.clone(), "", "holds no slot file"),
        (slots.clone(), "soon", "SPECGEN_JOBS_WAIT=soon"),
    ] {
        let o = specgen()
            .env("SPECGEN_JOBS", &jobs)
            .env("SPECGEN_JOBS_WAIT", wait)
            .args(["eval", "--cos", "0.9", "--n", "4"])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{names}: {}", text(&o));
        assert!(text(&o).contains(names), "{names}: {}", text(&o));
    }
    // one slot, held by another process for the whole run: the wait is said and bounded
    let mut holder = std::process::Command::new("flock")
        .arg(&slot)
        .args(["sleep", "600"])
        .spawn()
        .unwrap();
    // (held once a try to take it fails: by state, not by a pause)
    wait_until("the holder to take the slot", || {
        !std::process::Command::new("flock")
            .args(["-n"])
            .arg(&slot)
            .arg("true")
            .status()
            .unwrap()
            .success()
    });
    let o = specgen()
        .env("SPECGEN_JOBS", &slots)
        .env("SPECGEN_JOBS_WAIT", "12")
        .args([
            "cosim",
            "--simulator",
            "icarus",
            "--vectors",
            "20",
            "--jobs",
            "1",
            "--rtl",
        ])
        .arg(&d)
        .output()
        .unwrap();
    let _ = holder.kill();
    let _ = holder.wait();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("waiting for a job slot of SPECGEN_JOBS="),
        "{}",
        text(&o)
    );
    assert!(
        text(&o).contains("came free within 12 s (SPECGEN_JOBS_WAIT)"),
        "{}",
        text(&o)
    );
}

/// The state letter of process `pid` (`/proc/<pid>/stat`'s third field: R, S, T…), if it lives.
fn process_state(pid: u32) -> Option<char> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    stat.rsplit_once(") ")?.1.chars().next()
}

/// The processes whose parent is `pid`.
fn children_of(pid: u32) -> Vec<u32> {
    std::fs::read_dir("/proc")
        .unwrap()
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse::<u32>().ok())
        .filter(|&c| {
            std::fs::read_to_string(format!("/proc/{c}/stat"))
                .ok()
                .and_then(|s| {
                    s.rsplit_once(") ")
                        .map(|(_, rest)| rest.split_whitespace().nth(1) == Some(&pid.to_string()))
                })
                .unwrap_or(false)
        })
        .collect()
}

/// Ctrl-Z stops specgen and the tool it runs (in a process group of
/// its own, which the terminal's signal does not reach), and `fg` continues both: the run then
/// ends as it would have.
#[test]
fn a_stop_stops_the_tool_and_a_continue_continues_it() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(tmp.path(), "u", &["--stages", "6"]);
    let mut run = specgen()
        .args(["synth", "--no-pnr", "--no-check", "--dsp", "--rtl"])
        .arg(&d)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let me = run.id();
    // yosys started (a child of specgen's), then the stop: waits by state, never by a count of
    // pauses (a loaded machine starts yosys later; only the hang guard ends a wait, named as
    // an infrastructure failure)
    let mut tool = None;
    wait_until("yosys to start under specgen, or specgen to end", || {
        tool = children_of(me).into_iter().find(|&c| {
            std::fs::read_to_string(format!("/proc/{c}/comm")).is_ok_and(|n| n.trim() == "yosys")
        });
        tool.is_some() || process_state(me).is_none_or(|s| s == 'Z')
    });
    let tool = tool.expect("yosys started under specgen");
    // SAFETY: signals to processes this test started
    unsafe { libc::kill(me as i32, libc::SIGTSTP) };
    wait_until("specgen and yosys to stop, or yosys to end", || {
        (process_state(me) == Some('T') && process_state(tool) == Some('T'))
            || process_state(tool).is_none_or(|s| s == 'Z')
    });
    assert!(
        process_state(me) == Some('T') && process_state(tool) == Some('T'),
        "specgen {:?} and yosys {:?} stopped",
        process_state(me),
        process_state(tool)
    );
    unsafe { libc::kill(me as i32, libc::SIGCONT) };
    // continued with specgen: yosys leaves the stopped state (else the run never ends)
    wait_until("yosys to continue with specgen", || {
        process_state(tool) != Some('T')
    });
    assert!(finished_within_guard(&mut run, "specgen synth after the continue").success());
}

/// A full disk during a co-simulation is named with its path. The
/// simulator's build and temporary files on a 300 KiB tmpfs (mounted for the test: as root, or in a user
/// namespace of its own): vvp's output is cut short, and the error says which disk is full and
/// which file was cut, not only that a line is malformed.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn a_full_disk_during_cosim_is_named_with_its_path() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let d = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "8",
            "--n-bits",
            "4",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
            "--interface",
            "ready",
            "--tag-bits",
            "4",
            "--stages",
            "2",
        ],
    );
    let small = tmp.path().join("small");
    std::fs::create_dir(&small).unwrap();
    let cosim = format!(
        "mount -t tmpfs -o size=300k tmpfs {0} && TMPDIR={0} SPECGEN_CACHE_DIR={1} {2} cosim --simulator icarus --vectors 2000 --jobs 1 --rtl {3}; s=$?; umount {0}; exit $s",
        small.display(),
        small.join("cache").display(),
        env!("CARGO_BIN_EXE_specgen"),
        d.display()
    );
    // SAFETY: geteuid has no preconditions
    let root = unsafe { libc::geteuid() } == 0;
    let mut sh = if root {
        std::process::Command::new("sh")
    } else {
        let mut c = std::process::Command::new("unshare");
        c.args(["--user", "--map-root-user", "--mount", "sh"]);
        c
    };
    let o = sh.arg("-c").arg(&cosim).output().unwrap();
    let said = text(&o);
    assert!(
        !said.contains("mount: ") && !said.contains("unshare: "),
        "a small tmpfs is needed for this test (root, or user namespaces): {said}"
    );
    assert_eq!(o.status.code(), Some(1), "{said}");
    assert!(
        said.contains(&format!("the disk holding {}", small.display()))
            && said.contains("is full")
            && said.contains("No space left on device"),
        "{said}"
    );
}

/// `generate --target ecp5 --rounding exact --k-frac-bits 24
/// --target-mhz …` took 5.5 minutes and 2 GB: the square of a 40-bit bracket's low 22 bits
/// was written as a table of 4 M lines (266 MB of Verilog a depth), and the depth search built
/// the combinational datapath again at every depth. At the widest widths of every model,
/// family and rounding, a search over every depth now builds the shared datapath once and
/// each depth once, and every generated unit stays small: work, not time, held to a bound.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn a_depth_search_at_the_widest_widths_is_bounded_work() {
    use specgen::config::{Arch, Params, Rounding, SpecularModel, Target};
    let mut planned = 0;
    for model in SpecularModel::ALL {
        for target in Target::ALL {
            for (rounding, arch) in [
                (Rounding::Exact, Arch::Lean),
                (Rounding::Faithful, Arch::Lean),
                (Rounding::Exact, Arch::Paper),
            ] {
                let params = Params {
                    model,
                    target,
                    rounding,
                    arch,
                    // (N at its default: the widest N only makes the fits slower, not the RTL larger)
                    cos_frac_bits: 20,
                    color_bits: 16,
                    intensity_frac_bits: 24,
                    k_frac_bits: 24,
                    ..Default::default()
                };
                let what = format!(
                    "{} {} {} {}",
                    model.name(),
                    target.name(),
                    rounding.name(),
                    arch.name()
                );
                let before = specgen::plan::datapath_builds();
                // a configuration the model does not take (paper is quadratic's) is refused, not planned
                let Ok(plan) = specgen::plan::Plan::from_params(params) else {
                    continue;
                };
                planned += 1;
                assert!(
                    specgen::plan::datapath_builds() - before <= 2,
                    "{what}: the shape built more than twice"
                );
                // a clock no depth reaches: the search plans every depth, and the calibrated
                // shapes it is read against (each once a process, its depth-free shape: at most
                // two builds each, fewer than 48 shapes a datapath and family)
                let before = specgen::plan::datapath_builds();
                let refused = specgen::timing::pick_stages(&plan, 1.0e6);
                let built = specgen::plan::datapath_builds() - before;
                assert!(refused.is_err(), "{what}: 1 THz picked");
                assert!(
                    built <= plan.cut_points as u64 + 96,
                    "{what}: {built} datapaths for {} depths",
                    plan.cut_points
                );
                // searched again, the shapes are known: each depth once
                let before = specgen::plan::datapath_builds();
                assert!(specgen::timing::pick_stages(&plan, 1.0e6).is_err());
                let built = specgen::plan::datapath_builds() - before;
                assert!(
                    built <= plan.cut_points as u64,
                    "{what}, searched again: {built} datapaths for {} depths",
                    plan.cut_points
                );
                {
                    let stages = plan.cut_points;
                    let files = specgen::emit::generate_files(&plan.with_stages(stages).unwrap());
                    let bytes: usize = files.iter().map(|(_, b)| b.len()).sum();
                    let rtl: usize = files
                        .iter()
                        .filter(|(n, _)| n.ends_with(".v"))
                        .map(|(_, b)| b.len())
                        .sum();
                    // the test bench's vectors are most of the bytes; the unit itself is a page
                    assert!(
                        rtl < 1 << 20,
                        "{what} at {stages} stages: {rtl} bytes of Verilog"
                    );
                    assert!(
                        bytes < 8 << 20,
                        "{what} at {stages} stages: {bytes} bytes in all"
                    );
                }
            }
        }
    }
    // every model faithful, and quadratic exact both lean and paper, on every family
    assert_eq!(
        planned,
        (SpecularModel::ALL.len() + 2) * Target::ALL.len(),
        "configurations planned"
    );
}
