//! The figures the docs quote are read from where they live: the README's table of models
//! against the built-in explorations (today's RTL) and, where an exploration holds no such
//! unit, against `benchmarks/hw.md`'s row, which it then names. A regenerated exploration or
//! bench that moves a figure fails here until the prose follows.

use serde_json::Value;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn exploration(family: &str) -> Vec<Value> {
    let text = std::fs::read_to_string(root().join(format!("data/explore/{family}.json"))).unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    v["points"].as_array().unwrap().clone()
}

/// The measured unit of `model` at the default widths and interface, `stages` deep, with its
/// tables in files and no budget.
fn unit<'a>(points: &'a [Value], model: &str, stages: u64) -> Option<&'a Value> {
    points.iter().find(|p| {
        let q = &p["params"];
        p["model"] == model
            && p["stages"] == stages
            && q["cos_frac_bits"] == 15
            && q["intensity_frac_bits"] == 15
            && q["n_bits"] == 10
            && q["color_bits"] == 8
            && q["interface"] == "valid"
            && q["dsp_budget"].is_null()
            && q["rom_style"] == "file"
            && q["fabric_registers"] != true
            && p["measured"]["fmax_mhz"].is_f64()
    })
}

/// `x` as the README writes a figure: three significant digits.
fn three(x: f64) -> String {
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// The leading number of a cell part ("12 stages" → 12).
fn number(part: &str) -> f64 {
    part.trim()
        .split(' ')
        .next()
        .unwrap()
        .trim_end_matches('*')
        .parse()
        .unwrap_or_else(|_| panic!("no number in {part:?}"))
}

#[test]
fn the_readmes_table_of_models_is_the_explorations_and_the_benchs() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let hw = std::fs::read_to_string(root().join("benchmarks/hw.md")).unwrap();
    let (ice40, ecp5) = (exploration("ice40"), exploration("ecp5"));
    let mut checked = 0;
    for line in readme
        .lines()
        .filter(|l| l.starts_with("| `") && l.contains("stages"))
    {
        let cells: Vec<&str> = line
            .split(" | ")
            .map(|c| c.trim_matches(|c| c == '|' || c == ' '))
            .collect();
        let model = cells[0].trim_matches('`').split('`').next().unwrap();
        let row = format!("README row {model}: {line}");
        // the error at the pixel (at the codes), default widths: the exploration's accuracy
        let (pixel, codes) = cells[2].split_once(" (").unwrap_or_else(|| panic!("{row}"));
        let any = ice40.iter().find(|p| {
            p["model"] == model
                && p["params"]["cos_frac_bits"] == 15
                && p["params"]["intensity_frac_bits"] == 15
        });
        if let Some(p) = any {
            assert_eq!(
                pixel,
                three(p["accuracy"]["pixel"]["max"].as_f64().unwrap()),
                "{row}"
            );
            let codes = codes.trim_end_matches(')');
            let at_codes = p["accuracy"]["max"].as_f64().unwrap();
            if !codes.contains('·') {
                assert_eq!(codes, three(at_codes), "{row}");
            }
        }
        // the UP5K at 100 MHz: "S stages, C logic cells, F MHz"
        let up5k: Vec<&str> = cells[3].split(", ").collect();
        if up5k.len() == 3 {
            let u = unit(&ice40, model, number(up5k[0]) as u64).unwrap_or_else(|| {
                panic!("{row}: no such measured unit in data/explore/ice40.json")
            });
            assert_eq!(
                number(up5k[1]) as u64,
                u["measured"]["logic_cells"].as_u64().unwrap(),
                "{row}"
            );
            assert_eq!(
                format!("{:.1}", number(up5k[2])),
                format!("{:.1}", u["measured"]["fmax_mhz"].as_f64().unwrap()),
                "{row}"
            );
            checked += 1;
        }
        // the ECP5 at 200 MHz: "S stages, F MHz" from the exploration, else hw.md's row, named
        let e: Vec<&str> = cells[4].split(", ").collect();
        if e.len() >= 2 {
            let stages = number(e[0]) as u64;
            let mhz = format!("{:.1}", number(e[1]));
            match unit(&ecp5, model, stages) {
                Some(u) => assert_eq!(
                    mhz,
                    format!("{:.1}", u["measured"]["fmax_mhz"].as_f64().unwrap()),
                    "{row}"
                ),
                None => {
                    assert!(cells[4].contains("hw.md"), "{row}: no measured unit in data/explore/ecp5.json, and the cell names no bench");
                    let name = if model == "quadratic" { "lean" } else { model };
                    let bench = hw.lines().find(|l| {
                        l.starts_with(&format!("| {name} | ECP5-25 | 200 MHz | {stages} ("))
                    });
                    let bench =
                        bench.unwrap_or_else(|| panic!("{row}: no row of benchmarks/hw.md"));
                    assert!(
                        bench.contains(&format!("| {mhz} (")),
                        "{row}: benchmarks/hw.md says {bench}"
                    );
                }
            }
            checked += 1;
        }
    }
    assert!(
        checked >= 8,
        "{checked} cells checked: the table's form changed"
    );
}

