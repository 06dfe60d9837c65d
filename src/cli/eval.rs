//! `eval` and `vectors`: the golden model's values on the command line.

use super::*;

pub(super) fn eval(
    cfg: &Config,
    cos: Option<&str>,
    cos_code: Option<u32>,
    n: u32,
    ks: Option<Vec<u32>>,
) -> Result<(), Failure> {
    let f = cfg.f();
    let cos_g = match (cos, cos_code) {
        (Some(text), _) => {
            let code = config::parse_decimal(text, f).map_err(|why| {
                usage(format!(
                    "invalid --cos: {}; allowed a decimal in [0, 2)",
                    why.reason()
                ))
            })?;
            if code >= 2u64 << f {
                let top = format!(
                    "{:.*}",
                    (f as usize * 3).div_ceil(10) + 1,
                    ((2u64 << f) - 1) as f64 / (1u64 << f) as f64
                );
                return Err(usage(
                    if text.trim_start().starts_with('-')
                        || text.trim().parse::<f64>().is_ok_and(|v| v >= 2.0)
                    {
                        format!(
                            "invalid --cos: {text} is out of range; allowed a decimal in [0, 2)"
                        )
                    } else {
                        format!(
                        "invalid --cos: {text} rounds to 2 at cos_frac_bits = {f} (the nearest multiple of 2^-{f}), one past the largest code; allowed a decimal in [0, 2) that rounds to at most {top}, or --cos-code"
                    )
                    },
                ));
            }
            code as u32
        }
        (None, Some(code)) if code < 2u32 << f => code,
        (None, Some(code)) => {
            return Err(usage(format!(
                "invalid --cos-code: {code} is out of range; allowed 0..={}",
                (2u32 << f) - 1
            )))
        }
        (None, None) => return Err(usage("one of --cos or --cos-code is required")),
    };
    let n_max = (1u32 << cfg.n_bits()) - 1;
    if n > n_max {
        return Err(usage(format!(
            "invalid --n: {n} is out of range; allowed 0..={n_max} (n_bits = {})",
            cfg.n_bits()
        )));
    }
    let ks_max = (1u32 << cfg.b()) - 1;
    let ks = ks.unwrap_or_else(|| vec![ks_max; 3]);
    if ks.len() != 3 {
        return Err(usage(format!(
            "invalid --ks: give three codes R,G,B, each 0..={ks_max}"
        )));
    }
    if let Some(bad) = ks.iter().find(|&&k| k > ks_max) {
        return Err(usage(format!(
            "invalid --ks: {bad} is out of range; allowed 0..={ks_max} (color_bits = {})",
            cfg.b()
        )));
    }
    let x = Inputs {
        cos_g,
        n,
        ks: [ks[0], ks[1], ks[2]],
    };
    // the golden model alone: no datapath, no Verilog
    let m = specgen::models::Model::new(cfg);
    let o = m.eval(x);
    let c = cos_g.min(1 << f) as f64 / (1u64 << f) as f64;
    let blinn = c.powi(n as i32);
    let scale = (cfg.fi() as f64).exp2();
    outln!(
        "input      cos_g = {cos_g} (UQ1.{f} = {}), n = {n}, ks = {:?}",
        exact_decimal(cos_g as u64, f),
        x.ks
    )?;
    outln!("model      {}", cfg.model().name())?;
    for line in m.unit().explain(x) {
        outln!("{line}")?;
    }
    outln!(
        "outputs    intensity = {} (UQ1.{} = {:.9})  spec = {:?}  done = {}",
        o.intensity,
        cfg.fi(),
        o.intensity as f64 / scale,
        o.spec,
        o.done
    )?;
    outln!(
        "fidelity   Blinn cos^n = {blinn:.9}; this unit gives {:.9}, off by {:.9}{}",
        o.intensity as f64 / scale,
        (o.intensity as f64 / scale - blinn).abs(),
        m.unit()
            .fidelity_note(x)
            .map_or(String::new(), |note| format!("; {note}"))
    )?;
    match m.check(x, o) {
        Ok(()) => outln!(
            "contract   {} rounding holds for this input ({} model)",
            cfg.rounding().name(),
            cfg.model().name()
        )?,
        Err(e) => return Err(failed(format!("contract violated: {e}"))),
    }
    Ok(())
}

pub(super) fn vectors(args: &VectorsArgs) -> Result<(), Failure> {
    use specgen::vectors::{Selection, VectorFormat};
    let design = specgen::cosim::Design::load(&args.rtl)?;
    design.verify_files(false)?;
    design.refuse_output("--out", &args.out)?;
    let model = design.plan.model();
    let selection = if args.exhaustive {
        Selection::Exhaustive
    } else {
        Selection::Random {
            count: args.count,
            seed: args.seed,
        }
    };
    let format = args.format.map(Into::into).unwrap_or_else(|| {
        match args
            .out
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("hex" | "mem") => VectorFormat::Hex,
            _ => VectorFormat::Csv,
        }
    });
    let (wanted, _) = specgen::vectors::inputs(&model, selection);
    if wanted > args.max_rows {
        return Err(usage(format!(
            "invalid --max-rows: this set is {wanted} rows ({:.1} GB or more as text) and --max-rows is {}; allowed: raise --max-rows to at least {wanted}, or narrow --n-bits/--cos-frac-bits, or use random vectors (--count)",
            wanted as f64 * 40.0 / 1e9,
            args.max_rows
        )));
    }
    let rows = specgen::output::write_file_with(&args.out, |w| {
        specgen::vectors::write(&model, selection, format, w)
    })
    .map_err(|e| Failure::io("write", &args.out, e))?;
    outln!(
        "{rows} vectors ({format:?}, latency {}) written to {}",
        design.cfg.latency(),
        args.out.display()
    )?;
    Ok(())
}
