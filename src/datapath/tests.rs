use super::*;

#[test]
fn chunks_cover_the_width_in_balanced_pieces() {
    for w in 1..80 {
        use crate::family::ice40::CHUNK_BITS;
        let c = chunks(w, CHUNK_BITS);
        assert_eq!(c.iter().map(|x| x.1).sum::<u32>(), w);
        assert!(c.iter().all(|x| x.1 <= CHUNK_BITS && x.1 >= 1));
        assert!(c.windows(2).all(|p| p[0].0 + p[0].1 == p[1].0));
        assert_eq!(c.len() as u32, w.div_ceil(CHUNK_BITS));
    }
}

/// The post-adder takes an add no wider than the operands (yosys 0.23's rule on the
/// iCE40; always in generic RTL); a wider one is the product, then a carry-select add over
/// the bits above the addend's low zeros (a complemented addend formed beside the product);
/// on the ECP5 always the product, then one carry chain.
#[test]
fn multiply_add_uses_the_post_adder_only_where_the_tool_takes_it() {
    let wire = |b: &Builder, name: &str| {
        b.steps
            .iter()
            .flat_map(|s| &s.wires)
            .find(|w| w.name == name)
            .cloned()
    };
    let expr = |b: &Builder, name: &str| wire(b, name).map(|w| w.expr.text);
    let (a, r) = ([Piece::sig("a", 0, 11)], [Piece::sig("r", 0, 7)]);
    let inputs = [("a", 11), ("r", 7), ("g", 20)];
    // 18 bits from 11 x 7: inside the block
    for target in [Target::Ice40, Target::Generic] {
        let mut b = Builder::new(&inputs, &[], target);
        b.step("t");
        b.multiply_add("s", &a, &r, &[Piece::sig("g", 0, 18)], 18, "t", "");
        assert_eq!(b.steps.len(), 1, "{target:?}");
        assert_eq!(
            wire(&b, "s").unwrap().kind,
            Kind::Product(11, 7),
            "{target:?}"
        );
        assert!(
            expr(&b, "s").unwrap().contains(" * ") && expr(&b, "s").unwrap().contains(" + "),
            "{target:?}"
        );
    }
    // 28 bits (the entry above 7 zero bits): in the generic RTL still one expression ...
    let addend = [Piece::zeros(7), Piece::not("g", 0, 20)];
    let mut b = Builder::new(&inputs, &[], Target::Generic);
    b.step("t");
    b.multiply_add("s", &a, &r, &addend, 28, "t", "");
    assert_eq!(b.steps.len(), 1);
    // ... on the iCE40 the product alone, the addend complemented beside it, then the add
    // of bits [27:7] in carry-select chunks, and the sum with the product's low bits
    let mut b = Builder::new(&inputs, &[], Target::Ice40);
    b.step("t");
    b.multiply_add("s", &a, &r, &addend, 28, "t", "");
    assert_eq!(expr(&b, "s_prod").unwrap(), "{7'h0, a} * {11'h0, r}");
    assert_eq!(expr(&b, "s_addend").unwrap(), "{1'h0, ~g}");
    assert_eq!(wire(&b, "s_addend").unwrap().expr.reads, ["g"]);
    assert!(
        b.steps.len() >= 3,
        "chunk sums and their select after the product"
    );
    assert!(expr(&b, "s_hi_part1_plus1").is_some());
    assert!(
        expr(&b, "s").unwrap().ends_with("s_prod_s1[6:0]}"),
        "{:?}",
        expr(&b, "s")
    );
    // on the ECP5 one carry chain after the product
    let mut b = Builder::new(&inputs, &[], Target::Ecp5);
    b.step("t");
    b.multiply_add("s", &a, &r, &addend, 28, "t", "");
    assert_eq!(b.steps.len(), 2);
    assert!(
        expr(&b, "s_hi").unwrap().contains("s_prod_s1[17:7]"),
        "{:?}",
        expr(&b, "s_hi")
    );
}

