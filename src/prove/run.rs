//! Running the tools: a watched run with a time limit and its progress lines, the verdicts of
//! `sat` and the bounded searches, the traces.

use super::*;

/// What a tool said: its standard output, and whether it ended by itself (false: stopped at
/// the time limit, `text` is what it said until then).
pub(super) struct Said {
    pub(super) text: String,
    pub(super) ended: bool,
}

/// Runs `program` with `args` in `dir`, stopped after `limit`; each line of its standard output
/// goes to `progress` as it comes when it is a line of progress (`is_progress`).
pub(super) fn run_watched(
    program: &str,
    args: &[String],
    dir: &Path,
    limit: Duration,
    progress: Option<fn(&str)>,
    is_progress: fn(&str) -> Option<String>,
) -> Result<Said, Error> {
    use std::io::{BufRead, Read};
    let mut child = crate::process::command(program)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| error::tool(program, format!("cannot run {program}: {e}")))?;
    let (alive, fired) = crate::cosim::backend::watchdog(child.id(), limit);
    let mut stderr = child.stderr.take().expect("piped");
    let errors = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = (&mut stderr).take(1 << 20).read_to_end(&mut text);
        let _ = std::io::copy(&mut stderr, &mut std::io::sink());
        text
    });
    let mut text = String::new();
    let mut out = std::io::BufReader::new(child.stdout.take().expect("piped"));
    let mut line = Vec::new();
    // a tool's output is read whole (sat's log is a few lines an edge), bounded at 256 MiB
    while (&mut out)
        .take(1 << 20)
        .read_until(b'\n', &mut line)
        .map_err(|e| error::tool(program, e.to_string()))?
        > 0
    {
        let l = String::from_utf8_lossy(&line);
        if let (Some(report), Some(said)) = (progress, is_progress(&l)) {
            report(&said);
        }
        if text.len() < 256 << 20 {
            text.push_str(&l);
        }
        line.clear();
    }
    let status = child
        .wait()
        .map_err(|e| error::tool(program, e.to_string()))?;
    drop(alive);
    let stderr = String::from_utf8_lossy(&errors.join().unwrap_or_default()).into_owned();
    if fired.load(std::sync::atomic::Ordering::SeqCst) {
        return Ok(Said { text, ended: false });
    }
    if !status.success() {
        return Err(error::tool(
            program,
            format!("{program} failed ({status}): {stderr}{}", tail(&text)),
        ));
    }
    Ok(Said { text, ended: true })
}

/// Runs `program` with `args` in `dir`, stopped after `limit`; `Ok(None)` when stopped.
pub(super) fn run(
    program: &str,
    args: &[String],
    dir: &Path,
    limit: Duration,
) -> Result<Option<String>, Error> {
    let said = run_watched(program, args, dir, limit, None, |_| None)?;
    Ok(said.ended.then_some(said.text))
}

/// A line of yosys `sat`'s log that tells the depth reached, in words.
pub(super) fn sat_progress(line: &str) -> Option<String> {
    let k = |prefix: &str| {
        line.trim()
            .strip_prefix(prefix)
            .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
            .and_then(|d| d.parse::<u32>().ok())
    };
    if let Some(k) = k("Base case for induction length ") {
        return Some(format!(
            "no failure within {k} edges from power-up (the base case)"
        ));
    }
    if line.contains("Induction step failed") {
        return Some("the induction step does not close yet: one edge deeper".into());
    }
    k("Setting up time step ")
        .filter(|k| k % 8 == 0)
        .map(|k| format!("bounded search: time step {k} set up"))
}

/// Rewrites ABC's counterexample (`cex.aiw`: a line of latch values, then one line of input
/// values a frame) as the AIGER witness yosys's `sim -r` reads (`witness.aiw`): the header, the
/// latches' first values (all zero: the model was written with `-zinit`, a free first value is
/// an input of the first frame), and each frame's inputs at the model's input count.
pub(super) fn yosys_witness(w: &Path) -> Result<(), Error> {
    let read = |f: &str, max: u64| {
        crate::small_file::read(&w.join(f), max)
            .map_err(|e| error::tool("abc", format!("{f}: {e}")))
    };
    let cex = read("cex.aiw", 256 << 20)?;
    let model = crate::small_file::read_bytes(&w.join("model.aig"), 1 << 30)
        .map_err(|e| error::tool("yosys", format!("model.aig: {e}")))?;
    let header =
        String::from_utf8_lossy(&model[..model.iter().position(|&b| b == b'\n').unwrap_or(0)])
            .into_owned();
    let count = |i: usize| {
        header
            .split_whitespace()
            .nth(i)
            .and_then(|n| n.parse::<usize>().ok())
    };
    let (Some(inputs), Some(latches)) = (count(2), count(3)) else {
        return Err(error::tool(
            "yosys",
            format!("model.aig has no AIGER header: {header:?}"),
        ));
    };
    let mut out = format!("1\nb0\n{}\n", "0".repeat(latches));
    for frame in cex
        .split_whitespace()
        .skip(1)
        .filter(|l| l.chars().all(|c| c == '0' || c == '1'))
    {
        let bits: String = frame.chars().take(inputs).collect();
        out.push_str(&format!("{bits:0<inputs$}\n"));
    }
    out.push_str(".\n");
    put(w, "witness.aiw", out)
}

/// The frame in which ABC says a property fails ("Output 0 of miter "model" was asserted in
/// frame 3."), if it does.
pub(super) fn frame_asserted(text: &str) -> Option<u32> {
    text.split("was asserted in frame ")
        .nth(1)
        .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|d| d.parse::<u32>().ok())
}

