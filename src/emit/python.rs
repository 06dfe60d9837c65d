//! The unit as the Python HDLs' users write it: an Amaranth 0.5 component
//! (`<top>_amaranth.py`) and a LiteX module (`<top>_litex.py`), beside every unit.
//!
//! Both are one template each (`templates/amaranth.py`, `templates/litex.py`) over one
//! description of the unit, embedded as JSON: its ports with their widths (the manifest's
//! port table), which are the clock, the reset (and its polarity) and the handshake, how the
//! data ports form the input and output stream payloads (a port each, or the `axis` unit's
//! `tdata` fields by their bit offsets, the tag and tlast as fields), the ports of their own
//! (a clock enable, a static colour's registers) and the files the unit brings (its Verilog
//! and tables, not the simulation models or the testbench).

use crate::plan::Plan;
use askama::Template;
use serde::Serialize;

/// What both wrappers' templates read.
struct Wrapper<'a> {
    top: &'a str,
    version: &'a str,
    class_name: String,
    summary: String,
    latency: u32,
    unit_json: String,
}

#[derive(Template)]
#[template(path = "amaranth.py")]
struct AmaranthTemplate<'a> {
    w: &'a Wrapper<'a>,
}

#[derive(Template)]
#[template(path = "litex.py")]
struct LitexTemplate<'a> {
    w: &'a Wrapper<'a>,
}

/// One field of a stream's payload: the port it is (or is packed in, from bit `lo`).
#[derive(Serialize)]
struct Field {
    field: &'static str,
    width: u32,
    port: &'static str,
    lo: Option<u32>,
}

#[derive(Serialize)]
struct PortView {
    name: &'static str,
    direction: &'static str,
    width: u32,
}

#[derive(Serialize)]
struct Unit<'a> {
    top: &'a str,
    interface: &'a str,
    clock: Option<&'static str>,
    reset: Option<&'static str>,
    reset_low: bool,
    in_valid: &'static str,
    in_ready: Option<&'static str>,
    out_valid: &'static str,
    out_ready: Option<&'static str>,
    sink: Vec<Field>,
    source: Vec<Field>,
    other: Vec<PortView>,
    ports: Vec<PortView>,
    files: Vec<String>,
}

/// `specular_unit` → `SpecularUnit`.
fn class_name(top: &str) -> String {
    let mut out = String::new();
    for part in top.split('_').filter(|p| !p.is_empty()) {
        let mut c = part.chars();
        if let Some(first) = c.next() {
            out.extend(first.to_uppercase());
            out.push_str(c.as_str());
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert_str(0, "Unit");
    }
    out
}

/// The description both wrappers read: `files` are the names of the unit's RTL and tables.
fn unit_description<'a>(plan: &'a Plan, files: Vec<String>) -> Unit<'a> {
    let cfg = &plan.cfg;
    let ports = cfg.ports("");
    let axis = cfg.interface() == crate::config::Interface::Axis;
    let (s_fields, _, m_fields, _) = crate::ports::tdata_fields(cfg.port_widths());
    let mut u = Unit {
        top: cfg.top(),
        interface: cfg.interface().name(),
        clock: None,
        reset: None,
        reset_low: cfg.reset() == crate::config::Reset::SyncLow,
        in_valid: "",
        in_ready: None,
        out_valid: "",
        out_ready: None,
        sink: Vec::new(),
        source: Vec::new(),
        other: Vec::new(),
        ports: ports
            .iter()
            .map(|p| PortView {
                name: p.name,
                direction: p.direction,
                width: p.width,
            })
            .collect(),
        files,
    };
    for p in &ports {
        let field = |name: &'static str| match name {
            "in_tag" | "out_tag" | "s_axis_tuser" | "m_axis_tuser" => "tag",
            "s_axis_tlast" | "m_axis_tlast" => "last",
            other => other,
        };
        match (p.name, p.direction) {
            ("clk" | "aclk", _) => u.clock = Some(p.name),
            ("rst" | "rst_n" | "aresetn" | "areset", _) => u.reset = Some(p.name),
            ("in_valid" | "s_axis_tvalid", _) => u.in_valid = p.name,
            ("in_ready" | "s_axis_tready", _) => u.in_ready = Some(p.name),
            ("out_valid" | "m_axis_tvalid", _) => u.out_valid = p.name,
            ("out_ready" | "m_axis_tready", _) => u.out_ready = Some(p.name),
            ("s_axis_tdata", _) if axis => u.sink.extend(s_fields.iter().map(|f| Field {
                field: f.name,
                width: f.width,
                port: p.name,
                lo: Some(f.lo),
            })),
            ("m_axis_tdata", _) if axis => u.source.extend(m_fields.iter().map(|f| Field {
                field: f.name,
                width: f.width,
                port: p.name,
                lo: Some(f.lo),
            })),
            (name, "input") if p.data => u.sink.push(Field {
                field: field(name),
                width: p.width,
                port: name,
                lo: None,
            }),
            (name, _) if p.data => u.source.push(Field {
                field: field(name),
                width: p.width,
                port: name,
                lo: None,
            }),
            (name, direction) => u.other.push(PortView {
                name,
                direction,
                width: p.width,
            }),
        }
    }
    u
}

/// The two wrappers, by file name: `<top>_amaranth.py` and `<top>_litex.py`. `files` names
/// what the unit brings for synthesis (its Verilog and its tables).
pub fn python_files(plan: &Plan, files: Vec<String>) -> Vec<(String, String)> {
    let cfg = &plan.cfg;
    let top = cfg.top();
    let unit = unit_description(plan, files);
    assert!(
        unit.reset.is_some() || unit.clock.is_none(),
        "a clocked unit has a reset port"
    );
    let unit_json = serde_json::to_string(&unit).expect("the unit serialises");
    let summary = plan.model.unit().describe().summary.to_string();
    let latency = cfg.latency();
    let w = Wrapper {
        top,
        version: crate::names::VERSION,
        class_name: class_name(top),
        summary,
        latency,
        unit_json,
    };
    let (amaranth, litex) = (AmaranthTemplate { w: &w }, LitexTemplate { w: &w });
    vec![
        (
            format!("{top}_amaranth.py"),
            amaranth.render().expect("amaranth template renders") + "\n",
        ),
        (
            format!("{top}_litex.py"),
            litex.render().expect("litex template renders") + "\n",
        ),
    ]
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_class_is_named_after_its_top() {
        assert_eq!(super::class_name("specular_unit"), "SpecularUnit");
        assert_eq!(super::class_name("spec2_x"), "Spec2X");
        assert_eq!(super::class_name("_a__b_"), "AB");
    }
}
