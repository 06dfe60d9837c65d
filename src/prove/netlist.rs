//! What a proof refuses to be handed, read from the unit's own elaboration (yosys's JSON of it
//! after `proc; flatten; memory_map`), before any step:
//!
//! - **an input the unit drives.** The harness's inputs are free; a unit that drives one of its
//!   own input bits (`assign rst = 1'b0;`, a cell's output, another input) merges the harness's
//!   free input with its own value once flattened, and the environment is then the unit's (a
//!   reset assumed at the first edge becomes `assume(0)`: every property vacuously true).
//! - **a second clock.** Every flip-flop is clocked by the unit's clock port on its rising edge,
//!   every clock pin of a hard block is that port (or a constant): a derived, gated or inverted
//!   clock is stepped on the one global clock by the formal model, which is not the circuit.
//! - **a latch.** A level-sensitive cell holds state between edges the formal model does not
//!   have: not supported (named, never blamed on formal regions).
//!
//! Each is refused naming the port and bit or the cell, and what it is.

use serde_json::Value;
use std::collections::BTreeMap;

/// One bit of a net in yosys's JSON: a net number, or a constant ("0", "1", "x", "z").
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
enum Bit {
    Net(u64),
    Const(String),
}

fn bits(v: &Value) -> Vec<Bit> {
    v.as_array()
        .map(|a| {
            a.iter()
                .map(|b| {
                    b.as_u64()
                        .map(Bit::Net)
                        .unwrap_or_else(|| Bit::Const(b.as_str().unwrap_or("x").to_string()))
                })
                .collect()
        })
        .unwrap_or_default()
}

/// A yosys parameter as JSON writes it (a binary string, or a number) as a number.
fn param(v: Option<&Value>) -> Option<u64> {
    match v? {
        Value::String(s) => u64::from_str_radix(s.trim(), 2).ok(),
        Value::Number(n) => n.as_u64(),
        _ => None,
    }
}

/// Whether `kind` is a flip-flop, and its clock's polarity (true: rising edge); None when not one.
fn flip_flop(kind: &str, params: &Value) -> Option<bool> {
    match kind {
        "$dff" | "$dffe" | "$adff" | "$adffe" | "$sdff" | "$sdffe" | "$sdffce" | "$aldff"
        | "$aldffe" | "$dffsr" | "$dffsre" => {
            Some(param(params.get("CLK_POLARITY")).unwrap_or(1) == 1)
        }
        _ if kind.starts_with("$_") && kind.contains("DFF") => {
            // $_DFF_P_, $_DFFE_PN_, $_SDFF_PN0_, $_DFFSR_PNN_: the letter after the stem
            let parts: Vec<&str> = kind.split('_').collect();
            let stem = parts.iter().position(|p| p.contains("DFF"))?;
            Some(parts.get(stem + 1).and_then(|p| p.chars().next()) != Some('N'))
        }
        _ => None,
    }
}

/// Whether `kind` holds state without an edge: a latch, an SR cell, or a flip-flop on the
/// formal global clock.
fn level_sensitive(kind: &str) -> bool {
    matches!(
        kind,
        "$dlatch" | "$adlatch" | "$dlatchsr" | "$sr" | "$ff" | "$_FF_"
    ) || kind.starts_with("$_DLATCH")
        || kind.starts_with("$_SR_")
}

/// Whether a hard block's pin named `pin` is a clock (CLK, CLK0..3, CLKA, CLKB, RCLK, WCLK; not
/// a clock enable such as RCLKE).
fn clock_pin(pin: &str) -> bool {
    let p = pin.to_ascii_uppercase();
    let Some(at) = p.find("CLK") else {
        return false;
    };
    let rest = &p[at + 3..];
    at <= 1
        && (rest.is_empty()
            || (rest.len() == 1
                && (rest.chars().all(|c| c.is_ascii_digit()) || rest == "A" || rest == "B")))
}

