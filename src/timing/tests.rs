//! The delay model's tests: the grid's shapes, the reading between widths, the picks.

use super::*;
use crate::config::Config;

/// The models whose datapath has calibration units of its own on the UP5K (every one a part
/// holds: blinn-pow fits neither part and takes the family's line).
fn calibrated_models() -> Vec<crate::config::SpecularModel> {
    crate::config::SpecularModel::ALL
        .into_iter()
        .filter(|&model| {
            let cfg = Config::new(crate::config::Params {
                model,
                ..Default::default()
            })
            .unwrap();
            line(Target::Ice40, cfg.datapath_name()).is_ok_and(|l| !l.measured.is_empty())
        })
        .collect()
}

/// A line `offset + slope·e` ns (no mean term) with its (cap, cap_up_to), margin and
/// measured units, all at the default widths.
fn test_line(
    (offset_ns, ns_per_unit): (f64, f64),
    (cap_mhz, cap_up_to): (f64, f64),
    margin: f64,
    measured: Vec<[f64; 3]>,
) -> Line {
    Line {
        offset_ns,
        ns_per_unit,
        ns_per_mean_unit: 0.0,
        cap_mhz,
        cap_up_to,
        margin,
        r2: 0.0,
        measured,
        measured_args: vec![],
        measured_stages: vec![],
        measured_digest: vec![],
        corners: vec![],
        deepest: 0,
        surrounded: false,
        around: vec![],
        own: None,
    }
}

/// The calibration is a grid of widths (narrow 8/6/4/8 and the
/// defaults per datapath and family, and the wide lean on the ECP5). A configuration at a
/// grid point is calibrated; one between them is told so, naming the grid; one outside it
/// (narrower, wider, another rounding) is told it is an extrapolation.
#[test]
fn widths_outside_the_calibration_are_told() {
    let plan = |p: crate::config::Params| crate::plan::Plan::new(Config::new(p).unwrap()).unwrap();
    let narrow = |p: crate::config::Params| crate::config::Params {
        cos_frac_bits: 8,
        n_bits: 6,
        color_bits: 4,
        intensity_frac_bits: 8,
        ..p
    };
    for model in calibrated_models() {
        for target in [Target::Ice40, Target::Ecp5] {
            let p = crate::config::Params {
                model,
                target,
                ..Default::default()
            };
            assert_eq!(
                outside_calibration(&plan(p.clone())),
                None,
                "{model:?} on {target:?}"
            );
            assert_eq!(
                outside_calibration(&plan(narrow(p.clone()))),
                None,
                "{model:?} on {target:?}, narrow"
            );
            let between = crate::config::Params {
                cos_frac_bits: 12,
                n_bits: 8,
                color_bits: 6,
                intensity_frac_bits: 11,
                ..p.clone()
            };
            let why = outside_calibration(&plan(between)).expect("between the grid's widths");
            // read against the nearest widths around it: a narrow one below, one above
            assert!(why.starts_with("between calibrated widths"), "{why}");
            let narrower = crate::config::Params {
                cos_frac_bits: 6,
                ..narrow(p)
            };
            let why = outside_calibration(&plan(narrower)).expect("narrower than the grid");
            assert!(
                why.starts_with("outside the calibration") && why.contains("--cos-frac-bits 6"),
                "{why}"
            );
        }
    }
    // a shape is calibrated by units of today's RTL only: the wide lean of the ECP5 is where
    // its rows name today's digest; on the iCE40 it has none
    let wide = crate::config::Params {
        cos_frac_bits: 18,
        n_bits: 11,
        color_bits: 10,
        intensity_frac_bits: 18,
        k_frac_bits: 20,
        ..Default::default()
    };
    let wide_args =
        "--cos-frac-bits 18 --n-bits 11 --color-bits 10 --intensity-frac-bits 18 --k-frac-bits 20";
    let today = line(Target::Ecp5, "lean")
        .unwrap()
        .of_todays_rtl()
        .measured_args
        .iter()
        .any(|a| a == wide_args);
    assert_eq!(
        outside_calibration(&plan(crate::config::Params {
            target: Target::Ecp5,
            ..wide.clone()
        }))
        .is_none(),
        today
    );
    assert!(outside_calibration(&plan(wide))
        .unwrap()
        .starts_with("outside the calibration"));
    // a rounding or ROM style the calibration never had is outside too
    let exact = crate::config::Params {
        rounding: crate::config::Rounding::Exact,
        ..Default::default()
    };
    let why = outside_calibration(&plan(exact)).unwrap();
    assert!(
        why.starts_with("outside the calibration") && why.contains("--rounding exact"),
        "{why}"
    );
}

