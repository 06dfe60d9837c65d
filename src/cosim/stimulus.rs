//! The stimulus: corner cases, a boundary for every n, random vectors, the exhaustive sweep.

use super::Cycle;
use crate::config::Config;
use crate::models::{Inputs, Model};

/// A stream of cycles, addressable by index so a checker can regenerate what it needs.
/// Every run starts with a reset cycle when the unit is pipelined.
pub trait Stimulus: Send + Sync {
    fn len(&self) -> u64;
    fn cycle(&self, i: u64) -> Cycle;
    /// Cycles `from .. from + count` into `out` (cleared first): what a run streams and checks a
    /// batch at a time (a stimulus may step through them faster than [`Stimulus::cycle`] finds each).
    fn fill(&self, from: u64, count: u64, out: &mut Vec<Cycle>) {
        out.clear();
        out.extend((from..from + count).map(|i| self.cycle(i)));
    }
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The Verilator harness's own description of this stimulus (`SPECGEN_SWEEP`), when it can
    /// make the cycles itself instead of reading them: the exhaustive sweep.
    fn harness_sweep(&self) -> Option<String> {
        None
    }
}

/// A stimulus held in memory.
pub struct Recorded(pub Vec<Cycle>);

impl Stimulus for Recorded {
    fn len(&self) -> u64 {
        self.0.len() as u64
    }
    fn cycle(&self, i: u64) -> Cycle {
        self.0[i as usize]
    }
}

/// splitmix64: a small counter-based generator, so vectors are reproducible from the seed.
pub fn splitmix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// The corner cases: cos 0, 1.0, above 1.0, B−1, B, B+1 where B is n's boundary (the
/// cut-off ROM entry, or the first code with a non-zero output); n 0, 1, 2, 3, max; colour
/// codes 0, 1, max on every channel. Then, for every n, the three codes around its boundary
/// with colours that vary with n: a single wrong table entry at any n shows.
pub fn corner_vectors(model: &Model) -> Vec<Inputs> {
    let cfg = &model.cfg;
    let one = 1u32 << cfg.f();
    let cos_max = (2u32 << cfg.f()) - 1;
    let n_max = (1u32 << cfg.n_bits()) - 1;
    let ks_max = (1u32 << cfg.b()) - 1;
    let bounds = model.boundaries();
    let mut ns: Vec<u32> = vec![0, 1, 2, 3, n_max];
    ns.retain(|&n| n <= n_max);
    ns.dedup();
    let colours = [0, 1, ks_max];
    let mut v = Vec::new();
    for &n in &ns {
        let sp = bounds[n as usize];
        let mut coss = vec![
            0,
            one,
            one + 1,
            cos_max,
            sp.saturating_sub(1),
            sp,
            (sp + 1).min(cos_max),
        ];
        coss.sort();
        coss.dedup();
        for &cos_g in &coss {
            for &r in &colours {
                for &g in &colours {
                    for &b in &colours {
                        v.push(Inputs {
                            cos_g,
                            n,
                            ks: [r, g, b],
                        });
                    }
                }
            }
        }
    }
    for n in 0..=n_max {
        let sp = bounds[n as usize];
        let r = splitmix(n as u64 ^ 0x5bd1_e995);
        let ks = [ks_max, (r as u32) & ks_max, ((r >> 20) as u32) & ks_max];
        for cos_g in [sp.saturating_sub(1), sp, (sp + 1).min(cos_max)] {
            v.push(Inputs { cos_g, n, ks });
        }
    }
    v
}

/// A random input vector. Three in four inside the highlight: n ≥ 1 and cos_g = s^(1/n) for a
/// uniform s in (0, 1), so that cos^n (which every model approximates) is neither 0 nor full
/// scale (below the quadratic model's cut-off, s < e^(-1/k), its output is 0); the rest
/// uniform, cos_g over the whole port (codes above 1.0 too) and n over its range, where most
/// outputs of a high n are 0.
pub fn random_vector(cfg: &Config, seed: u64, i: u64) -> Inputs {
    let r = splitmix(seed.wrapping_mul(0x1000_0000_0000_0001) ^ i);
    let r2 = splitmix(r);
    let n_max = (1u64 << cfg.n_bits()) - 1;
    let one = 1u64 << cfg.f();
    let (cos_g, n) = if r & 6 != 0 {
        let n = 1 + (r >> 32) % n_max.max(1);
        // s in (0, 1) from 24 random bits
        let s = (((r >> 3) & 0xff_ffff) as f64 + 0.5) / (1u64 << 24) as f64;
        let c = s.powf(1.0 / n as f64);
        (
            ((c * one as f64).round() as u64).min(one) as u32,
            n.min(n_max) as u32,
        )
    } else {
        let cos_g = if r & 1 == 0 {
            ((r >> 3) % (one + 1)) as u32
        } else {
            ((r >> 3) & ((2 * one) - 1)) as u32
        };
        (cos_g, ((r >> 32) & n_max) as u32)
    };
    let bm = (1u64 << cfg.b()) - 1;
    Inputs {
        cos_g,
        n,
        ks: [
            (r2 & bm) as u32,
            ((r2 >> 16) & bm) as u32,
            ((r2 >> 32) & bm) as u32,
        ],
    }
}

