//! The builder's core: signals and their versions across cuts, steps, wires, products,
//! tables and the colour steps every model ends with; `finish` works out what is alive.

use super::*;

impl Builder {
    /// The family the datapath is shaped for.
    pub(crate) fn family(&self) -> &'static dyn crate::family::Family {
        crate::family::of(self.target)
    }

    /// Whether the family's products and table reads are blocks instantiated with their own
    /// registers (no post-adder; one carry chain a step): `Family::instantiated_blocks`.
    pub(crate) fn instantiated_blocks(&self) -> bool {
        self.family().instantiated_blocks()
    }

    /// `inputs`: the port signals, available from cut 0; `registered`: the cuts that hold a
    /// pipeline register (a reference resolves to the last of them before it, or to the
    /// defining wire when there is none: a combinational cut emits nothing).
    pub fn new(inputs: &[(&str, u32)], registered: &[u32], target: Target) -> Builder {
        Builder {
            steps: Vec::new(),
            signals: inputs
                .iter()
                .map(|&(n, w)| Signal {
                    name: n.into(),
                    width: w,
                    step: 0,
                    uses: Vec::new(),
                    dsp_registered: false,
                    held: None,
                })
                .collect(),
            tables: Vec::new(),
            reads: Vec::new(),
            registered: registered.to_vec(),
            target,
            view: None,
            chunk_limit: u32::MAX,
            read: BTreeMap::new(),
            products: Vec::new(),
            shifted_products: Vec::new(),
            copies: Vec::new(),
            product_uses: Vec::new(),
            fabric: Default::default(),
            logic_tables: false,
            fabric_registers: false,
        }
    }

    /// Writes every table read with [`Builder::rom_read_registered`] as LUTs (`--rom-style
    /// logic`, the plan's choice): no memory, so no block RAM's clock limit.
    pub(crate) fn tables_in_logic(&mut self, yes: bool) {
        self.logic_tables = yes;
    }

    /// Gives each hard block a fabric flip-flop on the routes to and from it
    /// ([`Builder::fabric_register_step`]; `--fabric-registers`, the plan's choice).
    pub(crate) fn registers_in_fabric(&mut self, yes: bool) {
        self.fabric_registers = yes;
    }

    /// Makes the input `name` one held in the register `register` for every pixel (a static
    /// colour): every step reads that register, and no cut carries it.
    pub fn hold(&mut self, name: &str, register: &str) {
        let s = self.signal(name);
        assert_eq!(s.step, 0, "datapath: only an input can be held");
        s.held = Some(register.to_string());
    }

    /// The step references are made from: the current one, or the one before a registered
    /// DSP while its operands are written.
    pub(super) fn cur(&self) -> usize {
        self.view.unwrap_or(self.steps.len())
    }

    pub fn target(&self) -> Target {
        self.target
    }

    /// The widest multiplier operand one DSP block takes on the target (generic: no limit).
    pub(crate) fn dsp_bits(&self) -> u32 {
        self.family().multiplier_bits()
    }

    /// Where a constant operand `k` of a hard product is split, `k = k_hi·2^s + k_lo`: the
    /// block's width, or below it while the family does not take the low part whole
    /// ([`crate::family::Family::takes_constant`]); `k` narrower than `s` is not split.
    pub(crate) fn constant_split(&self, k: u128) -> u32 {
        let low = |s: u32| if s >= 128 { k } else { k & ((1u128 << s) - 1) };
        let mut s = self.dsp_bits();
        while s > 1 && !self.family().takes_constant(low(s)) {
            s -= 1;
        }
        s
    }

    /// The longest carry chain one step holds on the target (generic: no limit).
    pub(crate) fn chunk_bits(&self) -> u32 {
        self.family().carry_chunk_bits()
    }

    pub(super) fn is_registered(&self, cut: usize) -> bool {
        self.registered.contains(&(cut as u32))
    }

    /// Whether the current step can be one ECP5 block (DSP or block RAM) with its registers:
    /// the cuts on both sides registered, the one before being a cut (not the input ports).
    pub(super) fn block_registers_here(&self) -> bool {
        let k = self.steps.len();
        self.family().instantiated_blocks()
            && k >= 2
            && self.is_registered(k - 1)
            && self.is_registered(k)
    }

    /// Runs `f` with references taken as the step before sees them, where a block's input
    /// registers take its inputs; each of `inputs` must be visible there (defined before it,
    /// and not another block's output registered at its end).
    pub(super) fn seen_from_step_before<T>(
        &mut self,
        inputs: &[&str],
        what: &str,
        f: impl FnOnce(&mut Self) -> T,
    ) -> T {
        let k = self.steps.len();
        for n in inputs {
            assert!(
                self.visible_before(n),
                "datapath: {n} is not visible in step {} for {what}",
                k - 1
            );
        }
        self.view = Some(k - 1);
        let out = f(self);
        self.view = None;
        out
    }

    /// Whether `name` is visible in the step before the current one, where a block's input
    /// registers take their operands: defined before the current step, and not another block's
    /// output registered at the cut between the two.
    pub(super) fn visible_before(&mut self, name: &str) -> bool {
        let k = self.steps.len();
        let s = self.signal(name);
        s.step < k && !(s.dsp_registered && s.step + 1 == k)
    }

    /// Records a new signal defined in `step` (`dsp_registered`: held by a block's output
    /// register at the cut after it).
    pub(super) fn define(&mut self, name: &str, width: u32, step: usize, dsp_registered: bool) {
        assert!(
            self.signals.iter().all(|s| s.name != name),
            "datapath: {name} defined twice"
        );
        self.signals.push(Signal {
            name: name.into(),
            width,
            step,
            uses: Vec::new(),
            dsp_registered,
            held: None,
        });
    }

    /// `name = a·b mod 2^width` (operands zero-extended; `width` at most their two widths
    /// summed keeps it exact). On ECP5, when both operands fit 18 bits and the cuts on both
    /// sides of this step are registered, one MULT18X18D with its own registers: its input
    /// registers are the cut before (they take the operands as the step before sees them, so
    /// no fabric register holds them), its output register is the cut after (the product is
    /// `name_cK` from there). Anywhere else, a `*` the synthesis tool maps.
    pub fn product(&mut self, name: &str, a: &[Piece], b: &[Piece], width: u32, comment: &str) {
        let (wa, wb) = (
            a.iter().map(Piece::width).sum::<u32>(),
            b.iter().map(Piece::width).sum::<u32>(),
        );
        let inputs: Vec<String> = a
            .iter()
            .chain(b)
            .filter_map(|p| {
                if let Piece::Sig { name, .. } = p {
                    Some(name.clone())
                } else {
                    None
                }
            })
            .collect();
        // an operand that is another block's output registered at the cut before cannot also
        // be this block's input register: then a `*` the tool maps
        let visible = inputs.iter().all(|n| self.visible_before(n));
        let on_dsp = visible
            && self.block_registers_here()
            && wa.max(wb) <= ECP5_DSP_BITS
            && width <= 2 * ECP5_DSP_BITS;
        if !on_dsp || self.is_in_fabric(name) {
            self.mul(name, width, (a, wa), (b, wb), &[], Delay::ZERO, comment);
            return;
        }
        self.count_product(name, wa, wb, width);
        self.product_delay(wa, wb, width, Delay::ZERO);
        let inputs: Vec<&str> = inputs.iter().map(String::as_str).collect();
        let (ea, eb) = self.seen_from_step_before(&inputs, &format!("the DSP of {name}"), |s| {
            (
                s.pieces(&sub_pieces(a, 0, ECP5_DSP_BITS)).text,
                s.pieces(&sub_pieces(b, 0, ECP5_DSP_BITS)).text,
            )
        });
        self.define(name, width, self.steps.len(), true);
        self.steps.last_mut().expect("a step").dsps.push(Dsp {
            name: name.into(),
            width,
            a: ea,
            b: eb,
            comment: comment.into(),
        });
    }

    /// `name = a·b + addend mod 2^width` (operands zero-extended), starting in this step.
    /// Where the DSP block's post-adder takes it, one multiply-add (the add inside the block):
    /// generic, and the iCE40's SB_MAC16 when the sum is no wider than the product's operands
    /// together (yosys 0.23 leaves a wider add in the fabric, on the product's unregistered
    /// output). Elsewhere (and always on the ECP5, whose MULT18X18D has no adder) the product
    /// `name_prod` alone here ([`Builder::product`]: on a block with its own registers where
    /// the cuts allow), then the add over the bits above the addend's low zeros in steps of its
    /// own, titled `title`: one carry chain on the ECP5, a carry-select add on the iCE40.
    /// Returns the name of the sum.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn multiply_add(
        &mut self,
        name: &str,
        a: &[Piece],
        b: &[Piece],
        addend: &[Piece],
        width: u32,
        title: &str,
        comment: &str,
    ) -> Sig {
        let (wa, wb) = (
            a.iter().map(Piece::width).sum::<u32>(),
            b.iter().map(Piece::width).sum::<u32>(),
        );
        let post_adder = self.family().post_adder(width, wa, wb);
        if post_adder {
            // an addend of constant zeros is none
            let addend = match all_zero(&sub_pieces(addend, 0, width)) {
                true => Vec::new(),
                false => addend.to_vec(),
            };
            let sum = self.mul(
                name,
                width,
                (a, wa),
                (b, wb),
                &addend,
                Delay::ZERO,
                &format!("{comment} (one DSP, the add inside it)"),
            );
            // (the block's output read by the fabric from a flip-flop of its own)
            self.fabric_register_step(&format!("{title}: the sum registered in the fabric"));
            return sum;
        }
        let product = format!("{name}_prod");
        let pw = width.min(wa + wb);
        self.product(
            &product,
            a,
            b,
            pw,
            &format!("the product alone (one DSP), exact: {pw} bits"),
        );
        // the addend's low zero bits: the sum there is the product's
        let mut z = 0;
        for p in addend {
            match p {
                Piece::Const { value: 0, width } => z += width,
                _ => break,
            }
        }
        let z = z.min(pw);
        let hi = if z == 0 {
            name.to_string()
        } else {
            format!("{name}_hi")
        };
        let mut pb = sub_pieces(addend, z, width - z);
        if pb
            .iter()
            .any(|p| matches!(p, Piece::Sig { invert: true, .. }))
        {
            // a complemented addend is formed here, beside the product: a carry chain's
            // operand takes no inverter, which would be a LUT level before it
            let e = self.pieces(&pb);
            let (aname, aw) = (format!("{name}_addend"), width - z);
            self.wire(
                &aname,
                aw,
                Kind::Logic,
                e,
                &format!("bits [{}:{z}] of the addend of {name}", width - 1),
            );
            pb = vec![Piece::sig(&aname, 0, aw)];
        }
        let pa = [Piece::sig(&product, z, pw - z)];
        self.fabric_register_step(&format!("{title}: the product registered in the fabric"));
        self.step(&format!("{title}: the add after the product"));
        let what = if z == 0 {
            comment.to_string()
        } else {
            format!("bits [{}:{z}] of {name}", width - 1)
        };
        if self.family().instantiated_blocks() {
            self.add(&hi, &pa, &pb, false, width - z, &what);
        } else {
            let p = self.add_start(&hi, &pa, &pb, false, width - z, &what);
            self.resolve(p, title);
        }
        if z > 0 {
            let (h, l) = (self.r(&hi), self.bits(&product, z - 1, 0));
            self.wire(name, width, Kind::Select, ex!("{{{}, {}}}", h, l), comment);
        }
        self.sig(name)
    }

    /// On the ECP5 only, a step titled `title` that only registers, where one flip-flop cannot
    /// serve two blocks or a long route needs a flip-flop at its start: before a DP16KD's
    /// address register when a carry chain or mux computes the address (blinn's log table
    /// address set the clock at 186–208 MHz over 5 seeds without it), and after a block RAM's
    /// output register when a MULT18X18D's input registers take the word next. The step is
    /// there whatever the cuts, so the datapath's shape does not depend on them.
    pub(crate) fn ecp5_register_step(&mut self, title: &str) {
        if self.family().instantiated_blocks() {
            self.register_only_step(title);
        }
    }

    /// With `--fabric-registers` ([`Builder::registers_in_fabric`]; implied by `--rom-style
    /// logic`), on a family with hard multipliers, a step that only registers, titled `title`,
    /// between a block's output and the logic that reads it, or between a carry chain and the
    /// block it feeds: the product leaves its block into a flip-flop of the fabric's, so the
    /// logic does not share a stage with the route out of the block's column and the one into
    /// the next block (ECP5 grade 6, 4.6-5.4 ns: schlick 203.6 MHz, blinn 214.7, fitted 215.9
    /// without it; UP5K, a 4.7 ns route from an SB_MAC16: schlick 111.3). Elsewhere nothing
    /// (the shapes the delay model is calibrated on stay as they are).
    pub(crate) fn fabric_register_step(&mut self, title: &str) {
        // (one such step is enough: none right after another with nothing in it)
        let just_registered = self.steps.last().is_some_and(|s| {
            s.wires.is_empty() && s.dsps.is_empty() && s.delay == REGISTER_ONLY_DELAY
        });
        if self.fabric_registers && self.family().dsp_capacity().is_some() && !just_registered {
            self.register_only_step(title);
        }
    }

    /// With `--fabric-registers` ([`Builder::registers_in_fabric`]) on a family whose blocks
    /// yosys infers (the iCE40: its fabric's long routes, from the middle of the die to the
    /// SB_MAC16s at its edges, are what the steps of two LUT levels lose), the registers that
    /// shorten a step to one LUT level between routes: a carry-select sum's last pick in a step
    /// of its own ([`Builder::resolve_all`]), a second register on each colour operand copy
    /// ([`Builder::colour_copies`]), and those a model asks for ([`Builder::route_register_step`]).
    /// Elsewhere none: the ECP5's steps were measured without them, and the calibrated shapes of
    /// the models without the flag stay as they are.
    pub(crate) fn route_registers(&self) -> bool {
        self.fabric_registers
            && self.family().dsp_capacity().is_some()
            && !self.family().instantiated_blocks()
    }

    /// Where [`Builder::route_registers`], a step titled `title` that only registers: a
    /// flip-flop where a long route starts, so that place-and-route can put one at each end.
    pub(crate) fn route_register_step(&mut self, title: &str) {
        if self.route_registers() {
            self.register_only_step(title);
        }
    }

    /// A step titled `title` that only registers (whatever the plan: the shape of the datapath
    /// does not depend on the cuts).
    pub(crate) fn register_only_step(&mut self, title: &str) {
        self.step(title);
        self.delay(REGISTER_ONLY_DELAY);
    }

    /// Starts the next step.
    pub(crate) fn step(&mut self, title: &str) {
        let index = self.steps.len() + 1;
        self.steps.push(Step {
            index,
            title: title.into(),
            wires: Vec::new(),
            dsps: Vec::new(),
            delay: Delay::ZERO,
            soft_product: false,
            small_product: false,
        });
    }

    /// Raises the current step's delay estimate to at least `d`.
    pub(crate) fn delay(&mut self, d: Delay) {
        let s = self.steps.last_mut().expect("a step");
        if d.ns > s.delay.ns {
            s.delay = d;
        }
    }

    pub(super) fn signal(&mut self, name: &str) -> &mut Signal {
        self.signals
            .iter_mut()
            .rev()
            .find(|s| s.name == name)
            .unwrap_or_else(|| panic!("datapath: {name} used before it is defined"))
    }

    /// Whether `name` is held in a block's output register defined in the current step (so
    /// it can be read only from the next step on).
    pub(crate) fn is_block_output_here(&mut self, name: &(impl AsRef<str> + ?Sized)) -> bool {
        let name = name.as_ref();
        let cur = self.cur();
        let s = self.signal(name);
        s.dsp_registered && s.step == cur
    }

    /// The name of `name` as seen from the current step.
    pub(super) fn version(&mut self, name: &str) -> String {
        let (cur, def, dsp) = (
            self.cur(),
            self.signal(name).step,
            self.signal(name).dsp_registered,
        );
        assert!(
            !(dsp && def == cur),
            "datapath: {name} is a DSP's registered output, read only after its step"
        );
        if let Some(held) = &self.signal(name).held {
            return held.clone();
        }
        visible(&self.registered, name, def, cur)
    }

    /// Bits `[hi:lo]` of a signal (the bare name when that is all of it).
    pub fn bits(&mut self, name: &(impl AsRef<str> + ?Sized), hi: u32, lo: u32) -> Expr {
        let name = name.as_ref();
        let cur = self.cur();
        let s = self.signal(name);
        assert!(
            hi < s.width && lo <= hi,
            "datapath: {name}[{hi}:{lo}] of a {}-bit signal",
            s.width
        );
        s.uses.push((cur, mask(hi + 1) & !mask(lo)));
        let whole = lo == 0 && hi + 1 == s.width;
        let v = self.version(name);
        *self.read.entry(v.clone()).or_default() |= mask(hi + 1) & !mask(lo);
        let text = match (whole, hi == lo) {
            (true, _) => v.clone(),
            (false, true) => format!("{v}[{lo}]"),
            (false, false) => format!("{v}[{hi}:{lo}]"),
        };
        Expr::read(v, text)
    }

    /// All of a signal.
    pub fn r(&mut self, name: &(impl AsRef<str> + ?Sized)) -> Expr {
        let name = name.as_ref();
        let w = self.signal(name).width;
        self.bits(name, w - 1, 0)
    }

    /// Bits `[lo, lo+width)` of a signal as an operand of exactly `out` bits: cut to its low
    /// `out` bits (enough for a result taken modulo 2^out) or zero-extended.
    pub fn operand(
        &mut self,
        name: &(impl AsRef<str> + ?Sized),
        lo: u32,
        width: u32,
        out: u32,
    ) -> Expr {
        let name = name.as_ref();
        self.pieces(&sub_pieces(&[Piece::sig(name, lo, width)], 0, out))
    }

    /// All of `name` zero-extended to `to` bits.
    pub(crate) fn zext(&mut self, name: &(impl AsRef<str> + ?Sized), to: u32) -> Expr {
        let name = name.as_ref();
        let w = self.signal(name).width;
        assert!(to >= w, "zext {name} from {w} to {to}");
        self.operand(name, 0, w, to)
    }

    /// `cond ? a : b` over `width` bits written as an AND-OR, for a mux where `a` or `b` has
    /// constant bits: yosys makes a `?:` of a constant before a register the register's
    /// synchronous set/reset (iCE40 SB_DFFSR/SS), and a set/reset driven by logic costs
    /// placement (the 8 flip-flops of a tile share one) and ~3.5 ns of route into the pin,
    /// or a global buffer ~6 ns away when it drives more than 15 flip-flops.
    pub fn select(cond: &Expr, a: &Expr, b: &Expr, width: u32) -> Expr {
        // one side a line
        ex!(
            "({{{}{{{}}}}} & {})\n    | (~{{{}{{{}}}}} & {})",
            width,
            cond,
            a,
            width,
            cond,
            b
        )
    }

    /// `cond ? value : other` for a constant `value` of `width` bits ([`Builder::select`]).
    pub(crate) fn select_const(cond: &Expr, value: u128, width: u32, other: &Expr) -> Expr {
        Builder::select(cond, &Expr::constant(lit(width, value)), other, width)
    }

    /// The value of the first case whose condition holds, else `default`, over `width` bits,
    /// as an AND-OR ([`Builder::select`]): each value gated by its condition and the others'
    /// before it clear.
    pub(crate) fn first_of(cases: &[(Expr, Expr)], default: &Expr, width: u32) -> Expr {
        let mut terms = Vec::new();
        let mut before: Vec<Expr> = Vec::new();
        for (cond, value) in cases {
            let mut all = before.clone();
            all.push(cond.clone());
            terms.push(Builder::gate(
                &ex!("({})", Expr::join(&all, " & ")),
                value,
                width,
            ));
            before.push(ex!("~{}", cond));
        }
        terms.push(Builder::gate(
            &ex!("({})", Expr::join(&before, " & ")),
            default,
            width,
        ));
        Expr::join(&terms, "\n    | ")
    }

    /// `cond ? a : 0` over `width` bits as an AND ([`Builder::select`]).
    pub(crate) fn gate(cond: &Expr, a: &Expr, width: u32) -> Expr {
        ex!("({{{}{{{}}}}} & {})", width, cond, a)
    }

    /// The Verilog for a list of pieces (LSB first), MSB first in a concatenation.
    pub(crate) fn pieces(&mut self, pieces: &[Piece]) -> Expr {
        let parts: Vec<Expr> = pieces
            .iter()
            .rev()
            .map(|p| match p {
                Piece::Sig {
                    name,
                    lo,
                    width,
                    invert,
                } => {
                    let b = self.bits(name, lo + width - 1, *lo);
                    if *invert {
                        ex!("~{}", b)
                    } else {
                        b
                    }
                }
                Piece::Const { value, width } => Expr::constant(lit(*width, *value)),
            })
            .collect();
        match parts.len() {
            1 => parts.into_iter().next().unwrap(),
            _ => ex!("{{{}}}", Expr::join(&parts, ", ")),
        }
    }

    /// The terms of `a·r·2^shift` mod 2^out: `a` shifted to each bit `k` of `r` (by `k + shift`)
    /// where that bit is set, for a sum with more addends (constants, a table's value).
    pub(crate) fn shift_add_terms(
        &mut self,
        a: &Piece,
        r: &Piece,
        shift: u32,
        out: u32,
    ) -> Vec<Expr> {
        self.shift_add_rows(a, r, shift, out, false)
            .into_iter()
            .map(|(t, _)| t)
            .collect()
    }

    /// [`Builder::shift_add_terms`], each term with its width: `out` bits, or (`narrow`) only
    /// its significant ones, `a`'s width above its shift (the bits above are 0).
    pub(super) fn shift_add_rows(
        &mut self,
        a: &Piece,
        r: &Piece,
        shift: u32,
        out: u32,
        narrow: bool,
    ) -> Vec<(Expr, u32)> {
        let (
            Piece::Sig {
                name: rn,
                lo: rlo,
                width: rw,
                ..
            },
            Piece::Sig {
                name: an,
                lo: alo,
                width: aw,
                ..
            },
        ) = (r, a)
        else {
            panic!("shift_add takes signal pieces")
        };
        let mut terms = Vec::new();
        for k in (0..*rw).filter(|k| k + shift < out) {
            let bit = self.bits(rn, rlo + k, rlo + k);
            let s = k + shift;
            let tw = if narrow { out.min(aw + s) } else { out };
            let av = self.operand(an, *alo, *aw, tw - s);
            let shifted = if s == 0 {
                av
            } else {
                ex!("{{{}, {}}}", av, lit(s, 0))
            };
            terms.push((Builder::gate(&bit, &shifted, tw), tw));
        }
        terms
    }

    /// ` + b` for an addend (`ext` applied), or nothing when it is constant zero.
    pub(super) fn addend(&mut self, pieces: &[Piece], ext: impl Fn(Expr) -> Expr) -> Expr {
        if all_zero(pieces) {
            Expr::default()
        } else {
            let e = self.pieces(pieces);
            ex!(" + {}", ext(e))
        }
    }

    /// Defines a wire of the current step computing `expr`, of kind `kind` (a product is made
    /// by [`Builder::mul`], nowhere else).
    pub fn wire(&mut self, name: &str, width: u32, kind: Kind, expr: Expr, comment: &str) -> Sig {
        let cur = self.cur();
        if let Kind::Product(..) = kind {
            self.products.push(name.to_string());
        }
        self.define(name, width, cur, false);
        self.steps.last_mut().expect("a step").wires.push(Wire {
            name: name.into(),
            width,
            kind,
            expr,
            comment: comment.into(),
            keep: false,
        });
        Sig {
            name: name.into(),
            width,
        }
    }

    /// [`Builder::wire`] marked `(* keep *)`: synthesis maps the logic up to it apart from the
    /// logic after it, so a function of more inputs than a LUT's is the two LUT levels the
    /// datapath wrote, not what the mapper makes of it. yosys 0.70's ABC9 relaxes a path to
    /// the deepest in the design (area recovery): a 9-input OR became a chain of three LUT4s,
    /// blinn's leading-zero pick three levels where two fit.
    pub(crate) fn wire_kept(
        &mut self,
        name: &str,
        width: u32,
        kind: Kind,
        expr: Expr,
        comment: &str,
    ) -> Sig {
        let sig = self.wire(name, width, kind, expr, comment);
        self.steps
            .last_mut()
            .expect("a step")
            .wires
            .last_mut()
            .expect("the wire")
            .keep = true;
        sig
    }

    /// The handle of a signal defined before (a unit input, or a wire a helper defined).
    pub(crate) fn sig(&mut self, name: &str) -> Sig {
        let width = self.signal(name).width;
        Sig {
            name: name.into(),
            width,
        }
    }

    /// Closes the datapath: `outputs` are read after the last step. Adds an `unused_*` wire
    /// for the bits of each signal that its last reader leaves unread, and lists the live
    /// signals of every cut.
    pub(crate) fn finish(mut self, outputs: &[&str]) -> Datapath {
        // a step with logic and no delay estimate would count 0 ns, and `--target-mhz` would
        // place its cuts on a wrong sum: every step's logic states its delay (Builder::delay)
        for s in &self.steps {
            let logic = s.wires.iter().any(|w| !w.is_plain()) || !s.dsps.is_empty();
            assert!(
                !logic || s.delay.ns > 0.0,
                "datapath: step {} ({}) has logic but no delay estimate: call Builder::delay in it",
                s.index,
                s.title
            );
        }
        let last = self.cur();
        for o in outputs {
            let w = self.signal(o).width;
            self.signal(o).uses.push((last + 1, mask(w)));
        }
        // unused bits: read nowhere at the last step that reads the signal; one sink for all
        let mut unused: Vec<String> = Vec::new();
        for s in &self.signals {
            let last_use = s
                .uses
                .iter()
                .map(|u| u.0)
                .max()
                .unwrap_or(s.step)
                .max(s.step);
            if last_use > last {
                continue;
            }
            let read = s
                .uses
                .iter()
                .filter(|u| u.0 == last_use)
                .fold(0u128, |m, u| m | u.1);
            let seen = s
                .held
                .clone()
                .unwrap_or_else(|| visible(&self.registered, &s.name, s.step, last_use));
            self.read.insert(seen.clone(), mask(s.width));
            unused.extend(bit_ranges(&seen, s.width, mask(s.width) & !read));
        }
        let live = (1..=last)
            .map(|k| {
                self.signals
                    .iter()
                    // a DSP's output register is the cut after its step: nothing to add there
                    .filter(|s| {
                        s.step <= k
                            && s.uses.iter().any(|u| u.0 > k)
                            && !(s.dsp_registered && s.step == k)
                            && s.held.is_none()
                    })
                    .map(|s| Live {
                        name: s.name.clone(),
                        width: s.width,
                        source: visible(&self.registered, &s.name, s.step, k),
                    })
                    .collect()
            })
            .collect();
        let outputs: Vec<(String, String)> = outputs
            .iter()
            .map(|o| {
                (o.to_string(), {
                    let d = self
                        .signals
                        .iter()
                        .rev()
                        .find(|s| s.name == *o)
                        .expect("output defined")
                        .step;
                    visible(&self.registered, o, d, last + 1)
                })
            })
            .collect();
        for (o, seen) in &outputs {
            let w = self.signal(o).width;
            self.read.insert(seen.clone(), mask(w));
        }
        Datapath {
            tables: self.tables,
            reads: self.reads,
            steps: self.steps,
            live,
            unused,
            outputs,
            registered: self.registered,
            read: self.read,
            products: self.products,
            product_uses: self.product_uses,
            shifted_products: self.shifted_products,
            copies: self.copies,
        }
    }
}
