//! Pictures of the specular term: a sphere and a plane at grazing light, each pixel's
//! `cos δ = N·H` quantised to the unit's `cos_g` port; per model, the unit's intensity beside
//! Blinn's float `cos^n δ` and their signed difference on one diverging scale, with titles,
//! row and column labels and colour bars drawn in a bundled bitmap font. [`picture`] builds
//! the sheet from golden models; `specgen render` first runs the same vectors through each
//! unit's RTL under the co-simulation harness and renders only when every pixel is
//! bit-identical.

use crate::models::{Inputs, Model};

/// The two scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scene {
    /// A unit sphere seen head-on, lit from the upper left.
    Sphere,
    /// A plane seen from above at an angle, lit from a light skimming its surface.
    GrazingPlane,
}

/// One pixel's geometry: `cos δ = N·H` and the diffuse term `N·L`, or nothing (background).
fn geometry(scene: Scene, u: f64, v: f64) -> Option<(f64, f64)> {
    let norm = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    match scene {
        Scene::Sphere => {
            let (x, y) = (2.0 * u - 1.0, 1.0 - 2.0 * v);
            let r2 = x * x + y * y;
            if r2 > 1.0 {
                return None;
            }
            let n = [x, y, (1.0 - r2).sqrt()];
            let l = norm([-0.45, 0.55, 0.70]);
            let h = norm([l[0], l[1], l[2] + 1.0]); // viewer at +z, far away
            Some((dot(n, h).max(0.0), dot(n, l).max(0.0)))
        }
        Scene::GrazingPlane => {
            // the plane z = 0, points (x, y) in [-1, 1]², eye above it, light almost in-plane
            let p = [2.0 * u - 1.0, 1.0 - 2.0 * v, 0.0];
            let n = [0.0, 0.0, 1.0];
            let eye = [0.0, -2.2, 1.2];
            let light = [0.0, 3.0, 0.25];
            let to = |a: [f64; 3]| norm([a[0] - p[0], a[1] - p[1], a[2] - p[2]]);
            let (vd, ld) = (to(eye), to(light));
            let h = norm([vd[0] + ld[0], vd[1] + ld[1], vd[2] + ld[2]]);
            Some((dot(n, h).max(0.0), dot(n, ld).max(0.0)))
        }
    }
}

/// The `cos_g` port code nearest to `c`.
pub fn cos_code(model: &Model, c: f64) -> u32 {
    (c * (model.cfg.f() as f64).exp2())
        .round()
        .min((model.cfg.f() as f64).exp2()) as u32
}

/// Every unit input a tile of `size`² pixels needs (background pixels excluded), in pixel order.
pub fn tile_inputs(model: &Model, scene: Scene, n: u32, size: u32) -> Vec<Inputs> {
    let ks = (1u32 << model.cfg.b()) - 1;
    let mut v = Vec::new();
    for py in 0..size {
        for px in 0..size {
            let (u, w) = (
                (px as f64 + 0.5) / size as f64,
                (py as f64 + 0.5) / size as f64,
            );
            if let Some((c, _)) = geometry(scene, u, w) {
                v.push(Inputs {
                    cos_g: cos_code(model, c),
                    n,
                    ks: [ks; 3],
                });
            }
        }
    }
    v
}

/// One pixel of a tile: the unit's intensity and Blinn's float `cos^n δ` at the pixel's
/// quantised `cos δ`, both in full scale; `None` off the object.
pub type Sample = Option<(f64, f64)>;

/// The samples of one tile, row-major, `size`² of them.
pub fn samples(model: &Model, scene: Scene, n: u32, size: u32) -> Vec<Sample> {
    let scale = (model.cfg.fi() as f64).exp2();
    let one = (model.cfg.f() as f64).exp2();
    let ks = (1u32 << model.cfg.b()) - 1;
    let mut out = Vec::with_capacity((size * size) as usize);
    for py in 0..size {
        for px in 0..size {
            let (u, w) = (
                (px as f64 + 0.5) / size as f64,
                (py as f64 + 0.5) / size as f64,
            );
            out.push(geometry(scene, u, w).map(|(c, _)| {
                let code = cos_code(model, c);
                let unit = model
                    .eval(Inputs {
                        cos_g: code,
                        n,
                        ks: [ks; 3],
                    })
                    .intensity as f64
                    / scale;
                (unit, (code as f64 / one).powi(n as i32))
            }));
        }
    }
    out
}

