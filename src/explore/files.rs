//! An exploration's files: points and fronts as CSV and JSON, the figure, the calibration rows.

use super::{Job, MergeReport, Metric, Point};
use crate::config::{Config, Params, SpecularModel};
use crate::error::{input, Error};
use serde::{Deserialize, Serialize};

/// A whole exploration as it is stored (`points.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Exploration {
    pub generator: String,
    pub version: String,
    pub target: String,
    pub part: String,
    pub metric: String,
    pub clocks: Vec<f64>,
    pub seeds: Vec<u32>,
    pub points: Vec<Point>,
}

impl Exploration {
    /// Reads an exploration (`points.json`), at most 64 MiB.
    pub fn from_text(text: &str, what: &str) -> Result<Exploration, Error> {
        let e: Exploration = serde_json::from_str(text).map_err(|e| {
            input(format!(
                "{what} is not an exploration (`specgen explore`'s points.json): {e}"
            ))
        })?;
        if e.generator != "specgen" {
            return Err(input(format!(
                "{what} is not an exploration written by specgen"
            )));
        }
        if e.points.len() > MAX_POINTS {
            return Err(input(format!(
                "{what} holds {} points; allowed at most {MAX_POINTS}",
                e.points.len()
            )));
        }
        // every number that is drawn or compared in range before anything reads it
        for p in &e.points {
            let bad = |what_field: &str, v: f64| {
                input(format!(
                    "{what}: point {} has {what_field} {v}, out of range",
                    p.id
                ))
            };
            let a = &p.accuracy;
            for (name, v) in [
                ("accuracy.max", a.max),
                ("accuracy.mean", a.mean),
                ("accuracy.rms", a.rms),
                ("accuracy.max_step_excess", a.max_step_excess),
            ] {
                if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                    return Err(bad(name, v));
                }
            }
            if !(a.psnr_db.is_finite() && (-1.0..=1000.0).contains(&a.psnr_db)) {
                return Err(bad("accuracy.psnr_db", a.psnr_db));
            }
            if let Some(x) = &a.pixel {
                for (name, v) in [
                    ("accuracy.pixel.max", x.max),
                    ("accuracy.pixel.mean", x.mean),
                    ("accuracy.pixel.rms", x.rms),
                ] {
                    if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                        return Err(bad(name, v));
                    }
                }
            }
            if let Some(d) = &a.display {
                for (name, v) in [
                    ("accuracy.display.max_codes", d.max_codes),
                    ("accuracy.display.banding_codes", d.banding_codes),
                ] {
                    if !(v.is_finite() && (0.0..=65535.0).contains(&v)) {
                        return Err(bad(name, v));
                    }
                }
            }
            let est = &p.estimate;
            for (name, v) in [
                ("estimate.fmax_mhz", est.fmax_mhz.unwrap_or(1.0)),
                ("estimate.stage_delay", est.stage_delay.max(0.0) + 1.0),
            ] {
                if !(v.is_finite() && v > 0.0 && v <= 1e6) {
                    return Err(bad(name, v));
                }
            }
            if let Some(m) = &p.measured {
                for &f in m.fmax_mhz.iter().chain(&m.fmax_seeds).chain(&m.route_seeds) {
                    if !(f.is_finite() && f > 0.0 && f <= 1000.0) {
                        return Err(bad("measured Fmax", f));
                    }
                }
                if m.logic_cells.is_some_and(|c| c > 10_000_000) {
                    return Err(bad(
                        "measured logic cells",
                        m.logic_cells.unwrap_or(0) as f64,
                    ));
                }
            }
            if p.estimate.logic_cells > 100_000_000 {
                return Err(bad("estimate.logic_cells", p.estimate.logic_cells as f64));
            }
        }
        Ok(e)
    }
}

/// The most points an exploration holds.
pub const MAX_POINTS: usize = 20_000;

