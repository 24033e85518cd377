//! The report of a Jacobian check (`romdyn check`): one row per element with its worst
//! entry, then a summary line.

use crate::dae::{AssembledMismatch, JacobianMismatch};

/// The report as text. An element passes when its relative error is at most `tolerance`.
pub fn jacobian_check_text(elements: &[JacobianMismatch], assembled: &[AssembledMismatch], tolerance: f64, time: f64, dcoef: f64) -> String {
    let mut s = format!(
        "# Jacobian check at t = {time} s, dCoef = {dcoef:e} s: each element's J(c) = F/y' + c F/y against central differences of its residual\n\
         # error = |analytic - fd| / max(max |J_element|, 1); tolerance {tolerance:e}\n"
    );
    s += &format!("{:<6}  {:<24}  {:>9}  {:>14}  {:>14}  worst entry d(equation)/d(unknown)\n", "status", "element", "error", "analytic", "fd");
    for e in elements {
        let status = if e.within(tolerance) { "ok" } else { "FAIL" };
        let entry = if e.equation.is_empty() { "none: analytic and finite differences agree exactly".to_string() } else { format!("d({})/d({})", e.equation, e.unknown) };
        let name = if e.drive_held { format!("{} *", e.element) } else { e.element.clone() };
        s += &format!("{status:<6}  {name:<24}  {:>9.2e}  {:>14.6e}  {:>14.6e}  {entry}\n", e.relative_error, e.analytic, e.finite_difference);
    }
    if elements.iter().any(|e| e.drive_held) {
        s += "* a drive of the element reads the model's state (model:: functions, node, dof or element drive callers): the differences hold it at this state, its derivatives are in no Jacobian (as in MBDyn)\n";
    }
    s += "# the whole model's F/y' and F/y (every element and the nodes' own rows, as the linearization assembles them) against central differences of the whole residual\n";
    s += "# error = (|analytic - fd| - rounding of the differences) / max(max |row|, max |column|, 1e-9 max |matrix|)\n";
    for m in assembled {
        let status = if m.within(tolerance) { "ok" } else { "FAIL" };
        let entry = if m.equation.is_empty() { "none: analytic and finite differences agree within rounding".to_string() } else { format!("d({})/d({})", m.equation, m.unknown) };
        s += &format!("{status:<6}  {:<24}  {:>9.2e}  {:>14.6e}  {:>14.6e}  {entry}\n", format!("whole model {}", m.matrix), m.relative_error, m.analytic, m.finite_difference);
    }
    let failed: Vec<&JacobianMismatch> = elements.iter().filter(|e| !e.within(tolerance)).collect();
    match failed.first() {
        None => s += &format!("{} elements checked: all agree within {tolerance:e}\n", elements.len()),
        Some(worst) => {
            s += &format!(
                "{} of {} elements disagree beyond {tolerance:e} (worst: {}, error {:.2e})\n",
                failed.len(),
                elements.len(),
                worst.element,
                worst.relative_error
            )
        }
    }
    let whole: Vec<&AssembledMismatch> = assembled.iter().filter(|m| !m.within(tolerance)).collect();
    if !whole.is_empty() {
        let names: Vec<String> = whole.iter().map(|m| format!("{} (error {:.2e} at d({})/d({}))", m.matrix, m.relative_error, m.equation, m.unknown)).collect();
        s += &format!("the whole model's {} disagree with the differences of its residual beyond {tolerance:e}\n", names.join(" and "));
    }
    s
}
