//! The shape of a configuration as the delay model sees it: what shapes a datapath's delays
//! beyond its depth (the widths, the rounding, the ROM style, the blocks a budget allows, the
//! constant's width and fitted's squarings where the model reads them, and whether some product
//! is left in LUTs for being too small for the family's block), typed; how shapes are ordered
//! (no wider, between) and how one is said (the `generate` flags beyond the defaults).

use crate::config::{Params, RomStyle, Rounding, SpecularModel};
use crate::plan::Plan;

/// A configuration's shape (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Shape {
    cos_frac_bits: u32,
    n_bits: u32,
    color_bits: u32,
    intensity_frac_bits: u32,
    /// where the model reads them
    k_frac_bits: Option<u32>,
    max_squarings: Option<u32>,
    /// the blocks a budget allows: no budget is the most there is, so that a budget lies
    /// between smaller ones and none
    dsp_budget: u32,
    rounding: Rounding,
    rom_style: RomStyle,
    fabric_registers: bool,
    /// some product of multi-bit operands is LUTs, too small for the family's block
    /// (`Family::soft_product`; a product by one bit is an AND on every family): a step no
    /// register splits (a narrow fitted's 7×4 colour product holds the iCE40 UP5K at 53 MHz
    /// at every depth, where widths a little wider map it to an SB_MAC16), so a width with one
    /// and a width without are not alike
    soft_products: bool,
}

/// The flags of the sizes, in the order of [`Shape::sizes`].
const SIZE_FLAGS: [&str; 7] = [
    "--cos-frac-bits",
    "--n-bits",
    "--color-bits",
    "--intensity-frac-bits",
    "--k-frac-bits",
    "--max-squarings",
    "--dsp-budget",
];

impl Shape {
    /// The shape of `p` for `model`, `soft_products` as its plan has it.
    fn of(p: &Params, model: SpecularModel, soft_products: bool) -> Shape {
        Shape {
            cos_frac_bits: p.cos_frac_bits,
            n_bits: p.n_bits,
            color_bits: p.color_bits,
            intensity_frac_bits: p.intensity_frac_bits,
            k_frac_bits: model.reads("k_frac_bits").then_some(p.k_frac_bits),
            max_squarings: model.reads("max_squarings").then_some(p.max_squarings),
            dsp_budget: p.dsp_budget.unwrap_or(crate::config::DSP_BUDGET.max),
            rounding: p.rounding,
            rom_style: p.rom_style,
            fabric_registers: p.fabric_registers,
            soft_products,
        }
    }

    /// The shape of `plan`'s configuration, a budget that leaves every product in a block read
    /// as no budget (the same datapath: a met budget changes nothing).
    pub(crate) fn of_plan(plan: &Plan) -> Shape {
        let soft = plan.datapath.steps.iter().any(|s| s.small_product);
        let mut sh = Shape::of(&plan.cfg.params, plan.cfg.model(), soft);
        if plan.datapath.fabric_products().is_empty() {
            sh.dsp_budget = crate::config::DSP_BUDGET.max;
        }
        sh
    }

    /// The shape of the default parameters of `base`'s model and target with a calibration
    /// row's `args` applied; None when they name a flag the model's shape does not read (not
    /// known to be any shape) or plan no unit.
    pub(crate) fn of_args(args: &str, base: &Params) -> Option<Shape> {
        let p = super::params_with_args(base, args)?;
        let sh = planned(&p)?;
        let reads = |flag: &str| match flag {
            "--k-frac-bits" => sh.k_frac_bits.is_some(),
            "--max-squarings" => sh.max_squarings.is_some(),
            "--rounding" | "--rom-style" | "--fabric-registers" => true,
            _ => SIZE_FLAGS.contains(&flag),
        };
        args.split_whitespace().step_by(2).all(reads).then_some(sh)
    }

    fn sizes(&self) -> [Option<u32>; 7] {
        [
            Some(self.cos_frac_bits),
            Some(self.n_bits),
            Some(self.color_bits),
            Some(self.intensity_frac_bits),
            self.k_frac_bits,
            self.max_squarings,
            Some(self.dsp_budget),
        ]
    }

