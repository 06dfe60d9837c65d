//! The command line: parse flags, build a [`Config`], call the library, map errors to exit codes
//! (2: bad parameters or usage, 1: a check failed or an I/O error).

mod calibrate;
mod cosim;
mod eval;
mod explore;
mod info;
mod params;
mod prove;
mod render;
mod sweep;
mod synth;
mod values;

use clap::{Args, Parser, Subcommand};
use params::*;
pub use params::{ParamArgs, RtlArgs};
use specgen::bits::exact_decimal;
use specgen::config::{self, Config, Params};
use specgen::emit;
use specgen::models::Inputs;
use specgen::plan::Plan;
use specgen::table::formats as rom;
use std::path::PathBuf;
use values::{
    ArchFlag, ColourFlag, InterfaceFlag, ModelFlag, ResetFlag, RomFormatFlag, RomStyleFlag,
    RoundingFlag, TargetFlag, VectorFormatFlag,
};

#[derive(Parser, Debug)]
#[command(
    name = "specgen",
    version,
    about = "Generate a fixed-point specular highlight unit (Verilog-2005) and its golden model",
    after_help = "Exit codes: 0 success; 1 a check failed (a mismatch, a broken contract, a tool's error) or a file could not be read or written; 2 invalid parameters or usage."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Write <top>.v, its table files (<top>_cos_sp_rom.hex, ...), <top>.json and <top>.core into DIR, atomically.
    Generate {
        /// Output directory (created, or replaced if it holds only a previous specgen output).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Replace a previous output even where its files were edited by hand.
        #[arg(long)]
        force: bool,
        /// Pick --stages: the shallowest pipeline that reaches F MHz on the --target's part (ice40: iCE40 UP5K, ecp5: ECP5-25 grade 6, gowin: GW1NR-9 C6/I5, with DSPs) by the delay model calibrated on nextpnr (in milliseconds; `synth --seeds K` measures it). Refused with --target generic, whose RTL names no device to be calibrated on: give --stages there.
        #[arg(
            long,
            value_name = "F",
            conflicts_with = "stages",
            allow_negative_numbers = true
        )]
        target_mhz: Option<f64>,
        /// Choose the unit (model, widths, depth, budget, ROM style) instead of taking the flags:
        /// the cheapest in logic cells of the exploration's measured units whose --metric error
        /// is at most E and whose median Fmax over seeds reaches --target-mhz (a --model or
        /// --dsp-budget given narrows the choice); it prints the choice and its evidence, and is
        /// refused naming the nearest units when none meets both [(0, 1]]
        #[arg(
            long,
            value_name = "E",
            requires = "target_mhz",
            allow_negative_numbers = true
        )]
        max_error: Option<f64>,
        /// The error --max-error bounds.
        #[arg(long, value_enum, default_value = "max", requires = "max_error")]
        metric: values::MetricFlag,
        /// The exploration --max-error chooses from (`specgen explore`'s points.json) [default:
        /// the one built in for the --target]
        #[arg(long, value_name = "FILE", requires = "max_error")]
        explored: Option<PathBuf>,
        /// The display of --metric display-max and display-banding: srgbB (sRGB, B bits) or
        /// gammaG:B (a power law) [B 1..=16, G 1..=4]
        #[arg(
            long,
            value_name = "DISPLAY",
            default_value = "srgb8",
            requires = "max_error"
        )]
        display: String,
        /// Where --target-mhz is refused, also say how: the best depth's figures, the rule of
        /// the delay model that gave them, the calibrated unit that holds them down.
        #[arg(long, requires = "target_mhz")]
        explain: bool,
        #[command(flatten)]
        params: ParamArgs,
        #[command(flatten)]
        rtl: RtlArgs,
    },
    /// Export one table of the unit: the cut-off ROM cos_sp(n) (quadratic), the fit ROM
    /// (fitted), the log2 or exp2 table (blinn), the reciprocal table (schlick).
    Rom {
        /// Which table [default: the model's first: cos_sp_rom, fit_rom, log2_rom, recip_rom]
        #[arg(long, value_name = "NAME")]
        table: Option<String>,
        #[arg(long, value_enum, default_value = "hex")]
        format: RomFormatFlag,
        /// Output file (default: standard output).
        #[arg(short = 'o', long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// The module name the .coe/.mif header names [default: specular_unit]
        #[arg(long)]
        top: Option<String>,
        #[command(flatten)]
        params: ParamArgs,
    },
    /// Show the golden model's outputs and internal values for one input, beside the exact
    /// value, formula (15) in real arithmetic, and Blinn's cos^n.
    Eval {
        /// cos(gamma) as a decimal in [0, 2), rounded to the nearest UQ1.F code.
        #[arg(
            allow_negative_numbers = true,
            long,
            value_name = "X",
            conflicts_with = "cos_code",
            required_unless_present = "cos_code"
        )]
        cos: Option<String>,
        /// cos(gamma) as the raw UQ1.F port code.
        #[arg(allow_negative_numbers = true, value_parser = param_whole, long, value_name = "CODE")]
        cos_code: Option<u32>,
        /// Specular exponent n.
        #[arg(allow_negative_numbers = true, value_parser = param_whole, long)]
        n: u32,
        /// Colour codes R,G,B (default: all ones, i.e. 1.0).
        #[arg(long, value_name = "R,G,B", value_delimiter = ',')]
        ks: Option<Vec<u32>>,
        #[command(flatten)]
        params: ParamArgs,
    },
    /// Check generated (or hand-edited, or synthesized) Verilog against the golden model.
    Cosim(cosim::CosimArgs),
    /// Prove the unit's edge, of the design synthesis builds (the elaboration every step reads is
    /// first proved equal to it at every port bit; the unit's own assumes are removed): valid's
    /// latency by ABC's pdr, unbounded; ready/axis: a port checker written from the manifest,
    /// apart from the RTL, over every output port bit, first searched for latency + 8 edges with
    /// the unit's own assertions (ABC's bmc3: a fault fails there with a trace), its covers
    /// reached, then proved for every edge by k-induction with yosys's sat over its assertions
    /// and the unit's own, and the values at cos_g = 1.0 checked against the datapath twin;
    /// --depth N searches the first N edges instead, --pipelining proves the pipeline changes
    /// nothing (ABC's iprove), --datapath that a ready/axis unit delivers its datapath's values.
    Prove(prove::ProveArgs),
    /// Write golden vectors for any testbench: CSV (a header row of port names) or $readmemh
    /// hex, one row per input with the golden model's outputs; the header states the timing.
    Vectors(VectorsArgs),
    /// Explore a space of units (models, widths, depths, --dsp-budget, --rom-style) on one
    /// target: each point's accuracy (golden model: max, mean, RMS error, the sphere's PSNR and
    /// banding step), its cost estimated, the points on or near the front as sweep jobs
    /// (jobs.json; scripts/sweep.sh runs them on Snakemake), and with --results the measured
    /// front, per clock, as CSV, JSON and SVG.
    Explore(explore::ExploreArgs),
    /// Run one job of a sweep (explore's jobs.json): generate its unit, synthesize and
    /// place-and-route it with its seed, write the result under its fingerprint.
    Measure(explore::MeasureArgs),
    /// List the measured rows of the explorations `generate --max-error` chooses from that are
    /// not of today's RTL (their jobs' RTL digest is another): exit 1 when any is.
    Stale(calibrate::StaleArgs),
    /// Fit the delay model of --target-mhz to a calibration CSV (data/delay_calibration.csv's
    /// columns): per family and datapath, the clock period as a plane in the slowest and the mean
    /// stretch of logic, its cap and margin, and each row kept as a floor; written as JSON
    /// (data/delay_model.json's form) to --out. Every row's stretches are planned here.
    Calibrate(calibrate::CalibrateArgs),
    /// What this specgen offers, for scripts (never parse an error message): its version, the
    /// models, the targets (with their parts, and whether a delay model and a built-in
    /// exploration speak for them), and the deepest pipeline of the configuration the flags give.
    Info {
        /// Print JSON (the only form; the flag says so in scripts).
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        params: ParamArgs,
        #[command(flatten)]
        rtl: RtlArgs,
    },
    /// Synthesize the RTL in DIR with yosys (and nextpnr for Fmax): LUTs, carries, DSPs, FFs, ROM.
    Synth(synth::SynthArgs),
    /// Render a sphere and a plane at grazing light with the unit in DIR, beside float cos^n and
    /// their difference, one row per n, as a PNG. Pixels go through the RTL (co-simulation) and
    /// must be bit-identical to the golden model; --model-only skips the simulator.
    Render(RenderArgs),
    /// Write DIR/index.html (self-contained) and DIR/report.json: the paper's claims
    /// recomputed and the configured unit's accuracy.
    Report {
        /// Output directory (created, or replaced if it holds only a previous report).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Replace a previous report even where its files were edited by hand.
        #[arg(long)]
        force: bool,
        /// A `specgen synth --json` result to show in the model comparison (repeatable).
        #[arg(long, value_name = "FILE.json")]
        hw: Vec<PathBuf>,
        /// An exploration (`specgen explore`'s points.json) whose measured front the page shows.
        #[arg(long, value_name = "FILE")]
        explored: Option<PathBuf>,
        #[command(flatten)]
        params: ParamArgs,
    },
}

