//! Adds and sums: carry chains, carry-select and carry-save sums, partial products (a
//! carry-select sum is finished in `carry_select`).

use super::carry_select::LastPick;
use super::*;

impl Builder {
    /// `name = (a + b + cin) mod 2^width` as one carry chain in this step, whatever its width
    /// (the ECP5's CCU2C chains are fast; the iCE40 shape uses [`Builder::add_start`]).
    pub(crate) fn add(
        &mut self,
        name: &str,
        a: &[Piece],
        b: &[Piece],
        cin: bool,
        width: u32,
        comment: &str,
    ) -> Sig {
        self.delay(add_delay(width.min(self.chunk_bits())));
        let ea = self.pieces(&sub_pieces(a, 0, width));
        let eb = self.addend(&sub_pieces(b, 0, width), |e| e);
        let plus = if cin {
            format!(" + {}", lit(width, 1))
        } else {
            String::new()
        };
        let kind = if eb.is_empty() && !cin {
            pieces_kind(a)
        } else {
            Kind::Sum
        };
        self.wire(name, width, kind, ex!("{}{}{}", ea, eb, plus), comment)
    }

    /// `name = a + b` over `width` bits whose top bit is the carry out of the bits below (both
    /// operands 0 there), as one carry chain with that carry kept complemented: a 1 above the
    /// first operand makes the top bit a sum bit, `~carry`, which the chain's last cell hands
    /// to its flip-flop. A plain carry-out leaves an ECP5 CCU2C chain through a LUT of its own
    /// (yosys 0.70: a LUT and 0.7 ns of route more, the path that held lean at 236 MHz), as it
    /// leaves an iCE40 chain ([`Builder::add_start`] keeps its chunks' carries the same way).
    /// Readers take `~name[width - 1]`.
    pub(crate) fn add_carry_complemented(
        &mut self,
        name: &str,
        a: &[Piece],
        b: &[Piece],
        width: u32,
        comment: &str,
    ) -> Sig {
        let top = width - 1;
        assert!(
            zero_bit(&sub_pieces(a, 0, width), top) && zero_bit(&sub_pieces(b, 0, width), top),
            "datapath: {name}'s top bit is not a carry-out"
        );
        let mut a = sub_pieces(a, 0, top);
        a.push(Piece::Const { value: 1, width: 1 });
        self.add(name, &a, b, false, width, comment)
    }