/// Cycles with nothing offered that empty a unit whose consumer is ready: its latency, and
/// behind a handshake the buffer's places too.
pub fn drain_cycles(cfg: &Config) -> u64 {
    cfg.latency() as u64 + crate::interface::buffer_places(cfg) + 4
}

/// The consumer's `out_ready` pattern behind a handshake, in four phases of 600 cycles: full
/// rate; a stall every other cycle at random; long stalls (100 cycles stalled, 20 ready);
/// rare stalls (one cycle in eight).
fn stalled(seed: u64, t: u64) -> bool {
    let r = splitmix(seed ^ 0x57a11 ^ t << 12);
    match (t / 600) % 4 {
        0 => false,
        1 => r & 1 == 0,
        2 => t % 120 < 100,
        _ => r.is_multiple_of(8),
    }
}

/// The clock enable's pattern (`--clock-enable`), in three phases of 450 cycles (against the
/// stalls' 600, so every mix of the two occurs): always high; low every other cycle at random;
/// low in runs of 20 of every 50 cycles.
fn disabled(seed: u64, t: u64) -> bool {
    let r = splitmix(seed ^ 0xc10c ^ t << 12);
    match (t / 450) % 3 {
        0 => false,
        1 => r & 1 == 0,
        _ => t % 50 < 20,
    }
}

/// Corners, then `count` random vectors. For a clocked unit: a reset first, random bubbles on
/// `in_valid` (one cycle in eight, and runs of them), and a reset in mid-stream. Behind a
/// handshake, the consumer stalls in the patterns of [`stalled`], and a clock enable goes low
/// in those of [`disabled`]. With a tag, every pixel
/// carries a random one. With a static colour: a load after the first reset, and a new colour
/// every quarter of the stream, each after the unit has drained.
pub fn random_stimulus(model: &Model, count: u64, seed: u64) -> Recorded {
    let cfg = &model.cfg;
    let clocked = cfg.clocked();
    let handshake = cfg.interface().handshake();
    let static_colour = cfg.colour() == crate::config::Colour::Static;
    let tag_mask = crate::bits::mask(cfg.carried_tag_bits()) as u64;
    let vectors: Vec<Inputs> = corner_vectors(model)
        .into_iter()
        .chain((0..count).map(|i| random_vector(cfg, seed, i)))
        .collect();
    let mut cycles: Vec<Cycle> = Vec::with_capacity(vectors.len() * 5 / 4 + 8);
    let load = |cycles: &mut Vec<Cycle>, k: u64| {
        for _ in 0..drain_cycles(cfg) {
            cycles.push(Cycle::default());
        }
        let ks = random_vector(cfg, seed ^ 0x10ad, k).ks;
        cycles.push(Cycle {
            inputs: Inputs {
                ks,
                ..Inputs::default()
            },
            load: true,
            ..Cycle::default()
        });
        if cfg.params.clock_enable {
            // a decoy: ks_load with another colour at an edge the clock enable leaves out
            let ks = random_vector(cfg, seed ^ 0xdec0, k).ks;
            cycles.push(Cycle {
                inputs: Inputs {
                    ks,
                    ..Inputs::default()
                },
                load: true,
                disabled: true,
                ..Cycle::default()
            });
        }
    };
    if clocked {
        cycles.push(Cycle {
            inputs: random_vector(cfg, seed ^ 0xdead, 0),
            valid: true,
            rst: true,
            ..Cycle::default()
        });
    }
    if static_colour {
        load(&mut cycles, 0);
    }
    let reset_at = vectors.len() / 2;
    let quarter = (vectors.len() / 4).max(1);
    for (i, &inputs) in vectors.iter().enumerate() {
        if clocked {
            let r = splitmix(seed ^ 0xb0bb1e5 ^ (i as u64) << 8);
            if r.is_multiple_of(8) {
                // a bubble, or a run of them
                for _ in 0..if r & 0x700 == 0 {
                    1 + (r >> 16) % 40
                } else {
                    1
                } {
                    cycles.push(Cycle {
                        inputs: random_vector(cfg, seed ^ 0xb0bb, i as u64),
                        ..Cycle::default()
                    });
                }
            }
            if i == reset_at {
                // a reset in mid-stream: the pixels inside are dropped, then the stream resumes
                cycles.push(Cycle {
                    inputs,
                    valid: true,
                    rst: true,
                    ..Cycle::default()
                });
                cycles.push(Cycle {
                    inputs,
                    valid: true,
                    rst: true,
                    ..Cycle::default()
                });
                if static_colour {
                    load(&mut cycles, i as u64);
                }
            } else if static_colour && i > 0 && i % quarter == 0 {
                load(&mut cycles, i as u64);
            }
        }
        let tag = splitmix(seed ^ 0x7a9 ^ (i as u64) << 4) & tag_mask;
        cycles.push(Cycle {
            tag,
            ..Cycle::pixel(inputs)
        });
    }
    if !handshake && clocked {
        // the last pixels' results leave the pipeline before the run ends
        for _ in 0..cfg.latency() + 1 {
            cycles.push(Cycle::default());
        }
    }
    if handshake {
        // the consumer's stalls, except on the cycles that load a colour (the unit is empty
        // there only if it could deliver), and a tail at full rate that empties the unit
        let enable = cfg.params.clock_enable;
        for (t, c) in cycles.iter_mut().enumerate() {
            c.stall = !c.load && stalled(seed, t as u64);
            c.disabled |= enable && !c.load && disabled(seed, t as u64);
        }
        for _ in 0..drain_cycles(cfg) {
            cycles.push(Cycle::default());
        }
        // drains before a load must run at full rate
        let mut t = cycles.len();
        while t > 0 {
            t -= 1;
            if cycles[t].load {
                for c in cycles[t.saturating_sub(drain_cycles(cfg) as usize)..t]
                    .iter_mut()
                    .filter(|c| !c.load)
                {
                    (c.stall, c.disabled) = (false, false);
                }
            }
        }
    }
    Recorded(cycles)
}