#[derive(Args, Debug, Clone)]
pub struct VectorsArgs {
    /// Directory with the generated unit (its manifest states the configuration).
    #[arg(long, value_name = "DIR")]
    pub rtl: PathBuf,
    /// Random vectors after the corner cases and every n's boundary [0..=100000000].
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u64).range(0..=100_000_000))]
    pub count: u64,
    /// Seed of the random vectors.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Every (cos_g <= 1.0, n), colours varied, instead of random vectors (2^N * (2^F + 1) rows).
    #[arg(long, conflicts_with_all = ["count", "seed"])]
    pub exhaustive: bool,
    /// The most rows written: a larger --exhaustive set is refused before anything is written
    /// (the default configuration's is 33.6 M rows, ~1.3 GB of CSV) [1..=4294967296]
    #[arg(long, value_name = "N", default_value_t = 1 << 26, value_parser = clap::value_parser!(u64).range(1..=1 << 32))]
    pub max_rows: u64,
    /// csv or hex [default: hex for FILE ending in .hex or .mem, else csv]
    #[arg(long, value_enum)]
    pub format: Option<VectorFormatFlag>,
    /// The file to write (atomically).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
}

#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// A directory with a generated unit (Verilog, tables, manifest); repeat it to put units
    /// side by side.
    #[arg(long, value_name = "DIR")]
    pub rtl: Vec<PathBuf>,
    /// Models to generate with default parameters (into a temporary directory) and render side
    /// by side, after the --rtl units: e.g. quadratic,fitted,blinn.
    #[arg(long, value_delimiter = ',', value_name = "MODEL,...")]
    pub models: Vec<values::ModelFlag>,
    /// The PNG to write.
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
    /// Exponents, one row each per scene [each 0..=2^n_bits-1]
    #[arg(long, value_delimiter = ',', default_value = "1,4,16,128")]
    pub n: Vec<u32>,
    /// Pixels per tile side [16..=1024]
    #[arg(allow_negative_numbers = true, value_parser = param_size, long, default_value_t = 128)]
    pub size: u32,
    /// Take the pixels from the golden models without simulating the RTL.
    #[arg(long)]
    pub model_only: bool,
    /// The simulator of the RTL's pixels.
    #[command(flatten)]
    pub sim: values::SimToolArgs,
}

