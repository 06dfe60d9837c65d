//! What is checked before anything is simulated: the table files as data, and the RTL's
//! ports against the manifest.

use super::Design;
use crate::error::{input, mismatch, Error as Failure};

/// Reads a `$readmemh` file: hex words separated by white space, `//` comments, `@addr`
/// address jumps. Returns the words by address (`None` where the file sets nothing); a
/// malformed file is the user's input error, naming the line.
pub fn parse_readmemh(text: &str, depth: usize) -> Result<Vec<Option<u128>>, Failure> {
    let mut words = vec![None; depth];
    let mut addr = 0usize;
    for (ln, line) in text.lines().enumerate() {
        let line = line.split("//").next().unwrap_or("");
        for tok in line.split_whitespace() {
            if let Some(a) = tok.strip_prefix('@') {
                addr = usize::from_str_radix(a, 16)
                    .map_err(|_| input(format!("line {}: bad address {tok:?}", ln + 1)))?;
                continue;
            }
            let v = u128::from_str_radix(&tok.replace('_', ""), 16)
                .map_err(|_| input(format!("line {}: {tok:?} is not a hex word", ln + 1)))?;
            if addr >= depth {
                return Err(input(format!("line {}: more than {depth} entries", ln + 1)));
            }
            words[addr] = Some(v);
            addr += 1;
        }
    }
    Ok(words)
}