fn csv(points: &[Point]) -> String {
    let mut s = String::from("id,model,cos_frac_bits,intensity_frac_bits,stages,dsp_budget,rom_style,error_max,error_mean,error_rms,psnr_db,max_step_excess,est_logic_cells,est_dsp_blocks,est_block_rams,est_fmax_mhz,measured_seeds,fmax_mhz,fmax_min,fmax_max,logic_cells,dsp_blocks,block_rams,limited_by,front_mhz\n");
    let opt = |v: Option<f64>| v.map_or(String::new(), |f| format!("{f:.1}"));
    for p in points {
        let m = p.measured.as_ref();
        let lo = m.and_then(|m| m.fmax_seeds.iter().copied().reduce(f64::min));
        let hi = m.and_then(|m| m.fmax_seeds.iter().copied().reduce(f64::max));
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{:.6e},{:.6e},{:.6e},{:.2},{:.6e},{},{},{},{},{},{},{},{},{},{},{},\"{}\",{}\n",
            p.id,
            p.model,
            p.cos_frac_bits,
            p.intensity_frac_bits,
            p.stages,
            p.dsp_budget.map_or(String::new(), |b| b.to_string()),
            p.rom_style,
            p.accuracy.max,
            p.accuracy.mean,
            p.accuracy.rms,
            p.accuracy.psnr_db,
            p.accuracy.max_step_excess,
            p.estimate.logic_cells,
            p.estimate.dsp_blocks,
            p.estimate.block_rams,
            opt(p.estimate.fmax_mhz),
            m.map_or(String::new(), |m| m.seeds.iter().map(u32::to_string).collect::<Vec<_>>().join(" ")),
            opt(m.and_then(|m| m.fmax_mhz)),
            opt(lo),
            opt(hi),
            m.and_then(|m| m.logic_cells).map_or(String::new(), |c| c.to_string()),
            m.map_or(String::new(), |m| m.dsp_blocks.to_string()),
            m.map_or(String::new(), |m| m.block_rams.to_string()),
            m.map_or(String::new(), |m| m.limited_by.replace('"', "'")),
            p.front.iter().map(|f| format!("{f}")).collect::<Vec<_>>().join(" "),
        ));
    }
    s
}

/// The measured points as the delay model's calibration rows (`data/delay_calibration.csv`'s
/// columns: family, datapath, stages, the two stretch estimates, nextpnr's median over the
/// seeds and each seed's, the generate flags beyond the defaults, and the RTL digest the row
/// was measured on where it is today's, else empty: such a row is the fit's data, no floor).
pub fn calibration_csv(e: &Exploration) -> String {
    let mut s = String::from("family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args,rtl_sha256\n");
    let defaults = Params::default();
    for p in &e.points {
        let Some(m) = p
            .measured
            .as_ref()
            .filter(|m| m.route_seeds.len() == m.seeds.len() && !m.route_seeds.is_empty())
        else {
            continue;
        };
        let Ok(cfg) = Config::new(p.params.clone()) else {
            continue;
        };
        // a calibration unit has no tag, per-pixel colours and no clock enable; a `ready` or
        // `axis` one is a row of its own (`--interface`), the handshake's ceiling, never the
        // line's data
        let edge = |q: &Params| (q.tag_bits, q.tlast, q.colour, q.clock_enable);
        if edge(&p.params) != edge(&defaults) || p.params.rounding != defaults.rounding {
            continue;
        }
        let mut args = Vec::new();
        if p.params.interface != defaults.interface {
            args.push(format!("--interface {}", p.params.interface.name()));
        }
        if p.params.fabric_registers {
            args.push("--fabric-registers true".to_string());
        }
        for (flag, v, d) in [
            (
                "--cos-frac-bits",
                p.params.cos_frac_bits,
                defaults.cos_frac_bits,
            ),
            ("--n-bits", p.params.n_bits, defaults.n_bits),
            ("--color-bits", p.params.color_bits, defaults.color_bits),
            (
                "--intensity-frac-bits",
                p.params.intensity_frac_bits,
                defaults.intensity_frac_bits,
            ),
        ] {
            if v != d {
                args.push(format!("{flag} {v}"));
            }
        }
        // the widths a model reads beyond those four (the delay model's shape reads them: a
        // row without them would stand for another unit)
        let model = p.params.model;
        for (flag, key, v, d) in [
            (
                "--k-frac-bits",
                "k_frac_bits",
                p.params.k_frac_bits,
                defaults.k_frac_bits,
            ),
            (
                "--max-squarings",
                "max_squarings",
                p.params.max_squarings,
                defaults.max_squarings,
            ),
        ] {
            if v != d && model.reads(key) {
                args.push(format!("{flag} {v}"));
            }
        }
        if let Some(b) = p.params.dsp_budget {
            args.push(format!("--dsp-budget {b}"));
        }
        if p.params.rom_style != defaults.rom_style {
            args.push(format!("--rom-style {}", p.params.rom_style.name()));
        }
        s.push_str(&format!(
            "{},{},{},{:.1},{:.2},{:.2},{},{},{}\n",
            e.target,
            cfg.datapath_name(),
            p.stages,
            p.estimate.stage_delay,
            p.estimate.stage_delay_mean,
            crate::synth::median(&m.route_seeds).unwrap_or(0.0),
            m.route_seeds
                .iter()
                .map(|f| format!("{f:.2}"))
                .collect::<Vec<_>>()
                .join(" "),
            args.join(" "),
            super::measured_today(p).ok().flatten().unwrap_or_default()
        ));
    }
    s
}

