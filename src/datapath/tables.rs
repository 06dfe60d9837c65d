//! Tables: a table added to the datapath, read as a memory (a block RAM where it fits) or,
//! written as logic (`--rom-style logic`), as a table's parts, each a function of the
//! address's low bits, and the picks among them by its top bits, a step each.

use super::*;

impl Builder {
    /// The first step of a table read written as logic (`--rom-style logic`: never a memory,
    /// never block RAM): for each value `h` of the address's top bits, the entry its low bits
    /// pick (`<signal>_part<h>`, an OR of the entries, each gated by its match: a function of
    /// the low bits alone, two LUT levels up to 6 of them). [`Builder::rom_pick`] takes the
    /// word in the next step. Returns the parts and how many low bits they read.
    pub(crate) fn rom_parts(&mut self, signal: &str, t: usize, addr: &str) -> (Vec<Sig>, u32) {
        self.rom_parts_of(signal, t, addr, u32::MAX, false)
    }

    /// [`Builder::rom_parts`], each part a function of at most `most` low bits (more parts,
    /// more picks: a function of more bits than a LUT4 takes is LUT4s and muxes the placer may
    /// put apart, fitted's table at 239-241 MHz on the ECP5). `copies` (where the family copies
    /// a table's address, [`Family::copies_table_address`](crate::family::Family::copies_table_address)):
    /// this step holds a copy of the low bits per part (`<signal>_addr<h>`, a
    /// [`Datapath::copies`] entry: its flip-flop kept) and the parts are made in the next.
    pub(crate) fn rom_parts_of(
        &mut self,
        signal: &str,
        t: usize,
        addr: &str,
        most: u32,
        copies: bool,
    ) -> (Vec<Sig>, u32) {
        let aw = self.signal(addr).width;
        let (width, words) = (self.tables[t].width, self.tables[t].words.clone());
        // the top bits pick among at most 16 parts (a 16:1 mux, two LUT levels), or more where
        // a part may read no more than `most` bits
        let hi = (aw / 2).clamp(1, 4).max(aw.saturating_sub(most)).min(aw);
        let lo = aw - hi;
        let mut parts = Vec::new();
        if lo == 0 {
            // a one-bit address: each part is its word
            for h in 0..2usize {
                let e = Expr::constant(lit(width, words.get(h).copied().unwrap_or(0)));
                let what = format!("{} at {addr} = {h}", self.tables[t].what);
                parts.push(self.wire(&format!("{signal}_part{h}"), width, Kind::Select, e, &what));
            }
            return (parts, 0);
        }
        // each part's own copy of the address's low bits, in a step of its own
        if copies {
            for h in 0..1usize << hi {
                let e = self.bits(addr, lo - 1, 0);
                self.wire(
                    &format!("{signal}_addr{h}"),
                    lo,
                    Kind::Select,
                    e,
                    &format!("{addr}[{}:0] for part {h} alone", lo - 1),
                );
                self.copies.push(format!("{signal}_addr{h}"));
            }
            self.delay(REGISTER_ONLY_DELAY);
            let what = self.tables[t].what.clone();
            self.step(&format!(
                "{what} (in LUTs): its parts, each from its own copy of {addr}[{}:0]",
                lo - 1
            ));
        }
        let shared = (!copies).then(|| self.bits(addr, lo - 1, 0));
        for h in 0..1usize << hi {
            let low = match &shared {
                Some(e) => e.clone(),
                None => self.r(&format!("{signal}_addr{h}")),
            };
            let entries = (0..1usize << lo).filter_map(|l| {
                words
                    .get(h << lo | l)
                    .copied()
                    .filter(|&v| v != 0)
                    .map(|v| (l as u128, Expr::constant(lit(width, v))))
            });
            let e = Builder::one_of(&low, lo, entries, width);
            let what = format!(
                "{} at {addr}[{}:{lo}] = {h}, by {addr}[{}:0]",
                self.tables[t].what,
                aw - 1,
                lo - 1
            );
            parts.push(self.wire(&format!("{signal}_part{h}"), width, Kind::Table, e, &what));
        }
        self.delay(if lo > LUT_INPUTS {
            2.0 * LUT_DELAY
        } else {
            LUT_DELAY
        });
        (parts, lo)
    }

