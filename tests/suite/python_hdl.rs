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

const NARROW: &[&str] = &["--n-bits", "4", "--cos-frac-bits", "8", "--intensity-frac-bits", "8", "--color-bits", "4", "--stages", "3"];

fn python(args: &[&str], dir: &Path) -> std::process::Output {
    output_guarded(tool("python3").arg(concat!(env!("CARGO_MANIFEST_DIR"), "/tb/python/user_top.py")).args(args).current_dir(dir), "user_top.py")
}

/// The user's top around the unit in `unit` through `kind`'s wrapper, simulated: (inputs
/// accepted, results, cycles a result was held back).
fn simulate(kind: &str, unit: &Path, work: &Path) -> (Vec<Vec<u32>>, Vec<Vec<u32>>, usize) {
    let o = python(&[kind, unit.to_str().unwrap(), work.to_str().unwrap()], unit);
    assert!(o.status.success(), "{kind}: {}", String::from_utf8_lossy(&o.stderr));
    let mut sources: Vec<String> = vec![work.join("user_tb.v").display().to_string(), work.join("user_top.v").display().to_string()];
    for e in std::fs::read_dir(unit).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "v") {
            sources.push(p.display().to_string());
        }
    }
    let sim = work.join("sim");
    let o = output_guarded(tool("iverilog").args(["-g2005", "-o"]).arg(&sim).args(&sources), "iverilog");
    assert!(o.status.success(), "{kind}: iverilog: {}", String::from_utf8_lossy(&o.stderr));
    // in the unit's directory: its tables are read from there
    let o = output_guarded(tool("vvp").arg(&sim).current_dir(unit), "vvp");
    assert!(o.status.success(), "{kind}: vvp: {}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(!text.contains("ERROR") && !text.contains("cannot open"), "{kind}: {text}");
    let row = |l: &str| l.split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect::<Vec<u32>>();
    let ins = text.lines().filter(|l| l.starts_with("I ")).map(row).collect();
    let outs = text.lines().filter(|l| l.starts_with("O ")).map(row).collect();
    (ins, outs, text.lines().filter(|l| *l == "S").count())
}

#[test]
fn the_amaranth_and_litex_wrappers_compute_the_golden_model_in_a_users_design() {
    require_tool("iverilog", "iverilog");
    require_tool("python3", "python3");
    let tmp = tempfile::tempdir().unwrap();
    for (name, extra) in
        [("valid", &[][..]), ("ready", &["--interface", "ready", "--tag-bits", "2"][..]), ("axis", &["--interface", "axis", "--tag-bits", "2", "--tlast"][..])]
    {
        let mut args = NARROW.to_vec();
        args.extend_from_slice(extra);
        let unit = generate(tmp.path(), name, &args);
        let manifest = unit.join("specular_unit.json");
        let model = Model::new(&Config::new(Params::from_json_file(&manifest).unwrap()).unwrap());
        for kind in ["amaranth", "litex"] {
            let work = tmp.path().join(format!("{name}-{kind}"));
            let (ins, outs, stalls) = simulate(kind, &unit, &work);
            assert!(outs.len() > 1000 && ins.len() >= outs.len() && ins.len() - outs.len() <= 8, "{name} {kind}: {} in, {} out", ins.len(), outs.len());
            assert_eq!(stalls > 0, name != "valid", "{name} {kind}: {stalls} cycles of back-pressure");
            for (i, (x, y)) in ins.iter().zip(&outs).enumerate() {
                let o = model.eval(Inputs { cos_g: x[0], n: x[1], ks: [x[2], x[3], x[4]] });
                assert_eq!(y, &vec![o.intensity, o.spec[0], o.spec[1], o.spec[2], o.done as u32], "{name} {kind}: result {i} of input {x:?}");
            }
        }
        // a producer one bit wider than the unit: refused at elaboration, naming the field and both widths
        for kind in ["amaranth", "litex"] {
            let o = python(&[kind, unit.to_str().unwrap(), tmp.path().join("wrong").to_str().unwrap(), "--wrong-width"], &unit);
            let e = String::from_utf8_lossy(&o.stderr);
            assert!(!o.status.success(), "{name} {kind}: a wrong width elaborated");
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
    let wider: Vec<&str> = NARROW.iter().map(|a| if *a == "8" { "9" } else { a }).collect();
    let other = generate(tmp.path(), "other", &wider);
    std::fs::copy(other.join("specular_unit.json"), unit.join("specular_unit.json")).unwrap();
    for kind in ["amaranth", "litex"] {
        let o = python(&[kind, unit.to_str().unwrap(), tmp.path().join("w").to_str().unwrap()], &unit);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && e.contains("port cos_g is ('input', 9) in this wrapper but ('input', 10)"), "{kind}: {e}");
    }
}