/// Off the object.
const BACKGROUND: [u8; 3] = [38, 44, 64];
/// The sheet around the tiles, and its text.
const PAPER: [u8; 3] = [240, 240, 236];
const INK: [u8; 3] = [20, 20, 24];

/// The specular term alone as a grey level, gamma-encoded (`S^(1/2.2)`) so that a broad
/// highlight (n = 1) is a gradient and not a white disc; a faint floor shows the object.
pub fn shade(s: f64) -> [u8; 3] {
    let v = 14.0 + 241.0 * s.clamp(0.0, 1.0).powf(1.0 / 2.2);
    [v.round() as u8; 3]
}

/// The diverging map of a signed error `e` against the sheet's scale `e_max`: neutral grey at
/// 0, red where the unit is too bright, blue where it is too dark, full hue at `±e_max`.
pub fn diverging(e: f64, e_max: f64) -> [u8; 3] {
    const ZERO: [f64; 3] = [226.0, 226.0, 222.0];
    const BRIGHT: [f64; 3] = [196.0, 28.0, 36.0];
    const DARK: [f64; 3] = [28.0, 72.0, 200.0];
    let t = (e / e_max).clamp(-1.0, 1.0);
    let to = if t >= 0.0 { BRIGHT } else { DARK };
    let t = t.abs();
    [0, 1, 2].map(|i| (ZERO[i] + (to[i] - ZERO[i]) * t).round() as u8)
}

/// What a tile shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Panel {
    /// The unit's intensity (golden model = RTL), [`shade`]d.
    Unit,
    /// Blinn's `cos^n δ` in floating point, [`shade`]d.
    Float,
    /// `unit − float`, signed, on the [`diverging`] map at the sheet's scale.
    Error,
}

/// RGB pixels of one tile from its samples, row-major, 3 bytes a pixel.
pub fn paint(samples: &[Sample], panel: Panel, e_max: f64) -> Vec<u8> {
    samples
        .iter()
        .flat_map(|s| match s {
            None => BACKGROUND,
            Some((unit, exact)) => match panel {
                Panel::Unit => shade(*unit),
                Panel::Float => shade(*exact),
                Panel::Error => diverging(unit - exact, e_max),
            },
        })
        .collect()
}

/// The smallest of 1, 2, 5 × 10^k at least `x` (`floor` when `x` is 0).
pub fn nice_ceiling(x: f64, floor: f64) -> f64 {
    if x <= 0.0 {
        return floor;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|v| *v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// A number to 3 significant digits (`0.4`, `1.87e-5`).
pub fn sig3(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-3..1e4).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let t = format!("{x:.decimals$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        let t = format!("{x:.2e}");
        let (m, e) = t.split_once('e').expect("an exponent");
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        format!("{m}e{e}")
    }
}

/// An RGB canvas that records the text drawn on it (what a reader reads; the tests read it).
pub struct Sheet {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) rgb: Vec<u8>,
    pub(crate) labels: Vec<String>,
}

/// Glyph cell of the bundled 8×8 font (font8x8, public domain), at scale 1.
const GLYPH: u32 = 8;

impl Sheet {
    fn new(width: u32, height: u32) -> Sheet {
        Sheet {
            width,
            height,
            rgb: PAPER.repeat((width * height) as usize),
            labels: Vec::new(),
        }
    }

    fn put(&mut self, x: u32, y: u32, c: [u8; 3]) {
        if x < self.width && y < self.height {
            let i = ((y * self.width + x) * 3) as usize;
            self.rgb[i..i + 3].copy_from_slice(&c);
        }
    }

