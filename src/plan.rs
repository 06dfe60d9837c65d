//! The plan of one command: a validated configuration, its model (fit or tables made once),
//! the registers placed, and the datapath they give — built once, and taken by everything
//! downstream (the RTL, the tables, the golden model, the manifest).
//!
//! This is also where `--stages` is bounded: by the cut points of this configuration's own
//! datapath, which only exists once the model is made; and where the registers are placed
//! ([`balanced_cuts`]) from the datapath's per-step delay estimates.

use crate::config::{Colour, Config, Params};
use crate::datapath::{Builder, Datapath, ProductUse};
use crate::error::Error;
use crate::models::Model;
use std::collections::BTreeSet;
use std::sync::Arc;

/// The signals every model's datapath defines, read by the output ports.
pub const OUTPUT_SIGNALS: [&str; 5] = ["spec_r", "spec_g", "spec_b", "intensity", "done"];

#[derive(Debug, Clone)]
pub struct Plan {
    pub cfg: Config,
    pub(crate) model: Model,
    /// The cuts that hold a pipeline register, 1-based step numbers (empty: combinational).
    pub registered_cuts: Vec<u32>,
    pub datapath: Datapath,
    /// the most `--stages` this configuration takes
    pub cut_points: u32,
    /// What every depth of this configuration shares: planned once, read by `with_stages`.
    shape: Arc<Shape>,
}

/// The depth-free part of a plan: the combinational datapath (the delays the registers are
/// placed by) and the products `--dsp-budget` puts in the fabric.
#[derive(Debug)]
struct Shape {
    combinational: Datapath,
    fabric: BTreeSet<String>,
}

