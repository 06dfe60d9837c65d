//! What `prove` refuses to be handed, before anything is proved: ports the manifest does not
//! name (the same port check as `cosim` and `synth`), an input the unit drives, a second clock
//! or a latch, a module named like a harness module or a stray file, formal regions that change
//! what is built; and an assumption in the unit, which is removed, never trusted.

use crate::common::*;
use crate::prove::{text, NARROW_READY};
use std::path::Path;

#[test]
fn prove_refuses_ports_the_manifest_does_not_name() {
    let tmp = tempfile::tempdir().unwrap();
    let narrow = [
        "--n-bits",
        "4",
        "--cos-frac-bits",
        "8",
        "--intensity-frac-bits",
        "8",
        "--color-bits",
        "4",
        "--stages",
        "2",
    ];
    for (name, from, to, says) in [
        (
            "extra",
            ") (\n",
            ") (\n    output wire        extra,\n",
            "extra is not a port the manifest implies",
        ),
        (
            "wider",
            "input  wire [3:0]  n,",
            "input  wire [4:0]  n,",
            "n is input of 5 bits in the RTL, input of 4 bits by the manifest",
        ),
    ] {
        let unit = generate(tmp.path(), name, &narrow);
        let v = std::fs::read_to_string(unit.join("specular_unit.v")).unwrap();
        assert!(v.contains(from), "{name}: the edit's anchor {from:?}");
        rewrite_sealed(&unit, "specular_unit.v", &v.replacen(from, to, 1));
        let o = output_guarded(specgen().args(["prove", "--rtl"]).arg(&unit), "prove");
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {e}");
        assert!(e.contains(says), "{name}: {e}");
    }
}

/// Narrow units of each interface, small enough to elaborate in a second.
fn narrow(interface: &str) -> Vec<&str> {
    let mut a = vec![
        "--n-bits",
        "4",
        "--cos-frac-bits",
        "8",
        "--intensity-frac-bits",
        "6",
        "--color-bits",
        "4",
        "--stages",
        "2",
    ];
    if interface != "valid" {
        a.extend(["--interface", interface]);
    }
    a
}

/// `prove` (with `flags`) on `unit`: its exit code and everything it said.
fn prove_says(unit: &std::path::Path, flags: &[&str]) -> (Option<i32>, String) {
    let o = output_guarded(
        specgen().arg("prove").args(flags).arg("--rtl").arg(unit),
        "prove",
    );
    (
        o.status.code(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ),
    )
}

/// `unit`'s Verilog with `line` added before the top's `endmodule` (sealed: the manifest lists
/// the new digest, so no `--edited` is needed and the check under test is the one that speaks).
fn add_line(unit: &std::path::Path, line: &str) {
    let v = std::fs::read_to_string(unit.join("specular_unit.v")).unwrap();
    assert_eq!(v.matches("\nendmodule").count(), 1, "one module");
    rewrite_sealed(
        unit,
        "specular_unit.v",
        &v.replacen("\nendmodule", &format!("\n{line}\nendmodule"), 1),
    );
}

/// Class 1: an input the unit drives ties the harness's free input: refused in every mode,
/// naming the port and bit, for every interface (a reset tied, a clock enable tied, a bit of
/// `n` driven by a register).
#[test]
fn an_input_the_unit_drives_is_refused_naming_it() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str], &str, &str); 4] = [
        (
            "valid",
            &[],
            "assign rst = 1'b0;",
            "the input rst is tied to the constant 0",
        ),
        (
            "ready",
            &["--clock-enable"],
            "assign clk_en = 1'b1;",
            "the input clk_en is tied to the constant 1",
        ),
        (
            "axis",
            &[],
            "assign aresetn = 1'b1;",
            "the input aresetn is tied to the constant 1",
        ),
        (
            "valid",
            &[],
            "reg n_tie = 1'b0; always @(posedge clk) n_tie <= ~n_tie; assign n[2] = n_tie;",
            "the input n[2] is driven by",
        ),
    ];
    for (i, (interface, more, line, says)) in cases.iter().enumerate() {
        let mut args = narrow(interface);
        args.extend(more.iter());
        let unit = generate(tmp.path(), &format!("tied{i}"), &args);
        add_line(&unit, line);
        let mut modes: Vec<&[&str]> = vec![&[]];
        if *interface == "valid" {
            modes.push(&["--pipelining"]);
        } else {
            modes.push(&["--datapath"]);
        }
        for mode in modes {
            let (code, said) = prove_says(&unit, mode);
            assert_eq!(code, Some(2), "{line} {mode:?}: {said}");
            assert!(
                said.contains(says) && said.contains("not a unit a proof can be handed"),
                "{line} {mode:?}: {said}"
            );
        }
    }
}

