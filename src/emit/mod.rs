//! Stage 3b/4: config + widths → template context → emitted files, written atomically.
//!
//! Rust decides every width, literal and register placement here; `templates/unit.v`
//! holds only the Verilog's shape.

use crate::bits::{lit, mask};
use crate::config::{Params, RomStyle, Target};
use crate::datapath::{self, DelayLine, Waiting, Wire};
use crate::plan::Plan;
use crate::ports::Port;
use crate::table::formats::{self as rom, RomFormat};
use askama::Template;
use serde::Serialize;

pub(crate) use crate::names::{SIM_DIR, VERSION};

mod unit;
pub(crate) use unit::*;
mod cuts;
mod python;
#[cfg(test)]
mod tests;
mod text;

use cuts::*;
mod digest;
pub use digest::rtl_digest;
pub(crate) use text::*;

#[derive(Template)]
#[template(path = "unit.core")]
struct CoreTemplate<'a> {
    top: &'a str,
    /// the sim targets' testbench, its module and the vectors it reads
    testbench: String,
    tb_top: String,
    tb_vectors: String,
    /// `<top>.sdc` (and `<top>.lpf` on ECP5)
    constraint_files: Vec<String>,
    clock_mhz: String,
    version: &'a str,
    name: String,
    params: String,
    description: String,
    table_files: Vec<String>,
    /// RTL files beside `<top>.v` (the ECP5 product module)
    rtl_files: Vec<String>,
    /// the simulation models of the ECP5 primitives, for lint and simulation only
    sim_models: Vec<String>,
    /// the family FuseSoC's `synth` target maps for (`ecp5`: yosys alone; else the icestorm flow)
    arch: &'a str,
    /// the FuseSoC flags under which a dependent core gets the simulation models
    sim_flags: Vec<&'static str>,
}

/// The FuseSoC flags under which a core that depends on a unit gets its simulation models: a
/// target named `sim`/`lint` (the flow API sets `target_<name>`), or a simulator as the tool.
const SIM_FLAGS: [&str; 7] = [
    "target_sim",
    "target_lint",
    "tool_icarus",
    "tool_verilator",
    "tool_modelsim",
    "tool_questa",
    "tool_xsim",
];

/// The clock constraint `<top>.sdc` (every unit) or `<top>.lpf` (ECP5).
#[derive(Template)]
#[template(path = "unit.sdc")]
struct SdcTemplate<'a> {
    top: &'a str,
    version: &'a str,
    params: String,
    /// the clock port (`clk`, `aclk`); none: a combinational unit
    clock: Option<&'a str>,
    mhz: String,
    /// ns, three decimals
    period: String,
}

#[derive(Template)]
#[template(path = "unit.lpf")]
struct LpfTemplate<'a> {
    top: &'a str,
    version: &'a str,
    params: String,
    clock: Option<&'a str>,
    mhz: String,
}

/// The clock port of a unit (none when combinational).
pub(crate) fn clock_port(cfg: &crate::config::Config) -> Option<&'static str> {
    cfg.ports("")
        .iter()
        .map(|p| p.name)
        .find(|n| *n == "clk" || *n == "aclk")
}

/// `<top>.sdc`, and `<top>.lpf` for ECP5, at the configuration's clock, on the clock port of
/// the user's top when given (`clock_port`), else on the unit's own.
fn constraint_files(cfg: &crate::config::Config) -> Vec<(String, String)> {
    let top = cfg.top();
    let mhz = crate::family::clock_mhz(cfg);
    let mhz_text = format!("{mhz}");
    let clock = clock_port(cfg).map(|own| cfg.params.clock_port.as_deref().unwrap_or(own));
    let sdc = SdcTemplate {
        top,
        version: VERSION,
        params: cfg.describe(),
        clock,
        mhz: mhz_text.clone(),
        period: format!("{:.3}", 1000.0 / mhz),
    };
    let mut files = vec![(
        format!("{top}.sdc"),
        sdc.render().expect("sdc renders") + "\n",
    )];
    if crate::family::of(cfg.target()).lpf_constraints() {
        let lpf = LpfTemplate {
            top,
            version: VERSION,
            params: cfg.describe(),
            clock,
            mhz: mhz_text,
        };
        files.push((
            format!("{top}.lpf"),
            lpf.render().expect("lpf renders") + "\n",
        ));
    }
    files.extend(crate::family::of(cfg.target()).constraint_files(top));
    files
}

/// The output buffer `<top>_out_buffer` of a `ready`/`axis` unit.
#[derive(Template)]
#[template(path = "out_buffer.v")]
struct OutBufferTemplate<'a> {
    top: &'a str,
    version: &'a str,
}

