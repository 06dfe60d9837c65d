//! The models: what each unit computes, each in one home behind one trait.
//!
//! A model's home (`quadratic/`, `fitted.rs`, `blinn/`, `blinn_pow.rs`, `schlick/`) holds everything
//! that model is: its error budget (module doc) and widths, its tables, its bit-exact golden
//! model, its exact reference and contract check, its datapath on the shared
//! [`Builder`](crate::datapath::Builder), its header text and its `eval` trace. Everything
//! downstream (`plan`, `emit`, `cosim`, `report`, `render`, `vectors`, the CLI) sees a model
//! only through [`SpecularUnit`], held by a [`Model`]; [`unit`] is the one registry.
//!
//! This module also holds what the contracts share: exact ideal values ([`Ideal`]), the
//! rounding check ([`check_value`]), the rigorous bounds on `c^n` ([`cos_n_bounds`],
//! [`check_cos_n`]) and the distance to Blinn every manifest reports ([`blinn_fidelity`]).

pub mod blinn;
pub mod blinn_pow;
pub mod display;
pub mod fitted;
pub mod quadratic;
pub mod schlick;

use crate::bits::mask;
use crate::config::{Config, Rounding, SpecularModel};
use crate::datapath::Builder;
use crate::error::Error;
pub use crate::ports::{Inputs, Outputs};
use std::sync::{Arc, OnceLock};

/// What a model's header, manifest and `.core` say of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Description {
    /// the model's own parameters, `name=value` words, for the header (none of `stages`,
    /// `rounding`, `rom_style`: the header adds those)
    pub(crate) param_line: String,
    /// the formula, one line each
    pub(crate) formula: Vec<String>,
    /// the rounding contract
    pub(crate) rounding: String,
    /// the datapath and its widths, one line
    pub(crate) datapath: String,
    /// what `done` means
    pub(crate) done_meaning: &'static str,
    /// one line for the `.core` description
    pub(crate) summary: &'static str,
    /// what it computes, in a few words (the report's model comparison)
    pub(crate) computes: &'static str,
}

/// The part a model plays in the report's verdict on the paper's premise (that `cos^n` itself
/// costs too much): the paper's formula, a cheaper fit, the table-based `cos^n`, or `cos^n`
/// the costly way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PremiseRole {
    /// the paper's own formula
    Paper,
    /// a closer approximation of the same shape
    Fit,
    /// `cos^n` itself, by tables
    Tables,
    /// `cos^n` itself, by square-and-multiply
    SquareAndMultiply,
}

/// One model of the unit (SPEC §3, §6): the golden model, its contract and its datapath.
///
/// Everything here is a function of the configuration the model was made from; a model is
/// made once per command ([`unit`]) and shared.
pub trait SpecularUnit: Send + Sync + std::fmt::Debug {
    /// The unit's outputs for one input, bit for bit as the RTL computes them.
    fn eval(&self, x: Inputs) -> Outputs;
    /// [`SpecularUnit::eval`] of every input of `xs`, into `out` (cleared first): what the
    /// co-simulation asks a batch at a time, one dynamic call a batch (this default is compiled
    /// for each model, so its `eval` is called, and inlined, directly).
    fn eval_batch(&self, xs: &[Inputs], out: &mut Vec<Outputs>) {
        out.clear();
        out.extend(xs.iter().map(|&x| self.eval(x)));
    }

    /// The intensity of `n` at every code of `codes` (colours zero), appended to `out`: what
    /// [`blinn_fidelity`] measures a row at a time, `eval` inlined with the colour products it
    /// does not read left out.
    fn intensity_row(&self, n: u32, codes: &[u32], out: &mut Vec<u32>) {
        out.extend(codes.iter().map(|&cos_g| {
            self.eval(Inputs {
                cos_g,
                n,
                ks: [0; 3],
            })
            .intensity
        }));
    }

    /// Checks outputs against this model's contract (its exact reference): `Err` says which
    /// output breaks it and by how much.
    fn check(&self, x: Inputs, got: Outputs) -> Result<(), Error>;

