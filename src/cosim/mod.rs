//! Stage 5: co-simulation — the RTL in a directory, whatever produced it, against the golden
//! model configured from the directory's manifest.
//!
//! - [`files`]: what is checked before anything runs — every table file entry by entry, the
//!   RTL's ports against the manifest;
//! - [`stimulus`]: corners, a boundary for every n, random and exhaustive streams;
//! - [`checking`]: the comparison with the golden model, cycle by cycle;
//! - [`backend`]: the simulators (Verilator harness, Icarus bench in `tb/`), their cached
//!   builds, and the runs. Vectors stream to the simulator in binary batches (Verilator) or a
//!   vector file (Icarus); the comparison is done here, in Rust.

pub mod adapter;
pub mod backend;
pub mod checking;
pub mod files;
pub mod stimulus;

pub use backend::{build, run_all, run_one, write_trace, Built};
pub use checking::{describe, Checker, Mismatch, Report};
pub use files::{check_ports, check_tables, parse_readmemh, source_ports};
pub use stimulus::{
    corner_vectors, random_stimulus, random_vector, splitmix, Exhaustive, Recorded, Stimulus,
};

use crate::config::{Config, Params};
use crate::error::{input, Error};
use crate::models::{Inputs, Outputs};
use sha2::Digest;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Simulator {
    Verilator,
    Icarus,
}

/// The simulator programs a run starts: each a name looked up on the PATH or a path, the
/// only programs specgen itself runs to simulate (Verilator's own build runs its `make` and
/// compiler). A program that is not found is named with its package; one that fails is the
/// tool's error, never the RTL's.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SimTools {
    pub verilator: String,
    pub iverilog: String,
    pub vvp: String,
}

impl Default for SimTools {
    fn default() -> Self {
        SimTools {
            verilator: "verilator".into(),
            iverilog: "iverilog".into(),
            vvp: "vvp".into(),
        }
    }
}

/// The prefix of the unit's files as [`Design::stage`] names them in a work directory.
const STAGED_UNIT: &str = "unit-";

/// A directory of RTL under test, with the configuration its manifest states.
#[derive(Debug, Clone)]
pub struct Design {
    pub dir: PathBuf,
    pub cfg: Config,
    /// the configuration's plan: its model, widths, datapath and tables
    pub plan: crate::plan::Plan,
    /// the synthesizable Verilog: every `*.v` but the simulation models
    pub(crate) sources: Vec<PathBuf>,
    /// simulation-only models beside it (the MULT18X18D model of an ECP5 unit): simulators
    /// read them after the sources, synthesis never
    pub(crate) sim_models: Vec<PathBuf>,
    /// every file of the unit: the manifest and the files it lists that are present
    pub(crate) inputs: Vec<PathBuf>,
}

/// The largest manifest read (a generated one is a few kB).
const MANIFEST_MAX_BYTES: u64 = 1 << 20;

/// Copies the unit's file `from` into `work` as `name` (bounded read).
fn copy_in(from: &Path, work: &Path, name: &str) -> Result<(), Error> {
    let bytes = crate::small_file::read_bytes(from, crate::small_file::UNIT_FILE_MAX)
        .map_err(|e| input(format!("{} {e}", from.display())))?;
    std::fs::write(work.join(name), bytes).map_err(|e| Error::io("write", work.join(name), e))
}

/// Whether `a` and `b` are the same file (device and inode; both must exist).
use crate::output::same_file;

impl Design {
    /// Stages the unit for a tool that runs in `work`: each source copied as `src<i>.v` and
    /// each table file under its own (generated) name, so the tool's scripts hold only names
    /// specgen chose — a file name of the user's (spaces, `;`, quotes, newlines) never reaches
    /// a command line. Copies, not links: a WebAssembly yosys (YoWASP) sees its working
    /// directory and nothing a link there points to. Returns the sources' names, in order.
    /// Whether `name` is one of the unit's files as [`Design::stage`] names them (no generated
    /// file's name has a `-`: a top is a Verilog identifier).
    pub(crate) fn is_staged_unit(name: &str) -> bool {
        name.strip_prefix(STAGED_UNIT)
            .and_then(|n| n.strip_suffix(".v"))
            .is_some_and(|i| !i.is_empty() && i.chars().all(|c| c.is_ascii_digit()))
    }

    pub(crate) fn stage(&self, work: &Path) -> Result<Vec<String>, Error> {
        let copy = |from: &Path, name: &str| copy_in(from, work, name);
        let mut names = Vec::new();
        for (i, src) in self.sources.iter().enumerate() {
            let name = format!("{STAGED_UNIT}{i}.v");
            copy(src, &name)?;
            names.push(name);
        }
        for t in &self.plan.datapath.tables {
            let file = t.file(self.cfg.top());
            let from = self.dir.join(&file);
            if from.exists() && !work.join(&file).exists() {
                copy(&from, &file)?;
            }
        }
        Ok(names)
    }

