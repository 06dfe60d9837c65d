//! The simulator cache: the caller's own directory, an entry only where it is ours, keyed by
//! the tools' identity.

use super::*;

/// The simulator cache: `$SPECGEN_CACHE_DIR`, `$XDG_CACHE_HOME/specgen`, `$HOME/.cache/specgen`
/// (where one can be made there), else `<tmp>/specgen-cache-<uid>`. Its programs are run, so it is the caller's own: created
/// `0700`, and checked on every use (`output::private_dir`: not a link, the caller's, writable
/// by no one else); a shared or planted directory is refused, never used.
pub(super) fn cache_root() -> Result<PathBuf, Failure> {
    let root = if let Some(dir) = std::env::var_os("SPECGEN_CACHE_DIR").filter(|d| !d.is_empty()) {
        // a relative name is the caller's working directory's (the simulators run elsewhere)
        std::path::absolute(PathBuf::from(&dir)).map_err(|e| {
            error::tool(
                "simulator",
                format!("SPECGEN_CACHE_DIR={}: {e}", PathBuf::from(&dir).display()),
            )
        })?
    } else if let Some(dir) =
        std::env::var_os("XDG_CACHE_HOME").filter(|d| Path::new(d).is_absolute())
    {
        PathBuf::from(dir).join("specgen")
    } else if let Some(cache) = std::env::var_os("HOME")
        .filter(|d| Path::new(d).is_absolute())
        .map(|home| PathBuf::from(home).join(".cache").join("specgen"))
        // a HOME where no cache can be made (not a directory, not writable) falls back to the
        // temporary one; a cache that is there is held to the rules below, never passed over
        .filter(|c| {
            c.exists()
                || c.parent()
                    .is_some_and(|p| std::fs::create_dir_all(p).is_ok())
        })
    {
        cache
    } else {
        std::env::temp_dir().join(format!("specgen-cache-{}", crate::output::euid()))
    };
    crate::output::private_dir(&root).map_err(|why| {
        error::tool(
            "simulator",
            format!("the simulator cache cannot be used: {why}"),
        )
    })?;
    Ok(root)
}

/// Whether a cache entry is a real directory of the caller's (not a link planted there).
pub(super) fn own_entry(dir: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    std::fs::symlink_metadata(dir).is_ok_and(|m| m.is_dir() && m.uid() == crate::output::euid())
}

/// What identifies the installed `tool` in a cache key: the program (a path as given, a name
/// as the PATH finds it), its size, modification time and inode (an upgrade or another install
/// changes them), read from the file system, not by running it (`verilator --version` starts
/// Perl: 30 ms a call). A program not found is the tool's error (exit 1), naming its package.
pub(super) fn tool_identity(tool: &str, package: &str) -> Result<String, Failure> {
    use std::os::unix::fs::MetadataExt;
    let missing = || {
        error::tool(tool, format!("{tool} not found: install the Debian package `{package}` (apt-get install -y {package}), or name the program"))
    };
    let program = if tool.contains('/') {
        Some(PathBuf::from(tool))
            .filter(|p| p.is_file())
            .ok_or_else(missing)?
    } else {
        let paths = std::env::var_os("PATH").ok_or_else(missing)?;
        std::env::split_paths(&paths)
            .map(|d| d.join(tool))
            .find(|p| p.is_file())
            .ok_or_else(missing)?
    };
    let real = std::fs::canonicalize(&program).unwrap_or(program);
    let m = std::fs::metadata(&real).map_err(|_| missing())?;
    Ok(format!(
        "{} {} {} {}",
        real.display(),
        m.len(),
        m.mtime(),
        m.ino()
    ))
}
