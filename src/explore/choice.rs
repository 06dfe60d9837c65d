//! The choice `generate --max-error` makes from an exploration: the question (the user's
//! parameters and edge), the evidence of today's RTL, and the cheapest measured unit that
//! answers it.

use super::*;

/// What [`choose`] picked, with its evidence.
#[derive(Debug, Clone)]
pub struct Choice {
    pub point: Point,
    /// its error by the question's metric, recomputed by the golden model (never the file's)
    pub error: f64,
    /// SHA-256 of the RTL and tables it was measured on: today's
    pub rtl: String,
    /// measured points of the exploration left out because their RTL is not today's
    pub stale: Vec<String>,
}

/// The parameters of the interface: a unit measured with another edge is another unit (its
/// handshake costs cells and clock), so a choice is made among units with the user's.
pub const EDGE_KEYS: [&str; 5] = ["interface", "tag_bits", "tlast", "colour", "clock_enable"];

/// The parameters a user may give beside `--max-error`, each narrowing the choice to the
/// points that have it (by `Params`' field name).
pub const CHOICE_KEYS: [&str; 13] = [
    "model",
    "cos_frac_bits",
    "intensity_frac_bits",
    "stages",
    "dsp_budget",
    "rom_style",
    "k",
    "k_frac_bits",
    "rounding",
    "arch",
    "max_squarings",
    "fabric_registers",
    "reset",
];

/// A `generate --max-error E --target-mhz F` question.
#[derive(Debug, Clone)]
pub struct Question<'a> {
    /// the user's parameters (given or default)
    pub base: &'a Params,
    /// which of [`CHOICE_KEYS`] the user gave: each narrows the choice
    pub given: &'a [&'a str],
    pub metric: Metric,
    pub max_error: f64,
    pub mhz: f64,
    /// the display the display metrics are in
    pub display: Display,
}

/// One field of `p` by its name, as JSON (the form the manifest and the explorations store).
pub(super) fn field(p: &Params, key: &str) -> serde_json::Value {
    serde_json::to_value(p)
        .ok()
        .and_then(|v| v.get(key).cloned())
        .unwrap_or(serde_json::Value::Null)
}

/// Whether a measured point's rows are of the RTL specgen writes today: each of its jobs'
/// fingerprints is the one a job of today's unit (its RTL and tables' digest), with the tools
/// that measured it, would have. Returns today's digest where they are.
pub fn measured_today(p: &Point) -> Result<Option<String>, Error> {
    let Some(m) = &p.measured else {
        return Ok(None);
    };
    if m.jobs.len() != m.seeds.len() || m.jobs.is_empty() {
        return Ok(None);
    }
    let rtl = rtl_digest(&Plan::new(Config::new(p.params.clone())?)?);
    let today = m.seeds.iter().zip(&m.jobs).all(|(&seed, fp)| {
        let j = Job::new(p, &rtl, seed, &m.tools);
        &j.fingerprint == fp || &j.fabric_only().fingerprint == fp
    });
    Ok(today.then_some(rtl))
}

/// What [`evidence`] finds of an exploration's measured rows.
#[derive(Debug, Clone, Default)]
pub struct Evidence {
    /// the measured points whose jobs are today's RTL's, with its digest
    pub today: Vec<(String, String)>,
    /// the measured points of an older RTL (or of rows that name no jobs)
    pub stale: Vec<String>,
}

/// Which measured rows of `e` are of the RTL specgen writes today ([`measured_today`]); each
/// point costs one generation of its unit's sources (no synthesis): seconds for an exploration.
pub fn evidence(e: &Exploration) -> Result<Evidence, Error> {
    let mut ev = Evidence::default();
    for p in e.points.iter().filter(|p| p.measured.is_some()) {
        match measured_today(p)? {
            Some(rtl) => ev.today.push((p.id.clone(), rtl)),
            None => ev.stale.push(p.id.clone()),
        }
    }
    Ok(ev)
}

