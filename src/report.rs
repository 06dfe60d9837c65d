//! `specgen report`: the paper's claims recomputed, and the generated unit's accuracy, as a
//! self-contained HTML page (inline SVG from plotters) plus `report.json` with every number.

mod figures;
use figures::*;

use crate::config::Config;
use crate::models::{Inputs, Model};
use crate::paper::{self, Claim};
use askama::Template;
use plotters::prelude::*;
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;

/// Sweeps above this many (cos_g, n) points are sampled with a stride on cos_g.
const SWEEP_LIMIT: u64 = 1 << 26;

/// The generated unit's error against the exact formula and against Blinn.
#[derive(Debug, Clone, Serialize)]
pub struct UnitAccuracy {
    /// "exhaustive" or "every k-th cos code"
    pub(crate) sweep: String,
    pub(crate) points: u64,
    /// |intensity − intensity*| in units of 2^-FI
    pub(crate) intensity_max_ulp: f64,
    pub(crate) intensity_mean_ulp: f64,
    /// |spec − spec*| at ks = all ones, in colour codes
    pub(crate) spec_max_ulp: f64,
    pub(crate) spec_mean_ulp: f64,
    /// |intensity/2^FI − cos^n| (model + quantisation error against Blinn)
    pub(crate) vs_blinn_max: f64,
    pub(crate) vs_blinn_mean: f64,
    /// |k_q-formula − real-k formula (15)|: what quantising k costs (the quadratic model only)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) k_quantisation_max: Option<f64>,
    /// max |intensity error| in ulps per (cos bin, n bin), row-major by n bin
    #[serde(skip)]
    pub(crate) heat: Vec<f64>,
}

/// Exhaustive (or strided) sweep of `(cos_g ∈ [0, 2^F], n)` on two threads.
pub(crate) fn unit_accuracy(m: &Model) -> UnitAccuracy {
    let cfg = &m.cfg;
    let f = cfg.f();
    let one = 1u64 << f;
    let n_count = 1u64 << cfg.n_bits();
    let total = (one + 1) * n_count;
    let stride = total.div_ceil(SWEEP_LIMIT).max(1);
    let ks_max = (1u32 << cfg.b()) - 1;
    #[derive(Default, Clone)]
    struct Acc {
        points: u64,
        imax: f64,
        isum: f64,
        smax: f64,
        ssum: f64,
        bmax: f64,
        bsum: f64,
        kmax: f64,
        heat: Vec<f64>,
    }
    let work = |lo: u64, hi: u64| {
        let mut a = Acc {
            heat: vec![0.0; HEAT_COS * HEAT_N],
            ..Acc::default()
        };
        for n in lo..hi {
            let nb = (n * HEAT_N as u64 / n_count) as usize;
            let mut cos_g = 0;
            while cos_g <= one {
                let x = Inputs {
                    cos_g: cos_g as u32,
                    n: n as u32,
                    ks: [ks_max; 3],
                };
                let o = m.eval(x);
                let (ideal_i, ideal_s) = m.ideal(x);
                let ie = (o.intensity as f64 - ideal_i).abs();
                let se = (o.spec[0] as f64 - ideal_s[0]).abs();
                let c = cos_g as f64 / one as f64;
                let s = o.intensity as f64 / (cfg.fi() as f64).exp2();
                let be = (s - c.powi(n as i32)).abs();
                let ke = m.unit().quantisation_error(x).unwrap_or(0.0);
                a.points += 1;
                a.imax = a.imax.max(ie);
                a.isum += ie;
                a.smax = a.smax.max(se);
                a.ssum += se;
                a.bmax = a.bmax.max(be);
                a.bsum += be;
                a.kmax = a.kmax.max(ke);
                let cb = ((cos_g * HEAT_COS as u64) / (one + 1)) as usize;
                let cell = &mut a.heat[nb * HEAT_COS + cb];
                *cell = cell.max(ie);
                cos_g += stride;
            }
        }
        a
    };
    let (a, b) = std::thread::scope(|s| {
        let h = s.spawn(|| work(0, n_count / 2));
        let b = work(n_count / 2, n_count);
        (h.join().unwrap(), b)
    });
    let points = a.points + b.points;
    UnitAccuracy {
        sweep: if stride == 1 {
            "exhaustive".into()
        } else {
            format!("every {stride}th cos code")
        },
        points,
        intensity_max_ulp: a.imax.max(b.imax),
        intensity_mean_ulp: (a.isum + b.isum) / points as f64,
        spec_max_ulp: a.smax.max(b.smax),
        spec_mean_ulp: (a.ssum + b.ssum) / points as f64,
        vs_blinn_max: a.bmax.max(b.bmax),
        vs_blinn_mean: (a.bsum + b.bsum) / points as f64,
        k_quantisation_max: m
            .unit()
            .quantisation_error(Inputs::default())
            .map(|_| a.kmax.max(b.kmax)),
        heat: a.heat.iter().zip(&b.heat).map(|(x, y)| x.max(*y)).collect(),
    }
}

