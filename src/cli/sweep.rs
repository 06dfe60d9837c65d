//! `explore --run`: the plan's jobs run, then merged, in one command. Each job is one
//! `specgen measure` (its result written whole under its fingerprint, a lock held for its
//! life), so a run killed midway and started again runs only what has no result, and never a
//! job beside itself. The jobs run on Snakemake where a profile is given (a cluster) or
//! `--engine snakemake` asks for it, else on this binary's own slots, `--run-jobs` at a time.

use super::{failed, usage, Failure};
use specgen::explore;
use std::path::{Path, PathBuf};

/// The Snakefile of a sweep, shipped in the binary (written beside the results it runs in).
const SNAKEFILE: &str = include_str!("../../scripts/sweep/Snakefile");

/// Which engine runs the jobs.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// Snakemake with a profile (--profile), else specgen's own slots
    Auto,
    /// specgen's own slots: `--run-jobs` jobs at a time on this machine
    Specgen,
    /// Snakemake (on PATH), with --profile if given, else --cores of --run-jobs
    Snakemake,
}

/// How `explore --run` runs the jobs.
pub struct RunOptions<'a> {
    pub engine: Engine,
    pub jobs_at_once: usize,
    pub profile: Option<&'a Path>,
    pub yosys: &'a str,
    pub nextpnr: Option<&'a str>,
}

/// Runs every job of `jobs` that has no result in `store` (each its own `specgen measure`):
/// Ok with the fingerprints that failed (named; the merge then lists them as missing).
pub fn run_jobs(
    jobs: &[explore::Job],
    store: &Path,
    o: &RunOptions,
) -> Result<Vec<String>, Failure> {
    std::fs::create_dir_all(store).map_err(|e| Failure::io("create", store, e))?;
    // one sweep at a time on a store: this lock is held for the run's life
    let lock_path = store.join(".specgen-sweep.lock");
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&lock_path)
        .map_err(|e| Failure::io("open", &lock_path, e))?;
    // (an flock, released when `lock` closes)
    if lock.try_lock().is_err() {
        return Err(failed(format!(
            "a sweep is running on {} (it holds {}); wait for it or stop it",
            store.display(),
            lock_path.display()
        )));
    }
    // the plan's jobs, as data the jobs read (named by their content: two plans never share one)
    let text = serde_json::to_string(jobs).expect("jobs serialise");
    let digest = specgen::bits::sha256_hex(text.as_bytes(), 8);
    // (in a directory of its own: every `*.json` of the store is read as a result)
    let own = store.join(".specgen");
    std::fs::create_dir_all(&own).map_err(|e| Failure::io("create", &own, e))?;
    let plan = own.join(format!("jobs-{digest}.json"));
    specgen::output::write_file(&plan, text.as_bytes())
        .map_err(|e| Failure::io("write", &plan, e))?;
    let me = std::env::current_exe().map_err(|e| {
        failed(format!(
            "cannot find specgen's own binary to run the jobs: {e}"
        ))
    })?;
    let snakemake = match o.engine {
        Engine::Specgen => false,
        Engine::Snakemake => true,
        Engine::Auto => o.profile.is_some(),
    };
    if snakemake {
        return run_snakemake(&plan, &me, store, o).map(|()| Vec::new());
    }
    let missing: Vec<&explore::Job> = jobs
        .iter()
        .filter(|j| !explore::whole_result(&store.join(format!("{}.json", j.fingerprint)), j))
        .collect();
    eprintln!(
        "explore --run: {} jobs, {} with a result already, {} to run, {} at a time",
        jobs.len(),
        jobs.len() - missing.len(),
        missing.len(),
        o.jobs_at_once
    );
    let mut failed_jobs = Vec::new();
    let mut running: Vec<(String, std::process::Child)> = Vec::new();
    let mut next = missing.iter();
    let (mut done, total) = (0usize, missing.len());
    loop {
        while running.len() < o.jobs_at_once.max(1) {
            let Some(job) = next.next() else { break };
            let mut cmd = std::process::Command::new(&me);
            cmd.arg("measure")
                .arg("--jobs")
                .arg(&plan)
                .arg("--fingerprint")
                .arg(&job.fingerprint);
            cmd.arg("--out")
                .arg(store.join(format!("{}.json", job.fingerprint)))
                .arg("--cache")
                .arg(store.join(".yosys-cache"));
            cmd.arg("--yosys").arg(o.yosys);
            if let Some(n) = o.nextpnr {
                cmd.arg("--nextpnr").arg(n);
            }
            cmd.stdout(std::process::Stdio::null());
            let child = cmd
                .spawn()
                .map_err(|e| failed(format!("cannot run {} measure: {e}", me.display())))?;
            running.push((job.fingerprint.clone(), child));
        }
        if running.is_empty() {
            break;
        }
        // the first that ends (polled: any order)
        let mut ended = None;
        while ended.is_none() {
            for (i, (_, c)) in running.iter_mut().enumerate() {
                if let Some(status) = c
                    .try_wait()
                    .map_err(|e| failed(format!("waiting for a job: {e}")))?
                {
                    ended = Some((i, status));
                    break;
                }
            }
            if ended.is_none() {
                std::thread::sleep(std::time::Duration::from_millis(200));
            }
        }
        let (i, status) = ended.expect("one ended");
        let (fp, _) = running.swap_remove(i);
        done += 1;
        if status.success() {
            eprintln!("explore --run: {done} of {total}: {fp} measured");
        } else {
            eprintln!("explore --run: {done} of {total}: {fp} failed ({status}); it stays without a result");
            failed_jobs.push(fp);
        }
    }
    drop(lock);
    Ok(failed_jobs)
}