/// A line of ABC `bmc3 -v`'s log, in words: the frames searched so far ("   5 + : Var = …").
pub(super) fn bmc_progress(line: &str) -> Option<String> {
    let frame: u32 = line.trim_start().split(' ').next()?.parse().ok()?;
    line.contains(" + :")
        .then(|| format!("bounded search: no failure within {} edges", frame + 1))
}

/// The frames ABC's bmc3 finished, from its log.
pub(super) fn bmc_reached(text: &str) -> Option<u32> {
    text.lines()
        .filter_map(|l| {
            l.trim_start()
                .split(' ')
                .next()?
                .parse::<u32>()
                .ok()
                .filter(|_| l.contains(" + :"))
        })
        .max()
        .map(|f| f + 1)
}

/// The depths yosys `sat`'s k-induction completed, from its log: base cases proven.
pub(super) fn sat_reached(text: &str) -> Option<u32> {
    text.lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix("Base case for induction length ")
                .and_then(|t| t.split(|c: char| !c.is_ascii_digit()).next())
                .and_then(|d| d.parse().ok())
        })
        .max()
}

/// Whether `e` is yosys saying it has no `sim` command (YoWASP's build leaves it out).
pub(super) fn without_sim(e: &Error) -> bool {
    let text = e.to_string();
    text.contains("No such command") && text.contains("sim")
}

/// The last lines of a tool's output, for a message.
pub(super) fn tail(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(20)..].join("\n")
}

/// A bounded search with yosys's `sat` over the first `steps` edges: `Some(true)` when every
/// property holds there, `Some(false)` when one fails (its trace in `trace.vcd`), `None` when
/// the search did not end within the limit.
pub(super) fn bounded(
    tools: &Tools,
    w: &Path,
    files: &[String],
    name: &str,
    steps: u32,
) -> Result<Option<bool>, Error> {
    Script {
        bounded: Some(steps),
        ..Script::model(name, files)
    }
    .write(w, "bounded.ys")?;
    run_sat(&tools.yosys, w, "bounded.ys", tools.limit)
}

/// Runs yosys's `sat` script `file` in `w` (a bounded search or a replay): `Some(true)` when
/// every property holds, `Some(false)` when one fails (its trace in `trace.vcd`), `None` when
/// it did not end within `limit`.
pub(super) fn run_sat(
    yosys: &str,
    w: &Path,
    file: &str,
    limit: Duration,
) -> Result<Option<bool>, Error> {
    let _ = std::fs::remove_file(w.join("trace.vcd"));
    // sat ends successfully whether or not it finds a failure: its verdict is its log's
    // ("SAT proof finished - model found: FAIL!") and the trace it writes only then; an error
    // exit is the tool's failure, never a verdict
    let text = match run(yosys, &["-s".into(), file.into()], w, limit)? {
        None => return Ok(None),
        Some(text) => text,
    };
    let failed = text.contains("model found: FAIL");
    let proved = text.contains("no model found: SUCCESS");
    match (failed, proved, w.join("trace.vcd").is_file()) {
        (true, false, true) => Ok(Some(false)),
        (false, true, false) => Ok(Some(true)),
        _ => Err(error::tool(
            yosys,
            format!(
                "yosys's sat gave no verdict (or a failure without its trace): {}",
                tail(&text)
            ),
        )),
    }
}

/// The counterexample's VCD that yosys's `sat` wrote in the work directory.
pub(super) fn trace(yosys: &str, w: &Path, design: &Design) -> Result<Vec<u8>, Error> {
    let vcd = w.join("trace.vcd");
    if !vcd.is_file() {
        return Err(error::tool(
            yosys,
            format!(
                "yosys's sat wrote no trace of the counterexample for {}",
                design.dir.display()
            ),
        ));
    }
    crate::small_file::read_bytes(&vcd, 1 << 30)
        .map_err(|e| error::tool(yosys, format!("the counterexample's trace: {e}")))
}

/// Writes `bytes` as `name` in the work directory `w`.
pub(super) fn put(w: &Path, name: &str, bytes: impl AsRef<[u8]>) -> Result<(), Error> {
    std::fs::write(w.join(name), bytes).map_err(|e| Error::io("write", w.join(name), e))
}

/// A `valid` unit's cover ([`VALID_COVER`]): after the reset, a result, within latency + 3
/// edges, searched by yosys's `sat` as the failure of its negation. None: reached; else the
/// proof that ends here (vacuous, or undecided within the time limit).
pub(super) fn valid_cover(
    design: &Design,
    tools: &Tools,
    w: &Path,
    files: &[String],
    unit_defines: &[String],
    name: &str,
    t0: Instant,
) -> Result<Option<Proof>, Error> {
    let reach = design.cfg.latency() + 3;
    Script {
        bounded: Some(reach),
        defines: vec!["SPECGEN_VALID_COVER".into()],
        ignore_unknown: !design.sim_models.is_empty(),
        unit_defines: unit_defines.to_vec(),
        ..Script::model(name, files)
    }
    .write(w, "cover.ys")?;
    let verdict = match run_sat(&tools.yosys, w, "cover.ys", tools.limit)? {
        // its negation fails: reached
        Some(false) => return Ok(None),
        Some(true) => Verdict::Unreached {
            covers: vec![VALID_COVER],
            depth: reach,
        },
        None => Verdict::Undecided {
            bounded: None,
            out_of_time: true,
            reached: None,
        },
    };
    let engine = format!("the cover ({VALID_COVER}) searched with yosys sat over {reach} edges");
    Ok(Some(Proof {
        name: name.to_string(),
        properties: properties(design),
        verdict,
        seconds: t0.elapsed().as_secs_f64(),
        engine,
        ports: None,
    }))
}
