//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The narrow widths of the delay model's calibration grid, F/N/B/FI 8/6/4/8, as generate flags.
pub const NARROW: [&str; 8] = [
    "--cos-frac-bits",
    "8",
    "--n-bits",
    "6",
    "--color-bits",
    "4",
    "--intensity-frac-bits",
    "8",
];

/// The cut points of `model`'s datapath at default parameters (its deepest `--stages`).
pub fn default_cut_points(model: specgen::config::SpecularModel) -> u32 {
    let cfg = specgen::config::Config::new(specgen::config::Params {
        model,
        ..Default::default()
    })
    .unwrap();
    specgen::plan::Plan::new(cfg).unwrap().cut_points
}

/// Fails (never skips) when an external tool is missing: the README's test command installs them.
pub fn require_tool(tool: &str, package: &str) {
    let found = Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {tool}"))
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    assert!(found, "{tool} is required for this test: run `scripts/test.sh` (installs it) or `apt-get install -y {package}`");
}

/// The suite's job slots: one file per core in a directory of this checkout's, named by
/// `SPECGEN_JOBS` for every specgen this process starts and every tool it runs itself
/// ([`tool`]), so that however many tests run at once (cargo's threads, nextest's processes,
/// [`for_each_parallel`]), at most as many external tools run as there are cores: each holds a
/// slot (`flock`) from its start until its last child ends.
pub fn jobs() -> &'static Path {
    use std::os::unix::fs::PermissionsExt;
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("job-slots");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::set_permissions(&d, std::fs::Permissions::from_mode(0o700)).unwrap();
        let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
        for i in 0..cores {
            let slot = d.join(format!("slot{i}"));
            if !slot.exists() {
                std::fs::write(&slot, b"").unwrap();
            }
            std::fs::set_permissions(&slot, std::fs::Permissions::from_mode(0o600)).unwrap();
        }
        // the library's own tool runs in this process read it too
        std::env::set_var("SPECGEN_JOBS", &d);
        d
    })
}

pub fn specgen() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_specgen"));
    c.env("SPECGEN_JOBS", jobs());
    c
}

/// An external tool the test runs itself, holding a job slot while it runs (see [`jobs`]).
pub fn tool(program: &str) -> Command {
    jobs();
    specgen::process::command(program)
}

/// A guard against a run that never ends, never a verdict: the limit on every wait in the
/// suite, many times what any of them takes on a loaded machine. Only a hang reaches it.
pub const HANG_GUARD_SECS: u64 = 600;

/// Waits until `cond` holds, polling; fails naming `what` only when the hang guard runs out.
pub fn wait_until(what: &str, mut cond: impl FnMut() -> bool) {
    let start = std::time::Instant::now();
    while !cond() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(HANG_GUARD_SECS),
            "infrastructure failure, not a verdict: {what} (the hang guard of {HANG_GUARD_SECS} s ran out)"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Waits for `child`, killing it and failing with `hang` when the hang guard runs out: the hang
/// a test is about would otherwise never end the suite.
pub fn finished_within_guard(
    child: &mut std::process::Child,
    hang: &str,
) -> std::process::ExitStatus {
    let mut status = None;
    let start = std::time::Instant::now();
    while status.is_none() {
        status = child.try_wait().unwrap();
        if status.is_none() && start.elapsed() > std::time::Duration::from_secs(HANG_GUARD_SECS) {
            let _ = child.kill();
            panic!("infrastructure failure, not a verdict: {hang} still running when the hang guard of {HANG_GUARD_SECS} s ran out");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    status.unwrap()
}

/// Runs `cmd` to its end with its output, under the hang guard (for a command whose bug would
/// be to block forever: on a FIFO, a device, a lock).
pub fn output_guarded(cmd: &mut Command, hang: &str) -> std::process::Output {
    use std::io::Read;
    let mut child = cmd
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let read_all = |mut from: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = from.read_to_end(&mut v);
            v
        })
    };
    let stdout = read_all(Box::new(child.stdout.take().unwrap()));
    let stderr = read_all(Box::new(child.stderr.take().unwrap()));
    let status = finished_within_guard(&mut child, hang);
    std::process::Output {
        status,
        stdout: stdout.join().unwrap(),
        stderr: stderr.join().unwrap(),
    }
}

/// The children of process `pid` (from /proc), with their command names.
pub fn children(pid: u32) -> Vec<(u32, String)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(child) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(format!("/proc/{child}/stat")) else {
            continue;
        };
        // pid (comm) state ppid …
        let Some((comm, rest)) = stat.split_once(" (").and_then(|(_, r)| r.rsplit_once(") "))
        else {
            continue;
        };
        if rest
            .split_whitespace()
            .nth(1)
            .and_then(|p| p.parse::<u32>().ok())
            == Some(pid)
        {
            out.push((child, comm.to_string()));
        }
    }
    out
}