    /// `name = (a + b + cin) mod 2^width`. One chunk: computed here. More: each chunk is added
    /// here with carry-in 0 and 1 (carry-select), and [`Builder::add_finish`] resolves the
    /// carries and picks in the next step.
    pub(crate) fn add_start(
        &mut self,
        name: &str,
        a: &[Piece],
        b: &[Piece],
        cin: bool,
        width: u32,
        comment: &str,
    ) -> PendingAdd {
        let parts = chunks(width, self.chunk_bits().min(self.chunk_limit));
        let n = parts.len();
        let no_carry_out = parts
            .iter()
            .map(|&(lo, w)| {
                sub_pieces(b, lo, w)
                    .iter()
                    .all(|p| matches!(p, Piece::Const { value: 0, .. }))
            })
            .collect();
        let max_chunk = parts.iter().map(|c| c.1).max().unwrap_or(1);
        self.delay(add_delay(max_chunk));
        let mut top_inverted = false;
        let mut plain_consts = Vec::new();
        if n == 1 {
            let ea = self.pieces(&sub_pieces(a, 0, width));
            let eb = self.addend(&sub_pieces(b, 0, width), |e| e);
            let plus = if cin {
                format!(" + {}", lit(width, 1))
            } else {
                String::new()
            };
            let kind = if eb.is_empty() && !cin {
                pieces_kind(a)
            } else {
                Kind::Sum
            };
            self.wire(name, width, kind, ex!("{}{}{}", ea, eb, plus), comment);
        } else {
            for (i, &(lo, w)) in parts.iter().enumerate() {
                let top = i + 1 == n;
                let ww = if top { w } else { w + 1 };
                let pa = sub_pieces(a, lo, w);
                let pb = sub_pieces(b, lo, w);
                // the top chunk's top bit a carry-out (0 above both operands): a 1 above the
                // first makes it a sum bit, the carry's complement, as below
                let pa = if top && zero_bit(&pa, w - 1) && zero_bit(&pb, w - 1) {
                    top_inverted = true;
                    let mut v = sub_pieces(&pa, 0, w - 1);
                    v.push(Piece::Const { value: 1, width: 1 });
                    v
                } else {
                    pa
                };
                // below the top chunk, the carry-out is kept complemented, as the sum bit of a
                // 1 above the first operand and a 0 above the second (1 + 0 + carry = ~carry
                // mod 2): the chain computes it in a LUT of its own that packs with its
                // flip-flop. A plain carry-out (0 above both, or 1 above both, which synthesis
                // folds to the same) is the chain's CO, which leaves an iCE40 chain through an
                // extra LUT placed apart from the flip-flop: 2-3 ns of routing more.
                // [`Builder::carry_out`] reads it back.
                let ext_a = |e: Expr| if top { e } else { ex!("{{1'b1, {}}}", e) };
                let ext_b = |e: Expr| if top { e } else { ex!("{{1'b0, {}}}", e) };
                // carry-in 1 as a 1 + 1 in an extra low bit: one adder that no synthesis tool
                // can share with the carry-in-0 sum (a shared "+ 1" would chain two adders)
                let ext1_a = |e: Expr| {
                    if top {
                        ex!("{{{}, 1'b1}}", e)
                    } else {
                        ex!("{{1'b1, {}, 1'b1}}", e)
                    }
                };
                let ext1_b = |e: Expr| {
                    if top {
                        ex!("{{{}, 1'b1}}", e)
                    } else {
                        ex!("{{1'b0, {}, 1'b1}}", e)
                    }
                };
                // the carry-in-0 sum's constant bits, where it only copies the first operand
                plain_consts.push(
                    (0..w)
                        .map(|j| match all_zero(&pb) {
                            // (the top bit of a top chunk kept complemented is read back complemented)
                            true => {
                                const_bit(&pa, j).map(|v| v != (top && top_inverted && j + 1 == w))
                            }
                            false => None,
                        })
                        .collect(),
                );
                let ea = self.pieces(&pa);
                let what = if top {
                    format!("bits [{}:{lo}]", lo + w - 1)
                } else {
                    format!("bits [{}:{lo}] and their carry (complemented)", lo + w - 1)
                };
                let sum0 = {
                    let eb = self.addend(&pb, ext_b);
                    (
                        if eb.is_empty() {
                            pieces_kind(&pa)
                        } else {
                            Kind::Sum
                        },
                        ex!("{}{}", ext_a(ea.clone()), eb),
                    )
                };
                let sum1 = {
                    let eb = self.addend(&pb, ext1_b);
                    let eb = if eb.is_empty() {
                        Expr::constant(format!(" + {}", lit(ww + 1, 1)))
                    } else {
                        eb
                    };
                    ex!("{}{}", ext1_a(ea), eb)
                };
                if i == 0 && cin {
                    self.wire(
                        &format!("{name}_part0"),
                        ww + 1,
                        Kind::Sum,
                        sum1,
                        &format!("{what} above bit 0, carry-in 1"),
                    );
                } else if i == 0 {
                    self.wire(
                        &format!("{name}_part0"),
                        ww,
                        sum0.0,
                        sum0.1,
                        &format!("{what}, carry-in 0"),
                    );
                } else {
                    self.wire(
                        &format!("{name}_part{i}"),
                        ww,
                        sum0.0,
                        sum0.1,
                        &format!("{what}, carry-in 0"),
                    );
                    self.wire(
                        &format!("{name}_part{i}_plus1"),
                        ww + 1,
                        Kind::Sum,
                        sum1,
                        &format!("{what} above bit 0, carry-in 1 (carry-select)"),
                    );
                }
            }
        }
        PendingAdd {
            name: name.into(),
            width,
            chunks: if n == 1 { Vec::new() } else { parts },
            part0_offset: u32::from(cin),
            no_carry_out,
            top_inverted,
            plain_consts,
            comment: comment.into(),
        }
    }