/// The cheapest measured point of `e` (logic cells, then the higher clock) whose error by the
/// question's metric is at most `max_error` and whose median Fmax reaches `mhz`, among those
/// of the user's fixed parameters (exponent's and colours' widths, target), the user's edge
/// ([`EDGE_KEYS`]) and every parameter given ([`CHOICE_KEYS`]), and measured on today's RTL.
/// The error is recomputed by the golden model for every point that could be chosen (a file's
/// figure is never believed). Err: none does, in one line: the reason, the nearest measured
/// unit and the command that would measure the one asked for.
pub fn choose(e: &Exploration, q: &Question) -> Result<Choice, Error> {
    let base = q.base;
    let mut keys: Vec<&str> = vec!["n_bits", "color_bits", "target"];
    keys.extend(EDGE_KEYS);
    // a budget given is a ceiling, not a shape: a unit of another budget (or none) that takes
    // no more blocks meets it
    let budget = if q.given.contains(&"dsp_budget") {
        base.dsp_budget
    } else {
        None
    };
    keys.extend(
        q.given
            .iter()
            .copied()
            .filter(|k| CHOICE_KEYS.contains(k) && *k != "dsp_budget"),
    );
    let fits = |p: &&Point| keys.iter().all(|k| field(&p.params, k) == field(base, k));
    let kept = |p: &&Point| budget.is_none_or(|b| under_budget(p, b));
    let measured: Vec<&Point> = e
        .points
        .iter()
        .filter(fits)
        .filter(kept)
        .filter(|p| p.measured.as_ref().is_some_and(|m| m.fmax_mhz.is_some()))
        .collect();
    let reach = |p: &&Point| {
        p.measured
            .as_ref()
            .and_then(|m| m.fmax_mhz)
            .is_some_and(|f| f >= q.mhz)
    };
    let mut reaching: Vec<&Point> = measured.iter().copied().filter(reach).collect();
    reaching.sort_by(|a, b| {
        a.cells()
            .cmp(&b.cells())
            .then(b.fmax().unwrap_or(0.0).total_cmp(&a.fmax().unwrap_or(0.0)))
            .then(a.id.cmp(&b.id))
    });
    // the error at the pixel is never below the error at the codes: a file's code figure
    // above the bound rules a point out without computing; every other is recomputed
    let mut accuracies: BTreeMap<String, Accuracy> = BTreeMap::new();
    let mut recomputed = |p: &Point| -> Result<Accuracy, Error> {
        let shape = Config::new(Params {
            stages: 0,
            dsp_budget: None,
            ..p.params.clone()
        })?;
        let key = shape.fingerprint();
        if let Some(a) = accuracies.get(&key) {
            return Ok(a.clone());
        }
        let a = accuracy_on(&Model::new(&shape), q.display);
        accuracies.insert(key, a.clone());
        Ok(a)
    };
    let mut stale = Vec::new();
    for p in &reaching {
        let floor = match q.metric {
            Metric::Max | Metric::CodeMax => p.accuracy.max,
            _ => 0.0,
        };
        if floor > q.max_error {
            continue;
        }
        let a = recomputed(p)?;
        let err = q.metric.of(&a);
        if err > q.max_error {
            continue;
        }
        match measured_today(p)? {
            Some(rtl) => {
                let point = Point {
                    accuracy: a,
                    ..(*p).clone()
                };
                return Ok(Choice {
                    point,
                    error: err,
                    rtl,
                    stale,
                });
            }
            None => stale.push(p.id.clone()),
        }
    }
    let show = |p: &Point| {
        format!(
            "{} ({} error {}, {:.1} MHz, {} logic cells)",
            p.id,
            q.metric.name(),
            short(q.metric.of(&p.accuracy)),
            p.fmax().unwrap_or(0.0),
            p.cells()
        )
    };
    let why = if measured.is_empty() {
        format!(
            "no unit of the {} exploration with these parameters ({}) was measured",
            e.part,
            keys.iter()
                .map(|k| format!("{k} {}", field(base, k)))
                .collect::<Vec<_>>()
                .join(", ")
        )
    } else if !stale.is_empty() {
        format!(
            "the units of the {} exploration that would meet it were measured on an older RTL ({})",
            e.part,
            stale.join(", ")
        )
    } else if reaching.is_empty() {
        format!(
            "no measured unit of the {} exploration reaches {} MHz",
            e.part, q.mhz
        )
    } else {
        format!(
            "no measured unit of the {} exploration that reaches {} MHz has {} error <= {}",
            e.part,
            q.mhz,
            q.metric.name(),
            q.max_error
        )
    };
    // the nearest: the most accurate unit reaching the clock (its error recomputed)
    let mut nearest = String::new();
    if let Some(p) = reaching.iter().min_by(|a, b| {
        q.metric
            .of(&a.accuracy)
            .total_cmp(&q.metric.of(&b.accuracy))
            .then(a.cells().cmp(&b.cells()))
    }) {
        let a = recomputed(p)?;
        nearest = format!(
            "; nearest: {}",
            show(&Point {
                accuracy: a,
                ..(*p).clone()
            })
        );
    } else if let Some(p) = measured
        .iter()
        .max_by(|a, b| a.fmax().unwrap_or(0.0).total_cmp(&b.fmax().unwrap_or(0.0)))
    {
        nearest = format!("; the fastest measured: {}", show(p));
    }
    // and the fastest measured unit of today's RTL within the error (its error recomputed): the
    // clock the user can have at that error
    let mut by_clock: Vec<&Point> = measured.iter().copied().filter(|p| !reach(p)).collect();
    by_clock.sort_by(|a, b| {
        b.fmax()
            .unwrap_or(0.0)
            .total_cmp(&a.fmax().unwrap_or(0.0))
            .then(a.cells().cmp(&b.cells()))
    });
    for p in by_clock
        .into_iter()
        .filter(|p| {
            !matches!(q.metric, Metric::Max | Metric::CodeMax) || p.accuracy.max <= q.max_error
        })
        .take(64)
    {
        let a = recomputed(p)?;
        if q.metric.of(&a) <= q.max_error && measured_today(p)?.is_some() {
            nearest.push_str(&format!(
                "; the fastest within the error: {}",
                show(&Point {
                    accuracy: a,
                    ..p.clone()
                })
            ));
            break;
        }
    }
    Err(Error::Config {
        parameter: "max_error",
        message: format!(
            "{why}{nearest}; measure the units you want: specgen explore --target {} --n-bits {} --color-bits {}{}{} --clocks {} --out DIR --results RESULTS --run, then generate --explored DIR/points.json",
            base.target.name(),
            base.n_bits,
            base.color_bits,
            match base.interface {
                crate::config::Interface::Valid => String::new(),
                i => format!(" --interface {}", i.name()),
            },
            q.given.iter().filter(|&&k| k == "model").map(|_| format!(" --models {}", base.model.name())).collect::<String>(),
            q.mhz
        ),
    })
}

/// Whether `p` keeps to a DSP budget of `b` blocks: its own budget is `b`, or its measurement
/// takes at most `b` blocks (a unit of another budget, or none, whose RTL the budget would not
/// change in function: it is written as measured, its digest the measurement's).
pub(super) fn under_budget(p: &Point, b: u32) -> bool {
    p.params.dsp_budget == Some(b)
        || p.measured
            .as_ref()
            .is_some_and(|m| m.dsp_blocks <= b as u64)
}

/// A figure in three significant digits.
pub(super) fn short(x: f64) -> String {
    format!("{x:.3e}")
}
