//! Children and temporaries that do not outlive a run. A leaf: imports nothing from the crate.
//!
//! - Every tool specgen runs (simulators, their builds, yosys, nextpnr) is started by
//!   [`command`]: the child gets `PR_SET_PDEATHSIG(SIGKILL)`, so it dies with specgen however
//!   specgen ends (a signal, SIGKILL included, or a panic), and the default signal mask.
//! - Every temporary directory is made by [`temp_dir`] or [`temp_dir_in`], which registers it
//!   until it is dropped or kept; [`remove_temporaries_on_signals`] (the command line calls it
//!   first thing) has SIGINT, SIGTERM and SIGHUP handled by a thread of their own that removes
//!   every registered directory and ends the process with 128 + the signal's number. SIGKILL
//!   cannot be caught: what it leaves is swept by the next run (the simulator cache's
//!   `.build-<pid>-…`, the output staging and temporary files, by their dead process id).

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

/// The temporary directories alive now.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The signal being handled (0: none): from then on only the signal thread ends the process.
static SIGNALLED: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);

/// Ends the process with `code`, unless a signal is being handled: then the signal thread ends
/// it, with 128 + the signal, once the temporaries are gone (a run stopped by a signal never
/// reports the failures the stopping caused, such as a simulator's directory removed under it).
pub fn exit(code: i32) -> ! {
    if SIGNALLED.load(std::sync::atomic::Ordering::SeqCst) != 0 {
        loop {
            std::thread::park();
        }
    }
    std::process::exit(code)
}

/// A command whose process dies with specgen's and starts with no signal blocked.
pub fn command(program: impl AsRef<OsStr>) -> Command {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(program);
    let parent = std::process::id() as libc::pid_t;
    // SAFETY: the closure runs in the child between fork and exec and calls only
    // async-signal-safe functions (prctl, getppid, sigemptyset, pthread_sigmask).
    unsafe {
        cmd.pre_exec(move || {
            #[cfg(target_os = "linux")]
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL as libc::c_ulong) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            // specgen ended before the line above: end too
            if libc::getppid() != parent {
                return Err(std::io::Error::other("specgen ended while this tool was starting"));
            }
            let mut none: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut none);
            libc::pthread_sigmask(libc::SIG_SETMASK, &none, std::ptr::null_mut());
            Ok(())
        });
    }
    cmd
}

/// A temporary directory removed when dropped, and on SIGINT/SIGTERM/SIGHUP.
#[derive(Debug)]
pub struct TempDir {
    inner: Option<tempfile::TempDir>,
}

impl TempDir {
    fn register(inner: tempfile::TempDir) -> TempDir {
        TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner()).push(inner.path().to_path_buf());
        TempDir { inner: Some(inner) }
    }

    pub fn path(&self) -> &Path {
        self.inner.as_ref().expect("alive").path()
    }

    /// Keeps the directory (it was renamed into place, or is the caller's now): no longer removed.
    pub fn keep(mut self) -> PathBuf {
        let inner = self.inner.take().expect("alive");
        unregister(inner.path());
        inner.keep()
    }
}

fn unregister(path: &Path) {
    let mut all = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(i) = all.iter().position(|p| p == path) {
        all.swap_remove(i);
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if let Some(inner) = self.inner.take() {
            unregister(inner.path());
            drop(inner);
        }
    }
}

/// A temporary directory in the system's temporary directory.
pub fn temp_dir() -> std::io::Result<TempDir> {
    Ok(TempDir::register(tempfile::tempdir()?))
}

/// A temporary directory `<prefix>…` in `parent`.
pub fn temp_dir_in(parent: &Path, prefix: &str) -> std::io::Result<TempDir> {
    Ok(TempDir::register(tempfile::Builder::new().prefix(prefix).tempdir_in(parent)?))
}

/// Has SIGINT, SIGTERM and SIGHUP remove every registered temporary directory and end the
/// process (status 128 + the signal). Call it before any other thread starts: the signals are
/// blocked in the calling thread, whose mask every later thread inherits, and waited for by a
/// thread of their own. Children get the default mask back ([`command`]).
pub fn remove_temporaries_on_signals() {
    // SAFETY: plain libc calls on a signal set we own
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&mut set, s);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        let waiter = std::thread::Builder::new().name("signals".into()).spawn(move || {
            let mut sig: libc::c_int = 0;
            if libc::sigwait(&set, &mut sig) == 0 {
                SIGNALLED.store(sig, std::sync::atomic::Ordering::SeqCst);
                let all = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner()).clone();
                for dir in all {
                    let _ = std::fs::remove_dir_all(dir);
                }
                // children die with us (PR_SET_PDEATHSIG)
                libc::_exit(128 + sig);
            }
        });
        if waiter.is_err() {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}
