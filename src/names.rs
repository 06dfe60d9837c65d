//! Names every layer refers to: the generator's version and the files that are not RTL (the
//! simulation-only models, the testbench). A leaf: imports nothing from the crate.

/// The generator's version, in every file header.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The file name of the DP16KD simulation model: simulators read it, synthesis must not.
pub const ECP5_BRAM_MODEL_FILE: &str = "ecp5_dp16kd_sim.v";

/// The file name of the MULT18X18D simulation model: simulators read it, synthesis must not.
pub const ECP5_SIM_MODEL_FILE: &str = "ecp5_mult18x18d_sim.v";

/// The simulation-only files specgen writes: simulators read them, synthesis never.
pub const SIM_MODEL_FILES: [&str; 2] = [ECP5_SIM_MODEL_FILE, ECP5_BRAM_MODEL_FILE];

/// The subdirectory of an output that holds the simulation models, so a flow that reads every
/// `*.v` of the output directory (`read_verilog *.v; synth_ecp5`) reads only RTL.
pub const SIM_DIR: &str = "sim";

/// What the self-checking testbench of the FuseSoC sim targets adds to the top's name
/// (`<top>_tb.sv`, SystemVerilog): not the unit's RTL, so cosim, synth and lint of `*.v` never read it.
pub const TESTBENCH_SUFFIX: &str = "_tb.sv";
