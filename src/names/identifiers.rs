//! The names a unit may not take: Verilog and SystemVerilog keywords, the unit's ports and
//! internal names, the tools' own modules and cells, and the modules a unit derives from its top.

use crate::error::Error;

/// SystemVerilog's keywords (IEEE 1800-2017 Annex B) beyond Verilog-2005's: tools read the
/// unit as SystemVerilog too (Verilator, FuseSoC's sim targets), so none may name it.
pub(crate) const SYSTEMVERILOG_KEYWORDS: &[&str] = &[
    "accept_on",
    "alias",
    "always_comb",
    "always_ff",
    "always_latch",
    "assert",
    "assume",
    "before",
    "bind",
    "bins",
    "binsof",
    "bit",
    "break",
    "byte",
    "chandle",
    "checker",
    "class",
    "clocking",
    "const",
    "constraint",
    "context",
    "continue",
    "cover",
    "covergroup",
    "coverpoint",
    "cross",
    "dist",
    "do",
    "endchecker",
    "endclass",
    "endclocking",
    "endgroup",
    "endinterface",
    "endpackage",
    "endprogram",
    "endproperty",
    "endsequence",
    "enum",
    "eventually",
    "expect",
    "export",
    "extends",
    "extern",
    "final",
    "first_match",
    "foreach",
    "forkjoin",
    "global",
    "iff",
    "ignore_bins",
    "illegal_bins",
    "implements",
    "implies",
    "import",
    "inside",
    "int",
    "interconnect",
    "interface",
    "intersect",
    "join_any",
    "join_none",
    "let",
    "local",
    "logic",
    "longint",
    "matches",
    "modport",
    "nettype",
    "new",
    "nexttime",
    "null",
    "package",
    "packed",
    "priority",
    "program",
    "property",
    "protected",
    "pure",
    "rand",
    "randc",
    "randcase",
    "randsequence",
    "ref",
    "reject_on",
    "restrict",
    "return",
    "s_always",
    "s_eventually",
    "s_nexttime",
    "s_until",
    "s_until_with",
    "sequence",
    "shortint",
    "shortreal",
    "soft",
    "solve",
    "static",
    "string",
    "strong",
    "struct",
    "super",
    "sync_accept_on",
    "sync_reject_on",
    "tagged",
    "this",
    "throughout",
    "timeprecision",
    "timeunit",
    "type",
    "typedef",
    "union",
    "unique",
    "unique0",
    "until",
    "until_with",
    "untyped",
    "var",
    "virtual",
    "void",
    "wait_order",
    "weak",
    "with",
    "within",
];

/// Modules the tools specgen runs the unit with already define: the harnesses' tops and the
/// FPGA primitives a unit instantiates or synthesizes to.
pub(crate) const TOOL_MODULES: &[&str] = &[
    "specgen_cosim_top",
    "specgen_icarus_bench",
    "specgen_synth_top",
    "MULT18X18D",
    "DP16KD",
    "SB_MAC16",
    "SB_RAM40_4K",
    "SB_LUT4",
    "SB_CARRY",
    "SB_DFF",
];

/// Every module of yosys's iCE40, ECP5 and Gowin cell libraries, 0.23 and 0.70 (`data/cell_names.txt`).
pub(crate) const CELL_NAMES: &str = include_str!("../../data/cell_names.txt");

/// The modules a unit derives from its top (`<top>_out_buffer`, …): a top ending so could be
/// another unit's derived module.
pub(crate) const DERIVED_SUFFIXES: &[&str] = &[
    "_out_buffer",
    "_mult18x18",
    "_rom1k18",
    "_delay_ram",
    "_tb",
    "_tb_ports",
];

pub(crate) const VERILOG_KEYWORDS: &[&str] = &[
    "always",
    "and",
    "assign",
    "automatic",
    "begin",
    "buf",
    "bufif0",
    "bufif1",
    "case",
    "casex",
    "casez",
    "cell",
    "cmos",
    "config",
    "deassign",
    "default",
    "defparam",
    "design",
    "disable",
    "edge",
    "else",
    "end",
    "endcase",
    "endconfig",
    "endfunction",
    "endgenerate",
    "endmodule",
    "endprimitive",
    "endspecify",
    "endtable",
    "endtask",
    "event",
    "for",
    "force",
    "forever",
    "fork",
    "function",
    "generate",
    "genvar",
    "highz0",
    "highz1",
    "if",
    "ifnone",
    "incdir",
    "include",
    "initial",
    "inout",
    "input",
    "instance",
    "integer",
    "join",
    "large",
    "liblist",
    "library",
    "localparam",
    "macromodule",
    "medium",
    "module",
    "nand",
    "negedge",
    "nmos",
    "nor",
    "noshowcancelled",
    "not",
    "notif0",
    "notif1",
    "or",
    "output",
    "parameter",
    "pmos",
    "posedge",
    "primitive",
    "pull0",
    "pull1",
    "pulldown",
    "pullup",
    "pulsestyle_ondetect",
    "pulsestyle_onevent",
    "rcmos",
    "real",
    "realtime",
    "reg",
    "release",
    "repeat",
    "rnmos",
    "rpmos",
    "rtran",
    "rtranif0",
    "rtranif1",
    "scalared",
    "showcancelled",
    "signed",
    "small",
    "specify",
    "specparam",
    "strong0",
    "strong1",
    "supply0",
    "supply1",
    "table",
    "task",
    "time",
    "tran",
    "tranif0",
    "tranif1",
    "tri",
    "tri0",
    "tri1",
    "triand",
    "trior",
    "trireg",
    "unsigned",
    "use",
    "uwire",
    "vectored",
    "wait",
    "wand",
    "weak0",
    "weak1",
    "while",
    "wire",
    "wor",
    "xnor",
    "xor",
    // SystemVerilog keywords a user's flow may parse the file as, and C++ names Verilator uses.
    "logic",
    "bit",
    "byte",
    "int",
    "shortint",
    "longint",
    "interface",
    "package",
    "class",
];

