//! What an output may replace: a directory of specgen's own output of the same kind, never a
//! user's file, a link, the working directory or a directory edited by hand (unless forced); and
//! how what it replaces is opened for removal.

use super::*;

/// The names a previous specgen output in `dir` may hold: every `*.json` manifest written by
/// specgen for the same kind of output (a unit's manifest has `ports`, a report's `claims`), and
/// the files it lists. `Err` names the first entry that is not one of them, the other kind of
/// output, or (unless `force`) a listed file whose SHA-256 is not the manifest's: edited by hand.
/// The subdirectories a specgen output holds: a unit's simulation models (`sim/`) and an
/// exploration's results over seeds (`synth/`, `specgen explore`).
pub(super) const OUTPUT_SUBDIRS: [&str; 2] = [SIM_DIR, "synth"];

pub(super) fn check_replaceable(dir: &Path, kind: Option<&str>, force: bool) -> Result<(), Error> {
    let report = kind.is_some();
    let occupied = |why: String| Error::Occupied {
        dir: dir.to_path_buf(),
        why,
    };
    if !dir.is_dir() {
        return Err(occupied("it exists and is not a directory".into()));
    }
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).at("read", dir)? {
        let entry = entry.at("read", dir)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let kind = entry.file_type().at("read", dir)?;
        if kind.is_dir() && OUTPUT_SUBDIRS.contains(&name.as_str()) {
            // a subdirectory specgen writes (a unit's simulation models, an exploration's
            // results over seeds): its files are listed as `<sub>/<name>`
            for inner in std::fs::read_dir(entry.path()).at("read", dir)? {
                let inner = inner.at("read", dir)?;
                if !inner.file_type().at("read", dir)?.is_file() {
                    return Err(occupied(format!(
                        "it contains {name}/{:?}, which is not a regular file",
                        inner.file_name()
                    )));
                }
                names.push(format!("{name}/{}", inner.file_name().to_string_lossy()));
            }
            continue;
        }
        if !kind.is_file() {
            return Err(occupied(format!(
                "it contains {:?}, which is not a regular file",
                entry.file_name()
            )));
        }
        names.push(name);
    }
    let mut allowed: Vec<String> = Vec::new();
    for name in names.iter().filter(|n| n.ends_with(".json")) {
        let Ok(text) = crate::small_file::read(&dir.join(name), 1 << 20) else {
            continue;
        };
        let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
            continue;
        };
        if v.get("generator").and_then(|g| g.as_str()) != Some("specgen") {
            continue;
        }
        match (report, v.get("claims").is_some(), v.get("ports").is_some()) {
            (true, false, true) => {
                return Err(occupied(
                    "it holds a unit written by `specgen generate`, not a report".into(),
                ))
            }
            (false, true, _) => {
                return Err(occupied(
                    "it holds a report written by `specgen report`, not a unit".into(),
                ))
            }
            _ => {}
        }
        if let Some(k) = kind {
            for other in ["claims", "exploration"].into_iter().filter(|o| *o != k) {
                if v.get(other).is_some() {
                    return Err(occupied(format!(
                        "it holds another kind of specgen output ({other}), not this one"
                    )));
                }
            }
            // only the manifest by its own name vouches for the directory: a copy of it under
            // another name (a user's annotated.json) is the user's
            let own = if k == "claims" {
                "report.json"
            } else {
                "explore.json"
            };
            if v.get(k).is_none() || name != own {
                continue;
            }
        }
        // a manifest vouches for its directory only when it is one specgen wrote: a unit's is
        // `<top>.json` and its fingerprint is its own parameters'; every file it lists is there
        // (a copy of a manifest, alone or hand-edited, vouches for nothing)
        if !report && !genuine_unit_manifest(name, &text) {
            continue;
        }
        let listed: Vec<(&str, Option<&str>)> = v
            .get("files")
            .and_then(|f| f.as_array())
            .into_iter()
            .flatten()
            .filter_map(|f| {
                Some((
                    f.get("name")?.as_str()?,
                    f.get("sha256").and_then(|h| h.as_str()),
                ))
            })
            .collect();
        if listed.is_empty()
            || listed
                .iter()
                .any(|(n, _)| !names.iter().any(|have| have == n))
        {
            continue;
        }
        allowed.push(name.clone());
        for (n, want) in listed {
            allowed.push(n.to_string());
            if let (Some(want), false) = (want, force) {
                let path = dir.join(n);
                let bytes = crate::small_file::read_bytes(&path, crate::small_file::UNIT_FILE_MAX)
                    .map_err(|e| occupied(format!("{n} {e}")))?;
                if crate::bits::sha256_hex(&bytes, 32) != want {
                    return Err(occupied(format!(
                        "{n} was changed since specgen wrote it (its SHA-256 is not the manifest's); move it away, or pass --force to replace it"
                    )));
                }
            }
        }
    }
    match names.iter().find(|n| !allowed.contains(n)) {
        Some(stranger) => Err(occupied(format!(
            "it contains {stranger:?}, which no specgen manifest there lists"
        ))),
        None => Ok(()),
    }
}

/// Gives the owner write access to `dir` and the directories in it (an output's `sim/`), so
/// that removing it can empty them; files need none.
pub(super) fn open_for_removal(dir: &Path) {
    use std::os::unix::fs::PermissionsExt;
    let mut dirs = vec![dir.to_path_buf()];
    if let Ok(entries) = std::fs::read_dir(dir) {
        dirs.extend(
            entries
                .flatten()
                .take(1000)
                .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
                .map(|e| e.path()),
        );
    }
    for d in dirs {
        if let Ok(m) = std::fs::symlink_metadata(&d) {
            if m.is_dir() {
                let _ = std::fs::set_permissions(
                    &d,
                    std::fs::Permissions::from_mode(m.permissions().mode() | 0o700),
                );
            }
        }
    }
}

/// Whether `text`, read as `name`, is a unit's manifest as specgen writes it: its parameters
/// make a valid configuration whose fingerprint is the manifest's and whose top names it.
pub(super) fn genuine_unit_manifest(name: &str, text: &str) -> bool {
    let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else {
        return false;
    };
    let Ok(params) = crate::config::Params::from_json(text) else {
        return false;
    };
    let Ok(cfg) = crate::config::Config::new(params) else {
        return false;
    };
    v.get("fingerprint").and_then(|f| f.as_str()) == Some(cfg.fingerprint().as_str())
        && name == format!("{}.json", cfg.top())
}
