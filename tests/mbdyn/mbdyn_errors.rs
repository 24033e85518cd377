//! Malformed MBDyn inputs: each gives its own message at the right file, line and column
//! (and never a panic).

use std::path::Path;

use romdyn::input::mbdyn::{build, parse_text};

/// The first line of the error ("file:line:column: error: message"), or "accepted".
fn error_of(text: &str) -> String {
    match parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => "accepted".into(),
        Err(e) => e.to_string().lines().next().unwrap_or("").to_string(),
    }
}

const HEAD: &str = "begin: data; problem: initial value; end: data;\n";

/// A file whose line 4 is `nodes` (inside the nodes block) and line 6 is `elements`.
fn model(control: &str, nodes: &str, elements: &str) -> String {
    format!("{HEAD}begin: control data; {control} end: control data;\nbegin: nodes;\n{nodes}\nend: nodes; begin: elements;\n{elements}\nend: elements;\n")
}

const NODES: &str = "structural: 1, static, null, eye, null, null; structural: 2, dynamic, 0., -1., 0., eye, null, null;";

fn check(cases: &[(String, &str)]) {
    let mut failures = Vec::new();
    for (text, want) in cases {
        let got = error_of(text);
        if !got.starts_with(want) {
            failures.push(format!("input:\n{text}\n  got:  {got}\n  want: {want}"));
        }
    }
    assert!(failures.is_empty(), "{} of {} cases:\n{}", failures.len(), cases.len(), failures.join("\n\n"));
}

#[test]
fn lexical_and_statement_errors() {
    let cases: Vec<(String, &str)> = vec![
        // 1. Unterminated comment: reported where it opens.
        ("set: real a = 1.;\n  /* never\nclosed".into(), "m.mbd:2:3: error: unterminated comment: expected '*/'"),
        // 2. Unterminated string.
        ("remark: \"abc;\n".into(), "m.mbd:1:9: error: unterminated string"),
        // 3. A character that is not part of the language.
        ("set: real a = 1. @ 2.;".into(), "m.mbd:1:18: error: unexpected character '@'"),
        // 4. Missing ';' between statements: the next keyword is named.
        (format!("{HEAD}begin: control data;\n  structural nodes: 1\n  rigid bodies: 0;\nend: control data;"), "m.mbd:4:3: error: missing ';' before 'rigid'"),
        // 5. Missing ';' at the end of the file.
        ("begin: data; problem: initial value; end: data".into(), "m.mbd:1:43: error: missing ';' at the end of this statement"),
        // 6. A statement outside of any block.
        ("structural: 1, static, null, eye, null, null;".into(), "m.mbd:1:1: error: statement 'structural' outside of any block"),
        // 7. A block that is never closed.
        (format!("{HEAD}begin: control data;\n structural nodes: 0;"), "m.mbd:2:1: error: block 'control data' is never closed"),
        // 8. 'end' of another block.
        (format!("{HEAD}begin: nodes;\nend: elements;"), "m.mbd:3:6: error: end: elements does not match the open block"),
        // 9. An unknown block.
        (format!("{HEAD}begin: flux capacitor;\nend: flux capacitor;"), "m.mbd:2:1: error: block 'flux capacitor' is not supported by romdyn"),
        // 10. The same block twice.
        (format!("{HEAD}begin: nodes; end: nodes;\nbegin: nodes; end: nodes;"), "m.mbd:3:1: error: block 'nodes' appears twice (first at line 2)"),
        // 11. An integer literal too large for MBDyn's integers.
        ("set: integer n = 99999999999999999999;".into(), "m.mbd:1:18: error: the integer 99999999999999999999 is too large"),
    ];
    check(&cases);
}

