//! Reading a file the user names, bounded: a regular file (never a FIFO or a device, which
//! would block or never end) of at most a stated size. One reader for every small input:
//! `--config`, `--hw`, the manifests found in an RTL directory, and every file of a unit.

use std::io::Read;
use std::path::Path;

/// A refusal: not a regular file, or larger than the limit. Its kind is `InvalidInput`, which
/// tells it from the OS's own errors ([`refused`]).
fn refusal(why: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidInput, why)
}

/// Whether a [`read`] error is ours (not a regular file, too large) rather than the OS's.
pub fn refused(e: &std::io::Error) -> bool {
    e.kind() == std::io::ErrorKind::InvalidInput && e.raw_os_error().is_none()
}

/// The OS's error (or text that is not UTF-8) in words that follow a path.
fn unreadable(e: impl std::fmt::Display) -> std::io::Error {
    std::io::Error::other(format!("cannot be read ({e})"))
}

/// The most any file of a unit may hold (RTL, table, simulation model): the largest generated
/// unit is well under a MiB; a file past this is not ours, and is not read.
pub const UNIT_FILE_MAX: u64 = 64 << 20;
/// The most a built simulator program (a Verilator harness, an Icarus image) may be: 1 GiB.
pub const PROGRAM_MAX: u64 = 1 << 30;

/// The bytes of `path` when it is a regular file of at most `limit` bytes. It is opened without
/// blocking (a FIFO put in its place between a check and the open cannot hang the reader) and
/// checked on the open file, and read with the limit, in case it grows.
pub fn read_bytes(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::os::unix::fs::OpenOptionsExt;
    let f = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(unreadable)?;
    let meta = f.metadata().map_err(unreadable)?;
    if !meta.is_file() {
        return Err(refusal("is not a regular file".into()));
    }
    if meta.len() > limit {
        return Err(refusal(format!("is {} bytes", meta.len())));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    f.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(unreadable)?;
    if bytes.len() as u64 > limit {
        return Err(refusal(format!("is {} bytes", bytes.len())));
    }
    Ok(bytes)
}

/// The text of `path` when it is a regular file of at most `limit` bytes ([`read_bytes`]).
pub fn read(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_bytes(path, limit)?).map_err(unreadable)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_small_regular_files_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.json");
        std::fs::write(&p, "{}").unwrap();
        assert_eq!(read(&p, 2).unwrap(), "{}");
        let large = read(&p, 1).unwrap_err();
        assert!(
            refused(&large) && large.to_string() == "is 2 bytes",
            "{large}"
        );
        let directory = read(dir.path(), 10).unwrap_err();
        assert!(
            refused(&directory) && directory.to_string() == "is not a regular file",
            "{directory}"
        );
        let missing = read(&dir.path().join("none"), 10).unwrap_err();
        assert!(
            !refused(&missing) && missing.to_string().starts_with("cannot be read ("),
            "{missing}"
        );
    }
}
