//! Stage 5: co-simulation — the RTL in a directory, whatever produced it, against the golden
//! model configured from the directory's manifest.
//!
//! The harnesses in `tb/` are generic over the manifest; builds are cached under a hash of
//! RTL + harness + flags + tool version. Vectors stream to the simulator in binary batches
//! (Verilator) or a vector file (Icarus); the comparison is done here, in Rust.

use crate::cli::{failed, usage, Failure};
use crate::config::{Config, Params};
use crate::model::{Inputs, Model, Outputs};
use sha2::{Digest, Sha256};
use std::io::{BufRead, BufReader, IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

const VERILATOR_HARNESS: &str = include_str!("../tb/verilator_harness.cpp");
const ICARUS_BENCH: &str = include_str!("../tb/icarus_bench.v");

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Simulator {
    Verilator,
    Icarus,
}

#[derive(clap::Args, Debug, Clone)]
pub struct CosimArgs {
    /// Directory with the Verilog (*.v) and the specgen manifest (<top>.json).
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    /// Number of vectors after the corner cases (random mode).
    #[arg(long, default_value_t = 100_000)]
    pub vectors: u64,
    /// Seed of the random vectors.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Every (cos_g, n) pair with cos_g in [0, 1.0], colours varied over every code.
    #[arg(long, conflicts_with = "vectors")]
    pub exhaustive: bool,
    #[arg(long, value_enum, default_value = "verilator")]
    pub simulator: Simulator,
    /// On a mismatch, write a VCD of a short replay around the first failure.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Parallel simulator processes [default: available cores].
    #[arg(long)]
    pub jobs: Option<usize>,
}

/// A directory of RTL under test, with the configuration its manifest states.
#[derive(Debug, Clone)]
pub struct Design {
    pub dir: PathBuf,
    pub cfg: Config,
    pub sources: Vec<PathBuf>,
}

impl Design {
    pub fn load(dir: &Path) -> Result<Design, Failure> {
        let entries = std::fs::read_dir(dir).map_err(|e| usage(format!("cannot read --rtl {}: {e}", dir.display())))?;
        let mut manifests = Vec::new();
        let mut sources = Vec::new();
        for entry in entries.flatten() {
            let path = entry.path();
            match path.extension().and_then(|e| e.to_str()) {
                Some("v") => sources.push(path),
                Some("json") => {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    let v: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
                    if v.get("generator").and_then(|g| g.as_str()) == Some("specgen") {
                        manifests.push((path, text));
                    }
                }
                _ => {}
            }
        }
        sources.sort();
        let (path, text) = match manifests.len() {
            1 => manifests.pop().unwrap(),
            0 => return Err(usage(format!("no specgen manifest (<top>.json) in --rtl {}", dir.display()))),
            _ => return Err(usage(format!("more than one specgen manifest in --rtl {}", dir.display()))),
        };
        if sources.is_empty() {
            return Err(usage(format!("no Verilog (*.v) in --rtl {}", dir.display())));
        }
        let params = Params::from_json(&text).map_err(|e| usage(format!("manifest {}: {e}", path.display())))?;
        let cfg = Config::new(params).map_err(|e| usage(format!("manifest {}: {e}", path.display())))?;
        Ok(Design { dir: dir.to_path_buf(), cfg, sources })
    }
}

/// One clock cycle of stimulus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Cycle {
    pub inputs: Inputs,
    pub valid: bool,
    pub rst: bool,
}

/// What the simulator returned for one cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sampled {
    pub outputs: Outputs,
    pub valid: bool,
}

