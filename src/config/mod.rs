//! Stage 1: user parameters → a validated [`Config`].
//!
//! Every parameter of SPEC §2 lives here with its default and its allowed range. Nothing
//! downstream re-checks a range: a `Config` that exists is a legal one.

mod kinds;
pub use kinds::*;

use crate::error::Error;
use serde::{Deserialize, Serialize};

mod parse;

pub use crate::names::identifiers::is_internal_name;
use crate::names::identifiers::{check_identifier, check_port_name};
pub use parse::{parse_clock_mhz, parse_decimal, parse_k};

/// Every datapath by its name ([`Config::datapath_name`]: a model's, or its architecture's
/// where the model reads one) with the parameters that build it on `target` (its model and
/// architecture, every other parameter the default), in the registry's order.
pub fn datapaths(target: Target) -> Vec<(&'static str, Params)> {
    let mut out = Vec::new();
    for model in SpecularModel::ALL {
        match model.reads("arch") {
            true => out.extend(Arch::ALL.map(|arch| {
                (
                    arch.name(),
                    Params {
                        model,
                        arch,
                        target,
                        ..Default::default()
                    },
                )
            })),
            false => out.push((
                model.name(),
                Params {
                    model,
                    target,
                    ..Default::default()
                },
            )),
        }
    }
    out
}

/// A closed integer range with the parameter's name and default: the one table that drives
/// validation, the defaults and the ranges `--help` shows.
pub struct Range {
    pub name: &'static str,
    pub min: u32,
    pub max: u32,
    pub default: u32,
}

pub const COS_FRAC_BITS: Range = Range {
    name: "cos_frac_bits",
    min: 4,
    max: 20,
    default: 15,
};
pub const N_BITS: Range = Range {
    name: "n_bits",
    min: 1,
    max: 12,
    default: 10,
};
pub const COLOR_BITS: Range = Range {
    name: "color_bits",
    min: 1,
    max: 16,
    default: 8,
};
pub const INTENSITY_FRAC_BITS: Range = Range {
    name: "intensity_frac_bits",
    min: 1,
    max: 24,
    default: 15,
};
pub const K_FRAC_BITS: Range = Range {
    name: "k_frac_bits",
    min: 4,
    max: 24,
    default: 16,
};
pub const MAX_SQUARINGS: Range = Range {
    name: "max_squarings",
    min: 0,
    max: 4,
    default: 3,
};
pub const TAG_BITS: Range = Range {
    name: "tag_bits",
    min: 0,
    max: 64,
    default: 0,
};
/// `--dsp-budget`: the most hard multiplier blocks the unit may take (its default, none given,
/// is no limit).
pub const DSP_BUDGET: Range = Range {
    name: "dsp_budget",
    min: 0,
    max: 256,
    default: 256,
};

/// Every integer parameter with a fixed range (`stages` depends on the datapath).
pub const RANGES: &[&Range] = &[
    &COS_FRAC_BITS,
    &N_BITS,
    &COLOR_BITS,
    &INTENSITY_FRAC_BITS,
    &K_FRAC_BITS,
    &MAX_SQUARINGS,
    &TAG_BITS,
];

impl Range {
    fn check(&self, value: u32) -> Result<u32, Error> {
        if value < self.min || value > self.max {
            Err(Error::Config {
                parameter: self.name,
                message: format!(
                    "{} is out of range; allowed {}..={}",
                    value, self.min, self.max
                ),
            })
        } else {
            Ok(value)
        }
    }
}

