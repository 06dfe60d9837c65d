//! The colours' end of every datapath: the colour products and sums (in blocks or the fabric),
//! their copies and rounding, the results, and the intensity rounded half up.

use super::*;

impl Builder {
    /// The colour multipliers (14–16) with the colours' rounding half as their addend, one
    /// multiply-add each (on a DSP block, the add is its post-adder):
    /// `color_sum_X = v·ks_X + 2^(wc−1)`, `B + wc` bits, for the `wc + 1`-bit UQ1.wc signal `v`
    /// (`what` names the value in the comments). [`Builder::colour_results`] takes the outputs.
    /// `after`: the delay of the logic behind the products in the same step.
    pub(crate) fn colour_sums(&mut self, v: &str, wc: u32, what: &str, after: Delay) {
        self.colour_sums_of([v; 3], wc, what, after)
    }

    /// [`Builder::colour_sums`] of one signal per channel (`vs`, in [`CHANNELS`]' order).
    fn colour_sums_of(&mut self, vs: [&str; 3], wc: u32, what: &str, after: Delay) {
        let bb = self.colour_bits();
        let cp = wc + bb;
        let vps = vs.map(|v| {
            let vw = self.signal(v).width;
            [Piece::sig(v, 0, vw)]
        });
        let ks = CHANNELS.map(|ch| [Piece::sig(&format!("ks_{ch}"), 0, bb)]);
        let items: Vec<MulItem> = CHANNELS
            .iter()
            .zip(&ks)
            .zip(&vps)
            .map(|((ch, k), vp)| MulItem {
                name: format!("color_sum_{ch}"),
                a: (vp, wc + 1),
                b: (k, bb),
                addend: vec![Piece::Const {
                    value: 1u128 << (wc - 1),
                    width: cp,
                }],
                comment: format!("UQ{bb}.{wc}: {what}*ks_{ch} + 1/2 colour ulp"),
            })
            .collect();
        self.muls(&items, cp, after);
    }

    /// The colour multipliers (14–16) in this step, for the `wc + 1`-bit UQ1.wc field of `src`
    /// from bit `lo` (`what` names the value). Where the DSP block has a post-adder (iCE40,
    /// generic) one multiply-add each with the colours' rounding half as its addend
    /// (`color_power`, then [`Builder::colour_sums`]); on the ECP5, whose MULT18X18D has none,
    /// the products alone (`color_prod_X`, on blocks with their own registers where the cuts
    /// allow), and [`Builder::colour_rounding`] adds the half in a later step.
    pub(crate) fn colour_products(&mut self, src: &str, lo: u32, wc: u32, what: &str) {
        if !self.family().instantiated_blocks() {
            if self.signals.iter().any(|s| s.name == "color_power_r") {
                // a copy per channel, made the step before ([`Builder::colour_copies`])
                self.colour_sums_of(
                    ["color_power_r", "color_power_g", "color_power_b"],
                    wc,
                    what,
                    Delay::ZERO,
                );
                return;
            }
            let cs = self.bits(src, lo + wc, lo);
            self.wire(
                "color_power",
                wc + 1,
                Kind::Select,
                cs,
                &format!("UQ1.{wc}: {what} floored to what the colours' budget needs"),
            );
            self.colour_sums("color_power", wc, what, Delay::ZERO);
            return;
        }
        let bb = self.colour_bits();
        for ch in CHANNELS {
            let (v, k) = (
                Piece::sig(src, lo, wc + 1),
                Piece::sig(&format!("ks_{ch}"), 0, bb),
            );
            self.product(
                &format!("color_prod_{ch}"),
                &[v],
                &[k],
                wc + bb,
                &format!("UQ{bb}.{wc}: {what}*ks_{ch}, {what} floored to what the colours' budget needs, exact"),
            );
        }
    }

    /// Before [`Builder::colour_products`], where the family registers a block's operand once
    /// per block (`Family::copies_block_operands`): a step with the UQ1.wc field of `src` from
    /// bit `lo` once per channel, `color_power_X`, each its own register at the cut (kept: a
    /// block reads it; and a copy, [`Datapath::copies`], its flip-flop kept too, or both yosys
    /// merge the three), which place-and-route puts by its block. `always`: whatever the plan;
    /// otherwise only with `--fabric-registers` ([`Builder::registers_in_fabric`]), so the
    /// calibrated shapes of the models that do without it stay as they are.
    pub(crate) fn colour_copies(&mut self, src: &str, lo: u32, wc: u32, what: &str, always: bool) {
        if !self.family().copies_block_operands()
            || self.family().instantiated_blocks()
            || !(always || self.fabric_registers)
        {
            return;
        }
        // a step of its own: each copy's register then takes its value from a register, not
        // from the logic before it, and can sit by its block (packed with a LUT of that logic,
        // one held blinn's colour products at 118 MHz)
        self.step(&format!(
            "colour multipliers: {what}'s colour field once per block"
        ));
        self.delay(REGISTER_ONLY_DELAY);
        for ch in CHANNELS {
            let cs = self.bits(src, lo + wc, lo);
            self.wire(
                &format!("color_power_{ch}"),
                wc + 1,
                Kind::Select,
                cs,
                &format!("UQ1.{wc}: {what} floored to what the colours' budget needs, for ks_{ch}"),
            );
            // three registers of one value: kept as flip-flops of their own, or yosys 0.23
            // merges them into one that reaches all three blocks (a 7.0 ns route from the
            // fabric to fitted's colour SB_MAC16 at 118.3 MHz)
            self.copies.push(format!("color_power_{ch}"));
        }
        // with route registers, each copy twice: one flip-flop by the logic before, one by
        // its block (a 6.8 ns route from the first to fitted's colour SB_MAC16: 120.6 MHz)
        self.route_register_step(&format!(
            "colour multipliers: {what}'s colour field again, by its block"
        ));
    }

