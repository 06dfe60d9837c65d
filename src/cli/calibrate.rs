//! `specgen stale` and `specgen calibrate`: which measured rows are of today's RTL, and the delay
//! model's fit to the calibration.

use super::{outln, usage, Failure};
use specgen::config::Target;
use specgen::explore;
use specgen::explore::Exploration;
use std::path::PathBuf;

#[derive(clap::Args, Debug, Clone)]
pub struct StaleArgs {
    /// An exploration to check (`specgen explore`'s points.json); repeat it [default: every
    /// family's built-in exploration, the data `generate --max-error` chooses from]
    #[arg(long, value_name = "FILE")]
    pub explored: Vec<PathBuf>,
    /// Also write the checked explorations' measured rows as delay-model calibration rows
    /// (data/delay_calibration.csv's columns, each with the RTL digest it was measured on where
    /// that is today's) to FILE, for `specgen calibrate --merge FILE`
    #[arg(long, value_name = "FILE")]
    pub write_calibration: Option<PathBuf>,
}

/// `specgen stale`: the measured rows that are not of today's RTL, per exploration; exit 1
/// when any is.
pub fn stale(a: &StaleArgs) -> Result<(), Failure> {
    let mut sets: Vec<(String, String)> = Vec::new();
    if a.explored.is_empty() {
        for t in Target::ALL {
            if let Some(text) = specgen::family::of(t).explored() {
                sets.push((
                    format!(
                        "the built-in exploration of the {}",
                        specgen::timing::part(t)
                    ),
                    text.to_string(),
                ));
            }
        }
    }
    for p in &a.explored {
        sets.push((
            p.display().to_string(),
            specgen::small_file::read(p, 64 << 20)
                .map_err(|e| usage(format!("invalid --explored: {} {e}", p.display())))?,
        ));
    }
    let mut stale = 0;
    let mut rows = String::new();
    // what is said, said after the rows are written (a reader that stops reading early loses
    // none of them)
    let mut said: Vec<String> = Vec::new();
    for (what, text) in &sets {
        let e = Exploration::from_text(text, what)?;
        let csv = explore::calibration_csv(&e);
        let body = if rows.is_empty() {
            csv.as_str()
        } else {
            csv.split_once('\n').map_or("", |(_, b)| b)
        };
        rows.push_str(body);
        let ev = explore::evidence(&e)?;
        said.push(format!(
            "{what}: {} measured rows, {} of today's RTL, {} of an older RTL",
            ev.today.len() + ev.stale.len(),
            ev.today.len(),
            ev.stale.len()
        ));
        said.extend(ev.stale.iter().map(|id| format!("  stale: {id}")));
        stale += ev.stale.len();
    }
    // the delay model's calibration units: a floor only where its row names today's RTL
    for t in Target::ALL {
        let ev = explore::calibration_evidence(t)?;
        if ev.today + ev.stale.len() + ev.fit_only > 0 {
            said.push(format!(
                "the delay model's calibration on the {}: {} floors of today's RTL, {} of an older RTL; {} rows that name no RTL (the fit's data, never a floor)",
                specgen::timing::part(t),
                ev.today,
                ev.stale.len(),
                ev.fit_only
            ));
            said.extend(ev.stale.iter().map(|s| format!("  stale floor: {s}")));
            stale += ev.stale.len();
        }
    }
    if let Some(path) = &a.write_calibration {
        specgen::output::write_file(path, rows.as_bytes())
            .map_err(|e| super::failed(format!("cannot write {}: {e}", path.display())))?;
    }
    for line in &said {
        outln!("{line}")?;
    }
    match stale {
        0 => Ok(()),
        n => Err(super::failed(format!("{n} measured rows are of an older RTL: measure them again (specgen explore --run, scripts/bench_explore.sh)"))),
    }
}