/// A register a multiplier reads (bits of a product, an input) is named for `(* keep *)`;
/// one only the fabric reads is not.
#[test]
fn a_register_read_by_a_block_is_kept() {
    let mut b = Builder::new(&[("a", 8), ("c", 8)], &[1, 2], Target::Ice40);
    b.step("p");
    b.mul(
        "p",
        16,
        (&[Piece::sig("a", 0, 8)], 8),
        (&[Piece::sig("c", 0, 8)], 8),
        &[],
        Delay::ZERO,
        "",
    );
    let e = b.bits("p", 15, 8);
    b.wire("hi", 8, Kind::Select, e, "");
    b.step("q");
    b.mul(
        "q",
        16,
        (&[Piece::sig("hi", 0, 8)], 8),
        (&[Piece::sig("c", 0, 8)], 8),
        &[],
        Delay::ZERO,
        "",
    );
    let e = b.bits("p", 7, 0);
    b.wire("lo", 8, Kind::Logic, ex!("~{}", e), "");
    let d = b.finish(&["q", "lo"]);
    assert!(
        d.read_by_block("hi", 1),
        "bits of a product, read by a multiplier"
    );
    assert!(
        !d.read_by_block("p", 1),
        "the product itself is read only by the fabric"
    );
    assert!(
        d.read_by_block("c", 1),
        "an input's register a multiplier reads"
    );
}

/// A multiplier reads a block's output register also through wires that only
/// slice it (yosys 0.70 took such a register into both blocks): it is kept too.
#[test]
fn a_block_output_register_read_through_slices_is_kept() {
    let mut b = Builder::new(&[("a", 8), ("c", 8)], &[1], Target::Ice40);
    b.step("p");
    b.mul(
        "p",
        16,
        (&[Piece::sig("a", 0, 8)], 8),
        (&[Piece::sig("c", 0, 8)], 8),
        &[],
        Delay::ZERO,
        "",
    );
    b.step("q");
    let e = b.bits("p", 15, 4);
    b.wire(
        "s",
        12,
        Kind::Select,
        e,
        "a slice of the registered product",
    );
    let e = b.bits("s", 11, 4);
    b.wire("t", 8, Kind::Select, e, "a slice of the slice");
    b.mul(
        "q",
        16,
        (&[Piece::sig("t", 0, 8)], 8),
        (&[Piece::sig("c", 0, 8)], 8),
        &[],
        Delay::ZERO,
        "",
    );
    let d = b.finish(&["q"]);
    assert!(
        d.read_by_block("p", 1),
        "read by a multiplier through two slices"
    );
}

/// No carry-out leaves a chain as the chain's own CO. Each chunk's carry is a sum
/// bit of its chunk, complemented (1 above the first operand, 0 above the second), and so
/// is the top chunk's when the add's top bit is a carry-out; the select reads them back
/// complemented.
#[test]
fn carries_are_sum_bits_kept_complemented() {
    let mut b = Builder::new(&[("x", 16), ("y", 15)], &[1, 2], Target::Ice40);
    b.step("add");
    b.chunk_limit = 6;
    // 17 bits of two 16/15-bit operands: the top bit is the carry-out
    let p = b.add_start(
        "s",
        &[Piece::sig("x", 0, 16)],
        &[Piece::sig("y", 0, 15)],
        false,
        17,
        "",
    );
    let expr = |b: &Builder, name: &str| {
        b.steps
            .iter()
            .flat_map(|s| &s.wires)
            .find(|w| w.name == name)
            .map(|w| w.expr.text.clone())
            .unwrap()
    };
    assert_eq!(expr(&b, "s_part0"), "{1'b1, x[5:0]} + {1'b0, y[5:0]}");
    assert_eq!(expr(&b, "s_part1"), "{1'b1, x[11:6]} + {1'b0, y[11:6]}");
    assert_eq!(
        expr(&b, "s_part1_plus1"),
        "{1'b1, x[11:6], 1'b1} + {1'b0, y[11:6], 1'b1}"
    );
    assert!(
        expr(&b, "s_part2").starts_with("{1'h1, x[15:12]}"),
        "{}",
        expr(&b, "s_part2")
    );
    b.step("carries");
    b.add_carries(&p);
    assert!(
        expr(&b, "s_carry2").starts_with("~s_part0_c1[6] ?"),
        "{}",
        expr(&b, "s_carry2")
    );
    b.step("select");
    b.add_finish(p);
    assert!(
        expr(&b, "s_chunk2").contains("{~s_part2_plus1_c2[5], s_part2_plus1_c2[4:1]}"),
        "{}",
        expr(&b, "s_chunk2")
    );
}