/// The generator's parameters as the user gives them (CLI flags or a manifest).
/// Field names are SPEC §2's; this is also the `parameters` part of the manifest.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Params {
    pub top: String,
    pub cos_frac_bits: u32,
    pub n_bits: u32,
    pub color_bits: u32,
    pub intensity_frac_bits: u32,
    pub k: String,
    pub k_frac_bits: u32,
    pub stages: u32,
    pub rounding: Rounding,
    pub rom_style: RomStyle,
    pub arch: Arch,
    pub model: SpecularModel,
    /// M of `--model fitted`: the largest `m_n` (the bracket is squared up to M times).
    pub max_squarings: u32,
    /// The family the datapath is shaped for.
    pub target: Target,
    /// The handshake: valid (default), ready or axis.
    pub interface: Interface,
    /// Bits of the tag carried beside each pixel (`in_tag` → `out_tag`), 0 for none.
    pub tag_bits: u32,
    /// Per-pixel colour operands, or static material registers.
    pub colour: Colour,
    /// The clock the constraints ask for, MHz as a plain decimal; none: the target's default.
    pub clock_mhz: Option<String>,
    /// The clock port of the user's top that drives the unit's clock, which the constraint
    /// files name (`<top>.sdc`, `<top>.lpf`); none: the unit's own clock pin (`clk`, `aclk`),
    /// right when the unit is the top.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clock_port: Option<String>,
    /// The reset's polarity; none: the interface's own (active high `rst` for `valid` and
    /// `ready`, active low `aresetn` for `axis`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reset: Option<Reset>,
    /// `axis`: `s_axis_tlast` → `m_axis_tlast`, carried with each pixel as `tuser` is.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub tlast: bool,
    /// `ready`/`axis`: a clock enable (`clk_en`, `aclken` under `axis`); a rising edge with it
    /// low transfers nothing and loads no colour.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub clock_enable: bool,
    /// The most hard multiplier blocks (SB_MAC16, MULT18X18D; generic: multipliers) the unit
    /// may take; the products past it are summed in the fabric. None: no limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dsp_budget: Option<u32>,
    /// A flip-flop of the fabric's after each hard multiplier's output that the fabric reads,
    /// before each hard multiplier that a carry chain feeds, and after the ports (a step that
    /// only registers, each): for the routes into and out of the DSP column. `--rom-style
    /// logic` implies the blocks' (not the ports').
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub fabric_registers: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            top: "specular_unit".into(),
            cos_frac_bits: COS_FRAC_BITS.default,
            n_bits: N_BITS.default,
            color_bits: COLOR_BITS.default,
            intensity_frac_bits: INTENSITY_FRAC_BITS.default,
            k: "0.3686".into(),
            k_frac_bits: K_FRAC_BITS.default,
            stages: 0,
            rounding: Rounding::Faithful,
            rom_style: RomStyle::File,
            arch: Arch::Lean,
            model: SpecularModel::Quadratic,
            max_squarings: MAX_SQUARINGS.default,
            target: Target::Ice40,
            interface: Interface::Valid,
            tag_bits: TAG_BITS.default,
            colour: Colour::Pixel,
            clock_mhz: None,
            clock_port: None,
            reset: None,
            tlast: false,
            clock_enable: false,
            fabric_registers: false,
            dsp_budget: None,
        }
    }
}

/// The parameters only some models read, with those models: every other model's manifest,
/// header and report leave them out (`k_code` is the quadratic model's output).
pub const MODEL_KEYS: &[(&str, &[SpecularModel])] = &[
    ("k", &[SpecularModel::Quadratic]),
    ("k_code", &[SpecularModel::Quadratic]),
    ("arch", &[SpecularModel::Quadratic]),
    (
        "k_frac_bits",
        &[SpecularModel::Quadratic, SpecularModel::Fitted],
    ),
    ("max_squarings", &[SpecularModel::Fitted]),
];

/// The values of shared parameters only some models take, with those models (every other
/// model refuses them, naming these).
pub const MODEL_OPTIONS: &[(&str, &[SpecularModel])] = &[
    ("rounding=exact", &[SpecularModel::Quadratic]),
    ("arch=paper", &[SpecularModel::Quadratic]),
    // the models with tables (blinn-pow has none)
    (
        "rom_style=logic",
        &[
            SpecularModel::Quadratic,
            SpecularModel::Schlick,
            SpecularModel::Fitted,
            SpecularModel::Blinn,
        ],
    ),
];

/// The models that take `option` of [`MODEL_OPTIONS`], by name ("quadratic", "quadratic and fitted").
fn takers(option: &str) -> String {
    let names: Vec<&str> = SpecularModel::ALL
        .into_iter()
        .filter(|m| m.takes(option))
        .map(SpecularModel::name)
        .collect();
    names.join(" and ")
}

/// Keys of a manifest that are outputs, not parameters (skipped when it is read as a config).
pub(crate) const MANIFEST_OUTPUT_KEYS: &[&str] = &[
    "generator",
    "version",
    "fingerprint",
    "k_code",
    "latency",
    "ports",
    "internal_widths",
    "files",
    "model_widths",
    "registered_cuts",
    "unregistered_products",
    "stage_delay_estimate",
    "stage_delay_mean",
    "predicted_fmax_mhz",
    "tdata",
    "blinn_error_max",
    "blinn_error_mean",
    "blinn_error_method",
    "pixel_error_max",
    "pixel_error_mean",
    "pixel_error_rms",
    "pixel_error_method",
];

/// An interface's own reset: active high `rst` for `valid` and `ready`, active low `aresetn`
/// for `axis`.
fn default_reset(interface: Interface) -> Reset {
    if interface == Interface::Axis {
        Reset::SyncLow
    } else {
        Reset::SyncHigh
    }
}

