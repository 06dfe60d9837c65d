//! Writing at the edge: the library returns generated files as `(name, bytes)`; this module
//! puts them on disk without ever leaving a half-written output or replacing what is not ours.
//!
//! **A directory output** (`generate`, `report`) is built in a staging directory beside it and
//! swapped in with one `renameat2(RENAME_EXCHANGE)`: at every instant the name holds either the
//! whole old output or the whole new one, never nothing, so a kill at any point loses nothing.
//! The old output, now in the staging name, is removed after the swap; if the run is killed
//! first, the next run writing the same output removes it (under the lock, when the name is
//! present). Where the exchange is not available (another OS, a file system without it) two
//! renames are used, and a later run puts a saved old copy back instead of deleting it while
//! the name is missing.
//! - The lock is per output: a lock file `.specgen-lock-<hash of the name>` in the parent,
//!   taken with `flock` and removed on release, so writers of sibling outputs run in parallel
//!   and nothing is left beside the output.
//! - What an existing output may be is decided by the caller's check (here,
//!   `check_replaceable`): an empty directory or a previous specgen output of the same kind.
//! - The new directory gets the old one's mode (setgid included) and group; a new one gets
//!   `0777 & !umask`, as `mkdir` would give it.
//! - `--out .`, or any directory holding the current one, is refused with its reason: swapping
//!   it would leave the caller in a deleted directory. A symbolic link is followed (the output
//!   lands where it points; the link stays). A parent we cannot write is named in the error.
//!
//! **A single-file output** (`rom -o`, `vectors --out`, `render --out`, `--trace`, `synth --json`)
//! is written to a temporary file beside it (`.specgen-<tag>-<pid>-…`; one a killed run left is
//! removed by the next run writing the same output) and renamed over it. A symbolic link is written
//! through (its target is replaced, the link stays); a FIFO or character device (`/dev/null`,
//! `/dev/stdout`) is written as a stream; any other special file is refused. `-` and standard
//! output by any of its names (`/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1`) are the process's
//! own stream, whatever it is (a file opened with `>>` keeps its lines; a pipe works). A replaced file
//! keeps its mode; a new one gets `0666 & !umask`.

mod replace;
use replace::*;

use crate::error::{plain, At, Error};
use crate::names::SIM_DIR;
use std::path::{Path, PathBuf};

/// Whether two paths name one file (device and inode, links followed): an output that is an
/// input of the same command is refused.
pub fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

/// The directory a path lives in (`.` for a bare name).
pub(crate) fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The process's umask, read without changing it (Linux `/proc/self/status`), else the usual 022.
fn umask() -> u32 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find_map(|l| {
                l.strip_prefix("Umask:")
                    .and_then(|v| u32::from_str_radix(v.trim(), 8).ok())
            })
        })
        .unwrap_or(0o022)
}

/// The tag of one output's staging and lock names in its parent: a hash of its file name, so
/// the names of two outputs never overlap and any file name is data.
pub fn tag(target: &Path) -> String {
    let name = target
        .file_name()
        .map(|n| n.as_encoded_bytes().to_vec())
        .unwrap_or_default();
    crate::bits::sha256_hex(&name, 6)
}

/// How long a writer waits for another writer of the same output before it gives up.
const LOCK_WAIT: std::time::Duration = std::time::Duration::from_secs(10);

/// Holds the exclusive lock of one output while it is swapped in, so two writers of the same
/// output never race; the staging directories an interrupted run left are tidied under it.
/// The lock file is removed on release (while still locked); a writer that locked a file
/// removed meanwhile sees that its file is no longer the one at the path and tries again.
struct OutputLock {
    file: std::fs::File,
    path: PathBuf,
}

