//! Stage 3a: the bit-exact golden model (what the RTL computes) and the exact reference
//! (what SPEC §3 says it must approximate).
//!
//! [`Model::eval`] does the RTL's arithmetic step for step — the same widths, the same
//! truncations, in the same order — so a co-simulation can demand bit equality.
//! [`reference`] computes the ideal outputs as exact dyadic rationals with no knowledge of
//! the internal widths; [`check`] states the rounding contract against it.

use crate::blinn::{self, BlinnTables, BlinnWidths};
use crate::config::{Config, Rounding, SpecularModel};
use crate::fitted::{self, Fit, FittedWidths};
use crate::rom;
use crate::widths::{mask, Widths};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// One input vector of the unit (port values as integers).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Inputs {
    /// UQ1.F; codes above 2^F are taken as 1.0.
    pub cos_g: u32,
    pub n: u32,
    /// `ks_r`, `ks_g`, `ks_b`: UNORM, all ones = 1.0.
    pub ks: [u32; 3],
}

/// The unit's outputs for one input vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Outputs {
    pub spec: [u32; 3],
    /// UQ1.FI
    pub intensity: u32,
    pub done: bool,
}

/// Every intermediate value of the datapath, named as in the RTL.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Trace {
    pub cos_clamped: u64,
    pub one_minus_cos: u64,
    pub cos_sp: u64,
    pub done: bool,
    pub kn: u64,
    pub deviation_full: u128,
    pub deviation: u64,
    pub bracket: u64,
    pub square_full: u128,
    pub square: u128,
    pub color_prod: [u128; 3],
    pub intensity_sum: u128,
    pub outputs: Outputs,
}

/// What a model needs beyond the common widths: its fit or its tables.
#[derive(Debug, Clone)]
pub enum Kind {
    Quadratic,
    BlinnPow,
    Fitted { fit: Arc<Fit>, widths: FittedWidths },
    Blinn { widths: BlinnWidths, tables: BlinnTables },
}

/// The fit of a configuration, computed once per process for each (N, M, KA).
pub fn cached_fit(cfg: &Config) -> Arc<Fit> {
    type Cache = Mutex<HashMap<(u32, u32, u32), Arc<Fit>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let key = (cfg.n_bits(), cfg.max_squarings(), cfg.kf());
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(f) = cache.lock().expect("fit cache").get(&key) {
        return f.clone();
    }
    let fit = Arc::new(fitted::fit(cfg));
    cache.lock().expect("fit cache").entry(key).or_insert(fit).clone()
}

impl Kind {
    /// The one place a configuration's model is chosen: every golden model, reference,
    /// datapath and table goes through here.
    pub fn new(cfg: &Config) -> Kind {
        match cfg.model() {
            SpecularModel::Quadratic => Kind::Quadratic,
            SpecularModel::BlinnPow => Kind::BlinnPow,
            SpecularModel::Fitted => {
                let fit = cached_fit(cfg);
                let widths = FittedWidths::derive(cfg, &fit);
                Kind::Fitted { fit, widths }
            }
            SpecularModel::Blinn => {
                let widths = BlinnWidths::derive(cfg);
                let tables = blinn::tables(&widths);
                Kind::Blinn { widths, tables }
            }
        }
    }
}

/// The golden model of one configuration.
#[derive(Debug, Clone)]
pub struct Model {
    pub cfg: Config,
    pub widths: Widths,
    /// The cut-off ROM `cos_sp(n)` (quadratic; empty for the other models).
    pub rom: Vec<u32>,
    pub kind: Kind,
}

impl Model {
    pub fn new(cfg: &Config) -> Model {
        Model::from_parts(cfg, Widths::derive(cfg), Kind::new(cfg))
    }

    /// A model from parts already made (`plan::Plan::model`).
    pub fn from_parts(cfg: &Config, widths: Widths, kind: Kind) -> Model {
        let rom = if cfg.model() == SpecularModel::Quadratic { rom::cos_sp_table(cfg) } else { Vec::new() };
        Model { cfg: cfg.clone(), widths, rom, kind }
    }

    /// The unit's outputs for one input, bit for bit.
    pub fn eval(&self, x: Inputs) -> Outputs {
        match &self.kind {
            Kind::Quadratic => self.trace(x).outputs,
            Kind::BlinnPow => self.eval_blinn_pow(x),
            Kind::Fitted { fit, widths } => fitted::trace(&self.cfg, fit, widths, x).1,
            Kind::Blinn { widths, tables } => blinn::trace(&self.cfg, widths, tables, x).1,
        }
    }