/// The unit's ports, and the shapes of its internal names: `x_sK` (a step's wire), `x_cK` (a
/// cut), every delay line (`*_line`), the tables and their file handles, `unused_*`. A module named like one
/// of them would be hidden by it inside the module (Verilator VARHIDDEN).
pub fn is_internal_name(name: &str) -> bool {
    const TABLES: &[&str] = &["cos_sp_rom", "fit_rom", "log2_rom", "exp2_rom", "recip_rom"];
    let step_or_cut = name.rsplit_once('_').is_some_and(|(_, tail)| {
        tail.len() > 1
            && (tail.starts_with('s') || tail.starts_with('c'))
            && tail[1..].bytes().all(|b| b.is_ascii_digit())
    });
    crate::ports::NAMES.contains(&name)
        || TABLES.contains(&name)
        || step_or_cut
        || name.starts_with("unused_")
        || name.ends_with("_fd")
        || name.ends_with("_FILE")
        || name.ends_with("_line")
        || name.contains("_line_")
        || TABLES.iter().any(|t| {
            name.strip_prefix(t)
                .is_some_and(|r| r == "_sum" || r == "_i")
        })
        || INTERNAL_NAMES.contains(&name)
}

/// The handshake's, tag's and material registers' own names inside the unit.
pub(crate) const INTERNAL_NAMES: &[&str] = &[
    "in_take",
    "out_result",
    "out_held",
    "out_buffer",
    "tag_line",
    "ks_r_material",
    "ks_g_material",
    "ks_b_material",
    "result_valid",
    "idle_q",
    "inside_up",
    "inside_down",
    "inside_less_one",
];

/// `clock_port`: a port name of the user's design, written into SDC and LPF files: a Verilog
/// identifier of at most 64 characters (no escaped names: the files quote nothing else).
pub(crate) fn check_port_name(port: &str) -> Result<(), Error> {
    let ok = port.len() <= 64
        && port
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && port.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    match ok {
        true => Ok(()),
        false => Err(Error::Config {
            parameter: "clock_port",
            message: format!("{port:?} is not a port name; allowed: a Verilog identifier [A-Za-z_][A-Za-z0-9_]* of at most 64 characters"),
        }),
    }
}

/// `--top`: a legal Verilog-2005 simple identifier, not a keyword, and so never a path.
pub(crate) fn check_identifier(top: &str) -> Result<(), Error> {
    let err = |why: &str| {
        Error::Config {
        parameter: "top",
        message: format!(
            "{top:?} {why}; allowed: a Verilog identifier [A-Za-z_][A-Za-z0-9_]* of at most 64 characters, not a keyword, not a port or internal name"
        ),
    }
    };
    let mut chars = top.chars();
    match chars.next() {
        None => return Err(err("is empty")),
        Some(c) if !(c.is_ascii_alphabetic() || c == '_') => {
            return Err(err("does not start with a letter or underscore"))
        }
        _ => {}
    }
    if !chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(err(
            "contains a character other than letters, digits and underscore",
        ));
    }
    if top.len() > 64 {
        return Err(err("is too long"));
    }
    if VERILOG_KEYWORDS.contains(&top) || SYSTEMVERILOG_KEYWORDS.contains(&top) {
        return Err(err("is a reserved word"));
    }
    if is_internal_name(top) {
        return Err(err(
            "is the name of a port or an internal signal of the unit",
        ));
    }
    if TOOL_MODULES.contains(&top) || CELL_NAMES.lines().any(|l| !l.starts_with('#') && l == top) {
        return Err(err("is a module the simulation or synthesis tools already define (a cell of an FPGA family's library)"));
    }
    if let Some(suffix) = DERIVED_SUFFIXES.iter().find(|s| top.ends_with(*s)) {
        return Err(err(&format!(
            "ends with {suffix}, the name of a module every unit derives from its top (<top>{suffix}): another unit's would be defined twice"
        )));
    }
    Ok(())
}
