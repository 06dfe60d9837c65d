//! `specgen prove`, the unit's edge proved for every input sequence (yosys and ABC's
//! pdr, unbounded), and each fault refuted with a counterexample VCD.
//! The stream edge's proofs and the port checker: `handshake`.

mod handshake;

use crate::common::*;
use std::path::Path;

/// Narrow widths: F = 8, N = 4, B = 4, FI = 6.
const NARROW: [&str; 8] = [
    "--cos-frac-bits",
    "8",
    "--n-bits",
    "4",
    "--color-bits",
    "4",
    "--intensity-frac-bits",
    "6",
];

/// A `ready` unit with a tag at narrow widths and 2 stages: small enough for a proof in seconds.
pub(crate) const NARROW_READY: [&str; 14] = [
    "--cos-frac-bits",
    "8",
    "--n-bits",
    "4",
    "--color-bits",
    "4",
    "--intensity-frac-bits",
    "6",
    "--interface",
    "ready",
    "--tag-bits",
    "4",
    "--stages",
    "2",
];

fn prove(dir: &Path, trace: &Path) -> std::process::Output {
    specgen()
        .args(["prove", "--edited", "--rtl"])
        .arg(dir)
        .arg("--trace")
        .arg(trace)
        .output()
        .unwrap()
}

/// `valid` at two depths (combinational, 3) and on the ECP5, at narrow widths (the depth, not
/// the widths, is what they vary; default widths, and the lean unit's deepest, 13, are
/// `the_valid_latency_is_proved_at_default_widths`, outside the suite's budget): out_valid is
/// in_valid delayed by exactly the latency, proved; the output one edge late (the simulation
/// suite's `valid_late` fault) is refuted with a VCD that names the signals.
#[test]
fn the_valid_latency_is_proved_and_a_late_valid_refuted() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let traces = tmp.path().join("late.vcd");
    // an ECP5 unit too: its primitives are black boxes to the proof; the 3-stage unit's table is
    // a file the proof reads
    let at = |stages: &'static str, target: &'static str| -> Vec<&'static str> {
        ["--stages", stages, "--target", target]
            .into_iter()
            .chain(NARROW)
            .collect()
    };
    for (name, args) in [
        ("v0", at("0", "ice40")),
        ("v3", at("3", "ice40")),
        ("e4", at("4", "ecp5")),
    ] {
        let dir = generate(tmp.path(), name, &args);
        assert!(
            name != "v3" || dir.join("specular_unit_cos_sp_rom.hex").is_file(),
            "the table is a file"
        );
        let o = prove(&dir, &traces);
        assert!(o.status.success(), "{name}: {}", text(&o));
        assert!(text(&o).contains("proved, unbounded"), "{}", text(&o));
        // not vacuously: the environment reaches a reset and then a result
        assert!(text(&o).contains("its cover (a reset at the first edge, then a result (out_valid high)) reached within"), "{}", text(&o));
    }
    let late: Vec<&str> = ["--stages", "3"].into_iter().chain(NARROW).collect();
    let dir = generate(tmp.path(), "late", &late);
    make_late(&dir);
    let o = prove(&dir, &traces);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("a property fails") && text(&o).contains("late.vcd"),
        "{}",
        text(&o)
    );
    let vcd = std::fs::read_to_string(&traces).unwrap();
    assert!(
        vcd.contains("$enddefinitions") && vcd.contains("valid_late"),
        "{vcd}"
    );
    // a bounded search (`--depth`, over the whole unit: narrow widths) reads sat's verdict, not
    // its exit code (which is 0 either way): a late unit is refuted within 8 edges, with its
    // trace, and the right one is not
    let tiny = [
        "--stages",
        "3",
        "--cos-frac-bits",
        "6",
        "--n-bits",
        "4",
        "--color-bits",
        "3",
        "--intensity-frac-bits",
        "5",
    ];
    let right = generate(tmp.path(), "n3", &tiny);
    let late_narrow = generate(tmp.path(), "n3-late", &tiny);
    make_late(&late_narrow);
    let bounded = |dir: &Path, trace: &Path| {
        specgen()
            .args(["prove", "--edited", "--depth", "8", "--rtl"])
            .arg(dir)
            .arg("--trace")
            .arg(trace)
            .output()
            .unwrap()
    };
    let within = tmp.path().join("late-bounded.vcd");
    let o = bounded(&late_narrow, &within);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("a property fails")
            && std::fs::read_to_string(&within)
                .unwrap()
                .contains("valid_late"),
        "{}",
        text(&o)
    );
    // the failing edge, not the search's depth: the late register has no reset, so its first
    // value after the reset is already free
    assert!(text(&o).contains("fails 1 clock edge into"), "{}", text(&o));
    let o = bounded(&right, &tmp.path().join("n3-bounded.vcd"));
    assert!(
        o.status.success() && text(&o).contains("no property fails within the first 8 clock edges"),
        "{}",
        text(&o)
    );
    assert!(!tmp.path().join("n3-bounded.vcd").exists());
}

