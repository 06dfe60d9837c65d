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

#[test]
fn render_through_the_rtl_equals_the_model_and_shows_the_difference() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let cache = cache_dir();
    for (name, args) in [("q", &["--stages", "3"][..]), ("b", &["--model", "blinn"][..])] {
        let dir = generate(tmp.path(), name, args);
        let (rtl_png, model_png) = (tmp.path().join(format!("{name}_rtl.png")), tmp.path().join(format!("{name}_model.png")));
        let o = specgen()
            .env("SPECGEN_CACHE_DIR", &cache)
            .args(["render", "--n", "1,16,128", "--size", "32", "--rtl"])
            .arg(&dir)
            .arg("--out")
            .arg(&rtl_png)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stderr).contains("through the RTL"));
        let o = specgen().args(["render", "--model-only", "--n", "1,16,128", "--size", "32", "--rtl"]).arg(&dir).arg("--out").arg(&model_png).output().unwrap();
        assert!(o.status.success());
        assert_eq!(std::fs::read(&rtl_png).unwrap(), std::fs::read(&model_png).unwrap(), "{name}: RTL and model pictures differ");
        // 6 tiles of 32 px and 7 gutters of 2 across, 3 rows down
        let (w, h, px) = decode(&rtl_png);
        assert_eq!((w, h), (6 * 34 + 2, 3 * 34 + 2));
        // the difference tile of the sphere at n = 16 (third tile, second row): red where the
        // unit differs from cos^n — plenty for the paper's quadratic, none for blinn
        let red = (0..32 * 32).filter(|i| {
            let (x, y) = (2 + 2 * 34 + i % 32, 2 + 34 + i / 32);
            let p = (y * w as usize + x) * 3;
            px[p] > 60 && px[p + 1] < 40
        });
        let red = red.count();
        match name {
            "q" => assert!(red > 50, "quadratic difference tile shows {red} red pixels"),
            _ => assert_eq!(red, 0, "blinn should be within one unit everywhere"),
        }
    }
}

#[test]
fn render_refuses_bad_arguments_and_faulty_rtl() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "q", &["--n-bits", "6"]);
    let out = tmp.path().join("x.png");
    for bad in [&["--n", "64"][..], &["--size", "8"][..], &["--n", "1,x"][..]] {
        let o = specgen().args(["render", "--model-only", "--rtl"]).arg(&dir).arg("--out").arg(&out).args(bad).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(!out.exists());
    }
    // intensity rounding broken in the RTL: no picture
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let from = "assign intensity = intensity_s";
    assert_eq!(src.matches(from).count(), 1);
    std::fs::write(&v, src.replace(from, "assign intensity = 16'h1 ^ intensity_s")).unwrap();
    let o = specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .args(["render", "--size", "16", "--n", "1,40", "--rtl"])
        .arg(&dir)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("differs from the golden model"));
    assert!(!out.exists());
}