    /// `sig[hi:lo] >= c` as AND/OR of its bits, most significant first (a bit of `c` set: that
    /// bit and the rest; clear: that bit or the rest; none left set: true): a few LUTs that
    /// synthesis maps as logic, where `>=` becomes a carry chain whose carry-out leaves it
    /// through an extra LUT placed apart (iCE40).
    pub(crate) fn at_least(&mut self, sig: &str, hi: u32, lo: u32, c: u128) -> Expr {
        let width = hi - lo + 1;
        if c == 0 {
            return Expr::constant("1'b1");
        }
        let mut expr = Expr::default();
        // x[i:0] >= c[i:0], from the lowest set bit of c up (below it, c's bits are 0: true)
        let low = c.trailing_zeros();
        for i in low..width {
            let bit = self.bits(sig, lo + i, lo + i);
            expr = if i == low {
                bit
            } else if (c >> i) & 1 == 1 {
                ex!("{} & ({})", bit, expr)
            } else {
                ex!("{} | ({})", bit, expr)
            };
        }
        expr
    }

    /// The carry out of a chunk of [`Builder::add_start`]: its bit `bit`, kept complemented.
    pub(super) fn carry_out(&mut self, part: &str, bit: u32) -> Expr {
        ex!("~{}", self.bits(part, bit, bit))
    }

    /// Second step of a carry-select add: the carry into each chunk from the third on
    /// (the first chunk's own carry-out is the carry into the second), rippled through the
    /// chunks' carry-outs. Nothing to do for one or two chunks.
    pub(crate) fn add_carries(&mut self, p: &PendingAdd) {
        let n = p.chunks.len();
        if n > 2 {
            self.add_carries_range(p, 1, n - 1);
        }
    }

    /// The carries into chunks `from + 1 ..= to` (one LUT level each, rippled).
    pub(super) fn add_carries_range(&mut self, p: &PendingAdd, from: usize, to: usize) {
        self.delay(LUT_DELAY * (to - from) as f64);
        let (_, w0) = p.chunks[0];
        let o = p.part0_offset;
        let mut carry = match from {
            1 => self.carry_out(&format!("{}_part0", p.name), w0 + o),
            _ => self.r(&format!("{}_carry{from}", p.name)),
        };
        for i in from..to {
            let w = p.chunks[i].1;
            let ca = self.carry_out(&format!("{}_part{i}_plus1", p.name), w + 1);
            let cname = format!("{}_carry{}", p.name, i + 1);
            let expr = if p.no_carry_out[i] {
                // an AND, not a ?: of 0 ([`Builder::select`])
                ex!("{} & {}", carry, ca)
            } else {
                let cb = self.carry_out(&format!("{}_part{i}", p.name), w);
                ex!("{} ? {} : {}", carry, ca, cb)
            };
            self.wire(
                &cname,
                1,
                Kind::Sum,
                expr,
                &format!("carry into bit {}", p.chunks[i + 1].0),
            );
            carry = self.r(&cname);
        }
    }

    /// The partial products of `a·r·2^shift` mod 2^width as wires `{name}_pp{k}` (one LUT
    /// level: `a` shifted to bit `k` of `r` where it is set, else 0; each complemented when
    /// `invert`, for a difference), as terms for [`Builder::sum_start`].
    ///
    /// A term is a wire of its significant bits only (`a`'s width above its shift), with zeros
    /// above it as constant pieces: the sum then knows where both its operands are 0, and keeps
    /// a carry-out there complemented ([`Builder::add_start`]). A carry-out registered as it is
    /// leaves an iCE40 chain through a LUT of its own placed apart from its flip-flop (blinn's
    /// n·l[32] held it at 115.8 MHz on yosys 0.23).
    pub(crate) fn partial_products(
        &mut self,
        name: &str,
        a: &Piece,
        r: &Piece,
        shift: u32,
        width: u32,
        invert: bool,
    ) -> Vec<Vec<Piece>> {
        let rows = self.shift_add_rows(a, r, shift, width, !invert);
        let mut out = Vec::new();
        for (k, (t, tw)) in rows.into_iter().enumerate() {
            let pp = format!("{name}_pp{k}");
            let (e, what) = if invert {
                (ex!("~{}", t), "complemented")
            } else {
                (t, "")
            };
            self.wire(
                &pp,
                tw,
                Kind::Logic,
                e,
                &format!(
                    "partial product {k}{}",
                    if invert {
                        format!(", {what}")
                    } else {
                        String::new()
                    }
                ),
            );
            let mut term = vec![Piece::sig(&pp, 0, tw)];
            if tw < width {
                term.push(Piece::zeros(width - tw));
            }
            out.push(term);
        }
        self.delay(LUT_DELAY);
        out
    }

