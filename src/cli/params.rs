//! The unit's parameters as flags (`ParamArgs`, `RtlArgs`) and their parsers: each a whole
//! number in its range, said in the error.

use super::*;

/// The generator parameters (SPEC §2) that define the arithmetic. Unset flags fall back to
/// --config, then to the defaults. Ranges in --help come from `config::RANGES`.
#[derive(Args, Debug, Default, Clone)]
pub struct ParamArgs {
    /// Read parameters from a JSON file (a manifest written by `generate`, or a subset of its keys).
    #[arg(long, value_name = "FILE.json", help_heading = "Parameters")]
    pub config: Option<PathBuf>,
    /// F: fractional bits of cos_g, UQ1.F
    #[arg(allow_negative_numbers = true, value_parser = param_cos_frac_bits, long, help_heading = "Number formats")]
    pub cos_frac_bits: Option<u32>,
    /// N: bits of the exponent n (tables indexed by n have 2^N entries)
    #[arg(allow_negative_numbers = true, value_parser = param_n_bits, long, help_heading = "Number formats")]
    pub n_bits: Option<u32>,
    /// B: bits of each colour input and output
    #[arg(allow_negative_numbers = true, value_parser = param_color_bits, long, help_heading = "Number formats")]
    pub color_bits: Option<u32>,
    /// FI: fractional bits of the intensity output, UQ1.FI
    #[arg(allow_negative_numbers = true, value_parser = param_intensity_frac_bits, long, help_heading = "Number formats")]
    pub intensity_frac_bits: Option<u32>,
    /// The function the unit computes, one of the models below [default quadratic]
    #[arg(long, value_enum, help_heading = "Model")]
    pub model: Option<ModelFlag>,
    /// The constant k of --model quadratic as a decimal string, 0 < k <= 1 [default "0.3686"]
    #[arg(allow_negative_numbers = true, long, help_heading = "Model")]
    pub k: Option<String>,
    /// KF: fractional bits k is rounded to (nearest, ties to even); with --model fitted, the
    /// fractional bits of every a_n
    #[arg(allow_negative_numbers = true, value_parser = param_k_frac_bits, long, help_heading = "Model")]
    pub k_frac_bits: Option<u32>,
    /// M of --model fitted: the bracket is squared up to M times (exponent 2^m_n, m_n <= M)
    #[arg(allow_negative_numbers = true, value_parser = param_max_squarings, long, help_heading = "Model")]
    pub max_squarings: Option<u32>,
    /// Output rounding: faithful (|error| < 1 ulp) or exact (nearest, ties away; quadratic only) [default faithful]
    #[arg(long, value_enum, help_heading = "Model")]
    pub rounding: Option<RoundingFlag>,
    /// Datapath of --model quadratic: lean (error-budget widths, DSP-sized) or paper (Fig. 5 literally) [default lean]
    #[arg(long, value_enum, help_heading = "Model")]
    pub arch: Option<ArchFlag>,
}

/// What only the generated RTL needs (`generate`).
#[derive(Args, Debug, Default, Clone)]
pub struct RtlArgs {
    /// Top module name (a Verilog identifier, not a port or internal name) [default: specular_unit]
    #[arg(long, help_heading = "RTL")]
    pub top: Option<String>,
    /// Pipeline registers; 0 = combinational; latency = stages [0..=the datapath's cut points,
    /// which depend on the model, the widths and the target; at default widths ice40 / ecp5 /
    /// gowin / generic: lean 13/11/11/10, fitted 65/48/48/16, blinn 41/37/37/24, blinn-pow 13,
    /// schlick 21/24/24/19, paper 6; with --fabric-registers on ice40: lean 14, fitted 77, blinn
    /// 51, schlick 28; a value above them is refused with the range; default 0]
    #[arg(allow_negative_numbers = true, value_parser = param_stages, long, help_heading = "RTL")]
    pub stages: Option<u32>,
    /// The most hard multiplier blocks the unit may take (ice40: SB_MAC16, ecp5: MULT18X18D,
    /// gowin: MULT18X18, generic: multipliers); the products past it are summed from partial products in the
    /// fabric, those cheapest in logic first, so several units can share one device [0..=256;
    /// default: no limit]
    #[arg(allow_negative_numbers = true, value_parser = param_dsp_budget, long, value_name = "N", help_heading = "RTL")]
    pub dsp_budget: Option<u32>,
    /// How tables are written: file ($readmemh), case (inline) or logic (LUTs over two steps,
    /// never block RAM: the lean quadratic unit on a family that takes it) [default file]
    #[arg(long, value_enum, help_heading = "RTL")]
    pub rom_style: Option<RomStyleFlag>,
    /// The FPGA family the datapath is shaped for: ice40 (16x16 DSPs with post-adders, short
    /// carry chains), ecp5 (MULT18X18D instances with their own registers, long carry chains;
    /// simulate with sim/<top>_ecp5_mult18x18d_sim.v, written with it) or generic (whole-width products
    /// and adds, left to the synthesis tool) [default ice40]
    #[arg(long, value_enum, help_heading = "RTL")]
    pub target: Option<TargetFlag>,
    /// The handshake: valid (in_valid/out_valid), ready (adds in_ready/out_ready, AXI4-Stream
    /// rules) or axis (AXI4-Stream names, fields packed in tdata) [default valid]
    #[arg(long, value_enum, help_heading = "Interface")]
    pub interface: Option<InterfaceFlag>,
    /// W: bits of a tag carried beside each pixel, in_tag -> out_tag (tuser with axis)
    #[arg(allow_negative_numbers = true, value_parser = param_tag_bits, long, help_heading = "Interface")]
    pub tag_bits: Option<u32>,
    /// The specular colour: pixel (ks_r/g/b with every pixel) or static (material registers
    /// loaded by ks_load while idle) [default pixel]
    #[arg(long, value_enum, help_heading = "Interface")]
    pub colour: Option<ColourFlag>,
    /// The reset's polarity, synchronous either way [default: sync-high (rst) for valid and
    /// ready, sync-low (aresetn) for axis]
    #[arg(long, value_enum, help_heading = "Interface")]
    pub reset: Option<ResetFlag>,
    /// With --interface axis: s_axis_tlast -> m_axis_tlast, carried with each pixel as tuser is
    #[arg(long, help_heading = "Interface")]
    pub tlast: bool,
    /// With --interface ready or axis: a clock enable, clk_en (aclken with axis); an edge with
    /// it low transfers nothing and loads no colour
    #[arg(long, help_heading = "Interface")]
    pub clock_enable: bool,
    /// A flip-flop of the fabric's after each hard multiplier's output that a carry chain
    /// reads, and before each one a chain feeds (a step that only registers, each: more cut
    /// points): for the routes into and out of the DSP column, at the deepest depths
    /// (--rom-style logic implies it; outside --target-mhz's calibration)
    #[arg(long)]
    pub fabric_registers: bool,
    /// The clock the constraints (<top>.sdc, <top>.lpf), the FuseSoC core and synth ask for, MHz
    /// [(0, 1000]; default --target-mhz when given, else 200 for ecp5 and 100 otherwise]
    #[arg(
        long,
        value_name = "F",
        allow_hyphen_values = true,
        help_heading = "Interface"
    )]
    pub clock_mhz: Option<String>,
    /// The clock port of your top that drives the unit, for the constraint files when the unit
    /// is embedded (their clock is found by that name) [default: the unit's own, clk or aclk]
    #[arg(long, value_name = "NAME", help_heading = "Interface")]
    pub clock_port: Option<String>,
}

