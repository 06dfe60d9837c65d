//! Faults the co-simulation must catch: mutants of the RTL, wrong or missing table entries and
//! files, faults derived from each model.

use super::*;

#[test]
fn injected_faults_are_caught() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let r = tmp.path();
    let random: &[&str] = &["--vectors", "100000"];
    /// name, generate flags, RTL text, its mutation, cosim flags
    type Fault<'a> = (&'a str, &'a [&'a str], &'a str, &'a str, &'a [&'a str]);
    let faults: Vec<Fault> = vec![
        // an off-by-one constant: k_code 24157 = 0x5e5d
        ("k_off_by_one", &[], "25'h5e5d", "25'h5e5e", random),
        // a dropped rounding bit: intensity truncates instead of rounding
        ("no_round", &[], "{1'b1, square_s11[5:0], 1'b1} + 8'h1;", "{1'b1, square_s11[5:0], 1'b1} + 8'h0;", random),
        // swapped colour channels
        (
            "swap_rg",
            &[],
            "assign spec_r    = spec_r_s12;\nassign spec_g    = spec_g_s12;",
            "assign spec_r    = spec_g_s12;\nassign spec_g    = spec_r_s12;",
            random,
        ),
        // a wrong cut-off comparison: cos <= cos_sp
        (
            "cutoff_le",
            &[],
            "{1'b1, cos_sp_s1[5:0]} + {1'b0, cos_complement_s1[5:0]};",
            "{1'b1, cos_sp_s1[5:0]} + {1'b0, cos_complement_s1[5:0]} + 7'h1;",
            random,
        ),
        // a fault at one single (cos_g, n): only the exhaustive run meets it
        ("one_point", &[], "assign done      = done_s5;", "assign done      = done_s5 ^ (cos_g == 16'd32000 && n == 10'd77);", &["--exhaustive"]),
        // out_valid one cycle late in a pipelined unit
        (
            "valid_late",
            &["--stages", "2"],
            "assign out_valid = valid_line[1];",
            "reg valid_late;\nalways @(posedge clk) valid_late <= valid_line[1];\nassign out_valid = valid_late;",
            random,
        ),
    ];
    for_each_parallel(&faults, |_, &(name, gen_args, from, to, args)| {
        let o = mutant(r, name, gen_args, from, to, args);
        assert_eq!(
            o.status.code(),
            Some(1),
            "fault {name} survived: {}",
            text(&o)
        );
        assert!(text(&o).contains("first mismatch"), "{name}: {}", text(&o));
    });
}

#[test]
fn injected_faults_in_the_new_models_are_caught() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let r = tmp.path();
    let random: &[&str] = &["--vectors", "100000"];
    let faults: Vec<(&str, &[&str], &str, &str)> = vec![
        // fitted: the second squaring done when m_n = 1 too
        (
            "fit_mux",
            &["--model", "fitted"],
            "(fit_s1[24:23] >= 2'h2)",
            "(fit_s1[24:23] >= 2'h1)",
        ),
        // fitted: intensity truncated instead of rounded
        (
            "fit_round",
            &["--model", "fitted"],
            "power3_s60[7:4], 1'b1} + 6'h1;",
            "power3_s60[7:4], 1'b1} + 6'h0;",
        ),
        // fitted: a_n's bit 16 left out of the deviation (a partial product beside its DSP)
        (
            "fit_a_hi",
            &["--model", "fitted"],
            "deviation_hi_pp0_s4 = ({16{fit_s1[16]}}",
            "deviation_hi_pp0_s4 = ({16{1'b0}}",
        ),
        // fitted: the first squaring's t*(hi*2^r + l') masked by the wrong bit of lo
        (
            "fit_sq_t",
            &["--model", "fitted"],
            "square1_t_top_s22 = ({21{power0_s21[4]}}",
            "square1_t_top_s22 = ({21{power0_s21[3]}}",
        ),
        // blinn: one exponent mis-encoded in the normalisation
        (
            "blinn_lzc",
            &["--model", "blinn"],
            "(~cos_minus_ulp_s3[10] & cos_minus_ulp_s3[9]) |",
            "(~cos_minus_ulp_s3[10] & cos_minus_ulp_s3[8]) |",
        ),
        // blinn: 0^0 taken as 0 (c = 0 saturates y even for n = 0)
        (
            "blinn_zero",
            &["--model", "blinn"],
            "cos_zero_s2 & (n_nonzero_any0_s1 | n_nonzero_any1_s1 | n_nonzero_any2_s1);",
            "cos_zero_s2;",
        ),
    ];
    for_each_parallel(&faults, |_, &(name, gen_args, from, to)| {
        let o = mutant(r, name, gen_args, from, to, random);
        assert_eq!(
            o.status.code(),
            Some(1),
            "fault {name} survived: {}",
            text(&o)
        );
        assert!(text(&o).contains("first mismatch"), "{name}: {}", text(&o));
    });
}