    /// Copies the unit's simulation models (an ECP5 unit's primitives) into `work` as
    /// `model<i>.v`, for a tool that reads the datapath through them; returns their names.
    pub(crate) fn stage_sim_models(&self, work: &Path) -> Result<Vec<String>, Error> {
        let mut names = Vec::new();
        for (i, m) in self.sim_models.iter().enumerate() {
            let name = format!("model{i}.v");
            copy_in(m, work, &name)?;
            names.push(name);
        }
        Ok(names)
    }

    /// Refuses an output path (`flag` names it) that is one of the unit's files: a command never
    /// writes over what it reads.
    pub fn refuse_output(&self, flag: &str, out: &Path) -> Result<(), Error> {
        // a symbolic link is written through: what it points at (dangling or not) is checked too
        let target = crate::output::through_links(out).unwrap_or_else(|_| out.to_path_buf());
        if target != out {
            self.refuse_output(flag, &target).map_err(|e| {
                input(format!(
                    "{flag} {} is a symbolic link to {}: {}",
                    out.display(),
                    target.display(),
                    e.reason()
                ))
            })?;
        }
        // the manifest, every file it lists, and every Verilog file the command compiles
        if let Some(i) = self
            .inputs
            .iter()
            .chain(&self.sources)
            .chain(&self.sim_models)
            .find(|i| same_file(out, i))
        {
            return Err(input(format!(
                "{flag} {} is the unit's own file {}; write it elsewhere",
                out.display(),
                i.display()
            )));
        }
        // nor a new file there that a later command would read as the unit's (every Verilog
        // file of the directory is compiled, every manifest and table read)
        const READ: [&str; 10] = [
            "v", "sv", "vh", "svh", "hex", "json", "core", "sdc", "lpf", "mem",
        ];
        let ext = out
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        if ext.as_ref().is_some_and(|e| READ.contains(&e.as_str()))
            && crate::output::inside(out, &self.dir)
        {
            return Err(input(format!(
                "{flag} {} is inside the unit's directory {} with a name a later command would read as one of the unit's files (*.{}); write it elsewhere",
                out.display(),
                self.dir.display(),
                ext.unwrap_or_default()
            )));
        }
        Ok(())
    }
    /// Whether the directory holds what specgen wrote, checked before anything is simulated or
    /// compared, each difference named (exit 2): the manifest's fingerprint against its own
    /// parameters (a hand-edited manifest), the unit's header against the manifest (files of two
    /// configurations), and, unless `edited` (an RTL changed on purpose, to be checked against
    /// the manifest's configuration), every listed file's SHA-256.
    pub fn verify_files(&self, edited: bool) -> Result<(), Error> {
        let manifest = &self.inputs[0];
        let text = crate::small_file::read(manifest, MANIFEST_MAX_BYTES)
            .map_err(|e| input(format!("manifest {}: {e}", manifest.display())))?;
        let v: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        let ours = self.cfg.fingerprint();
        if let Some(stated) = v.get("fingerprint").and_then(|f| f.as_str()) {
            if stated != ours {
                return Err(input(format!(
                    "manifest {}: its parameters are not the ones specgen wrote it with (fingerprint {stated} stated, {ours} from its parameters): edited by hand? regenerate the unit",
                    manifest.display()
                )));
            }
        }
        let top = self.dir.join(format!("{}.v", self.cfg.top()));
        if let Ok(unit) = crate::small_file::read(&top, 64 << 20) {
            let header = unit
                .lines()
                .take(40)
                .find_map(|l| l.strip_prefix("// Fingerprint: "))
                .and_then(|r| r.split_whitespace().next());
            if let Some(h) = header.filter(|h| *h != ours) {
                return Err(input(format!(
                    "{} was generated for another configuration (fingerprint {h}) than its manifest {} states ({ours}): files of two units in one directory",
                    top.display(),
                    manifest.display()
                )));
            }
        }
        // every Verilog file a tool would read is one the manifest lists: a stray `*.v` beside
        // the unit (a module named like one of specgen's, an old copy) is never read in silence,
        // edited or not. (A directory without the unit's own Verilog, a netlist beside its
        // manifest, is the netlist's: what it holds is what is read.)
        if let Some(listed) = v
            .get("files")
            .and_then(|f| f.as_array())
            .filter(|f| !f.is_empty())
        {
            let names: Vec<&str> = listed
                .iter()
                .filter_map(|f| f.get("name").and_then(|n| n.as_str()))
                .collect();
            let unit_here = names
                .iter()
                .any(|n| n.ends_with(".v") && self.dir.join(n).is_file());
            for src in self
                .sources
                .iter()
                .chain(&self.sim_models)
                .filter(|_| unit_here)
            {
                let rel = src
                    .strip_prefix(&self.dir)
                    .map(|r| r.to_string_lossy().into_owned())
                    .unwrap_or_default();
                if !names.contains(&rel.as_str()) {
                    return Err(input(format!(
                        "{} is not a file of this unit (manifest {} does not list it), and every tool would read it: move it out of {}",
                        src.display(),
                        manifest.display(),
                        self.dir.display()
                    )));
                }
            }
        }
        if edited {
            return Ok(());
        }
        // a manifest without its file list would check nothing: refused, not trusted
        let Some(files) = v
            .get("files")
            .and_then(|f| f.as_array())
            .filter(|f| !f.is_empty())
        else {
            return Err(input(format!(
                "manifest {} lists no files (`files` with their SHA-256): edited by hand? regenerate the unit, or pass --edited to check an RTL changed on purpose",
                manifest.display()
            )));
        };
        for f in files {
            let (Some(name), Some(want)) = (
                f.get("name").and_then(|n| n.as_str()),
                f.get("sha256").and_then(|h| h.as_str()),
            ) else {
                continue;
            };
            let Some(path) = self.inputs.iter().find(|p| {
                p.strip_prefix(&self.dir)
                    .is_ok_and(|r| r == Path::new(name))
            }) else {
                continue;
            };
            let bytes = crate::small_file::read_bytes(path, crate::small_file::UNIT_FILE_MAX)
                .map_err(|e| input(format!("{} {e}", path.display())))?;
            let got = crate::bits::sha256_hex(&bytes, 32);
            if got != want {
                return Err(input(format!(
                    "{} is not the file specgen wrote (its SHA-256 is not the one manifest {} lists): regenerate it, or pass --edited to check an RTL changed on purpose",
                    path.display(),
                    manifest.display()
                )));
            }
        }
        Ok(())
    }

