//! The real binary: invalid parameters, occupied directories, determinism, --config, ROM formats, eval.
//! What the binary says of itself (help, `info`): `help`.

mod help;

use crate::common::*;
use specgen::config::Config;
use std::path::Path;
use std::process::Output;

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn read_dir_sorted(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn invalid_parameters_exit_2_name_the_range_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let cases: &[(&[&str], &str, &str)] = &[
        (&["--cos-frac-bits", "3"], "--cos-frac-bits", "4..=20"),
        (&["--cos-frac-bits", "21"], "--cos-frac-bits", "4..=20"),
        (&["--n-bits", "0"], "--n-bits", "1..=12"),
        (&["--n-bits", "13"], "--n-bits", "1..=12"),
        (&["--color-bits", "0"], "--color-bits", "1..=16"),
        (&["--color-bits", "17"], "--color-bits", "1..=16"),
        (
            &["--intensity-frac-bits", "0"],
            "--intensity-frac-bits",
            "1..=24",
        ),
        (
            &["--intensity-frac-bits", "25"],
            "--intensity-frac-bits",
            "1..=24",
        ),
        (&["--k-frac-bits", "3"], "--k-frac-bits", "4..=24"),
        (&["--k-frac-bits", "25"], "--k-frac-bits", "4..=24"),
        (&["--stages", "14"], "--stages", "0..=13"),
        (&["--stages", "4294967295"], "--stages", "0..=13"),
        (&["--arch", "paper", "--stages", "7"], "--stages", "0..=6"),
        (&["--k", "abc"], "--k", "0 < k <= 1"),
        (&["--k", "1.5"], "--k", "0 < k <= 1"),
        (&["--k", "0"], "--k", "0 < k <= 1"),
        (&["--k", "0.000001"], "--k", "0 < k <= 1"),
        (&["--k", "1e-3"], "--k", "0 < k <= 1"),
        (&["--k", "0.3.6"], "--k", "0 < k <= 1"),
        (
            &["--k", "0.36860000000000000000000000001"],
            "--k",
            "at most 28",
        ),
        (&["--k=-0.5"], "--k", "0 < k <= 1"),
        (&["--top", "1abc"], "--top", "Verilog identifier"),
        (&["--top", "../evil"], "--top", "Verilog identifier"),
        (&["--top", "module"], "--top", "keyword"),
        (&["--rounding", "sloppy"], "--rounding", "faithful"),
        (&["--stages", "-1"], "", ""),
        (
            &["--model", "blinn-pow", "--rounding", "exact"],
            "--rounding",
            "faithful",
        ),
        (
            &["--model", "blinn-pow", "--arch", "paper"],
            "--arch",
            "lean",
        ),
        (
            &["--model", "blinn-pow", "--n-bits", "2", "--stages", "6"],
            "--stages",
            "0..=5",
        ),
        (&["--arch", "fast"], "--arch", "lean"),
        (&["--target-mhz", "0"], "--target-mhz", "[0.001, 1000]"),
        (&["--n-bits", "ten"], "--n-bits", ""),
    ];
    for (i, (args, param, range)) in cases.iter().enumerate() {
        let out = tmp.path().join(format!("o{i}"));
        let o = specgen()
            .arg("generate")
            .arg("--out")
            .arg(&out)
            .args(*args)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        let msg = String::from_utf8_lossy(&o.stderr);
        assert!(
            msg.contains(param) && msg.contains(range),
            "{args:?}: message {msg:?} should name {param} and {range}"
        );
        assert!(!out.exists(), "{args:?} wrote {out:?}");
    }
    assert_eq!(
        std::fs::read_dir(tmp.path()).unwrap().count(),
        0,
        "no temp files left behind"
    );
}

#[test]
fn occupied_output_directory_is_refused_untouched() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("mine");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("notes.txt"), "precious").unwrap();
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("notes.txt"), "{}", text(&o));
    assert_eq!(
        read_dir_sorted(&dir),
        vec![("notes.txt".to_string(), b"precious".to_vec())]
    );
    // a previous specgen output plus a stranger is refused too
    let gen = generate(tmp.path(), "gen", &[]);
    std::fs::write(gen.join("extra.v"), "// mine").unwrap();
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&gen)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(gen.join("extra.v").exists());
    // a file in place of the directory
    let file = tmp.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert_eq!(std::fs::read(&file).unwrap(), b"x");
}

