//! The delay model's fit: `data/delay_model.json` from `data/delay_calibration.csv`, in the
//! binary (`specgen calibrate`), the features of each row planned here (no unit generated).
//!
//! Per family, a unit's clock period is the plane `offset + a·e + b·m` in its slowest stretch of
//! logic `e` and its mean stretch `m` on the family's primitive delays (`super::stretches`,
//! rounded to hundredths), fitted by least squares to `1000 / fmax` with
//! non-negative slopes (else the line in one of them, or a constant: the best of those) and a
//! non-negative intercept (a negative one is held at 0, the slopes fitted again); `r2` is the
//! share of the periods' spread the line explains. `cap`
//! is the family's highest median; `cap_up_to` the longest `e` that reached it with no slower
//! unit as short. `margin` is the worst measured / predicted over the rows the line speaks for
//! (at most 1): what the model assures is its prediction times the margin. A line per family
//! ("all") and per model of three rows or more, which also keeps its rows (features, median,
//! widths, depth, digest): the floors `Line::of_todays_rtl` reads. A `ready`/`axis` row
//! (`--interface` in its flags) is no line's data: per family and datapath, the most such a unit
//! of each interface was measured at on today's RTL, the lesser interface's, is `handshake`: the
//! ceiling of a unit with the output buffer.
//!
//! A row's clock is its median over three seeds or more, else its slowest seed ([`row_figure`]):
//! every floor, cap, margin and line here is of what the rows assure, not of a mean of two.

use crate::config::{Params, Target};
use crate::error::Error;
use crate::plan::Plan;
use serde_json::{json, Map, Value};

/// At most this many calibration rows are read.
pub const MAX_ROWS: usize = 100_000;

/// One measured row, with its features.
struct Row {
    model: String,
    stages: u32,
    est: f64,
    mean: f64,
    fmax: f64,
    args: String,
    digest: String,
}

/// The clock a row stands for: its median where it was measured over [`MIN_SEEDS`] nextpnr
/// seeds or more, else its slowest seed. Two seeds' median is their mean, which a third seed can
/// move below a target the row was read to reach (the wide lean on the ECP5 at 13 stages: 151.3
/// over seeds 1-2, 148.8 over seeds 1-3); a single seed is its own slowest.
pub fn row_figure(median: f64, seeds: &[f64]) -> f64 {
    if seeds.len() >= MIN_SEEDS {
        median
    } else {
        seeds.iter().copied().fold(median, f64::min)
    }
}

/// The seeds a row's median stands for: with fewer, [`row_figure`] reads its slowest seed.
pub const MIN_SEEDS: usize = 3;

fn bad(message: String) -> Error {
    Error::Config {
        parameter: "calibration",
        message,
    }
}

/// The parameters of a calibration row's unit: its datapath by name (`config::datapaths`), its
/// family and depth, its `args` (the widths) applied.
fn row_params(family: &str, datapath: &str, stages: u32, args: &str) -> Option<Params> {
    let target = Target::ALL.into_iter().find(|t| t.name() == family)?;
    let (_, base) = crate::config::datapaths(target)
        .into_iter()
        .find(|(name, _)| *name == datapath)?;
    Some(Params {
        stages,
        ..super::params_with_args(&base, args)?
    })
}

/// Solves the square system `a x = b` (Gaussian elimination, partial pivoting).
fn solve(a: Vec<Vec<f64>>, b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    let mut m: Vec<Vec<f64>> = a
        .into_iter()
        .zip(b)
        .map(|(mut row, v)| (row.push(v), row).1)
        .collect();
    for i in 0..n {
        let p = (i..n).max_by(|&x, &y| m[x][i].abs().total_cmp(&m[y][i].abs()).then(y.cmp(&x)))?;
        m.swap(i, p);
        if m[i][i].abs() < 1e-12 {
            return None;
        }
        for r in 0..n {
            if r != i {
                let k = m[r][i] / m[i][i];
                let pivot = m[i].clone();
                m[r].iter_mut().zip(&pivot).for_each(|(x, y)| *x -= k * y);
            }
        }
    }
    Some((0..n).map(|i| m[i][n] / m[i][i]).collect())
}

