//! The digest that names a unit's RTL: what every measured row carries.

use super::source_files;
use crate::plan::Plan;

/// SHA-256 of what synthesis reads of a unit: its Verilog and table files as specgen writes them
/// (not the manifest, the testbench or the vectors). The clock a unit names (`clock_mhz`) reaches
/// its Verilog only as the parameters' fingerprint in a header comment, so the digest is taken of
/// the unit written without it: a unit generated for a clock is the very RTL measured without one.
pub fn rtl_digest(plan: &Plan) -> String {
    if plan.cfg.params.clock_mhz.is_some() {
        // the clock shapes no step of the plan: the same plan, its parameters without it
        let mut bare = plan.clone();
        bare.cfg.params.clock_mhz = None;
        return digest_of(&bare);
    }
    digest_of(plan)
}

fn digest_of(plan: &Plan) -> String {
    use sha2::Digest;
    let mut h = sha2::Sha256::new();
    for (name, bytes) in source_files(plan) {
        h.update(name.as_bytes());
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(&bytes);
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}
