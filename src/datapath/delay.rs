//! The delay estimate of each step, from which `plan::balanced_cuts` places the registers.

use super::*;

// Delay estimates in ns, after iCE40 UP5K post-route figures (logic and routing, without the
// clock-to-out and setup every register adds once): one LUT level with its route ~2.7, a
// carry chain ~0.7 + 0.3/bit plus the LUT that brings its carry-out back to the fabric, a
// DSP multiply(-add) of <= 16-bit operands ~5.5, an asynchronous 2^N-word ROM in LUTs about
// one LUT level per 2 address bits. Only the ratios matter: they place the registers. Each
// estimate also counts the primitives it passes through ([`Delay`]), which the delay model
// weighs with the family's own primitive delays (`crate::family::PrimitiveDelays`).

/// A step's delay: the placement estimate in ns (iCE40 figures: what places the registers,
/// the same on every family), and the primitives it counts, which each family weighs with its
/// own delays ([`Delay::on`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Delay {
    /// the placement estimate, ns (the iCE40 figures above)
    pub(crate) ns: f64,
    /// the primitives passed through, in the order of `PrimitiveDelays`' fields: LUT levels
    /// with their routes, carry chains, carry bits, hard multiplies, levels of a partial-product
    /// array past the block, register-only routes
    pub(crate) parts: [f64; 6],
}

impl Delay {
    pub(crate) const ZERO: Delay = Delay {
        ns: 0.0,
        parts: [0.0; 6],
    };

    /// The delay on a family of primitive delays `w`, ns.
    pub(crate) fn on(&self, w: &crate::family::PrimitiveDelays) -> f64 {
        self.parts
            .iter()
            .zip(w.as_array())
            .map(|(n, d)| n * d)
            .sum()
    }
}

impl std::ops::Add for Delay {
    type Output = Delay;
    fn add(self, o: Delay) -> Delay {
        let mut parts = self.parts;
        parts.iter_mut().zip(o.parts).for_each(|(a, b)| *a += b);
        Delay {
            ns: self.ns + o.ns,
            parts,
        }
    }
}

impl std::ops::Mul<f64> for Delay {
    type Output = Delay;
    fn mul(self, k: f64) -> Delay {
        Delay {
            ns: self.ns * k,
            parts: self.parts.map(|p| p * k),
        }
    }
}

impl std::ops::Mul<Delay> for f64 {
    type Output = Delay;
    fn mul(self, d: Delay) -> Delay {
        Delay {
            ns: self * d.ns,
            parts: d.parts.map(|p| self * p),
        }
    }
}

/// One LUT level and its route.
pub(crate) const LUT_DELAY: Delay = Delay {
    ns: 2.7,
    parts: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
};

/// Chunk bits of the carry-select add closing a carry-save sum ([`Builder::sum_start`]).
pub(crate) const SUM_CHUNK_BITS: u32 = 4;

/// A step that only registers its signals (a route, no logic).
pub(crate) const REGISTER_ONLY_DELAY: Delay = Delay {
    ns: 1.0,
    parts: [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
};

/// A carry-select sum of more chunks than this spreads over so many tiles that a carry
/// crosses a long route: [`Builder::resolve`] ripples its carries one a step.
pub(crate) const WIDE_SUM_CHUNKS: usize = 4;

/// A `w`-bit carry chain, carry-out included.
pub(crate) fn add_delay(w: u32) -> Delay {
    Delay {
        ns: 0.7 + 0.3 * w as f64 + LUT_DELAY.ns,
        parts: [1.0, 1.0, w as f64, 0.0, 0.0, 0.0],
    }
}

/// An a×b multiply: one DSP when both fit its operands, else an array of partial products.
/// (The family's own rule, small products in LUTs: [`Builder::mul_delay`].)
pub(super) fn dsp_or_array_delay(a: u32, b: u32) -> Delay {
    if a.max(b) <= DSP_BITS {
        Delay {
            ns: 5.5,
            parts: [0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        }
    } else {
        let levels = (a.min(b).max(1) as f64).log2().ceil() + 1.0;
        Delay {
            ns: 1.5 * levels + 0.3 * (a + b) as f64,
            parts: [0.0, 0.0, (a + b) as f64, 0.0, levels, 0.0],
        }
    }
}

/// A product yosys leaves in LUTs (too small for the family's block): partial products summed
/// by a tree of LUT levels, then a carry chain over the product.
pub(super) fn soft_mul_delay(a: u32, b: u32) -> Delay {
    LUT_DELAY * ((a.min(b).max(1) as f64).log2().ceil() + 1.0) + add_delay(a + b)
}

impl Builder {
    /// The delay estimate of an a×b multiply as this target's synthesis maps it: a product too
    /// small for the block (on the iCE40 fewer than 11 bits, on
    /// either family an operand of one bit) is LUTs, slower than the block (a narrow lean's
    /// 5×4 colour product set its clock at 52 MHz while the estimate had it as one DSP); else
    /// one DSP, or an array past the block's operands.
    pub(crate) fn mul_delay(&self, a: u32, b: u32) -> Delay {
        self.product_estimate(a, b, a + b).0
    }

    /// An a×b multiply kept to `y` bits: its delay estimate, and whether yosys leaves it in
    /// LUTs on this family (too small for its block: `Family::soft_product`).
    pub(super) fn product_estimate(&self, a: u32, b: u32, y: u32) -> (Delay, bool) {
        match self.family().soft_product(a, b, y) {
            true => (soft_mul_delay(a, b), true),
            false => (dsp_or_array_delay(a, b), false),
        }
    }

    /// Raises the current step's delay to an a×b multiply's, kept to `y` bits, plus `after`
    /// (the logic behind it in the same step), and marks the step when the product is LUTs,
    /// not a block ([`Step::soft_product`]).
    pub(crate) fn product_delay(&mut self, a: u32, b: u32, y: u32, after: Delay) {
        let (d, soft) = self.product_estimate(a, b, y);
        self.delay(d + after);
        let s = self.steps.last_mut().expect("a step");
        s.soft_product |= soft;
        s.small_product |= soft && a.min(b) >= 2;
    }
}