    /// The ideal outputs the contract refers to, as floats (for reports): `(intensity, spec)`.
    fn ideal(&self, x: Inputs) -> (f64, [f64; 3]);

    /// The cut-off code of `n` when the model stores it (the first `cos_g` with `done` low);
    /// `None` lets [`Model::boundary`] find the first code with a non-zero output.
    fn cut_off(&self, _n: u32) -> Option<u32> {
        None
    }

    /// Describes the datapath on the builder, step by step (the plan places the registers).
    /// It must define the output signals `spec_r`, `spec_g`, `spec_b`, `intensity`, `done`.
    fn datapath(&self, b: &mut Builder);

    /// The header text: formula, contract, widths.
    fn describe(&self) -> Description;

    /// The internal widths, for the manifest's `internal_widths`.
    fn widths(&self) -> serde_json::Value;

    /// The internal values of the golden model for one input, one line each, for `specgen eval`.
    fn explain(&self, x: Inputs) -> Vec<String>;

    /// Its part in the report's verdict on the paper's premise; none leaves it out of it.
    fn premise_role(&self) -> Option<PremiseRole> {
        None
    }

    /// What the model's exact reference is, in words (the report's contract line).
    fn reference_words(&self) -> &'static str {
        "its exact reference (the same function in exact arithmetic)"
    }

    /// What quantising the model's constant costs at one input, as a fraction of full scale
    /// (the model with its quantised constant against the same formula with the real one),
    /// when the model has such a constant; the report gives its maximum.
    fn quantisation_error(&self, _x: Inputs) -> Option<f64> {
        None
    }

    /// The ideal cut-off cosine at `n` beside the stored one ([`SpecularUnit::cut_off`]): the
    /// report draws both.
    fn ideal_cut_off(&self, _n: u32) -> Option<f64> {
        None
    }

    /// Whether `--target-mhz` reads the family's delay line for it where its datapath has no
    /// calibration rows of its own (an extrapolation, said so): a datapath never calibrated
    /// alone (the paper's literal one) or one that fits no part. False for a new model until
    /// its units are measured: the fit then gives it no line and `--target-mhz` refuses it,
    /// naming the calibration script (`timing::fit`).
    fn reads_family_delay_line(&self) -> bool {
        false
    }

    /// A sentence `specgen eval` adds to its fidelity line at one input (a formula in real
    /// arithmetic the model approximates), when there is one.
    fn fidelity_note(&self, _x: Inputs) -> Option<String> {
        None
    }
}

/// The registry: the model a configuration asks for. Every model is one line here.
pub fn unit(cfg: &Config) -> Arc<dyn SpecularUnit> {
    match cfg.model() {
        SpecularModel::Quadratic => Arc::new(quadratic::Quadratic::new(cfg)),
        SpecularModel::Fitted => Arc::new(fitted::Fitted::new(cfg)),
        SpecularModel::Blinn => Arc::new(blinn::Blinn::new(cfg)),
        SpecularModel::BlinnPow => Arc::new(blinn_pow::BlinnPow::new(cfg)),
        SpecularModel::Schlick => Arc::new(schlick::Schlick::new(cfg)),
    }
}

/// The golden model of one configuration: the configuration and its [`SpecularUnit`].
#[derive(Debug, Clone)]
pub struct Model {
    pub cfg: Config,
    unit: Arc<dyn SpecularUnit>,
    /// [`blinn_fidelity`], measured once and shared by every depth of the model
    fidelity: Arc<OnceLock<Fidelity>>,
}

impl Model {
    /// The model of a configuration (its fit or tables made here).
    pub fn new(cfg: &Config) -> Model {
        Model {
            cfg: cfg.clone(),
            unit: unit(cfg),
            fidelity: Arc::default(),
        }
    }

    /// This model under another configuration that differs only in `stages` (or nothing the
    /// arithmetic depends on): the fit or tables are shared, not made again.
    pub(crate) fn with_config(&self, cfg: Config) -> Model {
        let same = |c: &Config| crate::config::Params {
            stages: 0,
            ..c.params.clone()
        };
        debug_assert_eq!(same(&cfg), same(&self.cfg), "only stages may differ");
        Model {
            cfg,
            unit: self.unit.clone(),
            fidelity: self.fidelity.clone(),
        }
    }