/// `period = c0 + Σ c_k · feature_k` by least squares: the coefficients and the squared error;
/// with `origin`, `c0` is held at 0 (a line through the origin: what a negative intercept is
/// bounded to).
fn least_squares(rows: &[&Row], features: &[&str], origin: bool) -> Option<(Vec<f64>, f64)> {
    let get = |r: &Row, f: &str| if f == "est" { r.est } else { r.mean };
    if origin {
        let (c, err) = least_squares_of(
            rows.iter()
                .map(|r| features.iter().map(|f| get(r, f)).collect())
                .collect(),
            rows,
        )?;
        return Some((std::iter::once(0.0).chain(c).collect(), err));
    }
    least_squares_of(
        rows.iter()
            .map(|r| {
                std::iter::once(1.0)
                    .chain(features.iter().map(|f| get(r, f)))
                    .collect()
            })
            .collect(),
        rows,
    )
}

/// Least squares of `1000 / fmax` on the rows' columns `xs`.
fn least_squares_of(xs: Vec<Vec<f64>>, rows: &[&Row]) -> Option<(Vec<f64>, f64)> {
    let ys: Vec<f64> = rows.iter().map(|r| 1000.0 / r.fmax).collect();
    let k = xs.first().map_or(0, Vec::len);
    if k == 0 {
        return None;
    }
    let ata = (0..k)
        .map(|i| {
            (0..k)
                .map(|j| xs.iter().map(|x| x[i] * x[j]).sum())
                .collect()
        })
        .collect();
    let aty = (0..k)
        .map(|i| xs.iter().zip(&ys).map(|(x, y)| x[i] * y).sum())
        .collect();
    let c = solve(ata, aty)?;
    let err = xs
        .iter()
        .zip(&ys)
        .map(|(x, y)| (y - c.iter().zip(x).map(|(a, b)| a * b).sum::<f64>()).powi(2))
        .sum();
    Some((c, err))
}

/// `x` to `digits` decimals, correctly rounded (the nearest decimal to its exact binary value).
fn round(x: f64, digits: usize) -> f64 {
    format!("{x:.digits$}").parse().expect("a decimal")
}

