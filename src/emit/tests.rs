use super::*;

/// A chain is cut after a read word that ends an unread stretch as long as a memory tail
/// (8 words, 160 bits), never at its last word, and never without memory.
#[test]
fn a_long_unread_stretch_before_a_read_ends_the_line() {
    let mut read = vec![0u128; 30];
    read[3] = 1; // read early (n for c = 0)
    read[27] = 1; // then late (n*l), and the last words
    read[28] = 1;
    read[29] = 1;
    assert_eq!(
        unread_stretches(&read, 10, true),
        [27],
        "24 words of 10 bits after word 3"
    );
    assert_eq!(
        unread_stretches(&read, 6, true),
        Vec::<usize>::new(),
        "144 bits: flip-flops"
    );
    assert_eq!(
        unread_stretches(&read, 10, false),
        Vec::<usize>::new(),
        "no memory on the target"
    );
    read[27] = 0;
    read[28] = 0;
    assert_eq!(
        unread_stretches(&read, 10, true),
        Vec::<usize>::new(),
        "the last word ends the line anyway"
    );
}

/// A registered read of a word wider than a DP16KD is one per 18 bits, low first, each with
/// its own bits of every entry; one DP16KD keeps the bare names.
#[test]
fn a_wide_block_read_is_dp16kds_side_by_side() {
    let t = crate::table::Table {
        name: "t_rom".into(),
        param: "T_ROM_FILE".into(),
        width: 40,
        words: vec![(3u128 << 36) | (1 << 18) | 5, 7],
        what: String::new(),
        fields: vec![("v".into(), 40)],
        cosines: None,
    };
    let s = block_slices(&t, "w_c3", crate::family::ecp5::dp16kd_initvals);
    assert_eq!(
        s.iter()
            .map(|x| (x.suffix.as_str(), x.bits.as_str(), x.unused))
            .collect::<Vec<_>>(),
        [
            ("0", "w_c3[17:0]", 0),
            ("1", "w_c3[35:18]", 0),
            ("2", "w_c3[39:36]", 14)
        ]
    );
    // word 0 of each: 5, 1, 3 (the low 5 hex digits of INITVAL_00)
    for (slice, low) in s.iter().zip(["00005", "00001", "00003"]) {
        assert_eq!(slice.banks.len(), 1);
        assert!(
            slice.banks[0][0].1.ends_with(low),
            "{}",
            slice.banks[0][0].1
        );
    }
    // 1500 words: two banks, the second from word 1024
    let mut words = vec![0u128; 1500];
    words[1024] = 9;
    let banked = crate::table::Table {
        words,
        width: 18,
        ..t.clone()
    };
    let s = block_slices(&banked, "w_c3", crate::family::ecp5::dp16kd_initvals);
    assert_eq!(s[0].banks.len(), 2);
    assert!(s[0].banks[1][0].1.ends_with("00009") && s[0].banks[0][0].1.ends_with("00000"));
    let one = crate::table::Table {
        width: 18,
        ..t.clone()
    };
    assert_eq!(
        block_slices(&one, "w_c3", crate::family::ecp5::dp16kd_initvals)
            .iter()
            .map(|x| (x.suffix.as_str(), x.bits.as_str()))
            .collect::<Vec<_>>(),
        [("", "w_c3")]
    );
}