impl OutputLock {
    fn take(parent: &Path, target: &Path) -> Result<OutputLock, Error> {
        use std::os::unix::fs::MetadataExt;
        let tag = tag(target);
        let path = parent.join(format!(".specgen-lock-{tag}"));
        use std::os::unix::fs::OpenOptionsExt;
        let mut tries = 0;
        let start = std::time::Instant::now();
        let f = loop {
            // never through a link, never blocking on a FIFO: a lock path planted by someone
            // else is refused, not followed
            let f = std::fs::OpenOptions::new()
                .create(true)
                .truncate(false)
                .read(true)
                .write(true)
                .mode(0o600)
                .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC)
                .open(&path)
                .map_err(|e| match e.raw_os_error() {
                    Some(libc::ELOOP) => Error::Refused {
                        dir: target.to_path_buf(),
                        why: format!(
                            "its lock {} is a symbolic link, not specgen's: remove it",
                            path.display()
                        ),
                    },
                    Some(libc::ENXIO) => Error::Refused {
                        dir: target.to_path_buf(),
                        why: format!(
                            "its lock {} is a FIFO, not specgen's: remove it",
                            path.display()
                        ),
                    },
                    _ => unwritable(parent, target, e),
                })?;
            if !f.metadata().is_ok_and(|m| m.is_file()) {
                return Err(Error::Refused {
                    dir: target.to_path_buf(),
                    why: format!(
                        "its lock {} is not a regular file, not specgen's: remove it",
                        path.display()
                    ),
                });
            }
            match f.try_lock() {
                Ok(()) => {}
                // another writer: wait a bounded time, then name it
                Err(std::fs::TryLockError::WouldBlock) if start.elapsed() < LOCK_WAIT => {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    continue;
                }
                Err(std::fs::TryLockError::WouldBlock) => {
                    let mut holder = String::new();
                    let _ = std::io::Read::read_to_string(
                        &mut std::io::Read::take(&f, 32),
                        &mut holder,
                    );
                    return Err(Error::Busy {
                        dir: target.to_path_buf(),
                        holder: holder.trim().parse().ok(),
                    });
                }
                Err(std::fs::TryLockError::Error(e)) => {
                    return Err(Error::io("write", target, plain(e)))
                }
            }
            let same = match (f.metadata(), std::fs::metadata(&path)) {
                (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
                _ => false,
            };
            tries += 1;
            if same {
                break f;
            }
            if tries > 100 {
                return Err(Error::Busy {
                    dir: target.to_path_buf(),
                    holder: None,
                });
            }
        };
        // the holder's process id, for a writer that waits in vain
        let _ = f.set_len(0);
        let _ = std::io::Write::write_all(&mut &f, format!("{}\n", std::process::id()).as_bytes());
        // under the lock no other specgen is mid-swap on this output: what is left is from a
        // killed run. A saved old copy goes back when the name is missing, else it is removed.
        for entry in std::fs::read_dir(parent).at("write", target)?.flatten() {
            let name = entry.file_name();
            let name = name.to_string_lossy();
            let ours = name.starts_with(&format!(".specgen-old-{tag}-"))
                || name.starts_with(&format!(".specgen-new-{tag}-"));
            if !ours || !entry.file_type().is_ok_and(|t| t.is_dir()) {
                continue;
            }
            let saved = entry.path().join("old");
            if name.starts_with(".specgen-old-")
                && saved.is_dir()
                && std::fs::symlink_metadata(target).is_err()
            {
                std::fs::rename(&saved, target).at("write", target)?;
            }
            let _ = std::fs::remove_dir_all(entry.path());
        }
        // a signal mid-swap removes it too (the swap itself is atomic)
        crate::process::register(&path);
        Ok(OutputLock { file: f, path })
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        crate::process::unregister(&self.path);
        let _ = std::fs::remove_file(&self.path);
        let _ = self.file.unlock();
    }
}

/// The one-line reason a parent directory cannot take our staging directory or lock.
fn unwritable(parent: &Path, target: &Path, e: std::io::Error) -> Error {
    match e.raw_os_error() {
        Some(code) if code == libc::EACCES || code == libc::EPERM || code == libc::EROFS => Error::Refused {
            dir: target.to_path_buf(),
            why: format!(
                "its parent {} is not writable ({}), and specgen builds the new output beside the old one to swap it in whole",
                parent.display(),
                plain(e)
            ),
        },
        _ => Error::io("write", target, plain(e)),
    }
}