    /// `name = Σ terms mod 2^width` (each term pieces, LSB first) without a carry chain until
    /// the end: 3:2 carry-save layers (sum `a ^ b ^ c`, carry the majority shifted up: one LUT
    /// level each, from this step on; one a step on the iCE40, where two in a row are a function
    /// of up to 9 registers that yosys 0.70's ABC maps to three LUT4 levels, two a step
    /// elsewhere), then (iCE40: after a step that only
    /// registers them) the two vectors left into [`Builder::add_start`] in a step of its own.
    /// [`Builder::resolve`] finishes it.
    pub(crate) fn sum_start(
        &mut self,
        name: &str,
        terms: Vec<Vec<Piece>>,
        width: u32,
        title: &str,
        comment: &str,
    ) -> PendingAdd {
        self.sums_start(
            vec![(name.to_string(), terms, width, comment.to_string())],
            title,
        )
        .pop()
        .expect("one sum")
    }

    /// [`Builder::sum_start`] for several sums side by side (`(name, terms, width, comment)`):
    /// each carry-save layer of every sum in the same step, each closing add started in the same
    /// step, so that the sums take the steps of the longest, not their total.
    pub(crate) fn sums_start(
        &mut self,
        sums: Vec<(String, Vec<Vec<Piece>>, u32, String)>,
        title: &str,
    ) -> Vec<PendingAdd> {
        let mut layer = 0;
        let per_step = self.family().carry_save_layers_per_step();
        let mut all: Vec<(String, Vec<Vec<Piece>>, u32, String)> = sums;
        while all.iter().any(|s| s.1.len() > 2) {
            if layer % per_step == 0 {
                if per_step == 1 {
                    self.step(&format!("{title}: carry-save layer {}", layer + 1));
                } else {
                    self.step(&format!(
                        "{title}: carry-save layers {} and {}",
                        layer + 1,
                        layer + 2
                    ));
                }
                self.delay(per_step as f64 * LUT_DELAY);
            }
            layer += 1;
            for (name, terms, width, _) in all.iter_mut() {
                if terms.len() <= 2 {
                    continue;
                }
                let (name, width) = (name.clone(), *width);
                let mut next = Vec::new();
                let mut rest = std::mem::take(terms).into_iter();
                let mut i = 0;
                loop {
                    let group: Vec<Vec<Piece>> = rest.by_ref().take(3).collect();
                    if group.len() < 3 {
                        next.extend(group);
                        break;
                    }
                    // the bits each vector can have set: the sum's below the widest term's
                    // significant bits, the carries' below the second widest (a majority needs
                    // two), so the zeros above a term reach the closing add, which then keeps
                    // its carry-out complemented ([`Builder::add_start`]) where a synthesis
                    // tool would find those bits 0 through the registers and leave a bare
                    // carry-out (fitted's squaring held at 115.8 MHz on the UP5K)
                    let mut sig: Vec<u32> =
                        group.iter().map(|t| significant_bits(t, width)).collect();
                    sig.sort_unstable();
                    let (sw, cw) = (sig[2].max(1), sig[1].min(width - 1).max(1));
                    let es: Vec<Expr> = group
                        .iter()
                        .map(|t| self.pieces(&sub_pieces(t, 0, sw)))
                        .collect();
                    let ec: Vec<Expr> = group
                        .iter()
                        .map(|t| self.pieces(&sub_pieces(t, 0, cw)))
                        .collect();
                    let (sn, cn) = (
                        format!("{name}_csa{layer}_s{i}"),
                        format!("{name}_csa{layer}_c{i}"),
                    );
                    // one operand (or pair) a line
                    self.wire(
                        &sn,
                        sw,
                        Kind::Sum,
                        ex!("{}\n    ^ {}\n    ^ {}", &es[0], &es[1], &es[2]),
                        &format!("carry-save layer {layer}: the sum bits"),
                    );
                    self.wire(
                        &cn,
                        cw,
                        Kind::Sum,
                        ex!(
                            "({} & {})\n    | ({} & {})\n    | ({} & {})",
                            &ec[0],
                            &ec[1],
                            &ec[0],
                            &ec[2],
                            &ec[1],
                            &ec[2]
                        ),
                        &format!("carry-save layer {layer}: the carries (worth twice)"),
                    );
                    next.push(sub_pieces(&[Piece::sig(&sn, 0, sw)], 0, width));
                    next.push(sub_pieces(
                        &[Piece::zeros(1), Piece::sig(&cn, 0, cw)],
                        0,
                        width,
                    ));
                    i += 1;
                }
                *terms = next;
            }
        }
        if self.family().registers_carry_save_vectors() {
            // a step that only registers the two vectors (`Family::registers_carry_save_vectors`)
            self.register_only_step(&format!("{title}: the two vectors registered"));
        }
        self.step(&format!("{title}: chunk sums"));
        all.into_iter()
            .map(|(name, terms, width, comment)| {
                let zero = vec![Piece::zeros(width)];
                let (a, b) = (
                    terms.first().unwrap_or(&zero).clone(),
                    terms.get(1).unwrap_or(&zero).clone(),
                );
                // short chunks: the vectors come from registers spread over a wide sum
                self.add_start_short(&name, &a, &b, false, width, &comment)
            })
            .collect()
    }
    pub(crate) fn add_start_short(
        &mut self,
        name: &str,
        a: &[Piece],
        b: &[Piece],
        cin: bool,
        width: u32,
        comment: &str,
    ) -> PendingAdd {
        self.chunk_limit = SUM_CHUNK_BITS;
        let p = self.add_start(name, a, b, cin, width, comment);
        self.chunk_limit = u32::MAX;
        p
    }

