//! The crate's one error type: every stage returns it. Its variants say what went wrong in
//! the library's terms (a parameter, the user's input, an output directory, a tool, a failed
//! check, a file); the command line turns them into messages with flag names and exit codes.

use std::fmt;
use std::path::PathBuf;

/// What went wrong.
#[derive(Debug)]
pub enum Error {
    /// A parameter out of its range or malformed.
    Config(crate::config::ConfigError),
    /// Something the user gave is not what it must be: a directory without a manifest,
    /// arguments that cannot work together, a file of the wrong kind.
    Input(String),
    /// An output directory that is not ours to replace, or is being written.
    Output(OutputError),
    /// An external tool is missing, failed, or said something unexpected (its own text kept).
    Tool { tool: String, message: String },
    /// A check ran and failed: a mismatch with the golden model, a contract broken.
    Mismatch(String),
    /// Reading or writing a file failed.
    Io { action: &'static str, path: PathBuf, source: std::io::Error },
}

impl Error {
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Error {
        Error::Io { action, path: path.into(), source }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Config(e) => write!(f, "{e}"),
            Error::Output(e) => write!(f, "{e}"),
            Error::Input(m) | Error::Mismatch(m) => write!(f, "{m}"),
            Error::Tool { message, .. } => write!(f, "{message}"),
            Error::Io { action, path, .. } => write!(f, "cannot {action} {}", path.display()),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            Error::Output(OutputError::Io(e)) => Some(e),
            _ => None,
        }
    }
}

impl From<crate::config::ConfigError> for Error {
    fn from(e: crate::config::ConfigError) -> Self {
        Error::Config(e)
    }
}

impl From<OutputError> for Error {
    fn from(e: OutputError) -> Self {
        Error::Output(e)
    }
}

/// Why an output directory was refused, or could not be written.
#[derive(Debug)]
pub enum OutputError {
    /// It holds something that is not a previous specgen output.
    Occupied(PathBuf, String),
    /// It cannot be an output at all (the current directory, a parent we cannot write, a
    /// dangling link): the reason.
    Refused(PathBuf, String),
    /// Another specgen has been writing the same output for longer than we wait (its process
    /// id when known).
    Busy(PathBuf, Option<u32>),
    Io(std::io::Error),
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OutputError::Occupied(dir, why) => {
                write!(f, "refusing to write into {}: {why}; only an empty directory or a previous specgen output is replaced", dir.display())
            }
            OutputError::Refused(dir, why) => write!(f, "refusing to write {}: {why}", dir.display()),
            OutputError::Busy(dir, holder) => {
                let who = holder.map_or("another specgen".to_string(), |pid| format!("another specgen (process {pid})"));
                write!(f, "{who} has been writing {} for 10 s and still holds its lock; nothing written (try again when it has finished)", dir.display())
            }
            OutputError::Io(e) => write!(f, "{e}"),
        }
    }
}

/// The user's input is not what it must be.
pub fn input(message: impl Into<String>) -> Error {
    Error::Input(message.into())
}

/// A check failed.
pub fn mismatch(message: impl Into<String>) -> Error {
    Error::Mismatch(message.into())
}

/// A tool is missing or failed.
pub fn tool(tool: &str, message: impl Into<String>) -> Error {
    Error::Tool { tool: tool.into(), message: message.into() }
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
