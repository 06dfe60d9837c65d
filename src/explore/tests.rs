//! The front, the fingerprints, the merge and the choice.

use super::*;
use crate::config::{Params, RomStyle, SpecularModel};

fn space() -> Space {
    let base = Params {
        n_bits: 4,
        color_bits: 4,
        ..Params::default()
    };
    Space {
        base,
        models: SpecularModel::ALL[..2].to_vec(),
        cos_frac_bits: vec![8],
        intensity_frac_bits: vec![8],
        dsp_budgets: vec![None],
        rom_styles: vec![RomStyle::File],
        clocks: vec![],
        spread: 0,
        display: crate::models::display::Display::SRGB8,
    }
}

#[test]
fn a_front_is_what_no_point_beats_on_both() {
    let mut ps = points(&space(), &|_, _| {}).unwrap();
    assert!(ps.len() >= 2);
    let clocks = space().clocks();
    mark_fronts(&mut ps, Metric::Max, &clocks);
    for &mhz in &clocks {
        let on: Vec<&Point> = ps.iter().filter(|p| p.front.contains(&mhz)).collect();
        for p in &on {
            assert!(p.fmax().unwrap() >= mhz);
            // no point reaching the clock is both cheaper-or-equal and strictly better
            assert!(!ps.iter().any(|q| q.fmax().is_some_and(|f| f >= mhz)
                && q.cells() <= p.cells()
                && Metric::Max.of(&q.accuracy) < Metric::Max.of(&p.accuracy)));
        }
        // every point reaching the clock is beaten or matched by a front point
        for q in ps.iter().filter(|q| q.fmax().is_some_and(|f| f >= mhz)) {
            assert!(
                on.iter().any(|p| p.cells() <= q.cells()
                    && Metric::Max.of(&p.accuracy) <= Metric::Max.of(&q.accuracy)),
                "{} not covered",
                q.id
            );
        }
    }
}

#[test]
fn a_fingerprint_changes_with_params_seed_and_tools() {
    let ps = points(&space(), &|_, _| {}).unwrap();
    let tools: Versions = [("yosys".to_string(), "Yosys 0.23".to_string())].into();
    let a = Job::new(&ps[0], "r", 1, &tools);
    assert_eq!(a.fingerprint, a.compute_fingerprint());
    assert_ne!(a.fingerprint, Job::new(&ps[0], "r", 2, &tools).fingerprint);
    assert_ne!(a.fingerprint, Job::new(&ps[1], "r", 1, &tools).fingerprint);
    assert_ne!(
        a.fingerprint,
        Job::new(&ps[0], "another RTL", 1, &tools).fingerprint
    );
    let newer: Versions = [("yosys".to_string(), "Yosys 0.70".to_string())].into();
    assert_ne!(a.fingerprint, Job::new(&ps[0], "r", 1, &newer).fingerprint);
    // the fabric's products are another measurement; a job with the hard multipliers reads and
    // writes as before jobs could ask otherwise (its field left out)
    let fabric = a.clone().fabric_only();
    assert_ne!(a.fingerprint, fabric.fingerprint);
    assert_eq!(fabric.fingerprint, fabric.compute_fingerprint());
    let text = serde_json::to_string(&a).unwrap();
    assert!(!text.contains("\"dsp\""), "{text}");
    assert_eq!(serde_json::from_str::<Job>(&text).unwrap(), a);
    let text = serde_json::to_string(&fabric).unwrap();
    assert_eq!(serde_json::from_str::<Job>(&text).unwrap(), fabric);
}