#[test]
fn previous_output_is_replaced_whole() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "o", &["--top", "first_unit"]);
    let dir2 = generate(tmp.path(), "o", &["--top", "second_unit", "--stages", "2"]);
    assert_eq!(dir, dir2);
    let names: Vec<String> = read_dir_sorted(&dir).into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        names,
        [
            "second_unit.core",
            "second_unit.json",
            "second_unit.sdc",
            "second_unit.v",
            "second_unit_amaranth.py",
            "second_unit_cos_sp_rom.hex",
            "second_unit_litex.py",
            "second_unit_tb.sv",
            "second_unit_vectors.hex"
        ]
    );
    let hidden: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(hidden.len(), 1, "staging directories left: {hidden:?}");
}

#[test]
fn output_is_deterministic_and_config_reproduces_it() {
    let tmp = tempfile::tempdir().unwrap();
    let args = [
        "--cos-frac-bits",
        "12",
        "--n-bits",
        "8",
        "--k",
        "0.5",
        "--stages",
        "3",
        "--rounding",
        "exact",
        "--rom-style",
        "case",
        "--top",
        "u2",
    ];
    let a = generate(tmp.path(), "a", &args);
    let b = generate(tmp.path(), "b", &args);
    assert_eq!(read_dir_sorted(&a), read_dir_sorted(&b));
    let c = tmp.path().join("c");
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&c)
        .arg("--config")
        .arg(a.join("u2.json"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(read_dir_sorted(&a), read_dir_sorted(&c));
    // a flag overrides the file
    let d = tmp.path().join("d");
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(&d)
        .arg("--config")
        .arg(a.join("u2.json"))
        .args(["--stages", "1"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(std::fs::read_to_string(d.join("u2.json"))
        .unwrap()
        .contains("\"stages\": 1"));
    // a bad config file is a usage error
    std::fs::write(tmp.path().join("bad.json"), "{\"n_bitz\": 3}").unwrap();
    let o = specgen()
        .arg("generate")
        .arg("--out")
        .arg(tmp.path().join("e"))
        .arg("--config")
        .arg(tmp.path().join("bad.json"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("n_bitz"));
}

#[test]
fn manifest_lists_files_with_hashes_ports_and_widths() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = generate(tmp.path(), "m", &["--stages", "2"]);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("specular_unit.json")).unwrap())
            .unwrap();
    for key in [
        "top",
        "cos_frac_bits",
        "n_bits",
        "color_bits",
        "intensity_frac_bits",
        "k",
        "k_frac_bits",
        "stages",
        "rounding",
        "k_code",
        "latency",
        "ports",
        "internal_widths",
        "files",
        "version",
    ] {
        assert!(v.get(key).is_some(), "manifest lacks {key}");
    }
    assert_eq!(v["k_code"], 24157);
    assert_eq!(v["latency"], 2);
    for f in v["files"].as_array().unwrap() {
        let bytes = std::fs::read(dir.join(f["name"].as_str().unwrap())).unwrap();
        let out = std::process::Command::new("sha256sum")
            .arg(dir.join(f["name"].as_str().unwrap()))
            .output()
            .unwrap();
        let sum = String::from_utf8_lossy(&out.stdout)
            .split_whitespace()
            .next()
            .unwrap()
            .to_string();
        assert_eq!(
            f["sha256"].as_str().unwrap(),
            sum,
            "{} ({} bytes)",
            f["name"],
            bytes.len()
        );
    }
    let core = std::fs::read_to_string(dir.join("specular_unit.core")).unwrap();
    assert!(
        core.starts_with("CAPI=2:")
            && core.contains("- specular_unit.v")
            && core.contains("specular_unit_cos_sp_rom.hex")
    );
}

#[test]
fn rom_formats_follow_their_syntax_and_agree() {
    let cfg = Config::defaults();
    let table = specgen::models::quadratic::rom::cos_sp_table(&cfg);
    let run = |fmt: &str| {
        let o = specgen().args(["rom", "--format", fmt]).output().unwrap();
        assert_eq!(o.status.code(), Some(0));
        String::from_utf8(o.stdout).unwrap()
    };
    let hex = run("hex");
    let words: Vec<u32> = hex
        .lines()
        .map(|l| {
            assert_eq!(l.len(), 4, "{l}");
            u32::from_str_radix(l, 16).unwrap()
        })
        .collect();
    assert_eq!(words, table);
    let bin: Vec<u32> = run("bin")
        .lines()
        .map(|l| {
            assert_eq!(l.len(), 16);
            u32::from_str_radix(l, 2).unwrap()
        })
        .collect();
    assert_eq!(bin, table);
    let coe = run("coe");
    let body = coe.split("memory_initialization_vector=").nth(1).unwrap();
    assert!(coe.contains("memory_initialization_radix=16;") && body.trim_end().ends_with(';'));
    let coe_words: Vec<u32> = body
        .trim()
        .trim_end_matches(';')
        .split(',')
        .map(|w| u32::from_str_radix(w.trim(), 16).unwrap())
        .collect();
    assert_eq!(coe_words, table);
    let mif = run("mif");
    assert!(
        mif.contains("DEPTH = 1024;")
            && mif.contains("WIDTH = 16;")
            && mif.contains("ADDRESS_RADIX = HEX;")
            && mif.contains("DATA_RADIX = HEX;")
    );
    let content = mif
        .split("BEGIN")
        .nth(1)
        .unwrap()
        .split("END;")
        .next()
        .unwrap();
    for (i, line) in content.lines().filter(|l| !l.trim().is_empty()).enumerate() {
        let (addr, data) = line.trim_end_matches(';').split_once(" : ").unwrap();
        assert_eq!(usize::from_str_radix(addr, 16).unwrap(), i);
        assert_eq!(u32::from_str_radix(data, 16).unwrap(), table[i]);
    }
    let csv = run("csv");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("n,code,cosine,angle_deg"));
    for (i, line) in lines.enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[0].parse::<usize>().unwrap(), i);
        assert_eq!(f[1].parse::<u32>().unwrap(), table[i]);
        let cos: f64 = f[2].parse().unwrap();
        assert_eq!(cos, table[i] as f64 / 32768.0);
        assert!((f[3].parse::<f64>().unwrap() - cos.acos().to_degrees()).abs() < 1e-3);
    }
    // -o writes the same bytes
    let tmp = tempfile::tempdir().unwrap();
    let p = tmp.path().join("rom.coe");
    assert!(specgen()
        .args(["rom", "--format", "coe", "-o"])
        .arg(&p)
        .status()
        .unwrap()
        .success());
    assert_eq!(std::fs::read_to_string(&p).unwrap(), coe);
}