    /// Whether what is no size (rounding, ROM style, fabric registers, a product in LUTs for its
    /// size) is alike.
    pub(crate) fn alike(&self, o: &Shape) -> bool {
        (
            self.rounding,
            self.rom_style,
            self.fabric_registers,
            self.soft_products,
        ) == (o.rounding, o.rom_style, o.fabric_registers, o.soft_products)
    }

    /// Whether this shape is no wider than `o` in every size, the other flags alike.
    pub(crate) fn no_wider(&self, o: &Shape) -> bool {
        self.alike(o) && self.sizes().iter().zip(o.sizes()).all(|(a, b)| a <= &b)
    }

    /// Whether a unit of this shape is no harder to clock than one of `o`'s: alike, no wider in
    /// any width, and with as many blocks or more (a budget leaves products in the fabric, a
    /// slower shape; fewer blocks is not narrower here).
    pub(crate) fn easier_than(&self, o: &Shape) -> bool {
        let (own, theirs) = (self.sizes(), o.sizes());
        let budget = own.len() - 1;
        self.alike(o) && (0..budget).all(|i| own[i] <= theirs[i]) && own[budget] >= theirs[budget]
    }

    /// Whether this shape lies in the box `shapes` span: each size between the least and the
    /// most any of them has, each other flag one that one of them has.
    pub(crate) fn between(&self, shapes: &[Shape]) -> bool {
        let own = self.sizes();
        !shapes.is_empty()
            && (0..own.len()).all(|i| {
                shapes.iter().any(|s| s.sizes()[i] <= own[i])
                    && shapes.iter().any(|s| s.sizes()[i] >= own[i])
            })
            && shapes.iter().any(|s| s.rounding == self.rounding)
            && shapes.iter().any(|s| s.rom_style == self.rom_style)
            && shapes
                .iter()
                .any(|s| s.fabric_registers == self.fabric_registers)
            && shapes.iter().any(|s| s.soft_products == self.soft_products)
    }

    /// The `generate` flags by which it differs from the defaults of `model` ("the default
    /// widths" where none).
    pub(crate) fn flags(&self, model: SpecularModel) -> String {
        let default = Shape::of(&Params::default(), model, false);
        let mut v: Vec<String> = Vec::new();
        for (i, (own, d)) in self
            .sizes()
            .into_iter()
            .zip(default.sizes())
            .enumerate()
            .take(6)
        {
            if let (Some(x), true) = (own, own != d) {
                v.push(format!("{} {x}", SIZE_FLAGS[i]));
            }
        }
        if self.rounding != default.rounding {
            v.push(format!("--rounding {}", self.rounding.name()));
        }
        if self.rom_style != default.rom_style {
            v.push(format!("--rom-style {}", self.rom_style.name()));
        }
        if self.fabric_registers != default.fabric_registers {
            v.push("--fabric-registers".to_string());
        }
        if self.dsp_budget != default.dsp_budget {
            v.push(format!("--dsp-budget {}", self.dsp_budget));
        }
        if v.is_empty() {
            "the default widths".to_string()
        } else {
            v.join(" ")
        }
    }
}

/// The shape of `p`'s plan (a calibration row's configuration), planned once per
/// configuration: the shapes of every row are read at each depth a search tries.
fn planned(p: &Params) -> Option<Shape> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static SHAPES: OnceLock<Mutex<HashMap<String, Option<Shape>>>> = OnceLock::new();
    let key = format!("{p:?}");
    let cache = SHAPES.get_or_init(Default::default);
    if let Some(found) = cache.lock().ok()?.get(&key) {
        return found.clone();
    }
    let shape = crate::config::Config::new(p.clone())
        .and_then(Plan::new)
        .ok()
        .map(|plan| Shape::of_plan(&plan));
    // bounded: the calibration holds a few dozen widths; nothing else is asked here
    let mut map = cache.lock().ok()?;
    if map.len() < 4096 {
        map.insert(key, shape.clone());
    }
    shape
}