#[test]
fn a_merge_names_missing_and_conflicting_jobs() {
    let mut ps = points(&space(), &|_, _| {}).unwrap();
    let tools: Versions = [("yosys".to_string(), "x".to_string())].into();
    let ids = vec![ps[0].id.clone(), ps[1].id.clone()];
    let jobs = jobs_of(&ps, &ids, &[1, 2], &tools).unwrap();
    assert_eq!(jobs.len(), 4);
    let result = |j: &Job, f: f64| JobResult {
        job: j.clone(),
        synth: crate::synth::SynthResult {
            fmax_mhz: Some(f),
            logic_cells: Some(100),
            ..Default::default()
        },
    };
    let mut rs = vec![
        result(&jobs[0], 50.0),
        result(&jobs[1], 60.0),
        result(&jobs[2], 70.0),
        result(&jobs[2], 71.0),
    ];
    let report = merge(&mut ps, &jobs, &rs);
    assert_eq!(report.missing.len(), 1);
    assert!(report.missing[0].starts_with(&jobs[3].fingerprint));
    assert_eq!(report.conflicting.len(), 1);
    assert_eq!(ps[0].measured.as_ref().unwrap().fmax_mhz, Some(55.0));
    assert!(ps[1].measured.is_none());
    rs.pop();
    rs.push(result(&jobs[3], 80.0));
    let report = merge(&mut ps, &jobs, &rs);
    assert!(report.missing.is_empty() && report.conflicting.is_empty());
    assert_eq!(ps[1].measured.as_ref().unwrap().fmax_mhz, Some(75.0));
}

/// Every point of the space measured on today's RTL (its jobs' fingerprints today's), the
/// i-th at 50 + 10·i MHz and 100 + i cells.
fn measured_exploration() -> (Vec<Point>, Exploration) {
    let mut ps = points(&space(), &|_, _| {}).unwrap();
    let tools: Versions = [("yosys".to_string(), "x".to_string())].into();
    let ids: Vec<String> = ps.iter().map(|p| p.id.clone()).collect();
    let jobs = jobs_of(&ps, &ids, &[1], &tools).unwrap();
    for (i, p) in ps.iter_mut().enumerate() {
        p.measured = Some(Measured {
            seeds: vec![1],
            fmax_seeds: vec![50.0 + 10.0 * i as f64],
            fmax_mhz: Some(50.0 + 10.0 * i as f64),
            route_seeds: vec![],
            logic_cells: Some(100 + i as u64),
            luts: 0,
            flip_flops: 0,
            dsp_blocks: 0,
            block_rams: 0,
            limited_by: String::new(),
            note: String::new(),
            jobs: vec![jobs
                .iter()
                .find(|j| j.point == p.id)
                .unwrap()
                .fingerprint
                .clone()],
            tools: tools.clone(),
        });
    }
    let e = Exploration {
        generator: "specgen".into(),
        version: "x".into(),
        target: "ice40".into(),
        part: "p".into(),
        metric: "max".into(),
        clocks: vec![],
        seeds: vec![1],
        points: ps.clone(),
    };
    (ps, e)
}

fn ask<'a>(
    base: &'a Params,
    given: &'a [&'a str],
    metric: Metric,
    max_error: f64,
    mhz: f64,
) -> Question<'a> {
    Question {
        base,
        given,
        metric,
        max_error,
        mhz,
        display: crate::models::display::Display::SRGB8,
    }
}

#[test]
fn the_choice_is_the_cheapest_measured_point_meeting_both() {
    let (ps, e) = measured_exploration();
    let base = &space().base;
    let c = choose(&e, &ask(base, &[], Metric::Max, 1.0, 50.0)).unwrap();
    assert_eq!(c.point.id, ps[0].id);
    assert_eq!(c.rtl.len(), 64);
    let c = choose(&e, &ask(base, &[], Metric::Max, 1.0, 55.0)).unwrap();
    assert_eq!(c.point.id, ps[1].id);
    let err = choose(&e, &ask(base, &[], Metric::Max, 1e-9, 50.0)).unwrap_err();
    assert_eq!(err.parameter(), Some("max_error"));
    assert!(err.reason().contains("nearest"), "{}", err.reason());
    let other = Params {
        n_bits: 10,
        ..base.clone()
    };
    assert!(choose(&e, &ask(&other, &[], Metric::Max, 1.0, 50.0)).is_err());
}