impl Params {
    /// Reads parameters from JSON: a full manifest written by `generate`, or any subset of
    /// the parameter keys (the rest take their defaults). Unknown keys are an error.
    pub fn from_json(text: &str) -> Result<Params, Error> {
        let err = |message: String| Error::Config {
            parameter: "config",
            message,
        };
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| err(format!("not valid JSON: {e}")))?;
        let serde_json::Value::Object(mut map) = value else {
            return Err(err("must hold a JSON object".into()));
        };
        for key in MANIFEST_OUTPUT_KEYS {
            map.remove(*key);
        }
        let mut full = serde_json::to_value(Params::default()).expect("params serialise");
        // the parameters a manifest states only when given (absent: the default)
        for key in ["clock_port", "reset", "dsp_budget"] {
            full[key] = serde_json::Value::Null;
        }
        for key in ["tlast", "clock_enable", "fabric_registers"] {
            full[key] = serde_json::Value::Bool(false);
        }
        for (k, v) in map {
            if full.get(&k).is_none() {
                return Err(err(format!("unknown key {k:?}")));
            }
            full[&k] = v;
        }
        serde_json::from_value(full).map_err(|e| err(e.to_string()))
    }

    pub fn from_json_file(path: &std::path::Path) -> Result<Params, Error> {
        let err = |why: String| Error::Config {
            parameter: "config",
            message: format!("{}: {why}", path.display()),
        };
        let text =
            crate::small_file::read(path, 1 << 20).map_err(
                |e| match crate::small_file::refused(&e) {
                    true => err(format!("{e}; allowed a JSON file of at most 1 MiB")),
                    false => err(e
                        .to_string()
                        .replacen("cannot be read", "cannot read it", 1)),
                },
            )?;
        Params::from_json(&text).map_err(|e| err(e.reason()))
    }
}

/// A validated configuration: the parameters plus the constant they fix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Config {
    pub params: Params,
    /// `k_q · 2^KF`, the integer the hardware multiplies by (SPEC §3).
    pub k_code: u64,
}

impl Config {
    pub fn new(params: Params) -> Result<Config, Error> {
        check_identifier(&params.top)?;
        COS_FRAC_BITS.check(params.cos_frac_bits)?;
        N_BITS.check(params.n_bits)?;
        COLOR_BITS.check(params.color_bits)?;
        INTENSITY_FRAC_BITS.check(params.intensity_frac_bits)?;
        K_FRAC_BITS.check(params.k_frac_bits)?;
        MAX_SQUARINGS.check(params.max_squarings)?;
        TAG_BITS.check(params.tag_bits)?;
        if let Some(n) = params.dsp_budget {
            DSP_BUDGET.check(n)?;
        }
        if let Some(text) = &params.clock_mhz {
            parse_clock_mhz(text)?;
        }
        if let Some(port) = &params.clock_port {
            check_port_name(port)?;
        }
        if params.tlast && params.interface != Interface::Axis {
            return Err(Error::Config {
                parameter: "tlast",
                message: format!(
                    "applies to the axis interface only; allowed with {}: none",
                    params.interface.name()
                ),
            });
        }
        if params.clock_enable && !params.interface.handshake() {
            return Err(Error::Config {
                parameter: "clock_enable",
                message: format!(
                    "applies to the ready and axis interfaces only (their edge gates every transfer; a valid pipeline has none to gate); allowed with {}: none",
                    params.interface.name()
                ),
            });
        }
        if params.tlast && params.tag_bits == TAG_BITS.max {
            return Err(Error::Config {
                parameter: "tag_bits",
                message: format!(
                    "{} with tlast: the tag and tlast travel as one word of at most {} bits; allowed 0..={}",
                    params.tag_bits,
                    TAG_BITS.max,
                    TAG_BITS.max - 1
                ),
            });
        }
        let k_code = parse_k(&params.k, params.k_frac_bits)?;
        if params.rounding == Rounding::Exact && !params.model.takes("rounding=exact") {
            return Err(Error::Config {
                parameter: "rounding",
                message: format!(
                    "exact is not available with the {} model; allowed: faithful",
                    params.model.name()
                ),
            });
        }
        // (the family's part of the rule, which families write tables as logic, is the plan's:
        // `Family::writes_logic_tables`)
        if params.rom_style == RomStyle::Logic
            && !(params.model.takes("rom_style=logic") && params.arch == Arch::Lean)
        {
            return Err(Error::Config {
                parameter: "rom_style",
                message: format!(
                    "logic applies to the lean datapaths of {} (their tables kept out of block RAM); allowed with {} {} on {}: file, case",
                    takers("rom_style=logic"),
                    params.model.name(),
                    params.arch.name(),
                    params.target.name()
                ),
            });
        }
        if params.arch == Arch::Paper && !params.model.takes("arch=paper") {
            return Err(Error::Config {
                parameter: "arch",
                message: format!(
                    "paper applies to the {} model only; allowed with {}: lean",
                    takers("arch=paper"),
                    params.model.name()
                ),
            });
        }
        // `stages` is bounded by the datapath's cut points: `plan::Plan::new` checks it, since
        // validating a configuration builds nothing
        // a reset of the interface's own polarity is the unit without `reset`: one unit, one
        // fingerprint and one header, whichever way it was asked for (the manifest states it
        // either way)
        let mut params = params;
        if params.reset == Some(default_reset(params.interface)) {
            params.reset = None;
        }
        let cfg = Config { params, k_code };
        Ok(cfg)
    }

