//! The hard blocks a unit promises (a multiplier's registers, a DSP count) checked on the
//! netlist.

use super::*;

/// Every hard multiplier's registers are checked on the netlist. The narrow
/// schlick unit without stages has SB_MAC16s whose clock is a constant: `synth` names each under
/// `unregistered_blocks` and in its table, and its manifest lists them with why (a unit whose
/// every block keeps its registers is the promise tests' below).
#[test]
fn every_hard_multipliers_registers_are_checked_on_the_netlist() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW;
    let schlick: Vec<&str> = narrow
        .iter()
        .copied()
        .chain(["--model", "schlick", "--stages", "0"])
        .collect();
    let dir = generate(tmp.path(), "schlick", &schlick);
    let json = tmp.path().join("schlick-synth.json");
    let o = specgen()
        .args(["synth", "--no-pnr", "--dsp", "--rtl"])
        .arg(&dir)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let listed: Vec<&str> = r["unregistered_blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_str().unwrap())
        .collect();
    assert!(
        !listed.is_empty() && listed.iter().all(|b| b.starts_with("SB_MAC16 ")),
        "{listed:?}"
    );
    assert!(
        listed.iter().any(|b| b.contains("its clock is a constant")),
        "{listed:?}"
    );
    // the unit says so itself: its manifest lists the products without a register, with why
    // (no promise, so synth succeeds)
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("specular_unit.json")).unwrap())
            .unwrap();
    let own = manifest["unregistered_products"].as_array().unwrap();
    assert!(
        own.iter().any(|p| p["name"] == "den_half"
            && p["why"]
                .as_str()
                .unwrap()
                .contains("no register at the cut after its step")),
        "{own:?}"
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("unregistered") && out.contains("Fmax is an upper bound"),
        "{out}"
    );
}

/// Whether the unit in `dir` promises every hard multiplier a register of its own (its
/// manifest's `unregistered_products` is empty).
fn promised_blocks(dir: &Path) -> Option<bool> {
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("specular_unit.json")).ok()?)
            .ok()?;
    Some(manifest["unregistered_products"].as_array()?.is_empty())
}

/// The netlist's blocks without a register of their own (`synth --no-pnr --dsp`), and whether
/// synth succeeded, for the unit in `dir`.
fn synth_blocks(dir: &Path, json: &Path) -> (bool, Vec<String>, String) {
    let o = specgen()
        .args(["synth", "--no-pnr", "--dsp", "--rtl"])
        .arg(dir)
        .arg("--json")
        .arg(json)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    let listed = std::fs::read_to_string(json)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .map(|r| {
            r["unregistered_blocks"]
                .as_array()
                .unwrap()
                .iter()
                .map(|b| b.as_str().unwrap().to_string())
                .collect()
        })
        .unwrap_or_default();
    (o.status.success(), listed, err)
}

/// Lean, schlick and blinn-pow at their deepest on the iCE40 at 8/6/4/8 bits
/// promise every block its register (their manifests list no `unregistered_products`), and
/// `synth` holds the netlist to it: each passes with none without (fitted and blinn, and the
/// ECP5, are the heavy test's below). The lean unit with one bit of logic between a
/// product and its register (the SHA-256 in its manifest updated, as a tool that rewrites RTL
/// would) fails with exit 1, naming the block and the promise.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn a_block_without_its_promised_register_fails_synth_naming_it() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW;
    let models = ["quadratic", "schlick", "blinn-pow"];
    for_each_parallel(&models, |_, model| {
        let args: Vec<&str> = narrow.iter().copied().chain(["--model", model]).collect();
        let stages = deepest(&args);
        let args: Vec<&str> = args
            .into_iter()
            .chain(["--stages", stages.as_str()])
            .collect();
        let dir = generate(tmp.path(), model, &args);
        assert_eq!(promised_blocks(&dir), Some(true), "{model} at its deepest");
        let (ok, listed, err) = synth_blocks(&dir, &tmp.path().join(format!("{model}.json")));
        assert!(ok && listed.is_empty(), "{model}: {err} {listed:?}");
    });
    // the squarer's product register takes its low bit through an XOR with an input: the
    // block can no longer hold it
    let dir = tmp.path().join("quadratic");
    let v = dir.join("specular_unit.v");
    let text = std::fs::read_to_string(&v).unwrap();
    let line = text
        .lines()
        .find(|l| {
            l.contains("always @(posedge clk) square_full_c")
                || l.contains("always @(posedge clk) kn_c")
        })
        .expect("a product register")
        .to_string();
    let (head, source) = line.rsplit_once(" <= ").unwrap();
    let source = source.trim_end_matches(';');
    let width: u32 = head
        .split('[')
        .nth(1)
        .unwrap()
        .split(':')
        .next()
        .unwrap()
        .parse::<u32>()
        .unwrap()
        + 1;
    let broken = format!("{head} <= {source} ^ {{{}'h0, cos_g[0]}};", width - 1);
    std::fs::write(&v, text.replace(&line, &broken)).unwrap();
    let digest = specgen::bits::sha256_hex(&std::fs::read(&v).unwrap(), 32);
    let mpath = dir.join("specular_unit.json");
    let mut manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&mpath).unwrap()).unwrap();
    for f in manifest["files"].as_array_mut().unwrap() {
        if f["name"] == "specular_unit.v" {
            f["sha256"] = serde_json::Value::String(digest.clone());
        }
    }
    std::fs::write(&mpath, serde_json::to_string_pretty(&manifest).unwrap()).unwrap();
    let o = specgen()
        .args(["synth", "--no-pnr", "--dsp", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("promises every hard multiplier a register of its own")
            && err.contains("SB_MAC16 "),
        "{err}"
    );
}

