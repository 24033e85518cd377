//! Pencil files: accepted forms and the error for each malformed input.

use std::path::Path;

use romdyn::input::pencil::{parse_pencil, PencilError};
use romdyn::linear::Jacobians;

fn parse(text: &str) -> Result<romdyn::input::pencil::PencilFile, PencilError> {
    parse_pencil(text, Path::new("test.json"))
}

fn err(text: &str) -> String {
    parse(text).err().map(|e| e.to_string()).unwrap_or_else(|| "accepted".into())
}

const OK: &str = r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]}"#;

#[test]
fn derivative_form_is_read_with_default_names() {
    let p = parse(OK).unwrap();
    assert!(matches!(p.dae.jacobians, Jacobians::Derivatives { .. }));
    assert_eq!(p.dae.dim(), 2);
    assert_eq!(p.dae.input_names, ["u1"]);
    assert_eq!(p.dae.output_names, ["z1"]);
    assert_eq!(p.dcoef, None);
}

#[test]
fn coefficient_form_needs_dcoef() {
    let t = r#"{"J": [[1,0],[0,1]], "Jstar": [[1,0],[0,1]], "B": [[0],[1]], "C": [[1,0]], "dcoef": 0.01}"#;
    let p = parse(t).unwrap();
    assert!(matches!(p.dae.jacobians, Jacobians::Coefficient { dcoef, .. } if dcoef == 0.01));
    let t = r#"{"J": [[1,0],[0,1]], "Jstar": [[1,0],[0,1]], "B": [[0],[1]], "C": [[1,0]]}"#;
    assert_eq!(err(t), "test.json: field \"dcoef\": missing (required with J and Jstar)");
}

#[test]
fn malformed_files_name_the_field_and_what_was_expected() {
    let cases: &[(&str, &str)] = &[
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]"#, "test.json:1:"),
        (r#"[1, 2]"#, "expected a JSON object at the top level"),
        (r#"{"Fyd": [[1,0],[0,1]], "B": [[0],[1]], "C": [[1,0]]}"#, "expected either \"Fyd\" and \"Fy\""),
        (r#"{"Fyd": [[1,0],[0]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]}"#, "field \"Fyd\": row 2 has 1 entries, row 1 has 2"),
        (r#"{"Fyd": [[1,"a"],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]}"#, "field \"Fyd\": row 1, column 2: expected a number, found a string"),
        (r#"{"Fyd": 3, "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]}"#, "field \"Fyd\": expected an array of rows of numbers, found a number"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1,0],[1,0,0]], "B": [[0],[1]], "C": [[1,0]]}"#, "both must be square and of the same size"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0]], "C": [[1,0]]}"#, "field \"B\": has 1 rows, expected 2"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1]]}"#, "field \"C\": has 1 columns, expected 2"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "C": [[1,0]]}"#, "field \"B\": missing"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]], "input_names": ["a", "b"]}"#, "field \"input_names\": expected 1 names, found 2"),
        (r#"{"Fyd": [[1,0],[0,1]], "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]], "dcoef": -1}"#, "field \"dcoef\": expected a positive number"),
        (r#"{"Fyd": {"mtx": "a"}, "Fy": [[0,-1],[1,0]], "B": [[0],[1]], "C": [[1,0]]}"#, "field \"Fyd\": expected an array of rows, a path string"),
    ];
    for (text, want) in cases {
        let got = err(text);
        assert!(got.contains(want), "input {text}\n  got:  {got}\n  want: {want}");
    }
}

#[test]
fn json_syntax_error_reports_line_and_column() {
    let text = "{\n  \"Fyd\": [[1, 0],\n   [0, 1]],,\n}";
    let e = err(text);
    assert!(e.starts_with("test.json:3:12: invalid JSON"), "{e}");
}

#[test]
fn matrix_market_reference_is_resolved_relative_to_the_file() {
    let dir = std::env::temp_dir().join(format!("romdyn-pencil-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("fy.mtx"), "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 2 -1\n2 1 1\n").unwrap();
    let text = r#"{"Fyd": [[1,0],[0,1]], "Fy": "fy.mtx", "B": [[0],[1]], "C": [[1,0]]}"#;
    let p = parse_pencil(text, &dir.join("p.json")).unwrap();
    let (_, fy) = p.dae.jacobians.derivatives();
    assert_eq!((fy[(0, 1)], fy[(1, 0)], fy[(0, 0)]), (-1.0, 1.0, 0.0));
    let missing = r#"{"Fyd": [[1,0],[0,1]], "Fy": {"matrix_market": "nope.mtx"}, "B": [[0],[1]], "C": [[1,0]]}"#;
    let e = parse_pencil(missing, &dir.join("p.json")).unwrap_err().to_string();
    assert!(e.contains("field \"Fy\"") && e.contains("nope.mtx"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