/// A carry-save layer's vectors are as wide as the bits they can have set (the sum
/// the widest term's, the carries the second widest's, one up), so the zeros above the terms
/// reach the closing add, whose top bit is then a carry-out kept complemented. Wires as wide
/// as the sum left those zeros to the synthesis tool, which found them through the registers
/// and left the chain's carry-out bare (fitted's squaring at 115.8 MHz on the UP5K).
#[test]
fn carry_save_vectors_keep_the_zeros_above_their_terms() {
    let mut b = Builder::new(&[("x", 8), ("y", 9), ("z", 10)], &[1, 2, 3], Target::Ice40);
    b.step("terms");
    let term = |n: &str, w: u32| vec![Piece::sig(n, 0, w), Piece::zeros(14 - w)];
    let p = b.sum_start(
        "s",
        vec![term("x", 8), term("y", 9), term("z", 10)],
        14,
        "t",
        "",
    );
    let wire = |b: &Builder, name: &str| {
        b.steps
            .iter()
            .flat_map(|s| &s.wires)
            .find(|w| w.name == name)
            .cloned()
            .unwrap()
    };
    assert_eq!(
        wire(&b, "s_csa1_s0").width,
        10,
        "the sum bits: below the widest term's"
    );
    assert_eq!(
        wire(&b, "s_csa1_c0").width,
        9,
        "the carries: below the second widest term's"
    );
    assert!(
        p.top_inverted,
        "x + y + z < 2^11: the 14-bit sum's top bit is a carry-out of zeros"
    );
    // a term with no zeros above it: full width, as before
    let mut b = Builder::new(
        &[("x", 14), ("y", 14), ("z", 14)],
        &[1, 2, 3],
        Target::Ice40,
    );
    b.step("terms");
    let p = b.sum_start(
        "s",
        vec![term("x", 14), term("y", 14), term("z", 14)],
        14,
        "t",
        "",
    );
    assert_eq!(
        (wire(&b, "s_csa1_s0").width, wire(&b, "s_csa1_c0").width),
        (14, 13)
    );
    assert!(!p.top_inverted);
}

/// A carry-select pick whose carry-in-0 arm holds a constant bit (the second addend
/// 0 over the chunk, the first a constant there) is an AND or OR with the carry, never a ?:
/// with a constant arm, which yosys makes the flip-flop's synchronous set or reset over the
/// slow set/reset route (fitted's sign bit at 112.5 MHz on the UP5K).
#[test]
fn a_pick_with_a_constant_arm_is_an_and_or() {
    let mut b = Builder::new(&[("x", 16), ("y", 10)], &[1, 2], Target::Ice40);
    b.step("add");
    b.chunk_limit = 6;
    // bit 16 of the first operand a constant 1 (a sign extension), the second 0 above bit 9
    let a = [Piece::sig("x", 0, 16), Piece::Const { value: 1, width: 1 }];
    let p = b.add_start("s", &a, &[Piece::sig("y", 0, 10)], false, 17, "");
    let expr = |b: &Builder, name: &str| {
        b.steps
            .iter()
            .flat_map(|s| &s.wires)
            .find(|w| w.name == name)
            .map(|w| w.expr.text.clone())
            .unwrap()
    };
    b.step("carries");
    b.add_carries(&p);
    b.step("select");
    b.add_finish(p);
    let top = expr(&b, "s_chunk2");
    assert!(top.starts_with("{(s_part2_plus1_c2[5] | ~s_carry2_c2), (s_carry2_c2 ? s_part2_plus1_c2[4] : s_part2_c2[3])"), "{top}");
    assert!(
        !top.contains("1'h1") && !top.contains("1'b1"),
        "no constant arm: {top}"
    );
    // the chunk with the second addend in it picks as before
    assert_eq!(
        expr(&b, "s_chunk1"),
        "~s_part0_c2[6] ? s_part1_plus1_c2[6:1] : s_part1_c2[5:0]"
    );
}