/// Swaps two directory entries in one step (Linux `renameat2(RENAME_EXCHANGE)`). `Ok(false)`:
/// not available here (another OS, or a file system without it).
fn exchange(a: &Path, b: &Path) -> std::io::Result<bool> {
    #[cfg(target_os = "linux")]
    {
        use std::ffi::CString;
        use std::os::unix::ffi::OsStrExt;
        let ca = CString::new(a.as_os_str().as_bytes())
            .map_err(|_| std::io::Error::from(std::io::ErrorKind::InvalidInput))?;
        let cb = CString::new(b.as_os_str().as_bytes())
            .map_err(|_| std::io::Error::from(std::io::ErrorKind::InvalidInput))?;
        // SAFETY: two NUL-terminated paths that live across the call; no memory is shared.
        let r = unsafe {
            libc::renameat2(
                libc::AT_FDCWD,
                ca.as_ptr(),
                libc::AT_FDCWD,
                cb.as_ptr(),
                libc::RENAME_EXCHANGE,
            )
        };
        if r == 0 {
            return Ok(true);
        }
        let e = std::io::Error::last_os_error();
        match e.raw_os_error() {
            Some(libc::EINVAL) | Some(libc::ENOSYS) | Some(libc::EOPNOTSUPP) => Ok(false),
            _ => Err(e),
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (a, b);
        Ok(false)
    }
}

/// Whether `dir` is the current directory or holds it.
fn holds_cwd(dir: &Path) -> bool {
    match (std::env::current_dir(), std::fs::canonicalize(dir)) {
        (Ok(cwd), Ok(dir)) => cwd.starts_with(&dir),
        _ => false,
    }
}

/// Writes `files` as the whole content of `dir`, atomically (see the module doc). `check` is
/// asked, under the lock, whether an existing `dir` may be replaced.
pub fn write_dir(
    dir: &Path,
    files: &[(String, Vec<u8>)],
    check: impl FnOnce(&Path) -> Result<(), Error>,
) -> Result<(), Error> {
    // `link/` names the link (the trailing separator would make every rename of it fail)
    let normal: PathBuf = dir.components().collect();
    let dir = normal.as_path();
    // a symbolic link is followed: the output lands where it points, and the link stays
    let resolved;
    let dir = match std::fs::symlink_metadata(dir) {
        Ok(m) if m.file_type().is_symlink() => {
            resolved = std::fs::canonicalize(dir).map_err(|_| Error::Refused {
                dir: dir.to_path_buf(),
                why: "it is a symbolic link to nothing (a dangling link)".into(),
            })?;
            resolved.as_path()
        }
        _ => dir,
    };
    if holds_cwd(dir) {
        return Err(Error::Refused {
            dir: dir.to_path_buf(),
            why: "it is the current directory or holds it; the output is swapped in whole, which would leave this shell in a removed directory: run from outside it"
                .into(),
        });
    }
    if dir.file_name().is_none() {
        return Err(Error::Refused {
            dir: dir.to_path_buf(),
            why: "it has no name of its own (`/`, `..`): name the output directory".into(),
        });
    }
    let parent = parent_dir(dir);
    std::fs::create_dir_all(&parent).at("write", dir)?;
    let _lock = OutputLock::take(&parent, dir)?;
    let old = std::fs::metadata(dir).ok();
    if old.is_some() {
        check(dir)?;
    }
    let tag = tag(dir);
    let staging = tempfile::Builder::new()
        .prefix(&format!(".specgen-new-{tag}-"))
        .tempdir_in(&parent)
        .map_err(|e| unwritable(&parent, dir, e))?;
    // the old directory's mode and group, or what mkdir would give a new one: the group and a
    // setgid bit first (writable by us meanwhile), so the files written in it take its group
    // as they would in the old one; the mode itself once they are written
    #[cfg(unix)]
    let mode = {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        if let Some(m) = &old {
            let _ = std::os::unix::fs::chown(staging.path(), None, Some(m.gid()));
        }
        let mode = old.as_ref().map_or(0o777 & !umask(), |m| m.mode() & 0o7777);
        std::fs::set_permissions(
            staging.path(),
            std::fs::Permissions::from_mode((mode | 0o700) & 0o7777),
        )
        .at("write", dir)?;
        mode
    };
    for (name, bytes) in files {
        let path = staging.path().join(name);
        if let Some(sub) = path.parent().filter(|p| *p != staging.path()) {
            std::fs::create_dir_all(sub).at("write", dir)?;
        }
        std::fs::write(path, bytes).at("write", dir)?;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(staging.path(), std::fs::Permissions::from_mode(mode))
            .at("write", dir)?;
    }
    if old.is_none() {
        std::fs::rename(staging.path(), dir).at("write", dir)?;
    } else if exchange(staging.path(), dir).at("write", dir)? {
        // the staging name now holds the old output: dropping it removes it (an old output the
        // user made read-only, 0555, is made the owner's to empty first, or it would stay)
        open_for_removal(staging.path());
        return Ok(());
    } else {
        let graveyard = tempfile::Builder::new()
            .prefix(&format!(".specgen-old-{tag}-"))
            .tempdir_in(&parent)
            .at("write", dir)?;
        std::fs::rename(dir, graveyard.path().join("old")).at("write", dir)?;
        if let Err(e) = std::fs::rename(staging.path(), dir) {
            // put the previous output back before reporting
            let _ = std::fs::rename(graveyard.path().join("old"), dir);
            return Err(Error::io("write", dir, plain(e)));
        }
        open_for_removal(&graveyard.path().join("old"));
        drop(graveyard); // removes the previous output
    }
    let _ = staging.keep(); // renamed away: nothing left to clean up
    Ok(())
}

/// Writes one file (see the module doc).
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_file_with(path, |w| w.write_all(bytes))
}