/// The jobs on Snakemake: the shipped Snakefile written beside the results, the paths passed
/// in the environment (data, never parsed), a profile where given.
fn run_snakemake(plan: &Path, me: &Path, store: &Path, o: &RunOptions) -> Result<(), Failure> {
    let snakefile = store.join(".specgen").join("Snakefile");
    specgen::output::write_file(&snakefile, SNAKEFILE.as_bytes())
        .map_err(|e| Failure::io("write", &snakefile, e))?;
    // this run holds the store's sweep lock: a Snakemake lock there is a killed sweep's, lifted
    // (a job of it still running holds its own job's lock, so none starts beside itself)
    if store.join(".snakemake").join("locks").is_dir() {
        let _ = std::process::Command::new("snakemake")
            .arg("-s")
            .arg(&snakefile)
            .arg("--directory")
            .arg(store)
            .arg("--unlock")
            .env("SPECGEN_SWEEP_JOBS", plan)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status();
    }
    let mut cmd = std::process::Command::new("snakemake");
    cmd.arg("-s").arg(&snakefile).arg("--directory").arg(store);
    cmd.args([
        "--ignore-incomplete",
        "--rerun-triggers",
        "mtime",
        "--keep-going",
    ]);
    match o.profile {
        Some(p) => {
            cmd.arg("--profile").arg(p);
        }
        None => {
            cmd.arg("--cores").arg(o.jobs_at_once.max(1).to_string());
        }
    }
    cmd.env("SPECGEN_SWEEP_JOBS", plan)
        .env("SPECGEN_SWEEP_SPECGEN", me)
        .env("SPECGEN_SWEEP_YOSYS", o.yosys);
    if let Some(n) = o.nextpnr {
        cmd.env("SPECGEN_SWEEP_NEXTPNR", n);
    }
    let status =
        cmd.status().map_err(|e| usage(format!("invalid --engine snakemake: cannot run snakemake ({e}): pip install snakemake, or --engine specgen")))?;
    if !status.success() {
        eprintln!("explore --run: snakemake ended with {status}; the jobs without a result are listed by the merge");
    }
    Ok(())
}

/// The store `explore --run` writes to: the first `--results`.
pub fn store(results: &[PathBuf]) -> Result<&Path, Failure> {
    results
        .first()
        .map(PathBuf::as_path)
        .ok_or_else(|| usage("invalid --run: give --results DIR, where the jobs' results are kept (a run killed midway resumes from it)"))
}
