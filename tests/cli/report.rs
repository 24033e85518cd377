//! `romdyn rom … --report DIR` (issue 37 point 6): the page and its plot are written as one
//! set with the other outputs, the kept modes' shapes are the eigenvectors at the nodes, and
//! a file given for the folder is refused before any work. (The page in a browser:
//! scripts/check_report.sh, run by .ci/run in headless Chromium.)

use crate::common::cli::{romdyn_at, temp_dir};

#[test]
fn the_report_holds_the_kept_modes_on_the_model_s_geometry() {
    let dir = temp_dir("rom-report");
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/simply_supported_beam.mbd");
    let (ok, _, err) = romdyn_at(&dir, &["rom", model, "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "-o", "rom.json", "--report", "report"]);
    assert!(ok, "{err}");
    assert!(err.contains("wrote report/index.html (open it in a browser)"), "{err}");
    for f in ["index.html", "bode.csv", "bode.svg", "bode.png"] {
        assert!(dir.join("report").join(f).metadata().map(|m| m.len() > 0).unwrap_or(false), "{f}");
    }
    let page = std::fs::read_to_string(dir.join("report/index.html")).unwrap();
    let data = page.split("id=\"romdyn-geometry\">").nth(1).and_then(|s| s.split("</script>").next()).expect("the geometry");
    let data: serde_json::Value = serde_json::from_str(data).unwrap();
    // 9 nodes, 4 beam3 elements of two segments each; the ROM keeps mode 1 (49.3265 Hz,
    // romdyn eig on the same file), whose shape is largest at mid-span (node 5) in y.
    assert_eq!(data["nodes"].as_array().unwrap().len(), 9);
    assert_eq!(data["edges"].as_array().unwrap().len(), 8);
    assert_eq!(data["modes"][0]["label"], "mode 1: 49.3265 Hz");
    let labels: Vec<u64> = data["labels"].as_array().unwrap().iter().map(|l| l.as_u64().unwrap()).collect();
    let mid = labels.iter().position(|&l| l == 5).unwrap();
    let y = |n: usize| data["modes"][0]["shape_re"][n][1].as_f64().unwrap().hypot(data["modes"][0]["shape_im"][n][1].as_f64().unwrap());
    assert!((y(mid) - 1.0).abs() < 1e-12, "mid-span |y| {} (scaled to 1)", y(mid));
    // The summary and the warnings are the ones printed.
    assert!(page.contains("ROM: 2 states from 1 kept mode(s)"), "{page}");
}

#[test]
fn a_file_for_the_report_folder_is_refused_before_any_work() {
    let dir = temp_dir("rom-report-file");
    std::fs::write(dir.join("taken"), "x").unwrap();
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/simply_supported_beam.mbd");
    let (ok, _, err) = romdyn_at(&dir, &["rom", model, "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--report", "taken"]);
    assert!(!ok && err.contains("--report: taken is a file"), "{err}");
}

/// With an imposed motion the report carries the transmissibility (issue 37 point 6:
/// "Bode/transmissibility … plots"): the same values as `--transmissibility` writes.
#[test]
fn the_report_of_an_imposed_motion_carries_the_transmissibility() {
    let dir = temp_dir("rom-report-isolator");
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/mbdyn_files/isolator_imposed.mbd");
    let (ok, _, err) = romdyn_at(&dir, &["rom", model, "--input", "3:Fx", "--output", "3:x", "--imposed", "2:x", "--band", "0:30", "--transmissibility", "t", "--report", "report"]);
    assert!(ok, "{err}");
    let page = std::fs::read_to_string(dir.join("report/index.html")).unwrap();
    assert!(page.contains("<img src=\"transmissibility.svg\""), "{page}");
    for f in ["transmissibility.csv", "transmissibility.svg", "transmissibility.png"] {
        assert!(dir.join("report").join(f).metadata().map(|m| m.len() > 0).unwrap_or(false), "{f}");
    }
    assert_eq!(std::fs::read_to_string(dir.join("report/transmissibility.csv")).unwrap(), std::fs::read_to_string(dir.join("t.csv")).unwrap());
    // Without an imposed motion, no such section (the first test's beam).
    let (ok, _, err) = romdyn_at(&dir, &["rom", model, "--input", "3:Fx", "--output", "3:x", "--band", "0:30", "--report", "plain"]);
    assert!(ok, "{err}");
    assert!(!std::fs::read_to_string(dir.join("plain/index.html")).unwrap().contains("transmissibility.svg"));
}
