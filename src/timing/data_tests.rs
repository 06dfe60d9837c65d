//! The delay model's tests of its data: which families and datapaths it speaks for, the
//! shipped model as the fit of the shipped rows, what a row stands for, and each family's
//! own primitive delays.

use super::*;
use crate::config::Config;
#[test]
fn an_uncalibrated_datapath_is_refused_by_name() {
    for target in [Target::Ice40, Target::Ecp5] {
        let e = line(target, "phong").unwrap_err();
        assert_eq!(e.parameter(), Some("target_mhz"));
        assert!(
            e.reason()
                .contains("the phong datapath has no delay calibration")
                && e.reason().contains("scripts/calibrate_delay.sh"),
            "{}",
            e.reason()
        );
        for model in crate::config::SpecularModel::ALL {
            assert!(
                line(target, model.name()).is_ok() || model.reads("arch"),
                "{target:?} {}",
                model.name()
            );
        }
        for arch in ["lean", "paper"] {
            assert!(line(target, arch).is_ok(), "{target:?} {arch}");
        }
    }
}

/// `generic` is its own target. No delay model speaks for it: a pick is
/// refused naming the target (never an iCE40 figure), no clock is predicted, and its part
/// names no device.
#[test]
fn the_generic_target_is_promised_no_clock() {
    let cfg = Config::new(crate::config::Params {
        target: Target::Generic,
        ..Config::defaults().params
    })
    .unwrap();
    let plan = Plan::new(cfg).unwrap();
    let e = pick_stages(&plan, 50.0).unwrap_err();
    assert_eq!(e.parameter(), Some("target_mhz"));
    assert!(
        e.reason().contains("the generic target has no delay model")
            && e.reason().contains("--target ice40"),
        "{}",
        e.reason()
    );
    assert!(
        !e.reason().contains("UP5K") && !e.reason().contains("ECP5-25"),
        "{}",
        e.reason()
    );
    assert_eq!(predicted_fmax(&plan), None);
    assert!(!part(Target::Generic).contains("iCE40"));
}

/// Which families and datapaths the delay model speaks for is the data's: a family is
/// calibrated where the fitted model holds lines under its name (a family copied from another
/// reads none of its lines), and a datapath without rows of its own gets the family's line only
/// where its model says it reads it; any other is left out, so `--target-mhz` refuses it.
#[test]
fn the_data_says_what_the_delay_model_speaks_for() {
    for t in Target::ALL {
        assert_eq!(
            calibrated(t),
            model_json()[t.name()].is_object(),
            "{}",
            t.name()
        );
    }
    assert!(!calibrated(Target::Generic) && calibrated(Target::Ice40));
    // the shipped rows with one datapath's removed: it keeps no line unless its model reads
    // the family's
    let csv = include_str!("../../data/delay_calibration.csv");
    let without: String = csv
        .lines()
        .filter(|l| !l.starts_with("ice40,schlick,"))
        .map(|l| format!("{l}\n"))
        .collect();
    let fitted = super::fit::fit_calibration(&without, "a test's rows").unwrap();
    assert!(
        fitted["ice40"].get("schlick").is_none(),
        "{}",
        fitted["ice40"]
    );
    assert_eq!(fitted["ice40"]["blinn-pow"], "all");
    assert_eq!(fitted["ice40"]["paper"], "all");
}

/// The shipped delay model is the fit of the shipped calibration (`specgen calibrate`): a row
/// added, changed or removed without a refit, or a change to the stretches' estimates that the
/// model was not refitted for, fails here.
#[test]
fn the_shipped_model_is_the_fit_of_the_shipped_calibration() {
    let csv = include_str!("../../data/delay_calibration.csv");
    let fitted = super::fit::fit_calibration(csv, "data/delay_calibration.csv").unwrap();
    let shipped: serde_json::Value =
        serde_json::from_str(include_str!("../../data/delay_model.json")).unwrap();
    assert!(fitted == shipped, "data/delay_model.json is not the fit of data/delay_calibration.csv: run specgen calibrate --calibration data/delay_calibration.csv --out data/delay_model.json");
}