/// Whether the file `path` is inside the directory `dir` (or is it), through links: both
/// resolved where they exist, so no spelling of either hides it.
pub fn inside(path: &Path, dir: &Path) -> bool {
    let resolve = |p: &Path| -> PathBuf {
        std::fs::canonicalize(p).unwrap_or_else(|_| {
            let abs = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
            match (abs.parent(), abs.file_name()) {
                (Some(parent), Some(name)) => std::fs::canonicalize(parent)
                    .unwrap_or_else(|_| parent.to_path_buf())
                    .join(name),
                _ => abs,
            }
        })
    };
    resolve(path).starts_with(resolve(dir))
}

/// Whether an output path means standard output: `-`, `/dev/stdout`, `/dev/fd/1`,
/// `/proc/self/fd/1`.
pub fn is_stdout(path: &Path) -> bool {
    ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"]
        .iter()
        .any(|p| path == Path::new(p))
}

/// Where a single-file output really goes: through a symbolic link to its target.
pub(crate) fn through_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut path = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&path) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&path)?;
                path = if to.is_absolute() {
                    to
                } else {
                    parent_dir(&path).join(to)
                };
            }
            _ => return Ok(path),
        }
    }
    Err(std::io::Error::from_raw_os_error(libc::ELOOP))
}

/// A directory only the caller can write (the simulator cache): created `0700` when missing;
/// an existing one must be a real directory (not a symbolic link), owned by the caller's user,
/// and writable by no one else. Checked on every use, so an entry planted by another user
/// is never run. `Err`: refused, with the reason.
pub fn private_dir(dir: &Path) -> Result<(), Error> {
    let refused = |why: String| Error::Refused {
        dir: dir.to_path_buf(),
        why,
    };
    use std::os::unix::fs::{DirBuilderExt, MetadataExt};
    if std::fs::symlink_metadata(dir).is_err() {
        // the directories that exist above it are checked before any is made below them: a
        // refusal leaves nothing behind in another user's directory
        if let Some(existing) = dir
            .ancestors()
            .skip(1)
            .find(|a| !a.as_os_str().is_empty() && std::fs::symlink_metadata(a).is_ok())
        {
            safe_ancestors(&existing.join("cache"))?;
        }
        if let Some(parent) = dir.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).map_err(|e| {
                refused(format!("cannot create {}: {}", parent.display(), plain(e)))
            })?;
        }
        match std::fs::DirBuilder::new().mode(0o700).create(dir) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => {
                return Err(refused(format!(
                    "cannot create {}: {}",
                    dir.display(),
                    plain(e)
                )))
            }
        }
    }
    let m = std::fs::symlink_metadata(dir)
        .map_err(|e| refused(format!("cannot read {}: {}", dir.display(), plain(e))))?;
    let me = euid();
    safe_ancestors(dir)?;
    if m.file_type().is_symlink() {
        Err(refused("it is a symbolic link; specgen runs programs from its cache only in a directory of your own".into()))
    } else if !m.is_dir() {
        Err(refused("it is not a directory".into()))
    } else if m.uid() != me {
        Err(refused(format!("it belongs to user {}, not to you (user {me}); specgen runs programs from its cache only in a directory of your own", m.uid())))
    } else if m.mode() & 0o022 != 0 {
        Err(refused(format!(
            "it is writable by others (mode {:04o}); specgen runs programs from its cache only in a directory no one else can write (chmod go-w)",
            m.mode() & 0o7777
        )))
    } else {
        Ok(())
    }
}