/// A whole-number flag: a negative value gets a range error, not a "flag not found".
pub(super) fn whole_in(text: &str, r: Option<&config::Range>) -> Result<u32, String> {
    let range = r.map_or("allowed a whole number >= 0".to_string(), |r| {
        format!("allowed {}..={}", r.min, r.max)
    });
    match text.trim().parse::<i64>() {
        Ok(v) if v < 0 || v > u32::MAX as i64 => Err(format!("{v} is out of range; {range}")),
        Ok(v) => Ok(v as u32),
        Err(_) => Err(format!("{text:?} is not a whole number; {range}")),
    }
}

pub(super) fn param_whole(t: &str) -> Result<u32, String> {
    whole_in(t, None)
}

/// `render --size`: its own range, stated in the error.
pub(super) fn param_size(t: &str) -> Result<u32, String> {
    const SIZE: config::Range = config::Range {
        name: "size",
        min: 16,
        max: 1024,
        default: 128,
    };
    whole_in(t, Some(&SIZE)).and_then(|v| {
        if (SIZE.min..=SIZE.max).contains(&v) {
            Ok(v)
        } else {
            Err(format!("{v} is out of range; allowed 16..=1024"))
        }
    })
}

pub(super) fn param_stages(t: &str) -> Result<u32, String> {
    whole_in(t, None).map_err(|e| format!("{e} (up to the configuration's cut points)"))
}

impl ParamArgs {
    /// The configuration: --config, then these flags, then `rtl`'s (when the command has them).
    pub fn to_config(&self, rtl: Option<&RtlArgs>) -> Result<Config, Failure> {
        let mut p = match &self.config {
            Some(path) => Params::from_json_file(path)?,
            None => Params::default(),
        };
        macro_rules! set {
            ($src:expr; $($f:ident),*) => { $(if let Some(v) = $src.$f { p.$f = v.into(); })* };
        }
        set!(self; cos_frac_bits, n_bits, color_bits, intensity_frac_bits, k_frac_bits, rounding, arch, model, max_squarings);
        if let Some(r) = rtl {
            if let Some(v) = &r.top {
                p.top = v.clone();
            }
            set!(r; stages, rom_style, target, interface, tag_bits, colour);
            if let Some(v) = r.reset {
                p.reset = Some(v.into());
            }
            if r.tlast {
                p.tlast = true;
            }
            if let Some(v) = r.dsp_budget {
                p.dsp_budget = Some(v);
            }
            if r.clock_enable {
                p.clock_enable = true;
            }
            if r.fabric_registers {
                p.fabric_registers = true;
            }
            if let Some(v) = &r.clock_mhz {
                p.clock_mhz = Some(v.clone());
            }
            if let Some(v) = &r.clock_port {
                p.clock_port = Some(v.clone());
            }
        }
        if let Some(v) = &self.k {
            p.k = v.clone();
        }
        Config::new(p)
    }
}

macro_rules! range_params {
    ($($f:ident => $r:path),*) => { $(pub(super) fn $f(t: &str) -> Result<u32, String> { whole_in(t, Some(&$r)) })* };
}
range_params!(
    param_cos_frac_bits => config::COS_FRAC_BITS,
    param_n_bits => config::N_BITS,
    param_color_bits => config::COLOR_BITS,
    param_intensity_frac_bits => config::INTENSITY_FRAC_BITS,
    param_k_frac_bits => config::K_FRAC_BITS,
    param_max_squarings => config::MAX_SQUARINGS,
    param_tag_bits => config::TAG_BITS,
    param_dsp_budget => config::DSP_BUDGET
);
