//! `specgen vectors`: golden vectors for any testbench (cocotb, UVM, a vendor simulator).
//!
//! One row per input — corner cases, a boundary for every n, then random vectors; or every
//! `(cos_g ≤ 2^F, n)` — with the outputs the golden model gives for it. Two formats: CSV (a
//! header row of port names, unsigned decimal codes) and `$readmemh` hex (one packed word per
//! row). A comment header states the configuration and when the outputs of a row appear.
//! The rows are streamed to a writer, so an exhaustive set of 33.5 M rows never sits in memory.

use crate::config::Config;
use crate::cosim::{corner_vectors, random_vector, Exhaustive, Stimulus};
use crate::models::{Inputs, Model, Outputs};
use crate::ports::VECTOR_COLUMNS;
use askama::Template;
use std::io::Write;

/// Which inputs the rows cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    /// the corner cases and every n's boundary, then `count` random vectors from `seed`
    Random { count: u64, seed: u64 },
    /// every `(cos_g, n)` with `cos_g ∈ [0, 2^F]` (colours varied, as `cosim --exhaustive`),
    /// then every colour code at full intensity
    Exhaustive,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VectorFormat {
    /// CSV: comment header, a row of port names, one row per input (unsigned decimal)
    Csv,
    /// `$readmemh`: comment header, one packed hex word per input
    Hex,
}

/// The ports of a row, in column order (inputs, then outputs), with their widths: the port
/// table's data ports in the order of [`VECTOR_COLUMNS`].
pub(crate) fn columns(cfg: &Config) -> Vec<(&'static str, u32)> {
    // the logical ports: an `axis` unit packs them into tdata, at the same widths
    let ports = cfg.logical_ports();
    VECTOR_COLUMNS
        .iter()
        .map(|c| {
            (
                *c,
                ports
                    .iter()
                    .find(|p| p.name == *c)
                    .expect("every column is a port")
                    .width,
            )
        })
        .collect()
}

/// A row's values, in column order.
fn values(x: Inputs, y: Outputs) -> [u64; 10] {
    VECTOR_COLUMNS.map(|c| {
        x.value(c)
            .or_else(|| y.value(c))
            .expect("every column is an input or an output")
    })
}

/// The inputs of `selection`, in row order, and how many there are.
pub fn inputs(model: &Model, selection: Selection) -> (u64, Box<dyn Iterator<Item = Inputs> + '_>) {
    let cfg = &model.cfg;
    match selection {
        Selection::Random { count, seed } => {
            let corners = corner_vectors(model);
            (
                corners.len() as u64 + count,
                Box::new(
                    corners
                        .into_iter()
                        .chain((0..count).map(move |i| random_vector(cfg, seed, i))),
                ),
            )
        }
        Selection::Exhaustive => {
            let all = Exhaustive::parts(cfg, 1).pop().expect("one part");
            // every cycle but the reset (and colour load) a sweep starts with and its drain
            let rows = all.len() - all.lead() - all.drain;
            (
                rows,
                Box::new(
                    (0..all.len())
                        .map(move |i| all.cycle(i))
                        .filter(|c| c.valid && !c.rst)
                        .map(|c| c.inputs),
                ),
            )
        }
    }
}

#[derive(Template)]
#[template(path = "vectors.txt")]
struct Header<'a> {
    c: &'a str,
    top: &'a str,
    version: &'a str,
    model: &'a str,
    selection: String,
    rows: u64,
    params: String,
    fingerprint: String,
    latency: u32,
    handshake: bool,
    hex: bool,
    word_bits: u32,
    fields: String,
    columns: String,
}

/// Writes the vectors of `selection` to `out` in `format`; returns the number of rows.
pub fn write(
    model: &Model,
    selection: Selection,
    format: VectorFormat,
    out: &mut dyn Write,
) -> std::io::Result<u64> {
    let cfg = &model.cfg;
    let (rows, inputs) = inputs(model, selection);
    let cols = columns(cfg);
    let word_bits: u32 = cols.iter().map(|c| c.1).sum();
    let mut hi = word_bits;
    let fields = cols
        .iter()
        .map(|(name, w)| {
            hi -= w;
            format!("{name}[{}:{}]", hi + w - 1, hi)
        })
        .collect::<Vec<_>>()
        .join(" ");
    let hex = format == VectorFormat::Hex;
    let header = Header {
        c: if hex { "//" } else { "#" },
        top: cfg.top(),
        version: env!("CARGO_PKG_VERSION"),
        model: cfg.model().name(),
        selection: match selection {
            Selection::Random { count, seed } => format!(
                "corner cases and every n's boundary, then {count} random vectors (seed {seed})"
            ),
            Selection::Exhaustive => {
                "every (cos_g <= 1.0, n), then every colour code at full intensity".to_string()
            }
        },
        rows,
        params: cfg.describe(),
        fingerprint: cfg.fingerprint(),
        latency: cfg.latency(),
        handshake: cfg.interface().handshake(),
        hex,
        word_bits,
        fields,
        columns: cols.iter().map(|c| c.0).collect::<Vec<_>>().join(","),
    };
    let mut text = header.render().expect("vectors header renders");
    text.push('\n');
    out.write_all(text.as_bytes())?;
    let digits = word_bits.div_ceil(4) as usize;
    let mut line = String::new();
    for x in inputs {
        let v = values(x, model.eval(x));
        line.clear();
        if hex {
            let mut word = 0u128;
            for (value, (_, w)) in v.iter().zip(&cols) {
                word = (word << w) | *value as u128;
            }
            line.push_str(&format!("{word:0digits$x}\n"));
        } else {
            let mut first = true;
            for value in v {
                if !first {
                    line.push(',');
                }
                first = false;
                line.push_str(&value.to_string());
            }
            line.push('\n');
        }
        out.write_all(line.as_bytes())?;
    }
    Ok(rows)
}

