//! Children and temporaries that do not outlive a run. A leaf: imports nothing from the crate
//! but its error type.
//!
//! - Every tool specgen runs (simulators, their builds, yosys, nextpnr) is started by
//!   [`command`]: the child gets `PR_SET_PDEATHSIG(SIGKILL)` and the default signal mask, and
//!   joins one process group led by a *warden*, a small process forked before the first tool
//!   that waits for specgen to end (the read end of a pipe only specgen holds) and then kills
//!   the whole group. However specgen ends (returning, a signal, SIGKILL, a panic), every tool
//!   and every process a tool started (`verilator → make → g++ → cc1plus`, yosys's ABC) ends
//!   with it.
//! - With `SPECGEN_JOBS=DIR` (a directory of slot files, the caller's own), each tool holds one
//!   of them locked (`flock`) from before it starts until the last process that inherited it
//!   ends: several specgen runs started at once (a test suite's threads) never run more tools
//!   than there are slots. The lock is taken in the child, so a waiting tool holds nothing.
//! - Tools run with `TMPDIR` inside specgen's own work directory (`specgen-<pid>-tools`), so
//!   what they leave there goes with it.
//! - Every temporary directory is made by [`temp_dir`] or [`temp_dir_in`], named
//!   `specgen-<pid>-…` (the system's) or `<prefix><pid>-…`, and registered until it is dropped
//!   or kept; [`remove_temporaries_on_signals`] (the command line calls it first thing) has
//!   SIGINT, SIGTERM and SIGHUP handled by a thread of their own that removes every registered
//!   directory and ends the process with 128 + the signal's number. SIGKILL cannot be caught:
//!   what it leaves is swept by the next run, by its dead process id ([`remove_orphans`]).

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
    remove_tools_tmp();
    std::process::exit(code)
}

/// A command whose process (and every process it starts) dies with specgen's, starts with no
/// signal blocked, runs with `TMPDIR` in specgen's work directory, and holds a job slot while it
/// runs when `SPECGEN_JOBS` names a slot directory.
pub fn command(program: impl AsRef<OsStr>) -> Command {
    use std::os::unix::process::CommandExt;
    let mut cmd = Command::new(program);
    let parent = std::process::id() as libc::pid_t;
    let group = warden();
    if let Some(tmp) = tools_tmp() {
        cmd.env("TMPDIR", tmp);
    }
    let slots = job_slots();
    // SAFETY: the closure runs in the child between fork and exec and calls only
    // async-signal-safe functions (prctl, getppid, setpgid, open, flock, nanosleep,
    // sigemptyset, pthread_sigmask) on memory prepared before the fork.
    unsafe {
        cmd.pre_exec(move || {
            #[cfg(target_os = "linux")]
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL as libc::c_ulong) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            // specgen ended before the line above: end too
            if libc::getppid() != parent {
                return Err(std::io::Error::other(
                    "specgen ended while this tool was starting",
                ));
            }
            // the warden's group: killed whole when specgen ends
            if group > 0 {
                libc::setpgid(0, group);
            }
            if let Some(slots) = &slots {
                take_slot(slots)?;
            }
            let mut none: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut none);
            libc::pthread_sigmask(libc::SIG_SETMASK, &none, std::ptr::null_mut());
            Ok(())
        });
    }
    cmd
}

/// The job slots (`SPECGEN_JOBS=DIR`: every regular file of DIR, the caller's own, is a slot),
/// as C strings made before any fork, with the wait's bound and messages; none without the
/// variable. A malformed one is refused ([`check_environment`]) before anything runs.
struct Slots {
    files: Vec<std::ffi::CString>,
    /// written to standard error once a tool has waited 10 s for a slot
    waiting: std::ffi::CString,
    /// written when no slot came free within `wait_s` seconds (the tool then does not start)
    gave_up: std::ffi::CString,
    wait_s: u64,
    /// specgen's own standard error, duplicated before any fork (close-on-exec: no tool keeps it)
    stderr: libc::c_int,
}