    fn rect(&mut self, x: u32, y: u32, w: u32, h: u32, c: [u8; 3]) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, c);
            }
        }
    }

    /// Draws `text` with its top left at (x, y), at most `max_w` pixels wide; returns its width.
    fn text(&mut self, x: u32, y: u32, text: &str, scale: u32, max_w: u32) -> u32 {
        use font8x8::UnicodeFonts;
        self.labels.push(text.to_string());
        let mut cx = x;
        for ch in text.chars() {
            if cx + GLYPH * scale > x + max_w {
                break;
            }
            let glyph = font8x8::BASIC_FONTS
                .get(ch)
                .or_else(|| font8x8::GREEK_FONTS.get(ch))
                .or_else(|| font8x8::LATIN_FONTS.get(ch))
                .unwrap_or([0; 8]);
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits >> col & 1 == 1 {
                        self.rect(cx + col * scale, y + row as u32 * scale, scale, scale, INK);
                    }
                }
            }
            cx += GLYPH * scale;
        }
        cx - x
    }

    fn blit(&mut self, x: u32, y: u32, size: u32, tile: &[u8]) {
        for yy in 0..size {
            let src = (yy * size * 3) as usize;
            let dst = (((y + yy) * self.width + x) * 3) as usize;
            self.rgb[dst..dst + (size * 3) as usize]
                .copy_from_slice(&tile[src..src + (size * 3) as usize]);
        }
    }

    /// A horizontal colour bar of `w` pixels, `colour(t)` for t from 0 to 1, with tick labels
    /// `(t, full scale, output codes)` in two rows under it; returns the height used.
    fn bar(
        &mut self,
        x: u32,
        y: u32,
        w: u32,
        title: &str,
        colour: impl Fn(f64) -> [u8; 3],
        ticks: &[(f64, String, String)],
    ) -> u32 {
        self.text(x, y, title, 1, self.width - x);
        let y = y + GLYPH + 4;
        for i in 0..w {
            let c = colour(i as f64 / (w - 1) as f64);
            self.rect(x + i, y, 1, 14, c);
        }
        for (t, scale, codes) in ticks {
            let tx = x + (t * (w - 1) as f64).round() as u32;
            self.rect(tx, y + 14, 1, 4, INK);
            for (row, label) in [scale, codes].into_iter().enumerate() {
                let lw = label.chars().count() as u32 * GLYPH;
                let lx = tx
                    .saturating_sub(lw / 2)
                    .clamp(x, (x + w).saturating_sub(lw));
                self.text(lx, y + 20 + row as u32 * (GLYPH + 2), label, 1, lw);
            }
        }
        GLYPH + 4 + 20 + 2 * GLYPH + 2
    }
}

/// The picture `specgen render` writes and the report shows.
pub struct Picture {
    pub png: Vec<u8>,
    /// every text drawn on it, in drawing order
    pub labels: Vec<String>,
    /// the error colour scale, full scale (`±e_max` is full hue)
    pub e_max: f64,
    /// where each tile is: its row's label, its column's title, its top left corner
    pub tiles: Vec<TilePlace>,
}

/// Where a tile of the sheet is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TilePlace {
    /// `sphere n=16`
    pub row: String,
    /// `float cos^n`, `<model> unit`, `<model> signed error`
    pub column: String,
    pub x: u32,
    pub y: u32,
}

/// A column's name for the unit of `m`: its model, `F/FI` and depth (`blinn 15/15 s41`).
fn unit_name(m: &Model) -> String {
    format!(
        "{} {}/{} s{}",
        m.cfg.model().name(),
        m.cfg.f(),
        m.cfg.fi(),
        m.cfg.stages()
    )
}