/// Every `(cos_g, n)` with `cos_g ∈ [0, 2^F]` (codes above 1.0 all read as 1.0; the corners
/// cover them), n-major in chunk `part` of `parts`. Colours: `ks_X = (cos_g + n·m_X + o_X) mod 2^B`
/// with odd `m_X`, so along a row of fixed n every channel sees every code. The first part
/// ends with a tail of `2^B` cycles at `cos_g = 1.0` carrying every colour code on every
/// channel through full intensity (whatever N is).
pub struct Exhaustive {
    pub(crate) f: u32,
    pub(crate) b: u32,
    pub(crate) n_bits: u32,
    pub(crate) n_lo: u32,
    pub(crate) n_hi: u32,
    /// a reset first (the unit has registers)
    pub(crate) clocked: bool,
    /// a material load after the reset (a static colour): full-scale red, mid green, 1 blue
    pub(crate) static_colour: bool,
    /// idle cycles after those, before the sweep: 1 behind a handshake, whose `in_ready` is low
    /// the cycle after a reset (a pixel offered then is not taken, and would be missed)
    pub(crate) settle: u64,
    pub(crate) tag_bits: u32,
    pub(crate) full_intensity_tail: bool,
    /// idle cycles at the end, so the last pixels' results leave a pipelined unit
    pub(crate) drain: u64,
}

impl Exhaustive {
    pub fn parts(cfg: &Config, parts: u32) -> Vec<Exhaustive> {
        let n_count = 1u32 << cfg.n_bits();
        let parts = parts.clamp(1, n_count);
        (0..parts)
            .map(|p| Exhaustive {
                f: cfg.f(),
                b: cfg.b(),
                n_bits: cfg.n_bits(),
                n_lo: n_count * p / parts,
                n_hi: n_count * (p + 1) / parts,
                clocked: cfg.clocked(),
                static_colour: cfg.colour() == crate::config::Colour::Static,
                settle: cfg.interface().handshake() as u64,
                tag_bits: cfg.carried_tag_bits(),
                full_intensity_tail: p == 0,
                // behind a handshake the last results wait in the output buffer too
                drain: match cfg.clocked() {
                    false => 0,
                    true if cfg.interface().handshake() => drain_cycles(cfg),
                    true => cfg.latency() as u64 + 1,
                },
            })
            .collect()
    }
    fn row(&self) -> u64 {
        (1u64 << self.f) + 1
    }
    /// The cycles before the sweep: a reset, a material load, the settling cycles.
    pub fn lead(&self) -> u64 {
        self.clocked as u64 + self.static_colour as u64 + self.settle
    }
}

impl Exhaustive {
    /// The cycles of the sweep, before the tail.
    fn sweep(&self) -> u64 {
        (self.n_hi - self.n_lo) as u64 * self.row()
    }