/// The job slots `SPECGEN_JOBS` names (none without it), or why it names none usable (the
/// variable set but not a directory of the caller's own, not written by others, with a slot
/// file in it; a malformed `SPECGEN_JOBS_WAIT`).
fn slots_of_environment() -> Result<Option<Slots>, crate::error::Error> {
    use crate::error::input;
    use std::os::unix::ffi::OsStrExt;
    use std::os::unix::fs::MetadataExt;
    let Some(dir) = std::env::var_os("SPECGEN_JOBS")
        .filter(|d| !d.is_empty())
        .map(PathBuf::from)
    else {
        return Ok(None);
    };
    let named = format!("SPECGEN_JOBS={}", dir.display());
    let me = unsafe { libc::geteuid() };
    let ok = |m: &std::fs::Metadata| m.uid() == me && m.mode() & 0o022 == 0;
    if !std::fs::symlink_metadata(&dir).is_ok_and(|m| m.is_dir() && ok(&m)) {
        return Err(input(format!(
            "{named} is not a directory of yours that only you can write; allowed: a directory of slot files (one per tool that may run at once), or unset"
        )));
    }
    let mut files: Vec<std::ffi::CString> = std::fs::read_dir(&dir)
        .map_err(|e| input(format!("{named}: cannot read it: {e}")))?
        .flatten()
        .filter(|e| std::fs::symlink_metadata(e.path()).is_ok_and(|m| m.is_file() && ok(&m)))
        .filter_map(|e| std::ffi::CString::new(e.path().as_os_str().as_bytes()).ok())
        .take(256)
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(input(format!(
            "{named} holds no slot file (a regular file of yours); allowed: a directory with one file per tool that may run at once, or unset"
        )));
    }
    let wait_s = match std::env::var("SPECGEN_JOBS_WAIT").ok().filter(|v| !v.is_empty()) {
        None => 3600,
        Some(v) => v
            .parse::<u64>()
            .ok()
            .filter(|s| (1..=604_800).contains(s))
            .ok_or_else(|| input(format!("SPECGEN_JOBS_WAIT={v} is not a wait; allowed whole seconds 1..=604800 (or unset: 3600)")))?,
    };
    let c = |s: String| std::ffi::CString::new(s).unwrap_or_default();
    Ok(Some(Slots {
        files,
        waiting: c(format!("specgen: waiting for a job slot of {named}: every slot is held (at most {wait_s} s, SPECGEN_JOBS_WAIT)\n")),
        gave_up: c(format!("specgen: no job slot of {named} came free within {wait_s} s (SPECGEN_JOBS_WAIT); the tool was not started\n")),
        wait_s,
        // SAFETY: duplicating a descriptor this process holds
        stderr: unsafe { libc::fcntl(2, libc::F_DUPFD_CLOEXEC, 3) },
    }))
}

/// The environment specgen reads, checked before anything runs: a malformed `SPECGEN_JOBS` or
/// `SPECGEN_JOBS_WAIT` is an input error naming it (never ignored).
pub fn check_environment() -> Result<(), crate::error::Error> {
    slots_of_environment().map(|_| ())
}

/// The job slots, made once before any fork; none without `SPECGEN_JOBS` (or a malformed one,
/// which [`check_environment`] has refused already).
fn job_slots() -> Option<std::sync::Arc<Slots>> {
    static SLOTS: std::sync::OnceLock<Option<std::sync::Arc<Slots>>> = std::sync::OnceLock::new();
    SLOTS
        .get_or_init(|| {
            slots_of_environment()
                .ok()
                .flatten()
                .map(std::sync::Arc::new)
        })
        .clone()
}