#[test]
fn eval_shows_golden_exact_and_real_values() {
    let o = specgen()
        .args(["eval", "--cos", "0.98", "--n", "40", "--ks", "255,128,0"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let t = text(&o);
    for needle in [
        "cos_g = 32113",
        "intensity =",
        "Blinn cos^n",
        "formula (15)",
        "faithful rounding holds",
    ] {
        assert!(t.contains(needle), "missing {needle:?} in\n{t}");
    }
    let o = specgen()
        .args(["eval", "--cos", "0.9", "--n", "1024"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("--n") && text(&o).contains("0..=1023"));
    let o = specgen()
        .args(["eval", "--cos", "2.5", "--n", "1"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn rtl_out_is_what_the_generator_emits_now() {
    rtl_out_is_emitted_now(Path::new(env!("CARGO_MANIFEST_DIR")));
}

/// `root`'s `rtl_out/` is what `specgen generate --out rtl_out` writes today, byte for byte.
fn rtl_out_is_emitted_now(root: &Path) {
    let tmp = tempfile::tempdir().unwrap();
    let fresh = generate(tmp.path(), "fresh", &[]);
    let checked_in = root.join("rtl_out");
    let text = |d: &Path| {
        read_dir_sorted(d)
            .into_iter()
            .map(|(n, b)| (n, String::from_utf8_lossy(&b).into_owned()))
            .collect::<Vec<_>>()
    };
    let (old, new) = (text(&checked_in), text(&fresh));
    assert_eq!(
        old.iter().map(|f| &f.0).collect::<Vec<_>>(),
        new.iter().map(|f| &f.0).collect::<Vec<_>>(),
        "rtl_out/ file names"
    );
    for ((name, a), (_, b)) in old.iter().zip(&new) {
        let first = a.lines().zip(b.lines()).position(|(x, y)| x != y);
        assert!(a == b, "rtl_out/{name} is stale (first differing line {first:?}): run `specgen generate --out rtl_out`");
    }
}

/// The README's first command, run as a newcomer runs it in a copy of the checkout (its
/// tracked files), writes where no tracked file is, leaves `rtl_out/` as it was (what the
/// exhaustive co-simulation of the checked-in unit reads), and the pinned-output test passes
/// after it; the unit it picks is within its bound at the pixel on every input (the golden
/// model, every code's interval and every n: no stride).
#[test]
fn the_readmes_commands_work_in_its_order() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let first = readme
        .lines()
        .skip_while(|l| !l.starts_with("```sh"))
        .nth(1)
        .expect("a first command in the README");
    let command = first
        .split("&& ")
        .nth(1)
        .expect("cargo install … && specgen …")
        .split('#')
        .next()
        .unwrap()
        .trim();
    let words: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(words[..2], ["specgen", "generate"], "{first}");
    let tracked = tool("git")
        .args(["-C", root.to_str().unwrap(), "ls-files", "-z"])
        .output()
        .unwrap();
    assert!(tracked.status.success(), "git ls-files: {}", text(&tracked));
    let tmp = tempfile::tempdir().unwrap();
    let copy = tmp.path().join("checkout");
    let files: Vec<String> = String::from_utf8(tracked.stdout)
        .unwrap()
        .split('\0')
        .filter(|f| !f.is_empty())
        .map(String::from)
        .collect();
    for f in &files {
        let to = copy.join(f);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        if root.join(f).is_file() {
            std::fs::copy(root.join(f), &to).unwrap();
        }
    }
    let before = read_dir_sorted(&copy.join("rtl_out"));
    let o = specgen()
        .args(&words[1..])
        .current_dir(&copy)
        .output()
        .unwrap();
    assert!(o.status.success(), "{command}: {}", text(&o));
    let out = words
        .iter()
        .position(|w| *w == "--out")
        .map(|i| words[i + 1])
        .expect("the command names its --out");
    assert!(
        files.iter().all(|f| !Path::new(f).starts_with(out)),
        "{command} writes over tracked files under {out}/"
    );
    assert_eq!(
        read_dir_sorted(&copy.join("rtl_out")),
        before,
        "{command} changed rtl_out/"
    );
    rtl_out_is_emitted_now(&copy);
    // the bound it was asked for holds at the pixel, exhaustively
    let bound: f64 = words
        .iter()
        .position(|w| *w == "--max-error")
        .map(|i| words[i + 1].parse().unwrap())
        .expect("the README asks --max-error");
    let unit = copy.join(out);
    let manifest = std::fs::read_dir(&unit)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "json"))
        .unwrap();
    let cfg = Config::new(specgen::config::Params::from_json_file(&manifest).unwrap()).unwrap();
    let f = specgen::models::fidelity_exhaustive(&specgen::models::Model::new(&cfg));
    assert_eq!(f.stride, 1);
    assert!(
        !f.pixel.bound && f.pixel.max <= bound,
        "{command}: the unit is {} from cos^n at the pixel",
        f.pixel.max
    );
    assert!(
        text(&o).contains("measured") && text(&o).contains("today's RTL"),
        "{}",
        text(&o)
    );
    // and the evidence printed is of the unit written: its RTL's digest is the measurement's
    let digest = specgen::emit::rtl_digest(&specgen::plan::Plan::new(cfg).unwrap());
    assert!(
        text(&o).contains(&format!("today's RTL (sha256 {})", &digest[..16])),
        "the unit written is {digest}: {}",
        text(&o)
    );
}