    /// The ideal outputs this model's contract refers to, as floats (for reports): SPEC §3's
    /// for the quadratic unit, `S` with the stored `a_n` for fitted, `c^n` for the Blinn models.
    pub fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        let cfg = &self.cfg;
        let c = x.cos_g.min(1 << cfg.f()) as f64 / (cfg.f() as f64).exp2();
        let s = match &self.kind {
            Kind::Quadratic => {
                let r = reference(cfg, x);
                return (r.intensity.to_f64(), r.spec.map(Ideal::to_f64));
            }
            Kind::Fitted { fit, .. } => {
                let a = fit.a_code[x.n as usize] as f64 / (cfg.kf() as f64).exp2();
                let base = 1.0 - a * (1.0 - c);
                if base < 0.0 {
                    0.0
                } else {
                    base.powi(1 << fit.m[x.n as usize])
                }
            }
            Kind::Blinn { .. } | Kind::BlinnPow => c.powi(x.n as i32),
        };
        (s * (cfg.fi() as f64).exp2(), x.ks.map(|k| s * k as f64))
    }

    /// Checks outputs against this model's contract (its exact reference).
    pub fn check(&self, x: Inputs, got: Outputs) -> Result<(), String> {
        match &self.kind {
            Kind::Fitted { fit, .. } => fitted::check(&self.cfg, fit, x, got),
            _ => check(&self.cfg, x, got),
        }
    }

    /// The last `cos_g` code with a non-zero output, or the cut-off, for each n: the
    /// boundary a test stimulus should visit.
    pub fn boundaries(&self) -> Vec<u32> {
        (0..1u32 << self.cfg.n_bits()).map(|n| self.boundary(n)).collect()
    }

    /// [`Model::boundaries`] for one n.
    pub fn boundary(&self, n: u32) -> u32 {
        if let Kind::Quadratic = self.kind {
            return self.rom[n as usize];
        }
        // outputs are monotone in cos_g: bisect for the first code with intensity > 0
        let nz = |c: u32| self.eval(Inputs { cos_g: c, n, ks: [0; 3] }).intensity > 0;
        let (mut lo, mut hi) = (0u32, 1u32 << self.cfg.f());
        if nz(0) {
            return 0;
        }
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if nz(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// `--model blinn-pow`: square-and-multiply over the bits of n, LSB first, each product
    /// truncated to W fractional bits (see `widths::power_frac_bits`), as the RTL does it.
    pub fn eval_blinn_pow(&self, x: Inputs) -> Outputs {
        let w = self.widths.power_frac_bits;
        let (f, fi, b, nb) = (self.cfg.f(), self.cfg.fi(), self.cfg.b(), self.cfg.n_bits());
        let cos_g = x.cos_g as u128 & mask(f + 1);
        let n = x.n as u128 & mask(nb);
        // step 1: clamp to 1.0, widen UQ1.F → UQ1.W; r = 1.0
        let mut power = cos_g.min(1 << f) << (w - f);
        let mut result = 1u128 << w;
        // steps 2..N+1: one bit of n each
        for i in 0..nb {
            if (n >> i) & 1 == 1 {
                result = (result * power) >> w;
            }
            if i + 1 < nb {
                power = (power * power) >> w;
            }
        }
        // last step: round half up to the outputs
        let intensity = ((result + (1u128 << (w - fi - 1))) >> (w - fi)) as u32;
        let spec = x.ks.map(|k| (((result * (k as u128 & mask(b))) + (1u128 << (w - 1))) >> w) as u32);
        Outputs { spec, intensity, done: intensity == 0 }
    }

    /// Runs the quadratic datapath and returns every intermediate value (the other models
    /// have their own traces: [`fitted::trace`], [`blinn::trace`]).
    pub fn trace(&self, x: Inputs) -> Trace {
        if self.cfg.model() != SpecularModel::Quadratic {
            return Trace { outputs: self.eval(x), ..Trace::default() };
        }
        let w = &self.widths;
        let f = self.cfg.f();
        let wb = w.bracket_frac_bits;
        let ws = w.square_frac_bits;
        let fi = self.cfg.fi();
        let b = self.cfg.b();
        let one = 1u64 << f;
        let cos_g = x.cos_g as u64 & mask(f + 1) as u64;
        let n = x.n as u64 & mask(self.cfg.n_bits()) as u64;
        let ks = x.ks.map(|k| k as u128 & mask(b));

        // step 1: clamp, 1 − cos (adder 6), ROM, comparator, k_code·n
        let cos_clamped = cos_g.min(one);
        let one_minus_cos = one - cos_clamped;
        let cos_sp = self.rom[n as usize] as u64;
        let done = cos_clamped < cos_sp;
        let kn = self.cfg.k_code * n;
        // step 2: P = kn·d, truncation #1 to WB fractional bits (keep WB+1 bits)
        let deviation_full = kn as u128 * one_minus_cos as u128;
        let deviation = ((deviation_full >> w.deviation_shift) & mask(wb + 1)) as u64;
        // step 3: bracket = 1 − dev, zeroed by the key block beyond the cut-off (mod 2^(WB+1))
        let bracket = if done { 0 } else { ((1u128 << wb).wrapping_sub(deviation as u128) & mask(wb + 1)) as u64 };
        // step 4: square, truncation #2 to WS fractional bits
        let square_full = bracket as u128 * bracket as u128;
        let square = (square_full >> w.square_shift) & mask(ws + 1);
        // step 5: colour products (of the square cut to WS_C bits); intensity rounding add
        let wsc = w.color_square_frac_bits;
        let color_square = square >> (ws - wsc);
        let color_prod = ks.map(|k| color_square * k);
        let intensity_sum = if ws > fi { square + (1u128 << (ws - fi - 1)) } else { square << (fi - ws) };
        // step 6: colour rounding add and the final slices
        let spec = color_prod.map(|p| ((p + (1u128 << (wsc - 1))) >> wsc) as u32);
        let intensity = if ws > fi { (intensity_sum >> (ws - fi)) as u32 } else { intensity_sum as u32 };
        Trace {
            cos_clamped,
            one_minus_cos,
            cos_sp,
            done,
            kn,
            deviation_full,
            deviation,
            bracket,
            square_full,
            square,
            color_prod,
            intensity_sum,
            outputs: Outputs { spec, intensity, done },
        }
    }
}

/// An ideal output value `num / 2^den_log2`, exact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ideal {
    pub num: u128,
    pub den_log2: u32,
}