type Curve<'a> = (&'a str, RGBColor, Box<dyn Fn(f64) -> f64 + 'a>);

/// Everything the report shows; serialised as `report.json`.
/// One model of the comparison: its distance from Blinn at the report's widths, and its
/// hardware as `specgen synth --json` measured it (when given with `--hw`).
#[derive(Debug, Clone, Serialize)]
pub(crate) struct ModelComparison {
    pub(crate) model: String,
    pub(crate) computes: String,
    pub(crate) blinn_error_max: f64,
    pub(crate) blinn_error_mean: f64,
    /// the two, to 3 significant digits (as the page prints them)
    #[serde(skip)]
    pub(crate) blinn_error_max_text: String,
    #[serde(skip)]
    pub(crate) blinn_error_mean_text: String,
    pub(crate) worst_n: u32,
    pub(crate) worst_cos_g: u32,
    /// every `--hw` result of this model, in the order given (two units of one model are two rows)
    pub(crate) hardware: Vec<crate::synth::SynthResult>,
    /// its part in the verdict on the premise
    #[serde(skip)]
    pub(crate) role: Option<crate::models::PremiseRole>,
}

/// Every model at the report's widths (stages 0, faithful), in `SpecularModel::ALL`'s order:
/// quadratic (the paper, with the configured arch), fitted, blinn, blinn-pow; each with what
/// it computes, in its own words. Only the model is made (no datapath).
pub(crate) fn models_compared(cfg: &Config) -> Vec<(Model, &'static str)> {
    use crate::config::{Params, Rounding, SpecularModel};
    SpecularModel::ALL
        .into_iter()
        .map(|model| {
            let arch = if model.reads("arch") {
                cfg.arch()
            } else {
                crate::config::Arch::Lean
            };
            let p = Params {
                model,
                arch,
                stages: 0,
                rounding: Rounding::Faithful,
                ..cfg.params.clone()
            };
            let m =
                Model::new(&Config::new(p).expect("the report's widths are valid for every model"));
            let what = m.unit().describe().computes;
            (m, what)
        })
        .collect()
}

/// Where a row's hardware was measured: target, DSPs, widths, pipeline depth, the clock it was
/// constrained to when it was pipelined for one, budget and the seeds.
pub(crate) fn operating_point(h: &crate::synth::SynthResult) -> String {
    let clock = match (h.stages, h.clock_mhz) {
        (s, Some(c)) if s > 0 => format!(" for {c} MHz"),
        _ => String::new(),
    };
    let widths = match h.widths.is_empty() {
        true => String::new(),
        false => format!(", F/N/B/FI {}", h.widths),
    };
    let budget = h
        .dsp_budget
        .map_or(String::new(), |b| format!(", --dsp-budget {b}"));
    let seeds = match h.seeds.is_empty() {
        true => String::new(),
        false => format!(", nextpnr seeds {}", crate::synth::seed_list(&h.seeds)),
    };
    format!(
        "{}{}{widths}, {} stage(s){clock}{budget}{seeds}",
        h.target,
        if h.dsp { " with DSPs" } else { ", LUTs only" },
        h.stages
    )
}