    pub fn defaults() -> Config {
        Config::new(Params::default()).expect("defaults are valid")
    }

    /// F: fractional bits of `cos_g` (UQ1.F).
    pub fn f(&self) -> u32 {
        self.params.cos_frac_bits
    }
    /// N: bits of the exponent `n`.
    pub fn n_bits(&self) -> u32 {
        self.params.n_bits
    }
    /// B: bits of each colour channel.
    pub fn b(&self) -> u32 {
        self.params.color_bits
    }
    /// FI: fractional bits of `intensity` (UQ1.FI).
    pub fn fi(&self) -> u32 {
        self.params.intensity_frac_bits
    }
    /// KF: fractional bits of the constant k.
    pub fn kf(&self) -> u32 {
        self.params.k_frac_bits
    }
    pub fn stages(&self) -> u32 {
        self.params.stages
    }
    pub fn rounding(&self) -> Rounding {
        self.params.rounding
    }
    pub fn arch(&self) -> Arch {
        self.params.arch
    }
    pub fn model(&self) -> SpecularModel {
        self.params.model
    }
    /// M: the most squarings of `--model fitted`.
    pub fn max_squarings(&self) -> u32 {
        self.params.max_squarings
    }
    pub fn target(&self) -> Target {
        self.params.target
    }
    pub fn top(&self) -> &str {
        &self.params.top
    }
    pub fn interface(&self) -> Interface {
        self.params.interface
    }
    /// W: bits of the tag beside each pixel (0: no tag ports).
    pub fn tag_bits(&self) -> u32 {
        self.params.tag_bits
    }
    pub fn colour(&self) -> Colour {
        self.params.colour
    }
    /// The bits that travel beside each pixel: the tag, and `tlast` above it.
    pub fn carried_tag_bits(&self) -> u32 {
        self.params.tag_bits + self.params.tlast as u32
    }
    /// The reset's polarity: `reset` when given, else the interface's own.
    pub fn reset(&self) -> Reset {
        self.params.reset.unwrap_or(default_reset(self.interface()))
    }
    /// Whether the unit has a clock and reset: pipeline registers, a handshake's buffer or
    /// material registers.
    pub fn clocked(&self) -> bool {
        self.stages() > 0 || self.interface().handshake() || self.colour() == Colour::Static
    }
    /// The clock the unit names (`clock_mhz`), if any; `crate::family::clock_mhz` gives the
    /// family's default otherwise.
    pub fn explicit_clock_mhz(&self) -> Option<f64> {
        self.params
            .clock_mhz
            .as_ref()
            .map(|text| parse_clock_mhz(text).expect("validated"))
    }
    /// The unit's ports (SPEC §2) in module order; `done_meaning` completes `done`'s comment.
    pub fn ports(&self, done_meaning: &str) -> Vec<crate::ports::Port> {
        crate::ports::ports(self.port_widths(), done_meaning)
    }

    /// The ports under their plain names, the fields of an `axis` unit's `tdata` among them
    /// (the columns of vectors, the widths of the buffer's fields).
    pub(crate) fn logical_ports(&self) -> Vec<crate::ports::Port> {
        crate::ports::ports(
            crate::ports::PortWidths {
                axis: false,
                ..self.port_widths()
            },
            "",
        )
    }

    /// What the port table depends on.
    pub(crate) fn port_widths(&self) -> crate::ports::PortWidths {
        crate::ports::PortWidths {
            cos_frac_bits: self.f(),
            n_bits: self.n_bits(),
            color_bits: self.b(),
            intensity_frac_bits: self.fi(),
            clocked: self.clocked(),
            ready: self.interface().handshake(),
            axis: self.interface() == Interface::Axis,
            tag_bits: self.tag_bits(),
            static_colour: self.colour() == Colour::Static,
            reset_low: self.reset() == Reset::SyncLow,
            tlast: self.params.tlast,
            clock_enable: self.params.clock_enable,
        }
    }