impl Ideal {
    /// Round half up (= ties away from zero for these non-negative values).
    pub fn round_half_away(self) -> u128 {
        if self.den_log2 == 0 {
            self.num
        } else {
            (self.num + (1u128 << (self.den_log2 - 1))) >> self.den_log2
        }
    }
    pub fn is_integer(self) -> bool {
        self.num & mask(self.den_log2) == 0
    }
    pub fn to_f64(self) -> f64 {
        self.num as f64 / (self.den_log2 as f64).exp2()
    }
}

/// SPEC §3's ideal outputs for one input, as exact rationals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reference {
    /// `base · 2^(KF+F)` (may be negative).
    pub base_num: i128,
    pub base_den_log2: u32,
    pub done: bool,
    pub intensity: Ideal,
    pub spec: [Ideal; 3],
}

/// The exact reference: `c = min(cos_g, 2^F)/2^F`, `base = 1 − k_q·n·(1 − c)`,
/// `S = base²` (0 when `base < 0`), `intensity* = S·2^FI`, `spec_X* = S·ks_X`.
pub fn reference(cfg: &Config, x: Inputs) -> Reference {
    let (f, kf, fi) = (cfg.f(), cfg.kf(), cfg.fi());
    let c = (x.cos_g as i128).min(1i128 << f);
    let base_den_log2 = kf + f;
    let base_num = (1i128 << base_den_log2) - cfg.k_code as i128 * x.n as i128 * ((1i128 << f) - c);
    let done = base_num < 0;
    let s_num: u128 = if done { 0 } else { (base_num * base_num) as u128 };
    let den_log2 = 2 * base_den_log2;
    Reference { base_num, base_den_log2, done, intensity: Ideal { num: s_num << fi, den_log2 }, spec: x.ks.map(|k| Ideal { num: s_num * k as u128, den_log2 }) }
}