/// What a row's area is counted in: logic cells after packing (the wrapper included) when
/// place-and-route gave them, else LUT4.
fn area(h: &crate::synth::SynthResult) -> (u64, &'static str) {
    match h.logic_cells {
        Some(c) => (c, "logic cells"),
        None => (h.luts, "LUT4"),
    }
}

/// Whether a row's unit did not fit its part (place-and-route found no place for a cell).
fn did_not_fit(h: &crate::synth::SynthResult) -> bool {
    h.fmax_mhz.is_none()
        && (h.fmax_note.contains("no BELs remaining")
            || h.fmax_note.contains("Failed to expand region"))
}

/// What the comparison says about the paper's premise that cos^n is too costly: the errors
/// always; the hardware only as far as `--hw` gave it, each row at its own operating point.
/// Rows pipelined for one clock on one target are compared at that operating point (logic
/// cells when place-and-route counted them); a unit that does not fit the part says so.
fn premise(rows: &[ModelComparison]) -> String {
    use crate::models::PremiseRole;
    use crate::render::sig3;
    let get = |role: PremiseRole| rows.iter().find(|r| r.role == Some(role));
    let (q, f, b, p) = (
        get(PremiseRole::Paper),
        get(PremiseRole::Fit),
        get(PremiseRole::Tables),
        get(PremiseRole::SquareAndMultiply),
    );
    let (Some(q), Some(f), Some(b), Some(p)) = (q, f, b, p) else {
        return String::new();
    };
    let mut s = format!(
        "Against Blinn's cos^n, formula (15) is off by up to {} of full scale; the fitted form by {}; the table-based unit by {} (within one unit of the output), as exact as square-and-multiply ({}).",
        sig3(q.blinn_error_max),
        sig3(f.blinn_error_max),
        sig3(b.blinn_error_max),
        sig3(p.blinn_error_max)
    );
    let measured: Vec<&ModelComparison> = rows.iter().filter(|r| !r.hardware.is_empty()).collect();
    match (q.hardware.first(), b.hardware.first(), p.hardware.first()) {
        (Some(qh), Some(bh), Some(ph)) => {
            let (qa, unit) = area(qh);
            let (ba, bunit) = area(bh);
            let cost = |h: &crate::synth::SynthResult| {
                let (a, u) = area(h);
                // (each row in its own unit: a row without place-and-route has no logic cells)
                let fmax = h.fmax_mhz.map_or(String::new(), |m| format!(": {m:.1} MHz median"));
                format!("{a} {u}, {} flip-flops, {} DSP blocks and {} block RAMs ({}{fmax})", h.flip_flops, h.dsp_blocks, h.block_rams, operating_point(h))
            };
            let pow = if did_not_fit(ph) {
                format!("square-and-multiply does not fit the part ({} DSP blocks and {} LUT4 wanted, {})", ph.dsp_blocks, ph.luts, operating_point(ph))
            } else {
                format!("square-and-multiply {}", cost(ph))
            };
            s.push_str(&format!(" In hardware, (15) takes {}; blinn {}; {pow}.", cost(qh), cost(bh)));
            let same_clock = qh.stages > 0 && bh.stages > 0 && qh.clock_mhz.is_some() && qh.clock_mhz == bh.clock_mhz;
            let same_place = qh.target == bh.target && qh.dsp == bh.dsp && unit == bunit;
            if same_place && (same_clock || qh.stages == bh.stages) {
                let at = if same_clock { format!("pipelined for {} MHz", qh.clock_mhz.unwrap_or_default()) } else { "at that one operating point".to_string() };
                s.push_str(&format!(
                    " {} the table-based unit costs {:.1}× the {unit} of (15) for an error {:.0}× smaller.",
                    at[..1].to_uppercase() + &at[1..],
                    ba as f64 / qa.max(1) as f64,
                    q.blinn_error_max / b.blinn_error_max.max(1e-300)
                ));
            } else {
                s.push_str(" The rows were measured at different operating points, so their ratios are not a like-for-like cost.");
            }
            let pa = area(ph).0;
            let pow_cost =
                if did_not_fit(ph) { "it does not even fit the part".to_string() } else { format!("{:.1}× the {unit} of (15)", pa as f64 / qa.max(1) as f64) };
            s.push_str(&format!(
                " The paper's premise — that cos^n itself is too costly — holds for square-and-multiply ({pow_cost}), not for the table-based unit."
            ));
        }
        _ if !measured.is_empty() => s.push_str(&format!(
            " Hardware is given for {} only; the verdict on the premise needs {}, {} and {} measured (scripts/bench_hw.sh writes them).",
            measured.iter().map(|r| r.model.as_str()).collect::<Vec<_>>().join(", "),
            q.model,
            b.model,
            p.model
        )),
        _ => s.push_str(" No hardware was given: pass `specgen synth --json` results with --hw (scripts/bench_hw.sh writes them) to compare area and speed."),
    }
    s
}