/// The colour of a model in the figure.
fn colour(model: &str) -> plotters::style::RGBColor {
    use plotters::style::RGBColor;
    match SpecularModel::ALL.iter().position(|m| m.name() == model) {
        Some(0) => RGBColor(31, 119, 180),
        Some(1) => RGBColor(214, 39, 40),
        Some(2) => RGBColor(44, 160, 44),
        Some(3) => RGBColor(255, 127, 14),
        _ => RGBColor(148, 103, 189),
    }
}

/// The figure: error (log axis) against logic cells, one colour per model, measured points
/// filled and estimated ones hollow, each clock's front a line.
pub fn svg(e: &Exploration, metric: Metric) -> String {
    use plotters::prelude::*;
    let mut out = String::new();
    let pts: Vec<&Point> = e
        .points
        .iter()
        .filter(|p| metric.of(&p.accuracy) > 0.0 && metric.of(&p.accuracy).is_finite())
        .collect();
    let emin = pts
        .iter()
        .map(|p| metric.of(&p.accuracy))
        .fold(f64::INFINITY, f64::min)
        .min(1e-3)
        / 2.0;
    let emax = pts
        .iter()
        .map(|p| metric.of(&p.accuracy))
        .fold(0.0, f64::max)
        .max(1e-2)
        * 2.0;
    let cmax = pts.iter().map(|p| p.cells()).max().unwrap_or(100) as f64 * 1.08;
    // the axis starts near the cheapest point, not at zero cells
    let cmin = (pts.iter().map(|p| p.cells()).min().unwrap_or(0) as f64 * 0.9).min(cmax * 0.5);
    {
        let root = SVGBackend::with_string(&mut out, (900, 600)).into_drawing_area();
        root.fill(&WHITE).expect("svg");
        let title = format!(
            "{}: {} error vs logic cells ({}), filled = measured; the front per clock, a staircase",
            e.part,
            metric.name(),
            e.target
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(cmin..cmax, (emin..emax).log_scale())
            .expect("svg chart");
        chart
            .configure_mesh()
            .x_desc("logic cells (measured where filled, else estimated)")
            .y_desc(format!("{} |intensity - cos^n|", metric.name()))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .expect("svg mesh");
        let styles = [
            BLACK,
            RGBColor(100, 100, 100),
            RGBColor(170, 170, 170),
            RGBColor(210, 210, 210),
        ];
        let mut labelled: Vec<&str> = Vec::new();
        for (i, &mhz) in e.clocks.iter().enumerate().rev() {
            let mut on: Vec<&&Point> = pts.iter().filter(|p| p.front.contains(&mhz)).collect();
            on.sort_by_key(|p| p.cells());
            // a staircase: a point's error holds until the next (cheaper to more accurate)
            let mut line: Vec<(f64, f64)> = Vec::new();
            for (k, p) in on.iter().enumerate() {
                let (x, y) = (p.cells() as f64, metric.of(&p.accuracy));
                if k > 0 {
                    line.push((x, line[line.len() - 1].1));
                }
                line.push((x, y));
            }
            // each front point named once: model, widths, depth, Fmax
            for p in &on {
                if labelled.contains(&p.id.as_str()) {
                    continue;
                }
                labelled.push(&p.id);
                let text = format!(
                    "{} {}",
                    p.id,
                    p.fmax().map_or(String::new(), |f| format!("{f:.0} MHz"))
                );
                chart
                    .draw_series(std::iter::once(Text::new(
                        text,
                        (p.cells() as f64, metric.of(&p.accuracy)),
                        ("sans-serif", 10),
                    )))
                    .expect("svg label");
            }
            let style = styles[i.min(3)];
            chart
                .draw_series(LineSeries::new(line, style.stroke_width(2)))
                .expect("svg front")
                .label(format!("front at {mhz} MHz"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], style.stroke_width(2))
                });
        }
        for m in SpecularModel::ALL {
            let name = m.name();
            let c = colour(name);
            let mine: Vec<&&Point> = pts.iter().filter(|p| p.model == name).collect();
            if mine.is_empty() {
                continue;
            }
            chart
                .draw_series(mine.iter().map(|p| {
                    let filled = p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some());
                    Circle::new(
                        (p.cells() as f64, metric.of(&p.accuracy)),
                        4,
                        if filled {
                            c.filled()
                        } else {
                            c.stroke_width(1)
                        },
                    )
                }))
                .expect("svg points")
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .expect("svg legend");
        root.present().expect("svg");
    }
    out
}

