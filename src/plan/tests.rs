use super::*;

/// C's clamp and ~c (the operand of 1 − c) are made in different steps, from
/// different registers of cos: in one step the integer bit of cos drove both words and a
/// synthesis tool shared c's LUTs for ~c, so c's flip-flops took them over a route of
/// their own (schlick at 117.1 MHz on the UP5K).
#[test]
fn the_clamp_and_the_operand_of_one_minus_c_are_apart() {
    use crate::config::Target;
    for target in [Target::Ice40, Target::Ecp5, Target::Generic] {
        let cfg = crate::config::Config::new(crate::config::Params {
            model: crate::config::SpecularModel::Schlick,
            target,
            ..Default::default()
        })
        .unwrap();
        let plan = Plan::new(cfg).unwrap();
        let step_of = |name: &str| {
            plan.datapath
                .steps
                .iter()
                .position(|s| s.wires.iter().any(|w| w.name == name))
                .unwrap()
        };
        assert_eq!(
            step_of("cos_clamped"),
            step_of("cos_comp") + 1,
            "{target:?}"
        );
    }
}

use crate::config::SpecularModel;

#[test]
fn validation_builds_nothing_and_the_plan_bounds_stages() {
    // a configuration is valid without its datapath; the plan knows the cut points
    let cfg = Config::new(Params {
        stages: 99,
        ..Params::default()
    })
    .expect("stages are the plan's to check");
    let e = Plan::new(cfg).unwrap_err();
    assert_eq!(e.parameter(), Some("stages"));
    assert!(e.reason().contains("allowed 0..=13"), "{}", e.reason());
    for model in SpecularModel::ALL {
        let top = Plan::from_params(Params {
            model,
            stages: 0,
            n_bits: 6,
            ..Params::default()
        })
        .unwrap()
        .cut_points;
        let plan = Plan::from_params(Params {
            model,
            stages: top,
            n_bits: 6,
            ..Params::default()
        })
        .unwrap();
        // every cut registered; the same plan when the model is reused
        assert_eq!(
            plan.registered_cuts,
            (1..=top).collect::<Vec<_>>(),
            "{model:?}"
        );
        assert_eq!(plan.datapath.steps.len() as u32, top);
        let again = Plan::from_params(Params {
            model,
            stages: 0,
            n_bits: 6,
            ..Params::default()
        })
        .unwrap()
        .with_stages(top)
        .unwrap();
        assert_eq!(again.registered_cuts, plan.registered_cuts);
    }
}

/// On the iCE40 no step holds two carry-save layers (a function of up to 9
/// registers, three LUT levels on yosys 0.70), and fitted's lo^2 tables read at most a
/// LUT's inputs (a table of 5 bits was two LUT levels: fitted 96.2 MHz on yosys 0.23).
#[test]
fn ice40_steps_hold_one_carry_save_layer_and_one_lut_tables() {
    use crate::datapath::LUT_INPUTS;
    for model in [SpecularModel::Fitted, SpecularModel::Blinn] {
        let plan = Plan::from_params(Params {
            model,
            ..Params::default()
        })
        .unwrap();
        let mut layers = 0;
        for step in &plan.datapath.steps {
            let mut seen: Vec<&str> = step
                .wires
                .iter()
                .filter_map(|w| w.name.split("_csa").nth(1))
                .map(|t| t.split('_').next().unwrap())
                .collect();
            seen.dedup();
            assert!(
                seen.len() <= 1,
                "{model:?} step {} ({}): carry-save layers {seen:?}",
                step.index,
                step.title
            );
            layers += seen.len();
            for w in step.wires.iter().filter(|w| w.name.ends_with("_ll")) {
                assert!(
                    w.width <= 2 * LUT_INPUTS,
                    "{model:?} {}: a square table of {} bits",
                    w.name,
                    w.width / 2
                );
            }
        }
        assert!(
            layers >= 2,
            "{model:?}: carry-save sums exist ({layers} layers)"
        );
    }
    let plan = Plan::from_params(Params {
        model: SpecularModel::Fitted,
        ..Params::default()
    })
    .unwrap();
    assert!(
        plan.datapath
            .steps
            .iter()
            .flat_map(|s| &s.wires)
            .any(|w| w.name == "square1_t_top"),
        "lo's top bit split off the table"
    );
}

#[test]
fn cuts_are_distinct_increasing_and_in_range() {
    let plan = Plan::new(Config::defaults()).unwrap();
    let delays = plan.datapath.delays();
    let c = plan.cut_points;
    assert_eq!(delays.len(), c as usize);
    for s in 0..=c {
        let cuts = balanced_cuts(&delays, s);
        assert_eq!(cuts.len(), s as usize);
        assert!(cuts.windows(2).all(|w| w[0] < w[1]), "{cuts:?}");
        assert!(cuts.iter().all(|&x| (1..=c).contains(&x)));
    }
    assert_eq!(balanced_cuts(&delays, c), (1..=c).collect::<Vec<_>>());
}

