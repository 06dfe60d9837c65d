//! The delay model's data through the binary: `specgen calibrate` fits and merges the
//! calibration rows (the shipped model is the fit of the shipped rows), refuses what it cannot
//! read, and with `specgen stale` writes its files before it says anything.

use crate::common::*;

/// `specgen calibrate` fits the shipped rows to the shipped model, refuses to write over the
/// rows it reads, and refuses a row that is no calibration unit naming its line (exit 2,
/// nothing written).
#[test]
fn calibrate_fits_the_shipped_rows_and_refuses_what_it_cannot_read() {
    let tmp = tempfile::tempdir().unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = tmp.path().join("model.json");
    let o = output_guarded(
        specgen()
            .arg("calibrate")
            .arg("--calibration")
            .arg(root.join("data/delay_calibration.csv"))
            .arg("--out")
            .arg(&out),
        "calibrate",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut fitted: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let mut shipped: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("data/delay_model.json")).unwrap())
            .unwrap();
    // the same lines; `source` names the file as given
    assert!(fitted["source"]
        .as_str()
        .unwrap()
        .ends_with("data/delay_calibration.csv"));
    for m in [&mut fitted, &mut shipped] {
        m.as_object_mut().unwrap().remove("source");
    }
    assert!(
        fitted == shipped,
        "the fit of the shipped rows is not the shipped model"
    );
    let csv = tmp.path().join("rows.csv");
    std::fs::write(
        &csv,
        "family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args,rtl_sha256\nice40,lean,3,0,0,90.0,90.0,--cos-frac-bits 99,\n",
    )
    .unwrap();
    let bad = tmp.path().join("bad.json");
    let o = output_guarded(
        specgen()
            .arg("calibrate")
            .arg("--calibration")
            .arg(&csv)
            .arg("--out")
            .arg(&bad),
        "calibrate",
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("line 2") && said.contains("cos_frac_bits"),
        "{said}"
    );
    assert!(!bad.exists());
    let o = output_guarded(
        specgen()
            .arg("calibrate")
            .arg("--calibration")
            .arg(&csv)
            .arg("--out")
            .arg(&csv),
        "calibrate",
    );
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(std::fs::read_to_string(&csv)
        .unwrap()
        .contains("--cos-frac-bits 99"));
    // --merge: the explorations' rows of today's RTL (specgen stale's) are in the shipped rows
    // already (the merged file is the shipped one, byte for byte); a new unit is added, sorted in
    let rows = tmp.path().join("today.csv");
    assert!(output_guarded(
        specgen().arg("stale").arg("--write-calibration").arg(&rows),
        "stale"
    )
    .status
    .success());
    let merged = tmp.path().join("merged.csv");
    let shipped = root.join("data/delay_calibration.csv");
    let calibrate = |merge: &std::path::Path, out: &std::path::Path| {
        output_guarded(
            specgen()
                .arg("calibrate")
                .arg("--calibration")
                .arg(&shipped)
                .arg("--merge")
                .arg(merge)
                .arg("--keep")
                .arg("--rows-out")
                .arg(out)
                .arg("--out")
                .arg(tmp.path().join("m.json")),
            "calibrate --merge",
        )
    };
    let o = calibrate(&rows, &merged);
    assert!(
        o.status.success() && String::from_utf8_lossy(&o.stdout).contains("0 unit(s) added"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        std::fs::read(&merged).unwrap(),
        std::fs::read(&shipped).unwrap()
    );
    let one = tmp.path().join("one.csv");
    std::fs::write(
        &one,
        "family,model,stages,stage_delay_estimate,stage_delay_mean,fmax_mhz,fmax_seeds,args,rtl_sha256\nice40,lean,2,0,0,61.5,61.5,--n-bits 9,\n",
    )
    .unwrap();
    let o = calibrate(&one, &merged);
    assert!(
        o.status.success() && String::from_utf8_lossy(&o.stdout).contains("1 unit(s) added"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(std::fs::read_to_string(&merged)
        .unwrap()
        .contains("\nice40,lean,2,0,0,61.5,61.5,--n-bits 9,\n"));
    // the merged rows never replace a file the command reads
    let o = calibrate(&one, &one);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `stale --write-calibration` and `calibrate` write their files before they say anything: a
/// reader that stops reading at once (`| head -1`) loses none of them.
#[test]
fn a_reader_that_stops_early_loses_no_file() {
    let tmp = tempfile::tempdir().unwrap();
    let rows = tmp.path().join("rows.csv");
    let mut child = specgen()
        .arg("stale")
        .arg("--write-calibration")
        .arg(&rows)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait().unwrap();
    assert!(std::fs::read_to_string(&rows)
        .unwrap()
        .starts_with("family,model,stages"));
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let (merged, model) = (tmp.path().join("merged.csv"), tmp.path().join("model.json"));
    let mut child = specgen()
        .arg("calibrate")
        .arg("--calibration")
        .arg(root.join("data/delay_calibration.csv"))
        .arg("--merge")
        .arg(&rows)
        .arg("--keep")
        .arg("--rows-out")
        .arg(&merged)
        .arg("--out")
        .arg(&model)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait().unwrap();
    assert!(merged.exists() && model.exists());
}