    /// How far this model is from Blinn's `cos^n` ([`blinn_fidelity`]), measured on first use.
    pub fn fidelity(&self) -> &Fidelity {
        self.fidelity.get_or_init(|| blinn_fidelity(self))
    }

    /// The model behind the trait.
    pub fn unit(&self) -> &dyn SpecularUnit {
        self.unit.as_ref()
    }

    /// The unit's outputs for one input, bit for bit.
    pub fn eval(&self, x: Inputs) -> Outputs {
        self.unit.eval(x)
    }

    /// [`SpecularUnit::eval_batch`]: the outputs of every input of `xs`, into `out`.
    pub fn eval_batch(&self, xs: &[Inputs], out: &mut Vec<Outputs>) {
        self.unit.eval_batch(xs, out)
    }

    /// See [`SpecularUnit::ideal`].
    pub fn ideal(&self, x: Inputs) -> (f64, [f64; 3]) {
        self.unit.ideal(x)
    }

    /// Checks outputs against this model's contract (its exact reference).
    pub fn check(&self, x: Inputs, got: Outputs) -> Result<(), Error> {
        self.unit.check(x, got)
    }

    /// The last `cos_g` code with a non-zero output, or the cut-off, for each n: the
    /// boundary a test stimulus should visit.
    pub(crate) fn boundaries(&self) -> Vec<u32> {
        (0..1u32 << self.cfg.n_bits())
            .map(|n| self.boundary(n))
            .collect()
    }

    /// [`Model::boundaries`] for one n.
    pub fn boundary(&self, n: u32) -> u32 {
        if let Some(c) = self.unit.cut_off(n) {
            return c;
        }
        // outputs are monotone in cos_g: bisect for the first code with intensity > 0
        let nz = |c: u32| {
            self.eval(Inputs {
                cos_g: c,
                n,
                ks: [0; 3],
            })
            .intensity
                > 0
        };
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
}

/// `c = min(cos_g, 2^F)/2^F` as a float.
pub fn cosine(cfg: &Config, cos_g: u32) -> f64 {
    cos_g.min(1 << cfg.f()) as f64 / (cfg.f() as f64).exp2()
}

/// Ideal outputs `(S·2^FI, S·ks)` of a float `S`.
pub fn scaled(cfg: &Config, s: f64, x: Inputs) -> (f64, [f64; 3]) {
    (s * (cfg.fi() as f64).exp2(), x.ks.map(|k| s * k as f64))
}

/// The `exact` line of `specgen eval`: the ideal outputs, then `tail` (what they are).
pub(crate) fn explain_ideal(ideal: (f64, [f64; 3]), tail: &str) -> String {
    let (i, s) = ideal;
    format!(
        "exact      intensity* = {i:.9}  spec* = [{:.6}, {:.6}, {:.6}]  {tail}",
        s[0], s[1], s[2]
    )
}

/// An ideal output value `num / 2^den_log2`, exact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ideal {
    pub num: u128,
    pub den_log2: u32,
}

impl Ideal {
    /// Round half up (= ties away from zero for these non-negative values).
    pub(crate) fn round_half_away(self) -> u128 {
        if self.den_log2 == 0 {
            self.num
        } else {
            (self.num + (1u128 << (self.den_log2 - 1))) >> self.den_log2
        }
    }
    pub fn is_integer(self) -> bool {
        self.num & mask(self.den_log2) == 0
    }
    pub(crate) fn to_f64(self) -> f64 {
        self.num as f64 / (self.den_log2 as f64).exp2()
    }
}

