//! Lattice iCE40 UP5K: SB_MAC16 16×16 multipliers with post-adders, SB_RAM40_4K block RAM,
//! yosys's `synth_ice40`, nextpnr-ice40 (sg48 package) and IceStorm's `icetime`.

use super::{BlockLimit, Family, PlaceAndRoute};
use crate::config::Target;
use std::path::{Path, PathBuf};

pub(super) struct Ice40;

impl Family for Ice40 {
    fn name(&self) -> &'static str {
        "ice40"
    }
    fn part(&self) -> &'static str {
        "iCE40 UP5K"
    }
    fn calibration(&self) -> Option<&'static str> {
        Some("ice40")
    }
    fn synth_command(&self, dsp: bool, top: &str) -> String {
        format!("synth_ice40 -top {top}{}", if dsp { " -dsp" } else { "" })
    }
    fn place_and_route(&self, _grade: u32) -> Option<PlaceAndRoute> {
        Some(PlaceAndRoute {
            tools: &["nextpnr-ice40"],
            install: "apt-get install -y nextpnr-ice40",
            args: ["--up5k", "--package", "sg48", "--pcf-allow-unconstrained"].map(String::from).to_vec(),
        })
    }
    fn icetime(&self) -> bool {
        true
    }
    fn block_limits(&self, _grade: u32, dsp: bool, _bram: bool) -> Vec<BlockLimit> {
        // SB_RAM40_4K: IceStorm's data has no pulse width or period: no limit is known
        let mut out = Vec::new();
        if dsp {
            out.push(BlockLimit {
                block: "SB_MAC16",
                period_ns: 6.504,
                what:
                    "SB_MAC16 input to output register setup 6.504 ns, UP5K (IceStorm icefuzz/timings_up5k.txt, MAC_U_16X16_BYPASS); untimed by nextpnr-ice40"
                        .into(),
            });
        }
        out
    }
    fn has_block_ram(&self) -> bool {
        true
    }
    fn synthesized_on(&self) -> Target {
        Target::Ice40
    }
    fn cell_models(&self, datdir: &Path, _top: &str) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)> {
        let text = super::read(&datdir.join("ice40/cells_sim.v"))?;
        // port default values are SystemVerilog; the netlist connects every port it uses
        Ok(vec![("ice40_cells_sim.v".into(), format!("`define NO_ICE40_DEFAULT_ASSIGNMENTS\n{text}"))])
    }
}
