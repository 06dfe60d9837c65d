//! What the binary says of itself: each subcommand's flags and complete help, every range once,
//! the models in the registry's order with their deepest depths, the guide quoting the code, and
//! `info --json` for scripts.

use super::*;

/// Each subcommand takes only the parameters it uses; help states ranges from the one table
/// and the exit codes.
#[test]
fn subcommands_take_only_their_parameters_and_help_is_complete() {
    for (cmd, flag) in [
        ("rom", "--stages"),
        ("rom", "--rom-style"),
        ("eval", "--stages"),
        ("eval", "--top"),
        ("report", "--stages"),
        ("report", "--rom-style"),
    ] {
        let o = specgen().args([cmd, flag, "1"]).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{cmd} {flag}: {}", text(&o));
        assert!(
            text(&o).contains("unexpected argument"),
            "{cmd} {flag}: {}",
            text(&o)
        );
    }
    for cmd in ["generate", "rom", "eval", "report"] {
        let o = specgen().args([cmd, "--help"]).output().unwrap();
        let help = text(&o);
        assert!(
            o.status.success() && help.contains("Exit codes: 0 success"),
            "{cmd}: {help}"
        );
        for r in specgen::config::RANGES {
            let flag = format!("--{}", r.name.replace('_', "-"));
            if help.contains(&flag) {
                assert!(
                    help.contains(&format!("[{}..={}, default {}]", r.min, r.max, r.default)),
                    "{cmd} {flag}: range not from the table"
                );
            }
        }
    }
    let o = specgen().args(["generate", "--help"]).output().unwrap();
    for heading in ["Number formats:", "Model:", "RTL:"] {
        assert!(text(&o).contains(heading), "{heading}");
    }
}

/// Each ranged flag states its range once in --help (`--tag-bits` said
/// "[0..=64; default 0] [0..=64, default 0]").
#[test]
fn every_range_is_stated_once_in_help() {
    let o = specgen().args(["generate", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&o.stdout).replace('\n', " ");
    for r in specgen::config::RANGES {
        let range = format!("{}..={}", r.min, r.max);
        let flag = format!("--{} <", r.name.replace('_', "-"));
        let from = help
            .find(&flag)
            .unwrap_or_else(|| panic!("{flag} in --help"));
        let rest = &help[from + flag.len()..];
        let text = &rest[..rest.find("  --").unwrap_or(rest.len())];
        assert_eq!(text.matches(&range).count(), 1, "{flag}: {text}");
    }
}

/// The `--model` values are `SpecularModel::ALL`, in its order (the scripts read the list of
/// models from this message, and the help shows it).
#[test]
fn the_model_flag_lists_every_model_in_the_registrys_order() {
    let o = specgen()
        .args(["generate", "--model", "?"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stderr);
    let names: Vec<&str> = specgen::config::SpecularModel::ALL
        .iter()
        .map(|m| m.name())
        .collect();
    assert!(
        text.contains(&format!("[possible values: {}]", names.join(", "))),
        "{text}"
    );
}

/// What the help texts and the guide quote — each model's deepest
/// `--stages` per target at default widths, every `--rom-style`, the prove engines — is what
/// the code does; a changed depth fails here.
#[test]
fn help_lines_and_the_guide_quote_what_the_code_does() {
    use specgen::config::{Arch, Config, Params, SpecularModel, Target};
    let deepest = |model: SpecularModel, arch: Arch, target: Target| {
        specgen::plan::Plan::new(
            Config::new(Params {
                model,
                arch,
                target,
                ..Params::default()
            })
            .unwrap(),
        )
        .unwrap()
        .cut_points
    };
    // every family, generic last, in the order the help names them
    let targets: Vec<Target> = Target::ALL
        .into_iter()
        .filter(|&t| t != Target::Generic)
        .chain([Target::Generic])
        .collect();
    let families = targets
        .iter()
        .map(|t| t.name())
        .collect::<Vec<_>>()
        .join(" / ");
    let help = String::from_utf8(
        specgen()
            .args(["generate", "--help"])
            .output()
            .unwrap()
            .stdout,
    )
    .unwrap();
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        help.contains(&format!("at default widths {families}:")),
        "generate --help does not name the families {families}"
    );
    let guide =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/GUIDE.md")).unwrap();
    for model in SpecularModel::ALL {
        let archs: &[Arch] = if model.reads("arch") {
            &[Arch::Lean, Arch::Paper]
        } else {
            &[Arch::Lean]
        };
        for &arch in archs {
            let d: Vec<u32> = targets.iter().map(|&t| deepest(model, arch, t)).collect();
            let (help_name, guide_name) = match (model.reads("arch"), arch) {
                (true, Arch::Lean) => ("lean".to_string(), "quadratic (`lean`)".to_string()),
                (true, _) => ("paper".to_string(), "quadratic `--arch paper`".to_string()),
                _ => (model.name().to_string(), model.name().to_string()),
            };
            // the help: "name a/b/c/d" (a depth a target), or "name a" where every target has
            // the same depth
            let each: Vec<String> = d.iter().map(u32::to_string).collect();
            let quoted = if d.iter().all(|&x| x == d[0]) {
                format!("{help_name} {}", d[0])
            } else {
                format!("{help_name} {}", each.join("/"))
            };
            assert!(
                help.contains(&format!("{quoted},")) || help.contains(&format!("{quoted};")),
                "generate --help does not quote {quoted}"
            );
            // the guide's table of depths
            let row = format!("| {guide_name} | {} |", each.join(" | "));
            assert!(guide.contains(&row), "docs/GUIDE.md lacks the row {row}");
        }
    }
    // every ROM style is named in its help line
    let rom = help
        .split("--rom-style <ROM_STYLE>")
        .nth(1)
        .unwrap()
        .split("Possible values")
        .next()
        .unwrap();
    for style in ["file", "case", "logic"] {
        assert!(
            rom.contains(style),
            "--rom-style's help does not name {style}: {rom}"
        );
    }
    // prove: the port checker is proved for every edge (k-induction), searched first; --datapath too
    let prove =
        String::from_utf8(specgen().args(["prove", "--help"]).output().unwrap().stdout).unwrap();
    let prove = prove.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        prove.contains("proved for every edge by k-induction"),
        "{prove}"
    );
    assert!(
        !prove.contains("a bounded search) and its covers"),
        "the port checker is not only a bounded search: {prove}"
    );
    assert!(
        prove.contains("--datapath") && prove.contains("then proved for every edge by k-induction"),
        "{prove}"
    );
    // the help says of which design and what is assumed
    assert!(
        prove.contains("of the design synthesis builds")
            && prove.contains("the unit's own assumes are removed"),
        "{prove}"
    );
    assert!(
        !prove.contains("own assertions set aside"),
        "the first search keeps the unit's assertions: {prove}"
    );
}