#[test]
fn expression_errors() {
    let cases: Vec<(String, &str)> = vec![
        // 12. Undefined variable.
        ("set: real a = 2.*b;".into(), "m.mbd:1:18: error: undefined variable 'b'"),
        // 13. Division by zero, at the operator (integer and real).
        ("set: integer a = 1;\nset: real b = 3./(a - 1);".into(), "m.mbd:2:17: error: division by zero"),
        ("set: integer a = 7 % 0;".into(), "m.mbd:1:20: error: division by zero"),
        // 14. Outside a function's domain.
        ("set: real a = log(-1.);".into(), "m.mbd:1:15: error: log(-1): argument out of domain (x must be positive)"),
        // 15. Wrong number of arguments.
        ("set: real a = atan2(1.);".into(), "m.mbd:1:15: error: 'atan2' takes 2 argument(s), found 1"),
        // 16. Unbalanced parenthesis.
        ("set: real a = (1. + 2.;".into(), "m.mbd:1:15: error: unbalanced parenthesis: expected ')' to close this '('"),
        // 17. A constant cannot be assigned.
        ("set: const real a = 1.;\nset: a = 2.;".into(), "m.mbd:2:6: error: 'a' is a constant and cannot be assigned"),
        // 18. A variable cannot be declared twice (MBDyn: "cannot redefine var").
        ("set: real a = 1.;\nset: real a = 2.;".into(), "m.mbd:2:11: error: variable 'a' is already declared (declared at line 1)"),
        // 19. Assigning an undeclared variable.
        ("set: a = 2.;".into(), "m.mbd:1:6: error: undefined variable 'a': declare it first"),
        // 20. A function name is not a variable name.
        ("set: real sin = 2.;".into(), "m.mbd:1:11: error: 'sin' is a keyword of the math parser and cannot name a variable"),
        // 21. Functions that need a running simulation.
        ("set: real a = random();".into(), "m.mbd:1:15: error: function 'random' is not supported by romdyn"),
        // 22. A plain name where a number is expected.
        (model("structural nodes: 1;", "structural: 1, static, Lx, 0., 0., eye, null, null;", ""), "m.mbd:4:24: error: expected node position [m] (a number), found 'Lx', which is neither a number nor a defined variable"),
    ];
    check(&cases);
}