    /// What the unit's directory is now: its identity (device and inode: a swap by `generate`
    /// gives the name a new directory) and a digest of every file of the unit. Two snapshots
    /// differ when the directory changed in between.
    pub fn snapshot(&self) -> Vec<u8> {
        use std::os::unix::fs::MetadataExt;
        let mut h = sha2::Sha256::new();
        if let Ok(m) = std::fs::metadata(&self.dir) {
            h.update(m.dev().to_le_bytes());
            h.update(m.ino().to_le_bytes());
        }
        let mut files: Vec<&PathBuf> = self
            .inputs
            .iter()
            .chain(&self.sources)
            .chain(&self.sim_models)
            .collect();
        files.sort();
        files.dedup();
        for f in files {
            h.update(f.as_os_str().as_encoded_bytes());
            match crate::small_file::read_bytes(f, crate::small_file::UNIT_FILE_MAX) {
                Ok(bytes) => h.update(sha2::Sha256::digest(&bytes)),
                Err(_) => h.update(b"missing"),
            }
        }
        h.finalize().to_vec()
    }

    /// What a simulator reads: the sources, then the simulation models.
    pub(crate) fn sim_sources(&self) -> Vec<PathBuf> {
        self.sources
            .iter()
            .chain(&self.sim_models)
            .cloned()
            .collect()
    }
}

impl Design {
    /// The RTL in `dir` with the plan its manifest states.
    pub fn load(dir: &Path) -> Result<Design, Error> {
        let (path, params, sources, sim_models, inputs) = Design::files(dir)?;
        let plan = crate::plan::Plan::from_params(params)
            .map_err(|e| input(format!("manifest {}: {e}", path.display())))?;
        let cfg = plan.cfg.clone();
        Ok(Design {
            dir: dir.to_path_buf(),
            cfg,
            plan,
            sources,
            sim_models,
            inputs,
        })
    }

