//! The generated Verilog, for several configurations, is silent under
//! `verilator --lint-only -Wall`, compiles with `iverilog -g2005`, and synthesizes in yosys
//! with `check -assert`, no latches and no warnings.

use crate::common::*;

fn top_of<'a>(args: &[&'a str]) -> &'a str {
    args.iter()
        .position(|a| *a == "--top")
        .map(|i| args[i + 1])
        .unwrap_or("specular_unit")
}

/// Runs `tool args… <top>.v` in every generated configuration; it must succeed and print nothing.
fn silent_on_every_config(tool: &str, package: &str, args: &[&str]) {
    require_tool(tool, package);
    let tmp = tempfile::tempdir().unwrap();
    // as many at a time as there are job slots (each run holds one)
    for_each_parallel(&configs(), |i, gen_args| {
        // a parent of its own: specgen locks the parent while it swaps an output in
        let dir = generate(
            &tmp.path().join(format!("p{i}")),
            &format!("c{i}"),
            gen_args,
        );
        let top = top_of(gen_args);
        let files = unit_files(&dir, top);
        let out = crate::common::tool(tool)
            .current_dir(&dir)
            .args(args)
            .args(&files)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            out.status.success() && text.trim().is_empty(),
            "{tool} {gen_args:?}:\n{text}"
        );
    });
}

#[test]
fn verilator_lint_is_silent() {
    silent_on_every_config("verilator", "verilator", &["--lint-only", "-Wall"]);
}

#[test]
fn iverilog_compiles() {
    silent_on_every_config(
        "iverilog",
        "iverilog",
        &["-g2005", "-Wall", "-o", "/dev/null"],
    );
}

/// One representative of each model, rounding, ROM style and interface synthesizes in yosys
/// with no latch and no warning (the paper's arch, the 13-stage pipeline, the default-width
/// static colour and the 64-bit-tag axis unit: `yosys_synthesizes_the_deep_and_wide_shapes`,
/// in scripts/bench_suite.sh).
#[test]
fn yosys_synthesizes_without_latches_or_warnings() {
    let mut representative: Vec<Vec<&str>> = [0, 4, 9, 12, 14]
        .iter()
        .map(|&i| CONFIGS[i].to_vec())
        .collect();
    // and every model none of them is (a model added to the registry), at its narrow widths
    // behind a handshake with a static colour: yosys's generic `synth` spends most of its time
    // on wide multipliers, which teach nothing about latches (the default-width static unit,
    // CONFIGS[17], is in `yosys_synthesizes_the_deep_and_wide_shapes`)
    for model in specgen::config::SpecularModel::ALL {
        let of_model = |args: &Vec<&str>| {
            args.iter()
                .position(|a| *a == "--model")
                .map_or(model.name() == "quadratic", |i| args[i + 1] == model.name())
        };
        if !representative.iter().any(of_model) {
            let mut narrow = model_configs(model)[1].clone();
            narrow.extend(["--colour", "static", "--tag-bits", "3"]);
            representative.push(narrow);
        }
    }
    synthesizes_without_latches(&representative);
}

/// The rest of the shapes: the paper's arch, the 13-stage pipeline, the default-width static
/// colour, the 64-bit-tag axis unit with a static colour; outside the suite's budget.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn yosys_synthesizes_the_deep_and_wide_shapes() {
    synthesizes_without_latches(
        &[6, 7, 17, 18]
            .iter()
            .map(|&i| CONFIGS[i].to_vec())
            .collect::<Vec<_>>(),
    );
}

fn synthesizes_without_latches(configs: &[Vec<&str>]) {
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    for_each_parallel(configs, |i, args| {
        // a parent of its own: specgen locks the parent while it swaps an output in
        let dir = generate(&tmp.path().join(format!("p{i}")), &format!("c{i}"), args);
        let top = top_of(args);
        let files = unit_files(&dir, top).join(" ");
        let script =
            format!("read_verilog {files}; synth -top {top}; check -assert; select -assert-none t:$dlatch t:$_DLATCH_*; select -assert-min 1 t:*; stat");
        let out = tool("yosys")
            .current_dir(&dir)
            .args(["-p", &script])
            .output()
            .unwrap();
        let log = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{args:?}: yosys failed:\n{}",
            &log[log.len().saturating_sub(3000)..]
        );
        let warnings: Vec<&str> = log.lines().filter(|l| l.contains("Warning")).collect();
        assert!(warnings.is_empty(), "{args:?}: {warnings:?}");
    });
}