/// A unit measured at other widths is no floor for a configuration: only its own widths'
/// units are kept, in order (the line and margin, fitted over all, stay).
#[test]
fn only_units_of_the_same_widths_are_floors() {
    // (narrow widths whose products are all blocks, as the defaults': `soft_products_are_no_corner`)
    let narrow = "--cos-frac-bits 10 --n-bits 6 --intensity-frac-bits 8";
    let default = Plan::new(Config::defaults()).unwrap();
    let p = crate::config::Params {
        cos_frac_bits: 10,
        n_bits: 6,
        intensity_frac_bits: 8,
        ..Config::defaults().params
    };
    let small = Plan::new(Config::new(p).unwrap()).unwrap();
    // each width measured at its deepest, the defaults at half that too
    let (dd, dn) = (default.cut_points, small.cut_points);
    let l = Line {
        measured_args: vec![String::new(), narrow.into(), String::new()],
        measured_stages: vec![dd, dn, dd / 2],
        measured_digest: vec!["today".into(); 3],
        ..test_line(
            (5.0, 1.0),
            (300.0, -1.0),
            0.7,
            vec![[10.0, 6.0, 150.0], [9.0, 5.0, 50.0], [20.0, 9.0, 60.0]],
        )
    };
    assert_eq!(
        l.clone().at_widths_of(&default).measured,
        vec![[10.0, 6.0, 150.0], [20.0, 9.0, 60.0]]
    );
    let mine = l.clone().at_widths_of(&small);
    assert_eq!(mine.measured, vec![[9.0, 5.0, 50.0]]);
    assert_eq!(mine.cap_up_to, l.cap_up_to);
    assert_eq!(mine.margin, l.margin);
    // the narrow unit's 50 MHz is its widths' floor, never the default units' 150
    assert_eq!(mine.measured_floor(8.0, 4.0), 50.0);
    // widths never measured: no floor, and no stretch assured the cap
    let between = crate::config::Params {
        cos_frac_bits: 12,
        ..Config::defaults().params
    };
    let l = Line {
        cap_up_to: 8.0,
        ..l
    };
    let theirs = l.at_widths_of(&Plan::new(Config::new(between).unwrap()).unwrap());
    assert!(theirs.measured.is_empty() && theirs.cap_up_to < 0.0);
    assert!(theirs.fmax(7.0, 5.0) < theirs.cap_mhz);
    // and no depth is assured more than the calibrated widths measured at as many cuts from
    // their deepest, or shallower: a 12-bit cos_g lies between the narrow widths and the
    // defaults, both its corners; what they measured is assured (with the fit's corner margin) where
    // its slowest stretch is no longer than theirs
    assert!(theirs.surrounded && theirs.corners.len() == 2);
    let at = |from_deepest: u32, e: f64| theirs.corner(theirs.deepest - from_deepest, e);
    assert_eq!(
        at(theirs.deepest, 1.0),
        (50.0, false),
        "shallower than every unit: no floor, the ceiling of the shallowest ones"
    );
    assert_eq!(
        at(0, 1.0),
        (50.0, true),
        "the narrow unit at its deepest, the default one at its own"
    );
    assert_eq!(
        at(0, 10.0),
        (50.0, true),
        "a stretch as long as the longest of theirs"
    );
    assert_eq!(
        at(0, 10.5),
        (50.0, false),
        "a longer stretch: a ceiling only"
    );
    // the wider default widths cap nothing of 12-bit cosines (a wider unit is slower)...
    let wider_only = Line {
        corners: theirs
            .corners
            .iter()
            .filter(|c| c.args.is_empty())
            .cloned()
            .collect(),
        surrounded: false,
        ..theirs.clone()
    };
    assert_eq!(wider_only.corner(0, 1.0), (f64::INFINITY, false));
    // ...and a ceiling is a unit as deep as the depth read or deeper, never a shallower one (a
    // shallower unit runs slower: 60 MHz at 3 stages says nothing of 6), read here at the
    // default widths' own shape
    let default_corner = wider_only.corners[0].clone();
    let deeper = Line {
        own: Some(default_corner.shape.clone()),
        corners: vec![default_corner],
        surrounded: false,
        ..theirs.clone()
    };
    let d = deeper.corners[0].deepest;
    assert_eq!(d, dd);
    let read = |at: u32| deeper.corner(theirs.deepest - (d - at), 1.0);
    assert_eq!(
        read(dd / 2),
        (60.0, false),
        "the shallower unit at its own depth"
    );
    assert_eq!(
        read(dd / 2 + 1),
        (150.0, false),
        "the deeper unit, not the shallower one"
    );
    // a floor only from a unit near the depth read: the defaults' shallow unit says nothing
    // of a depth many cuts deeper
    let sparse = Line {
        corners: theirs
            .corners
            .iter()
            .cloned()
            .map(|mut c| (c.units.retain(|u| u.0 <= dd / 2), c).1)
            .collect(),
        ..theirs.clone()
    };
    assert!(
        !sparse.corner(theirs.deepest, 1.0).1,
        "the defaults measured only {} cuts shallower",
        dd - dd / 2
    );
    assert_eq!(mine.corner(3, 1.0), (f64::INFINITY, false));
}