/// A stream of cycles, addressable by index so a checker can regenerate what it needs.
/// Every run starts with a reset cycle when the unit is pipelined.
pub trait Stimulus: Send + Sync {
    fn len(&self) -> u64;
    fn cycle(&self, i: u64) -> Cycle;
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A stimulus held in memory.
pub struct Recorded(pub Vec<Cycle>);

impl Stimulus for Recorded {
    fn len(&self) -> u64 {
        self.0.len() as u64
    }
    fn cycle(&self, i: u64) -> Cycle {
        self.0[i as usize]
    }
}

/// splitmix64: a small counter-based generator, so vectors are reproducible from the seed.
pub fn splitmix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// The corner cases: cos 0, 1.0, above 1.0, B−1, B, B+1 where B is n's boundary (the
/// cut-off ROM entry, or the first code with a non-zero output); n 0, 1, 2, 3, max; colour
/// codes 0, 1, max on every channel. Then, for every n, the three codes around its boundary
/// with colours that vary with n: a single wrong table entry at any n shows.
pub fn corner_vectors(model: &Model) -> Vec<Inputs> {
    let cfg = &model.cfg;
    let one = 1u32 << cfg.f();
    let cos_max = (2u32 << cfg.f()) - 1;
    let n_max = (1u32 << cfg.n_bits()) - 1;
    let ks_max = (1u32 << cfg.b()) - 1;
    let bounds = model.boundaries();
    let mut ns: Vec<u32> = vec![0, 1, 2, 3, n_max];
    ns.retain(|&n| n <= n_max);
    ns.dedup();
    let colours = [0, 1, ks_max];
    let mut v = Vec::new();
    for &n in &ns {
        let sp = bounds[n as usize];
        let mut coss = vec![0, one, one + 1, cos_max, sp.saturating_sub(1), sp, (sp + 1).min(cos_max)];
        coss.sort();
        coss.dedup();
        for &cos_g in &coss {
            for &r in &colours {
                for &g in &colours {
                    for &b in &colours {
                        v.push(Inputs { cos_g, n, ks: [r, g, b] });
                    }
                }
            }
        }
    }
    for n in 0..=n_max {
        let sp = bounds[n as usize];
        let r = splitmix(n as u64 ^ 0x5bd1_e995);
        let ks = [ks_max, (r as u32) & ks_max, ((r >> 20) as u32) & ks_max];
        for cos_g in [sp.saturating_sub(1), sp, (sp + 1).min(cos_max)] {
            v.push(Inputs { cos_g, n, ks });
        }
    }
    v
}

/// A uniformly random input vector (cos_g over the whole port, half of them in [0, 1.0]).
pub fn random_vector(cfg: &Config, seed: u64, i: u64) -> Inputs {
    let r = splitmix(seed.wrapping_mul(0x1000_0000_0000_0001) ^ i);
    let r2 = splitmix(r);
    let cos_g = if r & 1 == 0 { ((r >> 1) % ((1u64 << cfg.f()) + 1)) as u32 } else { ((r >> 1) & ((2u64 << cfg.f()) - 1)) as u32 };
    let n = ((r >> 32) & ((1u64 << cfg.n_bits()) - 1)) as u32;
    let bm = (1u64 << cfg.b()) - 1;
    Inputs { cos_g, n, ks: [(r2 & bm) as u32, ((r2 >> 16) & bm) as u32, ((r2 >> 32) & bm) as u32] }
}

/// Corners, then `count` random vectors. For a pipelined unit: a reset first, random bubbles
/// on `in_valid` (one cycle in eight), and a reset in mid-stream.
pub fn random_stimulus(model: &Model, count: u64, seed: u64) -> Recorded {
    let cfg = &model.cfg;
    let pipelined = cfg.stages() > 0;
    let vectors: Vec<Inputs> = corner_vectors(model).into_iter().chain((0..count).map(|i| random_vector(cfg, seed, i))).collect();
    let mut cycles = Vec::with_capacity(vectors.len() * 9 / 8 + 8);
    if pipelined {
        cycles.push(Cycle { inputs: random_vector(cfg, seed ^ 0xdead, 0), valid: true, rst: true });
    }
    let reset_at = vectors.len() / 2;
    for (i, &inputs) in vectors.iter().enumerate() {
        if pipelined {
            let r = splitmix(seed ^ 0xb0bb1e5 ^ (i as u64) << 8);
            if r.is_multiple_of(8) {
                cycles.push(Cycle { inputs: random_vector(cfg, seed ^ 0xb0bb, i as u64), valid: false, rst: false });
            }
            if i == reset_at {
                // a reset in mid-stream: the vectors in flight are dropped, then the stream resumes
                cycles.push(Cycle { inputs, valid: true, rst: true });
                cycles.push(Cycle { inputs, valid: true, rst: true });
            }
        }
        cycles.push(Cycle { inputs, valid: true, rst: false });
    }
    Recorded(cycles)
}

/// Every `(cos_g, n)` with `cos_g ∈ [0, 2^F]` (codes above 1.0 all read as 1.0; the corners
/// cover them), n-major in chunk `part` of `parts`. Colours: `ks_X = (cos_g + n·m_X + o_X) mod 2^B`
/// with odd `m_X`, so along a row of fixed n every channel sees every code. The first part
/// ends with a tail of `2^B` cycles at `cos_g = 1.0` carrying every colour code on every
/// channel through full intensity (whatever N is).
pub struct Exhaustive {
    pub f: u32,
    pub b: u32,
    pub n_bits: u32,
    pub n_lo: u32,
    pub n_hi: u32,
    pub pipelined: bool,
    pub full_intensity_tail: bool,
}

impl Exhaustive {
    pub fn parts(cfg: &Config, parts: u32) -> Vec<Exhaustive> {
        let n_count = 1u32 << cfg.n_bits();
        let parts = parts.clamp(1, n_count);
        (0..parts)
            .map(|p| Exhaustive {
                f: cfg.f(),
                b: cfg.b(),
                n_bits: cfg.n_bits(),
                n_lo: n_count * p / parts,
                n_hi: n_count * (p + 1) / parts,
                pipelined: cfg.stages() > 0,
                full_intensity_tail: p == 0,
            })
            .collect()
    }
    fn row(&self) -> u64 {
        (1u64 << self.f) + 1
    }
}

impl Stimulus for Exhaustive {
    fn len(&self) -> u64 {
        let tail = if self.full_intensity_tail { 1u64 << self.b } else { 0 };
        (self.n_hi - self.n_lo) as u64 * self.row() + self.pipelined as u64 + tail
    }
    fn cycle(&self, i: u64) -> Cycle {
        if self.pipelined && i == 0 {
            return Cycle { inputs: Inputs::default(), valid: false, rst: true };
        }
        let j = i - self.pipelined as u64;
        let bm = (1u32 << self.b) - 1;
        let sweep = (self.n_hi - self.n_lo) as u64 * self.row();
        if j >= sweep {
            let code = (j - sweep) as u32;
            let n = code.wrapping_mul(7) & ((1u32 << self.n_bits) - 1);
            let ks = [code, code.wrapping_add(1) & bm, code.wrapping_add(2) & bm];
            return Cycle { inputs: Inputs { cos_g: 1 << self.f, n, ks }, valid: true, rst: false };
        }
        let n = self.n_lo + (j / self.row()) as u32;
        let cos_g = (j % self.row()) as u32;
        let ks = [
            cos_g.wrapping_add(n.wrapping_mul(1)) & bm,
            cos_g.wrapping_add(n.wrapping_mul(3)).wrapping_add(85) & bm,
            cos_g.wrapping_add(n.wrapping_mul(7)).wrapping_add(170) & bm,
        ];
        Cycle { inputs: Inputs { cos_g, n, ks }, valid: true, rst: false }
    }
}

/// The first disagreement found.
#[derive(Debug, Clone)]
pub struct Mismatch {
    /// cycle index within its run
    pub cycle: u64,
    pub run: usize,
    /// the inputs the compared outputs belong to (applied `latency` cycles before)
    pub cycle_in: Cycle,
    pub expected: Sampled,
    pub actual: Sampled,
    pub data_compared: bool,
}

/// The result of checking one or more runs.
#[derive(Debug, Clone, Default)]
pub struct Report {
    pub cycles: u64,
    pub checked: u64,
    pub mismatches: u64,
    pub first: Option<Mismatch>,
}

/// Compares a sampled stream against the golden model: `out_valid` on every cycle after the
/// first reset, data on every cycle whose output is valid (every cycle when combinational).
pub struct Checker<'a> {
    model: &'a Model,
    latency: u64,
    last_rst: Option<u64>,
    run: usize,
    pub report: Report,
}

