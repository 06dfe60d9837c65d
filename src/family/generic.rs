//! No family: whole-width products and adds that any synthesis tool maps; yosys's generic
//! `synth`, no place-and-route, no part, no delay model (its clock is the device's it lands on).

use super::{BlockLimit, Family, PlaceAndRoute};
use crate::config::Target;
use std::path::{Path, PathBuf};

pub(super) struct Generic;

impl Family for Generic {
    fn name(&self) -> &'static str {
        "generic"
    }
    fn part(&self) -> &'static str {
        "generic target (no part)"
    }
    fn dsp_capacity(&self) -> Option<u64> {
        None
    }
    fn explore_clocks(&self) -> &'static [f64] {
        &[]
    }
    fn synth_command(&self, _dsp: bool, top: &str) -> String {
        format!("synth -top {top}")
    }
    fn place_and_route(&self, _grade: u32) -> Option<PlaceAndRoute> {
        None
    }
    fn block_limits(&self, _grade: u32, _dsp: bool, _bram: bool) -> Vec<BlockLimit> {
        Vec::new()
    }
    fn has_block_ram(&self) -> bool {
        false
    }
    /// (its RTL maps anywhere; `synth` measures it on the iCE40 unless told otherwise)
    fn synthesized_on(&self) -> Target {
        Target::Ice40
    }
    fn generic_gates(&self) -> bool {
        true
    }
    fn multiplier_bits(&self) -> u32 {
        u32::MAX
    }
    fn carry_chunk_bits(&self) -> u32 {
        u32::MAX
    }
    fn soft_product(&self, _a: u32, _b: u32, _y: u32) -> bool {
        false
    }
    fn post_adder(&self, _width: u32, _wa: u32, _wb: u32) -> bool {
        true
    }
    fn cell_models(
        &self,
        _datdir: &Path,
        _top: &str,
    ) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)> {
        Ok(Vec::new())
    }
}