/// The delay line's memory module `<top>_delay_ram` (a word delayed CUTS clocks in RAM).
#[derive(Template)]
#[template(path = "delay_ram.v")]
struct DelayRamTemplate<'a> {
    top: &'a str,
    version: &'a str,
    /// what the memory is, in words
    memory: &'a str,
    /// the memory's attributes after `no_rw_check`
    ram_style: &'a str,
}

/// The (word bits, cuts) of every delay line's tail in RAM (`<top>_delay_ram`), the datapath's
/// and the tag's, each pair once, in order.
pub fn delay_rams(plan: &Plan) -> Vec<(u32, u32)> {
    let mut out: Vec<(u32, u32)> = Vec::new();
    for p in delay_ram_tails(plan) {
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

/// The (word bits, cuts) of every delay line's tail in RAM, one entry a tail (an instance of
/// `<top>_delay_ram` each), in order.
pub fn delay_ram_tails(plan: &Plan) -> Vec<(u32, u32)> {
    let lines = cut_list(&plan.datapath, plan.cfg.target())
        .into_iter()
        .flat_map(|c| c.lines)
        .chain(crate::interface::tag_line(plan));
    lines
        .filter_map(|l| l.memory_tail().map(|(_, cuts)| (l.word(), cuts as u32)))
        .collect()
}

/// The FuseSoC VLNV of a configuration: `specgen:specular:<top>-<digest>:<version>`, the digest
/// (8 hex digits of SHA-256) taken over every parameter that shapes the files, so two
/// configurations never replace each other in one cores-root, and one configuration always
/// gets the same name.
pub fn core_name(cfg: &crate::config::Config) -> String {
    let digest = sha256_hex(
        format!(
            "{} rom_style={} top={}",
            cfg.describe(),
            cfg.params.rom_style.name(),
            cfg.top()
        )
        .as_bytes(),
    );
    format!("specgen:specular:{}-{}:{VERSION}", cfg.top(), &digest[..8])
}

/// Where each field sits in the `axis` unit's `tdata`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Tdata {
    pub(crate) s_axis: Vec<crate::ports::Field>,
    pub(crate) m_axis: Vec<crate::ports::Field>,
}

#[derive(Debug, Clone, Serialize)]
pub(crate) struct FileEntry {
    pub(crate) name: String,
    pub(crate) sha256: String,
}

/// The manifest `<top>.json` (SPEC §4): parameters at top level under their SPEC names.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Manifest<'a> {
    pub(crate) generator: &'static str,
    pub(crate) version: &'static str,
    /// `Config::fingerprint`: the unit's header repeats it
    pub(crate) fingerprint: String,
    #[serde(flatten)]
    pub(crate) params: &'a Params,
    pub(crate) k_code: u64,
    pub(crate) latency: u32,
    pub(crate) ports: Vec<Port>,
    /// The fields packed into `s_axis_tdata` and `m_axis_tdata` (the `axis` interface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) tdata: Option<Tdata>,
    /// The model's own widths and table sizes.
    pub(crate) internal_widths: serde_json::Value,
    /// The cuts that hold a pipeline register (1-based step numbers).
    pub(crate) registered_cuts: &'a [u32],
    /// The hard products whose block has no output register (SPEC §7), each with why; empty:
    /// every block has it, and `synth` fails naming any that does not.
    pub(crate) unregistered_products: Vec<Unregistered>,
    /// `Plan::stage_delay`: the slowest stretch between registers, in the delay estimates'
    /// units (what `--target-mhz`'s delay model reads)
    pub(crate) stage_delay_estimate: f64,
    /// `Plan::stage_delay_mean`
    pub(crate) stage_delay_mean: f64,
    /// `timing::predicted_fmax`: the delay model's clock for this unit on its family's part
    /// (null for a datapath without calibration)
    pub(crate) predicted_fmax_mhz: Option<f64>,
    /// `max |intensity/2^FI − c^n|` over the inputs of `blinn_error_method` (SPEC §6).
    pub(crate) blinn_error_max: f64,
    pub(crate) blinn_error_mean: f64,
    pub(crate) blinn_error_method: String,
    /// the same at the pixel: over every real cosine in [0, 1], rounded to F bits before the
    /// unit reads it (SPEC §6)
    pub(crate) pixel_error_max: f64,
    pub(crate) pixel_error_mean: f64,
    pub(crate) pixel_error_rms: f64,
    pub(crate) pixel_error_method: String,
    pub(crate) files: Vec<FileEntry>,
}

