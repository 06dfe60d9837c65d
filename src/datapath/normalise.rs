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
    pub(crate) fn leading_zeros(&mut self, prefix: &str, src: &str, top: u32, width: u32, out: &str, out_bits: u32, what: &str, title: &str, comment: &str) {
        let groups: Vec<(u32, u32)> = (0..width.div_ceil(4)).map(|k| (top - 4 * k, (width - 4 * k).min(4))).collect(); // (top + 1, width)
        assert!(
            out_bits >= 2 && groups.len() as u128 <= 1u128 << (out_bits - 2) && (width as u128) < 1u128 << out_bits,
            "datapath: {out} is too narrow for {width} bits"
        );
        // each group's (has a one, leading zeros)
        let mut leads = Vec::new();
        for (k, &(hi, gw)) in groups.iter().enumerate() {
            let bits = self.bits(src, hi - 1, hi - gw);
            let any = self.wire(&format!("{prefix}_any{k}"), 1, Kind::Logic, ex!("|{}", bits), &format!("bits [{}:{}] of {what} have a one", hi - 1, hi - gw));
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
                let ors: Vec<Expr> = (0..gw).filter(|j| j >> v & 1 == 1).map(|j| first_at[j as usize].clone()).collect();
                if ors.is_empty() {
                    Expr::constant("1'b0")
                } else {
                    Expr::join(&ors, " | ")
                }
            };
            let (b1, b0) = (lz_bit(1), lz_bit(0));
            leads
                .push((any, self.wire(&format!("{prefix}_zeros{k}"), 2, Kind::Logic, ex!("{{{},\n    {}}}", b1, b0), "its leading zeros (when it has a one)")));
        }
        self.delay(LUT_DELAY);
        self.step(title);
        let mut cases = Vec::new();
        for (k, (any, lz)) in leads.iter().enumerate() {
            let (any, lz) = (self.r(any), self.r(lz));
            cases.push(ex!("{} ? {{{}, {}}}", any, lit(out_bits - 2, k as u128), lz));
        }
        cases.push(Expr::constant(lit(out_bits, width as u128)));
        self.wire(out, out_bits, Kind::Logic, Expr::join(&cases, "\n    : "), comment);
    }

    /// One level of a left shift by a signal, a 2:1 mux: `name = amount[s] ? src·2^(2^s) :
    /// src` over `width` bits, `src` zero-extended to them (the bits shifted past the top
    /// dropped). A shift by all of `amount` is one such level a step, from its top bit: the
    /// bit that fans out over the whole word drives one LUT level.
    pub(crate) fn shift_left_level(&mut self, name: &str, src: &str, amount: &str, s: u32, width: u32, what: &str) -> Sig {
        let sw = self.signal(src).width;
        let v = if sw == width { self.r(src) } else { self.zext(src, width) };
        let keep = sw.min(width - (1 << s));
        let mut parts = Vec::new();
        if width - (1 << s) > keep {
            parts.push(Expr::constant(lit(width - (1 << s) - keep, 0)));
        }
        parts.push(self.bits(src, keep - 1, 0));
        parts.push(Expr::constant(lit(1 << s, 0)));
        let shifted = ex!("{{{}}}", Expr::join(&parts, ", "));
        let bit = self.bits(amount, s, s);
        self.wire(name, width, Kind::Logic, Builder::select(&bit, &shifted, &v, width), what)
    }
}
