//! The unit in the Python HDLs its users write: the Amaranth 0.5 component and the LiteX
//! module `generate` writes beside every unit, each inside a user's top (tb/python/user_top.py:
//! a counter driving the inputs, a pseudo-random producer and consumer), converted to Verilog
//! by the package's own back end and simulated with the unit under Icarus: every result the
//! golden model's for the input accepted in the same order, under back-pressure where the
//! interface has it; a producer one bit wider than the unit is refused at elaboration.

use crate::common::*;
use specgen::config::{Config, Params};
use specgen::models::{Inputs, Model};
use std::path::Path;

const NARROW: &[&str] = &[
    "--n-bits",
    "4",
    "--cos-frac-bits",
    "8",
    "--intensity-frac-bits",
    "8",
    "--color-bits",
    "4",
    "--stages",
    "3",
];

fn python(args: &[&str], dir: &Path) -> std::process::Output {
    output_guarded(
        tool("python3")
            .arg(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/tb/python/user_top.py"
            ))
            .args(args)
            .current_dir(dir),
        "user_top.py",
    )
}

/// The user's top around the unit in `unit` through `kind`'s wrapper, simulated: (inputs
/// accepted, results, cycles a result was held back).
fn simulate(kind: &str, unit: &Path, work: &Path) -> (Vec<Vec<u32>>, Vec<Vec<u32>>, usize) {
    let o = python(
        &[kind, unit.to_str().unwrap(), work.to_str().unwrap()],
        unit,
    );
    assert!(
        o.status.success(),
        "{kind}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let mut sources: Vec<String> = vec![
        work.join("user_tb.v").display().to_string(),
        work.join("user_top.v").display().to_string(),
    ];
    for e in std::fs::read_dir(unit).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "v") {
            sources.push(p.display().to_string());
        }
    }
    let sim = work.join("sim");
    let o = output_guarded(
        tool("iverilog")
            .args(["-g2005", "-o"])
            .arg(&sim)
            .args(&sources),
        "iverilog",
    );
    assert!(
        o.status.success(),
        "{kind}: iverilog: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    // in the unit's directory: its tables are read from there
    let o = output_guarded(tool("vvp").arg(&sim).current_dir(unit), "vvp");
    assert!(
        o.status.success(),
        "{kind}: vvp: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        !text.contains("ERROR") && !text.contains("cannot open"),
        "{kind}: {text}"
    );
    let row = |l: &str| {
        l.split_whitespace()
            .skip(1)
            .map(|x| x.parse().unwrap())
            .collect::<Vec<u32>>()
    };
    let ins = text
        .lines()
        .filter(|l| l.starts_with("I "))
        .map(row)
        .collect();
    let outs = text
        .lines()
        .filter(|l| l.starts_with("O "))
        .map(row)
        .collect();
    (ins, outs, text.lines().filter(|l| *l == "S").count())
}

#[test]
fn the_amaranth_and_litex_wrappers_compute_the_golden_model_in_a_users_design() {
    require_tool("iverilog", "iverilog");
    require_tool("python3", "python3");
    let tmp = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("valid", &[][..]),
        ("ready", &["--interface", "ready", "--tag-bits", "2"][..]),
        (
            "axis",
            &["--interface", "axis", "--tag-bits", "2", "--tlast"][..],
        ),
    ] {
        let mut args = NARROW.to_vec();
        args.extend_from_slice(extra);
        let unit = generate(tmp.path(), name, &args);
        let manifest = unit.join("specular_unit.json");
        let model = Model::new(&Config::new(Params::from_json_file(&manifest).unwrap()).unwrap());
        for kind in ["amaranth", "litex"] {
            let work = tmp.path().join(format!("{name}-{kind}"));
            let (ins, outs, stalls) = simulate(kind, &unit, &work);
            assert!(
                outs.len() > 1000 && ins.len() >= outs.len() && ins.len() - outs.len() <= 8,
                "{name} {kind}: {} in, {} out",
                ins.len(),
                outs.len()
            );
            assert_eq!(
                stalls > 0,
                name != "valid",
                "{name} {kind}: {stalls} cycles of back-pressure"
            );
            for (i, (x, y)) in ins.iter().zip(&outs).enumerate() {
                let o = model.eval(Inputs {
                    cos_g: x[0],
                    n: x[1],
                    ks: [x[2], x[3], x[4]],
                });
                assert_eq!(
                    y,
                    &vec![o.intensity, o.spec[0], o.spec[1], o.spec[2], o.done as u32],
                    "{name} {kind}: result {i} of input {x:?}"
                );
            }
        }
        // a producer one bit wider than the unit: refused at elaboration, naming the field and both widths
        for kind in ["amaranth", "litex"] {
            let o = python(
                &[
                    kind,
                    unit.to_str().unwrap(),
                    tmp.path().join("wrong").to_str().unwrap(),
                    "--wrong-width",
                ],
                &unit,
            );
            let e = String::from_utf8_lossy(&o.stderr);
            assert!(
                !o.status.success(),
                "{name} {kind}: a wrong width elaborated"
            );
            let named = match kind {
                "amaranth" => e.contains("'cos_g': 9") && e.contains("'cos_g': 10"),
                _ => e.contains("field cos_g is 10 bits") && e.contains("but 9"),
            };
            assert!(named, "{name} {kind}: {e}");
        }
    }
}