/// The front at each clock as CSV: clock, then the front's points, cheapest first.
fn front_csv(e: &Exploration, metric: Metric) -> String {
    let mut s = format!(
        "clock_mhz,id,{}_error,logic_cells,fmax_mhz,measured\n",
        metric.name()
    );
    for &mhz in &e.clocks {
        let mut on: Vec<&Point> = e.points.iter().filter(|p| p.front.contains(&mhz)).collect();
        on.sort_by_key(|p| p.cells());
        for p in on {
            s.push_str(&format!(
                "{mhz},{},{:.6e},{},{},{}\n",
                p.id,
                metric.of(&p.accuracy),
                p.cells(),
                p.fmax().map_or(String::new(), |f| format!("{f:.1}")),
                p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some())
            ));
        }
    }
    s
}

/// The files of an exploration: `points.json` (everything), `points.csv`, `front.csv`,
/// `front.svg`, `jobs.json` (the measuring plan), `merge.json` (what the merge found) and
/// `explore.json`, the directory's manifest.
pub fn files(
    e: &Exploration,
    metric: Metric,
    jobs: &[Job],
    merge: &MergeReport,
) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = vec![
        ("points.json".into(), json(e)),
        ("points.csv".into(), csv(&e.points).into_bytes()),
        ("front.csv".into(), front_csv(e, metric).into_bytes()),
        ("front.svg".into(), svg(e, metric).into_bytes()),
        ("jobs.json".into(), json(jobs)),
        ("merge.json".into(), json(merge)),
        ("calibration.csv".into(), calibration_csv(e).into_bytes()),
    ];
    // each measured point as `synth --seeds K --json` writes it (for `report --hw`, the benches)
    files.extend(
        merge
            .synth
            .iter()
            .map(|(id, r)| (format!("synth/{id}.json"), json(r))),
    );
    // the directory's manifest: what specgen wrote there, so that a later run replaces it
    let listed: Vec<serde_json::Value> = files
        .iter()
        .map(|(n, b)| serde_json::json!({ "name": n, "sha256": crate::bits::sha256_hex(b, 32) }))
        .collect();
    let manifest = serde_json::json!({ "generator": "specgen", "version": e.version, "exploration": e.part, "files": listed });
    files.push(("explore.json".into(), json(&manifest)));
    files
}

/// A value as pretty JSON, with a final newline.
fn json<T: Serialize + ?Sized>(v: &T) -> Vec<u8> {
    let mut t = serde_json::to_string_pretty(v).expect("serialises");
    t.push('\n');
    t.into_bytes()
}