    /// The manifest (its path and the parameters it states), the Verilog sources and the
    /// simulation models in `dir`.
    #[allow(clippy::type_complexity)] // (manifest, its parameters, sources, sim models, inputs)
    fn files(
        dir: &Path,
    ) -> Result<(PathBuf, Params, Vec<PathBuf>, Vec<PathBuf>, Vec<PathBuf>), Error> {
        let entries = std::fs::read_dir(dir).map_err(|e| {
            input(format!(
                "cannot read the RTL directory {}: {e}",
                dir.display()
            ))
        })?;
        let mut manifests = Vec::new();
        // JSON files that could not be read as JSON, with why (named where no manifest is found)
        let mut unread: Vec<String> = Vec::new();
        let mut sources = Vec::new();
        let mut sim_models = Vec::new();
        // the simulation models live in `sim/` (an output of an older specgen has them beside)
        let sim_dir = dir.join(crate::names::SIM_DIR);
        if sim_dir.is_dir() {
            let models = std::fs::read_dir(&sim_dir)
                .map_err(|e| input(format!("cannot read {}: {e}", sim_dir.display())))?;
            sim_models.extend(
                models
                    .flatten()
                    .map(|e| e.path())
                    .filter(|p| p.extension().is_some_and(|e| e == "v")),
            );
        }
        for entry in entries.flatten() {
            let path = entry.path();
            match path.extension().and_then(|e| e.to_str()) {
                Some("v")
                    if path
                        .file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(crate::names::is_sim_model_file) =>
                {
                    sim_models.push(path)
                }
                Some("v") => sources.push(path),
                Some("json") => {
                    // a regular file of at most MANIFEST_MAX_BYTES (never a FIFO or a device)
                    let text = match crate::small_file::read(&path, MANIFEST_MAX_BYTES) {
                        Ok(t) => t,
                        Err(e) => {
                            unread.push(format!("{} {e}", path.display()));
                            continue;
                        }
                    };
                    let v: serde_json::Value = match serde_json::from_str(&text) {
                        Ok(v) => v,
                        Err(e) => {
                            unread.push(format!("{} is not JSON ({e})", path.display()));
                            continue;
                        }
                    };
                    if v.get("generator").and_then(|g| g.as_str()) == Some("specgen") {
                        manifests.push((path, text));
                    }
                }
                _ => {}
            }
        }
        sources.sort();
        sim_models.sort();
        let (path, text) = match manifests.len() {
            1 => manifests.pop().unwrap(),
            0 => {
                // at most three named, the rest counted
                let why = match unread.len() {
                    0 => String::new(),
                    n if n > 3 => format!(": {}; and {} more", unread[..3].join("; "), n - 3),
                    _ => format!(": {}", unread.join("; ")),
                };
                return Err(input(format!(
                    "no specgen manifest (<top>.json) in the RTL directory {}{why}",
                    dir.display()
                )));
            }
            _ => {
                return Err(input(format!(
                    "more than one specgen manifest in the RTL directory {}",
                    dir.display()
                )))
            }
        };
        if sources.is_empty() {
            return Err(input(format!(
                "no Verilog (*.v) in the RTL directory {}",
                dir.display()
            )));
        }
        let params = Params::from_json(&text)
            .map_err(|e| input(format!("manifest {}: {}", path.display(), e.reason())))?;
        let listed: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        let mut inputs = vec![path.clone()];
        for f in listed
            .get("files")
            .and_then(|f| f.as_array())
            .into_iter()
            .flatten()
        {
            // a listed name is a plain file name of the unit's; anything else is not ours to guard
            let plain = |n: &str| !n.is_empty() && !n.contains('/') && n != ".." && n != ".";
            let ours = |n: &&str| {
                plain(n)
                    || n.strip_prefix(crate::names::SIM_DIR)
                        .and_then(|r| r.strip_prefix('/'))
                        .is_some_and(plain)
            };
            if let Some(name) = f.get("name").and_then(|n| n.as_str()).filter(ours) {
                let p = dir.join(name);
                if p.exists() {
                    inputs.push(p);
                }
            }
        }
        Ok((path, params, sources, sim_models, inputs))
    }
}

/// One clock cycle of stimulus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Cycle {
    pub inputs: Inputs,
    pub valid: bool,
    pub rst: bool,
    /// `out_ready` low (a handshake unit's consumer stalls this cycle)
    pub stall: bool,
    /// `ks_load` high: the material registers take `inputs.ks` (a static colour)
    pub load: bool,
    /// `in_tag` (masked to the unit's tag bits)
    pub tag: u64,
    /// the clock enable low (`--clock-enable`): no transfer and no load at this edge
    pub disabled: bool,
}

impl Cycle {
    /// A pixel offered with `in_valid` high.
    pub fn pixel(inputs: Inputs) -> Cycle {
        Cycle {
            inputs,
            valid: true,
            ..Cycle::default()
        }
    }
    /// A reset cycle (nothing offered).
    pub fn reset() -> Cycle {
        Cycle {
            rst: true,
            ..Cycle::default()
        }
    }
}

/// What the simulator returned for one cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sampled {
    pub(crate) outputs: Outputs,
    pub(crate) valid: bool,
    /// `in_ready` (always 1 without a handshake)
    pub(crate) in_ready: bool,
    /// `idle` (0 without material registers)
    pub(crate) idle: bool,
    /// `out_tag` (0 without a tag)
    pub(crate) tag: u64,
}