/// The 3-stage unit in `dir` with its output one edge late (the simulation suite's
/// `valid_late` fault): `out_valid` through one more register.
fn make_late(dir: &Path) {
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let late =
        src.replace("assign out_valid = valid_line[2];", "reg valid_late;\nalways @(posedge clk) valid_late <= valid_line[2];\nassign out_valid = valid_late;");
    assert_ne!(late, src);
    std::fs::write(&v, late).unwrap();
}

/// The valid edge at default widths: 3 stages (its table a file the proof reads), the ECP5 at
/// 4, and the lean unit at its deepest, 13: each proved unbounded. Outside the suite's budget.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_valid_latency_is_proved_at_default_widths() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    for (name, args) in [
        ("v3", &["--stages", "3"][..]),
        ("e4", &["--target", "ecp5", "--stages", "4"]),
        ("v13", &["--stages", "13"]),
    ] {
        let dir = generate(tmp.path(), name, args);
        let o = prove(&dir, &tmp.path().join(format!("{name}.vcd")));
        assert!(
            o.status.success() && text(&o).contains("proved, unbounded"),
            "{name}: {}",
            text(&o)
        );
    }
}

pub(crate) fn text(o: &std::process::Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Pipelining changes nothing. lean and fitted at reduced widths, pipelined,
/// equal their depth-0 twins fed the same inputs `stages` edges late for every input sequence
/// (from any state, and from power-up); a register bypassed (a value taken one stage early) is
/// refuted with a VCD; a handshake unit is refused (exit 2).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn pipelining_is_proved_to_change_nothing_and_a_bypassed_register_refuted() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let traces = tmp.path().join("bypass.vcd");
    let prove_pipelining = |dir: &Path| {
        specgen()
            .args(["prove", "--pipelining", "--edited", "--rtl"])
            .arg(dir)
            .arg("--trace")
            .arg(&traces)
            .output()
            .unwrap()
    };
    let lean: &[&str] = &[
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "5",
        "--color-bits",
        "6",
        "--intensity-frac-bits",
        "8",
        "--stages",
        "6",
    ];
    let fitted: &[&str] = &[
        "--model",
        "fitted",
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "5",
        "--color-bits",
        "6",
        "--intensity-frac-bits",
        "8",
        "--stages",
        "4",
    ];
    for (name, args) in [("lean", lean), ("fitted", fitted)] {
        let dir = generate(tmp.path(), name, args);
        let o = prove_pipelining(&dir);
        assert!(o.status.success(), "{name}: {}", text(&o));
        assert!(
            text(&o).contains("proved, unbounded") && text(&o).contains("the depth-0 twin's"),
            "{}",
            text(&o)
        );
    }
    // power3 reads power2 one stage early: the result mixes two pixels
    let dir = tmp.path().join("fitted");
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let line = src
        .lines()
        .find(|l| l.starts_with("wire [") && l.contains("power3_s") && l.contains(": power2_c"))
        .expect("power3's bypass reads a register")
        .to_string();
    let reg = line
        .rsplit(": ")
        .next()
        .unwrap()
        .trim_end_matches(';')
        .to_string();
    let bypassed = line.replace(
        &format!(": {reg};"),
        &format!(": {};", reg.replace("power2_c", "power2_s")),
    );
    assert_ne!(bypassed, line);
    std::fs::write(&v, src.replace(&line, &bypassed)).unwrap();
    let o = prove_pipelining(&dir);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("a property fails") && text(&o).contains("bypass.vcd"),
        "{}",
        text(&o)
    );
    let vcd = std::fs::read_to_string(&traces).unwrap();
    assert!(
        vcd.contains("$enddefinitions")
            && vcd.contains("unit.dut.power2_c")
            && vcd.contains("valid_late"),
        "{vcd}"
    );
    let ready = generate(
        tmp.path(),
        "ready",
        &["--interface", "ready", "--stages", "2"],
    );
    let o = prove_pipelining(&ready);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("invalid --pipelining") && text(&o).contains("--interface valid"),
        "{}",
        text(&o)
    );
}

