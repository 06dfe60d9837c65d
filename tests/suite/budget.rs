//! `--dsp-budget N`. The generator keeps at most N hard multiplier blocks
//! (its own count, for every model, family and budget), a budget the unit already meets
//! changes no byte, the products it moves to the fabric compute the same values on every
//! input, and the netlist yosys maps holds the promise (`synth` fails a netlist over it).

use crate::common::*;
use specgen::config::{Params, SpecularModel, Target};
use specgen::plan::Plan;

fn blocks(plan: &Plan) -> u32 {
    plan.datapath.product_uses.iter().map(|u| u.blocks).sum()
}

fn plan(model: SpecularModel, target: Target, stages: u32, budget: Option<u32>) -> Plan {
    Plan::from_params(Params {
        model,
        target,
        stages,
        dsp_budget: budget,
        ..Params::default()
    })
    .unwrap()
}

/// Every model on every family, budgets from 0 to its unbudgeted count: the unit's blocks
/// stay within the budget, a larger budget never keeps fewer, and the budget it already meets
/// changes neither the datapath nor its registers.
#[test]
fn the_blocks_stay_within_every_budget_and_a_met_budget_changes_nothing() {
    for model in SpecularModel::ALL {
        for target in [Target::Ice40, Target::Ecp5, Target::Generic] {
            let free = plan(model, target, 3, None);
            let full = blocks(&free);
            assert!(full > 0, "{model:?} {target:?}: some product is a block");
            let mut last = 0;
            let mut budgets = vec![0, 1, 2, 3, full / 2, full.saturating_sub(1), full];
            budgets.retain(|&b| b <= full);
            budgets.sort();
            budgets.dedup();
            for budget in budgets {
                let p = plan(model, target, 3, Some(budget));
                let b = blocks(&p);
                assert!(
                    b <= budget,
                    "{model:?} {target:?} --dsp-budget {budget}: {b} blocks"
                );
                assert!(
                    b >= last,
                    "{model:?} {target:?}: a larger budget kept fewer blocks ({b} after {last})"
                );
                last = b;
                if budget == 0 {
                    let left = p.datapath.mapped_products();
                    assert_eq!(left, 0, "{model:?} {target:?} --dsp-budget 0: {left} product(s) the family maps left");
                }
            }
            assert_eq!(
                last, full,
                "{model:?} {target:?}: the whole budget keeps every block"
            );
            let met = plan(model, target, 3, Some(full));
            let same = format!("{:?}", free.datapath) == format!("{:?}", met.datapath)
                && free.registered_cuts == met.registered_cuts;
            assert!(
                same,
                "{model:?} {target:?}: --dsp-budget {full} (met) changed the datapath"
            );
        }
    }
}

/// The products a budget moves to the fabric are the golden model's on every input, for every
/// model, at 8/6/4/8 bits and 4 stages (Verilator, exhaustive): the default model on both
/// families' shapes (all of its products moved on the ice40, all but one on the ecp5), each other
/// model on one of them in turn (every model on both: the heavy test below).
#[test]
fn every_model_within_a_dsp_budget_is_right_on_its_whole_input_space() {
    let default = specgen::config::Params::default().model;
    exhaustive_within_budgets(|i, model, family| model == default || i % 2 == family);
}

/// Every model on both families' shapes; outside the suite's budget.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn every_model_within_a_dsp_budget_is_right_on_both_families() {
    exhaustive_within_budgets(|_, _, _| true);
}

/// Co-simulates exhaustively each model (`SpecularModel::ALL`'s `i`-th) on each family's shape
/// (0: ice40 at budget 0, 1: ecp5 at budget 1) that `take` takes.
fn exhaustive_within_budgets(take: impl Fn(usize, SpecularModel, usize) -> bool) {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let mut runs: Vec<Vec<String>> = Vec::new();
    for (i, model) in SpecularModel::ALL.into_iter().enumerate() {
        for (family, (target, budget)) in [("ice40", "0"), ("ecp5", "1")].into_iter().enumerate() {
            if !take(i, model, family) {
                continue;
            }
            let args = [
                "--model",
                model.name(),
                "--target",
                target,
                "--dsp-budget",
                budget,
                "--stages",
                "4",
            ];
            let narrow = NARROW;
            runs.push(args.iter().chain(&narrow).map(|s| s.to_string()).collect());
        }
    }
    for_each_parallel(&runs, |i, args| {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let dir = generate(&tmp.path().join(format!("b{i}")), "u", &args);
        let o = specgen()
            .env("SPECGEN_CACHE_DIR", cache_dir())
            .arg("cosim")
            .arg("--rtl")
            .arg(&dir)
            .arg("--exhaustive")
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(o.status.code(), Some(0), "{args:?}: {text}");
        assert!(
            text.contains(" 0 mismatches") && text.contains("exhaustive"),
            "{args:?}: {text}"
        );
    });
}

