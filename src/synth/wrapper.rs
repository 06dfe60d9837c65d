//! The wrapper synthesis places a unit in: its ports on the part's pins, serial where the
//! unit has more than the package (and the cost of that wrapper).

use super::*;

pub(super) struct WrapperPort {
    name: &'static str,
    hi: u32,
    lo: u32,
    /// the consumer's ready: it reaches the unit through two free flip-flops (the template says why)
    relay: bool,
}

#[derive(Template)]
#[template(path = "synth_wrapper.v")]
pub(super) struct Wrapper<'a> {
    top: &'a str,
    clocked: bool,
    /// the unit's clock and reset ports (`clk`/`rst`, or `aclk`/`aresetn`)
    clock: &'a str,
    reset: &'a str,
    in_bits: u32,
    out_bits: u32,
    inputs: Vec<WrapperPort>,
    outputs: Vec<WrapperPort>,
}

/// What the serial wrapper around a unit costs in the figures `synth` measures (they are of the
/// unit between its registers): (LUTs, flip-flops). Two registers a data bit in (the chain and
/// the word it loads), two out with a LUT each (the word and the chain it loads or shifts), the
/// reset's bit, two relay flip-flops a ready bit.
pub fn wrapper_cost(cfg: &Config) -> (u64, u64) {
    let w = wrapper_ports(cfg);
    let relays: u32 = w
        .inputs
        .iter()
        .filter(|p| p.relay)
        .map(|p| 2 * (p.hi - p.lo + 1))
        .sum();
    (
        w.out_bits as u64,
        2 * (w.in_bits + w.out_bits) as u64 + relays as u64,
    )
}

/// The wrapper's ports, packed into its input and output words.
pub(super) struct WrapperPorts {
    inputs: Vec<WrapperPort>,
    outputs: Vec<WrapperPort>,
    /// the input word's bits (the reset's among them where the unit has one)
    in_bits: u32,
    out_bits: u32,
}

pub(super) fn wrapper_ports(cfg: &Config) -> WrapperPorts {
    let ports = cfg.ports("");
    let pack = |dir: &str| {
        let mut lo = 0;
        let mut v = Vec::new();
        for p in ports.iter().filter(|p| {
            p.direction == dir
                && !["clk", "aclk", crate::ports::reset_port(cfg.port_widths())].contains(&p.name)
        }) {
            v.push(WrapperPort {
                name: p.name,
                hi: lo + p.width - 1,
                lo,
                relay: ["out_ready", "m_axis_tready"].contains(&p.name),
            });
            lo += p.width;
        }
        (v, lo)
    };
    let (inputs, in_data) = pack("input");
    let (outputs, out_bits) = pack("output");
    WrapperPorts {
        inputs,
        outputs,
        in_bits: in_data + cfg.clocked() as u32,
        out_bits,
    }
}

pub(super) fn wrapper(cfg: &Config) -> String {
    let WrapperPorts {
        inputs,
        outputs,
        in_bits,
        out_bits,
    } = wrapper_ports(cfg);
    let clocked = cfg.clocked();
    let axis = cfg.interface() == crate::config::Interface::Axis;
    let clock = if axis { "aclk" } else { "clk" };
    let reset = crate::ports::reset_port(cfg.port_widths());
    let mut text = Wrapper {
        top: cfg.top(),
        clocked,
        clock,
        reset,
        in_bits,
        out_bits,
        inputs,
        outputs,
    }
    .render()
    .expect("wrapper renders");
    text.push('\n');
    text
}
