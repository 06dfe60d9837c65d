//! The integration tests: one binary, one module per feature (ripgrep's layout), so the crate
//! is linked once. `common` holds the configurations and helpers they share.

mod common;

mod budget;
mod calibrate;
mod cli;
mod cosim;
mod embedding;
mod every_model;
mod exhaustive;
mod explore;
mod figures;
mod gowin;
mod hostile;
mod interfaces;
mod layers;
mod models;
mod processes;
mod properties;
mod prove;
mod prove_ports;
mod python_hdl;
mod reliability;
mod render;
mod report;
mod rtl_tools;
mod sharing;
mod synth;
mod targets;
mod vectors;