#[test]
fn balancing_splits_the_heaviest_step_off() {
    // one heavy step in the middle: a single register goes right next to it
    let d = [1.0, 1.0, 10.0, 1.0, 1.0];
    assert_eq!(balanced_cuts(&d, 1), vec![3]);
    assert_eq!(balanced_cuts(&d, 2), vec![2, 3]);
    // uniform steps: registers evenly spaced
    assert_eq!(balanced_cuts(&[1.0; 6], 2), vec![2, 4]);
}

/// Every placement tried: the slowest stretch, least; ties to the latest cuts.
fn balanced_cuts_by_search(delays: &[f64], s: usize) -> Vec<u32> {
    let c = delays.len();
    let worst = |cuts: &[usize]| {
        let mut edges = vec![0usize];
        edges.extend(cuts.iter().copied());
        edges.push(c);
        edges
            .windows(2)
            .map(|e| delays[e[0]..e[1]].iter().sum::<f64>())
            .fold(0.0f64, f64::max)
    };
    let mut best: Option<(f64, Vec<usize>)> = None;
    for mask in 0u32..(1 << c) {
        if mask.count_ones() as usize != s {
            continue;
        }
        let pick: Vec<usize> = (0..c)
            .filter(|i| mask >> i & 1 == 1)
            .map(|i| i + 1)
            .collect();
        let w = worst(&pick);
        let better = match &best {
            None => true,
            Some((bw, bc)) => w < *bw - 1e-9 || ((w - *bw).abs() <= 1e-9 && pick > *bc),
        };
        if better {
            best = Some((w, pick));
        }
    }
    best.map(|(_, p)| p.into_iter().map(|x| x as u32).collect())
        .unwrap_or_default()
}