/// In a child before exec: locks one of the slots (waiting, 20 ms a round, until one is free)
/// on a descriptor the tool and its children inherit, so the slot is free again only when the
/// last of them ends. After 10 s of waiting it says so on standard error; past the bound it
/// says so and fails (the tool does not start: the caller reports its start failing).
/// Async-signal-safe.
fn take_slot(slots: &Slots) -> std::io::Result<()> {
    let mut rounds: u64 = 0;
    loop {
        for slot in &slots.files {
            // SAFETY: open/flock/close on a path prepared before the fork
            unsafe {
                let fd = libc::open(slot.as_ptr(), libc::O_RDONLY);
                if fd < 0 {
                    continue;
                }
                if libc::flock(fd, libc::LOCK_EX | libc::LOCK_NB) == 0 {
                    return Ok(());
                }
                libc::close(fd);
            }
        }
        rounds += 1;
        let say = |text: &std::ffi::CString| {
            // SAFETY: write(2) of a string prepared before the fork, to specgen's own standard
            // error (the tool's is a pipe specgen reads only once the tool runs)
            unsafe { libc::write(slots.stderr, text.as_ptr().cast(), text.as_bytes().len()) };
        };
        if rounds == 500 {
            say(&slots.waiting);
        }
        if rounds >= slots.wait_s * 50 {
            say(&slots.gave_up);
            return Err(std::io::Error::from_raw_os_error(libc::EBUSY));
        }
        let pause = libc::timespec {
            tv_sec: 0,
            tv_nsec: 20_000_000,
        };
        // SAFETY: a plain sleep
        unsafe { libc::nanosleep(&pause, std::ptr::null_mut()) };
    }
}

/// The warden's process group, once made (see [`warden`]).
static WARDEN_GROUP: std::sync::OnceLock<libc::pid_t> = std::sync::OnceLock::new();

/// The warden's process group (0: none could be made, and tools run in specgen's group, still
/// with `PR_SET_PDEATHSIG`). Forked once, before the first tool: it leads a group of its own,
/// closes every descriptor but a pipe's read end, and waits on it; when specgen ends however it
/// ends, the pipe's last writer is gone, the read returns, and the warden kills its group (every
/// tool and every process a tool started, itself last).
fn warden() -> libc::pid_t {
    *WARDEN_GROUP.get_or_init(|| {
        let mut fds = [0 as libc::c_int; 2];
        // SAFETY: a pipe whose write end only this process holds (close-on-exec: no tool
        // inherits it), then a fork whose child calls only async-signal-safe functions
        unsafe {
            if libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) != 0 {
                return 0;
            }
            let [read, write] = fds;
            match libc::fork() {
                -1 => {
                    libc::close(read);
                    libc::close(write);
                    0
                }
                0 => {
                    libc::setpgid(0, 0);
                    for fd in 0..4096 {
                        if fd != read {
                            libc::close(fd);
                        }
                    }
                    // signals a terminal or a parent sends the group are specgen's to handle
                    libc::signal(libc::SIGINT, libc::SIG_IGN);
                    libc::signal(libc::SIGHUP, libc::SIG_IGN);
                    let mut byte = 0u8;
                    while libc::read(read, (&mut byte as *mut u8).cast(), 1) != 0 {
                        if *libc::__errno_location() != libc::EINTR {
                            break;
                        }
                    }
                    libc::kill(0, libc::SIGKILL);
                    libc::_exit(0)
                }
                pid => {
                    libc::close(read);
                    // the write end stays open (and leaks) for the process's life
                    libc::setpgid(pid, pid);
                    pid
                }
            }
        }
    })
}

/// Specgen's own temporary directory for its tools (their `TMPDIR`), made on first use and
/// registered, so a signal removes it and the next run sweeps it after SIGKILL.
fn tools_tmp() -> Option<PathBuf> {
    TOOLS_TMP
        .get_or_init(|| {
            let base = std::env::temp_dir();
            remove_orphans(&base, "specgen-", true);
            let dir = tempfile::Builder::new()
                .prefix(&format!("specgen-{}-tools-", std::process::id()))
                .tempdir_in(&base)
                .ok()?;
            let path = dir.keep();
            mark(&path);
            TEMPORARIES
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(path.clone());
            Some(path)
        })
        .clone()
}

/// The tools' `TMPDIR`, once made.
static TOOLS_TMP: std::sync::OnceLock<Option<PathBuf>> = std::sync::OnceLock::new();

/// Removes specgen's own tool directory at a normal end (the command line's exit).
fn remove_tools_tmp() {
    if let Some(Some(dir)) = TOOLS_TMP.get() {
        let _ = std::fs::remove_dir_all(dir);
    }
}

/// A temporary directory removed when dropped, and on SIGINT/SIGTERM/SIGHUP.
#[derive(Debug)]
pub struct TempDir {
    inner: Option<tempfile::TempDir>,
}

