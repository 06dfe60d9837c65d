//! `prove` is handed the ports the manifest names, or refuses: the same port check as `cosim`
//! and `synth`, before anything is proved (an extra output or a wider port was "proved").

use crate::common::*;

#[test]
fn prove_refuses_ports_the_manifest_does_not_name() {
    let tmp = tempfile::tempdir().unwrap();
    let narrow = ["--n-bits", "4", "--cos-frac-bits", "8", "--intensity-frac-bits", "8", "--color-bits", "4", "--stages", "2"];
    for (name, from, to, says) in [
        ("extra", ") (\n", ") (\n    output wire        extra,\n", "extra is not a port the manifest implies"),
        ("wider", "input  wire [3:0]  n,", "input  wire [4:0]  n,", "n is input of 5 bits in the RTL, input of 4 bits by the manifest"),
    ] {
        let unit = generate(tmp.path(), name, &narrow);
        let v = std::fs::read_to_string(unit.join("specular_unit.v")).unwrap();
        assert!(v.contains(from), "{name}: the edit's anchor {from:?}");
        rewrite_sealed(&unit, "specular_unit.v", &v.replacen(from, to, 1));
        let o = output_guarded(specgen().args(["prove", "--rtl"]).arg(&unit), "prove");
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {e}");
        assert!(e.contains(says), "{name}: {e}");
    }
}
