//! The simulators: cached builds of the harnesses in `tb/`, and runs that stream vectors
//! through them into a [`Checker`].

mod cache;
mod records;
use cache::*;
pub use records::write_trace;
use records::*;

use super::{
    Checker, Cycle, Design, Mismatch, Recorded, Report, Sampled, SimTools, Simulator, Stimulus,
};
use crate::error::{self, input, Error as Failure};
use crate::models::{Model, Outputs};
use sha2::{Digest, Sha256};
use std::io::{BufRead, BufReader, IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

const VERILATOR_HARNESS: &str = include_str!("../../tb/verilator_harness.cpp");
const ICARUS_BENCH: &str = include_str!("../../tb/icarus_bench.v");

/// A built simulator, ready to run vectors.
pub struct Built {
    pub(crate) simulator: Simulator,
    pub(crate) dir: PathBuf,
    /// the program that runs an Icarus build
    pub(crate) vvp: String,
    /// true when this call compiled it (false: taken from the cache)
    pub fresh: bool,
}

/// Runs of at most this many cycles get a Verilator model compiled without optimisation
/// (`-O0`): it compiles about a second sooner and simulates at 2–8 M cycles/s instead of
/// 10–24 (lean and blinn at default widths), so below a few million cycles the build is what
/// costs; an exhaustive run takes the optimised build. Each is its own cache entry.
pub const QUICK_BUILD_CYCLES: u64 = 1_000_000;

/// Builds (or finds in the cache) the simulator for `design`, for a run of about `cycles`
/// clock cycles (its optimisation: [`QUICK_BUILD_CYCLES`]).
pub fn build(
    design: &Design,
    simulator: Simulator,
    tools: &SimTools,
    trace: bool,
    cycles: u64,
) -> Result<Built, Failure> {
    let opt = if cycles <= QUICK_BUILD_CYCLES {
        "-O0"
    } else {
        "-O2"
    };
    let top = design.cfg.top().to_string();
    let adapter = super::adapter::adapter(&design.cfg);
    let (tool, package, harness) = match simulator {
        Simulator::Verilator => (tools.verilator.as_str(), "verilator", VERILATOR_HARNESS),
        Simulator::Icarus => (tools.iverilog.as_str(), "iverilog", ICARUS_BENCH),
    };
    let version = tool_identity(tool, package)?;
    if simulator == Simulator::Icarus {
        tool_identity(&tools.vvp, "iverilog")?;
    }
    let vvp = tools.vvp.clone();
    let mut h = Sha256::new();
    let (clocked, tagged) = (design.cfg.clocked(), design.cfg.carried_tag_bits() > 0);
    for part in [
        version.as_str(),
        harness,
        &top,
        &adapter,
        &format!("{trace} {simulator:?} {clocked} {tagged} {opt} v5"),
    ] {
        h.update(part.as_bytes());
        h.update([0u8]);
    }
    // the build reads copies named src<i>.v (so no path, however named, reaches a compiler
    // or a compiled program): the key is every input of the build, whole
    let mut texts = Vec::new();
    for src in &design.sim_sources() {
        let text = crate::small_file::read_bytes(src, crate::small_file::UNIT_FILE_MAX)
            .map_err(|e| input(format!("{} {e}", src.display())))?;
        h.update((text.len() as u64).to_le_bytes());
        h.update(&text);
        texts.push((src.clone(), text));
    }
    let key: String = h
        .finalize()
        .iter()
        .take(12)
        .map(|b| format!("{b:02x}"))
        .collect();
    let root = cache_root()?;
    let dir = root.join(format!("{}-{top}-{key}", package));
    // an entry is used only when its program is the one built: `ok` holds its SHA-256, so a
    // damaged entry (truncated, deleted, overwritten) is removed and built again
    let program = |d: &Path| {
        d.join(match simulator {
            Simulator::Verilator => "harness",
            Simulator::Icarus => "sim.vvp",
        })
    };
    // read as every other input is: a regular file, not through a link, bounded, never blocking
    // (an entry's program planted as a FIFO or a link to /dev/zero is damaged, not read forever)
    let digest = |p: &Path| {
        std::fs::symlink_metadata(p)
            .is_ok_and(|m| m.is_file())
            .then(|| crate::small_file::read_bytes(p, crate::small_file::PROGRAM_MAX).ok())
            .flatten()
            .map(|b| crate::bits::sha256_hex(&b, 32))
    };
    if own_entry(&dir) {
        if let Ok(stamp) = crate::small_file::read(&dir.join("ok"), 256) {
            if digest(&program(&dir)).is_some_and(|d| d == stamp.trim()) {
                return Ok(Built {
                    simulator,
                    dir,
                    vvp,
                    fresh: false,
                });
            }
        }
    }
    if std::fs::symlink_metadata(&dir).is_ok() {
        // damaged, partial or not ours: never used, removed (a link itself, not where it points)
        let _ = std::fs::remove_dir_all(&dir).or_else(|_| std::fs::remove_file(&dir));
    }
    // what killed runs left: build directories whose process is gone
    crate::output::remove_orphans(&root, ".build-", true);
    let work = crate::process::temp_dir_in(&root, &format!(".build-{}-", std::process::id()))
        .map_err(|e| {
            error::tool(
                "simulator",
                format!("cannot create a build directory in {}: {e}", root.display()),
            )
        })?;
    let mut sources = Vec::new();
    for (i, (_, text)) in texts.iter().enumerate() {
        let name = format!("src{i}.v");
        std::fs::write(work.path().join(&name), text)
            .map_err(|e| error::tool("simulator", e.to_string()))?;
        sources.push(PathBuf::from(name));
    }
    std::fs::write(work.path().join("cosim_top.v"), &adapter)
        .map_err(|e| error::tool("simulator", e.to_string()))?;
    sources.push(PathBuf::from("cosim_top.v"));
    let mut cmd;
    match simulator {
        Simulator::Verilator => {
            std::fs::write(work.path().join("harness.cpp"), harness)
                .map_err(|e| error::tool("simulator", e.to_string()))?;
            cmd = crate::process::command(tool);
            cmd.current_dir(work.path())
                .args([
                    "--cc",
                    "--exe",
                    "--build",
                    "-O3",
                    "--prefix",
                    "Vdut",
                    "--top-module",
                    "specgen_cosim_top",
                ])
                .args([
                    "-Wno-fatal",
                    "-Wno-lint",
                    "-Wno-style",
                    "-Mdir",
                    "obj",
                    "-o",
                    "../harness",
                ])
                .args([
                    "-j",
                    "2",
                    "-CFLAGS",
                    &format!(
                        "{opt} -DTRACE={} -DCLOCKED={} -DTAGGED={}",
                        trace as u8, clocked as u8, tagged as u8
                    ),
                ])
                .arg("-MAKEFLAGS")
                .arg(format!("OPT_FAST={opt}"));
            if trace {
                cmd.arg("--trace");
            }
            // every harness compiles the same Verilator runtime: with ccache there, compile it
            // once; ccache's directory (which holds its configuration, whose `prefix_command`
            // runs before every compile) is one of the cache's own, checked as the cache is, and
            // no other configuration file is read
            cmd.env("OBJCACHE", "").env_remove("CCACHE_CONFIGPATH");
            if on_path("ccache") {
                let ccache = root.join("ccache");
                if crate::output::private_dir(&ccache).is_ok() {
                    cmd.env("OBJCACHE", "ccache").env("CCACHE_DIR", &ccache);
                }
            }
            cmd.args(&sources).arg("harness.cpp");
        }
        Simulator::Icarus => {
            std::fs::write(work.path().join("bench.v"), harness)
                .map_err(|e| error::tool("simulator", e.to_string()))?;
            let c = &design.cfg;
            cmd = crate::process::command(tool);
            cmd.current_dir(work.path())
                .args(["-g2005", "-o", "sim.vvp", "-s", "specgen_icarus_bench"])
                .arg(format!("-DCOS_W={}", c.f() + 1))
                .arg(format!("-DN_W={}", c.n_bits()))
                .arg(format!("-DB_W={}", c.b()))
                .arg(format!("-DI_W={}", c.fi() + 1));
            cmd.arg("bench.v").args(&sources);
        }
    }
    let out = cmd
        .output()
        .map_err(|e| error::tool(tool, format!("cannot run {tool}: {e}")))?;
    if !out.status.success() {
        // the copies' names back to the user's files
        let mut log = String::from_utf8_lossy(&out.stderr).into_owned();
        // the RTL is to blame only when the tool names a line of it; else the tool itself failed
        // (a broken install, a wrapper that exits 1): its error, exit 1, never the RTL's
        let names_rtl = (0..texts.len()).any(|i| log.contains(&format!("src{i}.v:")))
            || log.contains("cosim_top.v:");
        for (i, (src, _)) in texts.iter().enumerate().rev() {
            log = log.replace(&format!("src{i}.v"), &src.display().to_string());
        }
        let tail: Vec<&str> = log.lines().rev().take(25).collect();
        let tail = tail.into_iter().rev().collect::<Vec<_>>().join("\n");
        if !names_rtl {
            return Err(error::tool(
                tool,
                format!("{tool} failed ({}) building the simulator of {}, naming no line of the RTL:\n{tail}", out.status, design.dir.display()),
            ));
        }
        return Err(input(format!(
            "{tool} could not build the RTL in {}:\n{tail}",
            design.dir.display()
        )));
    }
    let built = digest(&program(work.path())).ok_or_else(|| {
        error::tool(
            tool,
            format!("{tool} reported success but wrote no program"),
        )
    })?;
    std::fs::write(work.path().join("ok"), built)
        .map_err(|e| error::tool("simulator", e.to_string()))?;
    let kept = work.keep();
    if std::fs::rename(&kept, &dir).is_err() {
        // another process built it at the same time: use theirs
        let _ = std::fs::remove_dir_all(&kept);
    }
    Ok(Built {
        simulator,
        dir,
        vvp,
        fresh: true,
    })
}

/// Runs one stimulus through the built simulator, checking every cycle. `progress` counts
/// cycles done (for the progress bar).
/// How long one simulator run may take: a minute plus 2 ms a cycle under Verilator (millions of
/// cycles a second), 250 ms under Icarus (about 20 000 cycles a second on RTL, but some 20 on
/// a mapped netlist of thousands of cells: `synth --verify` of fitted at 65 stages took 8 211
/// cycles in about 7 minutes alone on 2 cores, 50 ms a cycle, and past the old limit of 50 ms
/// with two place-and-routes beside it), or `SPECGEN_SIM_TIMEOUT` seconds when set. A run past
/// it is killed and reported (a zero-delay loop in the RTL never advances time).
/// A malformed `SPECGEN_SIM_TIMEOUT` is an error naming it, never ignored.
fn time_limit(simulator: Simulator, cycles: u64) -> Result<std::time::Duration, Failure> {
    let per_cycle = match simulator {
        Simulator::Verilator => 2,
        Simulator::Icarus => 250,
    };
    match std::env::var_os("SPECGEN_SIM_TIMEOUT").filter(|v| !v.is_empty()) {
        Some(v) => match v.to_str().and_then(|s| s.trim().parse::<u64>().ok()).filter(|s| (1..=1_000_000).contains(s)) {
            Some(s) => Ok(std::time::Duration::from_secs(s)),
            None => Err(input(format!("SPECGEN_SIM_TIMEOUT={} is not a time limit; allowed whole seconds 1..=1000000 (or unset)", v.to_string_lossy()))),
        },
        None => Ok(std::time::Duration::from_secs(60) + std::time::Duration::from_millis(cycles.saturating_mul(per_cycle))),
    }
}

/// Kills process `pid` unless the returned sender is dropped (or sent to) within `limit`;
/// the flag tells afterwards whether it was killed.
pub(crate) fn watchdog(
    pid: u32,
    limit: std::time::Duration,
) -> (
    std::sync::mpsc::Sender<()>,
    std::sync::Arc<std::sync::atomic::AtomicBool>,
) {
    let (tx, rx) = std::sync::mpsc::channel::<()>();
    let fired = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let flag = fired.clone();
    std::thread::spawn(move || {
        if let Err(std::sync::mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(limit) {
            flag.store(true, Ordering::SeqCst);
            // SAFETY: a signal to our own child, which has not been waited for (the sender is
            // still alive), so its pid is not reused
            unsafe { libc::kill(pid as libc::pid_t, libc::SIGKILL) };
        }
    });
    (tx, fired)
}

fn timed_out(tool: &str, limit: std::time::Duration, len: u64) -> Failure {
    error::tool(
        tool,
        format!(
            "the simulation of {len} cycles did not finish within {} s and was stopped: a zero-delay loop in the RTL? (on a slower machine, set SPECGEN_SIM_TIMEOUT to more seconds)",
            limit.as_secs()
        ),
    )
}

pub fn run_one(
    built: &Built,
    design: &Design,
    model: &Model,
    stim: &dyn Stimulus,
    run: usize,
    progress: &AtomicU64,
    env: &[(&str, &Path)],
) -> Result<Report, Failure> {
    let mut checker = Checker::new(model, run);
    match built.simulator {
        Simulator::Verilator => {
            if !checker.digestible() {
                run_verilator(built, design, &mut checker, stim, progress, env, false)?;
                return Ok(checker.report);
            }
            if run_verilator(built, design, &mut checker, stim, progress, env, true)? {
                return Ok(checker.report);
            }
            // a batch's digest differed: run again with every record compared, which finds the
            // first mismatch and describes it
            let mut checker = Checker::new(model, run);
            run_verilator(
                built,
                design,
                &mut checker,
                stim,
                &AtomicU64::new(0),
                env,
                false,
            )?;
            if checker.report.first.is_none() {
                return Err(error::tool(
                    "verilator",
                    "the harness's digest of a batch differed from the golden model's, but none of its records did: a harness of another version?",
                ));
            }
            Ok(checker.report)
        }
        Simulator::Icarus => {
            let work = crate::process::temp_dir().map_err(|e| {
                crate::error::Error::io("create a temporary directory in", std::env::temp_dir(), e)
            })?;
            let vin = work.path().join("vectors.in");
            let vout = work.path().join("vectors.out");
            {
                let mut w = std::io::BufWriter::new(
                    std::fs::File::create(&vin)
                        .map_err(|e| crate::error::Error::io("write", &vin, e))?,
                );
                for i in 0..stim.len() {
                    let c = stim.cycle(i);
                    let x = c.inputs;
                    // ks_load in bit 0 of its column, the clock enable low in bit 1
                    let (v, r, o, l) = (
                        c.valid as u8,
                        c.rst as u8,
                        !c.stall as u8,
                        c.load as u8 | (c.disabled as u8) << 1,
                    );
                    writeln!(
                        w,
                        "{v:x} {r:x} {:x} {:x} {:x} {:x} {:x} {o:x} {l:x} {:x}",
                        x.cos_g, x.n, x.ks[0], x.ks[1], x.ks[2], c.tag
                    )
                    .map_err(|e| crate::error::Error::io("write", &vin, e))?;
                }
                w.flush()
                    .map_err(|e| crate::error::Error::io("write", &vin, e))?;
            }
            let child = crate::process::command(&built.vvp)
                .current_dir(&design.dir)
                .arg("-n")
                .arg(built.dir.join("sim.vvp"))
                .arg(format!("+vec_in={}", vin.display()))
                .arg(format!("+vec_out={}", vout.display()))
                .stdin(Stdio::null())
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .map_err(|e| {
                    error::tool(
                        "vvp",
                        format!("cannot run vvp (Debian package `iverilog`): {e}"),
                    )
                })?;
            let limit = time_limit(Simulator::Icarus, stim.len())?;
            let (alive, fired) = watchdog(child.id(), limit);
            let out = child
                .wait_with_output()
                .map_err(|e| error::tool("vvp", e.to_string()))?;
            drop(alive);
            if fired.load(Ordering::SeqCst) {
                return Err(timed_out("vvp", limit, stim.len()));
            }
            if !out.status.success() {
                return Err(error::tool(
                    "vvp",
                    format!("vvp failed: {}", String::from_utf8_lossy(&out.stderr)),
                ));
            }
            let said = String::from_utf8_lossy(&out.stdout);
            let file = std::fs::File::open(&vout).map_err(|e| {
                error::tool(
                    "vvp",
                    format!("vvp wrote no output ({e}); it said:\n{}", said.trim_end()),
                )
            })?;
            let mut t = 0;
            let (mut cycles, mut samples) = (Vec::new(), Vec::with_capacity(CHUNK as usize));
            let mut check = |t: u64, samples: &mut Vec<Sampled>| {
                let from = t - samples.len() as u64;
                stim.fill(from, samples.len() as u64, &mut cycles);
                checker.check_batch(from, &cycles, samples.drain(..));
            };
            for line in BufReader::new(file).lines() {
                let line = line.map_err(|e| error::tool("simulator", e.to_string()))?;
                let f: Vec<&str> = line.split_whitespace().collect();
                let hex = |s: &str| u32::from_str_radix(s, 16).unwrap_or(u32::MAX); // x/z never match
                if f.len() != 9 {
                    return Err(error::tool(
                        "vvp",
                        format!(
                            "vvp output line {t} is malformed: {line:?}{}",
                            full_disk(&vout)
                        ),
                    ));
                }
                let s = Sampled {
                    outputs: Outputs {
                        intensity: hex(f[2]),
                        spec: [hex(f[3]), hex(f[4]), hex(f[5])],
                        done: f[1] == "1",
                    },
                    valid: f[0] == "1",
                    in_ready: f[6] == "1",
                    idle: f[7] == "1",
                    tag: u64::from_str_radix(f[8], 16).unwrap_or(u64::MAX),
                };
                // outputs that are x/z before the pipeline fills are never compared (see Checker)
                if t >= stim.len() {
                    return Err(error::tool(
                        "vvp",
                        format!(
                            "vvp returned more than the {} cycles it was given",
                            stim.len()
                        ),
                    ));
                }
                samples.push(s);
                t += 1;
                if samples.len() as u64 == CHUNK {
                    check(t, &mut samples);
                }
            }
            check(t, &mut samples);
            if t != stim.len() {
                return Err(error::tool(
                    "vvp",
                    format!(
                        "vvp returned {t} of {} cycles{}",
                        stim.len(),
                        full_disk(&vout)
                    ),
                ));
            }
            progress.fetch_add(t, Ordering::Relaxed);
            Ok(checker.report)
        }
    }
}

/// Why a simulator's output file `out` may be cut short, when its disk is full: the words that
/// follow the error ("; the disk holding DIR is full: N bytes free"); empty otherwise (vvp's
/// `$fwrite` to a full disk fails without a word).
fn full_disk(out: &Path) -> String {
    use std::os::unix::ffi::OsStrExt;
    let dir = out.parent().unwrap_or(out);
    let Ok(c) = std::ffi::CString::new(dir.as_os_str().as_bytes()) else {
        return String::new();
    };
    // SAFETY: statvfs fills a struct we own from a NUL-terminated path
    let mut st: libc::statvfs = unsafe { std::mem::zeroed() };
    if unsafe { libc::statvfs(c.as_ptr(), &mut st) } != 0 {
        return String::new();
    }
    let free = st.f_bavail as u64 * st.f_frsize as u64;
    if free < 64 << 10 {
        format!(
            "; the disk holding {} is full ({free} bytes free): the simulator's output {} was cut short (No space left on device)",
            dir.display(),
            out.display()
        )
    } else {
        String::new()
    }
}

/// Gives a pipe to the harness room for a whole batch (1 MiB; the 64 KiB default wakes each
/// side several times a batch, which cost as much as the simulation). Best effort: a system
/// that refuses keeps the default, only slower.
fn widen_pipe(pipe: &impl std::os::fd::AsRawFd) {
    // SAFETY: F_SETPIPE_SZ on a pipe this process holds open; it changes only its capacity
    unsafe { libc::fcntl(pipe.as_raw_fd(), libc::F_SETPIPE_SZ, 1 << 20) };
}

/// Runs `stim` through the Verilator harness into `checker`. With `digest`, the harness
/// returns one digest a batch of what it sampled ([`super::checking::sample_hash`]) instead of
/// its records, checked against the golden model's ([`Checker::digest_batch`]); returns false
/// at the first batch whose digest differs (nothing is known then but that it does).
fn run_verilator(
    built: &Built,
    design: &Design,
    checker: &mut Checker,
    stim: &dyn Stimulus,
    progress: &AtomicU64,
    env: &[(&str, &Path)],
    digest: bool,
) -> Result<bool, Failure> {
    // the exhaustive sweep is made by the harness itself (no input stream); with records, each
    // batch's digest of what it applied is checked against the cycles checked here
    let sweep = stim.harness_sweep();
    let mut cmd = crate::process::command(built.dir.join("harness"));
    cmd.current_dir(&design.dir)
        .envs(env.iter().map(|(k, v)| (k, v.as_os_str())));
    match &sweep {
        Some(spec) => cmd.env("SPECGEN_SWEEP", spec).stdin(Stdio::null()),
        None => cmd.stdin(Stdio::piped()),
    };
    if digest {
        // what the harness folds: every cycle's outputs (combinational), or only the valid ones
        // after the first reset (pipelined)
        cmd.env(
            "SPECGEN_DIGEST",
            if design.cfg.latency() > 0 { "1" } else { "0" },
        );
    }
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| {
            error::tool(
                "verilator",
                format!("cannot start the Verilator harness: {e}"),
            )
        })?;
    let limit = time_limit(Simulator::Verilator, stim.len())?;
    let (_alive, fired) = watchdog(child.id(), limit);
    let stdin = child.stdin.take();
    let mut stdout = child.stdout.take().unwrap();
    if let Some(stdin) = &stdin {
        widen_pipe(stdin);
    }
    widen_pipe(&stdout);
    let len = stim.len();
    // a batch: its records, then the digest of the inputs applied (a sweep); or only the
    // digest of the outputs
    let record = if digest {
        0
    } else {
        out_record(design.cfg.carried_tag_bits() > 0)
    };
    let trailer = if sweep.is_some() || digest { 8 } else { 0 };
    let matched = std::thread::scope(|scope| -> Result<bool, Failure> {
        if let Some(mut stdin) = stdin {
            scope.spawn(move || {
                let mut buf = Vec::with_capacity(CHUNK as usize * IN_RECORD);
                let mut cycles = Vec::with_capacity(CHUNK as usize);
                let mut i = 0;
                while i < len {
                    buf.clear();
                    let end = (i + CHUNK).min(len);
                    stim.fill(i, end - i, &mut cycles);
                    for c in &cycles {
                        encode(c, &mut buf);
                    }
                    if stdin.write_all(&buf).is_err() {
                        return;
                    }
                    i = end;
                }
            });
        }
        let mut buf = vec![0u8; CHUNK as usize * record + trailer];
        let mut cycles = Vec::with_capacity(CHUNK as usize);
        let mut t = 0;
        while t < len {
            let n = (len - t).min(CHUNK) as usize;
            if let Err(e) = stdout.read_exact(&mut buf[..n * record + trailer]) {
                if fired.load(Ordering::SeqCst) {
                    let _ = child.wait();
                    return Err(timed_out("verilator", limit, len));
                }
                let mut err = String::new();
                let _ = child.stderr.take().map(|mut s| s.read_to_string(&mut err));
                let _ = child.wait();
                return Err(error::tool(
                    "verilator",
                    format!(
                        "the Verilator harness stopped after {t} of {len} cycles ({e}):\n{}",
                        err.trim_end()
                    ),
                ));
            }
            stim.fill(t, n as u64, &mut cycles);
            let trailer_word =
                || u64::from_le_bytes(buf[n * record..n * record + 8].try_into().expect("8 bytes"));
            if digest {
                if checker.digest_batch(t, &cycles) != trailer_word() {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Ok(false);
                }
            } else {
                checker.check_batch(
                    t,
                    &cycles,
                    buf[..n * record].chunks_exact(record).map(decode),
                );
                if trailer > 0 && trailer_word() != cycles.iter().fold(0, applied) {
                    let _ = child.kill();
                    let _ = child.wait();
                    let to = t + n as u64;
                    return Err(error::tool(
                        "verilator",
                        format!("the harness's sweep applied other inputs than the checker's in cycles {t}..{to} (harness and specgen of two versions?)"),
                    ));
                }
            }
            t += n as u64;
            progress.fetch_add(n as u64, Ordering::Relaxed);
        }
        Ok(true)
    })?;
    if !matched {
        return Ok(false);
    }
    let status = child
        .wait()
        .map_err(|e| error::tool("simulator", e.to_string()))?;
    if !status.success() {
        let mut err = String::new();
        let _ = child.stderr.take().unwrap().read_to_string(&mut err);
        return Err(error::tool(
            "verilator",
            format!("the Verilator harness failed ({status}): {err}"),
        ));
    }
    Ok(true)
}

/// Runs several independent stimuli on `jobs` parallel simulator processes and merges the reports.
pub fn run_all(
    built: &Built,
    design: &Design,
    model: &Model,
    stims: &[Box<dyn Stimulus>],
    jobs: usize,
) -> Result<Report, Failure> {
    let total: u64 = stims.iter().map(|s| s.len()).sum();
    let progress = Arc::new(AtomicU64::new(0));
    let next = AtomicU64::new(0);
    let results: Vec<Result<Vec<Report>, Failure>> = std::thread::scope(|scope| {
        let bar = {
            let progress = progress.clone();
            let done = Arc::new(std::sync::atomic::AtomicBool::new(false));
            let d2 = done.clone();
            let handle = scope.spawn(move || progress_bar(&progress, total, &d2));
            (handle, done)
        };
        let workers: Vec<_> = (0..jobs.max(1))
            .map(|_| {
                scope.spawn(|| {
                    let mut reports = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed) as usize;
                        if i >= stims.len() {
                            return Ok(reports);
                        }
                        reports.push(run_one(
                            built,
                            design,
                            model,
                            stims[i].as_ref(),
                            i,
                            &progress,
                            &[],
                        )?);
                    }
                })
            })
            .collect();
        let r = workers
            .into_iter()
            .map(|w| w.join().expect("worker panicked"))
            .collect();
        bar.1.store(true, Ordering::Relaxed);
        let _ = bar.0.join();
        r
    });
    let mut all = Report::default();
    for r in results {
        for rep in r? {
            all.cycles += rep.cycles;
            all.checked += rep.checked;
            all.results += rep.results;
            all.mismatches += rep.mismatches;
            let earlier = match (&all.first, &rep.first) {
                (None, Some(_)) => true,
                (Some(a), Some(b)) => (b.run, b.cycle) < (a.run, a.cycle),
                _ => false,
            };
            if earlier {
                all.first = rep.first;
            }
        }
    }
    Ok(all)
}

/// A progress bar on stderr for runs longer than a second; silent when stderr is no terminal.
fn progress_bar(progress: &AtomicU64, total: u64, done: &std::sync::atomic::AtomicBool) {
    if !std::io::stderr().is_terminal() || total == 0 {
        return;
    }
    let start = Instant::now();
    let mut shown = false;
    while !done.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(100));
        if start.elapsed() < Duration::from_secs(1) {
            continue;
        }
        let p = progress.load(Ordering::Relaxed).min(total);
        let width = 40;
        let filled = (p * width / total) as usize;
        let _ = write!(
            std::io::stderr(),
            "\r[{}{}] {:5.1}% {p}/{total} cycles",
            "#".repeat(filled),
            ".".repeat(width as usize - filled),
            p as f64 * 100.0 / total as f64
        );
        shown = true;
    }
    if shown {
        let _ = writeln!(std::io::stderr());
    }
}

/// Whether `tool` is an executable on the PATH (looked up directly, no shell).
pub(crate) fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|d| d.join(tool).is_file()))
}