impl TempDir {
    fn register(inner: tempfile::TempDir) -> TempDir {
        mark(inner.path());
        TEMPORARIES
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(inner.path().to_path_buf());
        TempDir { inner: Some(inner) }
    }

    pub fn path(&self) -> &Path {
        self.inner.as_ref().expect("alive").path()
    }

    /// Keeps the directory (it was renamed into place, or is the caller's now): no longer removed.
    pub fn keep(mut self) -> PathBuf {
        let inner = self.inner.take().expect("alive");
        unregister(inner.path());
        unmark(inner.path());
        inner.keep()
    }
}

/// Has a signal remove `path` (a file of ours, such as an output's lock) until [`unregister`].
pub(crate) fn register(path: &Path) {
    TEMPORARIES
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(path.to_path_buf());
}

pub(crate) fn unregister(path: &Path) {
    let mut all = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(i) = all.iter().position(|p| p == path) {
        all.swap_remove(i);
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if let Some(inner) = self.inner.take() {
            unregister(inner.path());
            unmark(inner.path());
            drop(inner);
        }
    }
}

/// A temporary directory `specgen-<pid>-…` in the system's temporary directory (what killed
/// runs left there is swept first).
pub fn temp_dir() -> std::io::Result<TempDir> {
    let base = std::env::temp_dir();
    remove_orphans(&base, "specgen-", true);
    Ok(TempDir::register(
        tempfile::Builder::new()
            .prefix(&format!("specgen-{}-", std::process::id()))
            .tempdir_in(base)?,
    ))
}

/// A temporary directory `<prefix>…` in `parent`.
pub fn temp_dir_in(parent: &Path, prefix: &str) -> std::io::Result<TempDir> {
    Ok(TempDir::register(
        tempfile::Builder::new().prefix(prefix).tempdir_in(parent)?,
    ))
}

/// Whether process `pid` is gone (signal 0 finds no such process).
pub(crate) fn process_gone(pid: i32) -> bool {
    // SAFETY: signal 0 only asks whether the process exists
    pid > 0
        && unsafe { libc::kill(pid, 0) } != 0
        && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH)
}

/// The file a temporary directory of specgen's holds from its first moment: what the sweep of
/// a killed run's leftovers asks before it removes a directory, so that a user's own
/// `specgen-2026-11-28/` (a name like ours) is never taken for one.
pub(crate) const MARKER: &str = ".specgen-temporary";

/// The marker's text for process `pid`.
fn marker_text(pid: u32) -> String {
    format!("a temporary directory of specgen process {pid}, removed when it ends\n")
}

/// Writes the marker into a directory just made.
///
/// The run holds an exclusive `flock` on the marker for its life (the kernel drops it when the
/// process ends, however it ends): the sweep of leftovers removes a directory only when it can
/// take that lock itself. A process id alone is no proof of death: from another PID namespace
/// (a container sharing `/tmp`, cluster nodes sharing a `TMPDIR`) a live run's pid looks gone.
fn mark(dir: &Path) {
    let path = dir.join(MARKER);
    let Ok(mut f) = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&path)
    else {
        return;
    };
    use std::io::Write;
    let _ = f.write_all(marker_text(std::process::id()).as_bytes());
    use std::os::fd::AsRawFd;
    // SAFETY: flock on a descriptor we own
    if unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0 {
        MARKER_LOCKS
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((dir.to_path_buf(), f));
    }
}

/// The markers' open files, each holding its directory's lock while the run lives.
static MARKER_LOCKS: std::sync::Mutex<Vec<(PathBuf, std::fs::File)>> =
    std::sync::Mutex::new(Vec::new());

/// Lets go of a directory's marker lock (the directory is removed or kept by its owner).
fn unmark(dir: &Path) {
    MARKER_LOCKS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|(d, _)| d != dir);
}

/// Whether a run holds `marker`'s lock: true where it cannot be taken now (or not opened).
fn marker_held(marker: &Path) -> bool {
    use std::os::fd::AsRawFd;
    let Ok(f) = std::fs::File::open(marker) else {
        return true;
    };
    // SAFETY: flock on a descriptor we own; released when `f` closes
    unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) != 0 }
}

