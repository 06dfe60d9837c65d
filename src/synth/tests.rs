use super::*;

/// The consumer's ready reaches a handshake unit through two free flip-flops of the
/// wrapper (under either name); a unit without it is wired straight from the input chain.
#[test]
fn the_wrapper_gives_the_consumers_ready_through_two_free_flip_flops() {
    use crate::config::{Interface, Params};
    for (interface, ready) in [
        (Interface::Valid, None),
        (Interface::Ready, Some("out_ready")),
        (Interface::Axis, Some("m_axis_tready")),
    ] {
        let cfg = Config::new(Params {
            interface,
            stages: 4,
            ..Default::default()
        })
        .unwrap();
        let text = wrapper(&cfg);
        match ready {
            None => assert!(!text.contains("_near"), "{text}"),
            Some(name) => {
                assert!(text.contains(&format!(".{name}({name}_near)")), "{text}");
                assert!(
                    text.contains(&format!("{name}_relay <= in_reg["))
                        && text.contains(&format!("{name}_near <= {name}_relay;")),
                    "{text}"
                );
            }
        }
    }
}

#[test]
fn logic_cells_are_read_from_the_device_utilisation() {
    let ice40 = "Info: Device utilisation:\nInfo: \t         ICESTORM_LC:   777/ 5280    14%\nInfo: \t        ICESTORM_RAM:     4/   30    13%\n";
    assert_eq!(logic_cells(ice40), Some(777));
    let ecp5 = "Info: Device utilisation:\nInfo: \t          TRELLIS_IO:    23/  197    11%\nInfo: \t       TRELLIS_SLICE:   312/12144     2%\n";
    assert_eq!(logic_cells(ecp5), Some(312));
    let ecp5_cells = "Info: Device utilisation:\nInfo: \t          TRELLIS_FF:    2684/  24288    11%\nInfo: \t        TRELLIS_COMB:    1510/  24288     6%\n";
    assert_eq!(logic_cells(ecp5_cells), Some(2684));
    assert_eq!(
        logic_cells("Info: Max frequency for clock 'clk': 102.60 MHz"),
        None
    );
}

/// The netlist check names every hard multiplier without the registers
/// SPEC §7 promises: an SB_MAC16 with a constant clock, one whose used output half is
/// combinational, a MULT18X18D without its output or an input register; a registered
/// block, a 16×16 product in its pipeline register (REG1 and both 8×8 registers, yosys's
/// mapping of one register after a product) and an unused half pass; REG1 alone does not.
#[test]
fn unregistered_blocks_are_named_from_the_netlist() {
    let macp = |clk: &str, top: u32, bot: u32, reg2: u32, pipe: (u32, u32), o: &str| {
        let (reg1, r8) = pipe;
        format!(
            r#"{{"type": "SB_MAC16", "parameters": {{"TOPOUTPUT_SELECT": "{top:02b}", "BOTOUTPUT_SELECT": "{bot:02b}", "PIPELINE_16x16_MULT_REG2": "{reg2}",
            "PIPELINE_16x16_MULT_REG1": "{reg1}", "TOP_8x8_MULT_REG": "{r8}", "BOT_8x8_MULT_REG": "{r8}"}},
            "port_directions": {{"CLK": "input", "O": "output"}}, "connections": {{"CLK": [{clk}], "O": {o}}}}}"#
        )
    };
    let mac =
        |clk: &str, top: u32, bot: u32, reg2: u32, o: &str| macp(clk, top, bot, reg2, (0, 0), o);
    let low: Vec<u32> = (10..26).collect();
    let both: Vec<u32> = (10..42).collect();
    let o_low = format!(
        "{:?}",
        low.iter()
            .chain(std::iter::repeat_n(&99, 16))
            .collect::<Vec<_>>()
    );
    let o_both = format!("{both:?}");
    let json = format!(
        r#"{{"modules": {{"u": {{"ports": {{"y": {{"direction": "output", "bits": {both:?}}}}},
        "cells": {{
          "$tied": {},
          "\\comb": {},
          "regd": {},
          "lowonly": {},
          "piped": {},
          "reg1only": {},
          "$m": {{"type": "MULT18X18D", "parameters": {{"REG_OUTPUT_CLK": "NONE", "REG_INPUTA_CLK": "CLK0", "REG_INPUTB_CLK": "CLK0"}}, "connections": {{}}}},
          "$ok": {{"type": "MULT18X18D", "parameters": {{"REG_OUTPUT_CLK": "CLK0", "REG_INPUTA_CLK": "CLK0", "REG_INPUTB_CLK": "CLK0"}}, "connections": {{}}}},
          "$w": {{"type": "MULT36X36", "parameters": {{"OUT0_REG": "0", "AREG": "1", "BREG": "1"}}, "connections": {{}}}},
          "$g": {{"type": "MULT18X18", "parameters": {{"OUT_REG": "1", "AREG": "1", "BREG": "1"}}, "connections": {{}}}}
        }}}}}}}}"#,
        mac("\"0\"", 1, 1, 0, &o_both),
        mac("5", 3, 3, 0, &o_both),
        mac("5", 3, 3, 1, &o_both),
        mac("5", 0, 1, 0, &o_low),
        macp("5", 3, 3, 0, (1, 1), &o_both),
        macp("5", 3, 3, 0, (1, 0), &o_both),
    );
    let found = unregistered_blocks(&json, "u").unwrap();
    assert_eq!(found.len(), 7, "{found:#?}");
    assert!(
        found[0].starts_with("MULT18X18D $m: no output register"),
        "{found:#?}"
    );
    assert!(
        found[1].starts_with("SB_MAC16 $tied: its clock is a constant"),
        "{found:#?}"
    );
    // a multiplier the synthesis tool infers is held to its registers too (Gowin's MULT36X36)
    assert!(
        found[2].starts_with("MULT36X36 $w: no output register (OUT0_REG = 0)"),
        "{found:#?}"
    );
    assert!(
        found[3].starts_with("SB_MAC16 comb: the top half")
            && found[4].starts_with("SB_MAC16 comb: the bottom half"),
        "{found:#?}"
    );
    assert!(
        found[5].starts_with("SB_MAC16 reg1only: the top half")
            && found[6].starts_with("SB_MAC16 reg1only: the bottom half"),
        "{found:#?}"
    );
    // the one held in its pipeline register is named apart: a register of its own, its last
    // add untimed
    let piped = pipelined_blocks(&json, "u").unwrap();
    assert_eq!(piped.len(), 1, "{piped:#?}");
    assert!(
        piped[0].starts_with("SB_MAC16 piped: the 16x16 product in the block's pipeline register"),
        "{piped:#?}"
    );
}

