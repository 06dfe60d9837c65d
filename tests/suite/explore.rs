//! `specgen explore`, its sweeps on Snakemake, and `generate --max-error`.

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

/// The sweep engine for real: Snakemake on this machine runs a plan's jobs; killed (the whole
/// process group, SIGKILL) after its first result, it leaves no half result and, run again,
/// runs only what is missing; the front it gives is the front of the same jobs run as shards of
/// `specgen measure` by hand and merged.
#[test]
fn a_sweep_on_snakemake_killed_midway_resumes_to_the_same_front() {
    // one seed: a job per point (the seeds' jobs are `explore_writes_every_point_its_front_and_the_sweeps_jobs`'s)
    let explore1 =
        |out: &Path, results: &[&Path], extra: &[&str]| explore_seeds(out, results, extra, "1");
    require_tool("snakemake", "snakemake (pip)");
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let plan = tmp.path().join("plan");
    let o = explore1(&plan, &[], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let jobs: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(plan.join("jobs.json")).unwrap()).unwrap();
    assert!(jobs.len() >= 2, "{}", jobs.len());
    let results = tmp.path().join("results");
    let sweep = |specgen: &Path| {
        let mut c = Command::new("bash");
        c.arg(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/sweep.sh"))
            .arg(plan.join("jobs.json"))
            .arg(&results)
            .args(["--cores", "1", "--quiet"]);
        c.env("SPECGEN", specgen)
            .env("SPECGEN_JOBS", crate::common::jobs());
        c.stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        c
    };
    // the first run, killed midway by its state, not by time: its specgen runs the first job
    // and stalls in the second, and the kill comes once the second has started (one job at a
    // time: the first's result is then whole and the second's not begun)
    let count = tmp.path().join("started");
    let stalling = tmp.path().join("stalling-specgen");
    std::fs::write(
        &stalling,
        format!(
            "#!/bin/bash\nn=$(( $(cat {count:?} 2>/dev/null || echo 0) + 1 )); echo $n > {count:?}\n[ $n -ge 2 ] && exec sleep {}\nexec {:?} \"$@\"\n",
            crate::common::HANG_GUARD_SECS,
            env!("CARGO_BIN_EXE_specgen")
        ),
    )
    .unwrap();
    std::fs::set_permissions(
        &stalling,
        std::os::unix::fs::PermissionsExt::from_mode(0o755),
    )
    .unwrap();
    let mut first = {
        use std::os::unix::process::CommandExt;
        sweep(&stalling).process_group(0).spawn().unwrap()
    };
    wait_until("the sweep's second job", || {
        std::fs::read_to_string(&count).is_ok_and(|n| n.trim() == "2")
    });
    unsafe {
        libc::kill(-(first.id() as i32), libc::SIGKILL);
    }
    finished_within_guard(&mut first, "the killed sweep");
    let done = results_in(&results).len();
    assert!(
        done >= 1 && done < jobs.len(),
        "{done} of {} done when killed",
        jobs.len()
    );
    // every result there is whole (the job writes atomically)
    for r in results_in(&results) {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&r).unwrap()).unwrap();
        assert_eq!(
            r.file_stem().unwrap().to_str().unwrap(),
            v["job"]["fingerprint"].as_str().unwrap()
        );
    }
    let kept: Vec<(PathBuf, std::time::SystemTime)> = results_in(&results)
        .into_iter()
        .map(|p| {
            (
                p.clone(),
                std::fs::metadata(&p).unwrap().modified().unwrap(),
            )
        })
        .collect();
    // resumed: the rest runs, what was done is not run again
    let mut again = sweep(Path::new(env!("CARGO_BIN_EXE_specgen")))
        .spawn()
        .unwrap();
    let status = finished_within_guard(&mut again, "the resumed sweep");
    assert!(status.success());
    assert_eq!(results_in(&results).len(), jobs.len());
    for (p, t) in kept {
        assert_eq!(
            std::fs::metadata(&p).unwrap().modified().unwrap(),
            t,
            "{} was run again",
            p.display()
        );
    }
    // the same jobs as two shards by hand
    let (shard_a, shard_b) = (tmp.path().join("a"), tmp.path().join("b"));
    for (i, j) in jobs.iter().enumerate() {
        let fp = j["fingerprint"].as_str().unwrap();
        let dir = if i % 2 == 0 { &shard_a } else { &shard_b };
        std::fs::create_dir_all(dir).unwrap();
        let o = output_guarded(
            specgen()
                .arg("measure")
                .arg("--jobs")
                .arg(plan.join("jobs.json"))
                .args(["--fingerprint", fp])
                .arg("--out")
                .arg(dir.join(format!("{fp}.json"))),
            "specgen measure",
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    // a shard alone names what it lacks
    let one = tmp.path().join("one");
    let o = explore1(&one, &[&shard_a], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let merge: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(one.join("merge.json")).unwrap()).unwrap();
    assert_eq!(merge["missing"].as_array().unwrap().len(), jobs.len() / 2);
    // both shards, and the resumed sweep: every job measured, the same points and fronts
    let (swept, merged) = (tmp.path().join("swept"), tmp.path().join("merged"));
    assert!(explore1(&swept, &[&results], &[]).status.success());
    assert!(explore1(&merged, &[&shard_a, &shard_b], &[])
        .status
        .success());
    let (ps, pm) = (points(&swept), points(&merged));
    assert_eq!(ps["points"], pm["points"]);
    for p in ps["points"].as_array().unwrap() {
        assert!(p["measured"]["fmax_mhz"].as_f64().unwrap() > 0.0, "{p}");
        assert_eq!(p["measured"]["seeds"], serde_json::json!([1]));
    }
    assert_eq!(
        std::fs::read(swept.join("front.csv")).unwrap(),
        std::fs::read(merged.join("front.csv")).unwrap()
    );
    // each measured point's seeds as one synth result (what `report --hw` and the benches read)
    for p in ps["points"].as_array().unwrap() {
        let id = p["id"].as_str().unwrap();
        let r: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(swept.join("synth").join(format!("{id}.json"))).unwrap(),
        )
        .unwrap();
        assert_eq!(
            (&r["seeds"], &r["fmax_mhz"]),
            (&serde_json::json!([1]), &p["measured"]["fmax_mhz"]),
            "{id}: {r}"
        );
    }
    // a bench's unit, generated and given whole (`explore --unit`), is the same job as the
    // space's point of its parameters: measured from these results, nothing run again
    let first = &ps["points"][0];
    let stages = first["params"]["stages"].to_string();
    let unit = tmp.path().join("unit");
    let o = specgen()
        .args([
            "generate",
            "--n-bits",
            "4",
            "--color-bits",
            "4",
            "--cos-frac-bits",
            "8",
            "--intensity-frac-bits",
            "8",
            "--stages",
            &stages,
            "--out",
        ])
        .arg(&unit)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let given = tmp.path().join("given");
    let o = output_guarded(
        specgen()
            .args(["explore", "--seeds", "1", "--out"])
            .arg(&given)
            .arg("--unit")
            .arg(&unit)
            .arg("--unit")
            .arg(&unit)
            .arg("--results")
            .arg(&results),
        "explore",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let pu = points(&given);
    assert_eq!(
        pu["points"].as_array().unwrap().len(),
        1,
        "one unit given twice is one point: {pu}"
    );
    assert_eq!(
        pu["points"][0]["measured"]["fmax_seeds"], first["measured"]["fmax_seeds"],
        "{pu}"
    );
    let merge: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(given.join("merge.json")).unwrap()).unwrap();
    assert_eq!(merge["missing"].as_array().unwrap().len(), 0, "{merge}");
    // with the products in the fabric, other jobs: none measured yet; a unit of another family
    // is refused, naming the flag
    let o = output_guarded(
        specgen()
            .args(["explore", "--seeds", "1", "--no-dsp", "--out"])
            .arg(tmp.path().join("lut"))
            .arg("--unit")
            .arg(&unit)
            .arg("--results")
            .arg(&results),
        "explore",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let lut_jobs: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("lut/jobs.json")).unwrap())
            .unwrap();
    assert!(
        lut_jobs
            .as_array()
            .unwrap()
            .iter()
            .all(|j| j["dsp"] == false),
        "{lut_jobs}"
    );
    let merge: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("lut/merge.json")).unwrap())
            .unwrap();
    assert_eq!(merge["missing"].as_array().unwrap().len(), 1, "{merge}");
    let o = output_guarded(
        specgen()
            .args(["explore", "--target", "ecp5", "--out"])
            .arg(tmp.path().join("ecp5"))
            .arg("--unit")
            .arg(&unit),
        "explore",
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("--unit") && !tmp.path().join("ecp5").exists(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // a unit whose Verilog is not the one its manifest lists is refused, as by every command
    // (explore measures the unit specgen writes for the manifest's parameters)
    let edited = tmp.path().join("edited");
    std::fs::create_dir(&edited).unwrap();
    for e in std::fs::read_dir(&unit)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_file())
    {
        std::fs::copy(e.path(), edited.join(e.file_name())).unwrap();
    }
    let v = std::fs::read_to_string(edited.join("specular_unit.v")).unwrap();
    std::fs::write(
        edited.join("specular_unit.v"),
        v.replacen("\nendmodule", "\n// edited\nendmodule", 1),
    )
    .unwrap();
    let o = output_guarded(
        specgen()
            .args(["explore", "--out"])
            .arg(tmp.path().join("edited_out"))
            .arg("--unit")
            .arg(&edited),
        "explore",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("invalid --unit")
            && said.contains("is not the file specgen wrote")
            && !tmp.path().join("edited_out").exists(),
        "{said}"
    );
    // shards that overlap merge (identical results are one); all three directories at once
    let all = tmp.path().join("all");
    assert!(explore1(&all, &[&results, &shard_a, &shard_b], &[])
        .status
        .success());
    assert_eq!(points(&all)["points"], ps["points"]);
    // a seed added plans its own jobs only: the results of the others are kept, its are missing
    let other = tmp.path().join("other");
    let o = explore_seeds(&other, &[&results], &[], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let merge: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(other.join("merge.json")).unwrap()).unwrap();
    assert_eq!(merge["missing"].as_array().unwrap().len(), jobs.len());
    // a result renamed is refused, naming it
    let r = results_in(&results)[0].clone();
    std::fs::rename(&r, results.join("00000000000000000000.json")).unwrap();
    let o = explore1(&tmp.path().join("renamed"), &[&results], &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("fingerprint"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `generate --max-error E --target-mhz F` picks a unit that meets its error, checked here
/// exhaustively with the golden model, and whose measured median Fmax (the built-in
/// exploration's, over its seeds) reaches F; refused with the nearest units when none does.
#[test]
fn generate_max_error_picks_a_measured_unit_within_its_error() {
    let tmp = tempfile::tempdir().unwrap();
    // at the pixel: 0.02 is met on both families; 1e-3 (F = 20) only slowly on the UP5K (with
    // --dsp-budget 8) and at the ECP5's deepest, below 100 MHz
    let cases: &[(&str, f64, &[&str])] = &[
        ("0.02", 100.0, &[]),
        ("0.001", 45.0, &[]),
        ("0.02", 200.0, &["--target", "ecp5"]),
    ];
    for (i, &(e, mhz, extra)) in cases.iter().enumerate() {
        let out = tmp.path().join(format!("u{i}"));
        let o = output_guarded(
            specgen()
                .args([
                    "generate",
                    "--max-error",
                    e,
                    "--target-mhz",
                    &mhz.to_string(),
                ])
                .args(extra)
                .arg("--out")
                .arg(&out),
            "generate --max-error",
        );
        assert!(
            o.status.success(),
            "{e} at {mhz}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let said = String::from_utf8_lossy(&o.stderr);
        assert!(
            said.contains("max-error: chose") && said.contains("median over nextpnr seeds"),
            "{said}"
        );
        let params =
            specgen::config::Params::from_json_file(&out.join("specular_unit.json")).unwrap();
        let cfg = specgen::config::Config::new(params).unwrap();
        // the error at the pixel, every code's interval and every n (above 2^26 points a bound,
        // never below the exact figure: SPEC §6)
        let f = specgen::models::blinn_fidelity(&specgen::models::Model::new(&cfg));
        assert!(
            f.pixel.max <= e.parse::<f64>().unwrap(),
            "{e}: the unit's error at the pixel is {}",
            f.pixel.max
        );
        // the clock: the measured median of the exploration's unit that was written (not the
        // figure printed), and no unit of the exploration meets both with fewer cells
        let family = if extra.is_empty() { "ice40" } else { "ecp5" };
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let explored: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(root.join(format!("data/explore/{family}.json"))).unwrap(),
        )
        .unwrap();
        let written: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        let points = explored["points"].as_array().unwrap();
        let same = |p: &&serde_json::Value| {
            p["params"].as_object().unwrap().iter().all(|(k, v)| {
                ["top", "clock_mhz"].contains(&k.as_str()) || written.get(k).is_none_or(|w| w == v)
            })
        };
        let row = points
            .iter()
            .find(same)
            .unwrap_or_else(|| panic!("the unit written is no unit of the exploration: {said}"));
        assert!(
            row["measured"]["fmax_mhz"].as_f64().unwrap() >= mhz,
            "{row}"
        );
        let meets = |p: &&serde_json::Value| {
            p["params"]["interface"] == "valid"
                && p["params"]["n_bits"] == 10
                && p["params"]["color_bits"] == 8
                && p["measured"]["fmax_mhz"].as_f64().is_some_and(|f| f >= mhz)
                && p["accuracy"]["pixel"]["max"]
                    .as_f64()
                    .is_some_and(|x| x <= e.parse::<f64>().unwrap())
        };
        let cheapest = points
            .iter()
            .filter(meets)
            .map(|p| p["measured"]["logic_cells"].as_u64().unwrap())
            .min()
            .unwrap();
        assert_eq!(
            row["measured"]["logic_cells"].as_u64().unwrap(),
            cheapest,
            "{said}"
        );
        // the constraints ask for the clock chosen for
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["clock_mhz"], serde_json::json!(mhz.to_string()));
    }
    // none meets both: refused (exit 2), naming the nearest, nothing written
    let out = tmp.path().join("none");
    let o = output_guarded(
        specgen()
            .args(["generate", "--max-error", "1e-9", "--target-mhz", "100"])
            .arg("--out")
            .arg(&out),
        "generate",
    );
    assert_eq!(o.status.code(), Some(2));
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(
        said.contains("--max-error")
            && said.contains("nearest: ")
            && said.contains("specgen explore --target ice40"),
        "{said}"
    );
    assert!(!out.exists());
}

/// `--interface ready --target-mhz 120` on the UP5K is refused
/// beforehand, naming the output buffer's own paths and the most a handshake unit measured,
/// where it used to pick 13 stages at "129.8 MHz predicted" for a unit that measures 101.7.
#[test]
fn a_handshake_unit_is_not_promised_what_its_buffer_cannot_do() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("u");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--interface",
                "ready",
                "--target-mhz",
                "120",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    assert_eq!(o.status.code(), Some(2));
    let said = String::from_utf8_lossy(&o.stderr);
    // the ceiling is the measured unit's, as the delay model's fit keeps it (its calibration's
    // `ready`/`axis` rows of today's RTL)
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("data/delay_model.json")).unwrap())
            .unwrap();
    let cap = model["handshake"]["ice40"]["lean"]["mhz"]
        .as_f64()
        .expect("a lean handshake unit measured on the UP5K");
    assert!(cap < 120.0 && cap > 95.0, "{cap}");
    assert!(
        said.contains("interface's output buffer has paths of its own")
            && said.contains(&format!("{cap:.1} MHz"))
            && said.contains("on today's RTL"),
        "{said}"
    );
    assert!(!out.exists());
    // a part where no unit with the buffer was measured on today's RTL: refused, saying how to measure one
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "gowin",
                "--interface",
                "ready",
                "--target-mhz",
                "50",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        model["handshake"]["gowin"].is_null(),
        "a ready unit of the GW1NR-9 measured: this refusal no longer holds"
    );
    assert!(
        said.contains("no ready unit was measured on the GW1NR-9")
            && said.contains("specgen explore --target gowin --interface ready"),
        "{said}"
    );
    assert!(!out.exists());
    // below the buffer's measured clock it is picked, and its prediction never above it
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--interface",
                "ready",
                "--target-mhz",
                "95",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
            .unwrap();
    assert!(
        m["predicted_fmax_mhz"].as_f64().unwrap() <= cap,
        "{}",
        m["predicted_fmax_mhz"]
    );
    // the interface is part of the question: an axis unit measured as axis answers, and the
    // evidence printed is of that unit (its interface, its depth)
    for (args, interface) in [
        (&["--max-error", "0.02", "--target-mhz", "90"][..], "axis"),
        (&["--model", "blinn", "--target-mhz", "90"][..], "axis"),
    ] {
        let out = tmp.path().join(format!("edge-{}", args.len()));
        let o = output_guarded(
            specgen()
                .arg("generate")
                .args(args)
                .args(["--interface", interface, "--out"])
                .arg(&out),
            "generate",
        );
        let said = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{said}");
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["interface"], interface, "{m}");
        let id = format!(
            "{}-f{}-fi{}-s{}-n10-c8-",
            m["model"].as_str().unwrap(),
            m["cos_frac_bits"],
            m["intensity_frac_bits"],
            m["stages"]
        );
        assert!(
            said.contains(&id) && said.contains("today's RTL (sha256 "),
            "{id}: {said}"
        );
    }
}

