//! Reading the tools' output: yosys's cell counts and netlist (the hard multipliers'
//! registers), nextpnr's and icetime's clocks and logic cells.

use super::*;

/// The cell counts of module `top` from yosys's `stat -json` (its text differs between 0.23
/// and 0.70; the JSON does not): cell type → count, sorted by type.
pub(crate) fn parse_stat_json(json: &str, top: &str) -> Result<Vec<(String, u64)>, Failure> {
    let v: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| error::tool("yosys", format!("yosys's stat -json is not JSON: {e}")))?;
    let module = v
        .get("modules")
        .and_then(|m| m.get(format!("\\{top}")).or_else(|| m.get(top)))
        .ok_or_else(|| error::tool("yosys", format!("yosys's stat -json has no module {top}")))?;
    let by_type = module
        .get("num_cells_by_type")
        .and_then(|c| c.as_object())
        .ok_or_else(|| error::tool("yosys", "yosys's stat -json has no num_cells_by_type"))?;
    let mut cells: Vec<(String, u64)> = by_type
        .iter()
        .filter_map(|(k, n)| n.as_u64().map(|n| (k.clone(), n)))
        .collect();
    cells.sort();
    Ok(cells)
}

/// The hard multipliers of module `top` in yosys's `write_json` netlist that lack a register
/// of their own (SPEC §7), each named with what is missing: an SB_MAC16
/// whose clock is a constant, or a half of its output that is used and not registered (output
/// select 1, the accumulator register; 3 with `PIPELINE_16x16_MULT_REG2`, or with the 16×16
/// product's pipeline register `PIPELINE_16x16_MULT_REG1` and both 8×8 registers, where
/// yosys's ice40_dsp puts a product's one register; 2 with the 8×8 product's register); a
/// MULT18X18D without its output register or either input register.
pub(crate) fn unregistered_blocks(json: &str, top: &str) -> Result<Vec<String>, Failure> {
    Ok(block_registers(json, top)?.0)
}

/// The SB_MAC16s of module `top` whose used output is a 16×16 product held only in the
/// block's pipeline register (`PIPELINE_16x16_MULT_REG1` and the 8×8 registers, no
/// `PIPELINE_16x16_MULT_REG2`): the product's last add runs after the register, inside the
/// block, and nextpnr does not time it.
pub(crate) fn pipelined_blocks(json: &str, top: &str) -> Result<Vec<String>, Failure> {
    Ok(block_registers(json, top)?.1)
}