/// Checks one output (`port`) against its ideal under the rounding contract.
pub(crate) fn check_value(
    port: &'static str,
    rounding: Rounding,
    got: u32,
    ideal: Ideal,
) -> Result<(), Error> {
    let scaled = (got as u128) << ideal.den_log2;
    let diff = scaled.abs_diff(ideal.num);
    let ok = match rounding {
        Rounding::Faithful => diff < 1u128 << ideal.den_log2,
        Rounding::Exact => got as u128 == ideal.round_half_away(),
    };
    if ok {
        Ok(())
    } else {
        Err(Error::breach(
            port,
            format!(
                "got {got}, ideal {} ({}/2^{})",
                ideal.to_f64(),
                ideal.num,
                ideal.den_log2
            ),
        ))
    }
}

/// Fractional bits of the interval reference for `cos^n`.
pub(crate) const POW_REF_BITS: u32 = 60;

/// Rigorous bounds `lo ≤ c^n·2^60 ≤ hi` for `c = min(cos_g, 2^F)/2^F`, by square-and-multiply
/// with every product rounded down (lo) and up (hi) at 60 fractional bits.
pub(crate) fn cos_n_bounds(cfg: &Config, cos_g: u32, n: u32) -> (u128, u128) {
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

/// Checks a `c^n` model's outputs (blinn, blinn-pow): every output within 1 of its ideal
/// `c^n·M` for every value the interval allows; `done` ⇔ intensity is 0.
pub(crate) fn check_cos_n(cfg: &Config, x: Inputs, got: Outputs) -> Result<(), Error> {
    let (lo, hi) = cos_n_bounds(cfg, x.cos_g, x.n);
    let q = POW_REF_BITS;
    let within = |o: u32, m: u128| {
        let o = (o as u128) << q;
        // |o − v·m| < 1 for every v in [lo, hi]: o > hi·m − 1 and o < lo·m + 1
        o + (1u128 << q) > hi * m && o < lo * m + (1u128 << q)
    };
    let scaled = |v: u128| v as f64 / (q as f64).exp2();
    if !within(got.intensity, 1u128 << cfg.fi()) {
        let (l, h) = (scaled(lo << cfg.fi()), scaled(hi << cfg.fi()));
        return Err(Error::breach(
            "intensity",
            format!("got {}, cos^n·2^FI in [{l}, {h}]", got.intensity),
        ));
    }
    for (i, name) in SPEC_PORTS.iter().enumerate() {
        if !within(got.spec[i], x.ks[i] as u128) {
            let (l, h) = (scaled(lo * x.ks[i] as u128), scaled(hi * x.ks[i] as u128));
            return Err(Error::breach(
                name,
                format!("got {}, cos^n·ks in [{l}, {h}]", got.spec[i]),
            ));
        }
    }
    if got.done != (got.intensity == 0) {
        return Err(Error::breach(
            "done",
            format!("got {}, intensity {}", got.done, got.intensity),
        ));
    }
    Ok(())
}

/// How far a configured unit is from Blinn's `cos^n` (SPEC §6): `|intensity/2^FI − c^n|`
/// over every `(cos_g ≤ 2^F, n)`, or over every `stride`-th `cos_g` (and 1.0) when the
/// space exceeds [`FIDELITY_POINTS`].
#[derive(Debug, Clone, PartialEq)]
pub struct Fidelity {
    pub max: f64,
    pub mean: f64,
    /// the root of the mean square error
    pub rms: f64,
    /// where the maximum is
    pub(crate) worst_n: u32,
    pub(crate) worst_cos: u32,
    pub points: u64,
    pub stride: u32,
    /// `max_c |intensity/2^FI − c^n|` for each n
    pub(crate) per_n_max: Vec<f64>,
    /// the error at the pixel: the real cosine rounded to F bits first ([`Pixel`])
    pub pixel: Pixel,
}

/// The error a shader sees (SPEC §6): its real cosine `c ∈ [0, 1]` is rounded to the nearest
/// F-bit code `q` before the unit reads it, so the intensity `I(q)` stands for every `c` of
/// `[(q − ½)/2^F, (q + ½)/2^F] ∩ [0, 1]`.
///
/// - `max`: the worst `|I(q)/2^FI − c^n|` over those `c` and every `n`. `c^n` is monotone in
///   `c`, so the worst `c` of a code is an end of its interval: exact where every code is
///   visited. Where only every `stride`-th code is, the codes between two visited ones `a < b`
///   hold intensities in `[I(a), I(b)]` (every model is monotone in `cos_g`) for `c` in
///   `[lo(a), lo(b)]`, and `max(I(b) − lo(a)^n, lo(b)^n − I(a))` bounds them: a bound, never
///   below the true figure.
/// - `mean`, `rms`: over `c` uniform in `[0, 1]` (and every `n`), integrated in closed form on
///   each visited code's interval (`∫ c^n = c^(n+1)/(n+1)`, split where `c^n` crosses `I`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pixel {
    pub max: f64,
    pub mean: f64,
    pub rms: f64,
    /// true: `max` is the stride's bound, not every code's exact figure
    pub bound: bool,
}

