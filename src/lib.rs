//! specgen: a generator of synthesizable Verilog for a fixed-point specular highlight unit
//! (Blinn's `cos^n δ` approximated by `[k·n·(cos δ − 1) + 1]²`, cut off at `cos γsp(n)`, and
//! the models past the paper), with a bit-exact golden model.
//!
//! Layers import only downward (docs/ARCHITECTURE.md draws them; the suite's `layers` tests
//! hold them):
//! 1. leaves: [`bits`] (fixed-point helpers), [`names`] (version, non-RTL file names), [`ports`]
//!    (the port table, `Inputs`/`Outputs`), [`table`] (a ROM), [`config`] (validated
//!    parameters), [`error`], [`process`] (children and temporaries that do not outlive a run),
//!    [`output`] (atomic writes), [`small_file`] (bounded reads);
//! 2. [`family`] (each FPGA family's facts, its hard blocks' limits among them);
//! 3. [`datapath`]: the step/cut IR and its `Builder`, which knows no model;
//! 4. [`models`]: one home per model behind the `SpecularUnit` trait, and the registry;
//! 5. [`plan`]: config → model → registers placed → datapath, built once per command;
//! 6. [`timing`] (the delay model), [`interface`] (the handshake, tag and colour around the
//!    datapath), [`emit`] and [`table::formats`] (files);
//! 7. [`cosim`], [`synth`], [`prove`], [`vectors`], [`render`], [`explore`] (the space, its
//!    measurements, the one depth search and the choice), [`report`], [`paper`].
//!
//! The command line lives in the binary (`src/main.rs`, `src/cli/`): the library knows no flag.

pub mod bits;
pub mod config;
pub mod cosim;
pub mod datapath;
pub mod emit;
pub mod error;
pub mod explore;
pub mod family;
pub mod interface;
pub mod models;
pub mod names;
pub mod output;
pub mod paper;
pub mod plan;
pub mod ports;
pub mod process;
pub mod prove;
pub mod render;
pub mod report;
pub mod small_file;
pub mod synth;
pub mod table;
pub mod timing;
pub mod vectors;
