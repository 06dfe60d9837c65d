//! `specgen render`: pixels through the RTL equal the golden model's (same PNG bytes), the
//! PNG decodes to the stated layout, bad arguments and a faulty RTL write nothing.

use crate::common::*;

fn decode(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).unwrap();
    (info.width, info.height, buf)
}

/// Pixels of a tile of the decoded sheet at `place`, `size`² RGB triples.
fn tile_pixels(
    px: &[u8],
    width: u32,
    place: &specgen::render::TilePlace,
    size: u32,
) -> Vec<[u8; 3]> {
    (0..size * size)
        .map(|i| {
            let (x, y) = (place.x + i % size, place.y + i / size);
            let p = ((y * width + x) * 3) as usize;
            [px[p], px[p + 1], px[p + 2]]
        })
        .collect()
}

#[test]
fn render_through_the_rtl_equals_the_model_and_shows_the_difference() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let cache = cache_dir();
    let q = generate(tmp.path(), "q", &["--stages", "3"]);
    let b = generate(tmp.path(), "b", &["--model", "blinn"]);
    let (rtl_png, model_png) = (tmp.path().join("rtl.png"), tmp.path().join("model.png"));
    let args = ["render", "--n", "1,16,128", "--size", "32", "--rtl"];
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", &cache)
        .args(args)
        .arg(&q)
        .arg("--rtl")
        .arg(&b)
        .arg("--out")
        .arg(&rtl_png)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        String::from_utf8_lossy(&o.stderr)
            .matches("through the RTL")
            .count(),
        2
    );
    let o = specgen()
        .arg("render")
        .arg("--model-only")
        .args(&args[1..])
        .arg(&q)
        .arg("--rtl")
        .arg(&b)
        .arg("--out")
        .arg(&model_png)
        .output()
        .unwrap();
    assert!(o.status.success());
    assert_eq!(
        std::fs::read(&rtl_png).unwrap(),
        std::fs::read(&model_png).unwrap(),
        "RTL and model pictures differ"
    );

    // the sheet the library draws for the same models is the file, and says what it shows
    let models: Vec<_> = [&q, &b]
        .iter()
        .map(|d| specgen::cosim::Design::load(d).unwrap().plan.model())
        .collect();
    let refs: Vec<_> = models.iter().collect();
    let pic = specgen::render::picture(&refs, &[1, 16, 128], 32);
    assert_eq!(pic.png, std::fs::read(&rtl_png).unwrap());
    // (a 32-pixel tile has room for "error", a wider one for "signed error")
    // each column names its unit: model, F/FI and depth; the title the same in words
    let (qs, bs) = (
        specgen::cosim::Design::load(&q).unwrap().cfg.stages(),
        specgen::cosim::Design::load(&b).unwrap().cfg.stages(),
    );
    for label in [
        format!("quadratic 15/15 s{qs}"),
        format!("blinn 15/15 s{bs}"),
    ] {
        assert!(
            pic.labels.contains(&label),
            "no column {label:?} in {:?}",
            pic.labels
        );
    }
    assert!(
        pic.labels.iter().any(|l| l.contains(&format!(
            "quadratic (F 15, FI 15, {qs} stages), blinn (F 15, FI 15, {bs} stages)"
        ))),
        "{:?}",
        pic.labels
    );
    for label in [
        "float",
        "cos^n",
        "unit",
        "error",
        "sphere n=1",
        "sphere n=16",
        "plane n=128",
    ] {
        assert!(
            pic.labels.iter().any(|l| l == label),
            "no label {label:?} in {:?}",
            pic.labels
        );
    }
    for words in [
        "intensity S: full scale",
        "signed error unit - float: blue too dark, red too bright",
        "32768",
    ] {
        assert!(
            pic.labels.iter().any(|l| l.contains(words)),
            "no label with {words:?} in {:?}",
            pic.labels
        );
    }
    // one error scale: (15) is off by up to 0.4 of full scale, so +/-0.5
    assert_eq!(pic.e_max, 0.5);
    assert!(
        pic.labels.iter().any(|l| l.ends_with("+/-0.5")),
        "{:?}",
        pic.labels
    );
    // 5 columns (float, then unit and error per model), 6 rows (2 scenes x 3 n)
    assert_eq!(pic.tiles.len(), 5 * 6);

    // the signed error tiles: red and blue rings for (15) at n = 16, none for blinn
    let (w, _, px) = decode(&rtl_png);
    let tile = |row: &str, column: &str| {
        let place = pic
            .tiles
            .iter()
            .find(|t| t.row == row && t.column == column)
            .unwrap_or_else(|| panic!("no tile {row} / {column}"));
        tile_pixels(&px, w, place, 32)
    };
    // red minus blue, 0 on the neutral grey (226, 226, 222) of a zero error
    let hue = |p: &[u8; 3]| p[0] as i32 - p[2] as i32 - 4;
    let q1 = tile("sphere n=1", &format!("quadratic 15/15 s{qs} error"));
    assert!(
        q1.iter().filter(|p| hue(p) > 60).count() > 100,
        "(15) is too bright at n = 1: a red disc"
    );
    let q16 = tile("sphere n=16", &format!("quadratic 15/15 s{qs} error"));
    let (red, blue) = (
        q16.iter().filter(|p| hue(p) > 10).count(),
        q16.iter().filter(|p| hue(p) < -10).count(),
    );
    assert!(
        red > 5 && blue > 5,
        "quadratic error tile at n = 16: {red} red, {blue} blue pixels"
    );
    for row in ["sphere n=1", "sphere n=16", "plane n=128"] {
        let b_err = tile(row, &format!("blinn 15/15 s{bs} error"));
        assert!(
            b_err
                .iter()
                .all(|p| hue(p).abs() <= 1 || p == &[38, 44, 64]),
            "blinn's error tile at {row} should be neutral (zero at this scale)"
        );
    }
    // exposure: n = 1 is a gradient, not a white disc
    let unit1 = tile("sphere n=1", &format!("blinn 15/15 s{bs} unit"));
    let greys: std::collections::BTreeSet<u8> = unit1
        .iter()
        .filter(|p| p[0] == p[2])
        .map(|p| p[0])
        .collect();
    assert!(
        greys.len() > 40 && unit1.iter().filter(|p| p[0] == 255).count() < 32,
        "n = 1 should be shaded, not blown out"
    );
}