/// A delay line's tail in RAM keeps words longer than the pipeline, so its
/// module (`<top>_delay_ram`) is proved apart — its contract, from the CUTS-th edge on q is d of
/// CUTS edges before, by induction with the module's lemmas — and the unit, with CUTS flip-flops
/// in the module's place, equals its depth-0 twin. A module whose read address sits one place
/// off, its lemmas deleted, is refuted with a VCD by the contract's search from power-up; one
/// with the lemmas kept, by its own lemma.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn a_delay_line_in_ram_is_proved_apart_and_the_pipeline_with_it() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "--cos-frac-bits",
        "6",
        "--n-bits",
        "4",
        "--color-bits",
        "8",
        "--intensity-frac-bits",
        "6",
        "--stages",
        "11",
    ];
    let dir = generate(tmp.path(), "lean", &args);
    let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
    assert!(
        unit.contains("specular_unit_delay_ram #(.WIDTH(24), .CUTS(8)) waiting_c1_c8_line_ram ("),
        "the colours wait in RAM:\n{unit}"
    );
    let trace = tmp.path().join("contract.vcd");
    let prove = |dir: &Path| {
        specgen()
            .args(["prove", "--pipelining", "--edited", "--rtl"])
            .arg(dir)
            .arg("--trace")
            .arg(&trace)
            .output()
            .unwrap()
    };
    let o = prove(&dir);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("proved, unbounded")
            && text(&o).contains("the delay RAM's contract proved alone (WIDTH = 24, CUTS = 8)")
            && text(&o).contains("the depth-0 twin's"),
        "{}",
        text(&o)
    );
    let module = dir.join("specular_unit_delay_ram.v");
    let src = std::fs::read_to_string(&module).unwrap();
    let next_from = "localparam integer NEXT_FROM_I = (1 << ABITS) + 1 - TRAIL_PLACES;";
    assert!(src.contains(next_from), "{src}");
    let off = src.replace(
        next_from,
        "localparam integer NEXT_FROM_I = (1 << ABITS) + 2 - TRAIL_PLACES;",
    );
    // the lemmas deleted (their ports stay): the contract's search from power-up finds it
    let (from, to) = (
        off.find("// the lemmas that make the contract").unwrap(),
        off.find("`endif\n\nendmodule").unwrap(),
    );
    for (name, edited) in [
        ("lemmas kept", off.clone()),
        ("lemmas deleted", format!("{}{}", &off[..from], &off[to..])),
    ] {
        std::fs::write(&module, &edited).unwrap();
        let _ = std::fs::remove_file(&trace);
        let o = prove(&dir);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
        assert!(
            text(&o).contains("a property fails")
                && text(&o).contains("specular_unit_delay_ram (WIDTH = 24, CUTS = 8) alone"),
            "{name}: {}",
            text(&o)
        );
        let vcd = std::fs::read_to_string(&trace).unwrap();
        assert!(vcd.contains("$enddefinitions"), "{name}: {vcd}");
    }
}