    /// A later step of [`Builder::rom_parts`]: the parts (picked by the address's bits from
    /// `lo` up, lowest first) four to one by the next two of those bits (a 4:1 mux, one slice
    /// of LUTs: an AND-OR, [`Builder::select`]'s rule). The last pick is `signal` itself.
    /// Returns the parts left and the address bit they are picked by.
    pub(crate) fn rom_pick(
        &mut self,
        signal: &str,
        t: usize,
        addr: &str,
        parts: &[Sig],
        lo: u32,
    ) -> (Vec<Sig>, u32) {
        self.rom_pick_of(signal, t, addr, parts, lo, 2)
    }

    /// [`Builder::rom_pick`] by at most `most` of the address's bits a step: one (2:1, a LUT4
    /// each) where a 4:1 pick's two LUT4 and their PFUMX would span slices (schlick's
    /// reciprocal at 238 MHz on the ECP5).
    pub(crate) fn rom_pick_of(
        &mut self,
        signal: &str,
        t: usize,
        addr: &str,
        parts: &[Sig],
        lo: u32,
        most: u32,
    ) -> (Vec<Sig>, u32) {
        let width = self.tables[t].width;
        let k: u32 = if parts.len() > 2 { 2 } else { 1 }.min(most);
        let sel = self.bits(addr, lo + k - 1, lo);
        let what = self.tables[t].what.clone();
        let mut out = Vec::new();
        for (g, group) in parts.chunks(1 << k).enumerate() {
            let cases: Vec<(u128, Expr)> = group
                .iter()
                .enumerate()
                .map(|(j, p)| (j as u128, self.r(p)))
                .collect();
            let last = parts.len() <= 1 << k;
            let name = if last {
                signal.to_string()
            } else {
                format!("{signal}_pick{}_{g}", lo + k)
            };
            let comment = if last {
                format!("{what} (a table in LUTs, address = {addr})")
            } else {
                format!(
                    "{addr}[{}:{lo}] picks among parts {}..{}",
                    lo + k - 1,
                    g << k,
                    (g << k) + group.len() - 1
                )
            };
            out.push(self.wire(
                &name,
                width,
                Kind::Logic,
                Builder::one_of(&sel, k, cases, width),
                &comment,
            ));
        }
        self.delay(LUT_DELAY);
        (out, lo + k)
    }
}

impl Builder {
    /// The value of `cases` (`(index, value)`) whose index `sel` (`bits` wide) equals, over
    /// `width` bits: an OR of the values, each gated by its match, one a line; 0 when there is
    /// none. A table or a mux in LUTs without a `?:` chain ([`Builder::select`]'s rule).
    pub(crate) fn one_of(
        sel: &Expr,
        bits: u32,
        cases: impl IntoIterator<Item = (u128, Expr)>,
        width: u32,
    ) -> Expr {
        let terms: Vec<Expr> = cases
            .into_iter()
            .map(|(i, v)| Builder::gate(&ex!("{} == {}", sel, lit(bits, i)), &v, width))
            .collect();
        match terms.is_empty() {
            true => Expr::constant(lit(width, 0)),
            false => Expr::join(&terms, "\n    | "),
        }
    }

