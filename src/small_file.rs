//! Reading a file the user names, bounded: a regular file (never a FIFO or a device, which
//! would block or never end) of at most a stated size. One reader for every small input:
//! `--config`, `--hw`, the manifests found in an RTL directory, and every file of a unit.

use std::io::Read;
use std::path::Path;

/// Why a small file could not be read, in words that follow its path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SmallFileError {
    /// a FIFO, a device, a directory
    NotRegular,
    /// larger than the limit (bytes)
    TooLarge(u64),
    /// the OS refused, or the text is not UTF-8
    Io(String),
}

impl std::fmt::Display for SmallFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SmallFileError::NotRegular => write!(f, "is not a regular file"),
            SmallFileError::TooLarge(n) => write!(f, "is {n} bytes"),
            SmallFileError::Io(e) => write!(f, "cannot be read ({e})"),
        }
    }
}

impl std::error::Error for SmallFileError {}

/// The most any file of a unit may hold (RTL, table, simulation model): the largest generated
/// unit is well under a MiB; a file past this is not ours, and is not read.
pub const UNIT_FILE_MAX: u64 = 64 << 20;

/// The bytes of `path` when it is a regular file of at most `limit` bytes. It is opened without
/// blocking (a FIFO put in its place between a check and the open cannot hang the reader) and
/// checked on the open file, and read with the limit, in case it grows.
pub fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>, SmallFileError> {
    use std::os::unix::fs::OpenOptionsExt;
    let f = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path).map_err(|e| SmallFileError::Io(e.to_string()))?;
    let meta = f.metadata().map_err(|e| SmallFileError::Io(e.to_string()))?;
    if !meta.is_file() {
        return Err(SmallFileError::NotRegular);
    }
    if meta.len() > limit {
        return Err(SmallFileError::TooLarge(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    f.take(limit + 1).read_to_end(&mut bytes).map_err(|e| SmallFileError::Io(e.to_string()))?;
    if bytes.len() as u64 > limit {
        return Err(SmallFileError::TooLarge(bytes.len() as u64));
    }
    Ok(bytes)
}

/// The text of `path` when it is a regular file of at most `limit` bytes ([`read_bytes`]).
pub fn read(path: &Path, limit: u64) -> Result<String, SmallFileError> {
    String::from_utf8(read_bytes(path, limit)?).map_err(|e| SmallFileError::Io(e.to_string()))
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
        assert_eq!(read(&p, 1), Err(SmallFileError::TooLarge(2)));
        assert_eq!(read(dir.path(), 10), Err(SmallFileError::NotRegular));
        assert!(matches!(read(&dir.path().join("none"), 10), Err(SmallFileError::Io(_))));
    }
}