/// A bound on the error at the pixel for a unit faithful to `c^n` itself (`blinn`,
/// `blinn-pow`: every intensity within one unit, 2^−FI, of `(q/2^F)^n`, their contracts): that
/// unit, plus the rounding's own worst, `max |c^n − (q/2^F)^n|` over `c` within half a code of
/// `q`. `(c + h)^n − c^n` grows with `c`, so the rounding's worst is at the top code,
/// `1 − (1 − 2^−(F+1))^n`, largest at the largest n. Where codes are visited with a stride this
/// is far tighter than the stride's monotone bound (which grows with the stride's width).
fn faithful_pixel_bound(cfg: &crate::config::Config) -> Option<f64> {
    if !matches!(cfg.model(), SpecularModel::Blinn | SpecularModel::BlinnPow) {
        return None;
    }
    let h = (-(cfg.f() as f64) - 1.0).exp2();
    let n_max = (1u64 << cfg.n_bits()) - 1;
    Some((-(cfg.fi() as f64)).exp2() + (1.0 - (1.0 - h).powi(n_max as i32)))
}

/// The ends of the real cosines that round to `codes` (and the last code's top, 1.0), clipped
/// to `[0, 1]`: `lo[i]` is code i's bottom, `hi[i]` its top.
fn pixel_ends(codes: &[u32], one: u32) -> (Vec<f64>, Vec<f64>) {
    let end = |x: f64| (x / one as f64).clamp(0.0, 1.0);
    (
        codes.iter().map(|&q| end(q as f64 - 0.5)).collect(),
        codes.iter().map(|&q| end(q as f64 + 0.5)).collect(),
    )
}

/// `∫ |i − c^n| dc` and `∫ (i − c^n)² dc` over `[lo, hi]`, from the powers of the ends.
#[allow(clippy::too_many_arguments)]
fn pixel_integrals(
    i: f64,
    n: u32,
    lo: f64,
    hi: f64,
    lo_n: f64,
    hi_n: f64,
    lo_n1: f64,
    hi_n1: f64,
    lo_2n1: f64,
    hi_2n1: f64,
) -> (f64, f64) {
    let w = hi - lo;
    let n1 = (n + 1) as f64;
    let area = (hi_n1 - lo_n1) / n1;
    let abs = if lo_n < i && i < hi_n {
        // c^n crosses i at c*: below it i − c^n, above it c^n − i
        let x = i.powf(1.0 / n as f64);
        let x_n1 = x.powi(n as i32 + 1) / n1;
        (i * (x - lo) - (x_n1 - lo_n1 / n1)) + ((hi_n1 / n1 - x_n1) - i * (hi - x))
    } else {
        (i * w - area).abs()
    };
    let square = i * i * w - 2.0 * i * area + (hi_2n1 - lo_2n1) / (2 * n + 1) as f64;
    (abs, square.max(0.0))
}

/// The most points [`blinn_fidelity`] visits: 2^26.
pub(crate) const FIDELITY_POINTS: u64 = 1 << 26;