/// A product whose block has no output register, and why.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct Unregistered {
    pub(crate) name: String,
    pub(crate) why: String,
}

/// The hard products of the plan's unit whose block has no output register, each with why
/// (empty: every block has it).
pub fn unregistered(plan: &Plan) -> Vec<(String, String)> {
    unregistered_products(
        &plan.datapath,
        &cut_list(&plan.datapath, plan.cfg.target()),
        plan.cfg.target(),
    )
}

fn sha256_hex(bytes: &[u8]) -> String {
    crate::bits::sha256_hex(bytes, 32)
}

/// A unit's sources: its Verilog (the top, then the modules it instantiates), the simulation
/// models of its family's blocks (under `sim/`) and its tables' files, by name.
pub struct Sources {
    pub top: (String, String),
    pub rtl: Vec<(String, String)>,
    pub sim_models: Vec<(String, String)>,
    pub tables: Vec<crate::table::Table>,
}

/// The unit's sources alone (no manifest, testbench or vectors): what its RTL digest covers.
pub fn sources(plan: &Plan) -> Sources {
    let cfg = &plan.cfg;
    let top = cfg.top();
    let mut verilog =
        fold_long_lines(&unit_template(plan).render().expect("unit template renders"));
    verilog.push('\n');
    let dp = &plan.datapath;
    let tables: Vec<_> = match cfg.params.rom_style {
        RomStyle::File => dp
            .tables
            .iter()
            .enumerate()
            .filter(|(i, _)| !block_table(dp, *i))
            .map(|(_, t)| t.clone())
            .collect(),
        RomStyle::Case | RomStyle::Logic => Vec::new(),
    };
    // the ECP5 primitives' wrappers (RTL) and their simulation models (never synthesized)
    let (mut rtl_files, mut sim_models) = (Vec::new(), Vec::new());
    if cfg.interface().handshake() {
        let text = OutBufferTemplate {
            top,
            version: VERSION,
        }
        .render()
        .expect("buffer template renders")
            + "\n";
        rtl_files.push((format!("{top}_out_buffer.v"), text));
    }
    let blocks = crate::family::of(cfg.target()).blocks();
    if let Some(b) = blocks.filter(|_| dp.has_dsp_blocks()) {
        rtl_files.push((format!("{top}_mult18x18.v"), (b.dsp_module)(top)));
        sim_models.push((
            format!("{SIM_DIR}/{top}{}", b.dsp_model_suffix),
            (b.dsp_model)(),
        ));
    }
    if !delay_rams(plan).is_empty() {
        let distributed = crate::family::of(cfg.target()).distributed_ram();
        let ram_style = if distributed {
            ", ram_style = \"distributed\""
        } else {
            ""
        };
        let memory = datapath::memory_kind(distributed);
        let text = DelayRamTemplate {
            top,
            version: VERSION,
            memory,
            ram_style,
        }
        .render()
        .expect("delay_ram template renders")
            + "\n";
        rtl_files.push((format!("{top}_delay_ram.v"), text));
    }
    if let Some(b) = blocks.filter(|_| dp.has_block_rams()) {
        rtl_files.push((format!("{top}_rom1k18.v"), (b.bram_module)(top)));
        sim_models.push((
            format!("{SIM_DIR}/{top}{}", b.bram_model_suffix),
            (b.bram_model)(),
        ));
    }
    // the primitives as black boxes, for a synthesis tool that lacks them
    if let Some((suffix, text)) = blocks
        .filter(|_| dp.has_dsp_blocks() || dp.has_block_rams())
        .and_then(|b| b.boxes)
    {
        rtl_files.push((format!("{top}{suffix}"), text(top)));
    }
    Sources {
        top: (format!("{top}.v"), verilog),
        rtl: rtl_files,
        sim_models,
        tables,
    }
}