/// The sheet: a title; a row per (scene, n), labelled; the columns "float cos^n" and then, per
/// model, "<model>" (its intensity) and "<model> error" (unit − float, signed); under them a
/// colour bar for the shaded tiles and one for the errors, each in full scale and in output
/// codes. Every model's tiles use one error scale, so a model with errors a thousand times
/// smaller shows as neutral beside one that is visibly off.
pub fn picture(models: &[&Model], ns: &[u32], size: u32) -> Picture {
    const GAP: u32 = 4;
    const MARGIN: u32 = 10;
    let scenes = [(Scene::Sphere, "sphere"), (Scene::GrazingPlane, "plane")];
    // every tile's samples first: the error scale is the sheet's
    let rows: Vec<(String, Vec<Vec<Sample>>)> = scenes
        .iter()
        .flat_map(|&(scene, name)| ns.iter().map(move |&n| (scene, name, n)))
        .map(|(scene, name, n)| {
            (
                format!("{name} n={n}"),
                models.iter().map(|m| samples(m, scene, n, size)).collect(),
            )
        })
        .collect();
    let worst = rows
        .iter()
        .flat_map(|r| r.1.iter().flatten().flatten())
        .map(|(u, e)| (u - e).abs())
        .fold(0.0f64, f64::max);
    let fi = models[0].cfg.fi();
    let ulp = (-(fi as f64)).exp2();
    let e_max = nice_ceiling(worst, ulp);
    // each column's title, in two lines
    let mut columns = vec![("float".to_string(), "cos^n")];
    for m in models {
        // which unit: model, F/FI and depth (two units of one model side by side differ here)
        let name = unit_name(m);
        columns.push((name.clone(), "unit"));
        // "signed error" where a tile is wide enough for it
        columns.push((
            name.to_string(),
            if size + GAP >= 12 * GLYPH {
                "signed error"
            } else {
                "error"
            },
        ));
    }
    let label_w = 14 * GLYPH + GAP;
    let body_w = columns.len() as u32 * (size + GAP);
    let subtitle = format!(
        "S alone, gamma 2.2; error = unit - float cos^n, one scale: +/-{}",
        sig3(e_max)
    );
    let intensity_title =
        format!("intensity S: full scale, and below it in output codes (UQ1.{fi})");
    let error_title =
        "signed error unit - float: blue too dark, red too bright; full scale, then ulps";
    let longest = [subtitle.len(), intensity_title.len(), error_title.len()]
        .into_iter()
        .max()
        .unwrap_or(0) as u32;
    let width = (MARGIN * 2 + label_w + body_w).max(MARGIN * 2 + longest * GLYPH);
    let top = MARGIN + 2 * GLYPH + 6 + GLYPH + 10 + 2 * GLYPH + 6;
    let body_h = rows.len() as u32 * (size + GAP);
    let bars_h = 2 * (GLYPH + 4 + 20 + 2 * GLYPH + 2 + 12);
    let height = top + body_h + 8 + bars_h + MARGIN;
    let mut sheet = Sheet::new(width, height);
    let names: Vec<String> = models
        .iter()
        .map(|m| {
            format!(
                "{} (F {}, FI {}, {} stages)",
                m.cfg.model().name(),
                m.cfg.f(),
                m.cfg.fi(),
                m.cfg.stages()
            )
        })
        .collect();
    let title = format!("specular term: {} vs float cos^n", names.join(", "));
    let big = title.chars().count() as u32 * 2 * GLYPH <= width - 2 * MARGIN;
    sheet.text(
        MARGIN,
        MARGIN,
        &title,
        if big { 2 } else { 1 },
        width - 2 * MARGIN,
    );
    sheet.text(
        MARGIN,
        MARGIN + 2 * GLYPH + 6,
        &subtitle,
        1,
        width - 2 * MARGIN,
    );
    let x0 = MARGIN + label_w;
    let y_head = MARGIN + 2 * GLYPH + 6 + GLYPH + 10;
    for (c, (first, second)) in columns.iter().enumerate() {
        sheet.text(x0 + c as u32 * (size + GAP), y_head, first, 1, size + GAP);
        sheet.text(
            x0 + c as u32 * (size + GAP),
            y_head + GLYPH + 2,
            second,
            1,
            size + GAP,
        );
    }
    let mut tiles = Vec::new();
    for (r, (label, per_model)) in rows.iter().enumerate() {
        let y = top + r as u32 * (size + GAP);
        sheet.text(MARGIN, y + size / 2 - GLYPH / 2, label, 1, label_w);
        let mut place = |c: usize, panel: Panel, s: &[Sample], sheet: &mut Sheet| {
            let x = x0 + c as u32 * (size + GAP);
            sheet.blit(x, y, size, &paint(s, panel, e_max));
            tiles.push(TilePlace {
                row: label.clone(),
                column: format!("{} {}", columns[c].0, columns[c].1),
                x,
                y,
            });
        };
        place(0, Panel::Float, &per_model[0], &mut sheet);
        for (i, s) in per_model.iter().enumerate() {
            place(1 + 2 * i, Panel::Unit, s, &mut sheet);
            place(2 + 2 * i, Panel::Error, s, &mut sheet);
        }
    }
    let bar_w = (width - 2 * MARGIN).min(480);
    let mut y = top + body_h + 8;
    let codes = |v: f64| format!("{}", (v * (fi as f64).exp2()).round() as i64);
    y += sheet.bar(
        MARGIN,
        y,
        bar_w,
        &intensity_title,
        shade,
        &[0.0, 0.25, 0.5, 0.75, 1.0].map(|t| (t, sig3(t), codes(t))),
    ) + 12;
    sheet.bar(
        MARGIN,
        y,
        bar_w,
        error_title,
        |t| diverging((2.0 * t - 1.0) * e_max, e_max),
        &[
            (0.0, -e_max),
            (0.25, -e_max / 2.0),
            (0.5, 0.0),
            (0.75, e_max / 2.0),
            (1.0, e_max),
        ]
        .map(|(t, e)| (t, sig3(e), sig3(e / ulp))),
    );
    let description = format!(
        "specgen {} render: rows {}; columns {}; error scale +/-{} full scale",
        crate::emit::VERSION,
        rows.iter()
            .map(|r| r.0.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        columns
            .iter()
            .map(|c| format!("{} {}", c.0, c.1))
            .collect::<Vec<_>>()
            .join(", "),
        sig3(e_max)
    );
    Picture {
        png: png(sheet.width, sheet.height, &sheet.rgb, &description),
        labels: sheet.labels,
        e_max,
        tiles,
    }
}

/// Encodes RGB8 pixels as PNG, with a text chunk describing the picture.
pub fn png(width: u32, height: u32, rgb: &[u8], description: &str) -> Vec<u8> {
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.add_text_chunk("Description".into(), description.into())
            .expect("text chunk");
        let mut w = enc.write_header().expect("PNG header to memory");
        w.write_image_data(rgb).expect("PNG data to memory");
    }
    bytes
}