impl Fidelity {
    pub fn method(&self) -> String {
        match self.stride {
            1 => format!("every (cos_g <= 2^F, n): {} points", self.points),
            s => format!(
                "every {s}th cos_g code (and 1.0) for every n: {} points",
                self.points
            ),
        }
    }
    /// How [`Fidelity::pixel`] was measured.
    pub fn pixel_method(&self) -> String {
        match self.pixel.bound {
            false => "every code's interval of real cosines (round to nearest) and every n: exact".to_string(),
            true => format!("every {}th code's interval and every n: max a bound (by monotonicity, or a unit faithful to c^n plus the rounding's worst), mean and RMS of the visited intervals", self.stride),
        }
    }
}

/// Measures [`Fidelity`] with the golden model (two threads or more).
///
/// Every model's outputs are monotone in `cos_g` (SPEC §6; the exhaustive tests check it on
/// every model's whole input space at the default widths, the property tests elsewhere), so a
/// row's outputs below its first non-zero one are zero: a bisection finds it, and only the
/// codes from there are evaluated (at `n` large, a few percent of the row). The errors are
/// the same numbers, summed in the same order, so the figures are the same bits.
pub fn blinn_fidelity(m: &Model) -> Fidelity {
    fidelity_within(m, FIDELITY_POINTS)
}

/// [`blinn_fidelity`] on every point, whatever the space's size (a test's: 2^30 points at
/// F = 20, N = 10).
pub fn fidelity_exhaustive(m: &Model) -> Fidelity {
    fidelity_within(m, u64::MAX)
}

