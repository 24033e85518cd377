//! Reading MBDyn text in tests, and comparing a file's model with one built through the API.

use std::path::Path;

use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::Element;
use romdyn::model::ModelBuilder;
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::model::ConstraintForm;
use romdyn::model::Model;

use super::fixtures::Noise;

pub fn read(text: &str) -> MbdynModel {
    parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

pub fn variables(text: &str) -> romdyn::input::mbdyn::Variables {
    parse_text(text, Path::new("m.mbd")).unwrap_or_else(|e| panic!("{e}")).variables
}

/// A file with the given control data, nodes and elements.
pub fn file(control: &str, nodes: &str, elements: &str) -> String {
    format!("begin: data; problem: initial value; end: data;\nbegin: control data; {control} end: control data;\nbegin: nodes;\n{nodes}\nend: nodes;\nbegin: elements;\n{elements}\nend: elements;\n")
}

/// `F(y, ẏ, t)` at the initial state moved by noise (same layout for equal models).
pub fn residual(model: &Model, t: f64, seed: u64) -> Vec<f64> {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    st.t = t;
    let mut n = Noise(seed);
    st.y.iter_mut().chain(st.yp.iter_mut()).for_each(|v| *v += 0.1 * n.next());
    asm.residual(&st, ConstraintForm::Plain, 1.0)
}

/// The model read from `text` has the residual of `expected` (same nodes and elements in the
/// same order) at three states and times, to 1e-12 relative.
pub fn assert_same_physics(text: &str, expected: Model) {
    let got = read(text).model;
    assert_eq!(got.nodes.len(), expected.nodes.len(), "node count");
    assert_eq!(got.elements.len(), expected.elements.len(), "element count");
    for (seed, t) in [(7, 0.0), (11, 0.37), (13, 2.5)] {
        let (a, b) = (residual(&got, t, seed), residual(&expected, t, seed));
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            assert!((x - y).abs() <= 1e-12 * scale, "t = {t}, equation {i}: read {x}, expected {y}");
        }
    }
}


/// A file of `tests/mbdyn_files/`.
pub fn test_file(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files").join(name)
}

/// Each changed text of the file `name` of `tests/mbdyn_files/` (`original` its text) is
/// refused with a message that holds `expected` and names the file (`name:line:col`).
pub fn assert_refused(name: &str, original: &str, cases: &[(String, &str)]) {
    for (changed, expected) in cases {
        assert_ne!(changed, original, "{expected}: the change did not apply");
        let err = parse_text(changed, &test_file(name)).and_then(|d| build(&d)).err().unwrap_or_else(|| panic!("accepted, expected {expected}"));
        let message = err.to_string();
        assert!(message.contains(expected), "{message}");
        assert!(message.contains(&format!("{name}:")), "no file:line:col in {message}");
    }
}

