//! Pictures of the specular term: a sphere and a plane at grazing light, each pixel's
//! `cos δ = N·H` quantised to the unit's `cos_g` port, the unit's intensity beside Blinn's
//! float `cos^n δ` and their difference amplified. [`tiles`] builds the pixels from a golden
//! model; `specgen render` first runs the same vectors through the RTL under the
//! co-simulation harness and renders only when every pixel is bit-identical.

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
    (c * (model.cfg.f() as f64).exp2()).round().min((model.cfg.f() as f64).exp2()) as u32
}

/// Every unit input a tile of `size`² pixels needs (background pixels excluded), in pixel order.
pub fn tile_inputs(model: &Model, scene: Scene, n: u32, size: u32) -> Vec<Inputs> {
    let ks = (1u32 << model.cfg.b()) - 1;
    let mut v = Vec::new();
    for py in 0..size {
        for px in 0..size {
            let (u, w) = ((px as f64 + 0.5) / size as f64, (py as f64 + 0.5) / size as f64);
            if let Some((c, _)) = geometry(scene, u, w) {
                v.push(Inputs { cos_g: cos_code(model, c), n, ks: [ks; 3] });
            }
        }
    }
    v
}

/// What a tile shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Panel {
    /// The unit's intensity (golden model = RTL) over a dim diffuse base.
    Unit,
    /// Blinn's `cos^n δ` in floating point, same base.
    Float,
    /// `|unit − float|`, amplified by [`DIFF_GAIN`], in red.
    Difference,
}

/// The gain of a difference panel.
pub(crate) const DIFF_GAIN: f64 = 8.0;

/// RGB pixels of one tile, row-major, `size`² × 3 bytes.
pub fn tile(model: &Model, scene: Scene, panel: Panel, n: u32, size: u32) -> Vec<u8> {
    let scale = (model.cfg.fi() as f64).exp2();
    let ks = (1u32 << model.cfg.b()) - 1;
    let mut out = Vec::with_capacity((size * size * 3) as usize);
    for py in 0..size {
        for px in 0..size {
            let (u, w) = ((px as f64 + 0.5) / size as f64, (py as f64 + 0.5) / size as f64);
            let rgb = match geometry(scene, u, w) {
                None => [18.0, 18.0, 24.0],
                Some((c, diffuse)) => {
                    let code = cos_code(model, c);
                    let unit = model.eval(Inputs { cos_g: code, n, ks: [ks; 3] }).intensity as f64 / scale;
                    let exact = (code as f64 / (model.cfg.f() as f64).exp2()).powi(n as i32);
                    let base = [40.0 + 60.0 * diffuse, 50.0 + 70.0 * diffuse, 90.0 + 110.0 * diffuse];
                    match panel {
                        Panel::Unit => base.map(|b| b + 255.0 * unit),
                        Panel::Float => base.map(|b| b + 255.0 * exact),
                        Panel::Difference => {
                            let d = ((unit - exact).abs() * DIFF_GAIN).min(1.0);
                            [30.0 + 225.0 * d, 30.0, 30.0]
                        }
                    }
                }
            };
            out.extend(rgb.map(|x| x.round().clamp(0.0, 255.0) as u8));
        }
    }
    out
}

/// Lays tiles out in a grid (rows of equal length) with 2-pixel gutters.
pub fn grid(rows: &[Vec<Vec<u8>>], size: u32) -> (u32, u32, Vec<u8>) {
    const GUTTER: u32 = 2;
    let cols = rows.iter().map(|r| r.len()).max().unwrap_or(0) as u32;
    let (w, h) = (cols * (size + GUTTER) + GUTTER, rows.len() as u32 * (size + GUTTER) + GUTTER);
    let mut img = vec![235u8; (w * h * 3) as usize];
    for (ry, row) in rows.iter().enumerate() {
        for (cx, t) in row.iter().enumerate() {
            let (x0, y0) = (GUTTER + cx as u32 * (size + GUTTER), GUTTER + ry as u32 * (size + GUTTER));
            for y in 0..size {
                let src = (y * size * 3) as usize;
                let dst = (((y0 + y) * w + x0) * 3) as usize;
                img[dst..dst + (size * 3) as usize].copy_from_slice(&t[src..src + (size * 3) as usize]);
            }
        }
    }
    (w, h, img)
}

/// Encodes RGB8 pixels as PNG, with a text chunk describing the picture.
pub fn png(width: u32, height: u32, rgb: &[u8], description: &str) -> Vec<u8> {
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.add_text_chunk("Description".into(), description.into()).expect("text chunk");
        let mut w = enc.write_header().expect("PNG header to memory");
        w.write_image_data(rgb).expect("PNG data to memory");
    }
    bytes
}

/// The picture `specgen render` writes: one row per n — sphere (unit, float, difference),
/// then the grazing plane (unit, float, difference).
pub fn picture(model: &Model, ns: &[u32], size: u32) -> Vec<u8> {
    let rows: Vec<Vec<Vec<u8>>> = ns
        .iter()
        .map(|&n| {
            let mut row = Vec::new();
            for scene in [Scene::Sphere, Scene::GrazingPlane] {
                for panel in [Panel::Unit, Panel::Float, Panel::Difference] {
                    row.push(tile(model, scene, panel, n, size));
                }
            }
            row
        })
        .collect();
    let (w, h, img) = grid(&rows, size);
    let description = format!(
        "specgen {} {} model: rows n = {:?}; columns: sphere (unit, float cos^n, |difference| x{DIFF_GAIN}), grazing plane (unit, float cos^n, |difference| x{DIFF_GAIN})",
        crate::emit::VERSION,
        model.cfg.model().name(),
        ns
    );
    png(w, h, &img, &description)
}

/// Base64 (RFC 4648), for pictures inlined in the report.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let v = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
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
        for (i, o) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foob", "Zm9vYg=="), ("fooba", "Zm9vYmE="), ("foobar", "Zm9vYmFy")] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }
}