/// Class 3: one clock, its rising edge: a gated clock, a falling edge and a latch are refused,
/// each naming the cell and what it is (never a raw yosys error, never "proved").
#[test]
fn a_second_clock_a_falling_edge_and_a_latch_are_refused() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            "gated",
            "wire gated_clk = clk & in_valid;\nreg [3:0] gq; always @(posedge gated_clk) gq <= n;\nassign spec_g = gq;",
            "not by the clock port clk: a derived, gated or inverted clock",
        ),
        ("negedge", "reg [3:0] nq; always @(negedge clk) nq <= n;\nassign spec_g = nq;", "clocked on the falling edge of clk"),
        ("latch", "reg [3:0] lq; always @* if (in_valid) lq = n;\nassign spec_g = lq;", "a latch (state held between clock edges): not supported"),
    ];
    for (name, line, says) in cases {
        let unit = generate(tmp.path(), name, &narrow("valid"));
        let v = std::fs::read_to_string(unit.join("specular_unit.v")).unwrap();
        let own = v
            .lines()
            .find(|l| l.starts_with("assign spec_g "))
            .expect("spec_g's assignment")
            .to_string();
        rewrite_sealed(
            &unit,
            "specular_unit.v",
            &v.replacen(&format!("{own}\n"), "", 1).replacen(
                "\nendmodule",
                &format!("\n{line}\nendmodule"),
                1,
            ),
        );
        for mode in [&[][..], &["--pipelining"]] {
            let (code, said) = prove_says(&unit, mode);
            assert_eq!(code, Some(2), "{name} {mode:?}: {said}");
            assert!(said.contains(says), "{name} {mode:?}: {said}");
        }
    }
}

/// Class 2: no stand-ins. A module of the unit named like one of specgen's proof modules is
/// refused in every mode, also where the top does not use it; a `*.v` the manifest does not
/// list is refused by every command that reads the unit, edited or not.
#[test]
fn an_impostor_module_and_a_stray_file_are_refused() {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let impostor = "endmodule\nmodule specular_unit_prove_ports(input wire clk);";
    for (interface, modes) in [
        ("valid", [&[][..], &["--pipelining"]]),
        ("ready", [&[][..], &["--datapath"]]),
    ] {
        let unit = generate(
            tmp.path(),
            &format!("impostor_{interface}"),
            &narrow(interface),
        );
        let v = std::fs::read_to_string(unit.join("specular_unit.v")).unwrap();
        // a second module in the unit's file, unused by its top
        rewrite_sealed(
            &unit,
            "specular_unit.v",
            &v.replacen("\nendmodule", &format!("\n{impostor}\nendmodule"), 1),
        );
        for mode in modes {
            for edited in [&[][..], &["--edited"]] {
                let flags: Vec<&str> = mode.iter().chain(edited).copied().collect();
                let (code, said) = prove_says(&unit, &flags);
                assert_eq!(code, Some(2), "{interface} {flags:?}: {said}");
                assert!(
                    said.contains("takes the name of one of specgen's proof modules"),
                    "{interface} {flags:?}: {said}"
                );
            }
        }
    }
    // a stray file beside a correct unit: named and refused, by prove and cosim alike
    let unit = generate(tmp.path(), "stray", &narrow("valid"));
    std::fs::write(
        unit.join("old_copy.v"),
        "module specular_unit_prove_ports(input wire clk);\nendmodule\n",
    )
    .unwrap();
    for cmd in [
        &["prove"][..],
        &["prove", "--edited"],
        &["cosim", "--vectors", "10"],
    ] {
        let o = output_guarded(specgen().args(cmd).arg("--rtl").arg(&unit), "stray");
        let said = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {said}");
        assert!(
            said.contains("old_copy.v is not a file of this unit"),
            "{cmd:?}: {said}"
        );
    }
}