/// Deeper targets never pick shallower pipelines, and each pick is the shallowest that the
/// model assures (how long a pick takes: benchmarks/target.md, not a test's verdict).
#[test]
fn picks_are_the_shallowest_and_grow_with_the_target() {
    let plan = Plan::new(Config::defaults()).unwrap();
    let l = line_of(&plan).unwrap();
    let (mut last, mut picked) = (0, 0);
    for f in [5.0, 20.0, 40.0, 60.0, 80.0, 100.0] {
        let Ok((stages, predicted)) = pick_stages(&plan, f) else {
            continue;
        };
        picked += 1;
        assert!(stages >= last, "{f} MHz: {stages} stages after {last}");
        let p = plan.with_stages(stages).unwrap();
        assert!(l.assured_of(&p) >= f && (predicted - l.fmax_of(&p)).abs() < 1e-9);
        if stages > 0 {
            assert!(
                l.assured_of(&plan.with_stages(stages - 1).unwrap()) < f,
                "{f} MHz: {} stages would do",
                stages - 1
            );
        }
        last = stages;
    }
    // the low clocks are picked (a test that skipped every refusal would assert nothing)
    assert!(picked >= 3, "only {picked} of the clocks picked");
    assert!(pick_stages(&plan, 5000.0).is_err());
}

#[test]
fn the_cap_holds_where_a_calibration_unit_reached_it() {
    let l = test_line((5.0, 1.0), (100.0, 3.0), 0.9, vec![]);
    assert_eq!(l.fmax(2.0, 50.0), 100.0);
    assert!((l.fmax(15.0, 0.0) - 50.0).abs() < 1e-9);
    // past the cap's stretch, where the line (1000 / (5 + 4) = 111 MHz) is above the cap: the cap
    assert_eq!(l.fmax(4.0, 0.0), 100.0);
    assert!((l.fmax(20.0, 0.0) - 1000.0 / 25.0).abs() < 1e-9);
}