/// Over the width space: for every model at default, 8/6/4/8 and the wide ECP5
/// wide 18/11/10/18 bits, at
/// its deepest and at half of it on the iCE40 and at its deepest on the ECP5 and the GW1NR-9, the manifest
/// promises every block its register exactly where the netlist has none without (a promise
/// never broken, and never withheld where the netlist would keep it), and synth passes.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_register_promise_matches_the_netlist_over_models_widths_and_families() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW;
    let wide = [
        "--cos-frac-bits",
        "18",
        "--n-bits",
        "11",
        "--color-bits",
        "10",
        "--intensity-frac-bits",
        "18",
    ];
    let mut cases: Vec<(String, Vec<String>, bool)> = Vec::new();
    for model in ["quadratic", "fitted", "blinn", "schlick", "blinn-pow"] {
        for (wname, widths) in [
            ("default", &[][..]),
            ("narrow", &narrow[..]),
            ("wide", &wide[..]),
        ] {
            for (target, half) in [
                ("ice40", false),
                ("ice40", true),
                ("ecp5", false),
                ("gowin", false),
            ] {
                // (yosys 0.23 maps no product to a Gowin block: a product the cuts leave to the tool
                // is LUTs there, so a unit that lists one (blinn-pow's split chain, the wide
                // widths') proves nothing of the rule)
                if target == "gowin" && (model == "blinn-pow" || wname == "wide") {
                    continue;
                }
                let args: Vec<String> = widths
                    .iter()
                    .copied()
                    .chain(["--model", model, "--target", target])
                    .map(String::from)
                    .collect();
                cases.push((
                    format!(
                        "{model}-{wname}-{target}-{}",
                        if half { "half" } else { "deepest" }
                    ),
                    args,
                    half,
                ));
            }
        }
    }
    for_each_parallel(&cases, |_, (name, args, half)| {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let most: u32 = deepest(&a).parse().unwrap();
        let stages = if *half { most / 2 } else { most }.to_string();
        let a: Vec<&str> = a.into_iter().chain(["--stages", stages.as_str()]).collect();
        let dir = generate(tmp.path(), name, &a);
        let promised = promised_blocks(&dir).unwrap();
        let (ok, listed, err) = synth_blocks(&dir, &tmp.path().join(format!("{name}.json")));
        assert!(ok, "{name}: {err}");
        assert_eq!(
            promised,
            listed.is_empty(),
            "{name}: promised {promised}, the netlist's blocks without a register {listed:?}"
        );
    });
}

/// Which units promise every hard block its register (their manifests). At
/// their deepest, the default-width lean, fitted, blinn and schlick units do on the iCE40 (one
/// block a product, each registered whole, read by nothing else in its step), on the ECP5
/// (instantiated MULT18X18Ds) and on the GW1NR-9 (instantiated MULT18X18s); blinn-pow's wide chain (each product over several blocks) does
/// not, and says why; a combinational unit lists every block; generic RTL promises nothing.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_units_that_promise_every_block_its_register() {
    let tmp = tempfile::tempdir().unwrap();
    let listed = |name: &str, model: &str, target: &str, deepest: bool| -> Vec<(String, String)> {
        let args = ["--model", model, "--target", target];
        let stages = if deepest {
            self::deepest(&args)
        } else {
            "0".to_string()
        };
        let args: Vec<&str> = args
            .iter()
            .copied()
            .chain(["--stages", stages.as_str()])
            .collect();
        let dir = generate(tmp.path(), name, &args);
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("specular_unit.json")).unwrap())
                .unwrap();
        let list = manifest["unregistered_products"].as_array().unwrap();
        list.iter()
            .map(|p| {
                (
                    p["name"].as_str().unwrap().to_string(),
                    p["why"].as_str().unwrap().to_string(),
                )
            })
            .collect()
    };
    // one model at a time on each core
    for_each_parallel(
        &["quadratic", "fitted", "blinn", "schlick", "blinn-pow"],
        |_, &model| {
            if model == "blinn-pow" {
                let pow = listed("pow", model, "ice40", true);
                assert!(
                    pow.iter().any(|(_, why)| why.contains("splits it over")),
                    "{pow:?}"
                );
                return;
            }
            for target in ["ice40", "ecp5", "gowin"] {
                assert_eq!(
                    listed(&format!("{model}-{target}"), model, target, true),
                    Vec::new(),
                    "{model} on {target}"
                );
            }
            let none = listed(&format!("{model}-0"), model, "ice40", false);
            assert!(
                !none.is_empty()
                    && none
                        .iter()
                        .all(|(_, why)| why.contains("no register at the cut after its step")),
                "{none:?}"
            );
            let generic = listed(&format!("{model}-generic"), model, "generic", true);
            assert!(
                !generic.is_empty()
                    && generic
                        .iter()
                        .all(|(_, why)| why.contains("generic maps it without registers")),
                "{generic:?}"
            );
        },
    );
}