/// A stretch as the manifest states it (hundredths, `emit`'s rounding).
fn hundredths(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// The line of `rows` under `cap`: the plane (or line, or constant) with non-negative slopes
/// that fits best, its cap's reach and its margin.
fn fit(rows: &[&Row], cap: f64) -> Map<String, Value> {
    let mut best: Option<(&[&str], Vec<f64>, f64)> = None;
    for features in [&["est", "mean"][..], &["mean"], &["est"], &[]] {
        if rows.len() < features.len() + 1 {
            continue;
        }
        let Some((mut c, mut err)) = least_squares(rows, features, false) else {
            continue;
        };
        if c[0] < 0.0 {
            // a clock period has no negative part: the intercept is bounded at 0
            let Some(o) = least_squares(rows, features, true) else {
                continue;
            };
            (c, err) = o;
        }
        if c[1..].iter().any(|&x| x < 0.0) {
            continue;
        }
        if best.as_ref().is_none_or(|b| err < b.2 - 1e-9) {
            best = Some((features, c, err));
        }
    }
    let (features, c, err) = best.expect("a constant fits any row");
    // the share of the periods' spread the line explains
    let periods: Vec<f64> = rows.iter().map(|r| 1000.0 / r.fmax).collect();
    let mean = periods.iter().sum::<f64>() / periods.len() as f64;
    let spread: f64 = periods.iter().map(|p| (p - mean).powi(2)).sum();
    let r2 = if spread > 0.0 {
        1.0 - err / spread
    } else {
        1.0
    };
    let coef = |f: &str| {
        features
            .iter()
            .position(|x| *x == f)
            .map_or(0.0, |i| c[i + 1])
    };
    let below = rows
        .iter()
        .filter(|r| r.fmax < 0.99 * cap)
        .map(|r| r.est)
        .fold(f64::INFINITY, f64::min);
    let at_cap = rows
        .iter()
        .filter(|r| r.fmax >= 0.99 * cap && r.est < below)
        .map(|r| r.est)
        .fold(f64::NEG_INFINITY, f64::max);
    let (offset, per_unit, per_mean) = (
        round(c[0], 4),
        round(coef("est"), 4),
        round(coef("mean"), 4),
    );
    let cap_up_to = if at_cap.is_finite() {
        round(at_cap, 4)
    } else {
        -1.0
    };
    let predict = |r: &Row| {
        if r.est <= cap_up_to {
            cap
        } else {
            cap.min(1000.0 / (offset + per_unit * r.est + per_mean * r.mean).max(1e-6))
        }
    };
    let ratios: Vec<f64> = rows
        .iter()
        .filter(|r| r.est > cap_up_to)
        .map(|r| r.fmax / predict(r))
        .collect();
    let ratios = if ratios.is_empty() { vec![1.0] } else { ratios };
    let (under, over) = (
        ratios.iter().copied().fold(f64::INFINITY, f64::min),
        ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    let line = json!({
        "offset_ns": offset,
        "ns_per_unit": per_unit,
        "ns_per_mean_unit": per_mean,
        "cap_mhz": round(cap, 2),
        "cap_up_to": cap_up_to,
        "margin": round(under.min(1.0), 4),
        "points": rows.len(),
        "r2": round(r2, 4),
        "worst_under": round(under, 4),
        "worst_over": round(over, 4),
    });
    match line {
        Value::Object(m) => m,
        _ => unreachable!("an object"),
    }
}

/// The calibration columns, in order.
pub const COLUMNS: [&str; 9] = [
    "family",
    "model",
    "stages",
    "stage_delay_estimate",
    "stage_delay_mean",
    "fmax_mhz",
    "fmax_seeds",
    "args",
    "rtl_sha256",
];

/// A CSV row: its line number, its text, its cells in [`COLUMNS`] order.
type CsvRow<'a> = (usize, &'a str, Vec<String>);

/// A calibration CSV's rows, each with its line number and text and its cells in [`COLUMNS`]
/// order (a column the header lacks reads empty; `family`, `model`, `stages`, `fmax_mhz` and
/// `args` are required). Err: a missing column, or more than [`MAX_ROWS`] rows.
fn csv_rows<'a>(text: &'a str, source: &str) -> Result<Vec<CsvRow<'a>>, Error> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    for c in ["family", "model", "stages", "fmax_mhz", "args"] {
        if !header.contains(&c) {
            return Err(bad(format!("{source} has no column {c}")));
        }
    }
    let at: Vec<Option<usize>> = COLUMNS
        .iter()
        .map(|c| header.iter().position(|h| h == c))
        .collect();
    let mut out = Vec::new();
    for (i, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        if out.len() >= MAX_ROWS {
            return Err(bad(format!(
                "{source} holds more than {MAX_ROWS} rows; allowed at most {MAX_ROWS}"
            )));
        }
        let cells: Vec<&str> = line.split(',').collect();
        let mut row: Vec<String> = at
            .iter()
            .map(|a| {
                a.and_then(|a| cells.get(a))
                    .map_or(String::new(), |c| c.trim().to_string())
            })
            .collect();
        row[7] = row[7].split_whitespace().collect::<Vec<_>>().join(" ");
        out.push((i + 2, line, row));
    }
    Ok(out)
}