/// The error chosen by is the pixel's (the real cosine rounded to F bits), recomputed: a file
/// whose figures lie is not believed, and the unit's error at its codes is a metric of its own.
#[test]
fn the_choice_bounds_the_error_at_the_pixel_recomputed() {
    let (ps, mut e) = measured_exploration();
    let base = &space().base;
    // the file claims every point perfect
    for p in &mut e.points {
        p.accuracy.pixel = Some(PixelAccuracy {
            max: 0.0,
            mean: 0.0,
            rms: 0.0,
            bound: false,
        });
        p.accuracy.max = 0.0;
    }
    let truth = accuracy(&Model::new(&Config::new(ps[0].params.clone()).unwrap()));
    let pixel = truth.pixel.unwrap();
    // at F = 8 and n up to 15 the rounding alone costs more than the codes' error
    assert!(pixel.max > truth.max, "{pixel:?} vs {}", truth.max);
    let c = choose(&e, &ask(base, &[], Metric::Max, 1.0, 50.0)).unwrap();
    assert_eq!(c.error, pixel.max);
    // below it, no point of that model: every other choice is within the bound, recomputed
    if let Ok(c) = choose(&e, &ask(base, &[], Metric::Max, pixel.max * 0.99, 50.0)) {
        assert_ne!(c.point.params.model, ps[0].params.model);
        assert!(c.error <= pixel.max * 0.99);
        assert_eq!(
            Some(c.error),
            accuracy(&Model::new(&Config::new(c.point.params.clone()).unwrap()))
                .pixel
                .map(|p| p.max)
        );
    }
    let c = choose(&e, &ask(base, &[], Metric::CodeMax, truth.max, 50.0)).unwrap();
    assert_eq!(c.point.id, ps[0].id);
    // in a display's codes: the question's display, recomputed (the file says nothing of it)
    for p in &mut e.points {
        p.accuracy.display = None;
    }
    let shown = crate::models::display::display_error(
        &Model::new(&Config::new(ps[0].params.clone()).unwrap()),
        crate::models::display::Display::SRGB8,
    );
    let c = choose(&e, &ask(base, &[], Metric::DisplayMax, 255.0, 50.0)).unwrap();
    assert_eq!(
        (c.point.id.as_str(), c.error),
        (ps[0].id.as_str(), shown.max_codes)
    );
    let c = choose(&e, &ask(base, &[], Metric::DisplayBanding, 255.0, 50.0)).unwrap();
    assert_eq!(c.error, shown.banding_codes);
}

/// A parameter the user gives narrows the choice; one that no measured unit has refuses it.
/// The edge (interface, tag, tlast, colour, clock enable) is always the user's.
#[test]
fn the_users_parameters_and_edge_are_part_of_the_question() {
    let (ps, e) = measured_exploration();
    let base = &space().base;
    let j = ps
        .iter()
        .position(|p| p.params.model != ps[0].params.model)
        .unwrap();
    // the model of a later point, given: the first (cheaper) is not chosen
    let second = Params {
        model: ps[j].params.model,
        ..base.clone()
    };
    let c = choose(&e, &ask(&second, &["model"], Metric::Max, 1.0, 50.0)).unwrap();
    assert_eq!(c.point.params.model, ps[j].params.model);
    // a width no point has, given: refused, never overwritten
    let wide = Params {
        cos_frac_bits: 12,
        ..base.clone()
    };
    let err = choose(&e, &ask(&wide, &["cos_frac_bits"], Metric::Max, 1.0, 50.0)).unwrap_err();
    assert!(
        err.reason().contains("cos_frac_bits 12"),
        "{}",
        err.reason()
    );
    // the same width not given: chosen for the user
    assert!(choose(&e, &ask(&wide, &[], Metric::Max, 1.0, 50.0)).is_ok());
    for edge in [
        Params {
            interface: crate::config::Interface::Axis,
            ..base.clone()
        },
        Params {
            clock_enable: true,
            ..base.clone()
        },
        Params {
            colour: crate::config::Colour::Static,
            ..base.clone()
        },
    ] {
        let err = choose(&e, &ask(&edge, &[], Metric::Max, 1.0, 50.0)).unwrap_err();
        assert!(err.reason().contains("was measured"), "{}", err.reason());
    }
}