/// The render sheet of every model (`specgen render`'s picture): the float cos^n column, then
/// each model's intensity and signed error on one scale, sphere and grazing plane, n = 1, 4,
/// 16, 128 (those within n_bits).
fn render_grid(models: &[(Model, &'static str)]) -> (crate::render::Picture, Vec<u32>) {
    let n_max = (1u32 << models[0].0.cfg.n_bits()) - 1;
    let ns: Vec<u32> = [1u32, 4, 16, 128]
        .into_iter()
        .filter(|&n| n <= n_max)
        .collect();
    let refs: Vec<&Model> = models.iter().map(|(m, _)| m).collect();
    (crate::render::picture(&refs, &ns, 96), ns)
}

#[derive(Debug, Clone, Serialize)]
pub(crate) struct ReportData {
    pub(crate) generator: &'static str,
    pub(crate) version: &'static str,
    /// the model every section but the paper's claims and the comparison is about
    pub(crate) model: String,
    /// its parameters, `name=value` words (only the ones the model reads)
    pub(crate) configuration: String,
    /// its parameters by name (only the ones the model reads)
    pub(crate) parameters: serde_json::Value,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) k_code: Option<u64>,
    pub(crate) claims: Vec<Claim>,
    pub(crate) unit: UnitAccuracy,
    pub(crate) models: Vec<ModelComparison>,
    pub(crate) premise: String,
    /// `--explored`: the front at each clock, cheapest first
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(crate) front: Vec<FrontRow>,
    pub(crate) files: Vec<serde_json::Value>,
}

/// One point of an exploration's front at one clock: which unit, its error at the pixel, its
/// cost and clock, and whether they are measured.
#[derive(Serialize, Debug, Clone)]
pub(crate) struct FrontRow {
    pub(crate) clock_mhz: f64,
    pub(crate) id: String,
    pub(crate) model: String,
    pub(crate) cos_frac_bits: u32,
    pub(crate) intensity_frac_bits: u32,
    pub(crate) stages: u32,
    pub(crate) pixel_error_max: f64,
    pub(crate) logic_cells: u64,
    pub(crate) fmax_mhz: Option<f64>,
    pub(crate) measured: bool,
}

/// The front of `e` at each of its clocks, cheapest first.
fn front_rows(e: &crate::explore::Exploration) -> Vec<FrontRow> {
    let mut rows = Vec::new();
    for &mhz in &e.clocks {
        let mut on: Vec<&crate::explore::Point> =
            e.points.iter().filter(|p| p.front.contains(&mhz)).collect();
        on.sort_by_key(|p| p.cells());
        rows.extend(on.into_iter().map(|p| FrontRow {
            clock_mhz: mhz,
            id: p.id.clone(),
            model: p.model.clone(),
            cos_frac_bits: p.cos_frac_bits,
            intensity_frac_bits: p.intensity_frac_bits,
            stages: p.stages,
            pixel_error_max: crate::explore::Metric::Max.of(&p.accuracy),
            logic_cells: p.cells(),
            fmax_mhz: p.fmax(),
            measured: p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some()),
        }));
    }
    rows
}