/// Calibration rows merged: each row of `new` (the explorations' `calibration.csv`, `specgen
/// stale --write-calibration`'s) replaces the row of `old` of the same unit (family, datapath,
/// depth, flags), or with `keep` only adds a unit `old` lacks. Returns the CSV, sorted by
/// family, datapath, flags and depth (the file's diff shows what came in), and how many units
/// were added. Err: a text whose header lacks a column.
pub fn merge_calibration(old: &str, new: &[&str], keep: bool) -> Result<(String, usize), Error> {
    type Key = (String, String, String, u64);
    let rows_of = |text: &str| -> Result<Vec<(Key, Vec<String>)>, Error> {
        let mut out = Vec::new();
        for (n, line, row) in csv_rows(text, "a calibration CSV")? {
            let stages = row[2].parse().map_err(|_| {
                bad(format!(
                    "a calibration CSV line {n}: {line}: stages is no count"
                ))
            })?;
            out.push((
                (row[0].clone(), row[1].clone(), row[7].clone(), stages),
                row,
            ));
        }
        Ok(out)
    };
    let mut rows: std::collections::BTreeMap<Key, Vec<String>> =
        rows_of(old)?.into_iter().collect();
    let mut added = 0;
    for text in new {
        for (key, row) in rows_of(text)? {
            if keep && rows.contains_key(&key) {
                continue;
            }
            added += usize::from(rows.insert(key, row).is_none());
        }
    }
    let mut csv = COLUMNS.join(",") + "\n";
    for row in rows.values() {
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    Ok((csv, added))
}

/// The margin of the reading between calibrated widths (`Line::corner`), found by leaving each
/// calibrated width out in turn and reading its units (floors of today's RTL) through the
/// others: the worst measured / read over every family and datapath, rounded down to hundredths
/// (at most 1; 1 where the rule is tried on no unit).
fn corner_margin(model: &Map<String, Value>) -> Result<f64, Error> {
    let mut worst = 1.0f64;
    for target in Target::ALL {
        let Some(lines) = super::family(target)
            .and_then(|f| model.get(f))
            .and_then(Value::as_object)
        else {
            continue;
        };
        for (name, base) in crate::config::datapaths(target) {
            let Some(full) = lines
                .get(name)
                .and_then(|v| serde_json::from_value::<super::Line>(v.clone()).ok())
            else {
                continue;
            };
            let full = full.of_todays_rtl();
            let mut widths = full.measured_args.clone();
            widths.sort();
            widths.dedup();
            for w in widths {
                let Some(params) = super::params_with_args(&base, &w) else {
                    continue;
                };
                let others: Vec<bool> = full.measured_args.iter().map(|a| *a != w).collect();
                let rest = full.clone().keeping(&others);
                for (i, unit) in full
                    .measured
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| full.measured_args[*i] == w)
                {
                    let plan = Plan::new(crate::config::Config::new(Params {
                        stages: full.measured_stages[i],
                        ..params.clone()
                    })?)?;
                    if let (read, true) = rest
                        .clone()
                        .at_widths_of(&plan)
                        .corner(plan.cfg.stages(), super::stretches(&plan).0)
                    {
                        worst = worst.min(unit[2] / read);
                    }
                }
            }
        }
    }
    Ok((worst * 100.0).floor() / 100.0)
}

