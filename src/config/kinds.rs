//! The choices a parameter takes (rounding, ROM style, arch, model, target, interface, reset,
//! colour), each with the name its flag and the manifest use.

use super::*;

/// Output rounding contract (SPEC §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Rounding {
    /// `|o − o*| < 1` for every output.
    Faithful,
    /// `|o − o*| ≤ 1/2`, ties away from zero.
    Exact,
}

impl Rounding {
    pub fn name(self) -> &'static str {
        match self {
            Rounding::Faithful => "faithful",
            Rounding::Exact => "exact",
        }
    }
}

/// How the cut-off ROM is written in the Verilog.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RomStyle {
    /// A memory initialised with `$readmemh` from `cos_sp_rom.hex`.
    File,
    /// A `case` table inlined in the module (no file to carry around).
    Case,
    /// The table written as logic, its read in two steps (the entry within each group of
    /// words, then the group): never a memory, never block RAM. Past the ECP5 DP16KD's clock
    /// limit; the lean quadratic datapath on the ECP5 only.
    Logic,
}

impl RomStyle {
    pub fn name(self) -> &'static str {
        match self {
            RomStyle::File => "file",
            RomStyle::Case => "case",
            RomStyle::Logic => "logic",
        }
    }
}

/// Which datapath is generated; all meet the same contract (SPEC §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Arch {
    /// The cheapest correct datapath: widths from the error budget, narrow colour path, DSP-sized squarer.
    Lean,
    /// The paper's Fig. 5 literally: full-width datapath, n·(cos − 1) then ·k, multiplier as squarer.
    Paper,
}

impl Arch {
    pub const ALL: [Arch; 2] = [Arch::Lean, Arch::Paper];
    pub fn name(self) -> &'static str {
        match self {
            Arch::Lean => "lean",
            Arch::Paper => "paper",
        }
    }
}

/// Which function the unit computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SpecularModel {
    /// The paper's formula (15): `[1 − k·n·(1 − cos)]²` cut off at `cos_sp(n)`.
    #[serde(rename = "quadratic")]
    Quadratic,
    /// Blinn's `cos^n` itself, by square-and-multiply over the bits of n (faithful only).
    #[serde(rename = "blinn-pow")]
    BlinnPow,
    /// Blinn's `cos^n` from log2/exp2 tables with linear interpolation (SPEC §6, faithful).
    #[serde(rename = "blinn")]
    Blinn,
    /// `[1 − a_n·(1 − cos)]^(2^m_n)` with per-n `a_n`, `m_n` from a minimax fit (SPEC §6).
    #[serde(rename = "fitted")]
    Fitted,
    /// The paper's modified Schlick (11), `c/(2n − 2n·c + c)`, by an interpolated reciprocal (SPEC §6).
    #[serde(rename = "schlick")]
    Schlick,
}

impl SpecularModel {
    /// Every model, from the coarsest to the exact ones (the order of reports and tests).
    pub const ALL: [SpecularModel; 5] = [
        SpecularModel::Quadratic,
        SpecularModel::Schlick,
        SpecularModel::Fitted,
        SpecularModel::Blinn,
        SpecularModel::BlinnPow,
    ];

    pub fn name(self) -> &'static str {
        match self {
            SpecularModel::Quadratic => "quadratic",
            SpecularModel::BlinnPow => "blinn-pow",
            SpecularModel::Blinn => "blinn",
            SpecularModel::Fitted => "fitted",
            SpecularModel::Schlick => "schlick",
        }
    }
}

/// The FPGA family the datapath is shaped for (`generate --target`): the operand width of its
/// multipliers, the carry chain a step may hold, and whether products use the DSP block's own
/// registers. Every target computes the same values (SPEC §3); only the RTL's shape differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// No family assumed: whole-width products and adds, mapped by the synthesis tool
    Generic,
    /// Lattice iCE40 UP5K: 16x16 SB_MAC16 with post-adders, short carry chains
    Ice40,
    /// Lattice ECP5: 18x18 MULT18X18D with its input and output registers, long carry chains
    Ecp5,
    /// Gowin GW1NR-9 (Tang Nano 9K): 18x18 MULT18X18 with its input and output registers,
    /// pROMX9 block RAM
    Gowin,
}

impl Target {
    /// Every target: a test that covers every family iterates this (a new family is added here
    /// and in `family::of`).
    pub const ALL: [Target; 4] = [Target::Generic, Target::Ice40, Target::Ecp5, Target::Gowin];

    pub fn name(self) -> &'static str {
        match self {
            Target::Generic => "generic",
            Target::Ice40 => "ice40",
            Target::Ecp5 => "ecp5",
            Target::Gowin => "gowin",
        }
    }
}

/// The unit's handshake (`generate --interface`, SPEC §7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Interface {
    /// `in_valid`/`out_valid` only: the pipeline never waits (today's ports)
    Valid,
    /// adds `in_ready`/`out_ready` with AXI4-Stream rules: backpressure, nothing lost
    Ready,
    /// the `ready` behaviour under AXI4-Stream names (`aclk`, `aresetn`, `s_axis_*`, `m_axis_*`)
    Axis,
}

impl Interface {
    pub fn name(self) -> &'static str {
        match self {
            Interface::Valid => "valid",
            Interface::Ready => "ready",
            Interface::Axis => "axis",
        }
    }
    /// The unit takes backpressure (`ready` or `axis`).
    pub fn handshake(self) -> bool {
        self != Interface::Valid
    }
}

/// Cycles the `ready`/`axis` output buffer adds after the pipeline (`templates/out_buffer.v`):
/// the write, the memory's read register, the output register.
pub const BUFFER_LATENCY: u32 = 3;

/// The reset's polarity (`generate --reset`, SPEC §7): synchronous either way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reset {
    /// `rst` (`areset` under `axis`), active high
    SyncHigh,
    /// `rst_n` (`aresetn` under `axis`), active low
    SyncLow,
}

impl Reset {
    pub fn name(self) -> &'static str {
        match self {
            Reset::SyncHigh => "sync-high",
            Reset::SyncLow => "sync-low",
        }
    }
}

/// Where the specular colour comes from (`generate --colour`, SPEC §7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Colour {
    /// `ks_r/g/b` are per-pixel operands, carried down the pipeline with each pixel
    Pixel,
    /// `ks_r/g/b` are material registers loaded by `ks_load` while the unit is `idle`
    Static,
}

impl Colour {
    pub fn name(self) -> &'static str {
        match self {
            Colour::Pixel => "pixel",
            Colour::Static => "static",
        }
    }
}

impl SpecularModel {
    /// Whether this model reads the parameter (or output) `key`: false only for the keys of
    /// [`MODEL_KEYS`] that belong to other models.
    pub fn reads(self, key: &str) -> bool {
        MODEL_KEYS
            .iter()
            .find(|(k, _)| *k == key)
            .is_none_or(|(_, models)| models.contains(&self))
    }

    /// Whether this model takes `option` (`name=value`): false only for the options of
    /// [`MODEL_OPTIONS`] that belong to other models.
    pub fn takes(self, option: &str) -> bool {
        MODEL_OPTIONS
            .iter()
            .find(|(o, _)| *o == option)
            .is_none_or(|(_, models)| models.contains(&self))
    }

    /// Drops from a JSON object (a manifest, a report's parameters) the keys of other models.
    pub fn keep_own_keys(self, value: &mut serde_json::Value) {
        if let serde_json::Value::Object(map) = value {
            map.retain(|k, _| self.reads(k));
        }
    }
}
