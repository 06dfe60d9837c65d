//! Sweeps that are interrupted, killed or run again: the same front, each unit's seeds
//! synthesized once, a killed tool no measurement.

use super::*;

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

/// Inputs that hung the tool or were bounded too late: a points file whose figure is out of
/// range (valid JSON, 1.7e308) is refused before it is drawn; an axis repeated past its bound
/// is refused before anything is computed; a value repeated is one value.
#[test]
fn hostile_explorations_are_refused_before_the_work() {
    let tmp = tempfile::tempdir().unwrap();
    let mut e: serde_json::Value =
        serde_json::from_str(include_str!("../../../data/explore/ice40.json")).unwrap();
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