/// The SPEC states what the tool promises: no commit of the history (a hash of 7 to 40 hex
/// digits) and no figure a bench measured (a "measured" or "median" number): those live in
/// `benchmarks/` and the data files, and the prose links to them.
#[test]
fn the_spec_holds_no_commit_and_no_measured_figure() {
    let spec = std::fs::read_to_string(root().join("docs/SPEC.md")).unwrap();
    let mut found = Vec::new();
    for (i, line) in spec.lines().enumerate() {
        for word in line.split(|c: char| !c.is_ascii_alphanumeric()) {
            let hex = (7..=40).contains(&word.len())
                && word
                    .chars()
                    .all(|c| c.is_ascii_hexdigit() && !c.is_ascii_uppercase())
                && word.chars().any(|c| c.is_ascii_digit())
                && word.chars().any(|c| c.is_ascii_alphabetic());
            if hex {
                found.push(format!("line {}: a commit? {word}", i + 1));
            }
        }
        let lower = line.to_lowercase();
        for lead in ["measured ", "measures ", "median ", "median of "] {
            for (at, _) in lower.match_indices(lead) {
                let next = lower[at + lead.len()..].chars().next();
                if next.is_some_and(|c| c.is_ascii_digit()) {
                    found.push(format!(
                        "line {}: a measured figure: {}",
                        i + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    assert!(found.is_empty(), "docs/SPEC.md:\n{}", found.join("\n"));
}

/// Every clock-sized figure the README and the GUIDE quote (a number of two or three digits
/// and one decimal: MHz, logic cells' shares) stands in a file under `benchmarks/`, where a
/// bench wrote it: a bench regenerated with other figures fails here until the prose follows,
/// and a figure no bench writes (a measurement of an older unit, a log line) has no place in
/// the prose.
#[test]
fn every_clock_the_readme_and_the_guide_quote_is_a_benchs() {
    let mut bench = String::new();
    let mut dirs = vec![root().join("benchmarks")];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "md" || x == "csv") {
                bench.push_str(&std::fs::read_to_string(&p).unwrap());
            }
        }
    }
    let mut missing = Vec::new();
    for doc in ["README.md", "docs/GUIDE.md"] {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        for (n, line) in text.lines().enumerate() {
            let b = line.as_bytes();
            let mut i = 0;
            while i < b.len() {
                // a run of digits and points, taken whole
                if !b[i].is_ascii_digit() {
                    i += 1;
                    continue;
                }
                let start = i;
                while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                    i += 1;
                }
                let run = line[start..i].trim_end_matches('.');
                let preceded =
                    start > 0 && (b[start - 1].is_ascii_alphabetic() || b[start - 1] == b'_');
                let clock = run
                    .split_once('.')
                    .is_some_and(|(int, frac)| (2..=3).contains(&int.len()) && frac.len() == 1);
                if clock && !preceded && !bench.contains(run) {
                    missing.push(format!("{doc}:{}: {run}", n + 1));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "figures no file under benchmarks/ holds: {missing:?}"
    );
}
