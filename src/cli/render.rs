//! `specgen render`: pictures of the units' pixels, drawn only when the RTL gives the golden
//! model's every pixel.

use super::{emit, errln, failed, outln, usage, Failure, RenderArgs};

pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    use specgen::cosim;
    if !(16..=1024).contains(&args.size) {
        return Err(usage(format!(
            "invalid --size: {}; allowed 16..=1024",
            args.size
        )));
    }
    if args.n.is_empty() || args.n.len() > 16 {
        return Err(usage(
            "invalid --n: give 1 to 16 exponents, e.g. 1,4,16,128",
        ));
    }
    let units = args.rtl.len() + args.models.len();
    if !(1..=6).contains(&units) {
        return Err(usage(format!(
            "render: give 1 to 6 units with --rtl DIR and --models LIST (got {units})"
        )));
    }
    // the --models units, generated at default parameters beside each other
    let scratch = specgen::process::temp_dir().map_err(|e| {
        specgen::error::Error::io("create a temporary directory in", std::env::temp_dir(), e)
    })?;
    let mut dirs = args.rtl.clone();
    for m in &args.models {
        let model: specgen::config::SpecularModel = (*m).into();
        let plan = specgen::plan::Plan::from_params(specgen::config::Params {
            model,
            ..Default::default()
        })?;
        let dir = scratch.path().join(model.name());
        specgen::output::write_dir_atomically(&dir, &emit::generate_files(&plan))?;
        dirs.push(dir);
    }
    let mut designs = Vec::new();
    for dir in &dirs {
        let design = cosim::Design::load(dir)?;
        design.verify_files(false)?;
        design.refuse_output("--out", &args.out)?;
        let n_max = (1u32 << design.cfg.n_bits()) - 1;
        if let Some(bad) = args.n.iter().find(|&&n| n > n_max) {
            return Err(usage(format!(
                "invalid --n: {bad} is out of range for {}; allowed 0..={n_max} (n_bits = {})",
                dir.display(),
                design.cfg.n_bits()
            )));
        }
        designs.push(design);
    }
    let models: Vec<specgen::models::Model> = designs.iter().map(|d| d.plan.model()).collect();
    if !args.model_only {
        for (design, model) in designs.iter().zip(&models) {
            let pixels = render_through_rtl(design, &args.sim.tools(), model, &args.n, args.size)?;
            errln!("render: {pixels} pixels through the RTL in {} (Verilator), all bit-identical to the golden model", design.dir.display());
        }
    }
    let refs: Vec<&specgen::models::Model> = models.iter().collect();
    let picture = specgen::render::picture(&refs, &args.n, args.size);
    specgen::output::write_file(&args.out, &picture.png)
        .map_err(|e| specgen::error::Error::io("write", &args.out, e))?;
    outln!("{}", args.out.display())?;
    Ok(())
}

/// Runs every pixel of a picture through the unit's RTL and checks each against the golden
/// model: the picture is drawn from the model only when all are bit-identical.
fn render_through_rtl(
    design: &specgen::cosim::Design,
    sim: &specgen::cosim::SimTools,
    model: &specgen::models::Model,
    ns: &[u32],
    size: u32,
) -> Result<u64, Failure> {
    use specgen::cosim::{self, Cycle, Recorded, Stimulus};
    use specgen::render::{self, Scene};
    cosim::check_ports(design)?;
    cosim::check_tables(design)?;
    let mut cycles = Vec::new();
    if design.cfg.clocked() {
        // a reset; then a cycle for in_ready to rise, which also loads a static colour
        // (every pixel of a picture has full-scale colours)
        cycles.push(Cycle::reset());
        let full = (1u32 << design.cfg.b()) - 1;
        let load = design.cfg.colour() == specgen::config::Colour::Static;
        cycles.push(Cycle {
            inputs: specgen::models::Inputs {
                ks: [full; 3],
                ..Default::default()
            },
            load,
            ..Cycle::default()
        });
    }
    let mut pixels = 0u64;
    for &n in ns {
        for scene in [Scene::Sphere, Scene::GrazingPlane] {
            let tile = render::tile_inputs(model, scene, n, size);
            pixels += tile.len() as u64;
            cycles.extend(tile.into_iter().map(Cycle::pixel));
        }
    }
    // the pipeline (and a handshake's buffer) empties before the run ends
    cycles.extend((0..design.cfg.latency() + 2).map(|_| Cycle::default()));
    let stim: Vec<Box<dyn Stimulus>> = vec![Box::new(Recorded(cycles))];
    let built = cosim::build(
        design,
        cosim::Simulator::Verilator,
        sim,
        false,
        stim[0].len(),
    )?;
    let report = cosim::run_all(&built, design, model, &stim, 1)?;
    let dir = design.dir.display();
    if report.mismatches > 0 {
        return Err(failed(format!(
            "the RTL in {dir} differs from the golden model at {} of {} pixels; no picture written (run `specgen cosim --rtl {dir}`)",
            report.mismatches, report.checked
        )));
    }
    if report.results != pixels {
        return Err(failed(format!(
            "the RTL in {dir} gave {} results for {pixels} pixels; no picture written",
            report.results
        )));
    }
    Ok(pixels)
}