/// Adds `delta` to entry `index` of a table file (one hex word a line).
fn corrupt(path: &Path, index: usize, delta: u128) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let w = lines[index].len();
    let v = u128::from_str_radix(&lines[index], 16).unwrap() + delta;
    lines[index] = format!("{v:0w$x}");
    std::fs::write(path, lines.join("\n") + "\n").unwrap();
}

#[test]
fn a_wrong_or_missing_table_entry_fails_cosim_at_default_settings() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    // ROM[700] + 1, and the same fault at a random n, fail the default cosim, naming the entry
    let n_random = (specgen::cosim::splitmix(std::process::id() as u64) % 1024) as usize;
    for (i, n) in [700usize, n_random].into_iter().enumerate() {
        let dir = generate(tmp.path(), &format!("q{i}"), &[]);
        corrupt(&dir.join("specular_unit_cos_sp_rom.hex"), n, 1);
        let o = cosim(&dir, &[]);
        assert_eq!(
            o.status.code(),
            Some(1),
            "ROM[{n}]+1 survived: {}",
            text(&o)
        );
        assert!(
            text(&o).contains(&format!("entry {n} is"))
                && text(&o).contains("specular_unit_cos_sp_rom.hex"),
            "{}",
            text(&o)
        );
    }
    // a table of the blinn unit, and a short and a missing file
    let dir = generate(tmp.path(), "b", &["--model", "blinn"]);
    corrupt(&dir.join("specular_unit_exp2_rom.hex"), 77, 1);
    let o = cosim(&dir, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit_exp2_rom.hex: entry 77 is"),
        "{}",
        text(&o)
    );
    let short = std::fs::read_to_string(dir.join("specular_unit_log2_rom.hex"))
        .unwrap()
        .lines()
        .take(5)
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(dir.join("specular_unit_log2_rom.hex"), short).unwrap();
    let o = cosim(&dir, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit_log2_rom.hex is short: entry 5 is missing"),
        "{}",
        text(&o)
    );
    std::fs::remove_file(dir.join("specular_unit_log2_rom.hex")).unwrap();
    let o = cosim(&dir, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit_log2_rom.hex is missing"),
        "{}",
        text(&o)
    );
    // every command that hands the RTL to a tool says so before the tool runs (synth's yosys
    // said "Can not open file … for $readmemh" after the elaboration)
    let dir = generate(tmp.path(), "c", &["--model", "blinn"]);
    std::fs::remove_file(dir.join("specular_unit_log2_rom.hex")).unwrap();
    let rtl = dir.to_str().unwrap();
    for args in [
        &["synth", "--rtl", rtl, "--no-pnr"][..],
        &["prove", "--rtl", rtl, "--depth", "1"][..],
    ] {
        let o = specgen().args(args).output().unwrap();
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", text(&o));
        assert!(
            text(&o).contains("table file")
                && text(&o).contains("specular_unit_log2_rom.hex is missing")
                && !text(&o).contains("yosys"),
            "{args:?}: {}",
            text(&o)
        );
    }
    // a manifest that is not JSON is named with why, not taken for no manifest at all
    std::fs::write(dir.join("specular_unit.json"), "{").unwrap();
    let o = cosim(&dir, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("specular_unit.json is not JSON"),
        "{}",
        text(&o)
    );
}