/// Writes to standard output; a closed pipe (`specgen rom … | head -1`) ends the program
/// quietly with exit 0, any other failure (a full disk) is an error naming standard output —
/// never a panic.
pub(crate) fn write_stdout(args: std::fmt::Arguments) -> Result<(), Failure> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_fmt(args).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => Err(Failure::io("write", "standard output", e)),
    }
}

/// `print!` that returns an error instead of panicking (see [`write_stdout`]).
macro_rules! out {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!($($t)*)) };
}
/// `println!` that returns an error instead of panicking (see [`write_stdout`]).
macro_rules! outln {
    ($($t:tt)*) => { $crate::cli::write_stdout(format_args!("{}\n", format_args!($($t)*))) };
}
/// `eprintln!` that never panics: a message to a full or closed standard error is lost, the
/// exit code is not.
macro_rules! errln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}
/// The CLI's names for the library's error constructors: a usage error is the user's input
/// not being what it must be (exit 2), a failed check is a mismatch (exit 1).
pub use specgen::error::{input as usage, mismatch as failed, Error as Failure};
pub(crate) use {errln, out, outln};

/// The exit code of an error: 2 for what the user must change (a parameter, an input, an
/// occupied output directory), 1 for a check that failed, a tool's error, a file.
fn exit_code(e: &Failure) -> i32 {
    match e {
        Failure::Config { .. }
        | Failure::Input(_)
        | Failure::Occupied { .. }
        | Failure::Refused { .. } => 2,
        Failure::Busy { .. }
        | Failure::Tool { .. }
        | Failure::Mismatch(_)
        | Failure::Breach { .. }
        | Failure::Io { .. } => 1,
    }
}

