//! The comparison with the golden model, cycle by cycle, and how a mismatch is described.

use super::{Cycle, Sampled, Stimulus};
use crate::config::{Colour, Config};
use crate::models::Model;
use std::collections::VecDeque;

/// The first disagreement found.
#[derive(Debug, Clone)]
pub struct Mismatch {
    /// cycle index within its run
    pub cycle: u64,
    pub run: usize,
    /// the inputs the compared outputs belong to (the pixel's own cycle)
    pub cycle_in: Cycle,
    pub expected: Sampled,
    pub actual: Sampled,
    pub data_compared: bool,
    /// what rule broke, when it is more than a wrong value (a handshake's or idle's rule)
    pub rule: Option<String>,
}

/// The result of checking one or more runs.
#[derive(Debug, Clone, Default)]
pub struct Report {
    pub cycles: u64,
    pub checked: u64,
    /// results delivered and compared (`out_valid`, and `out_ready` behind a handshake)
    pub results: u64,
    /// checked cycles with at least one difference (at most `checked`)
    pub mismatches: u64,
    pub first: Option<Mismatch>,
}

/// A pixel taken and not yet delivered (behind a handshake).
#[derive(Debug, Clone, Copy)]
struct Pending {
    taken_at: u64,
    cycle: Cycle,
    expected: Sampled,
}

/// Compares a sampled stream against the golden model.
///
/// - `valid` interface: cycle by cycle — `out_valid` on every cycle after the first reset,
///   data and tag on every cycle whose output is valid (every cycle when combinational), and
///   `idle` with a static colour.
/// - `ready`/`axis`: transaction by transaction — a pixel is taken when `in_valid && in_ready`
///   at a clock edge without reset, a result delivered when `out_valid && out_ready`; every
///   result must be the next pixel's, in order, with its tag; the outputs must hold while
///   stalled; a pixel taken `latency` cycles ago must be on the outputs (no bubbles);
///   `in_ready` must be high exactly when, three cycles before, fewer than the buffer's places - 3
///   were taken (except the cycle after a reset), and `idle` exactly while none is. An edge with
///   the clock enable low is one with nothing offered, the consumer stalled and no load.
pub struct Checker<'a> {
    model: &'a Model,
    latency: u64,
    last_rst: Option<u64>,
    run: usize,
    static_colour: bool,
    /// the material registers now (a static colour)
    material: [u32; 3],
    /// a load has set them (before it, they hold no value)
    material_loaded: bool,
    /// `valid`: the material in effect in each of the last `latency + 1` cycles
    history: VecDeque<[u32; 3]>,
    /// `ready`/`axis`: the buffer's places, the pixels inside, the last cycle's sample
    places: Option<usize>,
    pending: VecDeque<Pending>,
    /// pixels taken and not yet delivered one, two and three cycles before (none after a reset)
    pending_before: [usize; 3],
    before: Option<(Cycle, Sampled)>,
    /// the last cycle counted as a mismatch (several rules broken in one cycle count once)
    last_failed: Option<u64>,
    pub report: Report,
}

