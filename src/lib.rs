//! specgen: a generator of synthesizable Verilog for a fixed-point specular highlight unit
//! (Blinn's `cos^n δ` approximated by `[k·n·(cos δ − 1) + 1]²`, cut off at `cos γsp(n)`),
//! with a bit-exact golden model.
//!
//! Data flows one way: [`config`] (validated parameters) → [`plan`] (model, widths, datapath with
//! its registers, built once per command; [`widths`] holds the error analysis) →
//! {[`model`], [`rom`], [`emit`] (templates)} → files → [`cosim`] (simulators).
//! [`error`] is the one error type of every stage; [`cli`] is the command line over all of
//! it, and nothing else imports it.

pub mod blinn;
pub mod blinn_pow;
pub mod cli;
pub mod config;
pub mod cosim;
pub mod datapath;
pub mod emit;
pub mod error;
pub mod fitted;
pub mod model;
pub mod paper;
pub mod plan;
pub mod render;
pub mod report;
pub mod rom;
pub mod synth;
pub mod vectors;
pub mod widths;