    /// Cycles from a pixel in to its result out: the pipeline's registers, and behind a
    /// handshake the output buffer's (while the consumer is ready).
    pub fn latency(&self) -> u32 {
        self.stages()
            + if self.interface().handshake() {
                BUFFER_LATENCY
            } else {
                0
            }
    }

    /// The datapath's name in messages: the architecture for the quadratic model, else the model.
    pub(crate) fn datapath_name(&self) -> &'static str {
        if self.model().reads("arch") {
            self.arch().name()
        } else {
            self.model().name()
        }
    }

    /// A digest of the configuration: the first 16 hex digits of the SHA-256 of the model's own
    /// parameters as the manifest states them. The manifest and the unit's header both carry
    /// it, so a reader tells with one comparison whether the files belong together.
    pub fn fingerprint(&self) -> String {
        let mut v = serde_json::to_value(&self.params).expect("parameters serialise");
        self.model().keep_own_keys(&mut v);
        crate::bits::sha256_hex(v.to_string().as_bytes(), 8)
    }

    /// The parameters that define the unit, as `name=value` words (for file headers).
    pub fn describe(&self) -> String {
        let p = &self.params;
        let m = p.model;
        let mut s = format!(
            "model={} cos_frac_bits={} n_bits={} color_bits={} intensity_frac_bits={}",
            m.name(),
            p.cos_frac_bits,
            p.n_bits,
            p.color_bits,
            p.intensity_frac_bits
        );
        if m.reads("k") {
            s.push_str(&format!(" k={}", p.k));
        }
        if m.reads("k_frac_bits") {
            s.push_str(&format!(" k_frac_bits={}", p.k_frac_bits));
        }
        if m.reads("max_squarings") {
            s.push_str(&format!(" max_squarings={}", p.max_squarings));
        }
        s.push_str(&format!(
            " stages={} rounding={}",
            p.stages,
            p.rounding.name()
        ));
        if m.reads("arch") {
            s.push_str(&format!(" arch={}", p.arch.name()));
        }
        s.push_str(&format!(" target={}", p.target.name()));
        s.push_str(&self.interface_words());
        if let Some(mhz) = &p.clock_mhz {
            s.push_str(&format!(" clock_mhz={mhz}"));
        }
        if let Some(port) = &p.clock_port {
            s.push_str(&format!(" clock_port={port}"));
        }
        if let Some(n) = p.dsp_budget {
            s.push_str(&format!(" dsp_budget={n}"));
        }
        if p.fabric_registers {
            s.push_str(" fabric_registers");
        }
        s
    }

    /// ` interface=… tag_bits=… colour=…` for what is not the default (empty for the default
    /// unit, whose text stays as it was before these parameters).
    pub fn interface_words(&self) -> String {
        let p = &self.params;
        let mut s = String::new();
        if p.interface != Interface::Valid {
            s.push_str(&format!(" interface={}", p.interface.name()));
        }
        if p.tag_bits > 0 {
            s.push_str(&format!(" tag_bits={}", p.tag_bits));
        }
        if p.colour != Colour::Pixel {
            s.push_str(&format!(" colour={}", p.colour.name()));
        }
        if let Some(r) = p.reset {
            s.push_str(&format!(" reset={}", r.name()));
        }
        if p.tlast {
            s.push_str(" tlast");
        }
        if p.clock_enable {
            s.push_str(" clock_enable");
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_k_code_is_round_of_0_3686_times_2_16() {
        // 0.3686 · 65536 = 24156.97… → 24157
        assert_eq!(Config::defaults().k_code, 24157);
    }

    #[test]
    fn k_rejects_out_of_range_and_garbage() {
        for bad in ["", "abc", "-0.5", "1.5", "0", "0.00001", "1e-3", "0.3.6"] {
            assert!(parse_k(bad, 8).is_err(), "{bad} accepted");
        }
        assert_eq!(parse_k("1", 8).unwrap(), 256);
        assert_eq!(parse_k("1.0", 8).unwrap(), 256);
    }

    #[test]
    fn top_must_be_identifier() {
        for bad in ["", "1abc", "a-b", "../x", "a/b", "module", "wire", "a b"] {
            let p = Params {
                top: bad.into(),
                ..Params::default()
            };
            assert_eq!(
                Config::new(p).unwrap_err().parameter(),
                Some("top"),
                "{bad}"
            );
        }
        let p = Params {
            top: "my_unit_2".into(),
            ..Params::default()
        };
        assert!(Config::new(p).is_ok());
    }
}
