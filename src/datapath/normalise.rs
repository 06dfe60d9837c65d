//! Normalising: the leading zeros of a word, the way blinn's `c` and schlick's denominator
//! find their exponents.

use super::*;

impl Builder {
    /// `out` = the leading zeros of `src`'s bits `[top − 1 : top − width]` (`width` when they
    /// are all 0), `out_bits` wide, in two LUT steps: in the current step, per group of 4
    /// bits from the top, whether it has a one (`{prefix}_any{k}`) and where its first one is
    /// (`{prefix}_zeros{k}`); then a step titled `title` that picks the first group with a
    /// one. `what` names the word in the comments. The second step is left open (its delay
    /// is the caller's, who may add beside `out`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn leading_zeros(
        &mut self,
        prefix: &str,
        src: &str,
        top: u32,
        width: u32,
        out: &str,
        out_bits: u32,
        what: &str,
        title: &str,
        comment: &str,
    ) {
        let groups: Vec<(u32, u32)> = (0..width.div_ceil(4))
            .map(|k| (top - 4 * k, (width - 4 * k).min(4)))
            .collect(); // (top + 1, width)
        assert!(
            out_bits >= 2
                && groups.len() as u128 <= 1u128 << (out_bits - 2)
                && (width as u128) < 1u128 << out_bits,
            "datapath: {out} is too narrow for {width} bits"
        );
        // each group's (has a one, leading zeros)
        let mut leads = Vec::new();
        for (k, &(hi, gw)) in groups.iter().enumerate() {
            let bits = self.bits(src, hi - 1, hi - gw);
            let any = self.wire(
                &format!("{prefix}_any{k}"),
                1,
                Kind::Logic,
                ex!("|{}", bits),
                &format!("bits [{}:{}] of {what} have a one", hi - 1, hi - gw),
            );
            // its first one at j from the top: bits above it 0, bit j 1 (the last j: when the
            // group has a one, it is there if nowhere above); each bit of j an OR of those
            // conditions, no ?: of constants ([`Builder::select`])
            let bit = |b: &mut Builder, j: u32| b.bits(src, hi - 1 - j, hi - 1 - j);
            let first_at: Vec<Expr> = (0..gw)
                .map(|j| {
                    let mut terms: Vec<Expr> = (0..j).map(|i| ex!("~{}", bit(self, i))).collect();
                    if j + 1 < gw {
                        terms.push(bit(self, j));
                    }
                    if terms.is_empty() {
                        Expr::constant("1'b1")
                    } else {
                        ex!("({})", Expr::join(&terms, " & "))
                    }
                })
                .collect();
            let lz_bit = |v: u32| {
                let ors: Vec<Expr> = (0..gw)
                    .filter(|j| j >> v & 1 == 1)
                    .map(|j| first_at[j as usize].clone())
                    .collect();
                if ors.is_empty() {
                    Expr::constant("1'b0")
                } else {
                    Expr::join(&ors, " | ")
                }
            };
            let (b1, b0) = (lz_bit(1), lz_bit(0));
            leads.push((
                any,
                self.wire(
                    &format!("{prefix}_zeros{k}"),
                    2,
                    Kind::Logic,
                    ex!("{{{},\n    {}}}", b1, b0),
                    "its leading zeros (when it has a one)",
                ),
            ));
        }
        self.delay(LUT_DELAY);
        self.step(title);
        if leads.len() <= 2 {
            // each bit of the pick a function of at most 4 inputs: one LUT
            let mut cases = Vec::new();
            for (k, (any, lz)) in leads.iter().enumerate() {
                let (any, lz) = (self.r(any), self.r(lz));
                cases.push(ex!(
                    "{} ? {{{}, {}}}",
                    any,
                    lit(out_bits - 2, k as u128),
                    lz
                ));
            }
            cases.push(Expr::constant(lit(out_bits, width as u128)));
            self.wire(
                out,
                out_bits,
                Kind::Logic,
                Expr::join(&cases, "\n    : "),
                comment,
            );
            return;
        }
        // more groups: the pick in two LUT levels, the first kept ([`Builder::wire_kept`]): per
        // pair of groups, whether it has a one and its first one's leading zeros; then the
        // group's index from the groups' flags, and the zeros from the first pair with a one
        // (a function of 2 inputs a pair, at most 4 for 2 pairs: yosys 0.70's ABC9 made the
        // one ?: chain over 4 groups three LUT levels)
        let mut pairs = Vec::new();
        for (m, pair) in leads.chunks(2).enumerate() {
            let (a_any, a_lz) = (self.r(&pair[0].0), self.r(&pair[0].1));
            if pair.len() == 1 {
                pairs.push((a_any, a_lz));
                continue;
            }
            let (b_any, b_lz) = (self.r(&pair[1].0), self.r(&pair[1].1));
            let has = self.wire_kept(
                &format!("{prefix}_pair_any{m}"),
                1,
                Kind::Logic,
                ex!("{} | {}", a_any, b_any),
                &format!("groups {} and {} have a one", 2 * m, 2 * m + 1),
            );
            let lz = self.wire_kept(
                &format!("{prefix}_pair_zeros{m}"),
                2,
                Kind::Logic,
                ex!("{} ? {} : {}", a_any, a_lz, b_lz),
                "the leading zeros of the first of them with a one",
            );
            pairs.push((self.r(&has), self.r(&lz)));
        }
        // both as AND-ORs ([`Builder::first_of`]): a ?: chain ending in a constant before a
        // register is the register's synchronous set/reset to yosys, driven by logic
        let anys: Vec<Expr> = leads.iter().map(|(any, _)| self.r(any)).collect();
        let cases: Vec<(Expr, Expr)> = anys
            .iter()
            .enumerate()
            .map(|(k, a)| (a.clone(), Expr::constant(lit(out_bits - 2, k as u128))))
            .collect();
        let e = Builder::first_of(
            &cases,
            &Expr::constant(lit(out_bits - 2, (width >> 2) as u128)),
            out_bits - 2,
        );
        let group = format!("{prefix}_group");
        self.wire(
            &group,
            out_bits - 2,
            Kind::Logic,
            e,
            "the first group with a one",
        );
        let e = Builder::first_of(&pairs, &Expr::constant(lit(2, (width & 3) as u128)), 2);
        let lz = format!("{prefix}_zeros");
        self.wire(&lz, 2, Kind::Logic, e, "its leading zeros");
        let (g, z) = (self.r(&group), self.r(&lz));
        self.wire(
            out,
            out_bits,
            Kind::Select,
            ex!("{{{}, {}}}", g, z),
            comment,
        );
    }

    /// One level of a left shift by a signal, a 2:1 mux: `name = amount[s] ? src·2^(2^s) :
    /// src` over `width` bits, `src` zero-extended to them (the bits shifted past the top
    /// dropped). A shift by all of `amount` is one such level a step, from its top bit: the
    /// bit that fans out over the whole word drives one LUT level.
    pub(crate) fn shift_left_level(
        &mut self,
        name: &str,
        src: &str,
        amount: &str,
        s: u32,
        width: u32,
        what: &str,
    ) -> Sig {
        let sw = self.signal(src).width;
        let v = if sw == width {
            self.r(src)
        } else {
            self.zext(src, width)
        };
        let keep = sw.min(width - (1 << s));
        let mut parts = Vec::new();
        if width - (1 << s) > keep {
            parts.push(Expr::constant(lit(width - (1 << s) - keep, 0)));
        }
        parts.push(self.bits(src, keep - 1, 0));
        parts.push(Expr::constant(lit(1 << s, 0)));
        let shifted = ex!("{{{}}}", Expr::join(&parts, ", "));
        let bit = self.bits(amount, s, s);
        self.wire(
            name,
            width,
            Kind::Logic,
            Builder::select(&bit, &shifted, &v, width),
            what,
        )
    }
}