/// Where the select step would make the last carry and then the last chunk's pick
/// (two LUT levels from the carry register below), the last chunk picks by that register from
/// two kept picks by the carry-outs of the chunk below, and the last carry is not made: the
/// carry register, which the chunk below reads too, enters only the last LUT (fitted's
/// `square3_t_carry4` over a 3.0-3.6 ns route and two LUTs at 121 MHz on the UP5K).
#[test]
fn the_last_chunk_picks_by_the_carry_below_from_two_kept_picks() {
    let wire = |b: &Builder, name: &str| {
        b.steps
            .iter()
            .flat_map(|s| &s.wires)
            .find(|w| w.name == name)
            .cloned()
    };
    // three chunks of 6: the carry into chunk 2 would be made in the select step
    let mut b = Builder::new(&[("x", 18), ("y", 18)], &[1, 2], Target::Ice40);
    b.step("add");
    b.chunk_limit = 6;
    let p = b.add_start(
        "s",
        &[Piece::sig("x", 0, 18)],
        &[Piece::sig("y", 0, 18)],
        false,
        18,
        "",
    );
    b.resolve(p, "t");
    assert!(wire(&b, "s_carry2").is_none(), "the last carry is not made");
    let (if1, if0) = (
        wire(&b, "s_chunk2_if1").unwrap(),
        wire(&b, "s_chunk2_if0").unwrap(),
    );
    assert!(
        if1.keep && if0.keep,
        "both picks kept apart from the last LUT"
    );
    assert_eq!(
        if1.expr.text,
        "~s_part1_plus1_c1[7] ? s_part2_plus1_c1[6:1] : s_part2_c1"
    );
    assert_eq!(
        if0.expr.text,
        "~s_part1_c1[6] ? s_part2_plus1_c1[6:1] : s_part2_c1"
    );
    assert_eq!(
        wire(&b, "s_chunk2").unwrap().expr.text,
        "~s_part0_c1[6] ? s_chunk2_if1_s2 : s_chunk2_if0_s2"
    );
    // the second addend 0 over the chunk below: no carry out of it with carry-in 0, so the
    // pick with carry 0 is the plain sum; a constant of the plain sum stays an AND/OR
    let mut b = Builder::new(&[("x", 18), ("y", 6)], &[1, 2], Target::Ice40);
    b.step("add");
    b.chunk_limit = 6;
    let a = [Piece::sig("x", 0, 17), Piece::Const { value: 1, width: 1 }];
    let p = b.add_start("s", &a, &[Piece::sig("y", 0, 6)], false, 18, "");
    b.resolve(p, "t");
    assert!(
        wire(&b, "s_chunk2_if0").is_none(),
        "carry 0 into the chunk below: the plain sum"
    );
    let top = wire(&b, "s_chunk2").unwrap().expr.text;
    assert!(top.starts_with("{(s_chunk2_if1_s2[5] | s_part0_c1[6]), (~s_part0_c1[6] ? s_chunk2_if1_s2[4] : s_part2_c1[4])"), "{top}");
    // four chunks: the carries made two a step, the select step only picks, as before
    let mut b = Builder::new(&[("x", 24), ("y", 24)], &[1, 2], Target::Ice40);
    b.step("add");
    b.chunk_limit = 6;
    let p = b.add_start(
        "s",
        &[Piece::sig("x", 0, 24)],
        &[Piece::sig("y", 0, 24)],
        false,
        24,
        "",
    );
    b.resolve(p, "t");
    assert!(wire(&b, "s_carry3").is_some() && wire(&b, "s_chunk3_if1").is_none());
}

