use super::*;

/// With products in the fabric the registers balance the fabric's stretches, not the hard
/// block's step: a lone block step counts nothing (as in `Plan::stage_delay`), so the
/// four LUT steps after it are cut in two halves of 6 instead of 9 and 3.
#[test]
fn a_hard_steps_length_does_not_set_the_fabrics() {
    let delays = [10.0, 3.0, 3.0, 3.0, 3.0];
    assert_eq!(balanced_cuts(&delays, 2), vec![1, 4]);
    assert_eq!(
        balanced_cuts_by(&delays, &[true, false, false, false, false], 2),
        vec![1, 3]
    );
    assert_eq!(
        balanced_cuts_by(&delays, &[false; 5], 2),
        balanced_cuts(&delays, 2)
    );
}

fn product(name: &str, a: u32, b: u32, width: u32, blocks: u32) -> ProductUse {
    ProductUse {
        name: name.into(),
        a,
        b,
        width,
        blocks,
        fabric: false,
    }
}

/// The budget keeps the products costliest in the fabric on blocks: at 2 blocks `wide`
/// (16·32 partial-product bits) rather than both `mid`s (2·8·24).
#[test]
fn the_costliest_products_keep_their_blocks() {
    let uses = [
        product("small", 4, 8, 12, 1),
        product("wide", 16, 16, 32, 2),
        product("mid1", 8, 16, 24, 1),
        product("mid2", 8, 16, 24, 1),
        product("lut", 4, 3, 7, 0),
    ];
    let names = |v: &[&str]| {
        v.iter()
            .map(|s| s.to_string())
            .collect::<BTreeSet<String>>()
    };
    assert_eq!(to_fabric(&uses, 5), BTreeSet::new(), "every block fits");
    assert_eq!(to_fabric(&uses, 4), names(&["small"]));
    assert_eq!(
        to_fabric(&uses, 2),
        names(&["small", "mid1", "mid2"]),
        "16·32 > 2·8·24: wide keeps both blocks"
    );
    assert_eq!(
        to_fabric(&uses, 1),
        names(&["small", "wide", "mid2"]),
        "ties keep the product made first"
    );
    assert_eq!(
        to_fabric(&uses, 0),
        names(&["small", "wide", "mid1", "mid2"]),
        "a product of no block stays"
    );
}
