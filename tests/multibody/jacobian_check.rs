//! `romdyn check` and its library function: every element's Jacobian against finite
//! differences at a model's reference solution; a deliberately wrong element is caught.

use crate::common;

use common::cli::{pendulum_variant, romdyn, temp_dir, write_file, DISPLACED_NODE, PENDULUM_NODE};
use common::fixtures::WrongSpring;
use common::models::pendulum;
use romdyn::analysis::{check_model_jacobians, Reference, JACOBIAN_CHECK_TOLERANCE};
use romdyn::model::ConstraintForm;
use romdyn::model::{InitialValueProblem, Method, Model};
use romdyn::solve::newton_dcoef;

fn pendulum_with_wrong_spring() -> Model {
    let mut model = pendulum(0.0, false, ConstraintForm::Scaled);
    model.elements.push(Box::new(WrongSpring));
    model
}

#[test]
fn the_check_names_the_wrong_element_its_entry_and_both_values() {
    let model = pendulum_with_wrong_spring();
    let problem = InitialValueProblem::default();
    let check = check_model_jacobians(&model, &problem, Reference::Initial, JACOBIAN_CHECK_TOLERANCE).unwrap();
    assert!(!check.passed());
    let failures: Vec<_> = check.failures().collect();
    assert_eq!(failures.len(), 1, "{}", check.to_text());
    let w = failures[0];
    assert_eq!((w.element.as_str(), w.equation.as_str(), w.unknown.as_str()), ("wrong spring 99", "node 2 force y equilibrium", "node 2 y"));
    // J(c) entry: analytic c·20, finite differences c·10 (closed form of the spring), with
    // c = b₀ = h (δ + 1/2) of ms, ρ∞ = 0.6, h = 1e-3 s: δ = 0.16/7.68, c = 5.2083333e-4 s.
    let c = 1e-3 * (0.16 / 7.68 + 0.5);
    assert!((check.dcoef - c).abs() < 1e-15 && (newton_dcoef(Method::Ms { rho: 0.6 }, 1e-3) - c).abs() < 1e-15);
    assert!((w.analytic - 20.0 * c).abs() < 1e-12 && (w.finite_difference - 10.0 * c).abs() < 1e-9, "{w:?}");
    let text = check.to_text();
    assert!(text.contains("FAIL    wrong spring 99"), "{text}");
    assert!(text.contains("d(node 2 force y equilibrium)/d(node 2 y)"), "{text}");
    assert!(text.contains("\n1 of 4 elements disagree beyond 1e-6 (worst: wrong spring 99, error 5.21e-3)\n"), "{text}");
    // The whole model's F/y, which sums the wrong spring's 20 N/m with the rest, disagrees
    // with the whole residual's differences at the same entry (the spring's closed form:
    // 10 N/m); F/y' does not involve the spring.
    assert!(text.contains("FAIL    whole model F/y  ") && text.contains("ok      whole model F/y'"), "{text}");
    let [fyd, fy] = &check.assembled;
    assert!(fyd.within(1e-6) && !fy.within(1e-6), "{text}");
    assert_eq!((fy.equation.as_str(), fy.unknown.as_str()), ("node 2 force y equilibrium", "node 2 y"), "{text}");
    assert!((fy.analytic - fy.finite_difference - 10.0).abs() < 1e-6, "{fy:?}");
    assert!(text.trim_end().ends_with("the whole model's F/y (error 5.00e-1 at d(node 2 force y equilibrium)/d(node 2 y)) disagree with the differences of its residual beyond 1e-6"), "{text}");
}

#[test]
fn check_passes_on_the_pendulum_file_at_rest_and_swinging() {
    let (ok, out, err) = romdyn(&["check", "examples/pendulum.mbd"]);
    assert!(ok, "{err}");
    assert!(out.starts_with("# Jacobian check at t = 0 s, dCoef = 5.208333333333334e-4 s"), "{out}");
    assert!(out.contains("tolerance 1e-6"), "{out}");
    for element in ["clamp 1", "revolute hinge 2", "body 3"] {
        assert!(out.lines().any(|l| l.starts_with("ok") && l.contains(element)), "{element} in {out}");
    }
    assert!(out.trim_end().ends_with("3 elements checked: all agree within 1e-6"), "{out}");

    // Released at 0.1 rad and checked after 50 ms of swing (nonzero velocities and momenta).
    let dir = temp_dir("check-swing");
    let file = write_file(&dir, "swing.mbd", &pendulum_variant(&[(PENDULUM_NODE, DISPLACED_NODE)]));
    let (ok, out, err) = romdyn(&["check", &file, "--at", "0.05"]);
    assert!(ok, "{err}\n{out}");
    assert!(out.starts_with("# Jacobian check at t = 0.05"), "{out}");
    assert!(out.trim_end().ends_with("3 elements checked: all agree within 1e-6"), "{out}");
    let m = romdyn::input::mbdyn::read_model(std::path::Path::new(&file)).unwrap();
    let check = check_model_jacobians(&m.model, &m.problem, Reference::At(0.05), JACOBIAN_CHECK_TOLERANCE).unwrap();
    eprintln!("worst relative error while swinging: {:e} ({})", check.elements[0].relative_error, check.elements[0].element);
    std::fs::remove_dir_all(&dir).ok();
}