/// No product the synthesis tool maps takes a constant operand its family mis-maps
/// (`Family::takes_constant`: on the iCE40, yosys 0.23 drops the top bits of a 16-bit
/// constant of 0xC000 or more), over k_q's below, between and above that (0.6 and 0.7 are
/// 0x9999 and 0xB333, taken whole), both KF's, both datapaths that multiply by k_q, every
/// target and depth. It fails where such a constant reaches a product whole (the lean unit at
/// `--k 0.95` wrote `n * 16'hf333`), and where a constant that maps right is split anyway.
#[test]
fn no_mapped_product_takes_a_constant_its_family_mis_maps() {
    use crate::config::{Arch, Target};
    let narrow = Params {
        cos_frac_bits: 8,
        n_bits: 6,
        color_bits: 4,
        intensity_frac_bits: 8,
        ..Params::default()
    };
    let (mut checked, mut split) = (0, 0);
    // the hazard itself, apart from the family's rule: a 16-bit slice of 0xC000 or more
    let mis_mapped = |x: u128| (0..8).any(|i| (x >> (16 * i)) & 0xffff >= 0xc000);
    for target in Target::ALL {
        for arch in [Arch::Lean, Arch::Paper] {
            for k in ["0.3686", "0.6", "0.7", "0.8", "0.95", "0.99"] {
                for (kf, base) in [(16, Params::default()), (20, narrow.clone())] {
                    let params = Params {
                        target,
                        arch,
                        k: k.into(),
                        k_frac_bits: kf,
                        stages: 0,
                        ..base
                    };
                    let top = Plan::from_params(params.clone()).unwrap().cut_points;
                    for stages in [0, top] {
                        let plan = Plan::from_params(Params {
                            stages,
                            ..params.clone()
                        })
                        .unwrap();
                        let k_code = plan.cfg.k_code as u128;
                        for w in plan
                            .datapath
                            .steps
                            .iter()
                            .flat_map(|s| &s.wires)
                            .filter(|w| w.product().is_some())
                        {
                            // the operands of `a * b`: a literal one is `W'hX`
                            let text = w.expr.text.split(" + ").next().unwrap();
                            for operand in text.split(" * ") {
                                let operand = operand.trim();
                                if let Some((_, hex)) = operand
                                    .split_once("'h")
                                    .filter(|_| !operand.starts_with('{'))
                                {
                                    let value = u128::from_str_radix(hex, 16).unwrap();
                                    // no SB_MAC16 takes a constant with such a slice
                                    let at = format!(
                                        "{target:?} {arch:?} k={k} KF={kf} {stages}: {} = {}",
                                        w.name, w.expr.text
                                    );
                                    assert!(
                                        !(target == Target::Ice40 && mis_mapped(value)),
                                        "{at}"
                                    );
                                    // k_q is split only where it must be: wider than the
                                    // block (lean), or a hazard on the iCE40
                                    let must = (target == Target::Ice40 && mis_mapped(k_code))
                                        || (arch == Arch::Lean
                                            && 128 - k_code.leading_zeros()
                                                > crate::family::of(target).multiplier_bits());
                                    assert_eq!(value != k_code, must, "{at}");
                                    split += (value != k_code) as usize;
                                    checked += 1;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(
        checked > 50 && split > 0,
        "{checked} constant operands, {split} of them a split k_q"
    );
}

#[test]
fn balancing_equals_the_search_over_every_placement() {
    let mut r = 7u64;
    for _ in 0..300 {
        r = crate::bits::splitmix(r);
        let c = 1 + (r % 11) as usize;
        let delays: Vec<f64> = (0..c)
            .map(|i| {
                let v = crate::bits::splitmix(r ^ i as u64);
                // a few distinct values, so ties happen
                [0.0, 2.7, 3.4, 5.5, 8.1][(v % 5) as usize]
            })
            .collect();
        for s in 0..=c {
            assert_eq!(
                balanced_cuts(&delays, s as u32),
                balanced_cuts_by_search(&delays, s),
                "{delays:?} with {s} cuts"
            );
        }
    }
    // and a long datapath in no time (the search would take 2^43 placements)
    assert_eq!(balanced_cuts(&[2.7; 43], 43).len(), 43);
}
/// A wire's kind and reads are data the builder recorded as it made the operands,
/// never read back from the Verilog. Checked here against the text, over every model, family,
/// width, depth and budget: the reads are exactly the signal names the text holds; a select
/// is no more than bits and braces (a multi-line concatenation included: the old text rule
/// missed it, and left registers a block reads through one without their `keep`); a
/// product, and only a product, multiplies.
#[test]
fn every_wire_is_typed_as_its_text_reads() {
    use crate::config::{Arch, SpecularModel, Target};
    use crate::datapath::Kind;
    let narrow = Params {
        cos_frac_bits: 8,
        n_bits: 6,
        color_bits: 4,
        intensity_frac_bits: 8,
        ..Params::default()
    };
    let mut checked = 0;
    for model in SpecularModel::ALL {
        for target in Target::ALL {
            let logic = Params {
                rom_style: crate::config::RomStyle::Logic,
                ..narrow.clone()
            };
            let shapes = [
                (Params::default(), Arch::Lean),
                (narrow.clone(), Arch::Lean),
                (Params::default(), Arch::Paper),
                (logic, Arch::Lean),
            ];
            for (base, arch) in shapes {
                if arch == Arch::Paper && model != SpecularModel::Quadratic {
                    continue;
                }
                // a table as logic: the lean datapaths with tables, on the ECP5 only
                if base.rom_style == crate::config::RomStyle::Logic
                    && !(model.takes("rom_style=logic") && target == Target::Ecp5)
                {
                    continue;
                }
                for budget in [None, Some(1)] {
                    let params = Params {
                        model,
                        target,
                        arch,
                        dsp_budget: budget,
                        stages: 0,
                        ..base.clone()
                    };
                    let top = Plan::from_params(params.clone()).unwrap().cut_points;
                    for stages in [0, 1, top / 2, top] {
                        let plan = Plan::from_params(Params {
                            stages,
                            ..params.clone()
                        })
                        .unwrap();
                        let dp = &plan.datapath;
                        // every name a step, an output or the lint sink reads
                        let names: std::collections::BTreeSet<&str> =
                            dp.read.keys().map(String::as_str).collect();
                        for s in &dp.steps {
                            for w in &s.wires {
                                let text = &w.expr.text;
                                let mut in_text: Vec<&str> = text
                                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                    .filter(|t| names.contains(t))
                                    .collect();
                                in_text.sort();
                                in_text.dedup();
                                let mut reads: Vec<&str> =
                                    w.expr.reads.iter().map(String::as_str).collect();
                                reads.sort();
                                assert_eq!(
                                    reads, in_text,
                                    "{model:?} {target:?} {stages}: {}_s{} = {text}",
                                    w.name, s.index
                                );
                                let plain = text
                                    .chars()
                                    .all(|c| c.is_alphanumeric() || "_[]:{}, '\n".contains(c));
                                assert_eq!(
                                    w.kind == Kind::Select,
                                    plain,
                                    "{model:?} {target:?} {stages}: {}_s{} ({:?}) = {text}",
                                    w.name,
                                    s.index,
                                    w.kind
                                );
                                assert_eq!(
                                    w.product().is_some(),
                                    text.contains(" * "),
                                    "{model:?} {target:?}: {}_s{} = {text}",
                                    w.name,
                                    s.index
                                );
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(checked > 10_000, "{checked} wires");
}