impl<'a> Checker<'a> {
    pub fn new(model: &'a Model, run: usize) -> Checker<'a> {
        Checker { model, latency: model.cfg.stages() as u64, last_rst: None, run, report: Report::default() }
    }

    /// Checks the output sampled in cycle `t`.
    pub fn check(&mut self, stim: &dyn Stimulus, t: u64, got: Sampled) {
        let s = self.latency;
        self.report.cycles += 1;
        let now = stim.cycle(t);
        let (exp_valid, data_compared, src) = if s == 0 {
            (now.valid, true, now)
        } else {
            // valid needs a defined pipeline: a reset at some cycle before t
            let Some(last_rst) = self.last_rst else {
                if now.rst {
                    self.last_rst = Some(t);
                }
                return;
            };
            let v = t >= s && stim.cycle(t - s).valid && last_rst < t - s;
            let src = if t >= s { stim.cycle(t - s) } else { now };
            (v, v, src)
        };
        if now.rst {
            self.last_rst = Some(t);
        }
        let expected = Sampled { outputs: self.model.eval(src.inputs), valid: exp_valid };
        let ok = got.valid == exp_valid && (!data_compared || got.outputs == expected.outputs);
        self.report.checked += 1;
        if !ok {
            self.report.mismatches += 1;
            if self.report.first.is_none() {
                self.report.first = Some(Mismatch { cycle: t, run: self.run, cycle_in: src, expected, actual: got, data_compared });
            }
        }
    }
}

fn cache_root() -> PathBuf {
    if let Some(dir) = std::env::var_os("SPECGEN_CACHE_DIR") {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME") {
        return PathBuf::from(dir).join("specgen");
    }
    if let Some(home) = std::env::var_os("HOME") {
        return PathBuf::from(home).join(".cache").join("specgen");
    }
    std::env::temp_dir().join("specgen-cache")
}

fn tool_version(tool: &str, package: &str) -> Result<String, Failure> {
    let out = Command::new(tool)
        .arg(if tool == "iverilog" { "-V" } else { "--version" })
        .output()
        .map_err(|_| usage(format!("{tool} not found: install the Debian package `{package}` (apt-get install -y {package})")))?;
    let text = String::from_utf8_lossy(&out.stdout);
    Ok(text.lines().next().unwrap_or("").to_string())
}

/// A built simulator, ready to run vectors.
pub struct Built {
    pub simulator: Simulator,
    pub dir: PathBuf,
    /// true when this call compiled it (false: taken from the cache)
    pub fresh: bool,
}

/// Builds (or finds in the cache) the simulator for `design`.
pub fn build(design: &Design, simulator: Simulator, trace: bool) -> Result<Built, Failure> {
    let top = design.cfg.top().to_string();
    let has_clock = design.cfg.stages() > 0;
    let (tool, package, harness) = match simulator {
        Simulator::Verilator => ("verilator", "verilator", VERILATOR_HARNESS),
        Simulator::Icarus => ("iverilog", "iverilog", ICARUS_BENCH),
    };
    let version = tool_version(tool, package)?;
    let mut h = Sha256::new();
    for part in [version.as_str(), harness, &top, &format!("{has_clock} {trace} {simulator:?} v2")] {
        h.update(part.as_bytes());
        h.update([0u8]);
    }
    for src in &design.sources {
        h.update(src.file_name().unwrap().to_string_lossy().as_bytes());
        h.update(std::fs::read(src).map_err(|e| usage(format!("cannot read {}: {e}", src.display())))?);
    }
    let key: String = h.finalize().iter().take(12).map(|b| format!("{b:02x}")).collect();
    let root = cache_root();
    let dir = root.join(format!("{}-{top}-{key}", tool));
    if dir.join("ok").exists() {
        return Ok(Built { simulator, dir, fresh: false });
    }
    std::fs::create_dir_all(&root).map_err(|e| usage(format!("cannot create cache {}: {e}", root.display())))?;
    let work = tempfile::Builder::new()
        .prefix(".build-")
        .tempdir_in(&root)
        .map_err(|e| usage(format!("cannot create a build directory in {}: {e}", root.display())))?;
    let sources: Vec<PathBuf> = design.sources.iter().map(|p| std::fs::canonicalize(p).unwrap_or(p.clone())).collect();
    let mut cmd;
    match simulator {
        Simulator::Verilator => {
            std::fs::write(work.path().join("harness.cpp"), harness).map_err(|e| usage(e.to_string()))?;
            cmd = Command::new("verilator");
            cmd.current_dir(work.path())
                .args(["--cc", "--exe", "--build", "-O3", "--prefix", "Vdut", "--top-module", &top])
                .args(["-Wno-fatal", "-Wno-lint", "-Wno-style", "-Mdir", "obj", "-o", "../harness"])
                .args(["-j", "2", "-CFLAGS", &format!("-O2 -DHAS_CLOCK={} -DTRACE={}", has_clock as u8, trace as u8)])
                .arg("-MAKEFLAGS")
                .arg("OPT_FAST=-O2");
            if trace {
                cmd.arg("--trace");
            }
            cmd.args(&sources).arg("harness.cpp");
        }
        Simulator::Icarus => {
            std::fs::write(work.path().join("bench.v"), harness).map_err(|e| usage(e.to_string()))?;
            let c = &design.cfg;
            cmd = Command::new("iverilog");
            cmd.current_dir(work.path())
                .args(["-g2005", "-o", "sim.vvp", "-s", "specgen_icarus_bench"])
                .arg(format!("-DTOP={top}"))
                .arg(format!("-DCOS_W={}", c.f() + 1))
                .arg(format!("-DN_W={}", c.n_bits()))
                .arg(format!("-DB_W={}", c.b()))
                .arg(format!("-DI_W={}", c.fi() + 1));
            if has_clock {
                cmd.arg("-DHAS_CLOCK");
            }
            cmd.arg("bench.v").args(&sources);
        }
    }
    let out = cmd.output().map_err(|e| usage(format!("cannot run {tool}: {e}")))?;
    if !out.status.success() {
        let log = String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = log.lines().rev().take(25).collect();
        return Err(usage(format!("{tool} could not build the RTL in {}:\n{}", design.dir.display(), tail.into_iter().rev().collect::<Vec<_>>().join("\n"))));
    }
    std::fs::write(work.path().join("ok"), b"").map_err(|e| usage(e.to_string()))?;
    let kept = work.keep();
    if std::fs::rename(&kept, &dir).is_err() {
        // another process built it at the same time: use theirs
        let _ = std::fs::remove_dir_all(&kept);
    }
    Ok(Built { simulator, dir, fresh: true })
}

const IN_RECORD: usize = 16;
const OUT_RECORD: usize = 12;
const CHUNK: u64 = 1 << 14;

fn encode(c: &Cycle, buf: &mut Vec<u8>) {
    buf.extend_from_slice(&c.inputs.cos_g.to_le_bytes());
    buf.extend_from_slice(&(c.inputs.n as u16).to_le_bytes());
    for k in c.inputs.ks {
        buf.extend_from_slice(&(k as u16).to_le_bytes());
    }
    buf.push(c.valid as u8 | (c.rst as u8) << 1);
    buf.extend_from_slice(&[0, 0, 0]);
}

fn decode(rec: &[u8]) -> Sampled {
    let u16at = |i: usize| u16::from_le_bytes([rec[i], rec[i + 1]]) as u32;
    Sampled {
        outputs: Outputs { intensity: u32::from_le_bytes([rec[0], rec[1], rec[2], rec[3]]), spec: [u16at(4), u16at(6), u16at(8)], done: rec[10] & 2 != 0 },
        valid: rec[10] & 1 != 0,
    }
}

/// Runs one stimulus through the built simulator, checking every cycle. `progress` counts
/// cycles done (for the progress bar).
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
            let mut child = Command::new(built.dir.join("harness"))
                .current_dir(&design.dir)
                .envs(env.iter().map(|(k, v)| (k, v.as_os_str())))
                .stdin(Stdio::piped())
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .map_err(|e| usage(format!("cannot start the Verilator harness: {e}")))?;
            let mut stdin = child.stdin.take().unwrap();
            let mut stdout = child.stdout.take().unwrap();
            let len = stim.len();
            std::thread::scope(|scope| -> Result<(), Failure> {
                scope.spawn(move || {
                    let mut buf = Vec::with_capacity(CHUNK as usize * IN_RECORD);
                    let mut i = 0;
                    while i < len {
                        buf.clear();
                        let end = (i + CHUNK).min(len);
                        for j in i..end {
                            encode(&stim.cycle(j), &mut buf);
                        }
                        if stdin.write_all(&buf).is_err() {
                            return;
                        }
                        i = end;
                    }
                });
                let mut buf = vec![0u8; CHUNK as usize * OUT_RECORD];
                let mut t = 0;
                while t < len {
                    let n = (len - t).min(CHUNK) as usize;
                    if let Err(e) = stdout.read_exact(&mut buf[..n * OUT_RECORD]) {
                        let mut err = String::new();
                        let _ = child.stderr.take().map(|mut s| s.read_to_string(&mut err));
                        let _ = child.wait();
                        return Err(failed(format!("the Verilator harness stopped after {t} of {len} cycles ({e}):\n{}", err.trim_end())));
                    }
                    for k in 0..n {
                        checker.check(stim, t + k as u64, decode(&buf[k * OUT_RECORD..(k + 1) * OUT_RECORD]));
                    }
                    t += n as u64;
                    progress.fetch_add(n as u64, Ordering::Relaxed);
                }
                Ok(())
            })?;
            let status = child.wait().map_err(|e| failed(e.to_string()))?;
            if !status.success() {
                let mut err = String::new();
                let _ = child.stderr.take().unwrap().read_to_string(&mut err);
                return Err(failed(format!("the Verilator harness failed ({status}): {err}")));
            }
        }
        Simulator::Icarus => {
            let work = tempfile::tempdir().map_err(|e| usage(e.to_string()))?;
            let vin = work.path().join("vectors.in");
            let vout = work.path().join("vectors.out");
            {
                let mut w = std::io::BufWriter::new(std::fs::File::create(&vin).map_err(|e| usage(e.to_string()))?);
                for i in 0..stim.len() {
                    let c = stim.cycle(i);
                    let x = c.inputs;
                    writeln!(w, "{:x} {:x} {:x} {:x} {:x} {:x} {:x}", c.valid as u8, c.rst as u8, x.cos_g, x.n, x.ks[0], x.ks[1], x.ks[2])
                        .map_err(|e| usage(e.to_string()))?;
                }
            }
            let out = Command::new("vvp")
                .current_dir(&design.dir)
                .arg("-n")
                .arg(built.dir.join("sim.vvp"))
                .arg(format!("+vec_in={}", vin.display()))
                .arg(format!("+vec_out={}", vout.display()))
                .output()
                .map_err(|e| usage(format!("cannot run vvp (Debian package `iverilog`): {e}")))?;
            if !out.status.success() {
                return Err(failed(format!("vvp failed: {}", String::from_utf8_lossy(&out.stderr))));
            }
            let said = String::from_utf8_lossy(&out.stdout);
            let file = std::fs::File::open(&vout).map_err(|e| failed(format!("vvp wrote no output ({e}); it said:\n{}", said.trim_end())))?;
            let mut t = 0;
            for line in BufReader::new(file).lines() {
                let line = line.map_err(|e| failed(e.to_string()))?;
                let f: Vec<&str> = line.split_whitespace().collect();
                let hex = |s: &str| u32::from_str_radix(s, 16).unwrap_or(u32::MAX); // x/z never match
                if f.len() != 6 {
                    return Err(failed(format!("vvp output line {t} is malformed: {line:?}")));
                }
                let s = Sampled { outputs: Outputs { intensity: hex(f[2]), spec: [hex(f[3]), hex(f[4]), hex(f[5])], done: f[1] == "1" }, valid: f[0] == "1" };
                // outputs that are x/z before the pipeline fills are never compared (see Checker)
                checker.check(stim, t, s);
                t += 1;
            }
            if t != stim.len() {
                return Err(failed(format!("vvp returned {t} of {} cycles", stim.len())));
            }
            progress.fetch_add(t, Ordering::Relaxed);
        }
    }
    Ok(checker.report)
}