struct Row {
    name: &'static str,
    value: String,
}

#[derive(Template)]
#[template(path = "report.html")]
struct ReportPage<'a> {
    data: &'a ReportData,
    unit_rows: Vec<Row>,
    figures: Vec<Figure>,
    /// the model's name
    computes: &'a str,
    /// what section 2 measures against
    reference: &'a str,
    /// whether any row has --hw figures
    hw_given: bool,
    comparison_svg: String,
    grid_png: String,
    grid_models: Vec<String>,
    grid_ns: Vec<u32>,
    grid_scale: String,
    /// `--explored`: the exploration's front (SVG) and what it shows, in words
    front_svg: String,
    front_caption: String,
}

/// Builds `index.html` and `report.json` (file name, bytes); with an exploration, its measured
/// front is a section of the page.
pub fn build(
    cfg: &Config,
    hw: &[crate::synth::SynthResult],
    explored: Option<&crate::explore::Exploration>,
) -> Vec<(String, Vec<u8>)> {
    // the configured model, made once (its fit or tables) for every figure and row of its own
    let model = Model::new(cfg);
    let unit = unit_accuracy(&model);
    let figures = figures(cfg, &unit, model.unit());
    let models = models_compared(cfg);
    let mut fids = Vec::new();
    let rows: Vec<ModelComparison> = models
        .iter()
        .map(|(m, what)| {
            let f = m.fidelity();
            let name = m.cfg.model().name();
            fids.push((name.to_string(), f.per_n_max.clone()));
            ModelComparison {
                model: name.into(),
                computes: (*what).into(),
                blinn_error_max: f.max,
                blinn_error_mean: f.mean,
                blinn_error_max_text: crate::render::sig3(f.max),
                blinn_error_mean_text: crate::render::sig3(f.mean),
                worst_n: f.worst_n,
                worst_cos_g: f.worst_cos,
                hardware: hw.iter().filter(|h| h.model == name).cloned().collect(),
                role: m.unit().premise_role(),
            }
        })
        .collect();
    let comparison_svg = comparison_figure(&fids);
    let (grid, grid_ns) = render_grid(&models);
    let grid_png = crate::render::base64(&grid.png);
    let grid_models = models
        .iter()
        .map(|(m, _)| m.cfg.model().name().to_string())
        .collect();
    let premise = premise(&rows);
    let data = ReportData {
        generator: "specgen",
        version: crate::emit::VERSION,
        model: cfg.model().name().into(),
        configuration: cfg.describe(),
        parameters: {
            let mut v = serde_json::to_value(&cfg.params).expect("params serialise");
            cfg.model().keep_own_keys(&mut v);
            v
        },
        k_code: cfg.model().reads("k_code").then_some(cfg.k_code),
        claims: paper::claims(),
        unit,
        models: rows,
        premise,
        front: explored.map(front_rows).unwrap_or_default(),
        files: vec![serde_json::json!({"name": "index.html"})],
    };
    let u = &data.unit;
    use crate::render::sig3;
    let mut unit_rows = vec![
        Row {
            name: "sweep",
            value: format!("{} ({} points of (cos_g ∈ [0, 1.0], n))", u.sweep, u.points),
        },
        Row {
            name: "intensity error, max (ulp)",
            value: sig3(u.intensity_max_ulp),
        },
        Row {
            name: "intensity error, mean (ulp)",
            value: sig3(u.intensity_mean_ulp),
        },
        Row {
            name: "spec error at ks = 1.0, max (colour code)",
            value: sig3(u.spec_max_ulp),
        },
        Row {
            name: "spec error at ks = 1.0, mean (colour code)",
            value: sig3(u.spec_mean_ulp),
        },
        Row {
            name: "|intensity − cos^n|, max (full scale)",
            value: sig3(u.vs_blinn_max),
        },
        Row {
            name: "|intensity − cos^n|, mean (full scale)",
            value: sig3(u.vs_blinn_mean),
        },
    ];
    if let Some(k) = u.k_quantisation_max {
        unit_rows.push(Row {
            name: "k quantisation: |S(k_q) − S(k)|, max",
            value: sig3(k),
        });
    }
    let mut data = data;
    let reference = model.unit().reference_words();
    let hw_given = data.models.iter().any(|m| !m.hardware.is_empty());
    let page = ReportPage {
        data: &data,
        unit_rows,
        figures,
        computes: cfg.model().name(),
        reference,
        hw_given,
        comparison_svg,
        grid_png,
        grid_models,
        grid_ns,
        grid_scale: crate::render::sig3(grid.e_max),
        front_svg: explored.map_or(String::new(), |e| crate::explore::svg(e, crate::explore::Metric::Max)),
        front_caption: explored.map_or(String::new(), |e| {
            let measured = e.points.iter().filter(|p| p.measured.is_some()).count();
            format!(
                "The {} exploration: {} points, {measured} measured over nextpnr seeds {}; the max error at the pixel (the real cosine, rounded to F bits, against cos^n) against logic cells, one colour per model, measured points filled, the front at each of {} MHz a staircase, each of its points named (model, F, FI, depth, Fmax); the table below lists them.",
                e.part,
                e.points.len(),
                e.seeds.iter().map(u32::to_string).collect::<Vec<_>>().join(", "),
                e.clocks.iter().map(|c| format!("{c}")).collect::<Vec<_>>().join(", ")
            )
        }),
    };
    let html = page.render().expect("report template renders");
    drop(page);
    // the page with its SHA-256, so a later `report --out` here replaces it only unedited
    data.files = vec![
        serde_json::json!({"name": "index.html", "sha256": crate::bits::sha256_hex(html.as_bytes(), 32)}),
    ];
    let mut json = serde_json::to_string_pretty(&data).expect("report serialises");
    json.push('\n');
    vec![
        ("index.html".into(), html.into_bytes()),
        ("report.json".into(), json.into_bytes()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each model's colour is its name's, so every model of the registry
    /// has its own, and adding one repaints none.
    #[test]
    fn every_model_has_its_own_colour_by_name() {
        let names: Vec<&str> = crate::config::SpecularModel::ALL
            .iter()
            .map(|m| m.name())
            .collect();
        let colours: Vec<RGBColor> = names.iter().map(|n| model_colour(n)).collect();
        for (i, c) in colours.iter().enumerate() {
            assert!(
                colours[..i].iter().all(|d| d != c),
                "{} shares its colour with another model: {names:?}",
                names[i]
            );
        }
        assert_eq!(model_colour("blinn"), model_colour(&String::from("blinn")));
        // a model still to come takes a colour none of these has, whatever its name hashes to
        // (names that share a slot with one of them are among these)
        for i in 0..64 {
            let c = model_colour(&format!("model-{i}"));
            assert!(colours.iter().all(|d| *d != c), "model-{i}");
        }
    }

    #[test]
    fn small_unit_accuracy_is_within_contract() {
        let cfg = Config::new(crate::config::Params {
            cos_frac_bits: 8,
            n_bits: 4,
            ..Default::default()
        })
        .unwrap();
        let acc = unit_accuracy(&Model::new(&cfg));
        assert_eq!(acc.points, 257 * 16);
        assert!(acc.intensity_max_ulp < 1.0 && acc.spec_max_ulp < 1.0);
        assert!(acc.intensity_max_ulp > 0.0);
    }
}