/// Checks every directory above `dir` the way OpenSSH checks an `authorized_keys` path (its
/// real path, from the root down): each is owned by root or the caller, and one that others can
/// write has the sticky bit (`/tmp`: no one else can rename or remove what is ours there) and
/// is root's or the caller's. Another user who can write an ancestor could swap what is below
/// it for a directory of theirs.
fn safe_ancestors(dir: &Path) -> Result<(), Error> {
    let refused = |why: String| Error::Refused {
        dir: dir.to_path_buf(),
        why,
    };
    use std::os::unix::fs::MetadataExt;
    let parent = parent_dir(dir);
    let real = std::fs::canonicalize(&parent)
        .map_err(|e| refused(format!("cannot resolve {}: {}", parent.display(), plain(e))))?;
    let me = euid();
    for a in real.ancestors() {
        let m = std::fs::metadata(a)
            .map_err(|e| refused(format!("cannot read {}: {}", a.display(), plain(e))))?;
        if m.uid() != 0 && m.uid() != me {
            return Err(refused(format!(
                "{} above it belongs to user {}, who could replace what is below it; specgen runs programs from its cache only under directories of yours or root's",
                a.display(),
                m.uid()
            )));
        }
        if m.mode() & 0o022 != 0 && m.mode() & 0o1000 == 0 {
            return Err(refused(format!(
                "{} above it is writable by others (mode {:04o}) without the sticky bit; specgen runs programs from its cache only under directories no one else can change",
                a.display(),
                m.mode() & 0o7777
            )));
        }
    }
    Ok(())
}

/// The caller's effective user id.
pub(crate) fn euid() -> u32 {
    // SAFETY: geteuid has no preconditions and cannot fail
    unsafe { libc::geteuid() }
}

pub(crate) use crate::process::remove_orphans;