/// A row measured on another RTL (its jobs' fingerprints not today's) is never chosen.
#[test]
fn a_row_of_another_rtl_is_never_chosen() {
    let (ps, mut e) = measured_exploration();
    let base = &space().base;
    let stale =
        |p: &mut Point| p.measured.as_mut().unwrap().jobs = vec!["00000000000000000000".into()];
    stale(&mut e.points[0]);
    assert_eq!(measured_today(&e.points[0]).unwrap(), None);
    assert!(measured_today(&e.points[1]).unwrap().is_some());
    let c = choose(&e, &ask(base, &[], Metric::Max, 1.0, 50.0)).unwrap();
    assert_eq!(c.point.id, ps[1].id);
    assert_eq!(c.stale, vec![ps[0].id.clone()]);
    e.points.iter_mut().for_each(stale);
    let err = choose(&e, &ask(base, &[], Metric::Max, 1.0, 50.0)).unwrap_err();
    assert!(err.reason().contains("older RTL"), "{}", err.reason());
}

/// A point's estimate is its own parameters' plan's (a model shared across the space must not
/// carry one style's datapath into another's: lean's table as logic has more cut points).
#[test]
fn every_point_is_the_plan_of_its_own_parameters() {
    let quadratic = SpecularModel::ALL
        .into_iter()
        .filter(|m| m.takes("rounding=exact"))
        .collect();
    let target = crate::config::Target::ALL
        .into_iter()
        .find(|t| crate::family::of(*t).writes_logic_tables())
        .expect("a family writes tables as logic");
    let s = Space {
        base: Params {
            n_bits: 4,
            color_bits: 4,
            target,
            ..Params::default()
        },
        models: quadratic,
        cos_frac_bits: vec![8],
        intensity_frac_bits: vec![8],
        dsp_budgets: vec![None, Some(2)],
        rom_styles: vec![RomStyle::File, RomStyle::Logic],
        clocks: vec![],
        spread: 2,
        display: crate::models::display::Display::SRGB8,
    };
    let ps = points(&s, &|_, _| {}).unwrap();
    assert!(ps.iter().any(|p| p.params.rom_style == RomStyle::Logic));
    for p in &ps {
        let own = Plan::new(Config::new(p.params.clone()).unwrap()).unwrap();
        assert_eq!(estimate(&own), p.estimate, "{}", p.id);
    }
    let deepest = |rom| {
        ps.iter()
            .filter(|p| p.params.rom_style == rom && p.params.dsp_budget.is_none())
            .map(|p| p.stages)
            .max()
            .unwrap()
    };
    let own_deepest = |rom| {
        Plan::new(
            Config::new(Params {
                rom_style: rom,
                ..s.base.clone()
            })
            .unwrap(),
        )
        .unwrap()
        .cut_points
    };
    assert_eq!(deepest(RomStyle::Logic), own_deepest(RomStyle::Logic));
    assert_eq!(deepest(RomStyle::File), own_deepest(RomStyle::File));
}

