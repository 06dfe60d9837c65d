//! The adapter between a unit and the harnesses: `specgen_cosim_top` (`templates/cosim_top.v`)
//! gives every interface mode one set of port names, so one Verilator harness and one Icarus
//! bench drive them all.

use crate::config::{Config, Interface};
use crate::ports;
use askama::Template;

#[derive(Template)]
#[template(path = "cosim_top.v")]
struct CosimTop<'a> {
    name: &'a str,
    top: &'a str,
    interface: &'a str,
    version: &'a str,
    cos_w: u32,
    n_w: u32,
    b_w: u32,
    i_w: u32,
    /// bits of a handshake unit's lemma port (0: none)
    lemma_w: u32,
    body: Vec<String>,
    /// the unit's data outputs as connected, from the highest bits down (`f_out_ports`)
    raw: Vec<String>,
    raw_w: u32,
}

/// The adapter's Verilog for the unit `cfg` describes, as module `specgen_cosim_top`.
pub(crate) fn adapter(cfg: &Config) -> String {
    adapter_named(cfg, "specgen_cosim_top")
}

/// The adapter as module `name`.
pub(crate) fn adapter_named(cfg: &Config, name: &str) -> String {
    // the carried word: the tag, tlast above it
    let (tw, user) = (cfg.carried_tag_bits(), cfg.tag_bits());
    let axis = cfg.interface() == Interface::Axis;
    // a handshake unit's lemma port, passed through (`specgen prove`: SPECGEN_LEMMAS)
    let lemma_w = if cfg.interface().handshake() {
        crate::interface::CheckerState::of(cfg).width()
    } else {
        0
    };
    let (sf, sw, mf, mw) = ports::tdata_fields(cfg.port_widths());
    let mut body = Vec::new();
    let mut links = Vec::new();
    let table = cfg.ports("");
    let names: Vec<&str> = table.iter().map(|p| p.name).collect();
    // every data output as it leaves the unit (`specgen prove`'s port checker reads them whole)
    let mut raw = Vec::new();
    let mut raw_w = 0;
    for (name, port) in names.iter().zip(&table) {
        let to = match *name {
            "aclk" => "clk".to_string(),
            "aresetn" | "rst_n" => "~rst".to_string(),
            "areset" => "rst".to_string(),
            "aclken" => "clk_en".to_string(),
            "s_axis_tvalid" => "in_valid".to_string(),
            "s_axis_tready" => "in_ready".to_string(),
            "s_axis_tdata" => ports::packed_tdata(&sf, sw),
            "m_axis_tvalid" => "out_valid".to_string(),
            "m_axis_tready" => "out_ready".to_string(),
            "m_axis_tdata" => "m_tdata".to_string(),
            "s_axis_tuser" | "in_tag" => format!("in_tag[{}:0]", user - 1),
            "m_axis_tuser" | "out_tag" => format!("out_tag[{}:0]", user - 1),
            "s_axis_tlast" => format!("in_tag[{user}]"),
            "m_axis_tlast" => format!("out_tag[{user}]"),
            other => other.to_string(),
        };
        if port.direction == "output" && ports::port_rule(name) == Some(ports::PortRule::Data) {
            raw.push(to.clone());
            raw_w += port.width;
        }
        links.push(format!(".{name}({to})"));
    }
    if axis {
        body.push(format!("wire [{}:0] m_tdata;", mw - 1));
        for f in &mf {
            body.push(format!(
                "assign {} = m_tdata[{}:{}];",
                f.name,
                f.lo + f.width - 1,
                f.lo
            ));
        }
    }
    body.push(format!("{} dut (", cfg.top()));
    let n = links.len();
    for (i, l) in links.into_iter().enumerate() {
        body.push(format!("    {l}{}", if i + 1 < n { "," } else { "" }));
    }
    if lemma_w > 0 {
        body.push("`ifdef SPECGEN_LEMMAS".into());
        body.push("    , .f_ports(f_ports)".into());
        body.push("`endif".into());
    }
    body.push(");".into());
    if !names.contains(&"in_ready") && !names.contains(&"s_axis_tready") {
        body.push("assign in_ready = 1'b1;".into());
    }
    if tw == 0 {
        body.push("assign out_tag = 64'd0;".into());
    } else if tw < 64 {
        body.push(format!("assign out_tag[63:{tw}] = {}'d0;", 64 - tw));
    }
    if !names.contains(&"idle") {
        body.push("assign idle = 1'b0;".into());
    }
    CosimTop {
        name,
        top: cfg.top(),
        interface: cfg.interface().name(),
        version: crate::names::VERSION,
        cos_w: cfg.f() + 1,
        n_w: cfg.n_bits(),
        b_w: cfg.b(),
        i_w: cfg.fi() + 1,
        lemma_w,
        body,
        raw,
        raw_w,
    }
    .render()
    .expect("adapter template renders")
        + "\n"
}
