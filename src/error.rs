//! The crate's one error type: every stage returns it, the command line turns it into a
//! message (with its causes) and an exit code.

use std::fmt;
use std::path::PathBuf;

/// What went wrong, and so which exit code the command line gives.
#[derive(Debug)]
pub enum Error {
    /// A parameter out of its range or malformed (exit 2).
    Parameter(crate::config::ConfigError),
    /// Arguments that cannot work together, or input that is not what it must be (exit 2).
    Usage(String),
    /// A check ran and failed: a mismatch, a tool's error, a contract broken (exit 1).
    CheckFailed(String),
    /// Reading or writing a file failed (exit 1).
    Io { action: &'static str, path: PathBuf, source: std::io::Error },
}

impl Error {
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Parameter(_) | Error::Usage(_) => 2,
            Error::CheckFailed(_) | Error::Io { .. } => 1,
        }
    }
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Error {
        Error::Io { action, path: path.into(), source }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Parameter(e) => write!(f, "{e}"),
            Error::Usage(m) | Error::CheckFailed(m) => write!(f, "{m}"),
            Error::Io { action, path, .. } => write!(f, "cannot {action} {}", path.display()),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

impl From<crate::config::ConfigError> for Error {
    fn from(e: crate::config::ConfigError) -> Self {
        Error::Parameter(e)
    }
}

/// A usage error (exit 2).
pub fn usage(message: impl Into<String>) -> Error {
    Error::Usage(message.into())
}

/// A failed check (exit 1).
pub fn failed(message: impl Into<String>) -> Error {
    Error::CheckFailed(message.into())
}

/// The error and every cause under it, one per line after the first.
pub fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        s.push_str(&format!("\n  caused by: {c}"));
        cause = c.source();
    }
    s
}