#[derive(clap::Args, Debug, Clone)]
pub struct CalibrateArgs {
    /// The calibration rows (CSV: family, model, stages, …, fmax_mhz, fmax_seeds, args,
    /// rtl_sha256)
    #[arg(long, value_name = "FILE")]
    pub calibration: PathBuf,
    /// Where the fitted model goes (JSON), written atomically; never the --calibration file
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// New calibration rows (an exploration's calibration.csv, or `specgen stale
    /// --write-calibration`'s): each replaces the row of the same unit (family, datapath, depth,
    /// flags); the merged rows are fitted and written to --rows-out; repeat it
    #[arg(long, value_name = "FILE", requires = "rows_out")]
    pub merge: Vec<PathBuf>,
    /// With --merge: a row of --calibration stays, a new row only adds a unit it lacks
    #[arg(long, requires = "merge")]
    pub keep: bool,
    /// With --merge: where the merged rows go (CSV, sorted), written atomically; never a file
    /// this command reads (move it over the calibration file after)
    #[arg(long, value_name = "FILE", requires = "merge")]
    pub rows_out: Option<PathBuf>,
}

/// `specgen calibrate`: the delay model fitted to a calibration CSV, each line's fit printed.
pub fn calibrate(a: &CalibrateArgs) -> Result<(), Failure> {
    let inputs: Vec<&PathBuf> = std::iter::once(&a.calibration).chain(&a.merge).collect();
    for (flag, out) in [("--out", Some(&a.out)), ("--rows-out", a.rows_out.as_ref())] {
        if let Some(input) =
            out.and_then(|o| inputs.iter().find(|i| specgen::output::same_file(i, o)))
        {
            return Err(usage(format!(
                "invalid {flag}: {} is a file this command reads",
                input.display()
            )));
        }
    }
    let mut text = specgen::small_file::read(&a.calibration, 64 << 20).map_err(|e| {
        usage(format!(
            "invalid --calibration: {} {e}",
            a.calibration.display()
        ))
    })?;
    // said after every file is written (a reader that stops reading early loses none)
    let mut merged_said = None;
    if let Some(rows_out) = &a.rows_out {
        let mut new = Vec::new();
        for p in &a.merge {
            new.push(
                specgen::small_file::read(p, 64 << 20)
                    .map_err(|e| usage(format!("invalid --merge: {} {e}", p.display())))?,
            );
        }
        let (merged, added) = specgen::timing::fit::merge_calibration(
            &text,
            &new.iter().map(String::as_str).collect::<Vec<_>>(),
            a.keep,
        )?;
        specgen::output::write_file(rows_out, merged.as_bytes())
            .map_err(|e| super::failed(format!("cannot write {}: {e}", rows_out.display())))?;
        merged_said = Some(format!(
            "{}: {added} unit(s) added, {} in all",
            rows_out.display(),
            merged.lines().count() - 1
        ));
        text = merged;
    }
    let model = specgen::timing::fit::fit_calibration(&text, &a.calibration.display().to_string())?;
    let mut json = serde_json::to_string_pretty(&model).expect("JSON");
    json.push('\n');
    specgen::output::write_file(&a.out, json.as_bytes())
        .map_err(|e| super::failed(format!("cannot write {}: {e}", a.out.display())))?;
    if let Some(line) = merged_said {
        outln!("{line}")?;
    }
    for (family, caps) in model["handshake"].as_object().into_iter().flatten() {
        for (name, c) in caps.as_object().into_iter().flatten() {
            outln!(
                "{family} {name} with the output buffer: at most {} MHz ({})",
                c["mhz"],
                c["unit"].as_str().unwrap_or("")
            )?;
        }
    }
    for (family, lines) in model
        .as_object()
        .into_iter()
        .flatten()
        .filter(|(k, _)| !["source", "handshake"].contains(&k.as_str()))
    {
        for (name, m) in lines.as_object().into_iter().flatten() {
            match m.as_object() {
                None => outln!("{family} {name}: the family's line")?,
                Some(m) => outln!(
                    "{family} {name}: period = {} + {}*e + {}*m ns (R² {}), cap {} MHz, margin {} (measured/predicted {}..{}) over {} units",
                    m["offset_ns"],
                    m["ns_per_unit"],
                    m["ns_per_mean_unit"],
                    m["r2"],
                    m["cap_mhz"],
                    m["margin"],
                    m["worst_under"],
                    m["worst_over"],
                    m["points"]
                )?,
            }
        }
    }
    Ok(())
}
