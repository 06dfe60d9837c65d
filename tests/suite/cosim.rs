//! Co-simulation: generated RTL agrees bit-exactly with the golden model under Verilator and
//! Icarus, on several configurations and on a yosys netlist; injected faults are caught.
//! The faults it must catch: `faults`.

mod faults;

use crate::common::*;
use std::path::Path;
use std::process::Output;

fn cosim(dir: &Path, extra: &[&str]) -> Output {
    // --edited: these tests change the RTL on purpose (faults); the SHA-256 rule has its own test
    specgen()
        .env("SPECGEN_CACHE_DIR", cache_dir())
        .arg("cosim")
        .arg("--edited")
        .arg("--rtl")
        .arg(dir)
        .args(extra)
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The deep pipelines (13 stages of lean, valid and ready; blinn's 37): in
/// `the_deep_configs_pass_under_verilator`, outside the suite's budget (their C++ is the
/// longest to build; the exhaustive deep tests run there too).
const DEEP: [usize; 3] = [7, 13, 15];

/// The options whose every value the suite co-simulates at least once.
const SHAPING: [&str; 6] = [
    "--model",
    "--interface",
    "--rounding",
    "--rom-style",
    "--colour",
    "--arch",
];

/// The shallow configurations split in two: those that bring a value of a [`SHAPING`] option
/// not seen in an earlier one (a model, interface or option value added is simulated in the
/// suite with no line changing), and the rest.
fn shallow_configs() -> (Vec<Vec<&'static str>>, Vec<Vec<&'static str>>) {
    let mut seen = std::collections::BTreeSet::new();
    let (mut first, mut rest) = (vec![], vec![]);
    for c in configs()
        .into_iter()
        .enumerate()
        .filter(|(i, _)| !DEEP.contains(i))
        .map(|(_, c)| c)
    {
        let value = |o: &str| {
            c.iter()
                .position(|a| *a == o)
                .map_or("default", |p| c[p + 1])
        };
        // (every option's value recorded, not only the first new one: no `any`)
        let new = SHAPING
            .iter()
            .filter(|o| seen.insert((**o, value(o))))
            .count()
            > 0;
        if new {
            first.push(c);
        } else {
            rest.push(c);
        }
    }
    (first, rest)
}

#[test]
fn every_option_value_passes_under_verilator() {
    assert!(
        DEEP.iter()
            .all(|&i| CONFIGS[i].contains(&"13") || CONFIGS[i].contains(&"37")),
        "DEEP names the deep configurations"
    );
    let (first, rest) = shallow_configs();
    assert!(!rest.is_empty(), "some configurations are the heavy test's");
    passes_under_verilator(&first);
}

/// The shallow configurations that bring no new option value: outside the suite's budget.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_other_shallow_configs_pass_under_verilator() {
    passes_under_verilator(&shallow_configs().1);
}

#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn the_deep_configs_pass_under_verilator() {
    passes_under_verilator(
        &DEEP
            .iter()
            .map(|&i| CONFIGS[i].to_vec())
            .collect::<Vec<_>>(),
    );
}

fn passes_under_verilator(configs: &[Vec<&str>]) {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    for_each_parallel(configs, |i, args| {
        // a parent of its own: specgen locks the parent while it swaps an output in
        let dir = generate(&tmp.path().join(format!("p{i}")), &format!("c{i}"), args);
        let o = cosim(&dir, &["--vectors", "100000", "--seed", &i.to_string()]);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", text(&o));
        assert!(text(&o).contains(" 0 mismatches"), "{}", text(&o));
    });
}

#[test]
fn pipelined_and_combinational_pass_under_icarus() {
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    for (i, args) in [CONFIGS[0], CONFIGS[3]].iter().enumerate() {
        let dir = generate(tmp.path(), &format!("i{i}"), args);
        let o = cosim(&dir, &["--simulator", "icarus", "--vectors", "5000"]);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", text(&o));
    }
}

