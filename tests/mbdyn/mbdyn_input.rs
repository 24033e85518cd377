//! MBDyn input files: the shipped examples and malformed inputs with their diagnostics.

use std::path::Path;

use romdyn::dae::{check_jacobians, linearize, Assembler, State};
use romdyn::input::mbdyn::{build, parse_text, read_model};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::model::ConstraintForm;
use romdyn::model::Summary;
use romdyn::solve::{initial_derivatives, NewtonSettings};

/// ω = sqrt((g/L)/(1 + J/(m L²))) = 3.130527 rad/s (eq. 82, CASES C2).
const OMEGA: f64 = 3.130527;

fn eigenvalues(file: &str) -> Vec<romdyn::c64> {
    let m = read_model(Path::new(file)).unwrap();
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    initial_derivatives(&asm, &mut st, &NewtonSettings::default()).unwrap();
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
    modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic).map(|m| m.lambda).collect()
}

#[test]
fn pendulum_file_has_29_equations_and_eq_82_eigenvalues() {
    let m = read_model(Path::new("examples/pendulum.mbd")).unwrap();
    assert_eq!(Summary::of(&m.model).equations(), 29);
    assert_eq!(m.problem.eigenanalysis.as_ref().map(|e| e.times.clone()), Some(vec![0.0]));
    let ev = eigenvalues("examples/pendulum.mbd");
    assert_eq!(ev.len(), 2);
    // 1e-6 relative (CASES C2; the printed constant has 7 digits).
    assert!(ev.iter().all(|l| l.re.abs() < 1e-9 && (l.im.abs() - OMEGA).abs() / OMEGA < 1e-6), "{ev:?}");
}

#[test]
fn inverted_pendulum_file_has_real_eigenvalues() {
    let ev = eigenvalues("examples/inverted_pendulum.mbd");
    assert_eq!(ev.len(), 2);
    assert!(ev.iter().all(|l| l.im == 0.0 && (l.re.abs() - OMEGA).abs() / OMEGA < 1e-6), "{ev:?}");
}

/// Dynamic eigenvalues of an example, linearized after consistent initial derivatives
/// (as `romdyn eig` does).
fn dynamic_eigenvalues(file: &str) -> (usize, Vec<romdyn::c64>) {
    let m = read_model(Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    initial_derivatives(&asm, &mut st, &NewtonSettings::default()).unwrap();
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
    (Summary::of(&m.model).equations(), modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic).map(|m| m.lambda).collect())
}

#[test]
fn double_pendulum_frequencies_match_the_linearized_lagrangian() {
    let (equations, ev) = dynamic_eigenvalues("examples/double_pendulum.mbd");
    // 6 (ground) + 2 x 12 (bobs) + 6 (clamp) + 5 + 5 (revolute hinges).
    assert_eq!(equations, 46);
    // Independent source: Lagrange's equations of the double pendulum linearized about the
    // hanging position, bobs of mass m with inertia J about their centres, absolute link
    // angles θ1, θ2: M = [[2mL² + J, mL²], [mL², mL² + J]], K = diag(2mgL, mgL);
    // det(K − ω² M) = 0 is a quadratic in ω². For J → 0: ω² = (g/L)(2 ∓ √2).
    let (m, l, j, g) = (1.0f64, 0.5f64, 1e-6f64, 9.81f64);
    let a = (2.0 * m * l * l + j) * (m * l * l + j) - (m * l * l).powi(2);
    let b = -(2.0 * m * g * l * (m * l * l + j) + m * g * l * (2.0 * m * l * l + j));
    let c = 2.0 * (m * g * l).powi(2);
    let disc = (b * b - 4.0 * a * c).sqrt();
    let want = [((-b - disc) / (2.0 * a)).sqrt(), ((-b + disc) / (2.0 * a)).sqrt()];
    assert_eq!(ev.len(), 4, "{ev:?}");
    for w in want {
        // 1e-9 relative: the linearization is exact, the eigensolver's error is ~1e-14.
        assert!(ev.iter().filter(|l| l.re.abs() < 1e-9 && (l.im.abs() - w).abs() < 1e-9 * w).count() == 2, "{w} not in {ev:?}");
    }
    // The point-mass formula holds to the effect of J (J/(mL²) = 4e-6 relative).
    for (w, sign) in want.iter().zip([-1.0, 1.0]) {
        let point_mass = ((g / l) * (2.0 + sign * 2f64.sqrt())).sqrt();
        assert!((w - point_mass).abs() / point_mass < 1e-5, "{w} vs {point_mass}");
    }
}