    /// The ECP5's colour rounding after [`Builder::colour_products`], in this step:
    /// `color_sum_X = color_prod_X + 2^(wc−1)` on carry chains (elsewhere nothing: the half was
    /// the multiply-add's addend).
    pub(crate) fn colour_rounding(&mut self, wc: u32, what: &str) {
        if !self.family().instantiated_blocks() {
            return;
        }
        let cp = wc + self.colour_bits();
        for ch in CHANNELS {
            let half = Piece::Const {
                value: 1u128 << (wc - 1),
                width: wc,
            };
            let comment = format!("UQ{}.{wc}: {what}*ks_{ch} + 1/2 colour ulp", cp - wc);
            self.add(
                &format!("color_sum_{ch}"),
                &[Piece::sig(&format!("color_prod_{ch}"), 0, cp)],
                &[half],
                false,
                cp,
                &comment,
            );
        }
    }

    /// The colour outputs `spec_X` from `color_sum_X` (`B + wc` bits, the rounding half in it):
    /// its top B bits, the colour rounded half up.
    pub(crate) fn colour_results(&mut self, wc: u32, what: &str) {
        let bb = self.colour_bits();
        for ch in CHANNELS {
            let e = self.bits(&format!("color_sum_{ch}"), wc + bb - 1, wc);
            self.wire(
                &format!("spec_{ch}"),
                bb,
                Kind::Select,
                e,
                &format!("UNORM{bb}: {what}*ks_{ch} rounded half up"),
            );
        }
    }

    /// The last step, titled so: the intensity `src` (UQ1.`frac`, `what` in the comments)
    /// rounded half up to FI fractional bits by a carry-select add over the bits that matter
    /// (`(src[frac:frac−FI−1] + 1) >> 1`), `done` read off `src` beside it (the intensity is 0
    /// exactly when `src < 2^−(FI+1)`: its bits from there up all 0, per group of 4 here and
    /// all of them in the add's last step), and the colours' results (on the ECP5 their
    /// rounding half added here, after their products).
    pub(crate) fn round_intensity(&mut self, src: &str, frac: u32, fi: u32, wc: u32, what: &str) {
        self.step("the intensity rounding: chunk sums; done");
        // round half up on the bits that matter: (src[frac:frac-FI-1] + 1) >> 1
        let p = self.add_start(
            "intensity_sum",
            &[Piece::sig(src, frac - fi - 1, fi + 2)],
            &[],
            true,
            fi + 2,
            &format!(
                "UQ1.{}: {what} to 2^-{} plus one ulp = {what} + 2^-{} (round half up)",
                fi + 1,
                fi + 1,
                fi + 1
            ),
        );
        let (lo, hi) = (frac - fi - 1, self.signal(src).width);
        let mut groups = Vec::new();
        for (k, g) in (lo..hi).step_by(4).enumerate() {
            let gh = (g + 4).min(hi);
            let bits = self.bits(src, gh - 1, g);
            let name = format!("done_zero{k}");
            self.wire(
                &name,
                1,
                Kind::Logic,
                ex!("~|{}", bits),
                &format!("bits [{}:{g}] of {what} are 0", gh - 1),
            );
            groups.push(name);
        }
        self.colour_rounding(wc, what);
        let sum = self.resolve(p, "the intensity rounded half up");
        let zeros: Vec<Expr> = groups.iter().map(|g| self.r(g)).collect();
        self.wire(
            "done",
            1,
            Kind::Logic,
            Expr::join(&zeros, " & "),
            "the highlight is below the output's resolution (the intensity rounds to 0)",
        );
        self.colour_results(wc, what);
        let e = self.bits(&sum, fi + 1, 1);
        self.wire(
            "intensity",
            fi + 1,
            Kind::Select,
            e,
            &format!("UQ1.{fi}: {what} rounded half up"),
        );
    }

    /// B: the width of the colour ports.
    pub(super) fn colour_bits(&self) -> u32 {
        self.signals
            .iter()
            .find(|s| s.name == "ks_r")
            .expect("the colour ports are inputs")
            .width
    }
}
