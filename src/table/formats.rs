//! `specgen rom`: any table of the unit in an export format ($readmemh hex or binary, Xilinx
//! `.coe`, Intel `.mif`, a readable CSV).

use crate::bits::exact_decimal;
use crate::config::Config;
use crate::table::Table;
use askama::Template;

/// ROM export formats of `specgen rom`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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

/// Renders one table in one format. The text is complete and ends with a newline.
pub fn render_table(cfg: &Config, t: &Table, format: RomFormat) -> String {
    let (width, depth, top, what) = (t.width, t.words.len(), cfg.top(), t.what.as_str());
    let table = &t.words;
    let text = match format {
        RomFormat::Hex => ReadmemFile {
            words: words(table, 16, width),
        }
        .render(),
        RomFormat::Bin => ReadmemFile {
            words: words(table, 2, width),
        }
        .render(),
        RomFormat::Coe => CoeFile {
            top,
            what,
            width,
            depth,
            words: words(table, 16, width),
        }
        .render(),
        RomFormat::Mif => MifFile {
            top,
            what,
            width,
            depth,
            addr_digits: (t.address_bits() as usize).div_ceil(4).max(1),
            words: words(table, 16, width),
        }
        .render(),
        RomFormat::Csv if t.cosines.is_some() => {
            let f = t.cosines.unwrap_or_default();
            CsvFile {
                header: "n,code,cosine,angle_deg".into(),
                rows: table
                    .iter()
                    .enumerate()
                    .map(|(n, &code)| {
                        let cos = code as f64 / (1u64 << f) as f64;
                        format!(
                            "{n},{code},{},{:.4}",
                            exact_decimal(code as u64, f),
                            cos.acos().to_degrees()
                        )
                    })
                    .collect(),
            }
            .render()
        }
        RomFormat::Csv => CsvFile {
            header: format!(
                "index,word_hex,{}",
                t.fields
                    .iter()
                    .rev()
                    .map(|f| f.0.as_str())
                    .collect::<Vec<_>>()
                    .join(",")
            ),
            rows: table
                .iter()
                .enumerate()
                .map(|(i, &v)| {
                    let mut lo = 0;
                    let mut fields: Vec<String> = t
                        .fields
                        .iter()
                        .map(|(_, bits)| {
                            let f = (v >> lo) & crate::bits::mask(*bits);
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