/// With `--fabric-registers` on the iCE40 (route registers), the last
/// chunk's pick comes a step after its two kept picks, one LUT level each: the other chunks pick
/// in the select step beside the two, and the last picks in the next by the carry into the
/// chunk below, from the two registered. Fitted's two-level picks had held it at 116-123 MHz on
/// the UP5K. Without the flag, or on the ECP5 (its blocks instantiated), the pick stays where it
/// was (the calibrated shapes).
#[test]
fn with_route_registers_the_last_chunk_picks_a_step_after_its_two_picks() {
    let wire = |b: &Builder, name: &str| {
        b.steps.iter().find_map(|s| {
            s.wires
                .iter()
                .find(|w| w.name == name)
                .map(|w| (s.index, w.clone()))
        })
    };
    for (target, fabric, apart) in [
        (Target::Ice40, true, true),
        (Target::Ice40, false, false),
        (Target::Ecp5, true, false),
    ] {
        let mut b = Builder::new(&[("x", 18), ("y", 18)], &[1, 2, 3], target);
        b.registers_in_fabric(fabric);
        b.step("add");
        b.chunk_limit = 6;
        let p = b.add_start(
            "s",
            &[Piece::sig("x", 0, 18)],
            &[Piece::sig("y", 0, 18)],
            false,
            18,
            "",
        );
        b.resolve(p, "t");
        let (k1, if1) = wire(&b, "s_chunk2_if1").unwrap();
        let (k0, if0) = wire(&b, "s_chunk2_if0").unwrap();
        let (k, last) = wire(&b, "s_chunk2").unwrap();
        let (kb, below) = wire(&b, "s_chunk1").unwrap();
        assert!(
            if1.keep && if0.keep && k1 == 2 && k0 == 2 && kb == 2,
            "the two picks and the chunk below in the select step"
        );
        assert_eq!(
            below.expr.text,
            "~s_part0_c1[6] ? s_part1_plus1_c1[6:1] : s_part1_c1[5:0]"
        );
        if apart {
            assert_eq!(k, 3, "the last pick a step after");
            assert_eq!(
                last.expr.text,
                "~s_part0_c2[6] ? s_chunk2_if1_c2 : s_chunk2_if0_c2"
            );
            assert_eq!(wire(&b, "s").unwrap().0, 3);
        } else {
            assert_eq!(k, 2);
            assert_eq!(
                last.expr.text,
                "~s_part0_c1[6] ? s_chunk2_if1_s2 : s_chunk2_if0_s2"
            );
        }
    }
}

