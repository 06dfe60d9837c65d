//! The report's figures, drawn with plotters as SVG: line plots, heat maps, the cut-off curve
//! and the models compared, each model in a colour of its own.

use super::*;

/// Bins of the unit-error heat map (cos axis × n axis).
pub(super) const HEAT_COS: usize = 96;

pub(super) const HEAT_N: usize = 64;

pub(super) const W: u32 = 640;

pub(super) const H: u32 = 400;

pub(super) fn svg(
    draw: impl FnOnce(
        DrawingArea<SVGBackend, plotters::coord::Shift>,
    ) -> Result<(), Box<dyn std::error::Error + '_>>,
) -> String {
    let mut out = String::new();
    {
        let area = SVGBackend::with_string(&mut out, (W, H)).into_drawing_area();
        area.fill(&WHITE).expect("svg fill");
        draw(area).expect("svg plot");
    }
    out
}

pub(super) fn line_plot(title: &str, x_label: &str, x_max: f64, curves: Vec<Curve>) -> String {
    svg(|area| {
        let mut chart = ChartBuilder::on(&area)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..x_max, 0.0..1.05)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc("value")
            .y_label_formatter(&|v| crate::render::sig3(*v))
            .x_label_formatter(&|v| crate::render::sig3(*v))
            .draw()?;
        for (name, colour, f) in curves {
            let pts: Vec<(f64, f64)> = (0..=400)
                .map(|i| {
                    let x = x_max * i as f64 / 400.0;
                    (x, f(x).clamp(0.0, 1.05))
                })
                .collect();
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))?
                .label(name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
        Ok(())
    })
}

/// A tick label: a power of ten as `1e-5`, else 3 significant digits.
pub(super) fn tick(v: f64) -> String {
    let l = v.abs().log10();
    if v != 0.0 && (l - l.round()).abs() < 1e-6 {
        format!("{}1e{}", if v < 0.0 { "-" } else { "" }, l.round() as i32)
    } else {
        crate::render::sig3(v)
    }
}

/// An integer tick label (n, codes).
pub(super) fn int_tick(v: &f64) -> String {
    format!("{}", v.round() as i64)
}

#[allow(clippy::too_many_arguments)] // a plot's labels, axes and grid, each named at the call
pub(super) fn heat_map(
    title: &str,
    x_label: &str,
    y_label: &str,
    x_max: f64,
    y_max: f64,
    cols: usize,
    rows: usize,
    cells: &[f64],
) -> String {
    let peak = cells.iter().cloned().fold(0.0f64, f64::max).max(1e-300);
    svg(|area| {
        // the map, and beside it its colour bar from 0 to the maximum
        let (map, bar) = area.split_horizontally(W - 80);
        let mut chart = ChartBuilder::on(&map)
            .caption(title, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..x_max, 0.0..y_max)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .y_label_formatter(&int_tick)
            .draw()?;
        let (cw, rh) = (x_max / cols as f64, y_max / rows as f64);
        chart.draw_series((0..rows).flat_map(|r| (0..cols).map(move |c| (r, c))).map(
            |(r, c)| {
                let v = cells[r * cols + c] / peak;
                let colour = ViridisRGB::get_color(v);
                Rectangle::new(
                    [
                        (c as f64 * cw, r as f64 * rh),
                        ((c + 1) as f64 * cw, (r + 1) as f64 * rh),
                    ],
                    colour.filled(),
                )
            },
        ))?;
        // the colour bar: 100 bands from 0 (bottom) to the maximum (top), 5 labels beside
        let (top, bottom, x) = (50i32, H as i32 - 50, 8i32);
        for i in 0..100 {
            let y0 = bottom - (bottom - top) * (i + 1) / 100;
            let y1 = bottom - (bottom - top) * i / 100;
            bar.draw(&Rectangle::new(
                [(x, y0), (x + 18, y1)],
                ViridisRGB::get_color((i as f64 + 0.5) / 100.0).filled(),
            ))?;
        }
        for j in 0..=4 {
            let y = bottom - (bottom - top) * j / 4;
            bar.draw(&PathElement::new(vec![(x + 18, y), (x + 22, y)], BLACK))?;
            bar.draw(&Text::new(
                tick(peak * j as f64 / 4.0),
                (x + 25, y - 6),
                ("sans-serif", 12),
            ))?;
        }
        Ok(())
    })
}

pub struct Figure {
    pub(crate) id: &'static str,
    pub(crate) caption: String,
    pub(crate) svg: String,
}