/// A result is checked against its job: another model, depth, seed or family, an Fmax past
/// the part's reach or more cells than it has is refused, whatever the fingerprint says.
#[test]
fn a_result_is_checked_against_its_job() {
    let ps = points(&space(), &|_, _| {}).unwrap();
    let tools: Versions = [("yosys".to_string(), "x".to_string())].into();
    let job = jobs_of(&ps, &[ps[0].id.clone()], &[2], &tools)
        .unwrap()
        .remove(0);
    let p = &job.params;
    let good = crate::synth::SynthResult {
        model: p.model.name().into(),
        stages: p.stages,
        widths: format!(
            "{}/{}/{}/{}",
            p.cos_frac_bits, p.n_bits, p.color_bits, p.intensity_frac_bits
        ),
        seeds: vec![2],
        target: p.target.name().into(),
        dsp: true,
        fmax_mhz: Some(120.0),
        fmax_route_mhz: Some(120.0),
        fmax_seeds: vec![120.0],
        logic_cells: Some(300),
        ..Default::default()
    };
    assert!(JobResult {
        job: job.clone(),
        synth: good.clone()
    }
    .check()
    .is_ok());
    let edits: Vec<(&str, crate::synth::SynthResult)> = vec![
        (
            "model",
            crate::synth::SynthResult {
                model: SpecularModel::ALL
                    .iter()
                    .find(|m| **m != p.model)
                    .unwrap()
                    .name()
                    .into(),
                ..good.clone()
            },
        ),
        (
            "stages",
            crate::synth::SynthResult {
                stages: p.stages + 1,
                ..good.clone()
            },
        ),
        (
            "widths",
            crate::synth::SynthResult {
                widths: "15/10/8/15".into(),
                ..good.clone()
            },
        ),
        (
            "seeds",
            crate::synth::SynthResult {
                seeds: vec![1],
                ..good.clone()
            },
        ),
        (
            "target",
            crate::synth::SynthResult {
                target: "ecp5".into(),
                ..good.clone()
            },
        ),
        (
            "dsp",
            crate::synth::SynthResult {
                dsp: false,
                ..good.clone()
            },
        ),
        (
            "Fmax",
            crate::synth::SynthResult {
                fmax_mhz: Some(999.0),
                ..good.clone()
            },
        ),
        (
            "logic cells",
            crate::synth::SynthResult {
                logic_cells: Some(1_000_000),
                ..good.clone()
            },
        ),
    ];
    for (what, synth) in edits {
        let why = JobResult {
            job: job.clone(),
            synth,
        }
        .check()
        .unwrap_err()
        .reason();
        assert!(why.contains(what), "{what}: {why}");
    }
}

/// The one depth search: a unit of this configuration measured on today's RTL answers first
/// (the shallowest that reaches the clock, its digest named); a row of another RTL never does,
/// and the delay model's figure is then labelled, never "measured".
#[test]
fn the_depth_search_reads_todays_measured_units_first() {
    let e = Exploration::from_text(
        crate::family::of(crate::config::Target::Ice40)
            .explored()
            .expect("built in"),
        "built-in",
    )
    .unwrap();
    // a measured point, and a clock it reaches that a shallower measured one of its shape misses
    let p = e
        .points
        .iter()
        .filter(|p| {
            p.params.interface == crate::config::Interface::Valid
                && p.fmax().is_some_and(|f| f > 60.0)
        })
        .find(|p| p.measured.is_some())
        .expect("a measured point");
    let mhz = p.measured.as_ref().unwrap().fmax_mhz.unwrap();
    let plan = Plan::new(
        Config::new(Params {
            stages: 0,
            ..p.params.clone()
        })
        .unwrap(),
    )
    .unwrap();
    let pick = depth_for_clock(&plan, mhz, Policy::Assured, Some(&e), |_, _| {}).unwrap();
    let today = measured_today(p)
        .unwrap()
        .expect("shipped rows are today's");
    match &pick.evidence {
        ClockEvidence::Measured { median, digest, .. } => {
            assert!(*median >= mhz);
            assert!(
                pick.plan.cfg.stages() <= p.stages,
                "the shallowest measured depth that reaches it"
            );
            let shallowest = e.points.iter().find(|q| {
                measured_shape(&q.params) == measured_shape(&p.params)
                    && q.stages == pick.plan.cfg.stages()
            });
            assert_eq!(
                Some(digest.clone()),
                shallowest.and_then(|q| measured_today(q).unwrap())
            );
            let _ = today;
        }
        other => panic!("not measured: {other}"),
    }
    assert!(
        pick.evidence.to_string().starts_with("measured: "),
        "{}",
        pick.evidence
    );
    // every row of that shape of another RTL: the delay model speaks, and says it is not measured
    let mut stale = e.clone();
    for q in stale
        .points
        .iter_mut()
        .filter(|q| measured_shape(&q.params) == measured_shape(&p.params))
    {
        if let Some(m) = q.measured.as_mut() {
            m.jobs = vec!["00000000000000000000".into(); m.seeds.len()];
        }
    }
    match depth_for_clock(
        &plan,
        mhz.min(50.0),
        Policy::Assured,
        Some(&stale),
        |_, _| {},
    ) {
        Ok(pick) => {
            assert!(
                matches!(pick.evidence, ClockEvidence::Modelled { .. }),
                "{}",
                pick.evidence
            );
            let said = pick.evidence.to_string();
            assert!(
                (said.starts_with("interpolated: ") || said.starts_with("extrapolated: "))
                    && said.contains("not a measurement"),
                "{said}"
            );
        }
        Err(e) => assert!(!e.reason().contains("measured:"), "{}", e.reason()),
    }
}

