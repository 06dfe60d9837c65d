//! The bit-exact golden model, with every intermediate value ([`BlinnTrace`]).

use super::*;

/// Every intermediate value of the blinn datapath for one input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BlinnTrace {
    pub(crate) cos_clamped: u64,
    pub(crate) exponent: u32,
    pub(crate) x: u64,
    pub(crate) ghat: u128,
    pub(crate) ell: u128,
    pub(crate) y: u128,
    pub(crate) ehat: u128,
    pub(crate) v: u128,
}

/// The bit-exact golden model.
pub fn trace(cfg: &Config, w: &BlinnWidths, t: &BlinnTables, x: Inputs) -> (BlinnTrace, Outputs) {
    let (f, fi, b) = (cfg.f(), cfg.fi(), cfg.b());
    let c = (x.cos_g as u64 & mask(f + 1) as u64).min(1 << f);
    let n = x.n as u128 & mask(cfg.n_bits());
    let zero = c == 0;
    let cm1 = c.wrapping_sub(1) & mask(f) as u64;
    let e = f - bit_length(cm1 as u128);
    let cn = (c << e) & mask(f + 1) as u64;
    let xx = ((1u64 << f).wrapping_sub(cn)) & mask(f - 1) as u64;
    let rb = w.log_rest_bits(cfg);
    let (i, r) = ((xx >> rb) as usize, xx as u128 & mask(rb));
    let ghat = t.g[i] + ((t.dg[i] * r) >> rb);
    let l = xx as u128 * ghat; // frac F + WG
    let lf = f + w.log_frac_bits;
    let full = ((e as u128) << lf) + l;
    let ell = if lf >= w.ell_frac_bits {
        full >> (lf - w.ell_frac_bits)
    } else {
        full << (w.ell_frac_bits - lf)
    };
    let y_full = (n * ell) >> (w.ell_frac_bits - w.y_frac_bits);
    let y = if (zero && n != 0) || y_full >= w.y_sat() {
        w.y_sat()
    } else {
        y_full
    };
    let (yint, yfrac) = ((y >> w.y_frac_bits) as u32, y & mask(w.y_frac_bits));
    let re = w.exp2_rest_bits();
    let (j, rr) = ((yfrac >> re) as usize, yfrac & mask(re));
    let ehat = t.e[j] - ((t.de[j] * rr) >> re);
    let v = ehat >> yint;
    let we = w.exp2_frac_bits;
    let intensity = ((v + (1u128 << (we - fi - 1))) >> (we - fi)) as u32;
    let wc = w.color_frac_bits;
    let vc = v >> (we - wc);
    let spec =
        x.ks.map(|k| ((vc * (k as u128 & mask(b)) + (1u128 << (wc - 1))) >> wc) as u32);
    (
        BlinnTrace {
            cos_clamped: c,
            exponent: e,
            x: xx,
            ghat,
            ell,
            y,
            ehat,
            v,
        },
        Outputs {
            spec,
            intensity,
            done: intensity == 0,
        },
    )
}