/// A reviewer reads steps, not renamings: at `--stages 0` no wire of any model is just another
/// wire's or port's name, and there is one lint sink.
#[test]
fn combinational_units_have_no_renaming_wires_and_one_sink() {
    let tmp = tempfile::tempdir().unwrap();
    let mut units: Vec<Vec<&str>> = vec![vec!["--arch", "paper"]];
    units.extend(
        specgen::config::SpecularModel::ALL
            .iter()
            .map(|m| vec!["--model", m.name()]),
    );
    for (i, args) in units.iter().enumerate() {
        let dir = generate(tmp.path(), &format!("r{i}"), args);
        let v = std::fs::read_to_string(dir.join("specular_unit.v")).unwrap();
        // a wire's whole statement: its continuation lines (one operand a line) joined
        let mut statements: Vec<String> = Vec::new();
        for l in v.lines() {
            match statements.last_mut() {
                Some(last) if l.starts_with("    ") && !last.contains(';') => last.push_str(l),
                _ => statements.push(l.to_string()),
            }
        }
        for line in statements.iter().filter(|l| l.starts_with("wire ")) {
            let rhs = line.split_once(" = ").map(|x| x.1).unwrap_or("");
            let rhs = rhs.split(';').next().unwrap().trim();
            assert!(
                !rhs.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'),
                "{args:?}: a renaming wire: {line}"
            );
        }
        assert!(
            v.matches("unused").count() <= 1,
            "{args:?}: more than one unused sink"
        );
        let longest = v.lines().map(str::len).max().unwrap();
        assert!(longest <= 240, "{args:?}: a {longest}-character line (carry-select picks, shift-adds, sinks are one item a line)");
        assert!(
            v.starts_with("`resetall\n`timescale 1ns / 1ps\n`default_nettype none\n")
                && v.trim_end().ends_with("endmodule\n`resetall"),
            "{args:?}: preamble"
        );
    }
}