/// The cost estimate is of what synth measures: over every measured point of the built-in
/// explorations, the median of estimate / measured logic cells is within 10 % of 1 and most
/// points are within 10 %.
#[test]
fn the_estimate_is_near_what_synth_measures() {
    for target in [crate::config::Target::Ice40, crate::config::Target::Ecp5] {
        let e = built_in(target).unwrap().unwrap();
        let mut ratios: Vec<f64> = e
            .points
            .iter()
            .filter_map(|p| Some((p, p.measured.as_ref()?.logic_cells?)))
            .map(|(p, cells)| {
                estimate(&Plan::new(Config::new(p.params.clone()).unwrap()).unwrap()).logic_cells
                    as f64
                    / cells as f64
            })
            .collect();
        ratios.sort_by(f64::total_cmp);
        let median = ratios[ratios.len() / 2];
        let near = ratios.iter().filter(|r| (*r - 1.0).abs() <= 0.1).count();
        assert!(
            (0.9..=1.1).contains(&median),
            "{target:?}: estimate / measured, median {median:.2}"
        );
        assert!(
            2 * near > ratios.len(),
            "{target:?}: {near} of {} points within 10 %",
            ratios.len()
        );
    }
}

/// A calibration row names every width the delay model's shape reads: a unit measured with
/// `--k-frac-bits 20` is a row whose flags plan that unit (it had read as the default 16, the
/// shape of another unit).
#[test]
fn a_calibration_row_names_every_width_its_unit_was_measured_at() {
    let params = Params {
        k_frac_bits: 20,
        cos_frac_bits: 18,
        ..Params::default()
    };
    let mut ps = unit_points(std::slice::from_ref(&params)).unwrap();
    let p = &mut ps[0];
    p.measured = Some(Measured {
        seeds: vec![1],
        fmax_seeds: vec![90.0],
        fmax_mhz: Some(90.0),
        route_seeds: vec![90.0],
        logic_cells: Some(100),
        luts: 0,
        flip_flops: 0,
        dsp_blocks: 0,
        block_rams: 0,
        limited_by: String::new(),
        note: String::new(),
        jobs: vec![],
        tools: Versions::new(),
    });
    let e = Exploration {
        generator: "specgen".into(),
        version: "x".into(),
        target: "ice40".into(),
        part: "p".into(),
        metric: "max".into(),
        clocks: vec![],
        seeds: vec![1],
        points: ps,
    };
    let csv = calibration_csv(&e);
    let row = csv.lines().nth(1).expect("a row");
    let args = row.split(',').nth(7).unwrap();
    assert_eq!(args, "--cos-frac-bits 18 --k-frac-bits 20", "{row}");
    let read = crate::timing::params_with_args(&Params::default(), args).unwrap();
    assert_eq!((read.k_frac_bits, read.cos_frac_bits), (20, 18));
}