/// Runs several independent stimuli on `jobs` parallel simulator processes and merges the reports.
pub fn run_all(built: &Built, design: &Design, model: &Model, stims: &[Box<dyn Stimulus>], jobs: usize) -> Result<Report, Failure> {
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
                        reports.push(run_one(built, design, model, stims[i].as_ref(), i, &progress, &[])?);
                    }
                })
            })
            .collect();
        let r = workers.into_iter().map(|w| w.join().expect("worker panicked")).collect();
        bar.1.store(true, Ordering::Relaxed);
        let _ = bar.0.join();
        r
    });
    let mut all = Report::default();
    for r in results {
        for rep in r? {
            all.cycles += rep.cycles;
            all.checked += rep.checked;
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
        eprint!("\r[{}{}] {:5.1}% {p}/{total} cycles", "#".repeat(filled), ".".repeat(width as usize - filled), p as f64 * 100.0 / total as f64);
        shown = true;
    }
    if shown {
        eprintln!();
    }
}

fn describe(m: &Mismatch, cfg: &Config) -> String {
    let x = m.cycle_in.inputs;
    let mut s = format!(
        "first mismatch: run {}, cycle {} (latency {}), inputs cos_g={} n={} ks_r={} ks_g={} ks_b={}\n",
        m.run,
        m.cycle,
        cfg.stages(),
        x.cos_g,
        x.n,
        x.ks[0],
        x.ks[1],
        x.ks[2]
    );
    let e = m.expected;
    let a = m.actual;
    let mut row = |port: &str, exp: u64, act: u64, compared: bool| {
        let mark = if !compared {
            "  (not compared)"
        } else if exp != act {
            "  <-- differs"
        } else {
            ""
        };
        s.push_str(&format!("  {port:<10} expected {exp:>10}  actual {act:>10}{mark}\n"));
    };
    row("out_valid", e.valid as u64, a.valid as u64, true);
    let d = m.data_compared;
    row("spec_r", e.outputs.spec[0] as u64, a.outputs.spec[0] as u64, d);
    row("spec_g", e.outputs.spec[1] as u64, a.outputs.spec[1] as u64, d);
    row("spec_b", e.outputs.spec[2] as u64, a.outputs.spec[2] as u64, d);
    row("intensity", e.outputs.intensity as u64, a.outputs.intensity as u64, d);
    row("done", e.outputs.done as u64, a.outputs.done as u64, d);
    s
}