/// FuseSoC as users run it: the `.core` uses the flow API (no deprecation warning), two
/// configurations live side by side in one cores-root, `run --target lint` and the synth target
/// pass (iCE40 and ECP5), and the table files reach the tool's work directory.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn fusesoc_runs_the_core_with_the_flow_api() {
    require_tool("fusesoc", "fusesoc (pip install fusesoc==2.4.7)");
    require_tool("verilator", "verilator");
    require_tool("yosys", "yosys");
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path().join("cores");
    let a = generate(&root, "a", &["--n-bits", "6"]);
    let b = generate(
        &root,
        "b",
        &["--n-bits", "6", "--stages", "3", "--model", "blinn"],
    );
    let name = |dir: &std::path::Path| -> String {
        let text = std::fs::read_to_string(dir.join("specular_unit.core")).unwrap();
        text.lines()
            .find_map(|l| l.strip_prefix("name: "))
            .unwrap()
            .to_string()
    };
    let (na, nb) = (name(&a), name(&b));
    assert_ne!(na, nb, "two configurations, two core names");
    let fusesoc = |args: &[&str]| {
        let o = tool("fusesoc")
            .current_dir(tmp.path())
            .arg("--cores-root")
            .arg(&root)
            .args(args)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(o.status.success(), "fusesoc {args:?}:\n{text}");
        assert!(
            !text.to_lowercase().contains("deprecated"),
            "fusesoc {args:?} warns:\n{text}"
        );
        text
    };
    let list = fusesoc(&["core", "list"]);
    assert!(list.contains(&na) && list.contains(&nb), "{list}");
    fusesoc(&["run", "--target", "lint", &na]);
    fusesoc(&["run", "--target", "lint", &nb]);
    let synth = fusesoc(&["run", "--target", "synth", &nb]);
    assert!(
        synth.contains("SB_MAC16"),
        "synthesized with DSPs:\n{synth}"
    );
    let work = tmp
        .path()
        .join("build")
        .join(nb.replace(':', "_"))
        .join("synth");
    for table in ["specular_unit_log2_rom.hex", "specular_unit_exp2_rom.hex"] {
        assert_eq!(
            std::fs::read(work.join(table)).unwrap(),
            std::fs::read(b.join(table)).unwrap(),
            "{table} shipped to the tool"
        );
    }
    // an ECP5 unit: the primitives' models are linted with it, never synthesized
    let e = generate(&root, "e", &["--target", "ecp5", "--stages", "11"]);
    let ne = name(&e);
    fusesoc(&["run", "--target", "lint", &ne]);
    let synth = fusesoc(&["run", "--target", "synth", &ne]);
    assert!(synth.contains("synth_ecp5"), "{synth}");
    let cells = |cell: &str| {
        synth
            .lines()
            .filter_map(|l| l.trim().strip_prefix(cell))
            .next_back()
            .map(|n| n.trim().parse::<u32>().unwrap())
    };
    assert_eq!(
        (cells("MULT18X18D"), cells("DP16KD")),
        (Some(7), Some(1)),
        "the blocks instantiated, the models left out:\n{synth}"
    );
    // the same configuration gives the same name (and the same bytes)
    let again = generate(tmp.path(), "again", &["--n-bits", "6"]);
    assert_eq!(name(&again), na);
    // the sim targets run the self-checking testbench on the golden vectors, under
    // Icarus and Verilator, for a handshake unit with a tag and a static colour
    let h = generate(
        &root,
        "h",
        &[
            "--n-bits",
            "6",
            "--interface",
            "axis",
            "--tag-bits",
            "12",
            "--colour",
            "static",
            "--stages",
            "4",
        ],
    );
    let nh = name(&h);
    for target in ["sim", "sim_verilator"] {
        let out = fusesoc(&["run", "--target", target, &nh]);
        assert!(
            out.contains("PASS: ") && !out.contains("FAIL"),
            "{target}:\n{out}"
        );
    }
    // and the testbench fails when a golden value is wrong (one digit of the last row changed)
    let vectors = h.join("specular_unit_vectors.hex");
    let text = std::fs::read_to_string(&vectors).unwrap();
    let last = text.trim_end().rsplit('\n').next().unwrap().to_string();
    let flip = |c: char| if c == '0' { '1' } else { '0' };
    let bad: String =
        last[..last.len() - 1].to_string() + &flip(last.chars().last().unwrap()).to_string();
    std::fs::write(&vectors, text.replace(&last, &bad)).unwrap();
    let o = tool("fusesoc")
        .current_dir(tmp.path())
        .arg("--cores-root")
        .arg(&root)
        .args(["run", "--target", "sim", &nh])
        .output()
        .unwrap();
    let out = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        !o.status.success() && out.contains("FAIL: result"),
        "a wrong vector must fail the sim target:\n{out}"
    );
}

