//! The digest that names a unit's RTL: what every measured row carries.

use super::source_files;
use crate::plan::Plan;

/// SHA-256 of what synthesis reads of a unit: its Verilog and table files as specgen writes them
/// (not the manifest, the testbench or the vectors).
pub fn rtl_digest(plan: &Plan) -> String {
    use sha2::Digest;
    let mut h = sha2::Sha256::new();
    for (name, bytes) in source_files(plan) {
        h.update(name.as_bytes());
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(&bytes);
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}