    /// `name = v²` for the `r`-bit field `v = sig[lo..lo+r)`, by a table of 2^r entries in
    /// LUTs (no multiply, no carry chain): one LUT level up to [`LUT_INPUTS`] bits, two above.
    /// Written as an OR of the entries, each gated by its match: a `?:` chain of constants
    /// before a register would become the register's synchronous set/reset
    /// ([`Builder::select`]).
    pub(crate) fn square_table(&mut self, name: &str, sig: &str, lo: u32, r: u32, comment: &str) {
        // a table of 2^r lines: every caller splits wider squares otherwise (an invariant, not an input)
        assert!(
            r <= MAX_SQUARER_SPLIT,
            "a square table of {r} bits: at most {MAX_SQUARER_SPLIT}"
        );
        let v = self.bits(sig, lo + r - 1, lo);
        // one entry a line; v = 0 squares to 0 and adds nothing
        let e = Builder::one_of(
            &v,
            r,
            (1..1u128 << r).map(|x| (x, Expr::constant(lit(2 * r, x * x)))),
            2 * r,
        );
        self.wire(name, 2 * r, Kind::Table, e, comment);
        // a function of more inputs than a LUT has: two levels
        self.delay(if r > LUT_INPUTS {
            2.0 * LUT_DELAY
        } else {
            LUT_DELAY
        });
    }

    /// Adds a constant table to the unit; returns its index for [`Builder::rom_read`].
    pub fn table(&mut self, t: Table) -> usize {
        self.tables.push(t);
        self.tables.len() - 1
    }

    /// Defines `signal` in the current step as the entry of table `t` addressed by all of
    /// the signal `addr` (the template renders the memory and the read).
    pub(crate) fn rom_read(&mut self, signal: &str, t: usize, addr: &str) {
        let a = self.r(addr);
        let cur = self.cur();
        self.define(signal, self.tables[t].width, cur, false);
        let position = self.steps.last().expect("a step").wires.len();
        self.reads.push(RomRead {
            step: cur,
            signal: signal.into(),
            table: t,
            addr: a.text,
            block: false,
            position,
        });
    }

    /// [`Builder::rom_read`], on ECP5 block RAM with its registers when the table has at most
    /// 1024 words of at most [`MAX_BLOCK_SLICES`]·18 bits (one DP16KD, 1024 x 18, per 18 bits
    /// of the word) and the cuts on both sides of this step are registered: the address
    /// registers take the address as the step before sees it, the output registers are the cut
    /// after this step (the read's clock-to-out, 5.6 ns without them on LFE5U-25F grade 6,
    /// then never limits Fmax). Anywhere else, an asynchronous read in this step.
    ///
    /// With `--rom-style logic` ([`Builder::tables_in_logic`]) the table is LUTs instead: its
    /// parts in this step ([`Builder::rom_parts`]), then a step for each pick among them
    /// ([`Builder::rom_pick`], four to one), `signal` the last; what the caller writes after this
    /// call goes in the last of them.
    pub(crate) fn rom_read_registered(&mut self, signal: &str, t: usize, addr: &str) {
        if self.logic_tables {
            let copies = self.family().copies_table_address();
            let (mut parts, mut lo) = self.rom_parts_of(signal, t, addr, LOGIC_PART_BITS, copies);
            let what = self.tables[t].what.clone();
            // (at least two parts: the last pick is `signal` itself)
            while parts.len() > 1 {
                self.step(&format!(
                    "{what} (in LUTs): the entry picked by {addr}'s bits from {lo}"
                ));
                (parts, lo) = self.rom_pick_of(signal, t, addr, &parts, lo, 1);
            }
            return;
        }
        // up to 1024 words, or two banks of them addressed by a whole 11-bit signal
        let words = self.tables[t].words.len();
        let banks =
            words > DP16KD_WORDS && words <= 2 * DP16KD_WORDS && self.signal(addr).width == 11;
        let fits = (words <= DP16KD_WORDS || banks)
            && self.tables[t].width <= MAX_BLOCK_SLICES * DP16KD_BITS;
        if !(fits && self.block_registers_here()) {
            return self.rom_read(signal, t, addr);
        }
        let a = self.seen_from_step_before(&[addr], &format!("the block read of {signal}"), |s| {
            s.r(addr)
        });
        let k = self.steps.len();
        self.define(signal, self.tables[t].width, k, true);
        let position = self.steps.last().expect("a step").wires.len();
        self.reads.push(RomRead {
            step: k,
            signal: signal.into(),
            table: t,
            addr: a.text,
            block: true,
            position,
        });
    }
}