/// The files [`sources`] names, in the order `generate` lists them: the top, the RTL modules,
/// the simulation models, the tables.
pub fn source_files(plan: &Plan) -> Vec<(String, Vec<u8>)> {
    let s = sources(plan);
    let mut files = vec![(s.top.0, s.top.1.into_bytes())];
    files.extend(
        s.rtl
            .into_iter()
            .chain(s.sim_models)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    for t in &s.tables {
        files.push((
            t.file(plan.cfg.top()),
            rom::render_table(&plan.cfg, t, RomFormat::Hex).into_bytes(),
        ));
    }
    files
}

/// Every file of a `generate` run, in memory: (file name, contents).
pub fn generate_files(plan: &Plan) -> Vec<(String, Vec<u8>)> {
    let cfg = &plan.cfg;
    let top = cfg.top();
    let unit = plan.model.unit();
    let Sources {
        top: (top_name, verilog),
        rtl: rtl_files,
        sim_models,
        tables,
    } = sources(plan);
    let description = unit.describe().summary;
    let mut files = vec![(top_name, verilog.into_bytes())];
    let constraints = constraint_files(cfg);
    let testbench = crate::vectors::testbench_files(&plan.model);
    let core = CoreTemplate {
        testbench: testbench[0].0.clone(),
        tb_top: format!("{top}_tb"),
        tb_vectors: testbench[1].0.clone(),
        top,
        constraint_files: constraints.iter().map(|(n, _)| n.clone()).collect(),
        clock_mhz: format!("{}", crate::family::clock_mhz(cfg)),
        version: VERSION,
        name: core_name(cfg),
        params: cfg.describe(),
        description: format!("{description}, {}-cycle latency", cfg.latency()),
        table_files: tables.iter().map(|t| t.file(top)).collect(),
        rtl_files: rtl_files.iter().map(|(n, _)| n.clone()).collect(),
        sim_models: sim_models.iter().map(|(n, _)| n.clone()).collect(),
        arch: crate::family::of(cfg.target()).fusesoc_arch(),
        sim_flags: if sim_models.is_empty() {
            Vec::new()
        } else {
            SIM_FLAGS.to_vec()
        },
    }
    .render()
    .expect("core template renders")
        + "\n";
    files.extend(
        rtl_files
            .into_iter()
            .chain(sim_models)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    for t in &tables {
        files.push((
            t.file(top),
            rom::render_table(cfg, t, RomFormat::Hex).into_bytes(),
        ));
    }
    files.extend(
        constraints
            .into_iter()
            .chain(testbench)
            .map(|(n, t)| (n, t.into_bytes())),
    );
    files.push((format!("{top}.core"), core.into_bytes()));
    // the unit in the Python HDLs (Amaranth, LiteX): what they add to a build is its RTL and
    // tables, never the simulation models or the testbench
    let synthesized: Vec<String> = files
        .iter()
        .map(|(n, _)| n.clone())
        .filter(|n| {
            (n.ends_with(".v") || n.ends_with(".hex"))
                && !n.starts_with(SIM_DIR)
                && !n.ends_with("_vectors.hex")
        })
        .collect();
    files.extend(
        python::python_files(plan, synthesized)
            .into_iter()
            .map(|(n, t)| (n, t.into_bytes())),
    );
    let fidelity = plan.model.fidelity();
    let manifest = Manifest {
        generator: "specgen",
        version: VERSION,
        fingerprint: cfg.fingerprint(),
        // the reset's polarity stated always, the interface's own included
        params: &Params {
            reset: Some(cfg.reset()),
            ..cfg.params.clone()
        },
        k_code: cfg.k_code,
        latency: cfg.latency(),
        ports: cfg.ports(""),
        tdata: (cfg.interface() == crate::config::Interface::Axis).then(|| {
            let (s_axis, _, m_axis, _) = crate::ports::tdata_fields(cfg.port_widths());
            Tdata { s_axis, m_axis }
        }),
        internal_widths: unit.widths(),
        registered_cuts: &plan.registered_cuts,
        unregistered_products: unregistered(plan)
            .into_iter()
            .map(|(name, why)| Unregistered { name, why })
            .collect(),
        stage_delay_estimate: (plan.stage_delay() * 100.0).round() / 100.0,
        stage_delay_mean: (plan.stage_delay_mean() * 100.0).round() / 100.0,
        predicted_fmax_mhz: crate::timing::predicted_fmax(plan).map(|f| (f * 10.0).round() / 10.0),
        blinn_error_max: fidelity.max,
        blinn_error_mean: fidelity.mean,
        blinn_error_method: fidelity.method(),
        pixel_error_max: fidelity.pixel.max,
        pixel_error_mean: fidelity.pixel.mean,
        pixel_error_rms: fidelity.pixel.rms,
        pixel_error_method: fidelity.pixel_method(),
        files: files
            .iter()
            .map(|(name, bytes)| FileEntry {
                name: name.clone(),
                sha256: sha256_hex(bytes),
            })
            .collect(),
    };
    // only the model's own parameters (MODEL_KEYS): a reader branches on `model`
    let mut value = serde_json::to_value(&manifest).expect("manifest serialises");
    cfg.model().keep_own_keys(&mut value);
    let mut json = serde_json::to_string_pretty(&value).expect("manifest serialises");
    json.push('\n');
    files.push((format!("{top}.json"), json.into_bytes()));
    files
}