/// A unit that promises every block its register and a netlist with one
/// without is a broken promise naming the block; without the promise, or with every block
/// registered, nothing is broken.
#[test]
fn a_block_without_the_promised_register_is_named() {
    let missing =
        vec!["SB_MAC16 kn_c4_SB_MAC16_O: its clock is a constant (no register in use)".to_string()];
    let why = broken_register_promise(&missing, true, "u").expect("promised and missing");
    assert!(
        why.starts_with("unregistered_products: u promises every hard multiplier")
            && why.contains("SB_MAC16 kn_c4_SB_MAC16_O"),
        "{why}"
    );
    assert!(broken_register_promise(&missing, false, "u").is_none());
    assert!(broken_register_promise(&[], true, "u").is_none());
}

/// The slowest clock of the last report, not the last line: an SB_MAC16 whose clock is tied
/// low forms a clock of its own whose figure is only the routes between such blocks.
#[test]
fn fmax_is_the_slowest_clock_after_routing() {
    let log = "Info: Max frequency for clock    'clk$SB_IO_IN_$glb_clk': 47.68 MHz (FAIL at 100.00 MHz)\n\
               Info: Max frequency for clock '$PACKER_GND_NET_$glb_clk': 139.74 MHz (PASS at 100.00 MHz)\n\
               Info: Routing..\n\
               Warning: Max frequency for clock    'clk$SB_IO_IN_$glb_clk': 46.69 MHz (FAIL at 100.00 MHz)\n\
               Info: Max frequency for clock '$PACKER_GND_NET_$glb_clk': 129.77 MHz (PASS at 100.00 MHz)\n";
    assert_eq!(fmax_of_log(log), Some(46.69));
    assert!(has_unclocked_block(log));
    let one = "Info: Max frequency for clock 'clk': 90.00 MHz (FAIL at 100.00 MHz)\nInfo: Max frequency for clock 'clk': 102.60 MHz (PASS at 100.00 MHz)\n";
    assert_eq!(fmax_of_log(one), Some(102.6));
    assert!(!has_unclocked_block(one));
    assert!(has_unclocked_block("Info: Max delay posedge $PACKER_GND_NET_$glb_clk -> posedge clk$SB_IO_IN_$glb_clk   : 4.93 ns"));
    assert_eq!(fmax_of_log("Info: Routing..\n"), None);
}

/// A netlist with more hard multipliers than the unit's --dsp-budget is a
/// broken promise, named with its blocks; at the budget, or without one, it holds.
#[test]
fn a_netlist_over_the_dsp_budget_is_named() {
    let cells = vec![("SB_LUT4".to_string(), 900), ("SB_MAC16".to_string(), 3)];
    let why = over_dsp_budget(&cells, Some(2), "u").expect("3 blocks over a budget of 2");
    assert!(
        why.starts_with("dsp_budget: the netlist of u has 3 hard multiplier blocks (3 SB_MAC16)"),
        "{why}"
    );
    assert!(over_dsp_budget(&cells, Some(3), "u").is_none());
    assert!(over_dsp_budget(&cells, None, "u").is_none());
    let ecp5 = vec![("MULT18X18D".to_string(), 1), ("ALU54B".to_string(), 1)];
    assert!(over_dsp_budget(&ecp5, Some(1), "u")
        .expect("two blocks")
        .contains("1 MULT18X18D, 1 ALU54B"));
}