/// A row measured over fewer than three seeds stands for its slowest seed, never the mean of
/// two: every floor the shipped model holds is at most its row's slowest seed where the row has
/// fewer than three, and its median where it has more.
#[test]
fn a_floor_of_fewer_than_three_seeds_is_its_slowest_seed() {
    use super::fit::{row_figure, MIN_SEEDS};
    assert_eq!(row_figure(151.3, &[153.8, 148.8]), 148.8);
    assert_eq!(row_figure(150.0, &[148.0, 150.0, 155.0]), 150.0);
    assert_eq!(row_figure(90.0, &[90.0]), 90.0);
    let csv = include_str!("../../data/delay_calibration.csv");
    let model: serde_json::Value =
        serde_json::from_str(include_str!("../../data/delay_model.json")).unwrap();
    let mut floors = 0;
    let mut short = 0;
    for row in csv.lines().skip(1) {
        let c: Vec<&str> = row.split(',').collect();
        let (family, name, stages) = (c[0], c[1], c[2].parse::<u32>().unwrap());
        let seeds: Vec<f64> = c[6]
            .split_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        let Some(line) = model[family][name].as_object() else {
            continue;
        };
        let at = (0..line["measured"].as_array().unwrap().len())
            .find(|&i| line["measured_stages"][i] == stages && line["measured_args"][i] == c[7]);
        let Some(i) = at else { continue };
        let floor = line["measured"][i][2].as_f64().unwrap();
        let slowest = seeds.iter().copied().fold(f64::INFINITY, f64::min);
        if seeds.len() < MIN_SEEDS {
            short += 1;
            assert!(
                floor <= slowest + 0.005,
                "{row}: floor {floor} above its slowest seed"
            );
        } else {
            assert!(
                (floor - c[5].parse::<f64>().unwrap()).abs() < 0.005,
                "{row}: floor {floor}"
            );
        }
        floors += 1;
    }
    assert!(
        floors > 100 && short > 0,
        "{floors} floors read, {short} of fewer seeds"
    );
}

/// The lines are read in each family's own primitive delays: on the iCE40 the stretches are the
/// placement estimate's (its figures), on the ECP5 and the GW1NR-9 their own (a LUT level and a
/// hard multiply weigh otherwise there), and the shipped model says how well each line fits.
#[test]
fn each_family_weighs_the_stretches_with_its_own_primitive_delays() {
    let at = |target: Target| {
        Plan::new(
            Config::new(crate::config::Params {
                target,
                stages: 5,
                ..Config::defaults().params
            })
            .unwrap(),
        )
        .unwrap()
    };
    let ice40 = at(Target::Ice40);
    assert!(
        (stretches(&ice40).0 - ice40.stage_delay()).abs() < 1e-9
            && (stretches(&ice40).1 - ice40.stage_delay_mean()).abs() < 1e-9
    );
    for target in [Target::Ecp5, Target::Gowin] {
        let p = at(target);
        let w = crate::family::of(target).primitive_delays();
        assert_ne!(w, crate::family::of(Target::Ice40).primitive_delays());
        assert_eq!(
            stretches(&p),
            (p.stage_delay_on(&w), p.stage_delay_mean_on(&w))
        );
        assert!(
            stretches(&p).0 < p.stage_delay(),
            "{target:?}: a faster fabric than the UP5K's"
        );
    }
    for target in [Target::Ice40, Target::Ecp5, Target::Gowin] {
        for (name, l) in lines(target) {
            assert!(
                (0.0..=1.0).contains(&l.r2) && l.offset_ns >= 0.0,
                "{target:?} {name}: R² {} offset {}",
                l.r2,
                l.offset_ns
            );
        }
    }
}