/// Unbounded: the port checker's properties are proved for every edge
/// by an induction whose lemmas are the unit's own assertions, fed the checker's state. A unit
/// whose buffer deadlocks after its 40th pixel, past the bounded search's depth and its covers,
/// with every assertion of its own neutered (`assert(1'b1 || …)`, as many as specgen writes,
/// so its own induction says nothing): before, "proved, unbounded" on its own word and searched
/// at its ports; now undecided (exit 1), never proved; so is one neutered alone. With the lemma
/// port and the lemmas deleted too, the verdict is the ports' bounded search, said to be no
/// proof (exit 0, as `--depth`), never "proved, unbounded".
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn a_unit_whose_lemmas_are_neutered_is_not_proved_past_the_bounded_search() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let args = NARROW_READY;
    // (name, a deadlock after the 40th pixel, the lemma port and lemmas deleted)
    let cases = [
        ("deadlock_after_40", true, false),
        ("neutered_only", false, false),
        ("no_lemma_port", true, true),
    ];
    for_each_parallel(&cases, |_, (name, deadlock, no_port)| {
        let dir = generate(tmp.path(), name, &args);
        for file in ["specular_unit.v", "specular_unit_out_buffer.v"] {
            let path = dir.join(file);
            let mut src = std::fs::read_to_string(&path).unwrap();
            src = src.replace("assert(", "assert(1'b1 || ");
            // (as many empty assertions put back as the lemmas had: the count specgen writes kept)
            let mut deleted = 0;
            while let Some(a) = src.find("`ifdef SPECGEN_LEMMAS").filter(|_| *no_port) {
                let b = a + src[a..].find("`endif").unwrap() + "`endif".len();
                deleted += src[a..b].matches("assert(").count();
                src = format!("{}{}", &src[..a], &src[b..]);
            }
            if deleted > 0 {
                let end = src.rfind("endmodule").unwrap();
                src.insert_str(
                    end,
                    &format!(
                        "`ifdef FORMAL\nalways @(*) begin\n{}end\n`endif\n",
                        "    assert(1'b1);\n".repeat(deleted)
                    ),
                );
            }
            if *deadlock && file.ends_with("buffer.v") {
                let read = "wire                  read = (read_valid ? stored_at_least[2] : stored_at_least[1]) && !queue_full;";
                assert_eq!(src.matches(read).count(), 1);
                src = src.replace(
                    read,
                    "reg  [5:0] taken_count = 6'd0;\nalways @(posedge clk) if (take && taken_count != 6'd63) taken_count <= taken_count + 1'b1;\n\
                     wire                  read = (read_valid ? stored_at_least[2] : stored_at_least[1]) && !queue_full && taken_count < 6'd40;",
                );
            }
            std::fs::write(&path, src).unwrap();
        }
        let o = specgen()
            .args(["prove", "--edited", "--rtl"])
            .arg(&dir)
            .output()
            .unwrap();
        assert!(
            !text(&o).contains("proved, unbounded"),
            "{name}: {}",
            text(&o)
        );
        if *no_port {
            assert!(o.status.success(), "{name}: {}", text(&o));
            assert!(
                text(&o).contains("a bounded search, not a proof")
                    && text(&o).contains("has no lemma port f_ports"),
                "{name}: {}",
                text(&o)
            );
            return;
        }
        assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
        assert!(
            // by its depth (6 edges), never by the time guard
            text(&o).contains(
                "undecided: the port checker's k-induction with the unit's assertions as lemmas"
            ) && text(&o).contains("did not conclude within its depth; so not proved"),
            "{name}: {}",
            text(&o)
        );
    });
}

