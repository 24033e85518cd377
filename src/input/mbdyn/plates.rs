//! Plate elements (input manual, "Plate Elements", §Shell4): `shell4eas: LABEL, NODE_1
//! [, orientation, R], …, NODE_4 [, orientation, R], LAW [, prestress, (Vec12) S]` with
//! the 12×12 shell law `matr` (or bare, 144 values row by row), `sym` (the upper triangle,
//! 78 values row by row), `diag` (12 values), `isotropic, {E | Young modulus}, E, {nu |
//! Poisson modulus}, NU, {G | shear modulus}, G, thickness, H [, as, AS] [, at, AT]` (two
//! of E, ν, G; `as` = 1 and `at` = 0.01 by default, as MBDyn's shell.cc) or `plane stress
//! orthotropic`. A node's `orientation` is read and, as MBDyn 1.7.3 does, not used.
//! `shell4easans` and `membrane4eas` are refused with where MBDyn runs them.

use nalgebra::{SMatrix, SVector};

use super::cursor::Cursor;
use super::diagnostic::MbdynError;
use super::element_context::{ElementContext, Parsed};
use crate::element::{Shell4, ShellLaw, ShellVariant};
use crate::model::Label;

/// `shell4eas` and `shell4easans` (and the refusals of the other plate elements).
pub fn plate(keyword: &str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let variant = match keyword {
        "shell4eas" => ShellVariant::Eas,
        "shell4easans" => ShellVariant::EasAns,
        _ => return Err(c.error_at(c.statement().span, super::diagnostic::mbdyn_runs_it(&format!("element type '{keyword}' ({keyword} {label}; romdyn reads the plate elements 'shell4eas' and 'shell4easans')")))),
    };
    let mut nodes = Vec::with_capacity(4);
    for k in 1..=4 {
        let n = ctx.node(c, &format!("node {k} of {keyword} {label}"))?;
        if c.accept("orientation") {
            ctx.on(n).relative_orientation(c, &format!("orientation of node {k}"))?;
        }
        nodes.push((n.label, n.position, n.orientation));
    }
    let law = shell_law(c)?;
    let span = c.statement().span;
    let Ok(nodes) = <[_; 4]>::try_from(nodes) else {
        return Err(c.error_at(span, format!("{keyword} {label}: expected four nodes")));
    };
    let shell = Shell4::new(variant, label, nodes, law).map_err(|e| c.error_at(span, e.to_string()))?;
    Ok(Parsed::Element(Box::new(shell)))
}

/// The 12×12 law and its prestress.
fn shell_law(c: &mut Cursor) -> Result<ShellLaw, MbdynError> {
    let mut law = if c.accept("diag") {
        let mut k = SMatrix::<f64, 12, 12>::zeros();
        for i in 0..12 {
            k[(i, i)] = c.real(&format!("shell stiffness D({0},{0})", i + 1))?;
        }
        ShellLaw { stiffness: k, prestress: SVector::zeros() }
    } else if c.accept("sym") {
        let mut k = SMatrix::<f64, 12, 12>::zeros();
        for i in 0..12 {
            for j in i..12 {
                let v = c.real(&format!("shell stiffness D({},{})", i + 1, j + 1))?;
                k[(i, j)] = v;
                k[(j, i)] = v;
            }
        }
        ShellLaw { stiffness: k, prestress: SVector::zeros() }
    } else if c.accept("isotropic") {
        isotropic(c)?
    } else if c.accept("plane stress orthotropic") {
        return Err(c.error(super::diagnostic::mbdyn_runs_it("the shell law 'plane stress orthotropic' (write its 12x12 matrix with 'matr' or 'sym' as the input manual shows)")));
    } else {
        c.accept("matr");
        let mut k = SMatrix::<f64, 12, 12>::zeros();
        for i in 0..12 {
            for j in 0..12 {
                k[(i, j)] = c.real(&format!("shell stiffness D({},{})", i + 1, j + 1))?;
            }
        }
        ShellLaw { stiffness: k, prestress: SVector::zeros() }
    };
    if c.accept("prestress") {
        for i in 0..12 {
            law.prestress[i] = c.real(&format!("shell prestress component {} [N/m, N]", i + 1))?;
        }
    }
    Ok(law)
}

/// `isotropic, …` as MBDyn's shell.cc reads it: each datum once, two of E, ν, G (all
/// three consistent), the thickness.
fn isotropic(c: &mut Cursor) -> Result<ShellLaw, MbdynError> {
    let start = c.here();
    let mut got: [Option<f64>; 6] = [None; 6];
    const NAMES: [&str; 6] = ["Young's modulus E [Pa]", "Poisson's ratio nu", "shear modulus G [Pa]", "thickness [m]", "shear factor 'as'", "drilling factor 'at'"];
    loop {
        let which = if c.accept("E") || c.accept("Young modulus") {
            0
        } else if c.accept("nu") || c.accept("Poisson modulus") {
            1
        } else if c.accept("G") || c.accept("shear modulus") {
            2
        } else if c.accept("thickness") {
            3
        } else if c.accept("as") {
            4
        } else if c.accept("at") {
            5
        } else {
            break;
        };
        let span = c.here();
        if got[which].is_some() {
            return Err(c.error_at(span, format!("shell isotropic law: {} given twice", NAMES[which])));
        }
        let v = c.real(NAMES[which])?;
        let ok = if which == 1 { (0.0..0.5).contains(&v) } else { v > 0.0 };
        if !ok {
            let range = if which == 1 { "in [0, 0.5)" } else { "positive" };
            return Err(c.error_at(span, format!("shell isotropic law: {} must be {range}, found {v}", NAMES[which])));
        }
        got[which] = Some(v);
    }
    let (e, nu, g) = match (got[0], got[1], got[2]) {
        (Some(e), Some(nu), Some(g)) => {
            if (e / (2.0 * (1.0 + nu)) - g).abs() > f64::EPSILON * g.max(1.0) {
                return Err(c.error_at(start, format!("shell isotropic law: E = {e}, nu = {nu} and G = {g} are inconsistent (G must be E/(2 (1 + nu)))")));
            }
            (e, nu, g)
        }
        (Some(e), Some(nu), None) => (e, nu, e / (2.0 * (1.0 + nu))),
        (Some(e), None, Some(g)) => {
            let nu = e / (2.0 * g) - 1.0;
            if !(nu > 0.0 && nu < 0.5) {
                return Err(c.error_at(start, format!("shell isotropic law: E = {e} and G = {g} give nu = {nu}, outside (0, 0.5)")));
            }
            (e, nu, g)
        }
        (None, Some(nu), Some(g)) => (2.0 * (1.0 + nu) * g, nu, g),
        _ => return Err(c.error_at(start, "shell isotropic law: two of 'E', 'nu' and 'G' are needed")),
    };
    let Some(h) = got[3] else {
        return Err(c.error_at(start, "shell isotropic law: the 'thickness' is missing"));
    };
    Ok(ShellLaw::isotropic(e, nu, g, h, got[4].unwrap_or(1.0), got[5].unwrap_or(0.01)))
}