/// [`unregistered_blocks`] and [`pipelined_blocks`], from one reading of the netlist.
fn block_registers(json: &str, top: &str) -> Result<(Vec<String>, Vec<String>), Failure> {
    let v: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| error::tool("yosys", format!("yosys's write_json is not JSON: {e}")))?;
    let module = v
        .get("modules")
        .and_then(|m| m.get(top))
        .ok_or_else(|| error::tool("yosys", format!("yosys's netlist has no module {top}")))?;
    let empty = serde_json::Map::new();
    let cells = module
        .get("cells")
        .and_then(|c| c.as_object())
        .unwrap_or(&empty);
    // the nets something reads: a cell's input, or an output port of the module
    let mut read = std::collections::HashSet::new();
    for cell in cells.values() {
        let dirs = cell.get("port_directions").and_then(|d| d.as_object());
        for (port, bits) in cell
            .get("connections")
            .and_then(|c| c.as_object())
            .unwrap_or(&empty)
        {
            if dirs.and_then(|d| d.get(port)).and_then(|d| d.as_str()) != Some("output") {
                read.extend(
                    bits.as_array()
                        .into_iter()
                        .flatten()
                        .filter_map(|b| b.as_u64()),
                );
            }
        }
    }
    for port in module
        .get("ports")
        .and_then(|p| p.as_object())
        .unwrap_or(&empty)
        .values()
    {
        if port.get("direction").and_then(|d| d.as_str()) == Some("output") {
            read.extend(
                port.get("bits")
                    .and_then(|b| b.as_array())
                    .into_iter()
                    .flatten()
                    .filter_map(|b| b.as_u64()),
            );
        }
    }
    // a parameter as a number (yosys writes bit strings) or a string
    let param = |cell: &serde_json::Value, name: &str| -> String {
        cell.get("parameters")
            .and_then(|p| p.get(name))
            .and_then(|p| p.as_str())
            .map_or(String::new(), |s| s.trim().to_string())
    };
    let number = |cell: &serde_json::Value, name: &str| -> u64 {
        let text = param(cell, name);
        u64::from_str_radix(&text, 2).unwrap_or(0)
    };
    let bits = |cell: &serde_json::Value, port: &str| -> Vec<serde_json::Value> {
        cell.get("connections")
            .and_then(|c| c.get(port))
            .and_then(|b| b.as_array())
            .cloned()
            .unwrap_or_default()
    };
    let (mut missing, mut pipelined) = (Vec::new(), Vec::new());
    let mut names: Vec<&String> = cells.keys().collect();
    names.sort();
    for name in names {
        let cell = &cells[name];
        let shown = name.trim_start_matches('\\');
        match cell.get("type").and_then(|t| t.as_str()).unwrap_or("") {
            "SB_MAC16" => {
                if bits(cell, "CLK").iter().all(|b| b.as_u64().is_none()) {
                    missing.push(format!(
                        "SB_MAC16 {shown}: its clock is a constant (no register in use)"
                    ));
                    continue;
                }
                let out = bits(cell, "O");
                for (half, range, select) in [
                    ("top", 16..32, "TOPOUTPUT_SELECT"),
                    ("bottom", 0..16, "BOTOUTPUT_SELECT"),
                ] {
                    let used = out
                        .get(range)
                        .into_iter()
                        .flatten()
                        .any(|b| b.as_u64().is_some_and(|n| read.contains(&n)));
                    let registered = match number(cell, select) {
                        1 => true,
                        2 => {
                            number(
                                cell,
                                if half == "top" {
                                    "TOP_8x8_MULT_REG"
                                } else {
                                    "BOT_8x8_MULT_REG"
                                },
                            ) == 1
                        }
                        // the output register, or the block's own pipeline register after
                        // the 8×8 products (yosys's ice40_dsp puts the one register after a
                        // product there, and a second one at the output)
                        3 => {
                            number(cell, "PIPELINE_16x16_MULT_REG2") == 1
                                || [
                                    ("PIPELINE_16x16_MULT_REG1"),
                                    ("TOP_8x8_MULT_REG"),
                                    ("BOT_8x8_MULT_REG"),
                                ]
                                .iter()
                                .all(|r| number(cell, r) == 1)
                        }
                        _ => false,
                    };
                    let reg2 = number(cell, "PIPELINE_16x16_MULT_REG2") == 1;
                    if used
                        && registered
                        && number(cell, select) == 3
                        && !reg2
                        && !pipelined
                            .iter()
                            .any(|p: &String| p.starts_with(&format!("SB_MAC16 {shown}:")))
                    {
                        pipelined.push(format!(
                            "SB_MAC16 {shown}: the 16x16 product in the block's pipeline register, its last add after it (no PIPELINE_16x16_MULT_REG2)"
                        ));
                    }
                    if used && !registered {
                        missing.push(format!("SB_MAC16 {shown}: the {half} half of its output is not registered ({select} = {})", number(cell, select)));
                    }
                }
            }
            // a family's multiplier block (instantiated or inferred): each register its `Blocks` names
            ty => {
                let family_blocks = crate::config::Target::ALL
                    .into_iter()
                    .filter_map(|t| crate::family::of(t).blocks());
                let registers = family_blocks
                    .flat_map(|b| b.dsp_registers.iter())
                    .find(|(cell, _)| *cell == ty)
                    .map_or(&[][..], |(_, regs)| *regs);
                for &(reg, what) in registers {
                    let value = param(cell, reg);
                    if value.is_empty() || value == "NONE" || value.chars().all(|c| c == '0') {
                        missing.push(format!(
                            "{ty} {shown}: no {what} register ({reg} = {})",
                            if value.is_empty() { "NONE" } else { &value }
                        ));
                    }
                }
            }
        }
    }
    Ok((missing, pipelined))
}

/// nextpnr's Fmax of a routed design: the slowest of the clocks in its last report (each
/// clock's last "Max frequency" line: the one after routing). A hard block whose clock pin is
/// tied low (an SB_MAC16 with no register in use) forms a clock of its own,
/// `$PACKER_GND_NET`, whose figure is only the routes between such blocks: the wrapper's
/// `clk` may be far slower, so the figure is the least of them.
pub(crate) fn fmax_of_log(log: &str) -> Option<f64> {
    let mut last: Vec<(&str, f64)> = Vec::new();
    for l in log.lines() {
        let Some(rest) = l.split("Max frequency for clock").nth(1) else {
            continue;
        };
        let Some((name, value)) = rest.split_once("': ") else {
            continue;
        };
        let Some(mhz) = value
            .split_whitespace()
            .next()
            .and_then(|v| v.parse::<f64>().ok())
        else {
            continue;
        };
        let name = name.trim().trim_start_matches('\'');
        match last.iter_mut().find(|(n, _)| *n == name) {
            Some(slot) => slot.1 = mhz,
            None => last.push((name, mhz)),
        }
    }
    last.into_iter().map(|(_, f)| f).reduce(f64::min)
}