/// A calibration unit's measured Fmax holds for every unit whose two stretches are no
/// longer than its own, and only for those.
#[test]
fn a_measured_unit_is_a_floor_for_shorter_stretches() {
    let l = test_line(
        (5.0, 1.0),
        (300.0, -1.0),
        0.8,
        vec![[10.0, 6.0, 150.0], [20.0, 9.0, 60.0]],
    );
    assert_eq!(l.fmax(10.0, 6.0), 150.0);
    assert_eq!(l.fmax(9.0, 5.0), 150.0);
    assert!(
        (l.fmax(10.0, 7.0) - 66.666).abs() < 0.1,
        "a longer mean stretch: the line"
    );
    assert_eq!(l.measured_floor(21.0, 1.0), 0.0);
    // not monotone: the nearest longer unit, a unit measured itself its own figure
    let l = Line {
        measured: vec![[13.4, 11.7, 70.2], [13.4, 10.03, 64.3], [11.0, 7.8, 74.4]],
        ..l
    };
    assert_eq!(l.measured_floor(13.4, 10.03), 64.3);
    assert_eq!(l.measured_floor(13.4, 11.0), 70.2);
    assert_eq!(l.measured_floor(12.0, 9.0), 64.3);
}

/// Between two calibration units the model assures only what the longer one measured,
/// whatever the line says; beyond the shortest or the longest, the line (with its margin).
#[test]
fn between_calibration_units_only_the_longer_ones_figure_is_assured() {
    let l = test_line(
        (0.0, 0.25),
        (300.0, -1.0),
        0.9,
        vec![[20.0, 9.0, 130.0], [15.0, 5.0, 206.0]],
    );
    // the line says 1000/(0.25*17) = 235 MHz at e = 17: between the two, 130 is assured
    assert!(l.bracketed(17.0, 7.0));
    assert_eq!(l.assured(17.0, 7.0), 130.0);
    assert_eq!(
        l.assured(15.0, 5.0),
        206.0,
        "a calibration unit itself: its figure"
    );
    assert!(
        !l.bracketed(14.0, 4.0) && l.assured(14.0, 4.0) >= 206.0,
        "shorter than every unit: the floor at least"
    );
    assert!(!l.bracketed(30.0, 12.0));
    assert!(
        (l.assured(30.0, 12.0) - 0.9 * 1000.0 / 7.5).abs() < 1e-9,
        "longer than every unit: the line with its margin"
    );
    // a longer mean stretch than the shorter unit's, a shorter slowest one: not between
    assert!(!l.bracketed(14.0, 6.0));
}

/// Between calibrated widths a depth is assured what the widths around
/// it measured at as many cuts from their deepest, with [`corner_margin`]. Checked on the
/// calibration itself, each width left out in turn and its units read through the others:
/// none is assured more than it measured, over enough units that the rule is tried.
#[test]
fn leave_one_width_out() {
    let (mut tried, mut worst) = (0, f64::INFINITY);
    for target in [Target::Ice40, Target::Ecp5] {
        for model in calibrated_models() {
            let base = crate::config::Params {
                model,
                target,
                ..Default::default()
            };
            // (the floors: units of today's RTL)
            let full = line(target, Config::new(base.clone()).unwrap().datapath_name())
                .unwrap()
                .of_todays_rtl();
            let mut widths = full.measured_args.clone();
            widths.sort();
            widths.dedup();
            for w in widths {
                let Some(params) = params_with_args(&base, &w) else {
                    continue;
                };
                let others: Vec<bool> = full.measured_args.iter().map(|a| *a != w).collect();
                let l = full.clone().keeping(&others);
                for (i, unit) in full
                    .measured
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| full.measured_args[*i] == w)
                {
                    let plan = Plan::new(
                        Config::new(crate::config::Params {
                            stages: full.measured_stages[i],
                            ..params.clone()
                        })
                        .unwrap(),
                    )
                    .unwrap();
                    let read = l.clone().at_widths_of(&plan);
                    if let (v, true) = read.corner(plan.cfg.stages(), super::stretches(&plan).0) {
                        tried += 1;
                        worst = worst.min(unit[2] / v);
                        let assured = read.assured_of(&plan);
                        assert!(
                            assured <= unit[2],
                            "{target:?} {model:?} [{w}] at {} stages: assured {assured:.1} MHz, measured {}",
                            plan.cfg.stages(),
                            unit[2]
                        );
                    }
                }
            }
        }
    }
    // the rule is tried (not vacuous), and its margin is safe on every unit it was tried on
    // (not pinned from above: better data may raise the worst ratio)
    assert!(tried >= 20, "only {tried} units read between widths");
    eprintln!("leave_one_width_out: {tried} units, worst measured/read {worst:.4}");
    // the fit's margin is this worst ratio rounded down (computed apart, in `fit`)
    assert!(
        corner_margin() <= worst && worst - corner_margin() < 0.01,
        "the worst ratio {worst:.4}, the fit's margin {}",
        corner_margin()
    );
}