thread_local! {
    /// Datapaths built on this thread ([`datapath_builds`]).
    static BUILDS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// How many datapaths this thread has built: the work of planning, which a test holds to a
/// bound (a depth search builds each depth once, and the shared shape once).
#[doc(hidden)]
pub fn datapath_builds() -> u64 {
    BUILDS.with(|b| b.get())
}

/// The model's datapath with registers at `registered` cuts, the products named in `fabric`
/// summed in the fabric.
fn build(model: &Model, registered: &[u32], fabric: &BTreeSet<String>) -> Datapath {
    BUILDS.with(|b| b.set(b.get() + 1));
    let cfg = &model.cfg;
    let inputs = [
        ("cos_g", cfg.f() + 1),
        ("n", cfg.n_bits()),
        ("ks_r", cfg.b()),
        ("ks_g", cfg.b()),
        ("ks_b", cfg.b()),
    ];
    let mut b = Builder::new(&inputs, registered, cfg.target());
    b.in_fabric(fabric);
    let logic = cfg.params.rom_style == crate::config::RomStyle::Logic;
    b.tables_in_logic(logic);
    b.registers_in_fabric(cfg.params.fabric_registers || logic);
    if cfg.colour() == Colour::Static {
        for ch in crate::ports::CHANNELS {
            b.hold(&format!("ks_{ch}"), &format!("ks_{ch}_material"));
        }
    }
    if cfg.params.fabric_registers {
        // the ports into flip-flops first: the step after them reads no port's long route (an
        // input bit that fans out to every bit of the clamp, schlick on the UP5K at 117 MHz)
        b.fabric_register_step("the ports registered");
    }
    model.unit().datapath(&mut b);
    b.finish(&OUTPUT_SIGNALS)
}

impl Plan {
    pub fn new(cfg: Config) -> Result<Plan, Error> {
        Plan::for_model(Model::new(&cfg))
    }

    /// The plan of a model already made (its configuration's `stages` placed).
    pub(crate) fn for_model(model: Model) -> Result<Plan, Error> {
        let cfg = model.cfg.clone();
        if cfg.params.rom_style == crate::config::RomStyle::Logic
            && !crate::family::of(cfg.target()).writes_logic_tables()
        {
            let takers: Vec<&str> = crate::config::Target::ALL
                .into_iter()
                .filter(|t| crate::family::of(*t).writes_logic_tables())
                .map(|t| t.name())
                .collect();
            return Err(Error::Config {
                parameter: "rom_style",
                message: format!(
                    "logic is not written for {} {} on {}: that family's tables stay where its synthesis puts them; allowed there: file, case (logic: --target {})",
                    cfg.model().name(),
                    cfg.arch().name(),
                    cfg.target().name(),
                    takers.join(" or ")
                ),
            });
        }
        let mut combinational = build(&model, &[], &BTreeSet::new());
        let fabric = match cfg.params.dsp_budget {
            Some(budget) => to_fabric(&combinational.product_uses, budget),
            None => BTreeSet::new(),
        };
        if !fabric.is_empty() {
            combinational = build(&model, &[], &fabric);
        }
        Plan::placed(
            model,
            Arc::new(Shape {
                combinational,
                fabric,
            }),
        )
    }

    /// The plan of `model` at its configuration's depth, over a shape already planned.
    fn placed(model: Model, shape: Arc<Shape>) -> Result<Plan, Error> {
        let cfg = model.cfg.clone();
        let combinational = &shape.combinational;
        let cut_points = combinational.steps.len() as u32;
        if cfg.stages() > cut_points {
            return Err(Error::Config {
                parameter: "stages",
                message: format!(
                    "{} is out of range; allowed 0..={cut_points} (the cut points of the {} datapath with these widths on the {} target)",
                    cfg.stages(),
                    cfg.datapath_name(),
                    cfg.target().name()
                ),
            });
        }
        // with products in the fabric, the registers are placed by the measure stage_delay
        // reports (a hard-block step alone between registers counts nothing): else a block
        // RAM's long step sets the length of every fabric stretch (a lean at --dsp-budget 3, 28
        // stages: five carry-save layers in one stretch, 64 MHz in a pair on the UP5K)
        let registered_cuts = match shape.fabric.is_empty() {
            true => balanced_cuts(&combinational.delays(), cfg.stages()),
            false => balanced_cuts_by(
                &combinational.delays(),
                &hard_steps(combinational),
                cfg.stages(),
            ),
        };
        let datapath = if cfg.stages() == 0 {
            combinational.clone()
        } else {
            build(&model, &registered_cuts, &shape.fabric)
        };
        Ok(Plan {
            cfg,
            model,
            registered_cuts,
            datapath,
            cut_points,
            shape,
        })
    }

    pub fn from_params(params: Params) -> Result<Plan, Error> {
        Plan::new(Config::new(params)?)
    }

    /// The same configuration at another depth, the model reused (its fit or tables are not
    /// made again) and the depth-free shape too (the combinational datapath is not built
    /// again): one datapath built a depth, none at depth 0.
    pub fn with_stages(&self, stages: u32) -> Result<Plan, Error> {
        let cfg = Config::new(Params {
            stages,
            ..self.cfg.params.clone()
        })?;
        let model = self.model.with_config(cfg);
        Plan::placed(model, Arc::clone(&self.shape))
    }

    /// The golden model of this plan.
    pub fn model(&self) -> Model {
        self.model.clone()
    }

    /// The slowest stretch of logic between two registers (or between the ports and a
    /// register), by the datapath's per-step delay estimates: what the delay model of
    /// `--target-mhz` (`timing`) turns into a clock. A stretch that is one hard-block step
    /// alone (a product, a table read) counts nothing: with a register on each side the block
    /// uses its own input and output registers and runs as fast as the block itself does (the
    /// family's cap).
    pub fn stage_delay(&self) -> f64 {
        self.stage_delay_by(|d| d.ns)
    }

    /// [`Plan::stage_delay`] on a family of primitive delays `w` (each step's primitives
    /// weighed by the family's own delays: what the delay model reads).
    pub fn stage_delay_on(&self, w: &crate::family::PrimitiveDelays) -> f64 {
        self.stage_delay_by(|d| d.on(w))
    }

    fn stage_delay_by(&self, ns: impl Fn(&crate::datapath::Delay) -> f64) -> f64 {
        let dp = &self.datapath;
        let mut edges = vec![0usize];
        edges.extend(
            self.registered_cuts
                .iter()
                .map(|&c| (c as usize).min(dp.steps.len())),
        );
        edges.push(dp.steps.len());
        let hard = hard_steps(dp);
        edges
            .windows(2)
            .map(|e| match e[1].saturating_sub(e[0]) {
                1 if hard[e[0]] => 0.0,
                _ => dp.steps[e[0]..e[1].max(e[0])]
                    .iter()
                    .map(|s| ns(&s.delay))
                    .sum::<f64>(),
            })
            .fold(0.0, f64::max)
    }

    /// The longest step no register splits (a hard-block step alone counts nothing, as in
    /// [`Plan::stage_delay`]), read from the shape every depth shares: no datapath is built.
    pub(crate) fn longest_step(&self) -> f64 {
        let dp = &self.shape.combinational;
        let hard = hard_steps(dp);
        dp.steps
            .iter()
            .zip(hard)
            .map(|(s, h)| if h { 0.0 } else { s.delay.ns })
            .fold(0.0, f64::max)
    }

    /// The mean stretch of logic between registers: the datapath's whole delay estimate over
    /// the `stages + 1` stretches the registers cut it into. With `stage_delay` it is what the
    /// delay model reads: once one step that no register can split is the slowest stretch, the
    /// clock still rises as the others shorten (less logic and routing around each register).
    pub fn stage_delay_mean(&self) -> f64 {
        self.stage_delay_mean_by(|d| d.ns)
    }

    /// [`Plan::stage_delay_mean`] on a family of primitive delays `w`.
    pub fn stage_delay_mean_on(&self, w: &crate::family::PrimitiveDelays) -> f64 {
        self.stage_delay_mean_by(|d| d.on(w))
    }

    fn stage_delay_mean_by(&self, ns: impl Fn(&crate::datapath::Delay) -> f64) -> f64 {
        self.datapath
            .steps
            .iter()
            .map(|s| ns(&s.delay))
            .sum::<f64>()
            / (self.registered_cuts.len() + 1) as f64
    }
}

/// The products `--dsp-budget` puts in the fabric: those whose blocks the budget does not
/// hold, chosen so that the logic they cost is least. Each product's cost in the fabric is its
/// partial products' bits (the narrower operand's bits times the bits kept); the products
/// kept on blocks are the most costly set whose blocks fit the budget (a 0/1 knapsack over
/// the blocks, exact; ties keep the product made first). A product of no block (too small
/// for one) stays as it is.
pub(crate) fn to_fabric(uses: &[ProductUse], budget: u32) -> BTreeSet<String> {
    let hard: Vec<&ProductUse> = uses.iter().filter(|u| u.blocks > 0).collect();
    let cost = |u: &ProductUse| u.a.min(u.b) as u64 * u.width as u64;
    let cap = budget as usize;
    // best[i][c]: the most cost products i.. keep within c blocks
    let mut best = vec![vec![0u64; cap + 1]; hard.len() + 1];
    for i in (0..hard.len()).rev() {
        let (w, v) = (hard[i].blocks as usize, cost(hard[i]));
        for c in 0..=cap {
            let skip = best[i + 1][c];
            best[i][c] = if w <= c {
                skip.max(v + best[i + 1][c - w])
            } else {
                skip
            };
        }
    }
    let mut out = BTreeSet::new();
    let mut c = cap;
    for (i, u) in hard.iter().enumerate() {
        let w = u.blocks as usize;
        if w <= c && best[i][c] == cost(u) + best[i + 1][c - w] {
            c -= w;
        } else {
            out.insert(u.name.clone());
        }
    }
    out
}

/// Per step, whether it is a hard block's (iCE40: a `*` that becomes an SB_MAC16, a table read
/// that becomes an SB_RAM40_4K; ECP5: the MULT18X18D and DP16KD instances with their own
/// registers; `RomRead::step` is the 1-based step number; a product too small for the block is
/// LUTs: logic).
fn hard_steps(dp: &Datapath) -> Vec<bool> {
    (0..dp.steps.len())
        .map(|k| {
            let s = &dp.steps[k];
            !s.soft_product
                && (!s.dsps.is_empty()
                    || s.wires.iter().any(|w| w.product().is_some())
                    || dp.reads.iter().any(|r| r.step == k + 1))
        })
        .collect()
}

/// Places `stages` registers after steps (1-based) so that the slowest stretch of logic
/// between registers (inputs and outputs count as registered outside) is as short as
/// possible; ties go to the placement closest to the outputs. Exact: the least bound any
/// placement reaches (over the segment sums), then each cut as late as the bound allows.
pub(crate) fn balanced_cuts(delays: &[f64], stages: u32) -> Vec<u32> {
    balanced_cuts_by(delays, &vec![false; delays.len()], stages)
}

/// [`balanced_cuts`], a stretch that is one `hard` step alone counting nothing (as
/// `Plan::stage_delay` counts it). Every stretch inside another still costs no more than it,
/// so the greedy bound below stays exact.
pub(crate) fn balanced_cuts_by(delays: &[f64], hard: &[bool], stages: u32) -> Vec<u32> {
    const TIE: f64 = 1e-9;
    let c = delays.len();
    let s = (stages as usize).min(c);
    if s == 0 {
        return Vec::new();
    }
    let seg = |a: usize, b: usize| {
        if b == a + 1 && hard[a] {
            0.0
        } else {
            delays[a..b].iter().sum::<f64>()
        }
    };
    // the fewest cuts after an edge at `v` that keep every segment up to the end within `w`
    // (greedy: each segment as long as it may be); None when one step alone exceeds `w`
    let need = |v: usize, w: f64| -> Option<usize> {
        let (mut count, mut start) = (0, v);
        while seg(start, c) > w + TIE {
            let mut e = start;
            while e < c && seg(start, e + 1) <= w + TIE {
                e += 1;
            }
            if e == start {
                return None;
            }
            count += 1;
            start = e;
        }
        Some(count)
    };
    // the least worst step: the smallest segment sum that s cuts can keep every segment within
    let mut sums: Vec<f64> = (0..c)
        .flat_map(|a| (a + 1..=c).map(move |b| (a, b)))
        .map(|(a, b)| seg(a, b))
        .collect();
    sums.push(0.0);
    sums.sort_by(f64::total_cmp);
    let best = *sums
        .iter()
        .find(|&&w| need(0, w).is_some_and(|m| m <= s))
        .expect("c cuts always do");
    // among the cuts that reach it, the latest first, then the latest second, ...
    let (mut cuts, mut prev) = (Vec::with_capacity(s), 0usize);
    for i in 0..s {
        let after = s - i - 1;
        let v = (prev + 1..=c - after)
            .rev()
            .find(|&v| seg(prev, v) <= best + TIE && need(v, best).is_some_and(|m| m <= after))
            .expect("a cut that keeps the bound exists");
        cuts.push(v as u32);
        prev = v;
    }
    cuts
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod budget_tests;
