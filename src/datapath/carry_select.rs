//! A carry-select sum finished: the carries into each chunk, the arms (the chunk's sum with a
//! carry in of 0 and of 1) and the picks between them, the last chunk's picks in the step after.

use super::*;

impl Builder {
    /// Last step of a carry-select add: each chunk picks its sum by its carry-in (one LUT
    /// level). Returns the name of the sum.
    pub(crate) fn add_finish(&mut self, p: PendingAdd) -> Sig {
        self.finish_picks(p, LastPick::ByItsCarry)
    }

    /// [`Builder::add_finish`], the last chunk as `last` says. [`LastPick::Split`] (the carry
    /// into the last chunk is not made, [`Builder::resolve_all`]): the last chunk picks by the
    /// carry into the chunk below, from its two picks by that chunk's carry-outs, kept wires
    /// made beside it: `c ? (cp ? inc : plain) : (cn ? inc : plain)`. Two LUT levels, as a carry
    /// and a pick, but the carry register, which every bit of the chunk below reads too and so
    /// sits apart from most of its readers, enters only the last. Made as a carry then a pick,
    /// its 3.0-3.6 ns route and two LUTs held fitted at 121 MHz on the UP5K (yosys 0.70:
    /// `square3_t_carry4`, `deviation_hi_carry4`). [`LastPick::Apart`]: the two picks and the
    /// other chunks' were made a step before; here the last pick and the sum.
    pub(super) fn finish_picks(&mut self, p: PendingAdd, last: LastPick) -> Sig {
        if p.chunks.is_empty() {
            return self.sig(&p.name);
        }
        self.delay(LUT_DELAY);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let n = p.chunks.len();
        let mut words = vec![self.bits(&format!("{}_part0", p.name), w0 - 1 + o, o)];
        for (i, &(lo, w)) in p.chunks.iter().enumerate().skip(1) {
            let chunk = format!("{}_chunk{i}", p.name);
            match (last, i + 1 == n) {
                // made a step before ([`Builder::picks_below_last`])
                (LastPick::Apart, false) => {}
                (LastPick::ByItsCarry, _) | (_, false) => self.chunk_pick(&p, i),
                (split, true) => {
                    let (if1, if0) = match split {
                        LastPick::Apart => self.kept_arms_of(&p, i),
                        _ => self.last_chunk_arms(&p),
                    };
                    let carry = self.carry_into(&p, i - 1);
                    let what = format!(
                        "bits [{}:{lo}]: the sum with the carry into bit {lo}",
                        lo + w - 1
                    );
                    self.wire(&chunk, w, Kind::Sum, pick_expr(&carry, &if1, &if0), &what);
                }
            }
            words.push(self.r(&chunk));
        }
        words.reverse();
        let comment = p.comment.clone();
        // many chunks: one a line
        let sep = if words.len() > 4 { ",\n    " } else { ", " };
        self.wire(
            &p.name,
            p.width,
            Kind::Select,
            ex!("{{{}}}", Expr::join(&words, sep)),
            &comment,
        )
    }

    /// The carry into chunk `k` of `p` (chunk 1's is part0's carry-out), as this step reads it.
    fn carry_into(&mut self, p: &PendingAdd, k: usize) -> Expr {
        match k {
            1 => self.carry_out(&format!("{}_part0", p.name), p.chunks[0].1 + p.part0_offset),
            _ => self.r(&format!("{}_carry{k}", p.name)),
        }
    }