/// Table files are data: every table the configuration reads with `$readmemh` is compared
/// with the golden model's entry by entry before anything is simulated. A missing, short or
/// wrong file fails (exit 1) naming the file, and the first wrong entry by index and value.
/// Tables the sources do not name (a netlist with its ROMs inline) are not looked for.
pub fn check_tables(design: &Design) -> Result<(), Failure> {
    if design.cfg.params.rom_style != crate::config::RomStyle::File {
        return Ok(());
    }
    let sources: Vec<String> = design
        .sources
        .iter()
        .map(|p| crate::small_file::read(p, crate::small_file::UNIT_FILE_MAX).unwrap_or_default())
        .collect();
    for t in &design.plan.datapath.tables {
        let file = t.file(design.cfg.top());
        // a synthesized netlist holds its tables inline: only files the sources name are read
        if !sources.iter().any(|s| s.contains(&format!("\"{file}\""))) {
            continue;
        }
        let path = design.dir.join(&file);
        std::fs::metadata(&path).map_err(|e| {
            mismatch(format!(
                "table file {} is missing ({e}); `specgen generate` writes it beside the RTL",
                path.display()
            ))
        })?;
        let text = crate::small_file::read(&path, crate::small_file::UNIT_FILE_MAX)
            .map_err(|e| mismatch(format!("table file {} {e}", path.display())))?;
        let words = parse_readmemh(&text, t.words.len())
            .map_err(|e| mismatch(format!("table file {}: {e}", path.display())))?;
        for (i, (got, want)) in words.iter().zip(&t.words).enumerate() {
            match got {
                None => {
                    return Err(mismatch(format!(
                        "table file {} is short: entry {i} is missing ({} entries expected, {})",
                        path.display(),
                        t.words.len(),
                        t.what
                    )))
                }
                Some(v) if v != want => {
                    return Err(mismatch(format!(
                        "table file {}: entry {i} is {v:x}, the golden model's is {want:x} ({})",
                        path.display(),
                        t.what
                    )))
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// The ports of module `top` in Verilog source: (name, direction, width). Reads both
/// ANSI headers (`input wire [15:0] cos_g,`) and netlist declarations (`input [15:0] cos_g;`).
pub fn source_ports(text: &str, top: &str) -> Option<Vec<(String, &'static str, u32)>> {
    // drop comments
    let mut clean = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |i| &r[i..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
        } else {
            let c = rest.chars().next().unwrap();
            clean.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    let clean = without_formal(&clean);
    let tokens: Vec<String> = clean
        .replace('[', " [ ")
        .replace(']', " ] ")
        .replace([',', ';', '(', ')'], " , ")
        .split_whitespace()
        .map(String::from)
        .collect();
    let start = tokens
        .windows(2)
        .position(|w| w[0] == "module" && (w[1] == top || w[1].starts_with(&format!("{top}#"))))?;
    let end = tokens[start..]
        .iter()
        .position(|t| t == "endmodule")
        .map_or(tokens.len(), |e| start + e);
    let mut ports = Vec::new();
    let mut i = start;
    while i < end {
        let dir = match tokens[i].as_str() {
            "input" => "input",
            "output" => "output",
            _ => {
                i += 1;
                continue;
            }
        };
        i += 1;
        while i < end && ["wire", "reg", "signed"].contains(&tokens[i].as_str()) {
            i += 1;
        }
        let mut width = 1;
        if i < end && tokens[i] == "[" {
            // [ h : l ]
            let range: String = tokens[i + 1..]
                .iter()
                .take_while(|t| *t != "]")
                .cloned()
                .collect();
            let (h, l) = range.split_once(':')?;
            width = (h.trim().parse::<i64>().ok()? - l.trim().parse::<i64>().ok()?).unsigned_abs()
                as u32
                + 1;
            i += tokens[i..].iter().position(|t| t == "]")? + 1;
        }
        // one or more names, separated by commas, until a keyword or the end of the list
        while i < end {
            let t = tokens[i].as_str();
            if t == "," {
                i += 1;
                continue;
            }
            if [
                "input",
                "output",
                "wire",
                "reg",
                "assign",
                "always",
                "initial",
                "endmodule",
                "parameter",
                "localparam",
                "integer",
            ]
            .contains(&t)
                || !t
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '\\')
            {
                break;
            }
            ports.push((t.trim_start_matches('\\').to_string(), dir, width));
            i += 1;
            if tokens.get(i).is_some_and(|n| n != ",") {
                break;
            }
        }
    }
    Some(ports)
}

/// `text` without what only a proof reads: the lines from an `` `ifdef FORMAL `` or
/// `` `ifdef SPECGEN_… `` to its `` `endif `` (nested conditionals counted), whose ports (a
/// unit's lemma port `f_ports`) no flow sees.
fn without_formal(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut depth = 0usize;
    for line in text.lines() {
        let t = line.trim_start();
        let opens = t.starts_with("`ifdef") || t.starts_with("`ifndef");
        if depth > 0 {
            if opens {
                depth += 1;
            } else if t.starts_with("`endif") {
                depth -= 1;
            }
            continue;
        }
        let word = t.strip_prefix("`ifdef").map(str::trim);
        if word.is_some_and(|w| w.starts_with("FORMAL") || w.starts_with("SPECGEN_")) {
            depth = 1;
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The RTL's port names and widths must be those the manifest implies: a mismatch is a
/// usage error (exit 2), reported as such rather than as data mismatches.
pub fn check_ports(design: &Design) -> Result<(), Failure> {
    let top = design.cfg.top();
    let mut found = None;
    for src in &design.sources {
        let text = crate::small_file::read(src, crate::small_file::UNIT_FILE_MAX)
            .map_err(|e| input(format!("{} {e}", src.display())))?;
        if let Some(p) = source_ports(&text, top) {
            found = Some((src.clone(), p));
            break;
        }
    }
    let Some((src, got)) = found else {
        return Err(input(format!(
            "no module {top} (the manifest's top) in the Verilog of {}",
            design.dir.display()
        )));
    };
    let want = design.cfg.ports("");
    let mut problems = Vec::new();
    for p in &want {
        match got.iter().find(|g| g.0 == p.name) {
            None => problems.push(format!(
                "{} {} [{} bits] is missing",
                p.direction, p.name, p.width
            )),
            Some(g) if g.1 != p.direction || g.2 != p.width => problems.push(format!(
                "{} is {} of {} bits in the RTL, {} of {} bits by the manifest",
                p.name, g.1, g.2, p.direction, p.width
            )),
            _ => {}
        }
    }
    for g in &got {
        if !want.iter().any(|p| p.name == g.0) {
            problems.push(format!(
                "{} {} is not a port the manifest implies",
                g.1, g.0
            ));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(input(format!(
            "the ports of {top} in {} disagree with the manifest in {} (was one of them edited?):\n  {}",
            src.display(),
            design.dir.display(),
            problems.join("\n  ")
        )))
    }
}