/// Replays a short window around a failure with a tracing build and writes its VCD.
fn write_trace(design: &Design, model: &Model, stims: &[Box<dyn Stimulus>], m: &Mismatch, path: &Path) -> Result<(), Failure> {
    let built = build(design, Simulator::Verilator, true)?;
    let stim = stims[m.run].as_ref();
    let s = design.cfg.stages() as u64;
    let from = m.cycle.saturating_sub(16 + s);
    let to = (m.cycle + 4).min(stim.len() - 1);
    let mut cycles = Vec::new();
    if s > 0 {
        cycles.push(Cycle { rst: true, valid: false, ..stim.cycle(from) });
    }
    cycles.extend((from..=to).map(|i| stim.cycle(i)));
    let abs = if path.is_absolute() { path.to_path_buf() } else { std::env::current_dir().unwrap_or_default().join(path) };
    run_one(&built, design, model, &Recorded(cycles), 0, &AtomicU64::new(0), &[("SPECGEN_VCD", &abs)])?;
    Ok(())
}

/// `specgen cosim`: exit 0 when every output matches, 1 on any mismatch, 2 on usage errors.
pub fn run_cli(args: &CosimArgs) -> Result<(), Failure> {
    let design = Design::load(&args.rtl)?;
    check_ports(&design)?;
    check_tables(&design)?;
    let model = Model::new(&design.cfg);
    let jobs = args.jobs.unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1)).max(1);
    let t0 = Instant::now();
    let built = build(&design, args.simulator, false)?;
    let build_time = t0.elapsed();
    let stims: Vec<Box<dyn Stimulus>> = if args.exhaustive {
        Exhaustive::parts(&design.cfg, jobs as u32 * 2).into_iter().map(|e| Box::new(e) as Box<dyn Stimulus>).collect()
    } else {
        vec![Box::new(random_stimulus(&model, args.vectors, args.seed))]
    };
    let t1 = Instant::now();
    let report = run_all(&built, &design, &model, &stims, jobs)?;
    let check_time = t1.elapsed();
    let rate = report.cycles as f64 / check_time.as_secs_f64().max(1e-9);
    println!(
        "cosim {} ({:?}{}): {} cycles, {} checked, {} mismatches; build {:.2} s{}, check {:.2} s ({:.1} M cycles/s)",
        design.dir.display(),
        args.simulator,
        if args.exhaustive { ", exhaustive" } else { "" },
        report.cycles,
        report.checked,
        report.mismatches,
        build_time.as_secs_f64(),
        if built.fresh { "" } else { " (cached)" },
        check_time.as_secs_f64(),
        rate / 1e6
    );
    match &report.first {
        None if report.checked > 0 => Ok(()),
        None => Err(failed("no output was checked")),
        Some(m) => {
            let mut msg = format!("{} of {} checked cycles differ from the golden model\n{}", report.mismatches, report.checked, describe(m, &design.cfg));
            if let Some(path) = &args.trace {
                match write_trace(&design, &model, &stims, m, path) {
                    Ok(()) => msg.push_str(&format!("trace of the replay around the failure: {}", path.display())),
                    Err(e) => msg.push_str(&format!("could not write the trace: {}", e.message)),
                }
            }
            Err(failed(msg))
        }
    }
}