#[test]
fn masses_on_springs_oscillate_at_the_closed_form_frequencies() {
    let (equations, ev) = dynamic_eigenvalues("examples/mass_on_springs.mbd");
    // 6 + 2 x 12 node equations, clamp 6, two total joints with 3 rotations each.
    assert_eq!(equations, 42);
    assert_eq!(ev.len(), 12, "{ev:?}");
    // Independent source: m x'' + c x' + k x = 0 per direction,
    // λ = −c/(2m) ± j sqrt(k/m − (c/(2m))²); undamped λ = ± j sqrt(k/m).
    let m = 2.0f64;
    for (k, c) in [(100.0f64, 1.0f64), (400.0, 2.0), (900.0, 3.0)] {
        for damping in [0.0, c] {
            let want = romdyn::c64::new(-damping / (2.0 * m), (k / m - (damping / (2.0 * m)).powi(2)).sqrt());
            // 1e-9 relative (exact linear system; eigensolver error ~1e-13).
            let hits = ev.iter().filter(|l| (romdyn::c64::new(l.re, l.im.abs()) - want).norm() < 1e-9 * want.norm()).count();
            assert_eq!(hits, 2, "k = {k}, c = {damping}: {want} not twice in {ev:?}");
        }
    }
}

#[test]
fn spatial_mechanism_reads_assembles_and_has_exact_jacobians() {
    let m = read_model(Path::new("examples/spatial_mechanism.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let s = Summary::of(&m.model);
    // Hand count: 6 (static ground) + 4 x 12 (dynamic nodes) = 54 node equations;
    // clamp 6 + revolute hinge 5 + spherical hinge 3 + total joint 5 + total pin joint 5 = 24.
    assert_eq!((s.node_equations, s.constraint_equations), (54, 24));
    for kind in ["clamp", "revolute hinge", "spherical hinge", "total joint", "deformable displacement joint", "deformable hinge", "rod", "body", "absolute force", "follower force", "absolute couple", "follower couple", "gravity"] {
        assert!(s.elements.contains_key(kind), "no {kind} in {:?}", s.elements);
    }
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    let settings = NewtonSettings { tolerance: 1e-10, ..Default::default() };
    initial_derivatives(&asm, &mut st, &settings).unwrap_or_else(|e| panic!("{e:?}"));
    // Consistent: the residual vanishes at the initial state with the derivatives found.
    let f = asm.residual(&st, m.model.constraint_form, 1e-3);
    let worst = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(worst < 1e-8, "residual {worst}");
    // Every element's Jacobian against central differences of its residual: 1e-6
    // relative to the element's largest entry (the criterion of multibody_jacobians.rs).
    for (dcoef, form) in [(1e-3, ConstraintForm::Scaled), (0.1, ConstraintForm::Plain)] {
        let checks = check_jacobians(&asm, &st, dcoef, form);
        assert_eq!(checks.len(), m.model.elements.len());
        assert!(checks.iter().all(|c| c.relative_error < 1e-6), "{:?}", checks.first());
    }
}

const GOOD: &str = "begin: data; problem: initial value; end: data;
begin: control data; structural nodes: 1; rigid bodies: 1; end: control data;
begin: nodes; structural: 1, dynamic, null, eye, null, null; end: nodes;
begin: elements; body: 1, 1, 2., null, eye; end: elements;
";

fn error_of(text: &str) -> String {
    match parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => "accepted".into(),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_minimal_file_is_accepted() {
    assert_eq!(error_of(GOOD), "accepted");
}

#[test]
fn expressions_and_variables() {
    let text = "set: real a = 2 * (3 + 1) ^ 2 / 4 - -1; set: integer n = 7 / 2; set: real s = sqrt(16) + atan2(0, 1) + cos(pi);
begin: data; problem: initial value; end: data;";
    let d = parse_text(text, Path::new("m.mbd")).unwrap();
    let v = |n: &str| d.variables.real(n).unwrap_or(f64::NAN);
    // 2·16/4 + 1 = 9; integer division truncates 3.5 to 3; 4 + 0 − 1 = 3.
    assert_eq!((v("a"), v("n"), v("s")), (9.0, 3.0, 3.0));
}

#[test]
fn malformed_inputs_give_their_error_at_the_right_place() {
    let cases: &[(&str, &str)] = &[
        ("begin: data; problem: initial value end: data;", "m.mbd:1:37: error: missing ';' before 'end'"),
        ("begin: data; problem: initial value; end: data", "m.mbd:1:43: error: missing ';' at the end"),
        ("begin: data;\n  frobnicate: 1;\nend: data;", "m.mbd:2:3: error: statement 'frobnicate' in the data block is not supported"),
        ("set: real x = 1 / 0;", "m.mbd:1:17: error: division by zero"),
        ("set: real x = y + 1;", "m.mbd:1:15: error: undefined variable 'y'"),
        ("set: real x = sqrt(-1);", "m.mbd:1:15: error: sqrt(-1): argument out of domain"),
        ("set: real x = (1 + 2;", "m.mbd:1:15: error: unbalanced parenthesis"),
        ("set: const real x = 1; set: real x = 2;", "m.mbd:1:34: error: 'x' is a constant"),
        ("/* never closed\nbegin: data;", "m.mbd:1:1: error: unterminated comment"),
        ("include: \"nope.mbd\";", "m.mbd:1:10: error: cannot include"),
        ("begin: data; problem: initial value; end: nodes;", "m.mbd:1:43: error: end: nodes does not match"),
        ("end: data;", "m.mbd:1:1: error: end: data without a matching"),
        ("problem: initial value;", "m.mbd:1:1: error: statement 'problem' outside of any block"),
        ("begin: data; problem: initial value; end: data; begin: flux; end: flux;", "m.mbd:1:49: error: block 'flux' is not supported"),
        ("set: real x = 1 $ 2;", "m.mbd:1:17: error: unexpected character '$'"),
        ("set: real x = \"abc;", "m.mbd:1:15: error: unterminated string"),
    ];
    for (text, want) in cases {
        let got = error_of(text);
        assert!(got.starts_with(want), "input {text:?}\n  got:  {got}\n  want: {want}");
    }
}

#[test]
fn model_level_errors_name_the_statement() {
    let with = |from: &str, to: &str| GOOD.replace(from, to);
    let cases: Vec<(String, &str)> = vec![
        (with("rigid bodies: 1", "rigid bodies: 2"), "control data declares 2 rigid bodies, the model has 1"),
        (with("body: 1, 1, 2., null, eye;", "body: 1, 3, 2., null, eye;"), "structural node 3 is not defined"),
        (with("body: 1, 1, 2., null, eye;", "body: 1, 1, 2., null, eye; body: 1, 1, 2., null, eye;").replace("rigid bodies: 1", "rigid bodies: 2"), "body 1 is defined twice"),
        (with("body: 1, 1, 2., null, eye;", "aerodynamic body: 1, 1;"), "element type 'aerodynamic body' is not supported by romdyn"),
        (with("body: 1, 1, 2., null, eye;", "body: 1, 1, 2., null, eye; joint: 2, point contact, 1;"), "joint type 'point contact' is not supported by romdyn"),
        (with("dynamic", "flying"), "expected the node type (static, dynamic, dummy, modal, static displacement, dynamic displacement), found 'flying'"),
        (with("null, eye, null, null", "null, euler123, 1, 2, null, null"), "expected node orientation: angle about z [rad] (a number), found 'null'"),
        (with("null, eye, null, null", "null, 1, 1., 0., 0., 2, 2., 0., 0., null, null"), "the two vectors are null or parallel"),
        (with("body: 1, 1, 2., null, eye;", "body: 1, 1, 2., null, eye, 7;"), "unexpected extra argument the number 7"),
        (with("structural: 1,", "structural: -1,"), "expected node label (a non-negative integer label), found -1"),
    ];
    for (text, want) in &cases {
        let got = error_of(text);
        assert!(got.contains(want), "got:  {got}\nwant: {want}");
        assert!(got.starts_with("m.mbd:"), "{got}");
    }
}

#[test]
fn errors_show_the_line_with_a_caret() {
    let got = error_of("set: real x = 1;\nset: real y = x / 0;");
    assert_eq!(got, "m.mbd:2:17: error: division by zero\n  |\n2 | set: real y = x / 0;\n  |                 ^");
}

#[test]
fn random_mutations_never_panic() {
    // Deterministic byte-level mutations of a valid file (a bounded fuzz run).
    let base = std::fs::read_to_string("examples/pendulum.mbd").unwrap();
    let bytes = base.as_bytes();
    let mut s: u64 = 0x9E3779B97F4A7C15;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    let alphabet = b" \n,;:()+-*/^#\"=abcdeflnrstuvxyz0123456789._";
    for _ in 0..3000 {
        let mut m = bytes.to_vec();
        for _ in 0..(1 + next() % 4) {
            let i = (next() % m.len() as u64) as usize;
            match next() % 3 {
                0 => m[i] = alphabet[(next() % alphabet.len() as u64) as usize],
                1 => {
                    m.remove(i);
                }
                _ => m.insert(i, alphabet[(next() % alphabet.len() as u64) as usize]),
            }
        }
        let text = String::from_utf8_lossy(&m);
        let _ = parse_text(&text, Path::new("fuzz.mbd")).and_then(|d| build(&d));
    }
}

/// A file in the style of MBDyn's own examples: no data block, labels from `set:`
/// constants (one of them 0), label expressions, references named by variables, tabs,
/// total joints written with 'reference, node' everywhere.
const MBDYN_STYLE: &str = "begin: initial value;
\tinitial time: 0.;
\tfinal time: 1.;
\ttime step: 1e-3;
\ttolerance: 1.e-6;
\tmax iterations: 10;
\tthreads: disable;
end: initial value;

begin: control data;
\tstructural nodes: 2;
\trigid bodies: 1;
\tjoints: 3;
end: control data;

set: const integer BASE = 0;
set: const integer SLIDER = 10;
set: const real M = 2.;
set: const real L = 0.3;
set: const real EA = M*(5*2*pi)^2*L;   # axial stiffness EA/L: 5 Hz on purpose

reference: BASE, reference, global, null, reference, global, eye, reference, global, null, reference, global, null;
reference: SLIDER, reference, BASE, L, 0., 0., reference, BASE, eye, reference, BASE, null, reference, BASE, null;

begin: nodes;
\tstructural: BASE, static, reference, BASE, null, reference, BASE, eye, reference, BASE, null, reference, BASE, null;
\tstructural: SLIDER, dynamic, reference, SLIDER, null, reference, SLIDER, eye, reference, SLIDER, null, reference, SLIDER, null;
end: nodes;

begin: elements;
\tbody: SLIDER, SLIDER, M, null, null;   # no inertia: the rotations are locked
\tjoint: BASE, total pin joint,
\t\tBASE,
\t\t\tposition, reference, node, null,
\t\t\tposition orientation, reference, node, eye,
\t\t\trotation orientation, reference, node, eye,
\t\t\tposition, reference, node, null,
\t\t\tposition orientation, reference, node, eye,
\t\t\trotation orientation, reference, node, eye,
\t\tposition constraint, 1, 1, 1, null,
\t\torientation constraint, 1, 1, 1, null;
\tjoint: SLIDER, total joint,
\t\tBASE, position, reference, node, null, position orientation, reference, node, eye, rotation orientation, reference, node, eye,
\t\tSLIDER, position, reference, node, null, position orientation, reference, node, eye, rotation orientation, reference, node, eye,
\t\tposition constraint, 0, 1, 1, null,
\t\torientation constraint, 1, 1, 1, null;
\tjoint: SLIDER + 1, rod,
\t\tBASE, position, reference, node, null,
\t\tSLIDER, position, reference, node, null,
\t\tL,
\t\t\tlinear elastic, EA;
end: elements;
";

#[test]
fn a_file_in_mbdyn_style_gives_its_designed_frequency() {
    let m = parse_text(MBDYN_STYLE, Path::new("style.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    initial_derivatives(&asm, &mut st, &NewtonSettings::default()).unwrap();
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
    let ev: Vec<_> = modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic).map(|m| m.lambda).collect();
    // The slider moves along x on the rod only, whose stiffness is EA/L (manual, §Rod:
    // F = EA (l − l₀)/l₀): ω = sqrt(EA/(L M)) = 2π · 5 rad/s by the file's construction
    // EA = M (2π 5)² L; 1e-9 relative.
    let w = 2.0 * std::f64::consts::PI * 5.0;
    assert_eq!(ev.len(), 2, "{ev:?}");
    assert!(ev.iter().all(|l| l.re.abs() < 1e-6 && (l.im.abs() - w).abs() < 1e-9 * w), "{ev:?}");
}