/// Every seed's figure is capped as the median is. Schlick on the
/// ECP5 at grade 6 (its DP16KDs allow 211.9 MHz): nextpnr's seeds 203.2, 210.6 and 226.5 give
/// 203.2–211.9, nextpnr's own figures in parentheses; a unit under every limit is unchanged.
#[test]
fn every_seed_is_capped_by_the_blocks_limits() {
    let limits = vec![crate::family::BlockLimit {
        block: "DP16KD",
        period_ns: 4.719,
        what: "DP16KD clock pulse, grade 6".into(),
    }];
    let seeds = [203.2, 210.6, 226.5];
    let capped = capped_seeds(&seeds, &limits);
    assert_eq!(capped, vec![203.2, 210.6, 211.9]);
    let r = SynthResult {
        fmax_mhz: Some(210.6),
        fmax_route_mhz: Some(210.6),
        fmax_seeds: seeds.to_vec(),
        fmax_seeds_capped: capped,
        block_limits: limits
            .iter()
            .map(|l| (l.block.to_string(), l.mhz(), l.what.clone()))
            .collect(),
        ..Default::default()
    };
    assert_eq!(r.fmax_text().unwrap(), "210.6 median of 3 seeds (203.2–211.9), each capped by the DP16KD limit (nextpnr: 210.6, 203.2–226.5)");
    let under = SynthResult {
        fmax_seeds: vec![190.0, 200.0],
        fmax_seeds_capped: capped_seeds(&[190.0, 200.0], &limits),
        fmax_mhz: Some(195.0),
        ..r
    };
    assert_eq!(
        under.fmax_text().unwrap(),
        "195.0 median of 2 seeds (190.0–200.0)"
    );
}

/// A sweep's jobs, one seed each, read as one `synth --seeds 3`: the seeds in order, both
/// medians, the limit that caps the median named, the note's seed list; a failed seed fails the
/// whole.
#[test]
fn one_seed_results_are_one_result_over_the_seeds() {
    let limits = vec![crate::family::BlockLimit {
        block: "DP16KD",
        period_ns: 4.719,
        what: "DP16KD clock pulse, grade 6".into(),
    }];
    let one = |seed: u32, route: f64| {
        let (f, why) = crate::family::blocks::limited(route, &limits);
        SynthResult {
            seeds: vec![seed],
            fmax_mhz: Some(f),
            fmax_route_mhz: Some(route),
            fmax_limited_by: why,
            fmax_seeds: vec![route],
            fmax_seeds_capped: capped_seeds(&[route], &limits),
            fmax_note: format!("nextpnr-ecp5 --25k, median of seeds {seed} ({route:.1}), unit between registers of a serial-I/O wrapper"),
            luts: 100,
            ..Default::default()
        }
    };
    let all = SynthResult::over_seeds(&[one(1, 203.2), one(2, 226.5), one(3, 230.0)]).unwrap();
    assert_eq!(all.seeds, vec![1, 2, 3]);
    assert_eq!(all.fmax_seeds, vec![203.2, 226.5, 230.0]);
    assert_eq!(all.fmax_seeds_capped, vec![203.2, 211.9, 211.9]);
    assert_eq!(
        (all.fmax_mhz, all.fmax_route_mhz, all.luts),
        (Some(211.9), Some(226.5), 100)
    );
    assert!(
        all.fmax_limited_by.starts_with("DP16KD"),
        "{}",
        all.fmax_limited_by
    );
    assert_eq!(all.fmax_note, "nextpnr-ecp5 --25k, median of seeds 1..=3 (203.2, 226.5, 230.0), unit between registers of a serial-I/O wrapper");
    let under = SynthResult::over_seeds(&[one(1, 190.0), one(2, 200.0)]).unwrap();
    assert_eq!(
        (under.fmax_mhz, under.fmax_limited_by.as_str()),
        (Some(195.0), "routing (nextpnr)")
    );
    let failed = SynthResult {
        fmax_mhz: None,
        fmax_note: "place-and-route failed: ERROR: no BELs".into(),
        ..one(2, 0.0)
    };
    let whole = SynthResult::over_seeds(&[one(1, 190.0), failed]).unwrap();
    assert_eq!(
        (whole.fmax_mhz, whole.fmax_note.as_str()),
        (None, "place-and-route failed: ERROR: no BELs")
    );
    assert!(SynthResult::over_seeds(&[]).is_none());
}
