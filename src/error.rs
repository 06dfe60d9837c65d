//! The crate's one error type: every stage returns it. Its variants say what went wrong in
//! the library's terms (a parameter, the user's input, an output directory, a tool, a failed
//! check, a file); the command line turns them into messages with flag names and exit codes.

use std::fmt;
use std::path::PathBuf;

/// What went wrong.
#[derive(Debug)]
pub enum Error {
    /// A parameter out of its range or malformed: its name in SPEC §2 (as in the manifest)
    /// and what it may be.
    Config {
        parameter: &'static str,
        message: String,
    },
    /// Something the user gave is not what it must be: a directory without a manifest,
    /// arguments that cannot work together, a file of the wrong kind.
    Input(String),
    /// An output directory that holds something that is not a previous specgen output.
    Occupied { dir: PathBuf, why: String },
    /// An output that cannot be one at all (the current directory, a parent we cannot write,
    /// a dangling link, a cache directory another user can write): the reason.
    Refused { dir: PathBuf, why: String },
    /// Another specgen has been writing the same output for longer than we wait (its process
    /// id when known).
    Busy { dir: PathBuf, holder: Option<u32> },
    /// An external tool is missing, failed, or said something unexpected (its own text kept).
    Tool { tool: String, message: String },
    /// A check ran and failed: a mismatch with the golden model, a contract broken.
    Mismatch(String),
    /// A model's output outside its contract (SPEC §3) on one port: what it got against the
    /// ideal. A finding of `SpecularModel::check`, which the checkers turn into a mismatch.
    Breach { port: &'static str, detail: String },
    /// Reading or writing a file failed.
    Io {
        action: &'static str,
        path: PathBuf,
        source: std::io::Error,
    },
}

impl Error {
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Error {
        Error::Io {
            action,
            path: path.into(),
            source,
        }
    }

    /// The parameter a parameter's error names (SPEC §2), `None` for any other error.
    pub fn parameter(&self) -> Option<&'static str> {
        match self {
            Error::Config { parameter, .. } => Some(parameter),
            _ => None,
        }
    }

    /// What the error says without naming its parameter: a parameter's message, else the
    /// whole text (for a caller that names the parameter itself).
    pub fn reason(&self) -> String {
        match self {
            Error::Config { message, .. } => message.clone(),
            other => other.to_string(),
        }
    }

    /// A contract's breach on `port`.
    pub(crate) fn breach(port: &'static str, detail: impl Into<String>) -> Error {
        Error::Breach {
            port,
            detail: detail.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Config { parameter, message } => write!(f, "invalid {parameter}: {message}"),
            Error::Occupied { dir, why } => {
                write!(f, "refusing to write into {}: {why}; only an empty directory or a previous specgen output is replaced", dir.display())
            }
            Error::Refused { dir, why } => write!(f, "refusing to write {}: {why}", dir.display()),
            Error::Busy { dir, holder } => {
                let who = holder.map_or("another specgen".to_string(), |pid| {
                    format!("another specgen (process {pid})")
                });
                write!(f, "{who} has been writing {} for 10 s and still holds its lock; nothing written (try again when it has finished)", dir.display())
            }
            Error::Input(m) | Error::Mismatch(m) => write!(f, "{m}"),
            Error::Breach { port, detail } => write!(f, "{port}: {detail}"),
            Error::Tool { message, .. } => write!(f, "{message}"),
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

/// An I/O result's error as the crate's, naming the file and what was done to it.
pub(crate) trait At<T> {
    fn at(self, action: &'static str, path: &std::path::Path) -> Result<T, Error>;
}

impl<T> At<T> for std::io::Result<T> {
    fn at(self, action: &'static str, path: &std::path::Path) -> Result<T, Error> {
        self.map_err(|e| Error::io(action, path, plain(e)))
    }
}

/// An I/O error without the (temporary) path some crates put in its text: the caller names
/// the user's path.
pub(crate) fn plain(e: std::io::Error) -> std::io::Error {
    if let Some(code) = e.raw_os_error() {
        return std::io::Error::from_raw_os_error(code);
    }
    // tempfile wraps the OS error with its own path: find the OS error underneath
    let mut cause: Option<&(dyn std::error::Error + 'static)> =
        e.get_ref().map(|r| r as &(dyn std::error::Error + 'static));
    while let Some(c) = cause {
        if let Some(code) = c
            .downcast_ref::<std::io::Error>()
            .and_then(|io| io.raw_os_error())
        {
            return std::io::Error::from_raw_os_error(code);
        }
        cause = c.source();
    }
    // tempfile's PathError shows "<OS error> at path <temp path>": keep the OS error only
    let text = e.to_string();
    std::io::Error::new(
        e.kind(),
        text.split(" at path ").next().unwrap_or(&text).to_string(),
    )
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
    Error::Tool {
        tool: tool.into(),
        message: message.into(),
    }
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