    /// Finishes a carry-select add in the steps it needs, at most two LUT levels a step: none
    /// for one chunk; the chunk carries rippled two a step (one for a sum of more than
    /// [`WIDE_SUM_CHUNKS`] chunks), the last with each chunk's pick. Returns the name of the sum.
    pub(crate) fn resolve(&mut self, p: PendingAdd, title: &str) -> Sig {
        self.resolve_all(vec![p], title).pop().expect("one sum")
    }

    /// [`Builder::resolve`] for sums started side by side ([`Builder::sums_start`]): those of
    /// as many chunks as the first resolved in the same steps, any other after them.
    pub(crate) fn resolve_all(&mut self, ps: Vec<PendingAdd>, title: &str) -> Vec<Sig> {
        let n = ps.first().map_or(0, |p| p.chunks.len());
        if ps.iter().any(|p| p.chunks.len() != n) {
            return ps.into_iter().map(|p| self.resolve(p, title)).collect();
        }
        if n > 0 {
            // the carries into chunks from+1..=to (chunk 1's is part0's), `per_step` levels a
            // step, then the picks
            let to = n.saturating_sub(1).max(1);
            let per_step = if n > WIDE_SUM_CHUNKS { 1 } else { 2 };
            let mut from = 1;
            while to - from > 1 {
                self.step(&format!("{title}: carries"));
                for p in &ps {
                    self.add_carries_range(p, from, from + per_step);
                }
                from += per_step;
            }
            let rest = from < to;
            self.step(&format!(
                "{title}: {}select",
                if rest { "carries and " } else { "" }
            ));
            // a carry left (into chunk `to`) is not made: that chunk picks by the carry into the
            // chunk below, from two picks made beside it ([`Builder::finish_picks`])
            if rest && self.route_registers() {
                // ...and with route registers, in a step after them, one LUT level each
                for p in &ps {
                    self.picks_below_last(p);
                }
                self.step(&format!("{title}: the last chunk's pick"));
                return ps
                    .into_iter()
                    .map(|p| self.finish_picks(p, LastPick::Apart))
                    .collect();
            }
            let last = if rest {
                LastPick::Split
            } else {
                LastPick::ByItsCarry
            };
            return ps.into_iter().map(|p| self.finish_picks(p, last)).collect();
        }
        ps.into_iter()
            .map(|p| self.finish_picks(p, LastPick::ByItsCarry))
            .collect()
    }
}