/// What is wrong with the module `module` of yosys's JSON `json` as a unit handed to a proof,
/// each in words (none: nothing); `clock`: its clock port (none: a combinational unit).
pub(super) fn refusals(json: &str, module: &str, clock: Option<&str>) -> Vec<String> {
    let all: Value = serde_json::from_str(json).unwrap_or_default();
    let m = &all["modules"][module];
    let mut why = Vec::new();
    let Some(ports) = m["ports"].as_object() else {
        return vec![format!("yosys wrote no module {module} to check")];
    };
    let empty = serde_json::Map::new();
    let cells = m["cells"].as_object().unwrap_or(&empty);
    // every net a name: what a message calls a bit
    let mut names: BTreeMap<Bit, String> = BTreeMap::new();
    if let Some(nets) = m["netnames"].as_object() {
        for (name, n) in nets.iter().filter(|(n, _)| !n.starts_with('$')) {
            let b = bits(&n["bits"]);
            for (i, bit) in b.iter().enumerate() {
                let label = if b.len() == 1 {
                    name.clone()
                } else {
                    format!("{name}[{i}]")
                };
                names.entry(bit.clone()).or_insert(label);
            }
        }
    }
    let name_of = |b: &Bit| match b {
        Bit::Const(c) => format!("the constant {c}"),
        Bit::Net(_) => names
            .get(b)
            .cloned()
            .unwrap_or_else(|| "a net inside the unit".to_string()),
    };
    // the bits every cell drives, and by which cell
    let mut driven: BTreeMap<Bit, String> = BTreeMap::new();
    for (cname, c) in cells {
        let dirs = &c["port_directions"];
        for (pin, conn) in c["connections"].as_object().unwrap_or(&empty) {
            if dirs[pin].as_str() == Some("output") {
                for b in bits(conn) {
                    driven.insert(
                        b,
                        format!("{cname} (a {})", c["type"].as_str().unwrap_or("cell")),
                    );
                }
            }
        }
    }
    // the inputs: each bit the harness's alone
    let mut seen: BTreeMap<Bit, String> = BTreeMap::new();
    for (port, p) in ports.iter().filter(|(_, p)| p["direction"] == "input") {
        let b = bits(&p["bits"]);
        for (i, bit) in b.iter().enumerate() {
            let label = if b.len() == 1 {
                port.clone()
            } else {
                format!("{port}[{i}]")
            };
            let by = match bit {
                Bit::Const(c) => Some(format!("tied to the constant {c}")),
                Bit::Net(_) => match (driven.get(bit), seen.get(bit)) {
                    (Some(cell), _) => Some(format!("driven by {cell}")),
                    (None, Some(other)) => Some(format!("tied to the input {other}")),
                    (None, None) => None,
                },
            };
            if let Some(by) = by {
                why.push(format!(
                    "the input {label} is {by} inside the unit: an input is the environment's, free at every edge (a unit that drives its own input decides what the proof assumes)"
                ));
            }
            seen.entry(bit.clone()).or_insert(label);
        }
    }
    // one clock, its rising edge
    let clk: Option<Bit> = clock
        .and_then(|c| ports.get(c))
        .and_then(|p| bits(&p["bits"]).into_iter().next());
    for (cname, c) in cells {
        let kind = c["type"].as_str().unwrap_or("");
        let conns = c["connections"].as_object().unwrap_or(&empty);
        if level_sensitive(kind) {
            why.push(format!(
                "{cname} is a {kind}, a latch (state held between clock edges): not supported; a unit proved here has flip-flops on its clock's rising edge only"
            ));
            continue;
        }
        if let Some(rising) = flip_flop(kind, &c["parameters"]) {
            let on = conns
                .get("CLK")
                .or_else(|| conns.get("C"))
                .map(bits)
                .unwrap_or_default();
            match on.first() {
                Some(b) if Some(b) == clk.as_ref() && rising => {}
                Some(b) if Some(b) == clk.as_ref() => why.push(format!(
                    "{cname} (a {kind}) is clocked on the falling edge of {}: not supported; every flip-flop of a unit is clocked on its clock's rising edge",
                    clock.unwrap_or("clk")
                )),
                Some(b) => why.push(format!(
                    "{cname} (a {kind}) is clocked by {}, not by the clock port {}: a derived, gated or inverted clock; the proof has one clock, and every flip-flop is clocked by it on its rising edge (gate with a clock enable instead)",
                    name_of(b),
                    clock.unwrap_or("(none: a combinational unit)")
                )),
                None => why.push(format!("{cname} (a {kind}) has no clock")),
            }
            continue;
        }
        // a hard block's clock pins: the clock port, or a constant (an unused pin)
        if !kind.starts_with('$') {
            for (pin, conn) in conns.iter().filter(|(pin, _)| clock_pin(pin)) {
                for b in bits(conn) {
                    if Some(&b) != clk.as_ref() && !matches!(b, Bit::Const(_)) {
                        why.push(format!(
                            "{cname} (a {kind}) has its clock pin {pin} on {}, not on the clock port {}: a derived, gated or inverted clock",
                            name_of(&b),
                            clock.unwrap_or("(none)")
                        ));
                    }
                }
            }
        }
    }
    why
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_pins_are_clocks_not_enables() {
        for p in ["CLK", "CLK0", "CLK3", "CLKA", "CLKB", "RCLK", "WCLK", "clk"] {
            assert!(clock_pin(p), "{p}");
        }
        for p in ["RCLKE", "WCLKE", "CE", "CE0", "CLKEN", "ACLKX"] {
            assert!(!clock_pin(p), "{p}");
        }
    }

    #[test]
    fn flip_flops_and_their_edges() {
        let rising = serde_json::json!({"CLK_POLARITY": "1"});
        let falling = serde_json::json!({"CLK_POLARITY": "0"});
        assert_eq!(flip_flop("$dff", &rising), Some(true));
        assert_eq!(flip_flop("$sdffe", &falling), Some(false));
        assert_eq!(flip_flop("$_DFF_N_", &Value::Null), Some(false));
        assert_eq!(flip_flop("$_SDFFE_PN0P_", &Value::Null), Some(true));
        assert_eq!(flip_flop("$and", &Value::Null), None);
        assert!(
            level_sensitive("$dlatch")
                && level_sensitive("$_DLATCH_P_")
                && !level_sensitive("$dff")
        );
    }

    #[test]
    fn a_driven_input_a_second_clock_and_a_latch_are_named() {
        // yosys's JSON of: rst tied to 0, a[1] driven by q[0], q clocked by clk & en, r on negedge,
        // a latch
        let json = r#"{"modules":{"built":{"ports":{
            "clk":{"direction":"input","bits":[2]},"rst":{"direction":"input","bits":["0"]},
            "en":{"direction":"input","bits":[3]},"a":{"direction":"input","bits":[4,5]},
            "b":{"direction":"input","bits":[3]},
            "q":{"direction":"output","bits":[5,8]}},
          "cells":{
            "$and$1":{"type":"$and","port_directions":{"A":"input","B":"input","Y":"output"},"connections":{"A":[2],"B":[3],"Y":[15]}},
            "$dff$1":{"type":"$dff","parameters":{"CLK_POLARITY":"1"},"port_directions":{"CLK":"input","D":"input","Q":"output"},"connections":{"CLK":[15],"D":[4,4],"Q":[5,8]}},
            "$dff$2":{"type":"$dff","parameters":{"CLK_POLARITY":"0"},"port_directions":{"CLK":"input","D":"input","Q":"output"},"connections":{"CLK":[2],"D":[4],"Q":[9]}},
            "$dff$3":{"type":"$dff","parameters":{"CLK_POLARITY":"00000000000000000000000000000001"},"port_directions":{"CLK":"input","D":"input","Q":"output"},"connections":{"CLK":[2],"D":[4],"Q":[10]}},
            "$dlatch$1":{"type":"$dlatch","port_directions":{"EN":"input","D":"input","Q":"output"},"connections":{"EN":[3],"D":[4],"Q":[11]}},
            "mac":{"type":"SB_MAC16","port_directions":{"CLK":"input","CE":"input","O":"output"},"connections":{"CLK":[15],"CE":[3],"O":[12]}}},
          "netnames":{"g":{"bits":[15]},"clk":{"bits":[2]}}}}}"#;
        let why = refusals(json, "built", Some("clk"));
        let has = |s: &str| why.iter().any(|w| w.contains(s));
        assert!(has("the input rst is tied to the constant 0"), "{why:?}");
        assert!(has("the input a[1] is driven by $dff$1"), "{why:?}");
        assert!(has("the input b is tied to the input en"), "{why:?}");
        assert!(has("$dff$1 (a $dff) is clocked by g"), "{why:?}");
        assert!(
            has("$dff$2 (a $dff) is clocked on the falling edge"),
            "{why:?}"
        );
        assert!(!has("$dff$3"), "{why:?}");
        assert!(has("$dlatch$1 is a $dlatch, a latch"), "{why:?}");
        assert!(
            has("mac (a SB_MAC16) has its clock pin CLK on g"),
            "{why:?}"
        );
        assert!(!has("CE"), "{why:?}");
        assert_eq!(why.len(), 7, "{why:?}");
    }
}