/// A wrapper whose unit was regenerated with other widths is refused at elaboration, naming the
/// port and both widths.
#[test]
fn a_wrapper_refuses_a_manifest_of_other_widths() {
    require_tool("python3", "python3");
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(tmp.path(), "u", NARROW);
    let wider: Vec<&str> = NARROW
        .iter()
        .map(|a| if *a == "8" { "9" } else { a })
        .collect();
    let other = generate(tmp.path(), "other", &wider);
    std::fs::copy(
        other.join("specular_unit.json"),
        unit.join("specular_unit.json"),
    )
    .unwrap();
    for kind in ["amaranth", "litex"] {
        let o = python(
            &[
                kind,
                unit.to_str().unwrap(),
                tmp.path().join("w").to_str().unwrap(),
            ],
            &unit,
        );
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success()
                && e.contains("port cos_g is ('input', 9) in this wrapper but ('input', 10)"),
            "{kind}: {e}"
        );
    }
}

/// The component through Amaranth's own build: the unit inside a user's top on the iCEBreaker
/// (tb/python/icebreaker_top.py) built by amaranth-boards' `ICEBreakerPlatform` with the open
/// tools to a bitstream, nothing added by hand; the placed design holds the unit (at least the
/// logic cells `synth` places for it beside its serial wrapper's, less that wrapper's registers)
/// and its clock is `synth`'s within the top's own routes (median over the same seeds, at least
/// 90 %; `scripts/bench_amaranth.sh` measures the default unit over twenty seeds).
#[test]
fn the_amaranth_component_builds_an_icebreaker_bitstream_as_synth_places_the_unit() {
    for (t, package) in [
        ("yosys", "yosys"),
        ("nextpnr-ice40", "nextpnr-ice40"),
        ("icepack", "fpga-icestorm"),
        ("python3", "python3"),
    ] {
        require_tool(t, package);
    }
    let tmp = tempfile::tempdir().unwrap();
    let unit = generate(
        tmp.path(),
        "u",
        &[
            "--cos-frac-bits",
            "10",
            "--intensity-frac-bits",
            "10",
            "--stages",
            "6",
            "--clock-mhz",
            "100",
        ],
    );
    let seeds = 3;
    let json = tmp.path().join("synth.json");
    let o = output_guarded(
        specgen()
            .args(["synth", "--dsp", "--seeds", &seeds.to_string(), "--rtl"])
            .arg(&unit)
            .arg("--json")
            .arg(&json),
        "synth",
    );
    assert!(
        o.status.success(),
        "synth: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let synth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let mut fmax = Vec::new();
    let mut cells = 0u64;
    for seed in 1..=seeds {
        let build = tmp.path().join(format!("build{seed}"));
        let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tb/python/icebreaker_top.py");
        let args = [
            script,
            unit.to_str().unwrap(),
            build.to_str().unwrap(),
            "100",
            &seed.to_string(),
        ];
        let o = output_guarded(tool("python3").args(args), "icebreaker_top.py");
        assert!(
            o.status.success(),
            "Amaranth's build: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let bitstream = std::fs::read(build.join("top.bin")).unwrap();
        // an iCE40 bitstream: its synchronisation word, and the UP5K's size
        assert!(
            bitstream.len() > 100_000
                && bitstream.windows(4).any(|w| w == [0x7e, 0xaa, 0x99, 0x7e]),
            "{} bytes",
            bitstream.len()
        );
        let log = std::fs::read_to_string(build.join("top.tim")).unwrap();
        let mhz = log
            .lines()
            .rev()
            .filter_map(|l| l.split("Max frequency for clock 'clk': ").nth(1))
            .next()
            .expect("nextpnr's Fmax");
        fmax.push(mhz.split(' ').next().unwrap().parse::<f64>().unwrap());
        let lc = log
            .lines()
            .find_map(|l| l.split("ICESTORM_LC:").nth(1))
            .expect("nextpnr's utilisation");
        cells = lc.trim().split('/').next().unwrap().trim().parse().unwrap();
    }
    fmax.sort_by(f64::total_cmp);
    let (ours, theirs) = (
        fmax[fmax.len() / 2],
        synth["fmax_route_mhz"].as_f64().unwrap(),
    );
    assert!(
        ours >= 0.9 * theirs,
        "Amaranth's build {ours} MHz (seeds {fmax:?}), synth {theirs} MHz"
    );
    // the unit is all there (a logic cell holds one LUT and one flip-flop: the unit's own, as
    // synth counts them before its wrapper, need that many), and nothing but the top's own cost
    // beside it (its LFSR, boot and a flip-flop or two a result bit, over synth's cells, whose
    // serial wrapper costs more than that)
    let own = |k: &str| synth[k].as_u64().unwrap();
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(unit.join("specular_unit.json")).unwrap())
            .unwrap();
    let out_bits: u64 = m["ports"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["direction"] == "output")
        .map(|p| p["width"].as_u64().unwrap())
        .sum();
    assert!(
        cells >= own("luts").max(own("flip_flops")),
        "the build places {cells} logic cells, the unit alone has {} LUTs, {} flip-flops",
        own("luts"),
        own("flip_flops")
    );
    assert!(
        cells <= own("logic_cells") + 40 + 2 * out_bits,
        "the build places {cells} logic cells, synth {}",
        own("logic_cells")
    );
}