/// The generated unit itself refuses to run without its tables: from a working directory
/// without the file, Icarus and Verilator stop with an error that names it.
#[test]
fn a_missing_table_file_stops_both_simulators() {
    require_tool("verilator", "verilator");
    require_tool("iverilog", "iverilog");
    let tmp = tempfile::tempdir().unwrap();
    let elsewhere = tmp.path().join("elsewhere");
    std::fs::create_dir(&elsewhere).unwrap();
    // every table is read by the same template code: one unit's stands for all (at narrow
    // widths, whose C++ builds sooner)
    let args = [
        "--model",
        "blinn",
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "4",
        "--color-bits",
        "4",
        "--intensity-frac-bits",
        "6",
    ];
    let (name, args, file) = ("b", &args[..], "specular_unit_log2_rom.hex");
    let dir = generate(tmp.path(), name, args);
    let v = dir.join("specular_unit.v");
    let sim = tmp.path().join(format!("{name}.vvp"));
    assert!(tool("iverilog")
        .args(["-g2005", "-o"])
        .arg(&sim)
        .arg(&v)
        .status()
        .unwrap()
        .success());
    let o = tool("vvp")
        .current_dir(&elsewhere)
        .arg("-n")
        .arg(&sim)
        .output()
        .unwrap();
    assert!(
        text(&o).contains(&format!("cannot open table file {file}")),
        "Icarus: {}",
        text(&o)
    );
    // $fatal: a non-zero exit, not only a message (a plain `$finish` exits 0)
    assert!(!o.status.success(), "vvp exited 0 without its table");
    let mdir = tmp.path().join(format!("{name}_obj"));
    let b = tool("verilator")
        .args([
            "--binary",
            "-Wno-fatal",
            "--top-module",
            "specular_unit",
            "-o",
            "vsim",
            "--Mdir",
        ])
        .arg(&mdir)
        .arg(&v)
        .output()
        .unwrap();
    assert!(b.status.success(), "{}", text(&b));
    let o = specgen::process::command(mdir.join("vsim"))
        .current_dir(&elsewhere)
        .output()
        .unwrap();
    assert!(
        text(&o).contains(&format!("cannot open table file {file}")),
        "Verilator: {}",
        text(&o)
    );
    assert!(
        !o.status.success(),
        "the Verilator binary exited 0 without its table"
    );
    // and with the file where the simulator runs, neither complains
    std::fs::copy(dir.join(file), elsewhere.join(file)).unwrap();
    let o = tool("vvp")
        .current_dir(&elsewhere)
        .arg("-n")
        .arg(&sim)
        .output()
        .unwrap();
    assert!(
        !text(&o).contains(&format!("table file {file}")),
        "Icarus: {}",
        text(&o)
    );
    std::fs::remove_file(elsewhere.join(file)).unwrap();
}

/// Faults derived from every model's own RTL, not written per model: the
/// colours' rounding half dropped (the constant added in `color_sum_r`, whatever the model
/// computes before it) and `out_valid` one clock late in a pipelined unit. A model added to
/// `SpecularModel::ALL` is tested with no line here changed.
#[test]
fn derived_faults_are_caught_in_every_model() {
    require_tool("verilator", "verilator");
    let tmp = tempfile::tempdir().unwrap();
    let narrow = [
        "--cos-frac-bits",
        "8",
        "--n-bits",
        "6",
        "--color-bits",
        "4",
        "--intensity-frac-bits",
        "8",
        "--stages",
        "2",
    ];
    let mut faults: Vec<(String, &'static str)> = Vec::new();
    for model in specgen::config::SpecularModel::ALL {
        for fault in ["no_colour_half", "valid_late"] {
            faults.push((model.name().to_string(), fault));
        }
    }
    for_each_parallel(&faults, |i, (model, fault)| {
        let mut args = vec!["--model", model.as_str()];
        args.extend(narrow);
        let dir = generate(&tmp.path().join(format!("d{i}")), "u", &args);
        let v = dir.join("specular_unit.v");
        let src = std::fs::read_to_string(&v).unwrap();
        let edited = match *fault {
            // the last `+ W'hX` of the line that defines color_sum_r: the rounding half
            "no_colour_half" => {
                let line = src
                    .lines()
                    .find(|l| l.starts_with("wire") && l.contains(" color_sum_r_s"))
                    .unwrap_or_else(|| panic!("{model}: no color_sum_r"));
                let code = line.split("//").next().unwrap();
                let at = code
                    .rfind(" + ")
                    .unwrap_or_else(|| panic!("{model}: no addend in {line}"));
                let (width, _) = code[at + 3..]
                    .split_once("'h")
                    .unwrap_or_else(|| panic!("{model}: no constant in {line}"));
                let new = format!("{} + {width}'h0;{}", &code[..at], &line[code.len()..]);
                src.replacen(line, &new, 1)
            }
            _ => {
                let line = src
                    .lines()
                    .find(|l| l.starts_with("assign out_valid = "))
                    .unwrap_or_else(|| panic!("{model}: no out_valid"));
                let was = line
                    .trim_start_matches("assign out_valid = ")
                    .trim_end_matches(';');
                src.replacen(line, &format!("reg valid_late;\nalways @(posedge clk) valid_late <= {was};\nassign out_valid = valid_late;"), 1)
            }
        };
        assert_ne!(edited, src, "{model} {fault}: the fault applies");
        std::fs::write(&v, edited).unwrap();
        let o = cosim(&dir, &["--vectors", "20000"]);
        assert_eq!(
            o.status.code(),
            Some(1),
            "{model}: fault {fault} survived: {}",
            text(&o)
        );
        assert!(
            text(&o).contains("first mismatch"),
            "{model} {fault}: {}",
            text(&o)
        );
    });
}
