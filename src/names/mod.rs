//! Names every layer refers to: the generator's version, the files that are not RTL (the
//! simulation-only models, the testbench), and which identifiers a unit may take
//! ([`identifiers`]: Verilog and SystemVerilog keywords, the tools' and the families' cell
//! names, specgen's own module names). A leaf: imports only the error type.

pub mod identifiers;

/// The generator's version, in every file header.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// What the DP16KD simulation model's file name adds to the top's (`<top>_ecp5_dp16kd_sim.v`):
/// simulators read it, synthesis must not.
pub const ECP5_BRAM_MODEL_SUFFIX: &str = "_ecp5_dp16kd_sim.v";

/// What the MULT18X18D simulation model's file name adds to the top's: simulators read it,
/// synthesis must not.
pub const ECP5_SIM_MODEL_SUFFIX: &str = "_ecp5_mult18x18d_sim.v";

/// Whether a file name is one of the simulation-only models specgen writes (any unit's).
pub fn is_sim_model_file(name: &str) -> bool {
    [ECP5_SIM_MODEL_SUFFIX, ECP5_BRAM_MODEL_SUFFIX]
        .iter()
        .any(|s| name.len() > s.len() && name.ends_with(s))
}

/// The subdirectory of an output that holds the simulation models, so a flow that reads every
/// `*.v` of the output directory (`read_verilog *.v; synth_ecp5`) reads only RTL.
pub const SIM_DIR: &str = "sim";

/// What the self-checking testbench of the FuseSoC sim targets adds to the top's name
/// (`<top>_tb.sv`, SystemVerilog): not the unit's RTL, so cosim, synth and lint of `*.v` never read it.
pub const TESTBENCH_SUFFIX: &str = "_tb.sv";
