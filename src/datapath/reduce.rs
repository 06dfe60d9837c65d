//! Wide reductions written as the two LUT levels they take: the first level's LUTs kept
//! ([`Builder::wire_kept`]), so no mapper chains them deeper.

use super::*;

impl Builder {
    /// The OR of `bits` (Verilog bit expressions, most significant first) as at most `room`
    /// terms (`room` ≤ [`LUT_INPUTS`]), for the caller to combine (with `4 − room` other
    /// inputs) in one LUT: up to `room` bits are their own terms; more are ORed per group of up
    /// to 4 into kept wires `{name}_any{k}` ([`Builder::or_groups`]), and those again where
    /// they are still too many. `what` names the word the bits are of, in the comments.
    pub(crate) fn or_terms(
        &mut self,
        name: &str,
        bits: Vec<Expr>,
        room: u32,
        what: &str,
    ) -> Vec<Expr> {
        assert!(
            (1..=LUT_INPUTS).contains(&room),
            "datapath: {name}: room for {room} terms"
        );
        if bits.len() as u32 <= room {
            return bits;
        }
        let terms = self
            .or_groups(name, bits, what)
            .iter()
            .map(|g| self.r(g))
            .collect();
        self.or_terms(&format!("{name}_l"), terms, room, what)
    }

    /// The OR of `bits` (most significant first) per group of up to 4, as kept wires
    /// `{name}_any{k}` in this step (a lone bit of a group is a wire too): their names, for a
    /// later step to OR in one LUT (up to 4 groups: 16 bits).
    pub(crate) fn or_groups(&mut self, name: &str, bits: Vec<Expr>, what: &str) -> Vec<String> {
        let groups = bits.len().div_ceil(LUT_INPUTS as usize);
        let per = bits.len().div_ceil(groups.max(1));
        let mut names = Vec::new();
        for (k, group) in bits.chunks(per.max(1)).enumerate() {
            let any = format!("{name}_any{k}");
            self.wire_kept(
                &any,
                1,
                Kind::Logic,
                Expr::join(group, " | "),
                &format!("{what}: {} of its bits, any set", group.len()),
            );
            names.push(any);
        }
        names
    }

    /// `src[hi:lo]`'s bits, most significant first, one expression each.
    pub(crate) fn bit_list(&mut self, src: &str, hi: u32, lo: u32) -> Vec<Expr> {
        (lo..=hi).rev().map(|i| self.bits(src, i, i)).collect()
    }
}