/// At widths never measured, a ceiling comes only from calibrated widths of the same ROM style
/// (and rounding and registers): a unit with its tables in LUTs says nothing of one whose
/// tables are block RAM, however slow it ran.
#[test]
fn a_ceiling_comes_only_from_widths_of_the_same_rom_style() {
    let between = Plan::new(
        Config::new(crate::config::Params {
            cos_frac_bits: 12,
            ..Config::defaults().params
        })
        .unwrap(),
    )
    .unwrap();
    let with = |args: &str| {
        Line {
            measured_args: vec![args.into()],
            measured_stages: vec![between.cut_points],
            measured_digest: vec!["today".into()],
            ..test_line((5.0, 1.0), (300.0, -1.0), 0.7, vec![[10.0, 6.0, 20.0]])
        }
        .at_widths_of(&between)
    };
    let logic = with("--cos-frac-bits 10 --rom-style logic");
    assert!(logic.corners.is_empty(), "{:?}", logic.corners);
    assert_eq!(logic.corner(0, 1.0), (f64::INFINITY, false));
    let file = with("--cos-frac-bits 10");
    assert_eq!(file.corners.len(), 1);
    assert_eq!(
        file.corner(0, 1.0),
        (20.0, false),
        "the narrower width's unit, as deep or deeper: a ceiling"
    );
}

/// A figure says which rule gave it: where no row of today's RTL is at or around the widths
/// (the GW1NR-9's calibration is of an older RTL), the line spoke, an extrapolation; a
/// configuration with floors of today's RTL (the UP5K's default lean) reads one.
#[test]
fn the_rule_that_gave_a_figure_is_told() {
    let at = |target: Target, stages: u32| {
        Plan::new(
            Config::new(crate::config::Params {
                target,
                stages,
                ..Config::defaults().params
            })
            .unwrap(),
        )
        .unwrap()
    };
    let gowin = line(Target::Gowin, "lean").unwrap();
    if gowin.measured_digest.iter().all(|d| d.is_empty()) {
        assert_eq!(
            assured_reading(&at(Target::Gowin, 5)).map(|r| r.1),
            Some(Rule::Line)
        );
    }
    let l = line(Target::Ice40, "lean").unwrap().of_todays_rtl();
    let shallowest = l
        .measured_args
        .iter()
        .zip(&l.measured_stages)
        .filter(|(a, _)| a.is_empty())
        .map(|(_, s)| *s)
        .min()
        .expect("a default lean of today's RTL");
    assert_eq!(
        assured_reading(&at(Target::Ice40, shallowest)).map(|r| r.1),
        Some(Rule::Floor)
    );
}