/// The figures: analogues of the paper's, plus the ROM cut-off and two error maps.
pub fn figures(
    cfg: &Config,
    acc: &UnitAccuracy,
    unit: &dyn crate::models::SpecularUnit,
) -> Vec<Figure> {
    let mut v = Vec::new();
    let alpha = 0.15;
    v.push(Figure {
        id: "ward",
        caption: "Ward's exp(−tan²δ/α²) (2), its approximation (5) cut at the bracket's zero, and Blinn with n = 2/α², α = 0.15 (paper, Fig. 2).".into(),
        svg: line_plot(
            "Ward vs approximation (5), α = 0.15",
            "δ (rad)",
            0.8,
            vec![
                ("exp(−tan²δ/α²)", RED, Box::new(move |d| paper::ward(d, alpha))),
                ("[(cos δ−1)/(8α²)+1]^16", BLUE, Box::new(move |d| paper::ward_approx(d, alpha, true))),
                ("cos^(2/α²) δ", GREEN, Box::new(move |d| paper::blinn(d, 2.0 / (alpha * alpha)))),
            ],
        ),
    });
    for n in [10.0f64, 50.0, 200.0] {
        let x_max = (1.0 - 2.713 / n).max(-1.0).acos().max(0.3) * 1.2;
        v.push(Figure {
            id: "formula15",
            caption: format!("Blinn cos^n δ, (12) and (15) for n = {n} (paper, Fig. 4)."),
            svg: line_plot(
                &format!("Blinn vs (12) vs (15), n = {n}"),
                "δ (rad)",
                x_max.min(FRAC_PI_2),
                vec![
                    ("cos^n δ", RED, Box::new(move |d| paper::blinn(d, n))),
                    (
                        "(12): a = 2",
                        BLUE,
                        Box::new(move |d| paper::cosine_quadratic(d, n, 2.0)),
                    ),
                    (
                        "(15): a = 2.713",
                        GREEN,
                        Box::new(move |d| paper::cosine_quadratic(d, n, 2.713)),
                    ),
                ],
            ),
        });
    }
    v.push(Figure {
        id: "schlick_curves",
        caption: "Blinn, Schlick (7) and modified Schlick (11) for n = 10 (paper, Fig. 3).".into(),
        svg: line_plot(
            "Blinn, Schlick (7), (11), n = 10",
            "δ (rad)",
            FRAC_PI_2,
            vec![
                ("cos^10 δ", RED, Box::new(|d| paper::blinn(d, 10.0))),
                ("Schlick (7)", BLUE, Box::new(|d| paper::schlick(d, 10.0))),
                (
                    "(11)",
                    GREEN,
                    Box::new(|d| paper::schlick_ab(d, 10.0, 2.0, 2.0)),
                ),
            ],
        ),
    });
    let n_max = (1u64 << cfg.n_bits()) as f64;
    if let Some(fig) = cutoff_figure(cfg, unit) {
        v.push(fig);
    }
    v.push(Figure {
        id: "unit_error",
        caption: format!(
            "The {} unit's intensity error |intensity − intensity*| in ulps of UQ1.{} against its exact reference, over every (cos_g, n): the worst per cell ({} sweep, {} points), colour bar beside.",
            cfg.model().name(), cfg.fi(), acc.sweep, acc.points
        ),
        svg: heat_map(
            &format!("{} unit error (ulps), max {}", cfg.model().name(), crate::render::sig3(acc.intensity_max_ulp)),
            "cos_g (full scale)",
            "n",
            1.0,
            n_max,
            HEAT_COS,
            HEAT_N,
            &acc.heat,
        ),
    });
    let (cols, rows) = (96usize, 64usize);
    let cells: Vec<f64> = (0..rows)
        .flat_map(|r| (0..cols).map(move |c| (r, c)))
        .map(|(r, c)| {
            let n = 1.0 + 999.0 * (r as f64 + 0.5) / rows as f64;
            // δ axis: [0, 0.5 rad], where the highlights of n ≥ 10 live
            let d = 0.5 * (c as f64 + 0.5) / cols as f64;
            (paper::cosine_quadratic(d, n, 2.713) - paper::blinn(d, n)).abs()
        })
        .collect();
    let peak = cells.iter().cloned().fold(0.0f64, f64::max);
    v.push(Figure {
        id: "model_error",
        caption: "The paper's formula (15) in real numbers against Blinn, |(15) − cos^n δ|, over δ ∈ [0, 0.5] rad and n ∈ [1, 1000] only (cell centres): the highlights of n ≥ 10. Its worst over all δ and n (0.399, at n = 1) lies outside this window; see section 3.".into(),
        svg: heat_map(&format!("|(15) − cos^n δ|, δ ≤ 0.5 rad, n ≤ 1000: max {}", crate::render::sig3(peak)), "δ (rad)", "n", 0.5, 1000.0, cols, rows, &cells),
    });
    v
}

