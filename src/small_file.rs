//! Reading a file the user names, bounded: a regular file (never a FIFO or a device, which
//! would block or never end) of at most a stated size. One reader for every small input:
//! `--config`, `--hw`, and the manifests found in an RTL directory.

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

/// The text of `path` when it is a regular file of at most `limit` bytes (checked before it is
/// opened, and again while it is read, in case it grows).
pub fn read(path: &Path, limit: u64) -> Result<String, SmallFileError> {
    let meta = std::fs::metadata(path).map_err(|e| SmallFileError::Io(e.to_string()))?;
    if !meta.is_file() {
        return Err(SmallFileError::NotRegular);
    }
    if meta.len() > limit {
        return Err(SmallFileError::TooLarge(meta.len()));
    }
    let mut text = String::new();
    std::fs::File::open(path).and_then(|f| f.take(limit + 1).read_to_string(&mut text)).map_err(|e| SmallFileError::Io(e.to_string()))?;
    if text.len() as u64 > limit {
        return Err(SmallFileError::TooLarge(text.len() as u64));
    }
    Ok(text)
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