/// The delay model fitted to a calibration CSV's text (`family,model,stages,…,fmax_mhz,
/// fmax_seeds,args,rtl_sha256`), as `data/delay_model.json` holds it; `source` names the CSV.
/// Err: a row that is not a calibration unit (named by its line).
pub fn fit_calibration(csv: &str, source: &str) -> Result<Value, Error> {
    let mut by_family: std::collections::BTreeMap<String, Vec<Row>> = Default::default();
    for (n, line, row) in csv_rows(csv, source)? {
        let [family, model, stages, _, _, fmax, seeds, args, digest] = &row[..] else {
            unreachable!("a cell a column")
        };
        if fmax.is_empty() {
            continue;
        }
        let what = || format!("{source} line {n}: {line}");
        let stages: u32 = stages
            .parse()
            .map_err(|_| bad(format!("{}: stages is no count", what())))?;
        let fmax: f64 = fmax
            .parse()
            .ok()
            .filter(|f: &f64| *f > 0.0 && f.is_finite())
            .ok_or_else(|| bad(format!("{}: fmax_mhz is no clock", what())))?;
        let seeds: Vec<f64> = seeds
            .split_whitespace()
            .map(|s| s.parse().ok().filter(|f: &f64| *f > 0.0 && f.is_finite()))
            .collect::<Option<_>>()
            .ok_or_else(|| bad(format!("{}: fmax_seeds holds no clocks", what())))?;
        let fmax = row_figure(fmax, &seeds);
        let params = row_params(family, model, stages, args).ok_or_else(|| {
            bad(format!(
                "{}: no calibration unit (family, datapath or args)",
                what()
            ))
        })?;
        let plan = Plan::new(
            crate::config::Config::new(params).map_err(|e| bad(format!("{}: {e}", what())))?,
        )
        .map_err(|e| bad(format!("{}: {e}", what())))?;
        let (e, m) = super::stretches(&plan);
        by_family.entry(family.clone()).or_default().push(Row {
            model: model.clone(),
            stages,
            est: hundredths(e),
            mean: hundredths(m),
            fmax,
            args: args.clone(),
            digest: digest.clone(),
        });
    }
    let mut model = Map::new();
    let mut handshake = Map::new();
    for (family, rows) in by_family.iter_mut() {
        // a `ready`/`axis` unit is the handshake's ceiling, never the line's data: per datapath,
        // the most measured of each interface, the lesser interface's; of today's RTL only
        let (edge, line_rows): (Vec<Row>, Vec<Row>) = std::mem::take(rows)
            .into_iter()
            .partition(|r| r.args.contains("--interface "));
        *rows = line_rows;
        let mut caps = Map::new();
        let names: std::collections::BTreeSet<String> =
            edge.iter().map(|r| r.model.clone()).collect();
        for name in names {
            let mut least: Option<&Row> = None;
            for interface in ["ready", "axis"] {
                let flag = format!("--interface {interface}");
                let most = edge
                    .iter()
                    .filter(|r| r.model == name && r.args.contains(&flag) && !r.digest.is_empty())
                    .max_by(|a, b| a.fmax.total_cmp(&b.fmax));
                if let Some(r) = most.filter(|r| least.is_none_or(|l| r.fmax < l.fmax)) {
                    least = Some(r);
                }
            }
            if let Some(r) = least {
                let unit = format!(
                    "{name} at --stages {}{}",
                    r.stages,
                    format!(" {}", r.args).trim_end()
                );
                caps.insert(name, json!({ "mhz": round(r.fmax, 2), "unit": unit, "stages": r.stages, "args": r.args, "digest": r.digest }));
            }
        }
        if !caps.is_empty() {
            handshake.insert(family.clone(), Value::Object(caps));
        }
    }
    for (family, rows) in &by_family {
        let cap = rows.iter().map(|r| r.fmax).fold(0.0, f64::max);
        let all: Vec<&Row> = rows.iter().collect();
        let mut lines = Map::new();
        lines.insert("all".into(), Value::Object(fit(&all, cap)));
        let names: std::collections::BTreeSet<&str> =
            rows.iter().map(|r| r.model.as_str()).collect();
        for name in &names {
            let mut mine: Vec<&Row> = rows.iter().filter(|r| r.model == *name).collect();
            if mine.len() < 3 {
                continue;
            }
            let mut line = fit(&mine, cap);
            mine.sort_by(|a, b| a.args.cmp(&b.args).then(a.stages.cmp(&b.stages)));
            line.insert(
                "measured".into(),
                json!(mine
                    .iter()
                    .map(|r| json!([r.est, r.mean, round(r.fmax, 2)]))
                    .collect::<Vec<_>>()),
            );
            line.insert(
                "measured_args".into(),
                json!(mine.iter().map(|r| r.args.clone()).collect::<Vec<_>>()),
            );
            line.insert(
                "measured_stages".into(),
                json!(mine.iter().map(|r| r.stages).collect::<Vec<_>>()),
            );
            line.insert(
                "measured_digest".into(),
                json!(mine.iter().map(|r| r.digest.clone()).collect::<Vec<_>>()),
            );
            lines.insert(name.to_string(), Value::Object(line));
        }
        // a datapath with too few rows for a line of its own, or none where its model says it
        // reads the family's (`SpecularUnit::reads_family_delay_line`: the paper's, never
        // calibrated alone; one that fits no part), takes the family's by name; any other
        // datapath without rows gets no line, and `--target-mhz` refuses it
        let target = Target::ALL
            .into_iter()
            .find(|t| t.name() == family)
            .expect("a row's family");
        let declared = crate::config::datapaths(target)
            .into_iter()
            .filter(|(_, params)| {
                crate::models::Model::new(
                    &crate::config::Config::new(params.clone()).expect("a datapath's defaults"),
                )
                .unit()
                .reads_family_delay_line()
            })
            .map(|(n, _)| n);
        for name in names.iter().copied().chain(declared) {
            lines
                .entry(name.to_string())
                .or_insert_with(|| json!("all"));
        }
        model.insert(family.clone(), Value::Object(lines));
    }
    model.insert("corner_margin".into(), json!(corner_margin(&model)?));
    model.insert("handshake".into(), Value::Object(handshake));
    model.insert("source".into(), json!(source));
    Ok(Value::Object(model))
}