/// The promise on the netlist: with `--dsp-budget 1` the narrow lean unit (8/6/8/8 bits, which
/// takes more SB_MAC16s without a budget) maps one, `synth` says so, and the same unit stated to
/// have a budget of 0 (its manifest edited) is refused, naming the block.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_netlist_keeps_the_dsp_budget() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let synth = |dir: &std::path::Path| {
        let json = dir.with_extension("synth.json");
        let o = specgen()
            .args(["synth", "--dsp", "--no-pnr", "--rtl"])
            .arg(dir)
            .arg("--json")
            .arg(&json)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        let dsp = std::fs::read_to_string(&json)
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .and_then(|r| r["dsp_blocks"].as_u64());
        (o.status.code(), text, dsp)
    };
    let narrow = [
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "6",
        "--color-bits",
        "8",
        "--intensity-frac-bits",
        "8",
        "--stages",
        "6",
    ];
    let free = plan_blocks(&narrow);
    assert!(
        free > 1,
        "the narrow lean takes {free} blocks without a budget"
    );
    let mut args = narrow.to_vec();
    args.extend(["--dsp-budget", "1"]);
    let dir = generate(tmp.path(), "lean1", &args);
    let (code, text, dsp) = synth(&dir);
    assert_eq!(code, Some(0), "{text}");
    assert_eq!(dsp, Some(1), "--dsp-budget 1: {text}");
    assert!(
        text.contains("dsp budget     1 blocks (") && text.contains("product(s) in the fabric: "),
        "synth states the budget's cost: {text}"
    );
    // a budget edited into the manifest by hand is no promise of the RTL's: refused before
    // synthesis, never judged; the netlist against a budget it
    // exceeds is `synth::tests::a_netlist_over_the_dsp_budget_is_named`'s
    let manifest = dir.join("specular_unit.json");
    let text = std::fs::read_to_string(&manifest)
        .unwrap()
        .replace("\"dsp_budget\": 1", "\"dsp_budget\": 0");
    std::fs::write(&manifest, text).unwrap();
    let (code, text, _) = synth(&dir);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("edited by hand"), "{text}");
}

/// The blocks the generator counts for the default lean unit with `args`.
fn plan_blocks(args: &[&str]) -> u32 {
    let num = |flag: &str| {
        args.iter()
            .position(|a| *a == flag)
            .map(|i| args[i + 1].parse::<u32>().unwrap())
    };
    let p = Params {
        cos_frac_bits: num("--cos-frac-bits").unwrap(),
        n_bits: num("--n-bits").unwrap(),
        color_bits: num("--color-bits").unwrap(),
        intensity_frac_bits: num("--intensity-frac-bits").unwrap(),
        stages: num("--stages").unwrap(),
        ..Params::default()
    };
    blocks(&Plan::from_params(p).unwrap())
}

/// `--dsp-budget` out of its range is refused naming it (exit 2, nothing written), and a
/// budgeted unit's manifest, given back as `--config`, writes the very same unit.
#[test]
fn the_budget_is_a_parameter_like_the_others() {
    let tmp = tempfile::tempdir().unwrap();
    for bad in ["257", "-1", "x"] {
        let out = tmp.path().join(format!("bad{bad}"));
        let o = specgen()
            .args(["generate", "--dsp-budget", bad, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad}: {err}");
        assert!(
            err.contains("--dsp-budget") && err.contains("0..=256"),
            "{bad}: {err}"
        );
        assert!(!out.exists(), "{bad}: nothing written");
    }
    let a = generate(tmp.path(), "a", &["--dsp-budget", "2", "--stages", "5"]);
    let b = generate(
        tmp.path(),
        "b",
        &["--config", a.join("specular_unit.json").to_str().unwrap()],
    );
    for e in std::fs::read_dir(&a).unwrap().flatten() {
        let name = e.file_name();
        if e.path().is_file() {
            assert_eq!(
                std::fs::read(e.path()).unwrap(),
                std::fs::read(b.join(&name)).unwrap(),
                "{name:?} differs"
            );
        }
    }
    let manifest = std::fs::read_to_string(a.join("specular_unit.json")).unwrap();
    assert!(
        manifest.contains("\"dsp_budget\": 2"),
        "the manifest states the budget"
    );
}