/// A `--dsp-budget` given beside `--max-error` is a ceiling: the choice is the cheapest measured
/// unit taking at most that many blocks, whatever budget (or none) it was measured with, and the
/// unit is written as it was measured (its RTL the measurement's), saying the budget is met.
#[test]
fn a_dsp_budget_beside_max_error_is_a_ceiling() {
    let tmp = tempfile::tempdir().unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let e: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("data/explore/ice40.json")).unwrap(),
    )
    .unwrap();
    let (bound, mhz, budget) = (0.3, 100.0, 6u64);
    // the cheapest by the file's figures, at the default edge and widths N, B
    let meets = |p: &&serde_json::Value| {
        let m = &p["measured"];
        p["params"]["interface"] == "valid"
            && p["params"]["n_bits"] == 10
            && p["params"]["color_bits"] == 8
            && m["fmax_mhz"].as_f64().is_some_and(|f| f >= mhz)
            && m["dsp_blocks"].as_u64().is_some_and(|d| d <= budget)
            && p["accuracy"]["pixel"]["max"]
                .as_f64()
                .is_some_and(|x| x <= bound)
    };
    let cheapest = e["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(meets)
        .map(|p| p["measured"]["logic_cells"].as_u64().unwrap())
        .min();
    let cheapest = cheapest.expect(
        "the built-in exploration holds a unit of at most 6 DSP blocks at 100 MHz within 0.3",
    );
    let out = tmp.path().join("u");
    let args = [
        "--max-error",
        "0.3",
        "--target-mhz",
        "100",
        "--dsp-budget",
        "6",
    ];
    let o = output_guarded(
        specgen().arg("generate").args(args).arg("--out").arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    let cells: u64 = said
        .split(" logic cells")
        .next()
        .unwrap()
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{said}"));
    let blocks: u64 = said
        .split(" DSP blocks")
        .next()
        .unwrap()
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{said}"));
    assert!(
        blocks <= budget && cells == cheapest,
        "{cells} cells, {blocks} blocks; the cheapest meeting both: {cheapest}: {said}"
    );
    assert!(said.contains("--dsp-budget 6 is met"), "{said}");
}

/// The exploration issue's two refusals: a budgeted blinn at 100 MHz on the UP5K and lean's
/// table as logic at 250 MHz on the ECP5 are picked: from measured units of exactly that
/// configuration (median over seeds at or above the clock) where the delay model alone refuses,
/// or by the delay model at a shape it was calibrated at (the budgets 3 and 5 on the UP5K).
#[test]
fn the_refused_cases_are_picked_from_measured_units() {
    let tmp = tempfile::tempdir().unwrap();
    for (i, (args, mhz)) in [
        (&["--model", "blinn", "--dsp-budget", "5"][..], 100.0),
        (&["--target", "ecp5", "--rom-style", "logic"][..], 250.0),
    ]
    .into_iter()
    .enumerate()
    {
        let out = tmp.path().join(format!("u{i}"));
        let o = output_guarded(
            specgen()
                .arg("generate")
                .args(args)
                .args(["--target-mhz", &mhz.to_string(), "--out"])
                .arg(&out),
            "generate",
        );
        let said = String::from_utf8_lossy(&o.stderr);
        if !o.status.success() {
            // refused only where no unit measured on today's RTL reaches it: said so, with the
            // nearest measured unit (or that none is) and the command that would measure it
            assert_eq!(o.status.code(), Some(2), "{args:?}: {said}");
            assert!(
                said.contains("is not assured on the")
                    && said.contains(
                        "no unit of this configuration measured on today's RTL reaches it"
                    ),
                "{said}"
            );
            assert!(
                said.contains("to measure this configuration: specgen generate --stages"),
                "{said}"
            );
            assert!(!out.exists());
            continue;
        }
        // "chose --stages N on the PART: measured: F MHz, …" (a unit of the built-in exploration
        // measured on today's RTL) or "…: interpolated: F MHz by the delay model" at a calibrated
        // shape (the budget is one); never an extrapolation
        let chose = said
            .split("chose --stages ")
            .nth(1)
            .unwrap_or_else(|| panic!("{said}"));
        let (kind, rest) = chose.split_once(": ").unwrap().1.split_once(": ").unwrap();
        let figure: f64 = rest
            .split(' ')
            .next()
            .unwrap()
            .trim_end_matches(',')
            .parse()
            .unwrap_or_else(|_| panic!("{said}"));
        assert!(figure >= mhz, "{said}");
        assert!(kind == "measured" || kind == "interpolated", "{said}");
        let stages: u32 = chose.split(' ').next().unwrap().parse().unwrap();
        let m: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
                .unwrap();
        assert_eq!(m["stages"], stages);
    }
}

/// An exploration's output with its results over seeds (`synth/<id>.json`) is a previous specgen
/// output that the next run replaces: `scripts/explore.sh` runs `explore` again over its own plan
/// when a sweep resumes, and the `synth/` directory made the output guard refuse it.
#[test]
fn an_exploration_with_results_over_seeds_is_replaced_by_the_next_run() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("plan");
    let files = |fmax: &str| -> Vec<(String, Vec<u8>)> {
        let synth = format!("{{\"fmax_mhz\": {fmax}}}\n").into_bytes();
        let sha = <sha2::Sha256 as sha2::Digest>::digest(&synth)
            .iter()
            .map(|x| format!("{x:02x}"))
            .collect::<String>();
        let manifest =
            format!("{{\"generator\": \"specgen\", \"exploration\": \"x\", \"files\": [{{\"name\": \"synth/p-1.json\", \"sha256\": \"{sha}\"}}]}}\n");
        vec![
            ("synth/p-1.json".to_string(), synth),
            ("explore.json".to_string(), manifest.into_bytes()),
        ]
    };
    specgen::output::write_dir_atomically(&dir, &files("100.0")).unwrap();
    specgen::output::write_dir_atomically(&dir, &files("101.0")).unwrap();
    assert_eq!(
        std::fs::read_to_string(dir.join("synth/p-1.json")).unwrap(),
        "{\"fmax_mhz\": 101.0}\n"
    );
    // a subdirectory of the user's is still refused
    std::fs::create_dir(dir.join("mine")).unwrap();
    let e = specgen::output::write_dir_atomically(&dir, &files("102.0"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"mine\", which is not a regular file"), "{e}");
}

