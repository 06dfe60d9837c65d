//! What the vendors' own timing data says a hard block allows, for the figures place-and-route
//! cannot give: nextpnr-ecp5 skips the cells' `Width` entries (`ecp5/trellis_import.py`:
//! `if entry["type"] == "Width": continue`), and nextpnr-ice40 models every SB_MAC16 port as a
//! register with 0.1 ns setup and clock-to-out, so neither times a block's own minimum period.
//! Every Fmax `synth` reports is the least of nextpnr's and these limits (docs/SPEC.md §7).
//!
//! Sources (the slow corner, the third of each triple):
//! - ECP5: Project Trellis database, `ECP5/timing/speed_{6,7,8}/cells.json`
//!   (YosysHQ/prjtrellis-db). DP16KD, normal write mode, either REGMODE: a clock pulse of at
//!   least 2.359 / 1.967 / 1.842 ns high and as long low. MULT18X18D with its input registers
//!   (`REGS=INPUT`): CLK0 → P 3.864 / 3.455 / 3.045 ns, the multiply between its input and
//!   output registers (the data has no setup for the output register: a lower bound).
//! - iCE40 UP5K: Project IceStorm, `icefuzz/timings_up5k.txt`. SB_MAC16 16×16 multiply-add
//!   with its inputs unregistered and its output registered (`MAC_U_16X16_BYPASS`): setup of
//!   B to CLK 6.504 ns; the block's route in comes on top, which nextpnr does time.
//!   SB_RAM40_4K: the file has no pulse width or period: no limit is known.

pub use super::BlockLimit;

/// The slowest of `limits` (the longest minimum period).
pub fn slowest(limits: &[BlockLimit]) -> Option<&BlockLimit> {
    limits
        .iter()
        .max_by(|a, b| a.period_ns.total_cmp(&b.period_ns))
}

/// The least of nextpnr's Fmax and the blocks' limits, and what sets it: `"routing (nextpnr)"`
/// or the limiting block's description.
pub fn limited(route_mhz: f64, limits: &[BlockLimit]) -> (f64, String) {
    match slowest(limits) {
        Some(l) if l.mhz() < route_mhz => (l.mhz(), l.what.clone()),
        _ => (route_mhz, "routing (nextpnr)".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Target;

    /// A grade-6 DP16KD allows 211.9 MHz, grade 8 271.4; the
    /// slower block wins; a faster route is capped, a slower one is not.
    #[test]
    fn the_slowest_block_caps_the_route() {
        let six = crate::family::of(Target::Ecp5).block_limits(6, true, true);
        assert_eq!(six.len(), 2);
        let (f, why) = limited(273.3, &six);
        assert_eq!(f, 211.9);
        assert!(
            why.starts_with("DP16KD") && why.contains("speed_6"),
            "{why}"
        );
        let eight = crate::family::of(Target::Ecp5).block_limits(8, false, true);
        let (f, _) = limited(eight[0].mhz() + 50.0, &eight);
        assert_eq!(f, 271.4);
        let (f, why) = limited(
            102.6,
            &crate::family::of(Target::Ice40).block_limits(0, true, true),
        );
        assert_eq!((f, why.as_str()), (102.6, "routing (nextpnr)"));
        assert!(crate::family::of(Target::Ecp5)
            .block_limits(6, false, false)
            .is_empty());
    }
}