    /// The last chunk's two picks by the carry-outs of the chunk below (`cp` with its carry-in
    /// 1, `cn` with 0), kept wires of this step: its sum if the carry into the chunk below is 1,
    /// and if it is 0 (the carry-in-0 sum itself where that chunk has no carry-out).
    fn last_chunk_arms(&mut self, p: &PendingAdd) -> (Arms, Arms) {
        let i = p.chunks.len() - 1;
        let (lo, w) = p.chunks[i];
        let chunk = format!("{}_chunk{i}", p.name);
        let (inc, plain) = self.pick_arms(p, i);
        let (k, wk) = (i - 1, p.chunks[i - 1].1);
        let lo_k = p.chunks[k].0;
        let cp = self.carry_out(&format!("{}_part{k}_plus1", p.name), wk + 1);
        let e = pick_expr(&cp, &inc, &plain);
        let if1 = self.kept_arm(
            &format!("{chunk}_if1"),
            w,
            e,
            &format!(
                "bits [{}:{lo}] if the carry into bit {lo_k} is 1",
                lo + w - 1
            ),
        );
        let if0 = if p.no_carry_out[k] {
            plain
        } else {
            let cn = self.carry_out(&format!("{}_part{k}", p.name), wk);
            let e = pick_expr(&cn, &inc, &plain);
            self.kept_arm(
                &format!("{chunk}_if0"),
                w,
                e,
                &format!(
                    "bits [{}:{lo}] if the carry into bit {lo_k} is 0",
                    lo + w - 1
                ),
            )
        };
        (if1, if0)
    }

    /// The last chunk's two picks made a step before ([`Builder::last_chunk_arms`]), as this
    /// step reads them.
    fn kept_arms_of(&mut self, p: &PendingAdd, i: usize) -> (Arms, Arms) {
        let w = p.chunks[i].1;
        let chunk = format!("{}_chunk{i}", p.name);
        let if1 = self.arm_of(&format!("{chunk}_if1"), w);
        let if0 = match p.no_carry_out[i - 1] {
            true => self.plain_arm(p, i),
            false => self.arm_of(&format!("{chunk}_if0"), w),
        };
        (if1, if0)
    }

    /// With route registers ([`Builder::route_registers`]), the select step of a sum
    /// whose last chunk picks by the carry below: every chunk's pick but the last's, and the
    /// last chunk's two picks ([`Builder::last_chunk_arms`]); [`Builder::finish_picks`] makes the
    /// last pick and the sum in the step after.
    pub(super) fn picks_below_last(&mut self, p: &PendingAdd) {
        self.delay(LUT_DELAY);
        let n = p.chunks.len();
        for i in 1..n - 1 {
            self.chunk_pick(p, i);
        }
        self.last_chunk_arms(p);
    }

    /// Chunk `i`'s pick by the carry into it, `<name>_chunk<i>`, on its own line (the sum is
    /// then a plain concatenation).
    fn chunk_pick(&mut self, p: &PendingAdd, i: usize) {
        let (lo, w) = p.chunks[i];
        let (inc, plain) = self.pick_arms(p, i);
        let carry = self.carry_into(p, i);
        let what = format!(
            "bits [{}:{lo}]: the sum with the carry into bit {lo}",
            lo + w - 1
        );
        self.wire(
            &format!("{}_chunk{i}", p.name),
            w,
            Kind::Sum,
            pick_expr(&carry, &inc, &plain),
            &what,
        );
    }

    /// Chunk `i`'s two sums as the pick reads them: with carry-in 1 ([`Builder::inc_arm`]) and
    /// with carry-in 0 ([`Builder::plain_arm`]).
    fn pick_arms(&mut self, p: &PendingAdd, i: usize) -> (Arms, Arms) {
        (self.inc_arm(p, i), self.plain_arm(p, i))
    }

    /// Chunk `i`'s sum with carry-in 1 (the carry-out above the top chunk's sum complemented
    /// back).
    fn inc_arm(&mut self, p: &PendingAdd, i: usize) -> Arms {
        let w = p.chunks[i].1;
        let inc = format!("{}_part{i}_plus1", p.name);
        let inverted = p.top_inverted && i + 1 == p.chunks.len();
        let bits = (0..w)
            .map(|j| {
                Arm::Bit(if inverted && j + 1 == w {
                    ex!("~{}", self.bits(&inc, w, w))
                } else {
                    self.bits(&inc, j + 1, j + 1)
                })
            })
            .collect();
        let word = match (inverted, w) {
            (false, _) => self.bits(&inc, w, 1),
            (true, 1) => ex!("~{}", self.bits(&inc, w, w)),
            (true, _) => ex!(
                "{{~{}, {}}}",
                self.bits(&inc, w, w),
                self.bits(&inc, w - 1, 1)
            ),
        };
        Arms {
            bits,
            word: Some(word),
        }
    }

