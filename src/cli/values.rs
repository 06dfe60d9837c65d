//! The command line's form of the library's enums: clap's `ValueEnum` lives here, never in the
//! library. Each flag value converts into its library type.

use specgen::config::{Arch, Colour, Interface, Reset, RomStyle, Rounding, SpecularModel, Target};
use specgen::cosim::Simulator;
use specgen::explore::Metric;
use specgen::table::formats::RomFormat;
use specgen::vectors::VectorFormat;

/// A clap value enum mirroring a library enum variant for variant, with its conversion.
macro_rules! flag_values {
    ($( $(#[$doc:meta])* $cli:ident => $lib:ident { $( $(#[$vdoc:meta])* $v:ident ),* $(,)? } )*) => { $(
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
        pub enum $cli { $( $(#[$vdoc])* $v ),* }
        impl From<$cli> for $lib {
            fn from(v: $cli) -> $lib {
                match v { $( $cli::$v => $lib::$v ),* }
            }
        }
    )* };
}

flag_values! {
    /// `--metric`
    MetricFlag => Metric {
        /// the largest |intensity - cos^n| at the pixel: over every real cosine in [0, 1] (rounded to F bits before the unit reads it) and every n
        Max,
        /// its mean over cosines uniform in [0, 1] and every n
        Mean,
        /// its root mean square
        Rms,
        /// the largest |intensity - cos^n| at the unit's own codes (cos = cos_g/2^F exactly): for a cosine that already arrives at F bits
        CodeMax,
        /// its mean at the codes
        CodeMean,
        /// its root mean square at the codes
        CodeRms,
        /// the largest step between neighbouring pixels of render's sphere beyond the float image's (banding)
        Step,
        /// the largest error at the pixel in codes of the --display (after its transfer function); E in codes
        DisplayMax,
        /// the largest jump in codes of the --display between neighbouring cosine codes, every n: 1 is no banding beyond the display's own; E in codes
        DisplayBanding,
    }
    /// `--rounding`
    RoundingFlag => Rounding {
        /// |o - o*| < 1 for every output
        Faithful,
        /// |o - o*| <= 1/2, ties away from zero (quadratic only)
        Exact,
    }
    /// `--rom-style`
    RomStyleFlag => RomStyle {
        /// a memory initialised with $readmemh from the table's file
        File,
        /// a case table inlined in the module (no file to carry around)
        Case,
        /// every table as logic over steps of its own, never block RAM (the lean datapaths with tables on the ECP5: past the DP16KD's clock limit)
        Logic,
    }
    /// `--arch`
    ArchFlag => Arch {
        /// the cheapest correct datapath: widths from the error budget, narrow colour path, DSP-sized squarer
        Lean,
        /// the paper's Fig. 5 literally: full-width datapath, n*(cos - 1) then *k, multiplier as squarer
        Paper,
    }
    /// `--model`
    ModelFlag => SpecularModel {
        /// the paper's formula (15): [1 - k*n*(1 - cos)]^2 cut off at cos_sp(n)
        Quadratic,
        /// the paper's modified Schlick (11): c/(2n - 2n*c + c), by an interpolated reciprocal
        Schlick,
        /// [1 - a_n*(1 - cos)]^(2^m_n) with per-n a_n, m_n from a minimax fit
        Fitted,
        /// Blinn's cos^n from log2/exp2 tables with linear interpolation
        Blinn,
        /// Blinn's cos^n by square-and-multiply over the bits of n
        BlinnPow,
    }
    /// `--interface`
    InterfaceFlag => Interface {
        /// in_valid/out_valid only: the pipeline never waits
        Valid,
        /// adds in_ready/out_ready with AXI4-Stream rules: backpressure, nothing lost
        Ready,
        /// the ready behaviour under AXI4-Stream names (aclk, aresetn, s_axis_*, m_axis_*)
        Axis,
    }
    /// `--reset`
    ResetFlag => Reset {
        /// synchronous, active high: rst (areset with axis)
        SyncHigh,
        /// synchronous, active low: rst_n (aresetn with axis)
        SyncLow,
    }
    /// `--colour`
    ColourFlag => Colour {
        /// ks_r/g/b are per-pixel operands carried with each pixel
        Pixel,
        /// ks_r/g/b are material registers loaded by ks_load while the unit is idle
        Static,
    }
    /// `--target`
    TargetFlag => Target {
        /// no family assumed: whole-width products and adds, mapped by the synthesis tool
        Generic,
        /// Lattice iCE40 UP5K: 16x16 SB_MAC16 with post-adders, short carry chains
        Ice40,
        /// Lattice ECP5: 18x18 MULT18X18D with its input and output registers, long carry chains
        Ecp5,
        /// Gowin GW1NR-9 (Tang Nano 9K): 18x18 MULT18X18 with its input and output registers,
        /// pROMX9 block RAM
        Gowin,
    }
    /// `specgen rom --format`
    RomFormatFlag => RomFormat {
        /// $readmemh: one zero-padded hex word a line
        Hex,
        /// $readmemb: one zero-padded binary word a line
        Bin,
        /// Xilinx memory coefficient file
        Coe,
        /// Intel memory initialization file
        Mif,
        /// readable table: n, code, cosine, angle in degrees
        Csv,
    }
    /// `specgen vectors --format`
    VectorFormatFlag => VectorFormat {
        /// CSV: comment header, a row of port names, one row per input (unsigned decimal)
        Csv,
        /// $readmemh: comment header, one packed hex word per input
        Hex,
    }
    /// `--simulator`
    SimulatorFlag => Simulator {
        Verilator,
        Icarus,
    }
}

/// The simulator programs, on every command that simulates: each a name on the PATH or a path;
/// only these run (a missing or failing one is its own error, exit 1).
#[derive(clap::Args, Debug, Clone)]
pub struct SimToolArgs {
    /// The Verilator program (e.g. a newer build than the PATH's).
    #[arg(
        long,
        value_name = "PATH",
        default_value = "verilator",
        help_heading = "Simulators"
    )]
    pub verilator: String,
    /// Icarus Verilog's compiler.
    #[arg(
        long,
        value_name = "PATH",
        default_value = "iverilog",
        help_heading = "Simulators"
    )]
    pub iverilog: String,
    /// Icarus Verilog's runtime.
    #[arg(
        long,
        value_name = "PATH",
        default_value = "vvp",
        help_heading = "Simulators"
    )]
    pub vvp: String,
}

impl SimToolArgs {
    pub fn tools(&self) -> specgen::cosim::SimTools {
        specgen::cosim::SimTools {
            verilator: self.verilator.clone(),
            iverilog: self.iverilog.clone(),
            vvp: self.vvp.clone(),
        }
    }
}