#[test]
fn checked_in_default_unit_is_right_on_its_whole_input_space() {
    require_tool("verilator", "verilator");
    let rtl_out = Path::new(env!("CARGO_MANIFEST_DIR")).join("rtl_out");
    let o = cosim(&rtl_out, &["--exhaustive"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // (2^15 + 1) · 2^10 pairs, plus 2^8 full-intensity colour cycles
    assert!(
        text(&o).contains(&format!(" {} results, 0 mismatches", 32769u64 * 1024 + 256)),
        "{}",
        text(&o)
    );
}

/// The fitted and blinn units at their deepest iCE40 pipelines (fitted's sums
/// carry-save and carry-select, a register before each squaring's DSP; blinn's interpolations
/// each a DSP multiply-add whose operands the table word widens, n waiting in block RAM between
/// its reads) are the golden model's on every input.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fitted_and_blinn_at_their_deepest_pipelines_are_right_on_the_whole_input_space() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    for (model, name, at_least) in [
        (specgen::config::SpecularModel::Fitted, "fitted", 50),
        (specgen::config::SpecularModel::Blinn, "blinn", 30),
    ] {
        let deepest = default_cut_points(model);
        assert!(
            deepest >= at_least,
            "{name}: the datapath's sums are cut into steps: {deepest} cut points"
        );
        let dir = generate(
            tmp.path(),
            name,
            &["--model", name, "--stages", &deepest.to_string()],
        );
        let o = cosim(&dir, &["--exhaustive"]);
        assert!(
            text(&o).contains(&format!(" {} results, 0 mismatches", 32769u64 * 1024 + 256)),
            "{name}: {}",
            text(&o)
        );
    }
}

/// The exhaustive sweep is made inside the Verilator harness, and a `valid` unit
/// returns one digest a batch instead of its records. Every mode is right end to end on a
/// small whole input space: a pipelined `valid` unit (digests after the first reset), a
/// handshake with a tag and a static colour, and AXI4-Stream with a clock enable (records, and
/// the digest of the inputs the harness applied); a fault at one point of a pipelined unit is
/// found through its digest and described at that very point.
#[test]
fn the_harness_sweep_is_right_in_every_mode_and_a_digest_finds_one_point() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let small = [
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "4",
        "--color-bits",
        "6",
        "--intensity-frac-bits",
        "8",
    ];
    let units: [&[&str]; 3] = [
        &["--stages", "3"],
        &[
            "--stages",
            "2",
            "--interface",
            "ready",
            "--tag-bits",
            "5",
            "--colour",
            "static",
        ],
        &[
            "--stages",
            "4",
            "--interface",
            "axis",
            "--tag-bits",
            "3",
            "--tlast",
            "--clock-enable",
        ],
    ];
    for_each_parallel(&units, |i, args| {
        let all: Vec<&str> = small.iter().chain(args.iter()).copied().collect();
        let dir = generate(&tmp.path().join(format!("m{i}")), &format!("m{i}"), &all);
        let o = cosim(&dir, &["--exhaustive"]);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", text(&o));
        assert!(
            text(&o).contains(&format!(" {} results, 0 mismatches", 257 * 16 + 64)),
            "{args:?}: {}",
            text(&o)
        );
    });
    // one wrong `done` at (cos_g, n) = (200, 9), three stages down the pipeline
    let dir = generate(
        &tmp.path().join("f"),
        "f",
        &[&small[..], &["--stages", "3"]].concat(),
    );
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    let line = src
        .lines()
        .find(|l| l.starts_with("assign done"))
        .expect("the done output")
        .to_string();
    let (lhs, rhs) = line.split_once('=').unwrap();
    let late =
        "reg [2:0] hit;\nalways @(posedge clk) hit <= {hit[1:0], cos_g == 9'd200 && n == 4'd9};\n";
    std::fs::write(
        &v,
        src.replace(
            &line,
            &format!(
                "{late}{lhs}= {} ^ hit[2];",
                rhs.trim().trim_end_matches(';')
            ),
        ),
    )
    .unwrap();
    let o = cosim(&dir, &["--exhaustive"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("1 of ") && text(&o).contains("cos_g=200 n=9"),
        "{}",
        text(&o)
    );
}