/// Checks one output against its ideal under the rounding contract.
pub fn check_value(rounding: Rounding, got: u32, ideal: Ideal) -> Result<(), String> {
    let scaled = (got as u128) << ideal.den_log2;
    let diff = scaled.abs_diff(ideal.num);
    let ok = match rounding {
        Rounding::Faithful => diff < 1u128 << ideal.den_log2,
        Rounding::Exact => got as u128 == ideal.round_half_away(),
    };
    if ok {
        Ok(())
    } else {
        Err(format!("got {got}, ideal {} ({}/2^{})", ideal.to_f64(), ideal.num, ideal.den_log2))
    }
}

/// Fractional bits of the interval reference for `cos^n`.
pub const POW_REF_BITS: u32 = 60;

/// Rigorous bounds `lo ≤ c^n·2^60 ≤ hi` for `c = min(cos_g, 2^F)/2^F`, by square-and-multiply
/// with every product rounded down (lo) and up (hi) at 60 fractional bits.
pub fn blinn_bounds(cfg: &Config, cos_g: u32, n: u32) -> (u128, u128) {
    let q = POW_REF_BITS;
    let one = 1u128 << q;
    let c = ((cos_g as u128).min(1 << cfg.f())) << (q - cfg.f());
    let (mut p_lo, mut p_hi, mut r_lo, mut r_hi) = (c, c, one, one);
    let mul_dn = |a: u128, b: u128| (a * b) >> q;
    let mul_up = |a: u128, b: u128| ((a * b + one - 1) >> q).min(one);
    let mut m = n;
    while m > 0 {
        if m & 1 == 1 {
            r_lo = mul_dn(r_lo, p_lo);
            r_hi = mul_up(r_hi, p_hi);
        }
        m >>= 1;
        if m > 0 {
            p_lo = mul_dn(p_lo, p_lo);
            p_hi = mul_up(p_hi, p_hi);
        }
    }
    (r_lo, r_hi)
}

/// Checks `--model blinn-pow` outputs: every output within 1 of its ideal `c^n·M` for every
/// value the interval allows; `done` ⇔ intensity is 0.
pub fn check_blinn_pow(cfg: &Config, x: Inputs, got: Outputs) -> Result<(), String> {
    let (lo, hi) = blinn_bounds(cfg, x.cos_g, x.n);
    let q = POW_REF_BITS;
    let within = |o: u32, m: u128| {
        let o = (o as u128) << q;
        // |o − v·m| < 1 for every v in [lo, hi]: o > hi·m − 1 and o < lo·m + 1
        o + (1u128 << q) > hi * m && o < lo * m + (1u128 << q)
    };
    if !within(got.intensity, 1u128 << cfg.fi()) {
        return Err(format!(
            "intensity: got {}, cos^n·2^FI in [{}, {}]",
            got.intensity,
            (lo << cfg.fi()) as f64 / (q as f64).exp2(),
            (hi << cfg.fi()) as f64 / (q as f64).exp2()
        ));
    }
    for (i, name) in ["spec_r", "spec_g", "spec_b"].iter().enumerate() {
        if !within(got.spec[i], x.ks[i] as u128) {
            return Err(format!(
                "{name}: got {}, cos^n·ks in [{}, {}]",
                got.spec[i],
                (lo * x.ks[i] as u128) as f64 / (q as f64).exp2(),
                (hi * x.ks[i] as u128) as f64 / (q as f64).exp2()
            ));
        }
    }
    if got.done != (got.intensity == 0) {
        return Err(format!("done: got {}, intensity {}", got.done, got.intensity));
    }
    Ok(())
}