/// The cut-off angle per n, stored (points) and ideal (line), for a model that stores its
/// cut-off ([`SpecularUnit::cut_off`](crate::models::SpecularUnit::cut_off),
/// [`ideal_cut_off`](crate::models::SpecularUnit::ideal_cut_off)); none for the others.
pub(super) fn cutoff_figure(
    cfg: &Config,
    unit: &dyn crate::models::SpecularUnit,
) -> Option<Figure> {
    let count = 1u32 << cfg.n_bits();
    let table: Vec<u32> = (0..count).map(|n| unit.cut_off(n)).collect::<Option<_>>()?;
    let ideal: Vec<f64> = (1..count)
        .map(|n| unit.ideal_cut_off(n))
        .collect::<Option<_>>()?;
    let one = (cfg.f() as f64).exp2();
    let n_max = table.len() as f64;
    Some(Figure {
        id: "cutoff",
        caption: format!("Cut-off angle γsp(n) = arccos(ROM[n]/2^{}) from the generated ROM (points), and the ideal cut-off (line).", cfg.f()),
        svg: svg(|area| {
            let mut chart = ChartBuilder::on(&area)
                .caption("Cut-off angle γsp(n) from the ROM", ("sans-serif", 18))
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(0.0..n_max, 0.0..90.0)?;
            chart.configure_mesh().x_desc("n").y_desc("γsp (degrees)").x_label_formatter(&int_tick).draw()?;
            let step = (table.len() / 256).max(1);
            chart.draw_series(
                table.iter().enumerate().step_by(step).skip(1).map(|(n, &c)| Circle::new((n as f64, (c as f64 / one).acos().to_degrees()), 2, BLUE.filled())),
            )?;
            chart.draw_series(LineSeries::new(ideal.iter().enumerate().map(|(i, &c)| ((i + 1) as f64, c.acos().to_degrees())), RED.stroke_width(1)))?;
            Ok(())
        }),
    })
}

/// The colours a model's curve is drawn in, one picked by its name.
pub(super) const MODEL_COLOURS: [RGBColor; 16] = [
    RGBColor(228, 26, 28),
    RGBColor(55, 126, 184),
    RGBColor(77, 175, 74),
    RGBColor(152, 78, 163),
    RGBColor(255, 127, 0),
    RGBColor(0, 0, 0),
    RGBColor(166, 86, 40),
    RGBColor(247, 129, 191),
    RGBColor(102, 102, 102),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(31, 31, 140),
    RGBColor(0, 128, 0),
    RGBColor(128, 0, 0),
    RGBColor(0, 128, 128),
    RGBColor(200, 0, 200),
];

/// A model's colour in the comparison figure, fixed by its name (FNV-1a over its bytes picks
/// a palette slot), not by its place in the registry: a model added keeps every other's colour
/// unless its name's slot is theirs. Where two names share a slot, the model earlier in the
/// registry keeps it and the other takes the next free one, so no two models share a colour.
pub(super) fn model_colour(name: &str) -> RGBColor {
    let slot = |n: &str| {
        let h = n.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
        });
        (h % MODEL_COLOURS.len() as u64) as usize
    };
    let mut taken: Vec<usize> = Vec::new();
    let names = crate::config::SpecularModel::ALL.map(|m| m.name());
    for n in names.iter().copied().chain(std::iter::once(name)) {
        let mut s = slot(n);
        while taken.contains(&s) && taken.len() < MODEL_COLOURS.len() {
            s = (s + 1) % MODEL_COLOURS.len();
        }
        if n == name {
            return MODEL_COLOURS[s];
        }
        taken.push(s);
    }
    unreachable!("the name is the chain's last")
}

/// The per-n worst error of every model against cos^n (log scale).
pub(super) fn comparison_figure(fids: &[(String, Vec<f64>)]) -> String {
    let n_max = fids.first().map_or(1, |f| f.1.len()) as f64;
    svg(|area| {
        let mut chart = ChartBuilder::on(&area)
            .caption(
                "Worst |intensity − cos^n| over cos_g, per n",
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(1.0..n_max, (1e-7f64..1.0).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("n")
            .y_desc("max error")
            .y_labels(8)
            .y_label_formatter(&|v| tick(*v))
            .x_label_formatter(&int_tick)
            .draw()?;
        for (name, per_n) in fids {
            let colour = model_colour(name);
            let pts: Vec<(f64, f64)> = per_n
                .iter()
                .enumerate()
                .skip(1)
                .map(|(n, &e)| (n as f64, e.max(1e-7)))
                .collect();
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(1)))?
                .label(name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
        Ok(())
    })
}