/// Whether process `pid` has ended (gone, or a zombie waiting for its new parent).
pub fn ended(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).map_or(true, |s| {
        s.rsplit_once(") ").is_some_and(|(_, r)| r.starts_with('Z'))
    })
}

/// Runs `specgen generate --out DIR args…` and returns DIR (inside `parent`).
pub fn generate(parent: &Path, name: &str, args: &[&str]) -> PathBuf {
    let dir = parent.join(name);
    let out = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&dir)
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "generate {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir
}

/// `f(i, item)` for every item, as many at a time as there are cores (for tests that run one
/// external tool per configuration); a panic in any fails the caller.
pub fn for_each_parallel<T: Sync>(items: &[T], f: impl Fn(usize, &T) + Sync) {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..cores.min(items.len()) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                match items.get(i) {
                    Some(item) => f(i, item),
                    None => break,
                }
            });
        }
    });
}

/// A cache directory for simulator builds shared by every test of this checkout: the caller's
/// own and writable by no one else (specgen refuses any other cache), whatever the umask.
pub fn cache_dir() -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    jobs();
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cosim-cache");
    std::fs::create_dir_all(&d).unwrap();
    std::fs::set_permissions(&d, std::fs::Permissions::from_mode(0o700)).unwrap();
    d
}

/// Configurations that exercise odd widths, pipeline depths from 0 to each datapath's full
/// depth, both roundings, both ROM styles, the interfaces and static colours: the options'
/// corners, written out. [`configs`] adds every model of `SpecularModel::ALL` twice.
pub const CONFIGS: &[&[&str]] = &[
    &[],
    &["--stages", "1", "--rom-style", "case"],
    &["--stages", "2", "--rounding", "exact"],
    &[
        "--stages",
        "3",
        "--cos-frac-bits",
        "11",
        "--n-bits",
        "7",
        "--color-bits",
        "5",
        "--intensity-frac-bits",
        "9",
        "--k",
        "0.5",
        "--k-frac-bits",
        "7",
    ],
    &[
        "--cos-frac-bits",
        "5",
        "--n-bits",
        "3",
        "--color-bits",
        "1",
        "--intensity-frac-bits",
        "13",
        "--k-frac-bits",
        "4",
        "--k",
        "1",
        "--rom-style",
        "case",
        "--rounding",
        "exact",
    ],
    &[
        "--stages",
        "6",
        "--cos-frac-bits",
        "17",
        "--n-bits",
        "12",
        "--color-bits",
        "13",
        "--intensity-frac-bits",
        "3",
        "--k",
        "0.0625",
        "--k-frac-bits",
        "19",
        "--top",
        "wide_unit",
    ],
    &["--arch", "paper", "--stages", "2"],
    &["--stages", "13", "--top", "deep_unit"],
    &["--model", "blinn-pow", "--stages", "3"],
    &[
        "--model",
        "blinn-pow",
        "--n-bits",
        "4",
        "--color-bits",
        "11",
        "--cos-frac-bits",
        "6",
        "--intensity-frac-bits",
        "4",
    ],
    &[
        "--arch",
        "paper",
        "--cos-frac-bits",
        "9",
        "--n-bits",
        "5",
        "--color-bits",
        "6",
        "--intensity-frac-bits",
        "11",
        "--k-frac-bits",
        "9",
        "--rom-style",
        "case",
    ],
    &["--model", "fitted", "--stages", "8"],
    &[
        "--model",
        "fitted",
        "--max-squarings",
        "1",
        "--n-bits",
        "6",
        "--cos-frac-bits",
        "9",
        "--color-bits",
        "5",
        "--intensity-frac-bits",
        "7",
        "--k-frac-bits",
        "10",
        "--stages",
        "2",
        "--rom-style",
        "case",
        "--top",
        "fit_unit",
    ],
    &["--model", "blinn", "--stages", "37"],
    &[
        "--model",
        "blinn",
        "--cos-frac-bits",
        "7",
        "--n-bits",
        "5",
        "--color-bits",
        "12",
        "--intensity-frac-bits",
        "6",
        "--stages",
        "4",
        "--rom-style",
        "case",
    ],
    // the interfaces, tags and static colours (indices 17..)
    &["--interface", "ready", "--tag-bits", "12", "--stages", "13"],
    &[
        "--interface",
        "axis",
        "--tag-bits",
        "64",
        "--colour",
        "static",
        "--model",
        "fitted",
        "--stages",
        "3",
        "--top",
        "axis_unit",
    ],
    &[
        "--colour",
        "static",
        "--tag-bits",
        "1",
        "--stages",
        "2",
        "--model",
        "blinn-pow",
    ],
    &[
        "--interface",
        "ready",
        "--model",
        "blinn",
        "--n-bits",
        "5",
        "--cos-frac-bits",
        "9",
        "--color-bits",
        "6",
        "--rom-style",
        "case",
    ],
];