/// On the ECP5 a table in LUTs gives each part its own register copy of
/// the address bits it reads, in a step before the parts; each copy is a datapath copy (its
/// flip-flop kept, so synthesis merges none) and its part reads it alone. ABC9 had mapped the
/// parts through each other's LUTs (fitted's table three and four LUT4 levels deep, 227 MHz).
/// Elsewhere (the iCE40) the parts read the address as before.
#[test]
fn table_parts_in_logic_read_their_own_address_copies_on_the_ecp5() {
    let words: Vec<u128> = (0..64).map(|i| (i * 37 + 5) % 251).collect();
    let table = || Table {
        name: "t".into(),
        param: "T".into(),
        width: 8,
        words: words.clone(),
        what: "w".into(),
        fields: vec![("w".into(), 8)],
        cosines: None,
    };
    let wires = |b: &Builder| {
        b.steps
            .iter()
            .flat_map(|s| s.wires.iter().map(move |w| (s.index, w.clone())))
            .collect::<Vec<_>>()
    };
    for target in [Target::Ecp5, Target::Ice40] {
        let mut b = Builder::new(&[("n", 6)], &[1, 2, 3, 4, 5], target);
        b.tables_in_logic(true);
        let t = b.table(table());
        b.step("read");
        b.rom_read_registered("w", t, "n");
        let all = wires(&b);
        let parts: Vec<_> = all
            .iter()
            .filter(|(_, w)| w.name.starts_with("w_part"))
            .collect();
        assert_eq!(
            parts.len(),
            8,
            "64 words: parts of n's 3 low bits, picked by its 3 top bits"
        );
        let copies: Vec<_> = all
            .iter()
            .filter(|(_, w)| w.name.starts_with("w_addr"))
            .collect();
        if target == Target::Ecp5 {
            assert_eq!(copies.len(), 8, "one copy a part");
            assert!(copies.iter().all(|(k, w)| *k == 1
                && w.width == 3
                && w.expr.text == "n[2:0]"
                && b.copies.contains(&w.name)));
            for (k, p) in &parts {
                let h = p.name.trim_start_matches("w_part");
                assert_eq!(
                    (*k, p.expr.reads.clone()),
                    (2, vec![format!("w_addr{h}_c1")]),
                    "{}",
                    p.name
                );
            }
        } else {
            assert!(copies.is_empty() && b.copies.is_empty());
            assert!(parts.iter().all(|(k, p)| *k == 1 && p.expr.reads == ["n"]));
        }
    }
}

/// A step with logic and no delay estimate is a build error (it would count 0 ns
/// and `--target-mhz` would place its cuts on a wrong sum); a step that only selects bits
/// needs none.
#[test]
#[should_panic(expected = "has logic but no delay estimate")]
fn a_step_without_a_delay_estimate_is_refused() {
    let mut b = Builder::new(&[("x", 8)], &[1], Target::Ice40);
    b.step("slices only");
    let e = b.bits("x", 7, 4);
    b.wire("hi", 4, Kind::Select, e, "");
    b.step("logic, no delay");
    let h = b.r("hi");
    b.wire("y", 4, Kind::Logic, ex!("~{}", h), "");
    b.finish(&["y"]);
}

/// `at_least` is `>=` on every value of a 6-bit signal for every constant: its AND/OR
/// expression, evaluated here, agrees with the integer comparison.
#[test]
fn at_least_is_the_comparison() {
    // a tiny evaluator of the expressions at_least writes: x[i], 1'b1, &, |, parentheses
    fn eval(e: &[u8], at: &mut usize, x: u32) -> bool {
        let mut v = term(e, at, x);
        while *at < e.len() && e[*at] != b')' {
            let op = e[*at];
            *at += 1;
            let r = term(e, at, x);
            v = if op == b'&' { v & r } else { v | r };
        }
        v
    }
    fn term(e: &[u8], at: &mut usize, x: u32) -> bool {
        match e[*at] {
            b'(' => {
                *at += 1;
                let v = eval(e, at, x);
                *at += 1;
                v
            }
            b'1' => {
                *at += 4;
                true
            }
            _ => {
                let end = e[*at..].iter().position(|&c| c == b']').unwrap() + *at;
                let bit: u32 = std::str::from_utf8(&e[*at + 2..end])
                    .unwrap()
                    .parse()
                    .unwrap();
                *at = end + 1;
                (x >> bit) & 1 == 1
            }
        }
    }
    let mut b = Builder::new(&[("x", 6)], &[], Target::Ice40);
    b.step("t");
    for c in 0..64u128 {
        let expr = b.at_least("x", 5, 0, c).text.replace(' ', "");
        for x in 0..64u32 {
            assert_eq!(
                eval(expr.as_bytes(), &mut 0, x),
                x as u128 >= c,
                "x = {x}, c = {c}: {expr}"
            );
        }
    }
}