/// The deepest `--stages` that `generate --help` lists at default widths, per model and target
/// (and with `--fabric-registers` on the iCE40), are the datapaths' cut points: a change of a
/// datapath that moves them fails here until the help says it.
#[test]
fn the_help_lists_each_models_deepest_stages() {
    let o = specgen().args(["generate", "--help"]).output().unwrap();
    let help = text(&o).split_whitespace().collect::<Vec<_>>().join(" ");
    let listed = |after: &str, name: &str| -> String {
        let rest = help
            .split(after)
            .nth(1)
            .unwrap_or_else(|| panic!("no {after:?} in the help: {help}"));
        rest.split(&format!(" {name} "))
            .nth(1)
            .unwrap_or_else(|| panic!("no {name} after {after:?}"))
            .split([',', ';', ' '])
            .next()
            .unwrap()
            .to_string()
    };
    let models = [
        ("quadratic", "lean"),
        ("fitted", "fitted"),
        ("blinn", "blinn"),
        ("schlick", "schlick"),
    ];
    for (model, name) in models {
        let want: Vec<String> = ["ice40", "ecp5", "gowin", "generic"]
            .iter()
            .map(|t| deepest(&["--model", model, "--target", t]))
            .collect();
        assert_eq!(
            listed("at default widths ice40 / ecp5 / gowin / generic:", name),
            want.join("/"),
            "{model}"
        );
        let fabric = deepest(&["--model", model, "--target", "ice40", "--fabric-registers"]);
        assert_eq!(
            listed("with --fabric-registers on ice40:", name),
            fabric,
            "{model} with --fabric-registers"
        );
    }
}

/// `specgen info --json` tells scripts what they used to scrape from error messages: the models,
/// the targets, and the deepest pipeline of a configuration (the plan's cut points).
#[test]
fn info_tells_scripts_the_models_targets_and_deepest_depth() {
    let o = specgen()
        .args([
            "info",
            "--json",
            "--model",
            "blinn",
            "--target",
            "ecp5",
            "--cos-frac-bits",
            "10",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let models: Vec<&str> = v["models"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    assert_eq!(
        models,
        specgen::config::SpecularModel::ALL
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
    );
    assert_eq!(
        v["targets"].as_array().unwrap().len(),
        specgen::config::Target::ALL.len()
    );
    let cfg = Config::new(specgen::config::Params {
        model: specgen::config::SpecularModel::Blinn,
        target: specgen::config::Target::Ecp5,
        cos_frac_bits: 10,
        ..Default::default()
    })
    .unwrap();
    assert_eq!(
        v["configuration"]["deepest_stages"].as_u64(),
        Some(specgen::plan::Plan::new(cfg).unwrap().cut_points as u64)
    );
}
