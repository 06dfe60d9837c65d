//! The comparison with the golden model, cycle by cycle, and how a mismatch is described.

use super::{Cycle, Sampled, Stimulus};
use crate::config::Config;
use crate::models::Model;

/// The first disagreement found.
#[derive(Debug, Clone)]
pub struct Mismatch {
    /// cycle index within its run
    pub cycle: u64,
    pub run: usize,
    /// the inputs the compared outputs belong to (applied `latency` cycles before)
    pub cycle_in: Cycle,
    pub expected: Sampled,
    pub actual: Sampled,
    pub data_compared: bool,
}

/// The result of checking one or more runs.
#[derive(Debug, Clone, Default)]
pub struct Report {
    pub cycles: u64,
    pub checked: u64,
    pub mismatches: u64,
    pub first: Option<Mismatch>,
}

/// Compares a sampled stream against the golden model: `out_valid` on every cycle after the
/// first reset, data on every cycle whose output is valid (every cycle when combinational).
pub struct Checker<'a> {
    model: &'a Model,
    latency: u64,
    last_rst: Option<u64>,
    run: usize,
    pub report: Report,
}

impl<'a> Checker<'a> {
    pub fn new(model: &'a Model, run: usize) -> Checker<'a> {
        Checker { model, latency: model.cfg.stages() as u64, last_rst: None, run, report: Report::default() }
    }

    /// Checks the output sampled in cycle `t`.
    pub fn check(&mut self, stim: &dyn Stimulus, t: u64, got: Sampled) {
        let s = self.latency;
        self.report.cycles += 1;
        let now = stim.cycle(t);
        let (exp_valid, data_compared, src) = if s == 0 {
            (now.valid, true, now)
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
        if now.rst {
            self.last_rst = Some(t);
        }
        let expected = Sampled { outputs: self.model.eval(src.inputs), valid: exp_valid };
        let ok = got.valid == exp_valid && (!data_compared || got.outputs == expected.outputs);
        self.report.checked += 1;
        if !ok {
            self.report.mismatches += 1;
            if self.report.first.is_none() {
                self.report.first = Some(Mismatch { cycle: t, run: self.run, cycle_in: src, expected, actual: got, data_compared });
            }
        }
    }
}

pub fn describe(m: &Mismatch, cfg: &Config) -> String {
    let x = m.cycle_in.inputs;
    let mut s = format!(
        "first mismatch: run {}, cycle {} (latency {}), inputs cos_g={} n={} ks_r={} ks_g={} ks_b={}\n",
        m.run,
        m.cycle,
        cfg.stages(),
        x.cos_g,
        x.n,
        x.ks[0],
        x.ks[1],
        x.ks[2]
    );
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
    s
}