/// The message of an error and its causes, a parameter named by its flag.
fn message(e: &Failure) -> String {
    match e {
        Failure::Config { parameter, message } => {
            format!("invalid --{}: {message}", parameter.replace('_', "-"))
        }
        _ => specgen::error::chain(e),
    }
}

/// Writes a whole output directory atomically; an occupied directory is a usage error.
fn write_output(
    out: &std::path::Path,
    files: &[(String, Vec<u8>)],
    force: bool,
) -> Result<(), Failure> {
    // an I/O error names the output as the user spelled it
    specgen::output::write_dir_atomically_forced(out, files, force).map_err(|e| match e {
        Failure::Io { action, source, .. } => Failure::io(action, out, source),
        other => other,
    })
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Generate {
            out,
            force,
            target_mhz,
            max_error,
            metric,
            explored,
            display,
            explain,
            params,
            rtl,
        } => {
            if let Some(config) = &params.config {
                if specgen::output::inside(config, &out) {
                    return Err(usage(format!(
                        "invalid --out: {} holds {}, the --config file this command reads; the output replaces its directory whole: write it elsewhere",
                        out.display(),
                        config.display()
                    )));
                }
            }
            let mut cfg = params.to_config(Some(&rtl))?;
            if let Some(mhz) = target_mhz {
                if !(0.001..=1000.0).contains(&mhz) {
                    let shown =
                        if mhz == 0.0 || (mhz.is_finite() && (1e-3..1e6).contains(&mhz.abs())) {
                            format!("{mhz}")
                        } else {
                            format!("{mhz:e}")
                        };
                    return Err(usage(format!(
                        "invalid --target-mhz: {shown}; allowed [0.001, 1000] MHz"
                    )));
                }
            }
            if let (Some(mhz), None) = (target_mhz, &cfg.params.clock_mhz) {
                // the constraints ask for the clock the pipeline was chosen for
                cfg = Config::new(Params {
                    clock_mhz: Some(format!("{}", (mhz * 1000.0).round() / 1000.0)),
                    ..cfg.params
                })?;
            }
            // --max-error: the unit is the exploration's choice, its depth measured, not predicted
            let mut pick_depth = target_mhz;
            if let (Some(e), Some(mhz)) = (max_error, target_mhz) {
                let metric: specgen::explore::Metric = metric.into();
                let display = specgen::models::display::Display::parse(&display)?;
                if metric.in_display_codes() {
                    let top = ((1u64 << display.bits) - 1) as f64;
                    if !(e > 0.0 && e <= top) {
                        return Err(usage(format!(
                            "invalid --max-error: {e}; allowed (0, {top}] codes of --display {}",
                            display.name()
                        )));
                    }
                } else if !(e > 0.0 && e <= 1.0) {
                    return Err(usage(format!(
                        "invalid --max-error: {e}; allowed (0, 1] (full scale)"
                    )));
                }
                if params.config.is_some() {
                    return Err(usage(
                        "invalid --config with --max-error: a configuration file fixes every parameter; give the ones your design fixes as flags (each narrows the choice)",
                    ));
                }
                let given = explore::given_keys(&params, &rtl);
                let chosen = explore::choose(
                    explored.as_deref(),
                    &cfg.params,
                    &given,
                    metric,
                    display,
                    e,
                    mhz,
                )?;
                cfg = Config::new(chosen)?;
                pick_depth = None;
            }
            // the plan: model, widths, registers, datapath, built once; --stages checked here
            let mut plan = Plan::new(cfg)?;
            if let Some(mhz) = pick_depth {
                // the delay model, no place-and-route: `synth --seeds K` measures the result
                // a depth at a time; said on standard error when the search takes a while
                let start = std::time::Instant::now();
                let said = std::cell::Cell::new(std::time::Duration::ZERO);
                // the options the user did not give may be chosen with the depth, from measured units
                let given = explore::given_keys(&params, &rtl);
                let free: Vec<&str> = ["rom_style", "fabric_registers"]
                    .into_iter()
                    .filter(|k| !given.contains(k))
                    .collect();
                let before = plan.cfg.params.clone();
                let picked = specgen::explore::depth_and_options_for_clock(
                    &plan,
                    mhz,
                    specgen::explore::Policy::Assured,
                    None,
                    &free,
                    |depth, deepest| {
                        let now = start.elapsed();
                        if now >= said.get() + std::time::Duration::from_secs(2) {
                            said.set(now);
                            errln!("target-mhz: planning --stages {depth} of at most {deepest} ({:.0} s)", now.as_secs_f64());
                        }
                    },
                );
                match picked {
                    Ok(pick) => {
                        plan = pick.plan;
                        let mut options = String::new();
                        if plan.cfg.params.rom_style != before.rom_style {
                            options.push_str(&format!(
                                " --rom-style {}",
                                plan.cfg.params.rom_style.name()
                            ));
                        }
                        if plan.cfg.params.fabric_registers != before.fabric_registers {
                            options.push_str(" --fabric-registers");
                        }
                        errln!(
                            "target-mhz: chose --stages {}{options} on the {}: {}",
                            plan.cfg.stages(),
                            specgen::timing::part(plan.cfg.target()),
                            pick.evidence
                        );
                        if !matches!(
                            pick.evidence,
                            specgen::explore::ClockEvidence::Measured { .. }
                        ) {
                            errln!(
                                "target-mhz: measure it: specgen synth --rtl {} --seeds 3",
                                out.display()
                            );
                        }
                    }
                    // the refusal names its reason, the best depth, the nearest measured unit and
                    // the command that measures this one; --explain says how the figure was read
                    Err(refused) => {
                        let mut why = refused.reason();
                        if let Some(b) = plan.cfg.params.dsp_budget {
                            why.push_str(&format!(
                                " (with --dsp-budget {b}: {} product(s) summed in the fabric)",
                                plan.datapath.fabric_products().len()
                            ));
                        }
                        why.push_str(&explore::nearest_measured(&plan.cfg.params, mhz)?);
                        why.push_str(&format!(
                            "; to measure this configuration: specgen generate --stages {} … --out DIR, then specgen synth --rtl DIR --seeds 3",
                            plan.cut_points
                        ));
                        if explain {
                            for line in specgen::timing::explain_refusal(&plan, mhz)? {
                                why.push_str(&format!("\n  {line}"));
                            }
                        } else {
                            why.push_str(" (--explain: how the delay model read it)");
                        }
                        return Err(Failure::Config {
                            parameter: "target_mhz",
                            message: why,
                        });
                    }
                }
            }
            let files = emit::generate_files(&plan);
            write_output(&out, &files, force)?;
            for (name, _) in &files {
                outln!("{}", out.join(name).display())?;
            }
            errln!(
                "FuseSoC core {} (fusesoc --cores-root {} run --target lint|sim|sim_verilator|synth <this name>)",
                emit::core_name(&plan.cfg),
                out.display()
            );
            Ok(())
        }
        Command::Rom {
            table,
            format,
            output,
            top,
            params,
        } => {
            let cfg = params.to_config(Some(&RtlArgs {
                top,
                ..RtlArgs::default()
            }))?;
            let plan = Plan::new(Config::new(Params {
                stages: 0,
                ..cfg.params.clone()
            })?)?;
            let tables = &plan.datapath.tables;
            let names = tables
                .iter()
                .map(|t| t.name.as_str())
                .collect::<Vec<_>>()
                .join(", ");
            let t = match &table {
                None => tables.first(),
                Some(name) => tables.iter().find(|t| &t.name == name),
            }
            .ok_or_else(|| {
                usage(match (&table, names.is_empty()) {
                    (_, true) => format!("--model {} has no table", cfg.model().name()),
                    (Some(name), false) => format!("invalid --table: {name:?}; allowed: {names}"),
                    (None, false) => unreachable!("a first table exists"),
                })
            })?;
            let text = rom::render_table(&cfg, t, format.into());
            if let (Some(out), Some(config)) = (&output, &params.config) {
                if specgen::output::same_file(out, config) {
                    return Err(usage(format!(
                        "-o {} is the --config file this command reads; write the table elsewhere",
                        out.display()
                    )));
                }
            }
            match output {
                Some(path) => specgen::output::write_file(&path, text.as_bytes())
                    .map_err(|e| failed(format!("cannot write {}: {e}", path.display()))),
                None => {
                    out!("{text}")?;
                    Ok(())
                }
            }
        }
        Command::Eval {
            cos,
            cos_code,
            n,
            ks,
            params,
        } => {
            let cfg = params.to_config(None)?;
            eval::eval(&cfg, cos.as_deref(), cos_code, n, ks)
        }
        Command::Cosim(args) => cosim::run(&args),
        Command::Prove(args) => prove::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Synth(args) => synth::run(&args),
        Command::Explore(args) => explore::run(&args),
        Command::Measure(args) => explore::measure(&args),
        Command::Stale(args) => calibrate::stale(&args),
        Command::Calibrate(args) => calibrate::calibrate(&args),
        Command::Info {
            json: _,
            params,
            rtl,
        } => info::run(&params, rtl),
        Command::Vectors(args) => eval::vectors(&args),
        Command::Report {
            out,
            force,
            hw,
            explored,
            params,
        } => {
            let cfg = params.to_config(None)?;
            let hw = hw
                .iter()
                .map(|p| {
                    specgen::synth::SynthResult::from_file(p)
                        .map_err(|e| usage(format!("invalid --hw: {e}")))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let explored = match &explored {
                Some(p) => {
                    let text = specgen::small_file::read(p, 64 << 20)
                        .map_err(|e| usage(format!("invalid --explored: {} {e}", p.display())))?;
                    Some(
                        specgen::explore::Exploration::from_text(&text, &p.display().to_string())
                            .map_err(|e| usage(format!("invalid --explored: {}", e.reason())))?,
                    )
                }
                None => None,
            };
            let files = specgen::report::build(&cfg, &hw, explored.as_ref());
            write_output(&out, &files, force)?;
            Ok(())
        }
    }
}

/// The command line, with each ranged parameter's help completed from `config::RANGES` (one
/// table drives validation, defaults and help) and the exit codes on every subcommand.
pub fn command() -> clap::Command {
    use clap::CommandFactory;
    let mut cmd = Cli::command();
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    for sub in names {
        cmd = cmd.mut_subcommand(&sub, |mut sc| {
            for r in config::RANGES {
                if sc.get_arguments().any(|a| a.get_id() == r.name) {
                    sc = sc.mut_arg(r.name, |a| {
                        let h = a.get_help().map(|h| h.to_string()).unwrap_or_default();
                        a.help(format!("{h} [{}..={}, default {}]", r.min, r.max, r.default))
                    });
                }
            }
            sc.after_help("Exit codes: 0 success; 1 a check failed or a file could not be read or written; 2 invalid parameters or usage.")
        });
    }
    cmd
}

/// Runs the command line; returns the process exit code.
pub fn main() -> i32 {
    use clap::FromArgMatches;
    // SIGINT/SIGTERM/SIGHUP: temporaries removed, children ended (before any thread starts)
    specgen::process::remove_temporaries_on_signals();
    let cli = match command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return e.exit_code();
        }
    };
    // the environment read before anything runs: a malformed variable is refused, never ignored
    if let Err(e) = specgen::process::check_environment() {
        errln!("specgen: error: {}", message(&e));
        return exit_code(&e);
    }
    match run(cli) {
        Ok(()) => 0,
        Err(e) => {
            errln!("specgen: error: {}", message(&e));
            exit_code(&e)
        }
    }
}
