//! The cut-off ROM `cos_sp(n)` (SPEC §3) and its export formats.
//!
//! Entry n is the smallest code `C ∈ [0, 2^F]` whose bracket `1 − k_q·n·(1 − C/2^F)` is
//! non-negative. With `P(C) = k_code·n·(2^F − C)` that is `P(C) ≤ 2^(KF+F)`, i.e.
//! `2^F − C ≤ ⌊2^(KF+F) / (k_code·n)⌋`, so `C = max(0, 2^F − ⌊2^(KF+F) / (k_code·n)⌋)`
//! (and `C = 0` for `n = 0`, where the bracket is 1 everywhere).

use crate::config::Config;
use crate::datapath::Table;
use askama::Template;

/// Every entry of the ROM, index n = 0 .. 2^N − 1.
pub fn cos_sp_table(cfg: &Config) -> Vec<u32> {
    (0..1u64 << cfg.n_bits()).map(|n| cos_sp(cfg, n)).collect()
}

/// The cut-off code for one exponent n.
pub fn cos_sp(cfg: &Config, n: u64) -> u32 {
    let one = 1u128 << cfg.f();
    let kn = cfg.k_code as u128 * n as u128;
    if kn == 0 {
        return 0;
    }
    let reach = (1u128 << (cfg.kf() + cfg.f())) / kn; // largest 2^F − C with bracket ≥ 0
    one.saturating_sub(reach) as u32
}

/// ROM export formats of `specgen rom`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum RomFormat {
    /// `$readmemh`: one zero-padded hex word a line.
    Hex,
    /// `$readmemb`: one zero-padded binary word a line.
    Bin,
    /// Xilinx memory coefficient file.
    Coe,
    /// Intel memory initialization file.
    Mif,
    /// Readable table: n, code, cosine, angle in degrees.
    Csv,
}

struct Word {
    index: usize,
    /// the word in the format's radix, zero-padded
    text: String,
    last: bool,
}

#[derive(Template)]
#[template(path = "rom.hex")]
struct ReadmemFile {
    words: Vec<Word>,
}

#[derive(Template)]
#[template(path = "rom.coe")]
struct CoeFile<'a> {
    top: &'a str,
    what: &'a str,
    width: u32,
    depth: usize,
    words: Vec<Word>,
}

#[derive(Template)]
#[template(path = "rom.mif")]
struct MifFile<'a> {
    top: &'a str,
    what: &'a str,
    width: u32,
    depth: usize,
    addr_digits: usize,
    words: Vec<Word>,
}

#[derive(Template)]
#[template(path = "rom.csv")]
struct CsvFile {
    header: String,
    rows: Vec<String>,
}

fn words(table: &[u128], radix: u32, width: u32) -> Vec<Word> {
    let digits = match radix {
        2 => width as usize,
        _ => width.div_ceil(4) as usize,
    };
    table
        .iter()
        .enumerate()
        .map(|(index, &v)| Word {
            index,
            text: match radix {
                2 => format!("{v:0digits$b}"),
                _ => format!("{v:0digits$x}"),
            },
            last: index + 1 == table.len(),
        })
        .collect()
}

/// `code / 2^F` written exactly in decimal (a dyadic fraction always has a finite expansion).
pub fn exact_decimal(code: u64, frac_bits: u32) -> String {
    let int = code >> frac_bits;
    let mut rem = (code & ((1u64 << frac_bits) - 1)) as u128;
    let mut s = format!("{int}.");
    if rem == 0 {
        s.push('0');
    }
    while rem != 0 {
        rem *= 10;
        s.push(char::from(b'0' + (rem >> frac_bits) as u8));
        rem &= (1u128 << frac_bits) - 1;
    }
    s
}

/// Renders one table in one format. The text is complete and ends with a newline.
pub fn render_table(cfg: &Config, t: &Table, format: RomFormat) -> String {
    let (width, depth, top, what) = (t.width, t.words.len(), cfg.top(), t.what.as_str());
    let table = &t.words;
    let text = match format {
        RomFormat::Hex => ReadmemFile { words: words(table, 16, width) }.render(),
        RomFormat::Bin => ReadmemFile { words: words(table, 2, width) }.render(),
        RomFormat::Coe => CoeFile { top, what, width, depth, words: words(table, 16, width) }.render(),
        RomFormat::Mif => {
            MifFile { top, what, width, depth, addr_digits: (t.address_bits() as usize).div_ceil(4).max(1), words: words(table, 16, width) }.render()
        }
        RomFormat::Csv if t.name == "cos_sp_rom" => CsvFile {
            header: "n,code,cosine,angle_deg".into(),
            rows: table
                .iter()
                .enumerate()
                .map(|(n, &code)| {
                    let cos = code as f64 / (1u64 << cfg.f()) as f64;
                    format!("{n},{code},{},{:.4}", exact_decimal(code as u64, cfg.f()), cos.acos().to_degrees())
                })
                .collect(),
        }
        .render(),
        RomFormat::Csv => CsvFile {
            header: format!("index,word_hex,{}", t.fields.iter().rev().map(|f| f.0.as_str()).collect::<Vec<_>>().join(",")),
            rows: table
                .iter()
                .enumerate()
                .map(|(i, &v)| {
                    let mut lo = 0;
                    let mut fields: Vec<String> = t
                        .fields
                        .iter()
                        .map(|(_, bits)| {
                            let f = (v >> lo) & crate::widths::mask(*bits);
                            lo += bits;
                            f.to_string()
                        })
                        .collect();
                    fields.reverse();
                    format!("{i},{v:x},{}", fields.join(","))
                })
                .collect(),
        }
        .render(),
    };
    text.expect("ROM templates render")
}

/// The cut-off ROM (10) as a table of the unit.
pub fn cos_sp_rom(cfg: &Config) -> Table {
    Table {
        name: "cos_sp_rom".into(),
        file: crate::emit::ROM_FILE.into(),
        param: "ROM_FILE".into(),
        width: cfg.f() + 1,
        words: cos_sp_table(cfg).into_iter().map(u128::from).collect(),
        what: format!("cut-off ROM cos_sp(n), UQ1.{}, address = n", cfg.f()),
        fields: vec![("cos_sp".into(), cfg.f() + 1)],
    }
}

/// Renders the cut-off ROM (quadratic) in one format.
pub fn render(cfg: &Config, format: RomFormat) -> String {
    render_table(cfg, &cos_sp_rom(cfg), format)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_decimal_is_exact() {
        assert_eq!(exact_decimal(1, 1), "0.5");
        assert_eq!(exact_decimal(3, 2), "0.75");
        assert_eq!(exact_decimal(1 << 15, 15), "1.0");
        assert_eq!(exact_decimal(1, 15), "0.000030517578125");
    }
}