/// The self-checking testbench of the FuseSoC sim targets.
#[derive(Template)]
#[template(path = "unit_tb.sv")]
struct Testbench<'a> {
    top: &'a str,
    version: &'a str,
    interface: &'a str,
    vectors: String,
    rows: u64,
    word_bits: u32,
    cos_w: u32,
    n_w: u32,
    b_w: u32,
    i_w: u32,
    handshake: bool,
    static_colour: bool,
    /// the unit has a clock enable: the bench drives it low one edge in four at random
    clock_enable: bool,
    tag_bits: u32,
    /// cycles a row may take at most (a colour load waits for the unit to drain)
    patience: u64,
    cos_g: (u32, u32),
    n: (u32, u32),
    ks_r: (u32, u32),
    ks_g: (u32, u32),
    ks_b: (u32, u32),
    intensity: (u32, u32),
    spec_r: (u32, u32),
    spec_g: (u32, u32),
    spec_b: (u32, u32),
    done: (u32, u32),
    /// the port adapter (`<top>_tb_ports`): one set of names for every interface
    ports: String,
}

/// Rows of the testbench's vectors: the corners, every n's boundary, and these random ones.
pub const TESTBENCH_RANDOM_ROWS: u64 = 1000;

/// The FuseSoC sim targets' files: `<top>_tb.sv` and the vectors it reads, `<top>_vectors.hex`.
pub fn testbench_files(model: &Model) -> Vec<(String, String)> {
    let cfg = &model.cfg;
    let top = cfg.top();
    let vectors_file = format!("{top}_vectors.hex");
    let mut text = Vec::new();
    let rows = write(
        model,
        Selection::Random {
            count: TESTBENCH_RANDOM_ROWS,
            seed: 1,
        },
        VectorFormat::Hex,
        &mut text,
    )
    .expect("vectors to memory");
    let cols = columns(cfg);
    let word_bits: u32 = cols.iter().map(|c| c.1).sum();
    let at = |name: &str| {
        let mut hi = word_bits;
        for (n, w) in &cols {
            hi -= w;
            if *n == name {
                return (hi + w - 1, hi);
            }
        }
        unreachable!("{name} is a column")
    };
    let handshake = cfg.interface().handshake();
    let static_colour = cfg.colour() == crate::config::Colour::Static;
    let places = crate::interface::buffer_places(cfg);
    let tb = Testbench {
        top,
        version: crate::names::VERSION,
        interface: cfg.interface().name(),
        vectors: vectors_file.clone(),
        rows,
        word_bits,
        cos_w: cfg.f() + 1,
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
        handshake,
        static_colour,
        clock_enable: cfg.params.clock_enable,
        tag_bits: cfg.carried_tag_bits(),
        patience: (if static_colour {
            cfg.latency() as u64 + places + 24
        } else {
            24
        }) * if cfg.params.clock_enable { 2 } else { 1 },
        cos_g: at("cos_g"),
        n: at("n"),
        ks_r: at("ks_r"),
        ks_g: at("ks_g"),
        ks_b: at("ks_b"),
        intensity: at("intensity"),
        spec_r: at("spec_r"),
        spec_g: at("spec_g"),
        spec_b: at("spec_b"),
        done: at("done"),
        ports: crate::cosim::adapter::adapter_named(cfg, &format!("{top}_tb_ports")),
    };
    let tb_text = tb.render().expect("testbench renders") + "\n";
    vec![
        (format!("{top}{}", crate::names::TESTBENCH_SUFFIX), tb_text),
        (
            vectors_file,
            String::from_utf8(text).expect("ASCII vectors"),
        ),
    ]
}