#[test]
fn sub_pieces_pads_with_zeros() {
    let p = [
        Piece::sig("a", 2, 3),
        Piece::Const {
            value: 0b101,
            width: 3,
        },
    ];
    let s = sub_pieces(&p, 1, 7);
    let mut b = Builder::new(&[("a", 8)], &[], Target::Ice40);
    b.step("t");
    assert_eq!(b.pieces(&s).text, "{2'h0, 3'h5, a[4:3]}");
}

#[test]
fn liveness_and_unused_bits() {
    let mut b = Builder::new(&[("x", 8)], &[1], Target::Ice40);
    b.step("one");
    let e = b.bits("x", 7, 4);
    b.wire("y", 4, Kind::Select, e, "");
    b.step("two");
    let e = b.bits("x", 0, 0);
    let y = b.r("y");
    b.wire("z", 5, Kind::Select, ex!("{{{}, {}}}", y, e), "");
    let d = b.finish(&["z"]);
    // cut 1 carries x (read again in step 2) and y
    assert_eq!(
        d.live[0]
            .iter()
            .map(|l| (l.name.as_str(), l.source.as_str()))
            .collect::<Vec<_>>(),
        [("x", "x"), ("y", "y_s1")]
    );
    assert_eq!(
        d.live[1]
            .iter()
            .map(|l| l.name.as_str())
            .collect::<Vec<_>>(),
        ["z"]
    );
    // step 2 reads x through the register of cut 1; bits 7:1 are left for the sink
    assert_eq!(d.unused, ["x_c1[7:1]"]);
    assert_eq!(d.outputs, [("z".to_string(), "z_s2".to_string())]);
}

#[test]
fn a_combinational_cut_is_no_name() {
    // nothing registered: every reference goes straight to the defining wire or port
    assert_eq!(visible(&[], "x", 0, 3), "x");
    assert_eq!(visible(&[], "y", 1, 3), "y_s1");
    assert_eq!(visible(&[2], "y", 1, 3), "y_c2");
    assert_eq!(visible(&[2], "y", 1, 2), "y_s1");
    assert_eq!(visible(&[1, 2], "y", 2, 2), "y_s2");
}

/// A long unread tail waits in memory; in LUT RAM (the ECP5) at most
/// `DISTRIBUTED_TAIL_MAX_CUTS` cuts of it (a memory of 32 words, one mux level deep), the cuts
/// before them in flip-flops; in block RAM the whole tail.
#[test]
fn a_tail_in_lut_ram_holds_at_most_32_words() {
    use super::delay_line::{DelayLine, DISTRIBUTED_TAIL_MAX_CUTS};
    let line = |cuts: usize, distributed: bool| DelayLine {
        name: "ks".into(),
        cuts: (1..=cuts).collect(),
        members: vec![Waiting {
            name: "ks".into(),
            width: 24,
            source: "ks".into(),
            read: vec![0; cuts],
        }],
        memory: true,
        distributed,
    };
    assert_eq!(
        line(40, false).memory_tail(),
        Some((0, 40)),
        "block RAM: the whole tail"
    );
    assert_eq!(
        line(40, true).memory_tail(),
        Some((40 - DISTRIBUTED_TAIL_MAX_CUTS, DISTRIBUTED_TAIL_MAX_CUTS)),
        "LUT RAM: 33 cuts"
    );
    assert_eq!(line(33, true).memory_tail(), Some((0, 33)));
    assert_eq!(
        DISTRIBUTED_TAIL_MAX_CUTS, 33,
        "32 words: the memory holds cuts - 1"
    );
    // the text: a flip-flop word before the memory, the memory's instance at 33 cuts
    let text = line(40, true).lines("u").join("\n");
    assert!(
        text.contains("u_delay_ram #(.WIDTH(24), .CUTS(33))"),
        "{text}"
    );
}