#[test]
fn include_errors() {
    let dir = std::env::temp_dir().join(format!("romdyn_include_errors_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.mbd"), "set: real a = 1.;\ninclude: \"b.mbd\";\n").unwrap();
    std::fs::write(dir.join("b.mbd"), "# b includes a again\n  include: \"a.mbd\";\n").unwrap();
    // 23. An include loop is reported where the file is included again.
    let got = romdyn::input::mbdyn::read_model(&dir.join("a.mbd")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(got.starts_with(&format!("{}:2:3: error: include loop: \"a.mbd\" is already being read", dir.join("b.mbd").display())), "{got}");
    // 24. A file that does not exist, at its name.
    assert!(error_of("include: \"no such file.mbd\";").starts_with("m.mbd:1:10: error: cannot include"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn reference_and_orientation_errors() {
    let node = |text: &str| model("structural nodes: 1;", text, "");
    let cases: Vec<(String, &str)> = vec![
        // 25. A reference that is not defined.
        (node("structural: 1, static, reference, 99, null, eye, null, null;"), "m.mbd:4:35: error: reference 99 is not defined"),
        // 26. A reference used before it is defined (loops cannot form).
        (format!("{HEAD}reference: 1, reference, 2, null, eye, null, null;\nreference: 2, null, eye, null, null;\nbegin: control data; end: control data;"), "m.mbd:2:26: error: reference 2 is used before its definition (line 3)"),
        // 27. A reference in its own definition.
        (format!("{HEAD}reference: 5, reference, 5, null, eye, null, null;"), "m.mbd:2:26: error: reference 5 is used in its own definition"),
        // 28. A reference label used twice.
        (format!("{HEAD}reference: 5, null, eye, null, null;\nreference: 5, null, eye, null, null;"), "m.mbd:3:12: error: reference 5 is defined twice (first at line 2)"),
        // 29. Parallel vectors in the two-vector form.
        (node("structural: 1, static, null, 1, 1., 0., 0., 2, -2., 0., 0., null, null;"), "m.mbd:4:48: error: node orientation: the two vectors are null or parallel (axes 1 and 2)"),
        // 30. The same axis twice.
        (node("structural: 1, static, null, 3, 0., 0., 1., 3, 1., 0., 0., null, null;"), "m.mbd:4:45: error: node orientation: the two axis indices must differ, both are 3"),
        // 31. An axis index out of range.
        (node("structural: 1, static, null, 4, 0., 0., 1., 1, 1., 0., 0., null, null;"), "m.mbd:4:30: error: node orientation: axis index must be 1, 2 or 3, found 4"),
        // 32. 'null' is not an orientation (MBDyn rejects it too).
        (node("structural: 1, static, null, null, null, null;"), "m.mbd:4:30: error: node orientation: an orientation cannot be 'null'"),
        // 33. A 'matr' that is not a rotation.
        (node("structural: 1, static, null, matr, 1., 0., 0., 0., 2., 0., 0., 0., 1., null, null;"), "m.mbd:4:36: error: node orientation: the 'matr' orientation is not a rotation matrix"),
        // 34. 'reference, node' where there is no node.
        (node("structural: 1, static, reference, node, null, eye, null, null;"), "m.mbd:4:35: error: 'reference, node' has no node here"),
    ];
    check(&cases);
}

#[test]
fn model_errors() {
    let cases: Vec<(String, &str)> = vec![
        // 35. Control data counts are checked against the model.
        (model("structural nodes: 3;", NODES, ""), "m.mbd:2:22: error: control data declares 3 structural nodes, the model has 2"),
        (model("structural nodes: 2; joints: 1;", NODES, "joint: 1, clamp, 1, node, node; joint: 2, clamp, 2, node, node;"), "m.mbd:2:43: error: control data declares 1 joints, the model has 2"),
        // 36. Elements that control data does not declare.
        (model("structural nodes: 2;", NODES, "body: 1, 2, 1., null, eye;"), "m.mbd:6:1: error: the model has 1 rigid bodies, but control data does not declare 'rigid bodies'"),
        // 37. A node label used twice.
        (model("structural nodes: 2;", "structural: 1, static, null, eye, null, null;\nstructural: 1, static, null, eye, null, null;", ""), "m.mbd:5:13: error: structural node 1 is defined twice (first at line 4)"),
        // 38. An element label used twice (forces and couples share labels).
        (model("structural nodes: 2; forces: 2;", NODES, "force: 3, absolute, 2, position, null, 1., 0., 0., 1.;\ncouple: 3, absolute, 2, 0., 0., 1., 1.;"), "m.mbd:7:9: error: force 3 is defined twice (first at line 6)"),
        // 39. A node referenced but not defined.
        (model("structural nodes: 2; rigid bodies: 1;", NODES, "body: 1, 7, 1., null, eye;"), "m.mbd:6:10: error: structural node 7 is not defined"),
        // 40. Unsupported element and joint types are named.
        (model("structural nodes: 2;", NODES, "aerodynamic body: 1, 2;"), "m.mbd:6:1: error: element type 'aerodynamic body' is not supported by romdyn"),
        (model("structural nodes: 2; joints: 1;", NODES, "joint: 1, point contact, 1, 2;"), "m.mbd:6:11: error: joint type 'point contact' is not supported by romdyn"),
        (model("structural nodes: 2; rigid bodies: 1;", NODES, "driven: 1, string, \"Time > 1.\", body: 1, 2, 1., null, eye;"), "m.mbd:6:1: error: driven: romdyn switches joints, forces and beams on and off, not bodies or gravity"),
        // 41. Beams: the two-node beam is not supported; a 3-node beam needs a length, a
        // section orientation before 'same', and a 6-D law.
        (model("structural nodes: 2; beams: 1;", NODES, "hbeam: 5, 1, null, 2, null, linear elastic, 1.;"), "m.mbd:6:1: error: element type 'hbeam' is not supported by romdyn (MBDyn 1.7.3 runs it, but its manual calls it experimental, for development only); use beam2, whose curvature is exact for a uniformly bent element"),
        (model("structural nodes: 2; beams: 1;", NODES, "beam3: 5, 1, null, 1, null, 1, null, eye, linear elastic, 1., same, same;"), "m.mbd:6:1: error: beam 5: the reference line has zero length at evaluation point I"),
        (model("structural nodes: 2; beams: 1;", NODES, "beam3: 5, 1, null, 2, null, 1, null, same, linear elastic, 1.;"), "m.mbd:6:38: error: expected orientation of section I: "),
        (model("structural nodes: 2; beams: 1;", NODES, "constitutive law: 1, 3, linear elastic, 1.;\nbeam3: 5, 1, null, 2, null, 2, 1., 0., 0., eye, reference, 1, same, same;"), "m.mbd:7:49: error: constitutive law 1 has dimension 3, this element needs 6"),
        // 42. Physics romdyn cannot honour is an error, not skipped.
        // (`model: static` turns dynamic nodes static, as MBDyn: tests/mbdyn/mbdyn_syntax.rs.)
        (model("structural nodes: 2; thermal nodes: 1;", NODES, ""), "m.mbd:2:58: error: control data declares thermal nodes, which romdyn does not support"),
        // 43. (A joint that does not hold as written is now assembled: tests/mbdyn/initial_assembly.rs.)
        // 44. A dummy node cannot carry elements.
        (model("structural nodes: 3; rigid bodies: 1;", &format!("{NODES} structural: 3, dummy, 2, offset, null, eye;"), "body: 1, 3, 1., null, eye;"), "m.mbd:6:10: error: structural node 3 is a dummy node"),
        // 45. Negative mass needs 'allow negative mass'.
        (model("structural nodes: 2; rigid bodies: 1;", NODES, "body: 1, 2, -1., null, eye;"), "m.mbd:6:13: error: negative mass -1"),
        // 46. Extra arguments.
        (model("structural nodes: 2; rigid bodies: 1;", NODES, "body: 1, 2, 1., null, eye, 7.;"), "m.mbd:6:28: error: unexpected extra argument the number 7 in 'body'"),
        // 47. A driven total joint with only some rotations locked (its
        // remnant is element history: tests/multibody/mbdyn_joints.rs runs the joint itself).
        (model("structural nodes: 2; joints: 1;", NODES, "driven: 1, const, 1., joint: 1, total joint, 1, 2, position, 0., 1., 0., orientation constraint, active, inactive, inactive, 1., 0., 0., const, .5;"), "m.mbd:6:1: error: driven: a driven total joint with events of its own (a bistop law, a total joint locking some rotation components only) is not supported by romdyn"),
    ];
    check(&cases);
}

#[test]
fn drive_and_law_errors() {
    let force = |drive: &str| model("structural nodes: 2; forces: 1;", NODES, &format!("force: 1, absolute, 2, position, null, 1., 0., 0., {drive};"));
    let cases: Vec<(String, &str)> = vec![
        // 48. Wrong drive arguments: a ramp that ends before it starts.
        (force("ramp, 1., 2., 1., 0."), "m.mbd:6:66: error: ramp: final time 1 is before the initial time 2"),
        // 49. A missing drive argument, at the ';'.
        (force("sine, 0., 1., 1., forever"), "m.mbd:6:77: error: expected initial value (a number), found the end of the statement"),
        // 50. Zero cycles.
        (force("cosine, 0., 1., 1., 0, 0."), "m.mbd:6:72: error: number of cycles must not be zero"),
        // 51. Piecewise linear points out of order.
        (force("piecewise linear, 2, 1., 0., 0.5, 1."), "m.mbd:6:81: error: piecewise linear: the points must increase, 0.5 does not follow 1"),
        // 52. A drive caller romdyn cannot represent.
        (force("ginac, \"t\""), "m.mbd:6:52: error: drive caller 'ginac' is not supported by romdyn"),
        // 53. An undefined drive caller.
        (force("reference, 4"), "m.mbd:6:52: error: drive caller 4 is not defined"),
        // 54. (Different drives on different components of one force: a sum since issue 12's
        // state drives, tests/mbdyn/mbdyn_state_drives.rs.)
        // 55. Time-varying gravity with different drives on its components.
        (model("structural nodes: 2; gravity;", NODES, "gravity: component, const, 1., ramp, 1., 0., 1., 0., inactive;"), "m.mbd:6:10: error: romdyn's time-varying gravity is one direction times one drive"),
        // 55b. Driven elements: hints, a label that is not the wrapped element's, `existing`.
        (model("structural nodes: 2; joints: 1;", NODES, "driven: 1, const, 1., hint, \"drive{1.}\", joint: 1, spherical hinge, 1, null, 2, null;"), "m.mbd:6:29: error: driven: hint 1 does not apply to a spherical hinge in romdyn"),
        (model("structural nodes: 2; joints: 1;", NODES, "driven: 1, const, 1., hint, \"offset{1}\", joint: 1, spherical hinge, 1, null, 2, null;"), "m.mbd:6:29: error: driven: hint \"offset{1}\" is not supported by romdyn"),
        (model("structural nodes: 2; joints: 1;", NODES, "driven: 2, const, 1., joint: 1, spherical hinge, 1, null, 2, null;"), "m.mbd:6:9: error: driven element 2 wraps spherical hinge 1: the labels must match"),
        (model("structural nodes: 2; joints: 1;", NODES, "joint: 1, spherical hinge, 1, null, 2, null; driven: 1, const, 1., existing: joint, 1;"), "m.mbd:6:68: error: driven: wrapping an 'existing' element is not supported by romdyn"),
        // 56. A constitutive law romdyn does not have, and one of the wrong dimension.
        (model("structural nodes: 2; joints: 1;", NODES, "joint: 1, deformable hinge, 1, 2, cubic elastic generic, 1., 2., 3.;"), "m.mbd:6:35: error: constitutive law 'cubic elastic generic' is not supported by romdyn"),
        (model("structural nodes: 2; joints: 1;", NODES, "constitutive law: 3, 1, linear elastic, 1.;\njoint: 1, deformable hinge, 1, 2, reference, 3;"), "m.mbd:7:35: error: constitutive law 3 has dimension 1, this element needs 3"),
        // A 6-D law (for beams) is read in full, 21 values of 'sym' or 6 of 'diag'.
        (model("structural nodes: 2; joints: 1;", NODES, &format!("constitutive law: 3, 6, linear viscoelastic generic, sym, {}, diag, 1., 1., 1., 1., 1., 1.;\njoint: 1, deformable hinge, 1, 2, reference, 3;", vec!["1."; 21].join(", "))), "m.mbd:7:35: error: constitutive law 3 has dimension 6, this element needs 3"),
        (model("structural nodes: 2;", NODES, "constitutive law: 3, 6, linear elastic generic, diag, 1., 1., 1., 1., 1.;"), "m.mbd:6:73: error: expected stiffness (a number), found the end of the statement"),
    ];
    check(&cases);
}

#[test]
fn problem_errors() {
    let iv = |s: &str| format!("{HEAD}begin: initial value;\n  {s}\nend: initial value;");
    let cases: Vec<(String, &str)> = vec![
        // 57. An unknown statement of the initial value block.
        (iv("frobnicate: 1;"), "m.mbd:3:3: error: statement 'frobnicate' in the initial value block is not supported by romdyn"),
        // 58. An integration method romdyn does not have.
        (iv("method: hope, .6;"), "m.mbd:3:11: error: integration method 'hope' is not supported by romdyn"),
        // 58b. Methods of later MBDyn versions that MBDyn 1.7.3 does not know ("Unknown
        // integration method") and romdyn does not have (`Bathe` and `hybrid` it has), and the
        // hybrid method with a default romdyn does not have.
        (iv("method: msstc3, .6;"), "m.mbd:3:11: error: integration method 'msstc3' is not known to MBDyn 1.7.3"),
        (iv("method: hybrid, hope, .6;"), "m.mbd:3:19: error: integration method 'hope' (the hybrid method's default) is not supported by romdyn"),
        (iv("method: hybrid, bdf;"), "m.mbd:3:19: error: expected the hybrid method's default method (implicit euler, crank nicolson, crank nicholson, ms, ms2, hope)"),
        (iv("method: bathe, 1.5;"), "m.mbd:3:18: error: the asymptotic spectral radius must be between 0 and 1, found 1.5"),
        // 59. A spectral radius out of range.
        (iv("method: ms, 1.5;"), "m.mbd:3:15: error: the asymptotic spectral radius must be between 0 and 1, found 1.5"),
        // 60. Eigenanalysis times out of order, and an unknown option.
        (iv("eigenanalysis: list, 2, 1., 0.5;"), "m.mbd:3:31: error: eigenanalysis times must increase"),
        (iv("eigenanalysis: 0., output everything;"), "m.mbd:3:22: error: expected an eigenanalysis option"),
        // 61. Another problem.
        ("begin: data; problem: inverse dynamics; end: data;".into(), "m.mbd:1:23: error: problem 'inverse dynamics' is not supported by romdyn"),
    ];
    check(&cases);
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    // 90 levels read (on a test thread's small stack), 150 are refused.
    let nested = |n: usize| format!("set: real a = {}1.{};", "(".repeat(n), ")".repeat(n));
    assert_eq!(error_of(&(nested(90) + HEAD)), "accepted");
    assert!(error_of(&nested(150)).starts_with("m.mbd:1:"), "{}", error_of(&nested(150)));
    assert!(error_of(&nested(150)).contains("nested more than 100 levels deep"));
    let unary = format!("set: real a = {}1.;", "- ".repeat(150));
    assert!(error_of(&unary).contains("nested more than 100 levels deep"));
    let arrays = model("structural nodes: 2; forces: 1;", NODES, &format!("force: 1, absolute, 2, position, null, {}1., 0., 0., const, 1.;", "array, 1, ".repeat(20)));
    assert!(error_of(&arrays).contains("nested in 'array' more than 8 deep"), "{}", error_of(&arrays));
}

#[test]
fn the_caret_lines_up_under_tabs() {
    let e = parse_text("begin: data;\n\tproblem: initial value\n\tfoo: 1;\nend: data;", Path::new("m.mbd")).err().unwrap();
    // Line 3 starts with a tab: the caret line keeps it, then one space per character.
    assert_eq!(e.to_string(), "m.mbd:3:2: error: missing ';' before 'foo'\n  |\n3 | \tfoo: 1;\n  | \t^");
}

/// Columns count characters, not bytes, after multi-byte UTF-8 text (the reader keeps the
/// text as UTF-8 with a byte cursor): the error on line 2 is at character 19.
#[test]
fn columns_count_characters_after_non_ascii_text() {
    let text = "# µ-strain at 30° (température)\nset: real x = 1.; ° \n";
    assert_eq!(error_of(text), "m.mbd:2:19: error: unexpected character '\\u{b0}'");
    // And within a line: "é" in a string is one character.
    let text = "set: string s = \"é\"; ° \n";
    assert_eq!(error_of(text), "m.mbd:1:22: error: unexpected character '\\u{b0}'");
}
