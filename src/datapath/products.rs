//! Products: every multiply of a datapath is made here, typed ([`Kind::Product`](super::Kind::Product), never found
//! by searching the text), counted in blocks ([`ProductUse`]), and — for the products the
//! unit's `--dsp-budget` leaves out of the blocks — summed from partial products in the
//! fabric, a carry-save sum the plan can cut like any other.

use super::*;

/// One product of several made side by side ([`Builder::muls`]).
pub(crate) struct MulItem<'a> {
    pub(crate) name: String,
    pub(crate) a: (&'a [Piece], u32),
    pub(crate) b: (&'a [Piece], u32),
    pub(crate) addend: Vec<Piece>,
    pub(crate) comment: String,
}

impl Builder {
    /// Puts the products named in `names` in the fabric (the plan's choice for the unit's
    /// `--dsp-budget`); every other product is the family's.
    pub(crate) fn in_fabric(&mut self, names: &std::collections::BTreeSet<String>) {
        self.fabric = names.clone();
    }

    /// Whether the product `name` is one the budget puts in the fabric.
    pub(crate) fn is_in_fabric(&self, name: &str) -> bool {
        self.fabric.contains(name)
    }

    /// Records a product for the budget: `a`×`b` significant bits, `width` kept.
    pub(super) fn count_product(&mut self, name: &str, a: u32, b: u32, width: u32) {
        let fabric = self.is_in_fabric(name);
        let blocks = if fabric {
            0
        } else {
            self.family().product_blocks(a, b, width)
        };
        self.product_uses.push(ProductUse {
            name: name.into(),
            a,
            b,
            width,
            blocks,
            fabric,
        });
    }

    /// `name = a·b (+ addend) mod 2^width`, in this step: one product the family's synthesis
    /// maps (a block, or LUTs when too small for one: `Family::soft_product`), the operands
    /// (`(pieces, significant bits)`) and the addend zero-extended to `width` bits (a block's
    /// post-adder takes the addend; empty: none). `after`: the delay of the logic behind the
    /// product in the same step. A product the budget leaves out of the blocks is
    /// [`Builder::fabric_products`] instead, in steps of its own.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn mul(
        &mut self,
        name: &str,
        width: u32,
        a: (&[Piece], u32),
        b: (&[Piece], u32),
        addend: &[Piece],
        after: Delay,
        comment: &str,
    ) -> Sig {
        let item = MulItem {
            name: name.into(),
            a,
            b,
            addend: addend.to_vec(),
            comment: comment.into(),
        };
        self.muls(&[item], width, after).pop().expect("one product")
    }

    /// Several products of `width` bits made side by side in this step ([`Builder::mul`]); in
    /// the fabric, their sums take the same steps.
    pub(crate) fn muls(&mut self, items: &[MulItem], width: u32, after: Delay) -> Vec<Sig> {
        for it in items {
            self.count_product(&it.name, it.a.1, it.b.1, width);
        }
        if items.iter().any(|it| self.is_in_fabric(&it.name)) {
            return self.fabric_products(items, width, after);
        }
        items
            .iter()
            .map(|it| {
                self.product_delay(it.a.1, it.b.1, width, after);
                let (pa, pb) = (sub_pieces(it.a.0, 0, width), sub_pieces(it.b.0, 0, width));
                if [&pa, &pb].iter().any(|p| matches!(p.first(), Some(Piece::Const { value, width }) if *width > 0 && value & 1 == 0)) {
                    self.shifted_products.push(it.name.clone());
                }
                let (ea, eb) = (self.pieces(&pa), self.pieces(&pb));
                let plus = match it.addend.is_empty() {
                    true => Expr::default(),
                    false => ex!(" + {}", self.pieces(&sub_pieces(&it.addend, 0, width))),
                };
                self.wire(&it.name, width, Kind::Product(it.a.1, it.b.1), ex!("{} * {}{}", ea, eb, plus), &it.comment)
            })
            .collect()
    }

    /// Products summed in the fabric, side by side: in this step each one's partial products
    /// (the wider operand gated by each bit of the narrower, or shifted by each set bit of a
    /// constant), and its addend as one more term; then one carry-save sum each, in steps of
    /// their own ([`Builder::sums_start`]), closed by a carry-select add. Exact: every term is
    /// kept to `width` bits and the sum is taken mod 2^width, as the product's wire is.
    pub(crate) fn fabric_products(
        &mut self,
        items: &[MulItem],
        width: u32,
        after: Delay,
    ) -> Vec<Sig> {
        let mut sums = Vec::new();
        for it in items {
            let mut terms = self.partial_terms(&it.name, it.a, it.b, width);
            if !it.addend.is_empty() {
                terms.push(sub_pieces(&it.addend, 0, width));
            }
            let comment = format!("{} (in the fabric: --dsp-budget)", it.comment);
            sums.push((it.name.clone(), terms, width, comment));
        }
        self.delay(LUT_DELAY);
        let title = format!(
            "{} in the fabric",
            items
                .iter()
                .map(|i| i.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        );
        let pending = self.sums_start(sums, &title);
        let out = self.resolve_all(pending, &title);
        let s = self.steps.last_mut().expect("a step");
        s.delay = s.delay + after;
        out
    }

    /// The partial products of `a`×`b` kept to `width` bits, as terms of a sum.
    fn partial_terms(
        &mut self,
        name: &str,
        a: (&[Piece], u32),
        b: (&[Piece], u32),
        width: u32,
    ) -> Vec<Vec<Piece>> {
        let constant = |p: &[Piece]| p.iter().all(|x| matches!(x, Piece::Const { .. }));
        let value = |p: &[Piece]| {
            let mut v = 0u128;
            let mut at = 0;
            for x in p {
                if let Piece::Const { value, width } = x {
                    v |= value << at;
                    at += width;
                }
            }
            v
        };
        // a constant operand: the other shifted by each of its set bits, no gates
        for (c, other) in [(b, a), (a, b)] {
            if constant(c.0) {
                let v = value(&sub_pieces(c.0, 0, width));
                return (0..width)
                    .filter(|k| v >> k & 1 == 1)
                    .map(|k| {
                        let mut t = vec![Piece::zeros(k)];
                        t.extend(sub_pieces(other.0, 0, width - k));
                        t
                    })
                    .collect();
            }
        }
        // the narrower operand's bits gate the wider one
        let (wide, narrow) = if a.1 >= b.1 { (a, b) } else { (b, a) };
        let wp = self.single_piece(&format!("{name}_mw"), wide.0, wide.1);
        let np = self.single_piece(&format!("{name}_mn"), narrow.0, narrow.1);
        self.partial_products(name, &wp, &np, 0, width, false)
    }

    /// `pieces` (of `bits` significant bits) as one signal piece: itself when it is one, else
    /// a wire `name` of its bits.
    fn single_piece(&mut self, name: &str, pieces: &[Piece], bits: u32) -> Piece {
        let p = sub_pieces(pieces, 0, bits);
        match p.as_slice() {
            [one @ Piece::Sig { invert: false, .. }] => one.clone(),
            _ => {
                let e = self.pieces(&p);
                self.wire(
                    name,
                    bits,
                    pieces_kind(&p),
                    e,
                    "an operand of the product below",
                );
                Piece::sig(name, 0, bits)
            }
        }
    }
}

/// The operands of an interpolation's DSP block: the step `delta` and the fraction `r`, each
/// at the block's width when the table word carries them so (`pad`: the step's field, and the
/// zero bits above it that widen `r`).
pub(crate) fn pad_operands(
    delta: Piece,
    r: Piece,
    word: &str,
    pad: Option<crate::table::OperandPad>,
) -> (Vec<Piece>, Vec<Piece>) {
    match (pad, &delta) {
        (Some(p), Piece::Sig { lo, .. }) => (
            vec![Piece::sig(word, *lo, p.a_bits)],
            vec![r, Piece::sig(word, lo + p.a_bits, p.b_pad)],
        ),
        _ => (vec![delta], vec![r]),
    }
}

impl Builder {
    /// Whether an interpolation `entry + Δ·r` (`Δ` of `delta_bits`, the fraction `r` of
    /// `rest_bits`, the sum `entry_bits + rest_bits` wide) is one DSP block's multiply-add: its
    /// operands fit the block and its sum twice them; and on a family whose block takes its
    /// operands whole (the iCE40), how the table word pads them ([`pad_operands`]).
    pub(crate) fn interpolation_on_block(
        &self,
        delta_bits: u32,
        rest_bits: u32,
        entry_bits: u32,
    ) -> (bool, Option<crate::table::OperandPad>) {
        let dsp = self.dsp_bits();
        let on = rest_bits > 0
            && delta_bits.max(rest_bits) <= dsp
            && entry_bits + rest_bits <= dsp.saturating_mul(2);
        (
            on,
            (on && self.family().pads_block_operands()).then_some(crate::table::OperandPad {
                a_bits: dsp,
                b_pad: dsp - rest_bits,
            }),
        )
    }
}
