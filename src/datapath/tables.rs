//! Tables written as logic (`--rom-style logic`): a table's parts, each a function of the
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