/// A tool's failure is no measurement: a nextpnr killed by a signal (the out-of-memory killer,
/// a cluster's preemption) or failing without saying the design does not fit makes `measure`
/// exit 1 and store nothing, so a sweep runs the job again; only nextpnr's own "does not fit"
/// words are stored as such. Two seeds of one unit through `--cache` run yosys once.
#[test]
fn a_killed_tool_is_no_measurement_and_a_units_seeds_synthesize_once() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let plan = tmp.path().join("plan");
    let o = explore(&plan, &[], &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let jobs: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(plan.join("jobs.json")).unwrap()).unwrap();
    let first = jobs[0]["point"].as_str().unwrap().to_string();
    let seeds: Vec<&str> = jobs
        .iter()
        .filter(|j| j["point"] == first.as_str())
        .map(|j| j["fingerprint"].as_str().unwrap())
        .collect();
    assert_eq!(seeds.len(), 2);
    // stand-ins that answer --version as the real tool does (the job's fingerprint names it)
    let stand_in = |name: &str, real: &str, body: &str| -> PathBuf {
        let p = tmp.path().join(name);
        std::fs::write(
            &p,
            format!(
                "#!/bin/bash\ncase \"$1\" in --version|-V) exec {real} \"$@\";; esac\n{body}\n"
            ),
        )
        .unwrap();
        std::fs::set_permissions(&p, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
        p
    };
    let measure = |fp: &str, out: &Path, nextpnr: &Path, yosys: &Path, cache: &Path| {
        output_guarded(
            specgen()
                .arg("measure")
                .arg("--jobs")
                .arg(plan.join("jobs.json"))
                .args(["--fingerprint", fp])
                .arg("--out")
                .arg(out)
                .arg("--nextpnr")
                .arg(nextpnr)
                .arg("--yosys")
                .arg(yosys)
                .arg("--cache")
                .arg(cache),
            "specgen measure",
        )
    };
    let runs = tmp.path().join("yosys-runs");
    let yosys = stand_in(
        "yosys",
        "yosys",
        &format!("echo run >> {runs:?}\nexec yosys \"$@\""),
    );
    let cache = tmp.path().join("cache");
    let out = tmp.path().join("out.json");
    for (name, body, exit) in [
        ("killed", "kill -9 $$", 1),
        ("crashed", "echo 'Info: placing' >&2; exit 3", 1),
        ("full", "echo \"ERROR: Unable to place cell 'x', no BELs remaining to implement cell type 'ICESTORM_DSP'\" >&2; exit 1", 0),
    ] {
        let nextpnr = stand_in(&format!("nextpnr-{name}"), "nextpnr-ice40", body);
        let o = measure(seeds[0], &out, &nextpnr, &yosys, &cache);
        assert_eq!(o.status.code(), Some(exit), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(out.exists(), exit == 0, "{name}: a result stored");
        if exit == 1 {
            let e = String::from_utf8_lossy(&o.stderr);
            assert!(e.contains("no measurement") && e.contains(if name == "killed" { "signal 9" } else { "code 3" }), "{name}: {e}");
        } else {
            let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
            assert!(r["synth"]["fmax_mhz"].is_null(), "{r}");
            std::fs::remove_file(&out).unwrap();
        }
    }
    // the unit was synthesized once (by the first run: the unit, and the unit in its serial
    // wrapper for place-and-route), whatever nextpnr did after; its seeds, through the same
    // cache, synthesize nothing
    let count = || {
        std::fs::read_to_string(&runs)
            .unwrap_or_default()
            .lines()
            .count()
    };
    assert_eq!(count(), 2, "yosys runs for one unit");
    let real = Path::new("nextpnr-ice40");
    for fp in &seeds {
        let o = measure(
            fp,
            &tmp.path().join(format!("{fp}.json")),
            real,
            &yosys,
            &cache,
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    assert_eq!(count(), 2, "yosys runs for the unit's two seeds");
}

/// Every measured row the tool ships (the built-in explorations `generate --max-error` chooses
/// from) is of the RTL this specgen writes: `specgen stale` finds none of an older RTL.
#[test]
fn the_shipped_explorations_are_of_todays_rtl() {
    let o = output_guarded(specgen().arg("stale"), "specgen stale");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.status.success(), "{text}");
    assert!(text.contains("of today's RTL, 0 of an older RTL"), "{text}");
    // the delay model's floors too: each names today's RTL (a row naming none is no floor)
    for part in ["iCE40 UP5K", "ECP5-25 grade 6"] {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("the delay model's calibration on the {part}:")))
            .unwrap_or_else(|| panic!("{text}"));
        assert!(
            line.contains(" 0 of an older RTL") && !line.contains(": 0 floors"),
            "{line}"
        );
    }
    // the library agrees, family by family
    for t in specgen::config::Target::ALL {
        let ev = specgen::explore::calibration_evidence(t).unwrap();
        assert!(ev.stale.is_empty(), "{t:?}: stale floors {:?}", ev.stale);
    }
}