/// A calibrated width with a product yosys leaves in LUTs (too small for the block: a step no
/// register splits) is no corner of a configuration whose products are all blocks, nor the
/// other way round: the narrow fitted unit's 7×4 colour product holds it at 53 MHz at every
/// depth on the UP5K, while at 11/6/5/14 that product is an SB_MAC16's.
#[test]
fn a_width_with_a_product_in_luts_is_no_corner_of_one_without() {
    let fitted = |cos_frac_bits, n_bits, color_bits, intensity_frac_bits| {
        let p = crate::config::Params {
            model: crate::config::SpecularModel::Fitted,
            cos_frac_bits,
            n_bits,
            color_bits,
            intensity_frac_bits,
            ..Config::defaults().params
        };
        Plan::new(Config::new(p).unwrap()).unwrap()
    };
    let (narrow, between) = (fitted(8, 6, 4, 8), fitted(11, 6, 5, 14));
    assert!(
        narrow.datapath.steps.iter().any(|s| s.small_product)
            && !between.datapath.steps.iter().any(|s| s.small_product)
    );
    let with = |args: &str, plan: &Plan| {
        Line {
            measured_args: vec![args.into(), String::new()],
            measured_stages: vec![plan.cut_points, plan.cut_points],
            measured_digest: vec!["today".into(); 2],
            ..test_line(
                (5.0, 1.0),
                (300.0, -1.0),
                0.7,
                vec![[15.0, 4.0, 53.0], [5.0, 3.0, 150.0]],
            )
        }
        .at_widths_of(plan)
    };
    let read = with(
        "--cos-frac-bits 8 --n-bits 6 --color-bits 4 --intensity-frac-bits 8",
        &between,
    );
    assert_eq!(
        read.corners.len(),
        1,
        "only the default widths: {:?}",
        read.corners
    );
    assert!(!read.surrounded);
    // a configuration with such a product of its own is read through it
    let own = fitted(8, 6, 4, 10);
    assert!(own.datapath.steps.iter().any(|s| s.small_product));
    let read = with(
        "--cos-frac-bits 8 --n-bits 6 --color-bits 4 --intensity-frac-bits 8",
        &own,
    );
    assert_eq!(read.corners.len(), 1);
    assert!(read.corners[0].args.contains("--color-bits 4"));
}

/// A ceiling comes only from widths no harder to clock: no wider in any width and with as many
/// blocks or more. A budget that leaves products in the fabric is harder, not narrower.
#[test]
fn a_ceiling_comes_from_no_wider_widths_with_as_many_blocks() {
    let base = Config::defaults().params;
    let sh = |args: &str| shape::Shape::of_args(args, &base).unwrap();
    let (default, narrower, budget) = (sh(""), sh("--cos-frac-bits 10"), sh("--dsp-budget 5"));
    assert!(narrower.easier_than(&default) && !default.easier_than(&narrower));
    assert!(!budget.easier_than(&default), "fewer blocks is slower");
    assert!(default.easier_than(&budget));
    assert!(default.easier_than(&default));
}

/// A depth that leaves a product to the synthesis tool on a family whose unit instantiates its
/// blocks with their registers (the ECP5) is assured nothing by the widths around it or the
/// line: schlick at 11/9/7/11 bits and 10 stages measured 70 MHz (a table read and a product
/// without registers) where the widths around it read 111. Deeper, every product is a block
/// with its registers and the widths around it speak again.
#[test]
fn a_depth_with_products_left_to_the_tool_is_assured_only_by_its_own_units() {
    let p = crate::config::Params {
        model: crate::config::SpecularModel::Schlick,
        target: Target::Ecp5,
        cos_frac_bits: 11,
        n_bits: 9,
        color_bits: 7,
        intensity_frac_bits: 11,
        stages: 10,
        ..Config::defaults().params
    };
    let shallow = Plan::new(Config::new(p).unwrap()).unwrap();
    assert!(super::line::inferred_blocks(&shallow));
    let (f, rule) = assured_reading(&shallow).unwrap();
    assert!(
        f == 0.0 || rule == Rule::Floor,
        "{f} MHz by {rule:?} at a depth no unit of these widths measured"
    );
    let deep = shallow.with_stages(shallow.cut_points).unwrap();
    assert!(!super::line::inferred_blocks(&deep));
    assert!(assured_reading(&deep).unwrap().0 > 0.0);
}