    /// Cycle `i`, which is in the sweep at `(cos_g, n)`.
    fn sweep_cycle(&self, i: u64, cos_g: u32, n: u32) -> Cycle {
        let bm = (1u32 << self.b) - 1;
        let ks = [
            cos_g.wrapping_add(n.wrapping_mul(1)) & bm,
            cos_g.wrapping_add(n.wrapping_mul(3)).wrapping_add(85) & bm,
            cos_g.wrapping_add(n.wrapping_mul(7)).wrapping_add(170) & bm,
        ];
        Cycle {
            tag: self.tag(i),
            ..Cycle::pixel(Inputs { cos_g, n, ks })
        }
    }

    fn tag(&self, i: u64) -> u64 {
        if self.tag_bits == 0 {
            0
        } else {
            splitmix(i) & crate::bits::mask(self.tag_bits) as u64
        }
    }
}

impl Stimulus for Exhaustive {
    fn len(&self) -> u64 {
        let tail = if self.full_intensity_tail {
            1u64 << self.b
        } else {
            0
        };
        self.sweep() + self.lead() + tail + self.drain
    }
    fn cycle(&self, i: u64) -> Cycle {
        let bm = (1u32 << self.b) - 1;
        if self.clocked && i == 0 {
            return Cycle::reset();
        }
        if self.static_colour && i == self.clocked as u64 {
            return Cycle {
                inputs: Inputs {
                    ks: [bm, bm / 2 + 1, 1.min(bm)],
                    ..Inputs::default()
                },
                load: true,
                ..Cycle::default()
            };
        }
        if i < self.lead() {
            return Cycle::default();
        }
        let j = i - self.lead();
        let sweep = self.sweep();
        let tail = if self.full_intensity_tail {
            1u64 << self.b
        } else {
            0
        };
        if j >= sweep + tail {
            return Cycle::default();
        }
        if j >= sweep {
            let code = (j - sweep) as u32;
            let n = code.wrapping_mul(7) & ((1u32 << self.n_bits) - 1);
            let ks = [code, code.wrapping_add(1) & bm, code.wrapping_add(2) & bm];
            return Cycle {
                tag: self.tag(i),
                ..Cycle::pixel(Inputs {
                    cos_g: 1 << self.f,
                    n,
                    ks,
                })
            };
        }
        self.sweep_cycle(
            i,
            (j % self.row()) as u32,
            self.n_lo + (j / self.row()) as u32,
        )
    }
    fn harness_sweep(&self) -> Option<String> {
        let flag = |b: bool| b as u8;
        Some(format!(
            "{} {} {} {} {} {} {} {} {} {} {}",
            self.f,
            self.b,
            self.n_bits,
            self.n_lo,
            self.n_hi,
            flag(self.clocked),
            flag(self.static_colour),
            self.settle,
            self.tag_bits,
            flag(self.full_intensity_tail),
            self.drain
        ))
    }
    /// Steps through the sweep (one division a batch, not two a cycle).
    fn fill(&self, from: u64, count: u64, out: &mut Vec<Cycle>) {
        out.clear();
        let (lead, sweep, row, end) = (self.lead(), self.sweep(), self.row(), from + count);
        let mut i = from;
        while i < end {
            if i < lead || i - lead >= sweep {
                out.push(self.cycle(i));
                i += 1;
                continue;
            }
            let j = i - lead;
            let (mut cos_g, mut n) = ((j % row) as u32, self.n_lo + (j / row) as u32);
            for i in i..end.min(lead + sweep) {
                out.push(self.sweep_cycle(i, cos_g, n));
                cos_g += 1;
                if u64::from(cos_g) == row {
                    (cos_g, n) = (0, n + 1);
                }
            }
            i = end.min(lead + sweep);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Colour, Interface, Params};

    #[test]
    fn the_sweep_steps_through_the_cycles_it_addresses() {
        // a batch may start and end anywhere: in the lead, mid-row, in the tail, in the drain
        let configs = [
            Params {
                cos_frac_bits: 5,
                n_bits: 3,
                color_bits: 4,
                ..Params::default()
            },
            Params {
                cos_frac_bits: 5,
                n_bits: 3,
                color_bits: 6,
                stages: 3,
                colour: Colour::Static,
                tag_bits: 5,
                interface: Interface::Ready,
                ..Params::default()
            },
        ];
        for params in configs {
            let cfg = Config::new(params).unwrap();
            for part in Exhaustive::parts(&cfg, 3) {
                let all: Vec<Cycle> = (0..part.len()).map(|i| part.cycle(i)).collect();
                for batch in [1, 7, 33, 1000] {
                    let mut got = Vec::new();
                    let mut out = Vec::new();
                    let mut i = 0;
                    while i < part.len() {
                        let n = batch.min(part.len() - i);
                        part.fill(i, n, &mut out);
                        got.extend_from_slice(&out);
                        i += n;
                    }
                    assert_eq!(got, all, "batches of {batch}");
                }
            }
        }
    }
}
