//! What a proof reads of the unit and says of it: its data outputs whole, the assertions it
//! states, the design and environment every verdict is of.

use super::*;

/// What a proof assumes of the unit's environment, in words: the harness's assumptions, the only
/// ones kept (the unit's own are removed before any step). `pipelining`: `prove --pipelining`'s
/// miter, which assumes nothing.
pub fn environment(pipelining: bool) -> &'static str {
    if pipelining {
        "nothing: every input free at every edge, from power-up and from any state"
    } else {
        "only the environment's: the first clock edge resets the unit (AXI: a stream starts in reset), every input free at every edge after it; the unit's own assume statements are removed"
    }
}

/// What every verdict is of, in words: the design built, shown equal to the one proved.
pub const OF_THE_BUILT: &str =
    "of the design synthesis builds: the unit as every step reads it (FORMAL and one set of macros) is proved equal to the RTL as synthesis reads it at every port bit before any step";

/// The unit's data outputs as the adapter joins them (`f_out_ports`, the first port's bits
/// highest): their width, and the bits among them that carry no field (`m_axis_tdata`'s
/// padding), as (highest, lowest) ranges.
pub(super) fn raw_outputs(cfg: &crate::config::Config) -> (u32, Vec<(u32, u32)>) {
    let data: Vec<_> = cfg
        .ports("")
        .into_iter()
        .filter(|p| {
            p.direction == "output"
                && crate::ports::port_rule(p.name) == Some(crate::ports::PortRule::Data)
        })
        .collect();
    let width: u32 = data.iter().map(|p| p.width).sum();
    let mut padding = Vec::new();
    let mut above = 0;
    for p in &data {
        above += p.width;
        let lo = width - above;
        padding.extend(
            crate::ports::padding(cfg.port_widths(), p.name)
                .into_iter()
                .map(|(h, l)| (h + lo, l + lo)),
        );
    }
    (width, padding)
}

/// `assert(` statements in Verilog text (outside comments).
fn assertions_in(text: &str) -> usize {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .map(|l| l.matches("assert(").count() + l.matches("assert (").count())
        .sum()
}

/// Whether the unit states the assertions specgen writes for its configuration: as many
/// `assert` statements in its Verilog as in the files generated from its manifest (an edited
/// RTL with some deleted states less than the list `prove` prints, so its induction proves
/// nothing that list could be trusted for).
pub(super) fn states_its_own_assertions(design: &Design) -> Result<bool, Error> {
    let mut count = 0;
    for src in &design.sources {
        let text = crate::small_file::read(src, crate::small_file::UNIT_FILE_MAX)
            .map_err(|e| error::input(format!("{} {e}", src.display())))?;
        count += assertions_in(&text);
    }
    let written: usize = crate::emit::generate_files(&design.plan)
        .iter()
        .filter(|(name, _)| name.ends_with(".v"))
        .map(|(_, bytes)| assertions_in(&String::from_utf8_lossy(bytes)))
        .sum();
    Ok(count > 0 && count >= written)
}