/// Whether `rest` (a name after `<prefix><pid>-`) is what specgen's own names put there: the
/// random part of `tempfile` (six letters or digits), perhaps after `tools-`.
fn random_part(rest: &str) -> bool {
    let r = rest.strip_prefix("tools-").unwrap_or(rest);
    r.len() == 6 && r.bytes().all(|b| b.is_ascii_alphanumeric())
}

/// Removes what a killed run left in `dir`: the entries named exactly as specgen names them
/// (`<prefix><pid>-<random>`) whose process no longer runs and that are the caller's own —
/// directories (`dirs`: work and build directories) only when they hold specgen's marker naming
/// that process, files (a single-file output's temporary) by their name. Nothing else is
/// touched, however like ours its name is.
pub(crate) fn remove_orphans(dir: &Path, prefix: &str, dirs: bool) {
    use std::os::unix::fs::MetadataExt;
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    // SAFETY: a plain query
    let me = unsafe { libc::geteuid() };
    for entry in entries.flatten().take(100_000) {
        let name = entry.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(prefix)) else {
            continue;
        };
        let Some((pid, random)) = rest.split_once('-') else {
            continue;
        };
        let Some(pid) = pid
            .parse::<i32>()
            .ok()
            .filter(|p| *p > 0 && pid.bytes().all(|b| b.is_ascii_digit()))
        else {
            continue;
        };
        if !random_part(random) {
            continue;
        }
        let Ok(meta) = std::fs::symlink_metadata(entry.path()) else {
            continue;
        };
        if meta.uid() != me || !process_gone(pid) {
            continue;
        }
        if dirs && meta.is_dir() {
            // ours only if it says so, naming that process (a bounded read of a regular file)
            let marker = entry.path().join(MARKER);
            let says = std::fs::symlink_metadata(&marker)
                .is_ok_and(|m| m.is_file() && m.len() < 256)
                && std::fs::read_to_string(&marker).is_ok_and(|t| t == marker_text(pid as u32));
            // and no run holds its lock, whatever its pid looks like from here
            if !says || marker_held(&marker) {
                continue;
            }
        }
        if dirs && meta.is_dir() {
            let _ = std::fs::remove_dir_all(entry.path());
        } else if !dirs && meta.is_file() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Has SIGINT, SIGTERM and SIGHUP remove every registered temporary directory and end the
/// process (status 128 + the signal); SIGTSTP (Ctrl-Z) stops the tools' group with specgen,
/// the warden still watching, and continues them when specgen is. Call it before any other thread starts: the signals are
/// blocked in the calling thread, whose mask every later thread inherits, and waited for by a
/// thread of their own. Children get the default mask back ([`command`]).
pub fn remove_temporaries_on_signals() {
    // SAFETY: plain libc calls on a signal set we own
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for s in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP, libc::SIGTSTP] {
            libc::sigaddset(&mut set, s);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        let waiter = std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || loop {
                let mut sig: libc::c_int = 0;
                if libc::sigwait(&set, &mut sig) != 0 {
                    return;
                }
                if sig == libc::SIGTSTP {
                    // Ctrl-Z: the tools (in the warden's group, not the terminal's) stop with
                    // specgen, and go on when it does; the warden itself keeps watching
                    let group = WARDEN_GROUP.get().copied().unwrap_or(0);
                    if group > 0 {
                        libc::kill(-group, libc::SIGSTOP);
                        libc::kill(group, libc::SIGCONT);
                    }
                    libc::raise(libc::SIGSTOP);
                    // continued (fg, bg, SIGCONT): the tools too
                    if group > 0 {
                        libc::kill(-group, libc::SIGCONT);
                    }
                    continue;
                }
                {
                    SIGNALLED.store(sig, std::sync::atomic::Ordering::SeqCst);
                    let all = TEMPORARIES
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .clone();
                    for path in all {
                        match std::fs::symlink_metadata(&path) {
                            Ok(m) if m.is_dir() => {
                                let _ = std::fs::remove_dir_all(&path);
                            }
                            Ok(_) => {
                                let _ = std::fs::remove_file(&path);
                            }
                            Err(_) => {}
                        }
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