impl<'a> Checker<'a> {
    pub fn new(model: &'a Model, run: usize) -> Checker<'a> {
        let cfg = &model.cfg;
        let places = cfg.interface().handshake().then(|| crate::interface::buffer_places(cfg) as usize);
        Checker {
            model,
            latency: cfg.latency() as u64,
            last_rst: None,
            run,
            static_colour: cfg.colour() == Colour::Static,
            material: [0; 3],
            material_loaded: false,
            history: VecDeque::new(),
            places,
            pending: VecDeque::new(),
            pending_before: [0; 3],
            before: None,
            last_failed: None,
            report: Report::default(),
        }
    }

    /// The outputs the golden model gives for a pixel offered in `c` under `material`.
    fn expect(&self, c: &Cycle, material: [u32; 3]) -> Sampled {
        let mut x = c.inputs;
        if self.static_colour {
            x.ks = material;
        }
        Sampled { outputs: self.model.eval(x), valid: true, tag: c.tag, ..Sampled::default() }
    }

    fn fail(&mut self, t: u64, cycle_in: Cycle, expected: Sampled, actual: Sampled, data_compared: bool, rule: Option<String>) {
        // mismatching cycles, never more than the cycles checked
        if self.last_failed != Some(t) {
            self.report.mismatches += 1;
            self.last_failed = Some(t);
        }
        if self.report.first.is_none() {
            self.report.first = Some(Mismatch { cycle: t, run: self.run, cycle_in, expected, actual, data_compared, rule });
        }
    }

    /// Checks the outputs sampled in cycle `t` (before its rising edge).
    pub fn check(&mut self, stim: &dyn Stimulus, t: u64, got: Sampled) {
        self.report.cycles += 1;
        let mut now = stim.cycle(t);
        if now.disabled {
            // the clock enable low: the edge is one without a transfer or a load, as if nothing
            // were offered and the consumer stalled
            (now.valid, now.stall, now.load) = (false, true, false);
        }
        if self.places.is_some() {
            self.check_stream(now, t, got);
        } else {
            self.check_cycle(stim, now, t, got);
        }
        if now.load {
            self.material = now.inputs.ks;
            self.material_loaded = true;
        }
    }

    fn check_cycle(&mut self, stim: &dyn Stimulus, now: Cycle, t: u64, got: Sampled) {
        let s = self.latency;
        if self.static_colour {
            self.history.push_back(self.material);
            if self.history.len() as u64 > s + 1 {
                self.history.pop_front();
            }
        }
        let (exp_valid, data_compared, src) = if s == 0 {
            // combinational: the outputs follow the inputs in every cycle, but a static colour
            // has no value (x in Icarus) before its first load
            (now.valid, !self.static_colour || self.material_loaded, now)
        } else {
            // valid needs a defined pipeline: a reset at some cycle before t
            let Some(last_rst) = self.last_rst else {
                if now.rst {
                    self.last_rst = Some(t);
                }
                return;
            };
            let v = t >= s && stim.cycle(t - s).valid && last_rst < t - s;
            let src = if t >= s { stim.cycle(t - s) } else { now };
            (v, v, src)
        };
        let material = self.history.front().copied().unwrap_or(self.material);
        let mut expected = Sampled { valid: exp_valid, ..self.expect(&src, material) };
        let mut ok = got.valid == exp_valid && (!data_compared || (got.outputs == expected.outputs && got.tag == expected.tag));
        if self.static_colour {
            // idle: no pixel taken since the last reset is still in the pipeline
            let from = t.saturating_sub(s).max(self.last_rst.map_or(0, |r| r + 1));
            expected.idle = s == 0 || !(from..t).any(|j| stim.cycle(j).valid);
            ok &= got.idle == expected.idle;
        }
        if now.rst {
            self.last_rst = Some(t);
        }
        self.report.checked += 1;
        self.report.results += (data_compared && exp_valid) as u64;
        if !ok {
            self.fail(t, src, expected, got, data_compared, None);
        }
    }

    fn check_stream(&mut self, now: Cycle, t: u64, got: Sampled) {
        let places = self.places.expect("a handshake");
        if self.last_rst.is_none() {
            if now.rst {
                self.last_rst = Some(t);
            }
            return;
        }
        self.report.checked += 1;
        let after_reset = self.last_rst == Some(t.wrapping_sub(1));
        // the outputs hold while stalled
        if let Some((c, s)) = self.before {
            if s.valid && c.stall && !c.rst && (!got.valid || got.outputs != s.outputs || got.tag != s.tag) {
                let front = self.pending.front().map_or(c, |p| p.cycle);
                self.fail(t, front, s, got, true, Some("the result changed or went away while out_ready was low".into()));
            }
        }
        // in_ready: high exactly when fewer than places - 3 were taken three cycles before (the
        // count's strobes, the count, their difference, in_ready: registers; a reset empties
        // them all); idle: none is taken now
        let used_three_before = self.pending_before[2];
        self.pending_before = if now.rst { [0; 3] } else { [self.pending.len(), self.pending_before[0], self.pending_before[1]] };
        let exp_ready = !after_reset && used_three_before + 3 < places;
        if got.in_ready != exp_ready {
            let e = Sampled { in_ready: exp_ready, ..got };
            let rule = format!("in_ready is {} with {used_three_before} of {places} places taken three cycles before", got.in_ready as u8);
            self.fail(t, now, e, got, false, Some(rule));
        }
        if self.static_colour && got.idle != self.pending.is_empty() {
            let e = Sampled { idle: self.pending.is_empty(), ..got };
            self.fail(t, now, e, got, false, Some(format!("idle is {} with {} pixels inside", got.idle as u8, self.pending.len())));
        }
        if now.load && !got.idle {
            self.fail(t, now, got, got, false, Some("the stimulus loads a colour while the unit is not idle".into()));
        }
        if now.rst {
            self.pending.clear();
            self.last_rst = Some(t);
            self.before = Some((now, got));
            return;
        }
        // a result delivered: the oldest pixel's, with its tag
        if got.valid {
            match self.pending.front().copied() {
                None => self.fail(t, now, Sampled::default(), got, false, Some("out_valid with no pixel inside: a result invented or repeated".into())),
                Some(p) => {
                    if got.outputs != p.expected.outputs || got.tag != p.expected.tag {
                        let rule = (got.outputs == p.expected.outputs).then(|| "the tag is not its pixel's".to_string());
                        self.fail(t, p.cycle, p.expected, got, true, rule);
                    }
                    if !now.stall {
                        self.pending.pop_front();
                        self.report.results += 1;
                    }
                }
            }
        } else if let Some(p) = self.pending.front().copied() {
            if p.taken_at + self.latency <= t {
                let rule = format!("no result {} cycles after its pixel was taken (latency {}): lost or late", t - p.taken_at, self.latency);
                self.fail(t, p.cycle, p.expected, got, true, Some(rule));
            }
        }
        // a pixel taken
        if now.valid && got.in_ready {
            let expected = self.expect(&now, self.material);
            self.pending.push_back(Pending { taken_at: t, cycle: now, expected });
        }
        self.before = Some((now, got));
    }
}

pub fn describe(m: &Mismatch, cfg: &Config) -> String {
    let x = m.cycle_in.inputs;
    let mut s = format!(
        "first mismatch: run {}, cycle {} (latency {}), inputs cos_g={} n={} ks_r={} ks_g={} ks_b={}\n",
        m.run,
        m.cycle,
        cfg.latency(),
        x.cos_g,
        x.n,
        x.ks[0],
        x.ks[1],
        x.ks[2]
    );
    if m.cycle_in.tag != 0 || cfg.carried_tag_bits() > 0 {
        s = s.trim_end().to_string() + &format!(" tag={:#x}\n", m.cycle_in.tag);
    }
    if let Some(rule) = &m.rule {
        s.push_str(&format!("  rule broken: {rule}\n"));
    }
    let e = m.expected;
    let a = m.actual;
    let mut row = |port: &str, exp: u64, act: u64, compared: bool| {
        let mark = if !compared {
            "  (not compared)"
        } else if exp != act {
            "  <-- differs"
        } else {
            ""
        };
        s.push_str(&format!("  {port:<10} expected {exp:>10}  actual {act:>10}{mark}\n"));
    };
    row("out_valid", e.valid as u64, a.valid as u64, true);
    let d = m.data_compared;
    row("spec_r", e.outputs.spec[0] as u64, a.outputs.spec[0] as u64, d);
    row("spec_g", e.outputs.spec[1] as u64, a.outputs.spec[1] as u64, d);
    row("spec_b", e.outputs.spec[2] as u64, a.outputs.spec[2] as u64, d);
    row("intensity", e.outputs.intensity as u64, a.outputs.intensity as u64, d);
    row("done", e.outputs.done as u64, a.outputs.done as u64, d);
    if cfg.carried_tag_bits() > 0 {
        row("out_tag", e.tag, a.tag, d);
    }
    if cfg.interface().handshake() {
        row("in_ready", e.in_ready as u64, a.in_ready as u64, m.rule.as_deref().is_some_and(|r| r.starts_with("in_ready")));
    }
    if cfg.colour() == crate::config::Colour::Static {
        row("idle", e.idle as u64, a.idle as u64, m.rule.as_deref().is_none_or(|r| r.starts_with("idle")));
    }
    s
}