/// Opens a FIFO for writing without hanging: its reader has `FIFO_WAIT` to appear, then the
/// write fails ("no process reads it").
#[cfg(unix)]
fn open_fifo(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    use std::os::unix::io::AsRawFd;
    const FIFO_WAIT: std::time::Duration = std::time::Duration::from_secs(10);
    let start = std::time::Instant::now();
    loop {
        match std::fs::OpenOptions::new()
            .write(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(path)
        {
            Ok(f) => {
                // blocking writes from here on: the reader paces the stream
                // SAFETY: fcntl on a descriptor we own
                let flags = unsafe { libc::fcntl(f.as_raw_fd(), libc::F_GETFL) };
                if flags < 0
                    || unsafe {
                        libc::fcntl(f.as_raw_fd(), libc::F_SETFL, flags & !libc::O_NONBLOCK)
                    } < 0
                {
                    return Err(std::io::Error::last_os_error());
                }
                return Ok(f);
            }
            Err(e) if e.raw_os_error() == Some(libc::ENXIO) && start.elapsed() < FIFO_WAIT => {
                std::thread::sleep(std::time::Duration::from_millis(50))
            }
            Err(e) if e.raw_os_error() == Some(libc::ENXIO) => {
                return Err(std::io::Error::other(format!(
                    "it is a FIFO and no process opened it for reading within {} s",
                    FIFO_WAIT.as_secs()
                )))
            }
            Err(e) => return Err(e),
        }
    }
}

/// Writes one file from a writer `fill` streams into: a buffered temp file in the same
/// directory, renamed over the target only when `fill` succeeded (on error nothing is left);
/// a FIFO or character device gets the stream itself.
pub fn write_file_with<T>(
    path: &Path,
    fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<T>,
) -> std::io::Result<T> {
    // `-` and standard output by any of its names are the stream itself, whatever it is: a
    // file opened for appending (`>> log`) keeps its lines, a pipe works (its /proc link names
    // nothing that can be opened)
    if is_stdout(path) {
        let mut w = std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
        let v = fill(&mut w)?;
        std::io::Write::flush(&mut w)?;
        return Ok(v);
    }
    let path = through_links(path)?;
    let existing = std::fs::metadata(&path).ok();
    #[cfg(unix)]
    if let Some(m) = &existing {
        use std::os::unix::fs::FileTypeExt;
        let t = m.file_type();
        if t.is_fifo() || t.is_char_device() {
            let f = if t.is_fifo() {
                open_fifo(&path)?
            } else {
                std::fs::OpenOptions::new().write(true).open(&path)?
            };
            let mut w = std::io::BufWriter::with_capacity(1 << 16, f);
            let v = fill(&mut w)?;
            std::io::Write::flush(&mut w)?;
            return Ok(v);
        }
        if !t.is_file() {
            let what = if t.is_dir() {
                "a directory"
            } else if t.is_block_device() {
                "a block device"
            } else {
                "a special file"
            };
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("it is {what}, not a file specgen may replace"),
            ));
        }
    }
    let parent = parent_dir(&path);
    // the temporary file is `.specgen-<tag>-<pid>-…`: what a killed run left for this output
    // (its process gone) is removed by the next run writing it
    let prefix = format!(".specgen-{}-", tag(&path));
    remove_orphans(&parent, &prefix, false);
    let mut tmp = tempfile::Builder::new()
        .prefix(&format!("{prefix}{}-", std::process::id()))
        .tempfile_in(&parent)
        .map_err(plain)?;
    let value = {
        let mut w = std::io::BufWriter::with_capacity(1 << 20, tmp.as_file_mut());
        let v = fill(&mut w)?;
        std::io::Write::flush(&mut w)?;
        v
    };
    // a replaced file keeps its mode; a new one gets what `open(…, 0666)` would give it
    // (tempfile creates 0600)
    #[cfg(unix)]
    {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        let mode = existing
            .as_ref()
            .map_or(0o666 & !umask(), |m| m.mode() & 0o7777);
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))?;
        if let Some(m) = &existing {
            let _ = std::os::unix::fs::fchown(tmp.as_file(), None, Some(m.gid()));
        }
    }
    tmp.persist(&path).map_err(|e| plain(e.error))?;
    Ok(value)
}

/// Writes `files` as the whole content of `dir`, atomically (`output::write_dir`). An
/// existing `dir` is replaced only when it is empty or holds nothing but a previous specgen
/// output of the same kind, unedited.
pub fn write_dir_atomically(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<(), Error> {
    write_dir_atomically_forced(dir, files, false)
}

/// [`write_dir_atomically`]; with `force`, also over files of a previous output edited by hand.
pub fn write_dir_atomically_forced(
    dir: &Path,
    files: &[(String, Vec<u8>)],
    force: bool,
) -> Result<(), Error> {
    // a report's manifest is report.json (it has `claims`), an exploration's explore.json (it
    // has `exploration`); a unit's is <top>.json (it has `ports`)
    let kind = match (
        files.iter().any(|(n, _)| n == "report.json"),
        files.iter().any(|(n, _)| n == "explore.json"),
    ) {
        (true, _) => Some("claims"),
        (_, true) => Some("exploration"),
        _ => None,
    };
    write_dir(dir, files, |d| check_replaceable(d, kind, force))
}
