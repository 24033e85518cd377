//! The Octave script reader on the forms MBDyn writes, and its diagnostics.

use std::path::Path;

use romdyn::input::octave_m::{parse_octave_script, OctaveMatrix, OctaveScript, Position};

fn parse(text: &str) -> Result<OctaveScript, String> {
    parse_octave_script(text, Path::new("e.m")).map_err(|e| e.to_string())
}

#[test]
fn full_sparse_and_complex_matrices_as_mbdyn_writes_them() {
    let s = parse(
        "% coefficient\ndCoef = 5.0e-01;\nAplus = [1 2.5e0 ;\n-3 4 ];\n\
         Aminus = [\n1 1 2;\n2 2 -1e-3;\n3 3 0;\n];\nAminus = spconvert(Aminus);\n\
         VR = [\n1.0e0+i*2.0e0 1.0e0-i*2.0e0 NaN ;\n-Inf 0 3];\nz = zeros(2, 0);\n",
    )
    .unwrap();
    assert_eq!(s.get("dCoef").and_then(OctaveMatrix::scalar), Some(0.5));
    let a = s.get("Aplus").unwrap();
    assert_eq!((a.rows, a.cols, a.re.clone()), (2, 2, vec![1.0, 2.5, -3.0, 4.0]));
    // spconvert: size from the largest index (the explicit "3 3 0" entry), duplicates add.
    let m = s.get("Aminus").unwrap();
    assert_eq!((m.rows, m.cols, m.from_sparse), (3, 3, true));
    assert_eq!((m.get(0, 0), m.get(1, 1), m.get(2, 2), m.get(0, 1)), (2.0, -1e-3, 0.0, 0.0));
    let v = s.get("VR").unwrap();
    assert_eq!((v.rows, v.cols), (2, 3));
    assert_eq!(v.im.as_ref().unwrap()[..2], [2.0, -2.0]);
    assert!(v.re[2].is_nan() && v.re[3] == f64::NEG_INFINITY);
    assert_eq!((s.get("z").unwrap().rows, s.get("z").unwrap().cols), (2, 0));
    // The last assignment counts: the spconvert line.
    assert_eq!(s.position("Aminus"), Some(Position { line: 10, column: 1 }));
}

#[test]
fn errors_name_line_and_column() {
    assert_eq!(parse("a = [1 2;\n3];").unwrap_err(), "e.m:2:1: this row has 1 entries, the first row has 2");
    assert_eq!(parse("a = [1 2x];").unwrap_err(), "e.m:1:9: expected a blank, ',', ';' or ']' after a number, found 'x'");
    assert_eq!(parse("dCoef 0.5;").unwrap_err(), "e.m:1:7: expected '=' after 'dCoef', found '0'");
    assert_eq!(parse("a = [1 2").unwrap_err(), "e.m:1:5: this '[' is never closed");
    assert_eq!(parse("a = eig(b);").unwrap_err(), "e.m:1:5: function 'eig' is not supported (romdyn reads numbers, [matrices], spconvert and zeros)");
    assert_eq!(parse("a = spconvert(b);").unwrap_err(), "e.m:1:15: 'b' is not defined before this line");
    assert_eq!(parse("a = 1 2;").unwrap_err(), "e.m:1:7: expected the end of the statement, found '2'");
}

#[test]
fn a_pencil_file_without_matrices_says_how_to_get_them() {
    let dir = std::env::temp_dir().join(format!("romdyn-octave-script-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("eig.m");
    std::fs::write(&file, "dTime = 0;\ndCoef = 0.5;\nalpha = [1 0 1;];\n").unwrap();
    let ports = romdyn::input::eigen_pencil::PencilPorts::default();
    let err = romdyn::input::pencil::read_pencil_file(&file, &ports).unwrap_err().to_string();
    assert!(err.ends_with("eig.m: 'Aplus' is missing; write the eigenanalysis with 'output matrices' (MBDyn) or 'output full matrices'"), "{err}");
    std::fs::write(&file, "dCoef = -1;\nAplus = [1];\nAminus = [1];\n").unwrap();
    let err = romdyn::input::pencil::read_pencil_file(&file, &ports).unwrap_err().to_string();
    assert!(err.ends_with("eig.m:1:1: 'dCoef' must be a positive normal number (s), found -1"), "{err}");
    std::fs::write(&file, "dCoef = 1;\nAplus = [1 2];\nAminus = [1];\n").unwrap();
    let err = romdyn::input::pencil::read_pencil_file(&file, &ports).unwrap_err().to_string();
    assert!(err.ends_with("eig.m:2:1: 'Aplus' is 1x2, expected 2x2 (square, the size of the other matrix)"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
