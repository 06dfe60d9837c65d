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
mod tests {
    use super::*;

    /// C's clamp and ~c (the operand of 1 − c) are made in different steps, from
    /// different registers of cos: in one step the integer bit of cos drove both words and a
    /// synthesis tool shared c's LUTs for ~c, so c's flip-flops took them over a route of
    /// their own (schlick at 117.1 MHz on the UP5K).
    #[test]
    fn the_clamp_and_the_operand_of_one_minus_c_are_apart() {
        use crate::config::Target;
        for target in [Target::Ice40, Target::Ecp5, Target::Generic] {
            let cfg = crate::config::Config::new(crate::config::Params {
                model: crate::config::SpecularModel::Schlick,
                target,
                ..Default::default()
            })
            .unwrap();
            let plan = Plan::new(cfg).unwrap();
            let step_of = |name: &str| {
                plan.datapath
                    .steps
                    .iter()
                    .position(|s| s.wires.iter().any(|w| w.name == name))
                    .unwrap()
            };
            assert_eq!(
                step_of("cos_clamped"),
                step_of("cos_comp") + 1,
                "{target:?}"
            );
        }
    }

    use crate::config::SpecularModel;

    #[test]
    fn validation_builds_nothing_and_the_plan_bounds_stages() {
        // a configuration is valid without its datapath; the plan knows the cut points
        let cfg = Config::new(Params {
            stages: 99,
            ..Params::default()
        })
        .expect("stages are the plan's to check");
        let e = Plan::new(cfg).unwrap_err();
        assert_eq!(e.parameter(), Some("stages"));
        assert!(e.reason().contains("allowed 0..=13"), "{}", e.reason());
        for model in SpecularModel::ALL {
            let top = Plan::from_params(Params {
                model,
                stages: 0,
                n_bits: 6,
                ..Params::default()
            })
            .unwrap()
            .cut_points;
            let plan = Plan::from_params(Params {
                model,
                stages: top,
                n_bits: 6,
                ..Params::default()
            })
            .unwrap();
            // every cut registered; the same plan when the model is reused
            assert_eq!(
                plan.registered_cuts,
                (1..=top).collect::<Vec<_>>(),
                "{model:?}"
            );
            assert_eq!(plan.datapath.steps.len() as u32, top);
            let again = Plan::from_params(Params {
                model,
                stages: 0,
                n_bits: 6,
                ..Params::default()
            })
            .unwrap()
            .with_stages(top)
            .unwrap();
            assert_eq!(again.registered_cuts, plan.registered_cuts);
        }
    }

    /// On the iCE40 no step holds two carry-save layers (a function of up to 9
    /// registers, three LUT levels on yosys 0.70), and fitted's lo^2 tables read at most a
    /// LUT's inputs (a table of 5 bits was two LUT levels: fitted 96.2 MHz on yosys 0.23).
    #[test]
    fn ice40_steps_hold_one_carry_save_layer_and_one_lut_tables() {
        use crate::datapath::LUT_INPUTS;
        for model in [SpecularModel::Fitted, SpecularModel::Blinn] {
            let plan = Plan::from_params(Params {
                model,
                ..Params::default()
            })
            .unwrap();
            let mut layers = 0;
            for step in &plan.datapath.steps {
                let mut seen: Vec<&str> = step
                    .wires
                    .iter()
                    .filter_map(|w| w.name.split("_csa").nth(1))
                    .map(|t| t.split('_').next().unwrap())
                    .collect();
                seen.dedup();
                assert!(
                    seen.len() <= 1,
                    "{model:?} step {} ({}): carry-save layers {seen:?}",
                    step.index,
                    step.title
                );
                layers += seen.len();
                for w in step.wires.iter().filter(|w| w.name.ends_with("_ll")) {
                    assert!(
                        w.width <= 2 * LUT_INPUTS,
                        "{model:?} {}: a square table of {} bits",
                        w.name,
                        w.width / 2
                    );
                }
            }
            assert!(
                layers >= 2,
                "{model:?}: carry-save sums exist ({layers} layers)"
            );
        }
        let plan = Plan::from_params(Params {
            model: SpecularModel::Fitted,
            ..Params::default()
        })
        .unwrap();
        assert!(
            plan.datapath
                .steps
                .iter()
                .flat_map(|s| &s.wires)
                .any(|w| w.name == "square1_t_top"),
            "lo's top bit split off the table"
        );
    }