/// Base64 (RFC 4648), for pictures inlined in the report.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let v = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for i in 0..4 {
            if i <= c.len() {
                s.push(A[(v >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_examples() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }
}

/// What the eye sees of a unit's error in [`Scene::Sphere`]: the sphere at `size`² pixels for
/// each exponent, the unit's intensity at each pixel's quantised `cos δ` against Blinn's float
/// `cos^n δ` at the exact `cos δ` (so the quantisation of `cos_g` counts too).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ImageFigures {
    /// `10·log10(1 / mean squared error)` over every pixel of every tile, dB (capped at 200:
    /// an exact image)
    pub psnr_db: f64,
    /// the largest step between two neighbouring pixels (across or down) of the unit's image
    /// beyond the float image's step there: a band's edge, in full scale
    pub max_step_excess: f64,
}

/// [`ImageFigures`] of `model` over the exponents `ns` at `size`² pixels a tile.
pub fn image_figures(model: &Model, ns: &[u32], size: u32) -> ImageFigures {
    let scale = (model.cfg.fi() as f64).exp2();
    let ks = (1u32 << model.cfg.b()) - 1;
    let (mut squares, mut count, mut step) = (0.0f64, 0u64, 0.0f64);
    for &n in ns {
        // (unit, float) per pixel, row-major; None off the sphere
        let mut px: Vec<Option<(f64, f64)>> = Vec::with_capacity((size * size) as usize);
        for py in 0..size {
            for pxx in 0..size {
                let (u, w) = (
                    (pxx as f64 + 0.5) / size as f64,
                    (py as f64 + 0.5) / size as f64,
                );
                px.push(geometry(Scene::Sphere, u, w).map(|(c, _)| {
                    let unit = model
                        .eval(Inputs {
                            cos_g: cos_code(model, c),
                            n,
                            ks: [ks; 3],
                        })
                        .intensity as f64
                        / scale;
                    (unit, c.powi(n as i32))
                }));
            }
        }
        let s = size as usize;
        for i in 0..px.len() {
            let Some((u, r)) = px[i] else { continue };
            squares += (u - r) * (u - r);
            count += 1;
            let right = (i % s + 1 < s).then(|| px[i + 1]).flatten();
            let down = (i + s < px.len()).then(|| px[i + s]).flatten();
            for (u2, r2) in [right, down].into_iter().flatten() {
                step = step.max((u - u2).abs() - (r - r2).abs());
            }
        }
    }
    let mse = squares / count.max(1) as f64;
    let psnr_db = if mse > 0.0 {
        (10.0 * (1.0 / mse).log10()).min(200.0)
    } else {
        200.0
    };
    ImageFigures {
        psnr_db,
        max_step_excess: step.max(0.0),
    }
}
