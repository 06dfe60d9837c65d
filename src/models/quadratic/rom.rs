//! The cut-off ROM `cos_sp(n)` (SPEC §3) and its export formats.
//!
//! Entry n is the smallest code `C ∈ [0, 2^F]` whose bracket `1 − k_q·n·(1 − C/2^F)` is
//! non-negative. With `P(C) = k_code·n·(2^F − C)` that is `P(C) ≤ 2^(KF+F)`, i.e.
//! `2^F − C ≤ ⌊2^(KF+F) / (k_code·n)⌋`, so `C = max(0, 2^F − ⌊2^(KF+F) / (k_code·n)⌋)`
//! (and `C = 0` for `n = 0`, where the bracket is 1 everywhere).

use crate::config::Config;
use crate::table::Table;

/// Every entry of the ROM, index n = 0 .. 2^N − 1.
pub fn cos_sp_table(cfg: &Config) -> Vec<u32> {
    (0..1u64 << cfg.n_bits()).map(|n| cos_sp(cfg, n)).collect()
}

/// The cut-off code for one exponent n.
pub fn cos_sp(cfg: &Config, n: u64) -> u32 {
    let one = 1u128 << cfg.f();
    let kn = cfg.k_code as u128 * n as u128;
    if kn == 0 {
        return 0;
    }
    let reach = (1u128 << (cfg.kf() + cfg.f())) / kn; // largest 2^F − C with bracket ≥ 0
    one.saturating_sub(reach) as u32
}

/// The cut-off ROM (10) as a table of the unit.
pub fn cos_sp_rom(cfg: &Config) -> Table {
    Table {
        name: "cos_sp_rom".into(),
        param: "ROM_FILE".into(),
        width: cfg.f() + 1,
        words: cos_sp_table(cfg).into_iter().map(u128::from).collect(),
        what: format!("cut-off ROM cos_sp(n), UQ1.{}, address = n", cfg.f()),
        fields: vec![("cos_sp".into(), cfg.f() + 1)],
        cosines: Some(cfg.f()),
    }
}