/// The two configurations [`configs`] gives every model: at default widths, two stages; at
/// small widths behind a handshake, one stage.
pub fn model_configs(model: specgen::config::SpecularModel) -> [Vec<&'static str>; 2] {
    let m = model.name();
    [
        vec!["--model", m, "--stages", "2"],
        vec![
            "--model",
            m,
            "--cos-frac-bits",
            "7",
            "--n-bits",
            "4",
            "--color-bits",
            "5",
            "--intensity-frac-bits",
            "6",
            "--interface",
            "ready",
            "--stages",
            "1",
        ],
    ]
}

/// What the lint, co-simulation and synthesis tests draw from: [`CONFIGS`], then
/// [`model_configs`] of every model of `SpecularModel::ALL` that `CONFIGS` holds fewer than
/// twice (the one list of models: a model added there is linted, simulated and synthesised
/// with no line here changing; one `CONFIGS` already shapes twice is not built again).
pub fn configs() -> Vec<Vec<&'static str>> {
    let mut all: Vec<Vec<&'static str>> = CONFIGS.iter().map(|c| c.to_vec()).collect();
    let default = specgen::config::Params::default().model;
    for model in specgen::config::SpecularModel::ALL {
        let of_model = |args: &Vec<&str>| {
            args.iter()
                .position(|a| *a == "--model")
                .map_or(model == default, |i| args[i + 1] == model.name())
        };
        if all.iter().filter(|a| of_model(a)).count() < 2 {
            all.extend(model_configs(model));
        }
    }
    all
}

proptest::prop_compose! {
    /// A configuration of a `cos^n` model (blinn or blinn-pow) over every width range.
    pub fn power_config(model: specgen::config::SpecularModel)(
        f in specgen::config::COS_FRAC_BITS.min..=specgen::config::COS_FRAC_BITS.max,
        n in specgen::config::N_BITS.min..=specgen::config::N_BITS.max,
        b in specgen::config::COLOR_BITS.min..=specgen::config::COLOR_BITS.max,
        fi in specgen::config::INTENSITY_FRAC_BITS.min..=specgen::config::INTENSITY_FRAC_BITS.max,
    ) -> specgen::config::Config {
        specgen::config::Config::new(specgen::config::Params {
            cos_frac_bits: f, n_bits: n, color_bits: b, intensity_frac_bits: fi,
            model, ..specgen::config::Params::default()
        }).unwrap()
    }
}

proptest::prop_compose! {
    /// A configuration of `model` over every width range (n_bits up to 9 for the fit's sake).
    pub fn model_config(model: specgen::config::SpecularModel)(
        f in specgen::config::COS_FRAC_BITS.min..=specgen::config::COS_FRAC_BITS.max,
        n in 1u32..=9,
        b in specgen::config::COLOR_BITS.min..=specgen::config::COLOR_BITS.max,
        fi in specgen::config::INTENSITY_FRAC_BITS.min..=specgen::config::INTENSITY_FRAC_BITS.max,
        kf in specgen::config::K_FRAC_BITS.min..=specgen::config::K_FRAC_BITS.max,
        m in specgen::config::MAX_SQUARINGS.min..=specgen::config::MAX_SQUARINGS.max,
    ) -> specgen::config::Config {
        specgen::config::Config::new(specgen::config::Params {
            cos_frac_bits: f, n_bits: n, color_bits: b, intensity_frac_bits: fi, k_frac_bits: kf,
            max_squarings: m, model, ..specgen::config::Params::default()
        }).unwrap()
    }
}

/// Writes `text` as `file` of the unit in `dir` and makes its manifest list the new SHA-256, as
/// a faulty generator would have written them together (so the file checks pass and the
/// simulation has to find the fault).
pub fn rewrite_sealed(dir: &Path, file: &str, text: &str) {
    let sha = |b: &[u8]| -> String {
        <sha2::Sha256 as sha2::Digest>::digest(b)
            .iter()
            .map(|x| format!("{x:02x}"))
            .collect()
    };
    let path = dir.join(file);
    let before = std::fs::read(&path).unwrap();
    std::fs::write(&path, text).unwrap();
    let manifest = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "json"))
        .expect("a manifest");
    let m = std::fs::read_to_string(&manifest).unwrap();
    assert!(
        m.contains(&sha(&before)),
        "{file} is listed in {}",
        manifest.display()
    );
    std::fs::write(&manifest, m.replace(&sha(&before), &sha(text.as_bytes()))).unwrap();
}