    #[test]
    fn cuts_are_distinct_increasing_and_in_range() {
        let plan = Plan::new(Config::defaults()).unwrap();
        let delays = plan.datapath.delays();
        let c = plan.cut_points;
        assert_eq!(delays.len(), c as usize);
        for s in 0..=c {
            let cuts = balanced_cuts(&delays, s);
            assert_eq!(cuts.len(), s as usize);
            assert!(cuts.windows(2).all(|w| w[0] < w[1]), "{cuts:?}");
            assert!(cuts.iter().all(|&x| (1..=c).contains(&x)));
        }
        assert_eq!(balanced_cuts(&delays, c), (1..=c).collect::<Vec<_>>());
    }

    #[test]
    fn balancing_splits_the_heaviest_step_off() {
        // one heavy step in the middle: a single register goes right next to it
        let d = [1.0, 1.0, 10.0, 1.0, 1.0];
        assert_eq!(balanced_cuts(&d, 1), vec![3]);
        assert_eq!(balanced_cuts(&d, 2), vec![2, 3]);
        // uniform steps: registers evenly spaced
        assert_eq!(balanced_cuts(&[1.0; 6], 2), vec![2, 4]);
    }

    /// Every placement tried: the slowest stretch, least; ties to the latest cuts.
    fn balanced_cuts_by_search(delays: &[f64], s: usize) -> Vec<u32> {
        let c = delays.len();
        let worst = |cuts: &[usize]| {
            let mut edges = vec![0usize];
            edges.extend(cuts.iter().copied());
            edges.push(c);
            edges
                .windows(2)
                .map(|e| delays[e[0]..e[1]].iter().sum::<f64>())
                .fold(0.0f64, f64::max)
        };
        let mut best: Option<(f64, Vec<usize>)> = None;
        for mask in 0u32..(1 << c) {
            if mask.count_ones() as usize != s {
                continue;
            }
            let pick: Vec<usize> = (0..c)
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| i + 1)
                .collect();
            let w = worst(&pick);
            let better = match &best {
                None => true,
                Some((bw, bc)) => w < *bw - 1e-9 || ((w - *bw).abs() <= 1e-9 && pick > *bc),
            };
            if better {
                best = Some((w, pick));
            }
        }
        best.map(|(_, p)| p.into_iter().map(|x| x as u32).collect())
            .unwrap_or_default()
    }

    /// No product the synthesis tool maps takes a constant operand its family mis-maps
    /// (`Family::takes_constant`: on the iCE40, yosys 0.23 drops the top bits of a 16-bit
    /// constant of 0xC000 or more), over k_q's below, between and above that (0.6 and 0.7 are
    /// 0x9999 and 0xB333, taken whole), both KF's, both datapaths that multiply by k_q, every
    /// target and depth. It fails where such a constant reaches a product whole (the lean unit at
    /// `--k 0.95` wrote `n * 16'hf333`), and where a constant that maps right is split anyway.
    #[test]
    fn no_mapped_product_takes_a_constant_its_family_mis_maps() {
        use crate::config::{Arch, Target};
        let narrow = Params {
            cos_frac_bits: 8,
            n_bits: 6,
            color_bits: 4,
            intensity_frac_bits: 8,
            ..Params::default()
        };
        let (mut checked, mut split) = (0, 0);
        // the hazard itself, apart from the family's rule: a 16-bit slice of 0xC000 or more
        let mis_mapped = |x: u128| (0..8).any(|i| (x >> (16 * i)) & 0xffff >= 0xc000);
        for target in Target::ALL {
            for arch in [Arch::Lean, Arch::Paper] {
                for k in ["0.3686", "0.6", "0.7", "0.8", "0.95", "0.99"] {
                    for (kf, base) in [(16, Params::default()), (20, narrow.clone())] {
                        let params = Params {
                            target,
                            arch,
                            k: k.into(),
                            k_frac_bits: kf,
                            stages: 0,
                            ..base
                        };
                        let top = Plan::from_params(params.clone()).unwrap().cut_points;
                        for stages in [0, top] {
                            let plan = Plan::from_params(Params {
                                stages,
                                ..params.clone()
                            })
                            .unwrap();
                            let k_code = plan.cfg.k_code as u128;
                            for w in plan
                                .datapath
                                .steps
                                .iter()
                                .flat_map(|s| &s.wires)
                                .filter(|w| w.product().is_some())
                            {
                                // the operands of `a * b`: a literal one is `W'hX`
                                let text = w.expr.text.split(" + ").next().unwrap();
                                for operand in text.split(" * ") {
                                    let operand = operand.trim();
                                    if let Some((_, hex)) = operand
                                        .split_once("'h")
                                        .filter(|_| !operand.starts_with('{'))
                                    {
                                        let value = u128::from_str_radix(hex, 16).unwrap();
                                        // no SB_MAC16 takes a constant with such a slice
                                        let at = format!(
                                            "{target:?} {arch:?} k={k} KF={kf} {stages}: {} = {}",
                                            w.name, w.expr.text
                                        );
                                        assert!(
                                            !(target == Target::Ice40 && mis_mapped(value)),
                                            "{at}"
                                        );
                                        // k_q is split only where it must be: wider than the
                                        // block (lean), or a hazard on the iCE40
                                        let must = (target == Target::Ice40 && mis_mapped(k_code))
                                            || (arch == Arch::Lean
                                                && 128 - k_code.leading_zeros()
                                                    > crate::family::of(target).multiplier_bits());
                                        assert_eq!(value != k_code, must, "{at}");
                                        split += (value != k_code) as usize;
                                        checked += 1;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        assert!(
            checked > 50 && split > 0,
            "{checked} constant operands, {split} of them a split k_q"
        );
    }

    #[test]
    fn balancing_equals_the_search_over_every_placement() {
        let mut r = 7u64;
        for _ in 0..300 {
            r = crate::bits::splitmix(r);
            let c = 1 + (r % 11) as usize;
            let delays: Vec<f64> = (0..c)
                .map(|i| {
                    let v = crate::bits::splitmix(r ^ i as u64);
                    // a few distinct values, so ties happen
                    [0.0, 2.7, 3.4, 5.5, 8.1][(v % 5) as usize]
                })
                .collect();
            for s in 0..=c {
                assert_eq!(
                    balanced_cuts(&delays, s as u32),
                    balanced_cuts_by_search(&delays, s),
                    "{delays:?} with {s} cuts"
                );
            }
        }
        // and a long datapath in no time (the search would take 2^43 placements)
        assert_eq!(balanced_cuts(&[2.7; 43], 43).len(), 43);
    }
    /// A wire's kind and reads are data the builder recorded as it made the operands,
    /// never read back from the Verilog. Checked here against the text, over every model, family,
    /// width, depth and budget: the reads are exactly the signal names the text holds; a select
    /// is no more than bits and braces (a multi-line concatenation included: the old text rule
    /// missed it, and left registers a block reads through one without their `keep`); a
    /// product, and only a product, multiplies.
    #[test]
    fn every_wire_is_typed_as_its_text_reads() {
        use crate::config::{Arch, SpecularModel, Target};
        use crate::datapath::Kind;
        let narrow = Params {
            cos_frac_bits: 8,
            n_bits: 6,
            color_bits: 4,
            intensity_frac_bits: 8,
            ..Params::default()
        };
        let mut checked = 0;
        for model in SpecularModel::ALL {
            for target in Target::ALL {
                let logic = Params {
                    rom_style: crate::config::RomStyle::Logic,
                    ..narrow.clone()
                };
                let shapes = [
                    (Params::default(), Arch::Lean),
                    (narrow.clone(), Arch::Lean),
                    (Params::default(), Arch::Paper),
                    (logic, Arch::Lean),
                ];
                for (base, arch) in shapes {
                    if arch == Arch::Paper && model != SpecularModel::Quadratic {
                        continue;
                    }
                    // a table as logic: the lean datapaths with tables, on the ECP5 only
                    if base.rom_style == crate::config::RomStyle::Logic
                        && !(model.takes("rom_style=logic") && target == Target::Ecp5)
                    {
                        continue;
                    }
                    for budget in [None, Some(1)] {
                        let params = Params {
                            model,
                            target,
                            arch,
                            dsp_budget: budget,
                            stages: 0,
                            ..base.clone()
                        };
                        let top = Plan::from_params(params.clone()).unwrap().cut_points;
                        for stages in [0, 1, top / 2, top] {
                            let plan = Plan::from_params(Params {
                                stages,
                                ..params.clone()
                            })
                            .unwrap();
                            let dp = &plan.datapath;
                            // every name a step, an output or the lint sink reads
                            let names: std::collections::BTreeSet<&str> =
                                dp.read.keys().map(String::as_str).collect();
                            for s in &dp.steps {
                                for w in &s.wires {
                                    let text = &w.expr.text;
                                    let mut in_text: Vec<&str> = text
                                        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                        .filter(|t| names.contains(t))
                                        .collect();
                                    in_text.sort();
                                    in_text.dedup();
                                    let mut reads: Vec<&str> =
                                        w.expr.reads.iter().map(String::as_str).collect();
                                    reads.sort();
                                    assert_eq!(
                                        reads, in_text,
                                        "{model:?} {target:?} {stages}: {}_s{} = {text}",
                                        w.name, s.index
                                    );
                                    let plain = text
                                        .chars()
                                        .all(|c| c.is_alphanumeric() || "_[]:{}, '\n".contains(c));
                                    assert_eq!(
                                        w.kind == Kind::Select,
                                        plain,
                                        "{model:?} {target:?} {stages}: {}_s{} ({:?}) = {text}",
                                        w.name,
                                        s.index,
                                        w.kind
                                    );
                                    assert_eq!(
                                        w.product().is_some(),
                                        text.contains(" * "),
                                        "{model:?} {target:?}: {}_s{} = {text}",
                                        w.name,
                                        s.index
                                    );
                                    checked += 1;
                                }
                            }
                        }
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked} wires");
    }
}

#[cfg(test)]
mod budget_tests {
    use super::*;

    /// With products in the fabric the registers balance the fabric's stretches, not the hard
    /// block's step: a lone block step counts nothing (as in `Plan::stage_delay`), so the
    /// four LUT steps after it are cut in two halves of 6 instead of 9 and 3.
    #[test]
    fn a_hard_steps_length_does_not_set_the_fabrics() {
        let delays = [10.0, 3.0, 3.0, 3.0, 3.0];
        assert_eq!(balanced_cuts(&delays, 2), vec![1, 4]);
        assert_eq!(
            balanced_cuts_by(&delays, &[true, false, false, false, false], 2),
            vec![1, 3]
        );
        assert_eq!(
            balanced_cuts_by(&delays, &[false; 5], 2),
            balanced_cuts(&delays, 2)
        );
    }

    fn product(name: &str, a: u32, b: u32, width: u32, blocks: u32) -> ProductUse {
        ProductUse {
            name: name.into(),
            a,
            b,
            width,
            blocks,
            fabric: false,
        }
    }

    /// The budget keeps the products costliest in the fabric on blocks: at 2 blocks `wide`
    /// (16·32 partial-product bits) rather than both `mid`s (2·8·24).
    #[test]
    fn the_costliest_products_keep_their_blocks() {
        let uses = [
            product("small", 4, 8, 12, 1),
            product("wide", 16, 16, 32, 2),
            product("mid1", 8, 16, 24, 1),
            product("mid2", 8, 16, 24, 1),
            product("lut", 4, 3, 7, 0),
        ];
        let names = |v: &[&str]| {
            v.iter()
                .map(|s| s.to_string())
                .collect::<BTreeSet<String>>()
        };
        assert_eq!(to_fabric(&uses, 5), BTreeSet::new(), "every block fits");
        assert_eq!(to_fabric(&uses, 4), names(&["small"]));
        assert_eq!(
            to_fabric(&uses, 2),
            names(&["small", "mid1", "mid2"]),
            "16·32 > 2·8·24: wide keeps both blocks"
        );
        assert_eq!(
            to_fabric(&uses, 1),
            names(&["small", "wide", "mid2"]),
            "ties keep the product made first"
        );
        assert_eq!(
            to_fabric(&uses, 0),
            names(&["small", "wide", "mid1", "mid2"]),
            "a product of no block stays"
        );
    }
}