/// Reads a `$readmemh` file: hex words separated by white space, `//` comments, `@addr`
/// address jumps. Returns the words by address (`None` where the file sets nothing).
pub fn parse_readmemh(text: &str, depth: usize) -> Result<Vec<Option<u128>>, String> {
    let mut words = vec![None; depth];
    let mut addr = 0usize;
    for (ln, line) in text.lines().enumerate() {
        let line = line.split("//").next().unwrap_or("");
        for tok in line.split_whitespace() {
            if let Some(a) = tok.strip_prefix('@') {
                addr = usize::from_str_radix(a, 16).map_err(|_| format!("line {}: bad address {tok:?}", ln + 1))?;
                continue;
            }
            let v = u128::from_str_radix(&tok.replace('_', ""), 16).map_err(|_| format!("line {}: {tok:?} is not a hex word", ln + 1))?;
            if addr >= depth {
                return Err(format!("line {}: more than {depth} entries", ln + 1));
            }
            words[addr] = Some(v);
            addr += 1;
        }
    }
    Ok(words)
}

/// Table files are data: every table the configuration reads with `$readmemh` is compared
/// with the golden model's entry by entry before anything is simulated. A missing, short or
/// wrong file fails (exit 1) naming the file, and the first wrong entry by index and value.
/// Tables the sources do not name (a netlist with its ROMs inline) are not looked for.
pub fn check_tables(design: &Design) -> Result<(), Failure> {
    if design.cfg.params.rom_style != crate::config::RomStyle::File {
        return Ok(());
    }
    let sources: Vec<String> = design.sources.iter().map(|p| std::fs::read_to_string(p).unwrap_or_default()).collect();
    for t in crate::rom::tables(&design.cfg) {
        // a synthesized netlist holds its tables inline: only files the sources name are read
        if !sources.iter().any(|s| s.contains(&format!("\"{}\"", t.file))) {
            continue;
        }
        let path = design.dir.join(&t.file);
        let meta = std::fs::metadata(&path)
            .map_err(|e| failed(format!("table file {} is missing ({e}); `specgen generate` writes it beside the RTL", path.display())))?;
        if !meta.is_file() || meta.len() > 64 << 20 {
            return Err(failed(format!("table file {} is not a regular file of at most 64 MiB", path.display())));
        }
        let text = std::fs::read_to_string(&path).map_err(|e| failed(format!("cannot read table file {}: {e}", path.display())))?;
        let words = parse_readmemh(&text, t.words.len()).map_err(|e| failed(format!("table file {}: {e}", path.display())))?;
        for (i, (got, want)) in words.iter().zip(&t.words).enumerate() {
            match got {
                None => {
                    return Err(failed(format!(
                        "table file {} is short: entry {i} is missing ({} entries expected, {})",
                        path.display(),
                        t.words.len(),
                        t.what
                    )))
                }
                Some(v) if v != want => {
                    return Err(failed(format!("table file {}: entry {i} is {v:x}, the golden model's is {want:x} ({})", path.display(), t.what)))
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// The ports of module `top` in Verilog source: (name, direction, width). Reads both
/// ANSI headers (`input wire [15:0] cos_g,`) and netlist declarations (`input [15:0] cos_g;`).
pub fn source_ports(text: &str, top: &str) -> Option<Vec<(String, &'static str, u32)>> {
    // drop comments
    let mut clean = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |i| &r[i..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
        } else {
            let c = rest.chars().next().unwrap();
            clean.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    let tokens: Vec<String> = clean.replace('[', " [ ").replace(']', " ] ").replace([',', ';', '(', ')'], " , ").split_whitespace().map(String::from).collect();
    let start = tokens.windows(2).position(|w| w[0] == "module" && (w[1] == top || w[1].starts_with(&format!("{top}#"))))?;
    let end = tokens[start..].iter().position(|t| t == "endmodule").map_or(tokens.len(), |e| start + e);
    let mut ports = Vec::new();
    let mut i = start;
    while i < end {
        let dir = match tokens[i].as_str() {
            "input" => "input",
            "output" => "output",
            _ => {
                i += 1;
                continue;
            }
        };
        i += 1;
        while i < end && ["wire", "reg", "signed"].contains(&tokens[i].as_str()) {
            i += 1;
        }
        let mut width = 1;
        if i < end && tokens[i] == "[" {
            // [ h : l ]
            let range: String = tokens[i + 1..].iter().take_while(|t| *t != "]").cloned().collect();
            let (h, l) = range.split_once(':')?;
            width = (h.trim().parse::<i64>().ok()? - l.trim().parse::<i64>().ok()?).unsigned_abs() as u32 + 1;
            i += tokens[i..].iter().position(|t| t == "]")? + 1;
        }
        // one or more names, separated by commas, until a keyword or the end of the list
        while i < end {
            let t = tokens[i].as_str();
            if t == "," {
                i += 1;
                continue;
            }
            if ["input", "output", "wire", "reg", "assign", "always", "initial", "endmodule", "parameter", "localparam", "integer"].contains(&t)
                || !t.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '\\')
            {
                break;
            }
            ports.push((t.trim_start_matches('\\').to_string(), dir, width));
            i += 1;
            if tokens.get(i).is_some_and(|n| n != ",") {
                break;
            }
        }
    }
    Some(ports)
}

/// The RTL's port names and widths must be those the manifest implies: a mismatch is a
/// usage error (exit 2), reported as such rather than as data mismatches.
pub fn check_ports(design: &Design) -> Result<(), Failure> {
    let top = design.cfg.top();
    let mut found = None;
    for src in &design.sources {
        let text = std::fs::read_to_string(src).map_err(|e| usage(format!("cannot read {}: {e}", src.display())))?;
        if let Some(p) = source_ports(&text, top) {
            found = Some((src.clone(), p));
            break;
        }
    }
    let Some((src, got)) = found else {
        return Err(usage(format!("no module {top} (the manifest's top) in the Verilog of {}", design.dir.display())));
    };
    let want = crate::emit::ports(&design.cfg);
    let mut problems = Vec::new();
    for p in &want {
        match got.iter().find(|g| g.0 == p.name) {
            None => problems.push(format!("{} {} [{} bits] is missing", p.direction, p.name, p.width)),
            Some(g) if g.1 != p.direction || g.2 != p.width => {
                problems.push(format!("{} is {} of {} bits in the RTL, {} of {} bits by the manifest", p.name, g.1, g.2, p.direction, p.width))
            }
            _ => {}
        }
    }
    for g in &got {
        if !want.iter().any(|p| p.name == g.0) {
            problems.push(format!("{} {} is not a port the manifest implies", g.1, g.0));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(usage(format!(
            "the ports of {top} in {} disagree with the manifest in {} (was one of them edited?):\n  {}",
            src.display(),
            design.dir.display(),
            problems.join("\n  ")
        )))
    }
}