/// An `assume` in the unit under proof
/// is not honoured. A buffer that drops a result on a stall, with an assumption under
/// `ifdef FORMAL` that the consumer is always ready (so no stall is ever seen), is refuted:
/// only the harness's environment assumptions stay.
#[test]
fn an_assumption_in_the_unit_hides_no_fault() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let args = NARROW_READY;
    let dir = generate(tmp.path(), "hidden", &args);
    let (name, file, from, to) = HANDSHAKE_FAULTS.iter().find(|f| f.0 == "dropped").unwrap();
    apply_handshake_fault(&dir, name, file, from, to);
    let buffer = dir.join(file);
    let src = std::fs::read_to_string(&buffer).unwrap();
    let anchor = "    if (!f_started) assume(rst);";
    assert_eq!(src.matches(anchor).count(), 1);
    std::fs::write(
        &buffer,
        src.replace(anchor, &format!("{anchor}\n    assume(out_ready);")),
    )
    .unwrap();
    let o = specgen()
        .args(["prove", "--edited", "--depth", "12", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "a dropped result hidden by the unit's assume: {}",
        text(&o)
    );
    assert!(
        text(&o).contains("refuted") || text(&o).contains("fails"),
        "{}",
        text(&o)
    );
}

/// The design proved is the one built. Every step reads the unit with
/// one set of macros, and that elaboration is proved equal at the ports to the RTL as synthesis
/// reads it; a unit whose formal regions change a built result (an `` `else `` of `ifdef
/// FORMAL`, a branch where SPECGEN_LEMMAS is undefined, a register's first value) is refused
/// with what differs, exit 1, before any search — here with `--depth 4`, which would otherwise
/// pass a fault that shows only past the search.
#[test]
fn a_unit_whose_formal_regions_change_what_is_built_is_refused() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    // (the generated unit is the built one, and the verdict says so:
    // `a_ready_units_edge_is_proved_with_every_cover_reached`)
    let prove_at = |dir: &Path| {
        specgen()
            .args(["prove", "--edited", "--depth", "4", "--rtl"])
            .arg(dir)
            .output()
            .unwrap()
    };
    let anchor = "assign {out_tag, done, intensity, spec_b, spec_g, spec_r} = out_held;";
    let broken = "assign {out_tag, done, intensity, spec_b, spec_g, spec_r} = out_held ^ 1'b1;";
    let cases = [
        ("else", format!("`ifdef FORMAL\n{anchor}\n`else\n{broken}\n`endif"), "spec_r (bit "),
        ("lemmas", format!("`ifndef SPECGEN_LEMMAS\n{broken}\n`else\n{anchor}\n`endif"), "spec_r (bit "),
        (
            "first value",
            "`ifdef FORMAL\nreg f_fz = 1'b0;\n`else\nreg f_fz = 1'b1;\n`endif\nalways @(posedge clk) f_fz <= f_fz;\nassign {out_tag, done, intensity, spec_b, spec_g, spec_r} = out_held ^ f_fz;".to_string(),
            "f_fz starts at 1'1 built, at 1'0 in the proof",
        ),
    ];
    for (what, text_in, names) in cases {
        let case = generate(tmp.path(), &what.replace(' ', "_"), &NARROW_READY);
        let unit = case.join("specular_unit.v");
        let src = std::fs::read_to_string(&unit).unwrap();
        assert_eq!(src.matches(anchor).count(), 1);
        std::fs::write(&unit, src.replace(anchor, &text_in)).unwrap();
        let o = prove_at(&case);
        assert_eq!(o.status.code(), Some(1), "{what}: {}", text(&o));
        assert!(
            text(&o).contains("is not the one synthesis builds"),
            "{what}: {}",
            text(&o)
        );
        assert!(
            text(&o).contains(names),
            "{what} names what differs ({names}): {}",
            text(&o)
        );
    }
    // a valid unit too, by the default proof and by --pipelining
    let valid = generate(
        tmp.path(),
        "valid",
        &[
            "--cos-frac-bits",
            "8",
            "--n-bits",
            "4",
            "--color-bits",
            "4",
            "--intensity-frac-bits",
            "6",
            "--stages",
            "3",
        ],
    );
    let unit = valid.join("specular_unit.v");
    let src = std::fs::read_to_string(&unit).unwrap();
    let line = src
        .lines()
        .find(|l| l.starts_with("assign spec_r "))
        .expect("spec_r's assignment")
        .to_string();
    let flipped = line.replace("= ", "= ~");
    std::fs::write(
        &unit,
        src.replace(
            &line,
            &format!("`ifdef FORMAL\n{line}\n`else\n{flipped}\n`endif"),
        ),
    )
    .unwrap();
    for flow in [&["prove"][..], &["prove", "--pipelining"]] {
        let o = specgen()
            .args(flow)
            .args(["--edited", "--rtl"])
            .arg(&valid)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{flow:?}: {}", text(&o));
        assert!(
            text(&o).contains("is not the one synthesis builds")
                && text(&o).contains("spec_r (bit "),
            "{flow:?}: {}",
            text(&o)
        );
    }
}