/// The pixels of a fixed `--model-only` render, hashed: any change to the scenes, the tone
/// curve, the colour maps, the layout or the font shows here (update the hash when a change
/// is meant, after looking at the picture).
#[test]
fn model_only_render_pixels_are_golden() {
    use sha2::Digest;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g.png");
    let o = specgen()
        .args([
            "render",
            "--model-only",
            "--models",
            "quadratic,blinn",
            "--n",
            "1,16",
            "--size",
            "32",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, px) = decode(&out);
    let hash: String = sha2::Sha256::digest(&px)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(
        (w, h, hash.as_str()),
        (GOLDEN.0, GOLDEN.1, GOLDEN.2),
        "the render changed; look at {} and update GOLDEN",
        out.display()
    );
}

const GOLDEN: (u32, u32, &str) = (
    652,
    358,
    "baf69d3aab98679fc3c2d598bd8e261b436ace456fbd6fbc974d7510b492400b",
);

#[test]
fn render_refuses_bad_arguments_and_faulty_rtl() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "q", &["--n-bits", "6"]);
    let out = tmp.path().join("x.png");
    for bad in [
        &["--n", "64"][..],
        &["--size", "8"][..],
        &["--n", "1,x"][..],
    ] {
        let o = specgen()
            .args(["render", "--model-only", "--rtl"])
            .arg(&dir)
            .arg("--out")
            .arg(&out)
            .args(bad)
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(2),
            "{bad:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!out.exists());
    }
    // intensity rounding broken in the RTL: no picture
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let from = "assign intensity = intensity_s";
    assert_eq!(src.matches(from).count(), 1);
    std::fs::write(
        &v,
        src.replace(from, "assign intensity = 16'h1 ^ intensity_s"),
    )
    .unwrap();
    // as it stands the unit is not the file specgen wrote: named before rendering (exit 2)
    let o = specgen()
        .args(["render", "--size", "16", "--n", "1,40", "--rtl"])
        .arg(&dir)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not the file specgen wrote"));
    // the manifest made to list the broken file, as a faulty generator would write it: the
    // simulation shows the difference
    std::fs::write(&v, &src).unwrap();
    rewrite_sealed(
        &dir,
        "specular_unit.v",
        &src.replace(from, "assign intensity = 16'h1 ^ intensity_s"),
    );
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["render", "--size", "16", "--n", "1,40", "--rtl"])
        .arg(&dir)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("differs from the golden model"));
    assert!(!out.exists());
}