/// The pipelined RTL reads top to bottom. For every configuration: every line is at
/// most 120 characters (header included); every internal name (`x_sK`, `x_cK`) is declared
/// before the first line that uses it; no register is a same-name copy of the one before it
/// on a line of its own (a signal that only waits is one delay line); and the deepest blinn
/// unit, at default widths, is well under its former 2466 lines.
#[test]
#[ignore = "heavy: outside the suite's 10-minute budget, run by scripts/bench_suite.sh"]
fn pipelined_rtl_reads_top_to_bottom() {
    let tmp = tempfile::tempdir().unwrap();
    let internal = |w: &str| {
        w.rsplit_once('_').is_some_and(|(head, tail)| {
            !head.is_empty()
                && tail.len() > 1
                && (tail.starts_with('s') || tail.starts_with('c'))
                && tail[1..].bytes().all(|b| b.is_ascii_digit())
        })
    };
    let words = |line: &str| -> Vec<String> {
        line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    for (i, args) in configs().iter().enumerate() {
        let dir = generate(tmp.path(), &format!("r{i}"), args);
        let v = std::fs::read_to_string(dir.join(format!("{}.v", top_of(args)))).unwrap();
        let mut declared = std::collections::HashSet::new();
        for (n, line) in v.lines().enumerate() {
            assert!(
                line.chars().count() <= 120,
                "{args:?} line {}: {} characters",
                n + 1,
                line.chars().count()
            );
        }
        // the code without comments, cut into statements at `;`, each with its first line
        let mut statements: Vec<(usize, String)> = Vec::new();
        let mut cur = String::new();
        let mut start = 0;
        for (n, line) in v.lines().enumerate() {
            let code = line.split("//").next().unwrap();
            // a declaration, an always block or an assign starts its line
            let t = code.trim_start();
            if ["wire ", "reg ", "always ", "assign "]
                .iter()
                .any(|k| t.starts_with(k))
                && !cur.trim().is_empty()
            {
                statements.push((start, std::mem::take(&mut cur)));
            }
            if cur.trim().is_empty() {
                start = n + 1;
            }
            let mut rest = code;
            while let Some(i) = rest.find(';') {
                cur.push_str(&rest[..i]);
                statements.push((start, std::mem::take(&mut cur)));
                start = n + 1;
                rest = &rest[i + 1..];
            }
            cur.push_str(rest);
            cur.push(' ');
        }
        for (n, st) in &statements {
            // an attribute before a declaration (`(* keep *) reg …`) names nothing
            let t = st.trim();
            let t = t.strip_prefix("(* keep *) ").unwrap_or(t);
            // a declaration's items (split at commas outside brackets) declare the names left
            // of their `=` and use those right of it; every other statement only uses names
            let (mut declares, mut uses) = (String::new(), String::new());
            if t.starts_with("wire ") || t.starts_with("reg ") {
                let mut depth = 0i32;
                let mut item = String::new();
                let mut items = Vec::new();
                for c in t.chars() {
                    match c {
                        '{' | '(' | '[' => depth += 1,
                        '}' | ')' | ']' => depth -= 1,
                        ',' if depth == 0 => {
                            items.push(std::mem::take(&mut item));
                            continue;
                        }
                        _ => {}
                    }
                    item.push(c);
                }
                items.push(item);
                for it in items {
                    // the ranges of a declaration (`[13:0]`) name nothing
                    match it.split_once(" = ") {
                        Some((d, u)) => {
                            declares.push_str(d);
                            uses.push_str(u);
                        }
                        None => declares.push_str(&it),
                    }
                    declares.push(' ');
                    uses.push(' ');
                }
            } else {
                uses.push_str(t);
            }
            declared.extend(words(&declares).into_iter().filter(|w| internal(w)));
            for w in words(&uses) {
                if internal(&w) {
                    assert!(
                        declared.contains(&w),
                        "{args:?} line {n}: {w} used before it is declared:\n{t}"
                    );
                }
            }
            // `x_cK <= x_cJ` alone is a copy a delay line should hold
            if let Some((l, r)) = t
                .strip_prefix("always @(posedge clk) ")
                .unwrap_or(t)
                .split_once(" <= ")
            {
                let (ln, rn) = (l.trim().rsplit_once("_c"), r.trim().rsplit_once("_c"));
                assert!(
                    !matches!((ln, rn), (Some((a, _)), Some((b, _))) if a == b && !l.contains('{')),
                    "{args:?} line {n}: a copy on its own:\n{t}"
                );
            }
        }
    }
    let deepest = default_cut_points(specgen::config::SpecularModel::Blinn).to_string();
    let dir = generate(
        tmp.path(),
        "blinn",
        &["--model", "blinn", "--stages", &deepest],
    );
    let lines = std::fs::read_to_string(dir.join("specular_unit.v"))
        .unwrap()
        .lines()
        .count();
    assert!(lines < 1000, "blinn at {deepest} stages is {lines} lines");
}
