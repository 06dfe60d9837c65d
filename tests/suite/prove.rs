//! Issue 38: `specgen prove`, the unit's edge proved for every input sequence (yosys and ABC's
//! pdr, unbounded), and each fault refuted with a counterexample VCD.

use crate::common::*;
use std::path::Path;

fn prove(dir: &Path, trace: &Path) -> std::process::Output {
    specgen().args(["prove", "--edited", "--rtl"]).arg(dir).arg("--trace").arg(trace).output().unwrap()
}

/// `valid` at three depths (combinational, 3, the lean unit's deepest 13) and on the ECP5: out_valid is
/// in_valid delayed by exactly the latency, proved; the output one edge late (the simulation
/// suite's `valid_late` fault) is refuted with a VCD that names the signals.
#[test]
fn the_valid_latency_is_proved_and_a_late_valid_refuted() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let traces = tmp.path().join("late.vcd");
    // an ECP5 unit too: its primitives are black boxes to the proof
    for (name, args) in
        [("v0", &["--stages", "0"][..]), ("v3", &["--stages", "3"]), ("v13", &["--stages", "13"]), ("e4", &["--target", "ecp5", "--stages", "4"])]
    {
        let dir = generate(tmp.path(), name, args);
        let o = prove(&dir, &traces);
        assert!(o.status.success(), "{name}: {}", text(&o));
        assert!(text(&o).contains("proved, unbounded"), "{}", text(&o));
    }
    let dir = generate(tmp.path(), "late", &["--stages", "3"]);
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let late =
        src.replace("assign out_valid = valid_line[2];", "reg valid_late;\nalways @(posedge clk) valid_late <= valid_line[2];\nassign out_valid = valid_late;");
    assert_ne!(late, src);
    std::fs::write(&v, late).unwrap();
    let o = prove(&dir, &traces);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("a property fails") && text(&o).contains("late.vcd"), "{}", text(&o));
    let vcd = std::fs::read_to_string(&traces).unwrap();
    assert!(vcd.contains("$enddefinitions") && vcd.contains("valid_late"), "{vcd}");
}

fn text(o: &std::process::Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}