/// `prove --datapath`, the values a handshake unit delivers are its
/// datapath's. At narrow widths: a ready unit with a static colour and a clock enable is
/// searched to its default depth with every delivered result compared with its depth-0 `valid`
/// twin's, and the compare reached (its cover); a material register that loads at a disabled
/// edge (the outside set's fault: no port rule sees it, only a value does) and a result bit
/// flipped before the buffer are refuted with a VCD; then the unbroken unit is proved for every
/// edge (k-induction, the unit's lemmas placing the followed pixel's result in the buffer), and
/// the bit flipped only from the 40th pixel on, past the search, is undecided, never proved; a
/// `valid` unit is refused (exit 2).
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_delivered_values_are_the_datapaths_and_a_wrong_one_refuted() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = [
        "--cos-frac-bits",
        "6",
        "--n-bits",
        "4",
        "--color-bits",
        "3",
        "--intensity-frac-bits",
        "5",
        "--stages",
        "2",
    ];
    let flags = [
        "--interface",
        "ready",
        "--colour",
        "static",
        "--clock-enable",
        "--tag-bits",
        "2",
    ];
    // (one textual edit each, asserted to apply once: the suite's fault helper)
    let edit = |dir: &Path, file: &str, from: &str, to: &str| {
        apply_handshake_fault(dir, "datapath", file, from, to)
    };
    type Edit<'a> = &'a (dyn Fn(&Path) + Sync);
    let none: Edit = &|_: &Path| {};
    let disabled_load: Edit = &|dir: &Path| {
        edit(
            dir,
            "specular_unit.v",
            "if (ks_load && clk_en)",
            "if (ks_load)",
        )
    };
    // the red result's last bit flipped before the buffer: only a value shows it
    let flipped: Edit = &|dir: &Path| {
        edit(
            dir,
            "specular_unit.v",
            "wire [2:0] spec_r_s10 = color_sum_r_s9[6:4];",
            "wire [2:0] spec_r_s10 = color_sum_r_s9[6:4] ^ 3'd1;",
        )
    };
    // the same bit flipped from the 40th pixel on: past the bounded search, so only the induction
    // can speak of it, and it must not prove it
    let flipped_late: Edit = &|dir: &Path| {
        edit(
            dir,
            "specular_unit.v",
            "wire [2:0] spec_r_s10 = color_sum_r_s9[6:4];",
            "reg  [5:0] taken_count = 6'd0;\nalways @(posedge clk) if (in_take && taken_count != 6'd63) taken_count <= taken_count + 1'b1;\n\
             wire [2:0] spec_r_s10 = color_sum_r_s9[6:4] ^ {2'd0, taken_count >= 6'd40};",
        )
    };
    // (name, edit, the verdict: proved, refuted or undecided)
    let cases: Vec<(&str, Edit, &str)> = vec![
        ("ok", none, "proved"),
        ("disabled_load", disabled_load, "refuted"),
        ("flipped", flipped, "refuted"),
        ("flipped_late", flipped_late, "undecided"),
    ];
    for_each_parallel(&cases, |_, (name, edit, verdict)| {
        let args: Vec<&str> = narrow.iter().chain(flags.iter()).copied().collect();
        let dir = generate(tmp.path(), name, &args);
        edit(&dir);
        let trace = tmp.path().join(format!("{name}.vcd"));
        let o = specgen()
            .args(["prove", "--datapath", "--edited", "--rtl"])
            .arg(&dir)
            .arg("--trace")
            .arg(&trace)
            .output()
            .unwrap();
        if *verdict == "undecided" {
            assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
            // by its depth, never by the time guard
            assert!(
                text(&o).contains("undecided")
                    && text(&o).contains("did not conclude within its depth; so not proved"),
                "{name}: {}",
                text(&o)
            );
            assert!(
                text(&o).contains("the properties hold for the first 13 clock edges"),
                "{name}: {}",
                text(&o)
            );
        } else if *verdict == "refuted" {
            assert_eq!(o.status.code(), Some(1), "{name}: {}", text(&o));
            assert!(
                text(&o).contains("a property fails") && text(&o).contains("the datapath twin"),
                "{name}: {}",
                text(&o)
            );
            assert!(
                std::fs::read_to_string(&trace)
                    .unwrap()
                    .contains("$enddefinitions"),
                "{name}"
            );
            if *name == "disabled_load" {
                // a bounded search of the default proof's kind (`--depth`) runs the colour check too
                let o = specgen()
                    .args(["prove", "--depth", "12", "--edited", "--rtl"])
                    .arg(&dir)
                    .arg("--trace")
                    .arg(&trace)
                    .output()
                    .unwrap();
                assert_eq!(o.status.code(), Some(1), "{name} --depth 12: {}", text(&o));
                assert!(
                    text(&o).contains("the value check"),
                    "{name} --depth 12: {}",
                    text(&o)
                );
            }
        } else {
            assert!(o.status.success(), "{name}: {}", text(&o));
            let t = text(&o);
            assert!(
                t.contains("no property fails within the first 13 clock edges")
                    && t.contains("the n-th result delivered (every output field)"),
                "{t}"
            );
            // and for every edge: the unit's lemmas place the followed pixel's result, the twin's
            assert!(
                t.contains("proved, unbounded") && t.contains("then for every edge: k-induction"),
                "{t}"
            );
            assert!(
                t.contains("a delivered result compared with the twin's"),
                "the cover reached: {t}"
            );
        }
    });
    let dir = generate(tmp.path(), "valid", &narrow);
    let o = specgen()
        .args(["prove", "--datapath", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("--datapath") && text(&o).contains("allowed: --interface ready or axis"),
        "{}",
        text(&o)
    );
}