/// Checks a full output vector against its model's contract for one input (SPEC §3 for the
/// quadratic unit, faithful `c^n` for blinn and blinn-pow, its own formula for fitted).
pub fn check(cfg: &Config, x: Inputs, got: Outputs) -> Result<(), String> {
    match cfg.model() {
        SpecularModel::BlinnPow | SpecularModel::Blinn => return check_blinn_pow(cfg, x, got),
        SpecularModel::Fitted => return fitted::check(cfg, &cached_fit(cfg), x, got),
        SpecularModel::Quadratic => {}
    }
    let r = reference(cfg, x);
    if got.done != r.done {
        return Err(format!("done: got {}, reference {}", got.done, r.done));
    }
    check_value(cfg.rounding(), got.intensity, r.intensity).map_err(|e| format!("intensity: {e}"))?;
    for (i, name) in ["spec_r", "spec_g", "spec_b"].iter().enumerate() {
        check_value(cfg.rounding(), got.spec[i], r.spec[i]).map_err(|e| format!("{name}: {e}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_cosine_gives_full_colour() {
        let cfg = Config::defaults();
        let m = Model::new(&cfg);
        let o = m.eval(Inputs { cos_g: 1 << 15, n: 500, ks: [255, 7, 0] });
        assert_eq!(o, Outputs { spec: [255, 7, 0], intensity: 1 << 15, done: false });
    }

    #[test]
    fn check_rejects_off_by_one() {
        let cfg = Config::defaults();
        let x = Inputs { cos_g: 32000, n: 40, ks: [200, 100, 50] };
        let mut o = Model::new(&cfg).eval(x);
        assert!(check(&cfg, x, o).is_ok());
        o.spec[1] += 1;
        assert!(check(&cfg, x, o).is_err());
    }
}

/// How far a configured unit is from Blinn's `cos^n` (SPEC §6): `|intensity/2^FI − c^n|`
/// over every `(cos_g ≤ 2^F, n)`, or over every `stride`-th `cos_g` (and 1.0) when the
/// space exceeds [`FIDELITY_POINTS`].
#[derive(Debug, Clone, PartialEq)]
pub struct Fidelity {
    pub max: f64,
    pub mean: f64,
    /// where the maximum is
    pub worst_n: u32,
    pub worst_cos: u32,
    pub points: u64,
    pub stride: u32,
    /// `max_c |intensity/2^FI − c^n|` for each n
    pub per_n_max: Vec<f64>,
}

/// The most points [`blinn_fidelity`] visits: 2^26.
pub const FIDELITY_POINTS: u64 = 1 << 26;

impl Fidelity {
    pub fn method(&self) -> String {
        match self.stride {
            1 => format!("every (cos_g <= 2^F, n): {} points", self.points),
            s => format!("every {s}th cos_g code (and 1.0) for every n: {} points", self.points),
        }
    }
}

/// Measures [`Fidelity`] with the golden model (two threads or more).
pub fn blinn_fidelity(m: &Model) -> Fidelity {
    let cfg = &m.cfg;
    let one = 1u32 << cfg.f();
    let n_count = 1u32 << cfg.n_bits();
    let full = (one as u64 + 1) * n_count as u64;
    let stride = full.div_ceil(FIDELITY_POINTS).max(1) as u32;
    let scale = (cfg.fi() as f64).exp2();
    // a fixed partition (not the core count), so the sums and the manifest are the same bytes
    // on every machine
    let threads = 8u32;
    /// one thread's part: max, sum, worst n, worst cos_g, points, per-n maxima
    type Part = (f64, f64, u32, u32, u64, Vec<(u32, f64)>);
    let parts: Vec<Part> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    let (mut max, mut sum, mut wn, mut wc, mut count) = (0.0f64, 0.0f64, 0u32, 0u32, 0u64);
                    let mut per_n = Vec::new();
                    for n in (t..n_count).step_by(threads as usize) {
                        let mut row_max = 0.0f64;
                        let mut cos_g = 0u32;
                        loop {
                            let c = cos_g as f64 / one as f64;
                            let got = m.eval(Inputs { cos_g, n, ks: [0; 3] }).intensity as f64 / scale;
                            let err = (got - c.powi(n as i32)).abs();
                            sum += err;
                            count += 1;
                            row_max = row_max.max(err);
                            if err > max {
                                (max, wn, wc) = (err, n, cos_g);
                            }
                            if cos_g == one {
                                break;
                            }
                            cos_g = (cos_g + stride).min(one);
                        }
                        per_n.push((n, row_max));
                    }
                    (max, sum, wn, wc, count, per_n)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("fidelity thread")).collect()
    });
    let mut f = Fidelity { max: 0.0, mean: 0.0, worst_n: 0, worst_cos: 0, points: 0, stride, per_n_max: vec![0.0; n_count as usize] };
    let mut sum = 0.0;
    for (max, s, wn, wc, count, per_n) in parts {
        for (n, e) in per_n {
            f.per_n_max[n as usize] = e;
        }
        if max > f.max || (max == f.max && (wn, wc) < (f.worst_n, f.worst_cos)) {
            (f.max, f.worst_n, f.worst_cos) = (max, wn, wc);
        }
        sum += s;
        f.points += count;
    }
    f.mean = sum / f.points as f64;
    f
}
