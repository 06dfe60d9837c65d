//! The comparison with the golden model, cycle by cycle, and how a mismatch is described.

use super::{Cycle, Sampled};
use crate::config::{Colour, Config};
use crate::models::{Inputs, Model, Outputs};
use std::collections::VecDeque;

/// The first disagreement found.
#[derive(Debug, Clone)]
pub struct Mismatch {
    /// cycle index within its run
    pub(crate) cycle: u64,
    pub(crate) run: usize,
    /// the inputs the compared outputs belong to (the pixel's own cycle)
    pub(crate) cycle_in: Cycle,
    pub(crate) expected: Sampled,
    pub(crate) actual: Sampled,
    pub(crate) data_compared: bool,
    /// what rule broke, when it is more than a wrong value (a handshake's or idle's rule)
    pub(crate) rule: Option<String>,
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

/// What a cycle of a `valid` unit must show.
struct Due {
    expected: Sampled,
    /// the data and tag are compared (else only `out_valid`, and `idle`)
    data_compared: bool,
    /// the cycle whose inputs the outputs belong to
    src: Cycle,
}

/// The hash of checked cycle `t`: `out_valid`, and the outputs and tag when they are compared.
/// A batch's digest is the sum of its cycles' hashes (mod 2^64): each hash mixes (multiply,
/// shift) the cycle's index with what it shows, so differences never cancel as in a plain
/// sum, and no cycle waits for the one before. The Verilator harness hashes what it samples in
/// the same steps (its `sample_hash`).
pub fn sample_hash(t: u64, s: &Sampled, compared: bool) -> u64 {
    let mix = |x: u64| {
        let x = x.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        x ^ (x >> 29)
    };
    let o = &s.outputs;
    let (w0, w1) = if compared {
        let w0 = s.valid as u64 | 2 | (o.done as u64) << 2 | (o.intensity as u64) << 32;
        let w1 = (o.spec[0] & 0xffff) as u64
            | ((o.spec[1] & 0xffff) as u64) << 16
            | ((o.spec[2] & 0xffff) as u64) << 32;
        (w0, w1 ^ s.tag.rotate_left(17))
    } else {
        (s.valid as u64, 0)
    };
    mix(mix(t ^ w0.rotate_left(8)) ^ w1)
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
    /// `valid`, pipelined: the stimulus's last `latency + 1` cycles as given, each with the
    /// golden model's outputs for it (the oldest is the one whose result is on the outputs now)
    recent: VecDeque<(Cycle, Outputs)>,
    /// a batch's scratch: what each cycle offers under the material then, whether a load had
    /// set the material, and the golden model's outputs
    offered: Vec<Inputs>,
    loaded: Vec<bool>,
    expected: Vec<Outputs>,
    /// `valid`: pixels offered in the last `latency` cycles after the last reset (the pipeline
    /// holds one: `idle` low)
    offered_inside: u64,
    /// `ready`/`axis`: the buffer's places, the pixels inside, the last cycle's sample
    places: Option<usize>,
    pending: VecDeque<Pending>,
    /// pixels taken and not yet delivered one, two and three cycles before (none after a reset)
    pending_before: [usize; 3],
    before: Option<(Cycle, Sampled)>,
    /// the last cycle counted as a mismatch (several rules broken in one cycle count once)
    last_failed: Option<u64>,
    pub(crate) report: Report,
}

impl<'a> Checker<'a> {
    pub fn new(model: &'a Model, run: usize) -> Checker<'a> {
        let cfg = &model.cfg;
        let places = cfg
            .interface()
            .handshake()
            .then(|| crate::interface::buffer_places(cfg) as usize);
        Checker {
            model,
            latency: cfg.latency() as u64,
            last_rst: None,
            run,
            static_colour: cfg.colour() == Colour::Static,
            material: [0; 3],
            material_loaded: false,
            recent: VecDeque::new(),
            offered: Vec::new(),
            loaded: Vec::new(),
            expected: Vec::new(),
            offered_inside: 0,
            places,
            pending: VecDeque::new(),
            pending_before: [0; 3],
            before: None,
            last_failed: None,
            report: Report::default(),
        }
    }

    fn fail(
        &mut self,
        t: u64,
        cycle_in: Cycle,
        expected: Sampled,
        actual: Sampled,
        data_compared: bool,
        rule: Option<String>,
    ) {
        // mismatching cycles, never more than the cycles checked
        if self.last_failed != Some(t) {
            self.report.mismatches += 1;
            self.last_failed = Some(t);
        }
        if self.report.first.is_none() {
            self.report.first = Some(Mismatch {
                cycle: t,
                run: self.run,
                cycle_in,
                expected,
                actual,
                data_compared,
                rule,
            });
        }
    }

    /// Checks the outputs sampled in cycles `t0 ..` (each before its rising edge), whose
    /// stimulus is `cycles`; batches come in order, from cycle 0. The golden model evaluates the
    /// batch at once ([`Checker::evaluate`]).
    pub fn check_batch(
        &mut self,
        t0: u64,
        cycles: &[Cycle],
        got: impl IntoIterator<Item = Sampled>,
    ) {
        self.evaluate(cycles);
        let (expected, loaded) = (
            std::mem::take(&mut self.expected),
            std::mem::take(&mut self.loaded),
        );
        for (k, got) in got.into_iter().enumerate().take(cycles.len()) {
            self.check(cycles[k], t0 + k as u64, got, expected[k], loaded[k]);
        }
        (self.expected, self.loaded) = (expected, loaded);
    }

    /// The golden model's outputs for what each of `cycles` offers, into `expected`, and
    /// whether a load had set the material then, into `loaded`: each pixel under the material
    /// in effect when it is offered (a load takes effect at its edge, and not at an edge the
    /// clock enable leaves out).
    fn evaluate(&mut self, cycles: &[Cycle]) {
        self.offered.clear();
        self.loaded.clear();
        for c in cycles {
            self.offered.push(if self.static_colour {
                Inputs {
                    ks: self.material,
                    ..c.inputs
                }
            } else {
                c.inputs
            });
            self.loaded.push(self.material_loaded);
            if c.load && !c.disabled {
                self.material = c.inputs.ks;
                self.material_loaded = true;
            }
        }
        self.model.eval_batch(&self.offered, &mut self.expected);
    }

    /// Checks cycle `t`: stimulus `now`, sampled `got`, the golden model's outputs for what it
    /// offers, and whether the material had been loaded.
    fn check(&mut self, now: Cycle, t: u64, got: Sampled, expected: Outputs, loaded: bool) {
        let now = self.arrive(now, expected);
        if self.places.is_some() {
            self.check_stream(now, t, got, expected);
        } else {
            self.check_cycle(now, t, got, expected, loaded);
        }
    }

    /// A cycle comes in, with the golden model's outputs for what it offers: counted, kept
    /// while its result may be due; returned as its edge acts (the clock enable low: an edge
    /// without a transfer or a load, as if nothing were offered and the consumer stalled).
    #[inline(always)]
    fn arrive(&mut self, mut now: Cycle, outputs: Outputs) -> Cycle {
        self.report.cycles += 1;
        if self.places.is_none() && self.latency > 0 {
            self.recent.push_back((now, outputs));
            if self.recent.len() as u64 > self.latency + 1 {
                self.recent.pop_front();
            }
        }
        if now.disabled {
            (now.valid, now.stall, now.load) = (false, true, false);
        }
        now
    }

    fn check_cycle(&mut self, now: Cycle, t: u64, got: Sampled, outputs: Outputs, loaded: bool) {
        let Some(due) = self.due(now, t, outputs, loaded) else {
            return;
        };
        let e = due.expected;
        let mut ok = got.valid == e.valid
            && (!due.data_compared || (got.outputs == e.outputs && got.tag == e.tag));
        if self.static_colour {
            ok &= got.idle == e.idle;
        }
        if !ok {
            self.fail(t, due.src, e, got, due.data_compared, None);
        }
    }

    /// What cycle `t` of a `valid` unit must show (`None`: nothing, before the first reset of a
    /// pipelined unit), and the window moved on; counts the cycle checked and its result.
    #[inline(always)]
    fn due(&mut self, now: Cycle, t: u64, outputs: Outputs, loaded: bool) -> Option<Due> {
        let s = self.latency;
        let (exp_valid, data_compared, (src, outputs)) = if s == 0 {
            // combinational: the outputs follow the inputs in every cycle, but a static colour
            // has no value (x in Icarus) before its first load
            (now.valid, !self.static_colour || loaded, (now, outputs))
        } else {
            // valid needs a defined pipeline: a reset at some cycle before t
            let Some(last_rst) = self.last_rst else {
                if now.rst {
                    self.last_rst = Some(t);
                }
                return None;
            };
            // the cycle whose result is due now, `s` before (`recent` holds s + 1 from t ≥ s)
            let due = (t >= s).then(|| self.recent[0]);
            let v = due.is_some_and(|(d, _)| d.valid && last_rst < t - s);
            (v, v, due.unwrap_or((now, outputs)))
        };
        let mut expected = Sampled {
            outputs,
            valid: exp_valid,
            tag: src.tag,
            ..Sampled::default()
        };
        if self.static_colour {
            // idle: no pixel offered since the last reset is still in the pipeline (offered in
            // the last s cycles)
            expected.idle = s == 0 || self.offered_inside == 0;
        }
        if now.rst {
            self.last_rst = Some(t);
        }
        // the window moves on to t + 1 - s ..= t: cycle t comes in (counted when after the last
        // reset), cycle t - s leaves (counted if it was, that is offered after the last reset)
        if s > 0 {
            let after_rst = |j: u64| self.last_rst.is_some_and(|r| j > r);
            // as given: what was offered, whatever the clock enable
            let offered = self.recent.back().is_some_and(|(c, _)| c.valid);
            if offered && after_rst(t) {
                self.offered_inside += 1;
            }
            if now.rst {
                self.offered_inside = 0;
            } else if t >= s && self.recent[0].0.valid && after_rst(t - s) {
                self.offered_inside -= 1;
            }
        }
        self.report.checked += 1;
        self.report.results += (data_compared && exp_valid) as u64;
        Some(Due {
            expected,
            data_compared,
            src,
        })
    }

    /// Whether the unit's every rule is a comparison of each cycle's outputs with what is due
    /// ([`Checker::digest_batch`] can stand for the check): the `valid` interface without a
    /// static colour (whose `idle` is a rule of its own).
    pub fn digestible(&self) -> bool {
        self.places.is_none() && !self.static_colour
    }

    /// The digest of what cycles `t0 ..` (stimulus `cycles`) must show, as the harness digests
    /// what they do show ([`sample_hash`]): equal digests mean every compared output equal,
    /// as [`Checker::check_batch`] would find them. Counts the cycles as checked; finds no
    /// mismatch itself (a differing digest is run again with every record compared).
    pub fn digest_batch(&mut self, t0: u64, cycles: &[Cycle]) -> u64 {
        debug_assert!(self.digestible());
        self.evaluate(cycles);
        let expected = std::mem::take(&mut self.expected);
        let mut h = 0u64;
        for (k, (&c, &outputs)) in cycles.iter().zip(&expected).enumerate() {
            let t = t0 + k as u64;
            let now = self.arrive(c, outputs);
            if let Some(d) = self.due(now, t, outputs, true) {
                h = h.wrapping_add(sample_hash(t, &d.expected, d.data_compared));
            }
        }
        self.expected = expected;
        h
    }

    fn check_stream(&mut self, now: Cycle, t: u64, got: Sampled, outputs: Outputs) {
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
            if s.valid
                && c.stall
                && !c.rst
                && (!got.valid || got.outputs != s.outputs || got.tag != s.tag)
            {
                let front = self.pending.front().map_or(c, |p| p.cycle);
                self.fail(
                    t,
                    front,
                    s,
                    got,
                    true,
                    Some("the result changed or went away while out_ready was low".into()),
                );
            }
        }
        // in_ready: high exactly when fewer than places - 3 were taken three cycles before (the
        // count's strobes, the count, their difference, in_ready: registers; a reset empties
        // them all); idle: none is taken now
        let used_three_before = self.pending_before[2];
        self.pending_before = if now.rst {
            [0; 3]
        } else {
            [
                self.pending.len(),
                self.pending_before[0],
                self.pending_before[1],
            ]
        };
        let exp_ready = !after_reset && used_three_before + 3 < places;
        if got.in_ready != exp_ready {
            let e = Sampled {
                in_ready: exp_ready,
                ..got
            };
            let rule = format!("in_ready is {} with {used_three_before} of {places} places taken three cycles before", got.in_ready as u8);
            self.fail(t, now, e, got, false, Some(rule));
        }
        if self.static_colour && got.idle != self.pending.is_empty() {
            let e = Sampled {
                idle: self.pending.is_empty(),
                ..got
            };
            self.fail(
                t,
                now,
                e,
                got,
                false,
                Some(format!(
                    "idle is {} with {} pixels inside",
                    got.idle as u8,
                    self.pending.len()
                )),
            );
        }
        if now.load && !got.idle {
            self.fail(
                t,
                now,
                got,
                got,
                false,
                Some("the stimulus loads a colour while the unit is not idle".into()),
            );
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
                None => self.fail(
                    t,
                    now,
                    Sampled::default(),
                    got,
                    false,
                    Some("out_valid with no pixel inside: a result invented or repeated".into()),
                ),
                Some(p) => {
                    if got.outputs != p.expected.outputs || got.tag != p.expected.tag {
                        let rule = (got.outputs == p.expected.outputs)
                            .then(|| "the tag is not its pixel's".to_string());
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
                let rule = format!(
                    "no result {} cycles after its pixel was taken (latency {}): lost or late",
                    t - p.taken_at,
                    self.latency
                );
                self.fail(t, p.cycle, p.expected, got, true, Some(rule));
            }
        }
        // a pixel taken
        if now.valid && got.in_ready {
            let expected = Sampled {
                outputs,
                valid: true,
                tag: now.tag,
                ..Sampled::default()
            };
            self.pending.push_back(Pending {
                taken_at: t,
                cycle: now,
                expected,
            });
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
        s.push_str(&format!(
            "  {port:<10} expected {exp:>10}  actual {act:>10}{mark}\n"
        ));
    };
    row("out_valid", e.valid as u64, a.valid as u64, true);
    let d = m.data_compared;
    row(
        "spec_r",
        e.outputs.spec[0] as u64,
        a.outputs.spec[0] as u64,
        d,
    );
    row(
        "spec_g",
        e.outputs.spec[1] as u64,
        a.outputs.spec[1] as u64,
        d,
    );
    row(
        "spec_b",
        e.outputs.spec[2] as u64,
        a.outputs.spec[2] as u64,
        d,
    );
    row(
        "intensity",
        e.outputs.intensity as u64,
        a.outputs.intensity as u64,
        d,
    );
    row("done", e.outputs.done as u64, a.outputs.done as u64, d);
    if cfg.carried_tag_bits() > 0 {
        row("out_tag", e.tag, a.tag, d);
    }
    if cfg.interface().handshake() {
        row(
            "in_ready",
            e.in_ready as u64,
            a.in_ready as u64,
            m.rule.as_deref().is_some_and(|r| r.starts_with("in_ready")),
        );
    }
    if cfg.colour() == crate::config::Colour::Static {
        row(
            "idle",
            e.idle as u64,
            a.idle as u64,
            m.rule.as_deref().is_none_or(|r| r.starts_with("idle")),
        );
    }
    s
}