/// The handshake faults both the simulation (`interfaces::faults_in_the_handshake_are_caught`)
/// and the proofs (`prove::the_stream_edge_…`) must catch: (name, file, from, to), each a
/// one-place edit of a generated `ready` unit with a 12-bit tag ([`apply_handshake_fault`]).
pub const HANDSHAKE_FAULTS: &[(&str, &str, &str, &str)] = &[
    // a result dropped on stall: the queue counts a result gone while out_ready is low
    ("dropped", BUFFER, "leaving = count != 2'd0 && ready;", "leaving = count != 2'd0;"),
    // payload changing while stalled
    ("unstable", BUFFER, "if (held_copy == 2'd0 || out_ready) out[HI:LO] <=", "if (1'b1) out[HI:LO] <="),
    // a result duplicated: the read pointer misses a step
    ("duplicated", BUFFER, "read_at      <= advance(read, read_at);", "read_at <= advance(read && read_at != 5, read_at);"),
    // a read started with no room in the queue: the result read has no register to go to
    ("queue_overrun", BUFFER, "queue_full <= !out_ready && (queue_full || (queue_two && read));", "queue_full <= 1'b0;"),
    // the occupancy thermometer loses a result: bit 2 never rises above bit 1
    (
        "thermometer",
        BUFFER,
        "else     stored_at_least[k] <= stored_level[k + 1] || (stored_level[k - 1] && grows_or_holds);",
        "else     stored_at_least[k] <= k == 2 ? 1'b0 : stored_level[k + 1] || (stored_level[k - 1] && grows_or_holds);",
    ),
    // the tag one stage off (the register before the last)
    ("tag_off", "specular_unit.v", "TAG_LAST", "TAG_BEFORE"),
    // credits miscounted: in_ready stays high as the last place fills
    ("overfull", BUFFER, "in_ready <= over_credits[DEPTH_LOG2];", "in_ready <= over_credits[DEPTH_LOG2] || over_credits == 0;"),
];

/// The output buffer's file in a unit with the default top.
const BUFFER: &str = "specular_unit_out_buffer.v";

/// Applies a fault of [`HANDSHAKE_FAULTS`] to the unit in `dir` (with a tag). `TAG_LAST`: the
/// tag's last word (`wire [11:0] tag_cZ = tag_line[59:48];`) takes the word before it instead.
pub fn apply_handshake_fault(dir: &Path, name: &str, file: &str, from: &str, to: &str) {
    let path = dir.join(file);
    let src = std::fs::read_to_string(&path).unwrap();
    let (from, to) = if from == "TAG_LAST" {
        let word = src
            .lines()
            .find(|l| l.starts_with("wire ") && l.contains("= tag_line["))
            .expect("the tag's last word");
        let select = &word[word.find("tag_line[").unwrap()..word.find(';').unwrap()];
        let (hi, lo) = select
            .trim_start_matches("tag_line[")
            .trim_end_matches(']')
            .split_once(':')
            .unwrap();
        let (hi, lo): (u32, u32) = (hi.parse().unwrap(), lo.parse().unwrap());
        let width = hi - lo + 1;
        (
            select.to_string(),
            format!("tag_line[{}:{}]", hi - width, lo - width),
        )
    } else {
        (from.to_string(), to.to_string())
    };
    assert_eq!(
        src.matches(&from).count(),
        1,
        "fault {name}: {from:?} must occur once in {file}"
    );
    std::fs::write(&path, src.replace(&from, &to)).unwrap();
}

/// The deepest `--stages` of the configuration `args` (from the range `generate` names).
pub fn deepest(args: &[&str]) -> String {
    let o = specgen()
        .args(["generate", "--out"])
        .arg(std::env::temp_dir().join("unused-never-written"))
        .args(args)
        .args(["--stages", "99"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(o.status.code(), Some(2), "{err}");
    // "... allowed 0..=N (the cut points ..."
    err.split("allowed 0..=")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .to_string()
}

/// The unit's Verilog: `<top>.v` and the modules it derives beside it (its output buffer, its
/// delay lines' memory).
pub fn unit_files(dir: &std::path::Path, top: &str) -> Vec<String> {
    let mut files = vec![format!("{top}.v")];
    for derived in ["_out_buffer.v", "_delay_ram.v"] {
        if dir.join(format!("{top}{derived}")).exists() {
            files.push(format!("{top}{derived}"));
        }
    }
    files
}