    /// Chunk `i`'s sum with carry-in 0, a constant bit where it only copies a constant of the
    /// first operand. (Read only where it is not a constant: a bit read is one the Verilog
    /// reads; and as a word only where no bit of it is a constant: a range read marks every bit
    /// of it read, and a bit marked read that the Verilog does not read is one Verilator's lint
    /// names.)
    fn plain_arm(&mut self, p: &PendingAdd, i: usize) -> Arms {
        let w = p.chunks[i].1;
        let plain = format!("{}_part{i}", p.name);
        let inverted = p.top_inverted && i + 1 == p.chunks.len();
        let bits: Vec<Arm> = (0..w)
            .map(|j| match p.plain_consts[i][j as usize] {
                Some(v) => Arm::Const(v),
                None => Arm::Bit(if inverted && j + 1 == w {
                    ex!("~{}", self.bits(&plain, w - 1, w - 1))
                } else {
                    self.bits(&plain, j, j)
                }),
            })
            .collect();
        let whole = bits.iter().all(|b| matches!(b, Arm::Bit(_)));
        let word = whole.then(|| match (inverted, w) {
            (false, _) => self.bits(&plain, w - 1, 0),
            (true, 1) => ex!("~{}", self.bits(&plain, w - 1, w - 1)),
            (true, _) => ex!(
                "{{~{}, {}}}",
                self.bits(&plain, w - 1, w - 1),
                self.bits(&plain, w - 2, 0)
            ),
        });
        Arms { bits, word }
    }

    /// A kept wire of `w` bits as an arm of a pick.
    fn kept_arm(&mut self, name: &str, w: u32, e: Expr, comment: &str) -> Arms {
        self.wire_kept(name, w, Kind::Sum, e, comment);
        self.arm_of(name, w)
    }

    /// The `w` bits of the signal `name` as an arm of a pick, as this step reads them.
    fn arm_of(&mut self, name: &str, w: u32) -> Arms {
        Arms {
            bits: (0..w).map(|j| Arm::Bit(self.bits(name, j, j))).collect(),
            word: Some(self.r(name)),
        }
    }
}

/// How a carry-select sum's last chunk picks ([`Builder::finish_picks`]).
#[derive(Clone, Copy)]
pub(super) enum LastPick {
    /// by the carry into it, as every chunk
    ByItsCarry,
    /// by the carry into the chunk below, from its two picks by that chunk's carry-outs, made
    /// beside it ([`Builder::last_chunk_arms`])
    Split,
    /// [`LastPick::Split`] a step after the two picks and every other chunk's
    /// ([`Builder::picks_below_last`]; [`Builder::route_registers`])
    Apart,
}

/// One bit of a pick's arm: a constant, or an expression.
enum Arm {
    Const(bool),
    Bit(Expr),
}

/// An arm of a pick: its bits (LSB first), and the word as one expression where no bit is a
/// constant.
struct Arms {
    bits: Vec<Arm>,
    word: Option<Expr>,
}

/// `carry ? a : b`, bit by bit (LSB first), as one `?:` of the two words when every bit of both
/// is an expression. A bit of `b` that is a constant is an AND or OR with the carry, not a `?:`
/// with a constant arm, which yosys makes the flip-flop's synchronous set or reset, driven over
/// the slow set/reset route (fitted's sign at 112.5 MHz).
fn pick_expr(carry: &Expr, a: &Arms, b: &Arms) -> Expr {
    if let (Some(wa), Some(wb)) = (&a.word, &b.word) {
        return ex!("{} ? {} : {}", carry, wa, wb);
    }
    let bits: Vec<Expr> = a
        .bits
        .iter()
        .zip(&b.bits)
        .rev()
        .map(|(x, y)| {
            let x = match x {
                Arm::Bit(e) => e.clone(),
                Arm::Const(v) => Expr::constant(if *v { "1'b1" } else { "1'b0" }),
            };
            match y {
                Arm::Const(true) => ex!("({} | {})", x, carry.not()),
                Arm::Const(false) => ex!("({} & {})", x, carry),
                Arm::Bit(y) => ex!("({} ? {} : {})", carry, x, y),
            }
        })
        .collect();
    ex!("{{{}}}", Expr::join(&bits, ", "))
}