/// yosys's own netlist of a unit (`synth`, its internal cells) co-simulates against the golden
/// model on every input: the harness takes a netlist for the RTL. At narrow widths (8/6/4/8: the
/// widths are not the subject) and under Icarus (Verilator's C++ compile of a gate-level netlist
/// takes half a minute; `synth --verify`'s tests run netlists under Verilator).
#[test]
fn yosys_netlist_of_a_unit_passes() {
    require_tool("yosys", "yosys");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = NARROW;
    let dir = generate(
        tmp.path(),
        "rtl",
        &[&["--stages", "2"][..], &narrow].concat(),
    );
    let net = tmp.path().join("netlist");
    std::fs::create_dir(&net).unwrap();
    let out = tool("yosys")
        .current_dir(&dir)
        .args(["-q", "-p"])
        .arg(format!(
            "read_verilog specular_unit.v; synth -top specular_unit; write_verilog -noattr {}",
            net.join("specular_unit_netlist.v").display()
        ))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::copy(
        dir.join("specular_unit.json"),
        net.join("specular_unit.json"),
    )
    .unwrap();
    // every input of the narrow unit
    let o = cosim(&net, &["--exhaustive", "--simulator", "icarus"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains(" 0 mismatches"), "{}", text(&o));
}

#[test]
fn mismatch_with_trace_writes_a_vcd() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let vcd = tmp.path().join("fail.vcd");
    let o = mutant(
        tmp.path(),
        "t",
        &["--stages", "1"],
        "{1'b1, square_s11[5:0], 1'b1} + 8'h1;",
        "{1'b1, square_s11[5:0], 1'b1} + 8'h0;",
        &["--trace", vcd.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let dump = std::fs::read_to_string(&vcd).unwrap();
    assert!(
        dump.contains("$enddefinitions") && dump.contains("intensity"),
        "not a VCD of the unit"
    );
    // a trace with nowhere to go is refused before the run, not claimed after it
    let nowhere = tmp.path().join("no-such-dir").join("fail.vcd");
    let o = cosim(
        &tmp.path().join("t_parent").join("t"),
        &["--trace", nowhere.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("does not exist") && !text(&o).contains("trace of the replay"),
        "{}",
        text(&o)
    );
}

#[test]
fn exhaustive_stimulus_covers_every_colour_code_at_full_intensity() {
    use specgen::config::{Config, Params};
    use specgen::cosim::{Exhaustive, Stimulus};
    // 12-bit colours, 3-bit n: the rows alone cannot carry every code at cos = 1.0
    let cfg = Config::new(Params {
        color_bits: 12,
        n_bits: 3,
        cos_frac_bits: 6,
        stages: 2,
        ..Params::default()
    })
    .unwrap();
    let parts = Exhaustive::parts(&cfg, 4);
    let mut seen = vec![[false; 3]; 1 << 12];
    let mut pairs = std::collections::HashSet::new();
    for p in &parts {
        for i in 0..p.len() {
            let c = p.cycle(i);
            if c.rst || !c.valid {
                continue;
            }
            pairs.insert((c.inputs.cos_g, c.inputs.n));
            if c.inputs.cos_g == 1 << 6 {
                for ch in 0..3 {
                    seen[c.inputs.ks[ch] as usize][ch] = true;
                }
            }
        }
    }
    assert_eq!(
        pairs.len(),
        65 * 8,
        "every (cos_g, n) with cos_g in [0, 1.0]"
    );
    assert!(
        seen.iter().all(|s| s.iter().all(|&b| b)),
        "a colour code never met full intensity"
    );
}

#[test]
fn usage_errors_exit_2() {
    let tmp = tempfile::tempdir().unwrap();
    let o = cosim(tmp.path(), &[]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("manifest"), "{}", text(&o));
    // a Verilog file that does not build
    let dir = generate(tmp.path(), "broken", &[]);
    std::fs::write(
        dir.join("specular_unit.v"),
        "module specular_unit(; endmodule\n",
    )
    .unwrap();
    let o = cosim(&dir, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("could not build"), "{}", text(&o));
}

/// Random stimulus spends at least half its rows inside the highlight, where the output is
/// neither 0 nor full scale (a uniform draw puts about 9 % of a blinn unit's rows there), for
/// every model; the other rows still reach cos_g codes above 1.0 and n = 0.
#[test]
fn random_stimulus_lands_inside_the_highlight_half_the_time() {
    use specgen::config::{Params, SpecularModel};
    for model in SpecularModel::ALL {
        let plan = specgen::plan::Plan::from_params(Params {
            model,
            ..Default::default()
        })
        .unwrap();
        let m = plan.model();
        let full = 1u32 << plan.cfg.fi();
        let count = 4000u64;
        let vectors: Vec<_> = (0..count)
            .map(|i| specgen::cosim::random_vector(&plan.cfg, 7, i))
            .collect();
        let inside = vectors
            .iter()
            .filter(|&&x| (1..full).contains(&m.eval(x).intensity))
            .count();
        assert!(
            inside as u64 * 2 >= count,
            "{}: {inside} of {count} rows inside the highlight",
            model.name()
        );
        assert!(
            vectors.iter().any(|x| x.cos_g > 1 << plan.cfg.f()),
            "{}: no cos_g above 1.0",
            model.name()
        );
        assert!(
            vectors.iter().any(|x| x.n == 0),
            "{}: no n = 0",
            model.name()
        );
    }
}

/// A delay line's long unread tail waits in block RAM on the families that have it (blinn's
/// per-pixel colours, a wide tag) and in registers in generic RTL; the unit is right either way,
/// under both simulators.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn long_delay_line_tails_wait_in_block_ram_and_stay_right() {
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let cases: &[(&str, &[&str], bool)] = &[
        (
            "blinn_ice40",
            &["--model", "blinn", "--stages", "20", "--target", "ice40"],
            true,
        ),
        (
            "blinn_ecp5",
            &["--model", "blinn", "--stages", "20", "--target", "ecp5"],
            true,
        ),
        // its colours' tail past 33 cuts: flip-flops, then 33 cuts in LUT RAM
        (
            "blinn_ecp5_deep",
            &["--model", "blinn", "--stages", "37", "--target", "ecp5"],
            true,
        ),
        (
            "blinn_generic",
            &["--model", "blinn", "--stages", "20", "--target", "generic"],
            false,
        ),
        (
            "tag_ready",
            &[
                "--stages",
                "13",
                "--tag-bits",
                "24",
                "--target",
                "ice40",
                "--interface",
                "ready",
            ],
            true,
        ),
    ];
    for_each_parallel(cases, |_, (name, args, memory)| {
        let dir = generate(tmp.path(), name, args);
        let unit = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        assert_eq!(
            unit.contains("_line_ram ("),
            *memory,
            "{name}: a tail in block RAM or not"
        );
        assert_eq!(
            dir.join("specular_unit_delay_ram.v").exists(),
            *memory,
            "{name}: the memory's module beside the unit or not"
        );
        for sim in ["verilator", "icarus"] {
            let vectors = if sim == "icarus" { "1500" } else { "20000" };
            let o = cosim(
                &dir,
                &["--simulator", sim, "--vectors", vectors, "--jobs", "1"],
            );
            assert!(
                o.status.success() && text(&o).contains(" 0 mismatches"),
                "{name} {sim}: {}",
                text(&o)
            );
        }
    });
}

/// Applies one textual mutation to the generated RTL (asserting it applies) and runs cosim.
fn mutant(
    root: &Path,
    name: &str,
    gen_args: &[&str],
    from: &str,
    to: &str,
    cosim_args: &[&str],
) -> Output {
    // a parent of its own: mutants are made in parallel, and specgen locks the parent
    let dir = generate(&root.join(format!("{name}_parent")), name, gen_args);
    let v = dir.join("specular_unit.v");
    let src = std::fs::read_to_string(&v).unwrap();
    assert_eq!(
        src.matches(from).count(),
        1,
        "mutation {name}: {from:?} must occur once"
    );
    std::fs::write(&v, src.replace(from, to)).unwrap();
    cosim(&dir, cosim_args)
}