/// `specgen stale` says which rows of an exploration are of an older RTL, and exits 1.
#[test]
fn a_stale_row_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let mut e: serde_json::Value =
        serde_json::from_str(include_str!("../../data/explore/ice40.json")).unwrap();
    let p = &mut e["points"][0];
    let id = p["id"].as_str().unwrap().to_string();
    p["measured"]["jobs"][0] = serde_json::json!("00000000000000000000");
    let file = tmp.path().join("e.json");
    std::fs::write(&file, e.to_string()).unwrap();
    let o = output_guarded(
        specgen().arg("stale").arg("--explored").arg(&file),
        "specgen stale",
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{text}");
    assert!(
        text.contains(&format!("  stale: {id}")) && text.contains("1 of an older RTL"),
        "{text}"
    );
}

/// Inputs that hung the tool or were bounded too late: a points file whose figure is out of
/// range (valid JSON, 1.7e308) is refused before it is drawn; an axis repeated past its bound
/// is refused before anything is computed; a value repeated is one value.
#[test]
fn hostile_explorations_are_refused_before_the_work() {
    let tmp = tempfile::tempdir().unwrap();
    let mut e: serde_json::Value =
        serde_json::from_str(include_str!("../../data/explore/ice40.json")).unwrap();
    e["points"][0]["accuracy"]["max"] = serde_json::json!(1.7e308);
    let file = tmp.path().join("e.json");
    std::fs::write(&file, e.to_string()).unwrap();
    let o = output_guarded(
        specgen()
            .args(["report", "--out"])
            .arg(tmp.path().join("r"))
            .arg("--explored")
            .arg(&file),
        "report",
    );
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("accuracy.max"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!tmp.path().join("r").exists());
    let many = vec!["none"; 10_001].join(",");
    let blinn = vec!["blinn"; 40].join(",");
    for (flag, value) in [
        ("--dsp-budget", many.as_str()),
        ("--models", blinn.as_str()),
    ] {
        let o = output_guarded(
            specgen()
                .args(["explore", "--out"])
                .arg(tmp.path().join("x"))
                .args([flag, value]),
            "explore",
        );
        assert_eq!(o.status.code(), Some(2), "{flag}");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(&format!("invalid {flag}")),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!tmp.path().join("x").exists());
    }
    let (once, twice) = (tmp.path().join("once"), tmp.path().join("twice"));
    assert!(explore(&once, &[], &[]).status.success());
    let o = explore(
        &twice,
        &[],
        &["--cos-frac-bits", "8,8", "--models", "quadratic,quadratic"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(points(&once)["points"], points(&twice)["points"]);
    assert_eq!(
        std::fs::read(once.join("jobs.json")).unwrap(),
        std::fs::read(twice.join("jobs.json")).unwrap()
    );
}

/// One command for a sweep: `explore --run` plans, runs the jobs without a result (on its own
/// slots, or on Snakemake) and merges. Killed midway and run again, it runs only what has no
/// result and gives the front an uninterrupted run gives; a second run measures nothing.
#[test]
fn explore_run_killed_midway_resumes_to_the_same_front() {
    require_tool("yosys", "yosys");
    require_tool("nextpnr-ice40", "nextpnr-ice40");
    let tmp = tempfile::tempdir().unwrap();
    let (store, whole) = (tmp.path().join("store"), tmp.path().join("whole"));
    let run = |out: &Path, store: &Path, extra: &[&str]| {
        let mut c = specgen();
        c.arg("explore")
            .arg("--out")
            .arg(out)
            .args(NARROW)
            .args(["--seeds", "2", "--clocks", "50", "--run", "--run-jobs", "1"])
            .args(extra);
        c.arg("--results").arg(store);
        c
    };
    // killed once its first result is whole
    let mut child = run(&tmp.path().join("a"), &store, &[])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let results = |dir: &Path| -> usize {
        std::fs::read_dir(dir)
            .map(|d| {
                d.flatten()
                    .filter(|e| e.path().extension().is_some_and(|x| x == "json"))
                    .count()
            })
            .unwrap_or(0)
    };
    wait_until("the first result of explore --run", || results(&store) >= 1);
    child.kill().unwrap();
    child.wait().unwrap();
    let jobs: serde_json::Value = {
        let plan = std::fs::read_dir(store.join(".specgen"))
            .unwrap()
            .flatten()
            .find(|e| e.file_name().to_string_lossy().starts_with("jobs-"))
            .unwrap();
        serde_json::from_str(&std::fs::read_to_string(plan.path()).unwrap()).unwrap()
    };
    let n = jobs.as_array().unwrap().len();
    assert!(n >= 4, "{n} jobs");
    assert!(results(&store) < n, "killed midway");
    // run again: only the rest runs, to the end
    let o = output_guarded(
        &mut run(&tmp.path().join("a"), &store, &[]),
        "explore --run, resumed",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    assert!(
        said.contains("with a result already")
            && !said.contains(&format!("0 with a result already, {n} to run")),
        "{said}"
    );
    assert_eq!(results(&store), n);
    // an uninterrupted run (Snakemake this time) draws the same front
    let o = output_guarded(
        &mut run(&tmp.path().join("b"), &whole, &["--engine", "snakemake"]),
        "explore --run on Snakemake",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let front =
        |out: &str| std::fs::read_to_string(tmp.path().join(out).join("front.csv")).unwrap();
    assert_eq!(front("a"), front("b"));
    assert!(front("a").lines().count() > 1, "a front: {}", front("a"));
    // and once more: nothing to run
    let o = output_guarded(
        &mut run(&tmp.path().join("a"), &store, &[]),
        "explore --run, again",
    );
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains(&format!("{n} with a result already, 0 to run")),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `--target-mhz` chooses the options the user did not give as it chooses the depth, from
/// units measured on today's RTL: the ECP5 blinn reaches 250 MHz only with its tables in logic,
/// so without `--rom-style` it is chosen (and said), and with `--rom-style file` the request is
/// refused, naming the measured unit that reaches it.
#[test]
fn target_mhz_chooses_the_options_not_given_from_measured_units() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("free");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "ecp5",
                "--model",
                "blinn",
                "--target-mhz",
                "250",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    assert!(
        said.contains("--rom-style logic on the ECP5-25 grade 6: measured: ")
            && said.contains("today's RTL (sha256 "),
        "{said}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("specular_unit.json")).unwrap())
            .unwrap();
    assert_eq!(m["rom_style"], "logic", "{m}");
    // the figure printed is the measured median of the unit written: its stages are the unit's
    let figure: f64 = said
        .split("measured: ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(figure >= 250.0, "{said}");
    let stages = m["stages"].as_u64().unwrap();
    assert!(
        said.contains(&format!("blinn-f15-fi15-s{stages}-logic")),
        "{said}"
    );
    // the user's own option kept: refused, naming the measured unit that reaches it
    let out = tmp.path().join("kept");
    let o = output_guarded(
        specgen()
            .args([
                "generate",
                "--target",
                "ecp5",
                "--model",
                "blinn",
                "--rom-style",
                "file",
                "--target-mhz",
                "250",
                "--out",
            ])
            .arg(&out),
        "generate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("is not assured on the ECP5-25") && said.contains("--rom-style logic"),
        "{said}"
    );
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