/// The model of a file of `tests/mbdyn_files/` with each `(old, new)` of its text replaced
/// (every `old` must occur).
pub fn rewritten_test_file(name: &str, replacements: &[(&str, &str)]) -> MbdynModel {
    let mut t = std::fs::read_to_string(test_file(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    for (old, new) in replacements {
        assert!(t.contains(old), "{name} does not contain {old:?}");
        t = t.replace(old, new);
    }
    parse_text(&t, &test_file(name)).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

/// The model of a file of `tests/mbdyn_files/`.
pub fn read_test_file(name: &str) -> MbdynModel {
    romdyn::input::mbdyn::read_model(&test_file(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs `m` up to `final_time` (the file's own when `None`) and checks every element's
/// Jacobian at the last state against central differences of its residual
/// (`dae::check_jacobians` with the coefficient `dcoef`), each within 1e-7 (central
/// differences on the library's elements: about 1e-9, `analysis::check`). Returns the
/// checks for the caller's own assertions (which element, drives held).
pub fn assert_jacobians_after_run(m: &mut MbdynModel, final_time: Option<f64>, dcoef: f64) -> Vec<romdyn::dae::JacobianMismatch> {
    if let Some(t) = final_time {
        m.problem.final_time = t;
    }
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let checks = romdyn::dae::check_jacobians(&asm, &report.final_state, dcoef, m.model.constraint_form);
    for c in &checks {
        assert!(c.within(1e-7), "{c:?}");
    }
    checks
}

/// Linearizing `m` at its initial state is refused with an error containing every one of
/// `needles`; `why` says what a linearization would get wrong.
pub fn assert_not_linearized(m: &MbdynModel, needles: &[&str], why: &str) {
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    let e = match romdyn::dae::linearize(&m.model, &st, &[], &[], None) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{why}"),
    };
    for n in needles {
        assert!(e.contains(n), "{n:?} not in: {e}");
    }
}

/// Nodes 1 (static), 2 and 3 (dynamic) at random positions, orientations and velocities,
/// with the given elements.
pub fn model_with(form: ConstraintForm, elements: impl FnOnce(&mut Noise) -> Vec<Box<dyn Element>>) -> romdyn::model::Model {
    let mut n = Noise(4242);
    let mut b = ModelBuilder::new();
    b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(3, n.vec(), n.rotation(), n.vec(), n.vec());
    for e in elements(&mut n) {
        b.boxed_element(e);
    }
    b.constraint_form(form);
    b.build().unwrap()
}

/// Every element's worst Jacobian entry at a random state (unknowns, derivatives,
/// multipliers all perturbed), both constraint forms, below 1e-6.
pub fn assert_jacobians(elements: impl Fn(&mut Noise) -> Vec<Box<dyn Element>>) {
    assert_model_jacobians(|form| model_with(form, &elements), 99, 1e-6);
}

/// Every element's worst Jacobian entry of `model_of(form)` at its initial state moved by
/// noise (seed `seed`, amplitude 0.5, t = 0.3 s, dCoef 0.37 s), both constraint forms,
/// below `tolerance`; returns how many elements were compared in each form.
pub fn assert_model_jacobians(model_of: impl Fn(ConstraintForm) -> Model, seed: u64, tolerance: f64) -> usize {
    let mut compared = 0;
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let model = model_of(form);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(seed);
        st.t = 0.3;
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        let mismatches = check_jacobians(&asm, &st, 0.37, form);
        assert!(!mismatches.is_empty(), "{form:?}: no entry compared");
        compared = mismatches.len();
        for w in mismatches {
            assert!(w.relative_error < tolerance, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
        }
    }
    compared
}

/// The string of `n` masses (`tests/mbdyn/use_arpack.rs` describes it) with `eigenanalysis: 0., OPTIONS;` (12 n + 24 equations).
pub fn string_of_masses(n: usize, options: &str) -> String {
    let mut t = format!(
        "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.; time step: 1.e-3; tolerance: 1.e-10;
    eigenanalysis: 0., {options};
end: initial value;
begin: control data; skip initial joint assembly; structural nodes: {}; rigid bodies: {n}; joints: {}; end: control data;
begin: nodes;
    structural: 0, static, null, eye, null, null;
    structural: {}, static, {}., 0., 0., eye, null, null;
",
        n + 2,
        n + 3,
        n + 1,
        n + 1
    );
    for i in 1..=n {
        t += &format!("    structural: {i}, dynamic displacement, {i}., 0., 0., null;\n");
    }
    t += &format!("end: nodes;\nbegin: elements;\n    joint: 0, clamp, 0, node, node;\n    joint: {}, clamp, {}, node, node;\n", n + 2, n + 1);
    for i in 1..=n + 1 {
        if i <= n {
            t += &format!("    body: {i}, {i}, 1.;\n");
        }
        t += &format!("    joint: {i}, rod, {}, {i}, 0.9, linear elastic, 900.;\n", i - 1);
    }
    t + "end: elements;\n"
}