/// icetime's estimate: `Total path delay: 9.56 ns (104.64 MHz)`.
pub(crate) fn icetime_mhz(report: &str) -> Option<f64> {
    let line = report.lines().rfind(|l| l.contains("Total path delay:"))?;
    line.split('(')
        .nth(1)?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// Whether nextpnr saw a hard block clocked by a constant: on the iCE40 an SB_MAC16 used
/// without any of its registers.
pub(crate) fn has_unclocked_block(log: &str) -> bool {
    log.lines().any(|l| {
        (l.contains("Max frequency for clock") || l.contains("Max delay"))
            && (l.contains("$PACKER_GND_NET") || l.contains("$PACKER_VCC_NET"))
    })
}

/// What `fmax_note` adds when [`has_unclocked_block`]: nextpnr-ice40 (0.4, `ice40/arch.cc`,
/// `getPortClockingInfo`) models every SB_MAC16 data port as a register of its CLK pin, with
/// 0.1 ns setup and clock-to-out, so the multiply inside is never timed, and a path through a
/// block whose CLK is tied low is cut in two.
pub const UNCLOCKED_BLOCK_NOTE: &str =
    "; an SB_MAC16 without registers (its clock tied low): nextpnr-ice40 does not time a path through it, so the figure is an upper bound";

/// The packed logic cells in a nextpnr log: `ICESTORM_LC: 777/ 5280 14%` or
/// `TRELLIS_SLICE: 312/ 12144 2%` under "Device utilisation", or the larger of
/// `TRELLIS_COMB` and `TRELLIS_FF` where those are counted instead.
pub(crate) fn logic_cells(log: &str) -> Option<u64> {
    let used = |cell: &str| {
        log.lines().find_map(|l| {
            let rest = l.split(&format!(" {cell}:")).nth(1)?;
            rest.split('/').next()?.trim().parse::<u64>().ok()
        })
    };
    // nextpnr-ecp5 builds that place LUTs and flip-flops as cells of their own report
    // TRELLIS_COMB and TRELLIS_FF, not slices: a LUT4 and a flip-flop together, as an
    // ICESTORM_LC holds them, is then the larger of the two
    // nextpnr-himbaechel (Gowin) counts LUT4s, ALUs (a LUT's place each) and DFFs: a LUT
    // with its flip-flop is one cell, as ICESTORM_LC counts them
    used("ICESTORM_LC")
        .or_else(|| used("TRELLIS_SLICE"))
        .or_else(|| Some(used("TRELLIS_COMB")?.max(used("TRELLIS_FF")?)))
        .or_else(|| Some((used("LUT4")? + used("ALU").unwrap_or(0)).max(used("DFF").unwrap_or(0))))
}

/// Whether a netlist cell is a hard multiplier block of any family (`CellKind::Dsp`).
pub(crate) fn is_dsp_block(cell: &str) -> bool {
    crate::config::Target::ALL
        .into_iter()
        .any(|t| crate::family::of(t).cell_kind(cell) == Some(crate::family::CellKind::Dsp))
}

/// The unit's `--dsp-budget` against its netlist's cells (`parse_stat_json`): why it is broken
/// (the blocks counted, by kind), or None when it holds or there is none.
/// The blocks of a netlist without a register of their own when the unit promised every block
/// one (its manifest lists no `unregistered_products`: SPEC §7), as a broken promise naming them.
pub(crate) fn broken_register_promise(
    unregistered: &[String],
    promised: bool,
    top: &str,
) -> Option<String> {
    (promised && !unregistered.is_empty()).then(|| {
        format!(
            "unregistered_products: {top} promises every hard multiplier a register of its own (its manifest lists none without), and the netlist has {} without:\n  {}",
            unregistered.len(),
            unregistered.join("\n  ")
        )
    })
}

pub(crate) fn over_dsp_budget(
    cells: &[(String, u64)],
    budget: Option<u32>,
    top: &str,
) -> Option<String> {
    let budget = budget?;
    let blocks: Vec<&(String, u64)> = cells
        .iter()
        .filter(|(n, c)| is_dsp_block(n) && *c > 0)
        .collect();
    let total: u64 = blocks.iter().map(|(_, c)| c).sum();
    (total > budget as u64).then(|| {
        let kinds: Vec<String> = blocks.iter().map(|(n, c)| format!("{c} {n}")).collect();
        format!(
            "dsp_budget: the netlist of {top} has {total} hard multiplier blocks ({}), more than the {budget} it was generated for (--dsp-budget {budget})",
            kinds.join(", ")
        )
    })
}
