//! `specgen explore`, its sweeps on Snakemake, and `generate --max-error`.
//! What the choice picks from (`choice`); sweeps interrupted and run again (`sweeps`).

mod choice;
mod sweeps;

use crate::common::{finished_within_guard, output_guarded, require_tool, specgen, wait_until};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A narrow space: quadratic at F = FI = 8, N = B = 4, every point measured ([`explore`]: two
/// seeds).
const NARROW: &[&str] = &[
    "--models",
    "quadratic",
    "--cos-frac-bits",
    "8",
    "--intensity-frac-bits",
    "8",
    "--n-bits",
    "4",
    "--color-bits",
    "4",
    "--measure-all",
];

fn explore(out: &Path, results: &[&Path], extra: &[&str]) -> std::process::Output {
    explore_seeds(out, results, extra, "2")
}

/// [`explore`] of the narrow space over nextpnr seeds 1..=`seeds`.
fn explore_seeds(
    out: &Path,
    results: &[&Path],
    extra: &[&str],
    seeds: &str,
) -> std::process::Output {
    let mut c = specgen();
    c.arg("explore")
        .arg("--out")
        .arg(out)
        .args(NARROW)
        .args(["--seeds", seeds])
        .args(extra);
    for r in results {
        c.arg("--results").arg(r);
    }
    output_guarded(&mut c, "specgen explore")
}

fn points(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("points.json")).unwrap()).unwrap()
}

fn results_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn explore_writes_every_point_its_front_and_the_sweeps_jobs() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    let o = explore(
        &out,
        &[],
        &[
            "--models",
            "quadratic,blinn",
            "--intensity-frac-bits",
            "8,10",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "points.json",
        "points.csv",
        "front.csv",
        "front.svg",
        "jobs.json",
        "merge.json",
        "calibration.csv",
        "explore.json",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let p = points(&out);
    let pts = p["points"].as_array().unwrap();
    // two models, two intensity widths, each at one depth or more
    assert!(pts.len() >= 4, "{}", pts.len());
    for pt in pts {
        let a = &pt["accuracy"];
        // the golden model's figures, exhaustive at these widths
        assert_eq!(a["stride"], 1);
        assert!(a["max"].as_f64().unwrap() >= a["rms"].as_f64().unwrap());
        assert!(a["rms"].as_f64().unwrap() >= a["mean"].as_f64().unwrap());
        assert!(a["psnr_db"].as_f64().unwrap() > 0.0);
    }
    // blinn is far more accurate than the paper's formula
    let max_of = |m: &str| {
        pts.iter()
            .filter(|p| p["model"] == m)
            .map(|p| p["accuracy"]["max"].as_f64().unwrap())
            .fold(0.0, f64::max)
    };
    assert!(max_of("blinn") < max_of("quadratic") / 10.0);
    // every point measured: two seeds each, one job per (point, seed), no result yet
    let jobs: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(out.join("jobs.json")).unwrap()).unwrap();
    assert_eq!(jobs.len(), 2 * pts.len());
    let merge: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("merge.json")).unwrap()).unwrap();
    assert_eq!(merge["missing"].as_array().unwrap().len(), jobs.len());
    let svg = std::fs::read_to_string(out.join("front.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("quadratic") && svg.contains("blinn"));
    // a second run replaces its own output; a user's file beside it stops it
    assert!(explore(&out, &[], &[]).status.success());
    std::fs::write(out.join("mine.txt"), "keep").unwrap();
    let o = explore(&out, &[], &[]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("mine.txt")).unwrap(),
        "keep"
    );
}

#[test]
fn explore_refuses_bad_input_naming_the_flag_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    for (args, flag) in [
        (&["--cos-frac-bits", "99"][..], "--cos-frac-bits"),
        (
            &["--intensity-frac-bits", "99"][..],
            "--intensity-frac-bits",
        ),
        (&["--near", "-1"][..], "--near"),
        (&["--dsp-budget", "lots"][..], "--dsp-budget"),
        (&["--clocks", "0"][..], "--clocks"),
    ] {
        let o = output_guarded(
            specgen().arg("explore").arg("--out").arg(&out).args(args),
            "explore",
        );
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(flag),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!out.exists());
    }
    // results kept inside the output, which is replaced whole, are refused
    let o = output_guarded(
        specgen()
            .arg("explore")
            .arg("--out")
            .arg(&out)
            .arg("--results")
            .arg(out.join("r"))
            .args(NARROW),
        "explore",
    );
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn generate_max_error_needs_a_clock_and_refuses_an_error_out_of_range() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    let o = output_guarded(
        specgen()
            .args(["generate", "--max-error", "0.02"])
            .arg("--out")
            .arg(&out),
        "generate",
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--target-mhz"));
    for e in ["0", "2", "-1"] {
        let o = output_guarded(
            specgen()
                .args(["generate", "--target-mhz", "100", "--max-error", e])
                .arg("--out")
                .arg(&out),
            "generate",
        );
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains("--max-error"),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    assert!(!out.exists());
}

/// `explore --interface` explores units of that interface (their edge is measured with them):
/// every point is an `axis` unit, named so apart from a `valid` one of the same shape, and a
/// `--max-error` refusal for an axis question names the command with `--interface axis`.
#[test]
fn explore_takes_the_interface_the_units_are_measured_with() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("axis");
    let o = output_guarded(
        specgen()
            .arg("explore")
            .arg("--out")
            .arg(&out)
            .args(NARROW)
            .args(["--interface", "axis"]),
        "explore --interface axis",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ps = points(&out);
    let ps = ps["points"].as_array().unwrap();
    assert!(!ps.is_empty());
    for p in ps {
        assert_eq!(p["params"]["interface"], "axis", "{p}");
        assert!(p["id"].as_str().unwrap().ends_with("-axis"), "{}", p["id"]);
    }
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--max-error",
                "0.001",
                "--target-mhz",
                "90",
                "--interface",
                "axis",
                "--out",
            ])
            .arg(tmp.path().join("u")),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("specgen explore --target ice40")
            && said.contains("--interface axis --clocks 90"),
        "{said}"
    );
}