/// [`blinn_fidelity`] visiting at most about `points` points.
fn fidelity_within(m: &Model, points: u64) -> Fidelity {
    let cfg = &m.cfg;
    let one = 1u32 << cfg.f();
    let n_count = 1u32 << cfg.n_bits();
    let full = (one as u64 + 1) * n_count as u64;
    let stride = full.div_ceil(points).max(1) as u32;
    let scale = (cfg.fi() as f64).exp2();
    // a fixed partition (not the core count), so the sums and the manifest are the same bytes
    // on every machine
    let threads = 8u32;
    /// one thread's part: max, sum, worst n, worst cos_g, points, per-n maxima; the pixel's
    /// max, integral of |error| and of its square, and the width integrated over
    type Part = (f64, f64, f64, u32, u32, u64, Vec<(u32, f64)>, [f64; 4]);
    // the codes of a row, and c = code/2^F (exact): the same for every n
    let mut codes: Vec<u32> = (0..one).step_by(stride as usize).collect();
    codes.push(one);
    let cs: Vec<f64> = codes.iter().map(|&c| c as f64 / one as f64).collect();
    let (los, his) = pixel_ends(&codes, one);
    let (codes, cs, los, his) = (&codes, &cs, &los, &his);
    let parts: Vec<Part> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    let (mut max, mut sum, mut squares_sum, mut wn, mut wc, mut count) =
                        (0.0f64, 0.0f64, 0.0f64, 0u32, 0u32, 0u64);
                    let mut per_n = Vec::new();
                    let (mut got, mut powers, mut squares) = (Vec::new(), Vec::new(), Vec::new());
                    let mut ends: [Vec<f64>; 6] = Default::default();
                    let mut pixel = [0.0f64; 4];
                    for n in (t..n_count).step_by(threads as usize) {
                        // below the row's first non-zero output every output is zero
                        // (monotone in cos_g), so only the rest is evaluated
                        let zeros = codes.partition_point(|&c| {
                            m.eval(Inputs {
                                cos_g: c,
                                n,
                                ks: [0; 3],
                            })
                            .intensity
                                == 0
                        });
                        got.clear();
                        got.resize(zeros, 0);
                        m.unit().intensity_row(n, &codes[zeros..], &mut got);
                        powi_row(cs, n, &mut powers, &mut squares);
                        let mut row_max = 0.0f64;
                        // in code order, as one sum: the same bits on every machine
                        for ((&cos_g, &g), &p) in codes.iter().zip(&got).zip(&powers) {
                            let err = (g as f64 / scale - p).abs();
                            sum += err;
                            squares_sum += err * err;
                            count += 1;
                            row_max = row_max.max(err);
                            if err > max {
                                (max, wn, wc) = (err, n, cos_g);
                            }
                        }
                        per_n.push((n, row_max));
                        // the pixel: each code's interval of real cosines (SPEC §6, [`Pixel`])
                        for (k, v) in ends.iter_mut().enumerate() {
                            let from = if k % 2 == 0 { los } else { his };
                            powi_row(from, [n, n + 1, 2 * n + 1][k / 2], v, &mut squares);
                        }
                        let [lo_n, hi_n, lo_n1, hi_n1, lo_2n1, hi_2n1] = &ends;
                        let last = codes.len() - 1;
                        for j in 0..codes.len() {
                            let i = got[j] as f64 / scale;
                            let worst = if stride == 1 {
                                (i - lo_n[j]).max(hi_n[j] - i)
                            } else {
                                // the codes up to the next visited one: intensities in
                                // [I(j), I(j+1)], cosines in [lo(j), lo(j+1)]
                                let (top_i, top_c) = if j < last {
                                    (got[j + 1] as f64 / scale, lo_n[j + 1])
                                } else {
                                    (i, hi_n[j])
                                };
                                (top_i - lo_n[j]).max(top_c - i)
                            };
                            pixel[0] = pixel[0].max(worst);
                            let (a, q) = pixel_integrals(
                                i, n, los[j], his[j], lo_n[j], hi_n[j], lo_n1[j], hi_n1[j],
                                lo_2n1[j], hi_2n1[j],
                            );
                            pixel[1] += a;
                            pixel[2] += q;
                            pixel[3] += his[j] - los[j];
                        }
                    }
                    (max, sum, squares_sum, wn, wc, count, per_n, pixel)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("fidelity thread"))
            .collect()
    });
    let mut f = Fidelity {
        max: 0.0,
        mean: 0.0,
        rms: 0.0,
        worst_n: 0,
        worst_cos: 0,
        points: 0,
        stride,
        per_n_max: vec![0.0; n_count as usize],
        pixel: Pixel {
            bound: stride > 1,
            ..Pixel::default()
        },
    };
    let (mut sum, mut squares) = (0.0, 0.0);
    let mut pixel = [0.0f64; 4];
    for (max, s, sq, wn, wc, count, per_n, px) in parts {
        pixel[0] = pixel[0].max(px[0]);
        for k in 1..4 {
            pixel[k] += px[k];
        }
        for (n, e) in per_n {
            f.per_n_max[n as usize] = e;
        }
        if max > f.max || (max == f.max && (wn, wc) < (f.worst_n, f.worst_cos)) {
            (f.max, f.worst_n, f.worst_cos) = (max, wn, wc);
        }
        sum += s;
        squares += sq;
        f.points += count;
    }
    f.mean = sum / f.points as f64;
    f.rms = (squares / f.points as f64).sqrt();
    f.pixel.max = pixel[0];
    if stride > 1 {
        if let Some(b) = faithful_pixel_bound(cfg) {
            f.pixel.max = f.pixel.max.min(b);
        }
    }
    f.pixel.mean = pixel[1] / pixel[3];
    f.pixel.rms = (pixel[2] / pixel[3]).sqrt();
    f
}

/// `c.powi(n)` of every `c` of `cs`, into `out`: `powi`'s own square-and-multiply (the
/// runtime's `__powidf2`: a product where n has a one bit, a squaring between), done a row at
/// a time so that each step is one loop over the row; the same operations in the same order,
/// so the same bits as `powi`.
fn powi_row(cs: &[f64], n: u32, out: &mut Vec<f64>, squares: &mut Vec<f64>) {
    out.clear();
    out.resize(cs.len(), 1.0);
    squares.clear();
    squares.extend_from_slice(cs);
    let mut pow = n;
    loop {
        if pow & 1 != 0 {
            for (o, a) in out.iter_mut().zip(squares.iter()) {
                *o *= *a;
            }
        }
        pow >>= 1;
        if pow == 0 {
            break;
        }
        for a in squares.iter_mut() {
            *a *= *a;
        }
    }
}

/// The colour output ports, in channel order.
pub(crate) const SPEC_PORTS: [&str; 3] = ["spec_r", "spec_g", "spec_b"];

#[cfg(test)]
mod tests;