/// The first bounded search keeps the unit's own assertions beside
/// the port checker's, so a buffer fault they see within its depth is refuted there (never left
/// undecided by an induction that stops earlier), and the failure says whose assertion fails.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_first_search_keeps_the_units_assertions_and_says_whose_fails() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "dropped", &NARROW_READY);
    let (name, file, from, to) = HANDSHAKE_FAULTS.iter().find(|f| f.0 == "dropped").unwrap();
    apply_handshake_fault(&dir, name, file, from, to);
    let o = prove(&dir, &tmp.path().join("dropped.vcd"));
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let said = text(&o);
    assert!(
        said.contains("a bounded search with ABC bmc3 over its assertions and the unit's own; "),
        "{said}"
    );
    assert!(
        said.contains("a rule at the ports fails")
            || said.contains("the unit's own assertion fails"),
        "{said}"
    );
}

/// A value check by default. A per-pixel-colour `axis` unit whose
/// intensity MSB is dropped in `m_axis_tdata` keeps every stream rule, and the default proof
/// refutes it: every pixel at cos_g = 1.0 and n = 1 against the datapath twin.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_default_proof_checks_values_of_a_per_pixel_colour() {
    require_tool("yosys", "yosys");
    require_tool("yosys-abc", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "4",
        "--color-bits",
        "4",
        "--intensity-frac-bits",
        "6",
        "--interface",
        "axis",
        "--tag-bits",
        "2",
        "--stages",
        "2",
    ];
    let dir = generate(tmp.path(), "msb", &args);
    let unit = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&unit).unwrap();
    let from = "1'd0, intensity};";
    assert_eq!(src.matches(from).count(), 1, "{src}");
    std::fs::write(&unit, src.replace(from, "1'd0, 1'b0, intensity[5:0]};")).unwrap();
    // (a bounded search of the default proof's kind runs the value check too, to its depth)
    let o = specgen()
        .args(["prove", "--edited", "--depth", "12", "--rtl"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("the value check")
            && text(&o).contains("every bit of the intensity and of each colour in its place"),
        "{}",
        text(&o)
    );
}
