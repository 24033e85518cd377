//! The `genel` cards romdyn builds (input manual §Genel Element; genel.cc, `ReadGenel`):
//! `clamp`, `distance`, `spring`, `spring support`, `cross spring support`, `mass`, `scalar
//! filter`, `state space SISO` and `state space MIMO`; and the abstract force (`force: L, abstract, NODE, TYPE, DRIVE`, §Abstract
//! force). Every other genel is refused by name.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use crate::mbdyn::nodes::scalar::scalar_dof;
use crate::element::{controllable_form, observable_form, AbstractForce, Element, ScalarClamp, ScalarDistance, ScalarInput, ScalarLaw, ScalarMass, ScalarSpring, ScalarSpringPair, StateSpace};
use crate::model::Label;
use crate::mbdyn::drives::callers;
use crate::mbdyn::syntax::parser;
use crate::mbdyn::syntax::keywords::{mbdyn_only, read, KeywordTable};

/// Every genel type of MBDyn 1.7.3 (genel.cc, `ReadGenel`), with whether romdyn builds it.
pub(in crate::mbdyn) const GENEL_TYPES: KeywordTable = KeywordTable {
    what: "genel type",
    keywords: &[
        read("clamp"), read("distance"), read("spring support"), read("cross spring support"), read("spring"), read("mass"),
        read("scalar filter"), read("state space SISO"), read("state space MIMO"),
        mbdyn_only("swashplate"), mbdyn_only("rotor trim"), mbdyn_only("take off"), mbdyn_only("inline"),
    ],
};

/// `genel: LABEL, TYPE, …` after the label.
pub fn genel(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let Some(kind) = c.accept_any(&GENEL_TYPES.read()) else {
        return Err(match c.peek_keyword() {
            Some(w) => c.error_at(span, GENEL_TYPES.refusal(w)),
            None => c.error(format!("expected the genel type ({}), found {}", GENEL_TYPES.read().join(", "), c.found())),
        });
    };
    let scalars = &ctx.nodes.2;
    let what = format!("genel {label} ({kind})");
    let e: Box<dyn Element> = match kind {
        "clamp" => {
            let (dof, _) = scalar_dof(c, scalars, &what, true)?;
            Box::new(ScalarClamp { label, dof, drive: callers::drive(c, ctx.drives, ctx.seq)? })
        }
        "distance" | "spring" => {
            let first = scalar_dof(c, scalars, &what, true)?.0;
            let second = scalar_dof(c, scalars, &what, true)?.0;
            let dofs = [first, second];
            if kind == "distance" {
                Box::new(ScalarDistance { label, dofs, drive: callers::drive(c, ctx.drives, ctx.seq)? })
            } else {
                let law_span = c.here();
                let law = scalar_law(c, ctx, &what)?;
                if law.viscosity != 0.0 {
                    return Err(c.error_at(law_span, format!("{what}: only elastic constitutive laws are allowed (MBDyn 1.7.3: \"only elastic constitutive laws allowed\")")));
                }
                Box::new(ScalarSpringPair { label, dofs, law })
            }
        }
        "spring support" | "cross spring support" => {
            let row = if kind == "cross spring support" { Some(scalar_dof(c, scalars, &what, true)?.0.node) } else { None };
            let col_span = c.here();
            let (col, differential) = scalar_dof(c, scalars, &what, true)?;
            if col.derivative || !differential {
                return Err(c.error_at(col_span, format!("{what}: the algebraic value of a differential node is required (MBDyn 1.7.3: \"illegal order … for ScalarDof\")")));
            }
            let law = scalar_law(c, ctx, &what)?;
            let mut x0 = 0.0;
            if kind == "spring support" && c.accept("position") {
                x0 = if c.accept("from node") { scalars.iter().find(|e| e.node.id == col.node).map_or(0.0, |e| e.node.value) } else { c.real("reference value X0")? };
            }
            Box::new(ScalarSpring { label, row: row.unwrap_or(col.node), col: col.node, law, x0 })
        }
        "mass" => {
            let dof_span = c.here();
            let (dof, differential) = scalar_dof(c, scalars, &what, true)?;
            if dof.derivative || !differential {
                return Err(c.error_at(dof_span, format!("{what}: the algebraic value of a differential node is required (input manual §Mass)")));
            }
            let initial_rate = scalars.iter().find(|e| e.node.id == dof.node).map_or(0.0, |e| e.node.derivative);
            Box::new(ScalarMass { label, node: dof.node, mass: callers::drive(c, ctx.drives, ctx.seq)?, initial_rate })
        }
        _ => state_space(label, kind, c, ctx, &what)?,
    };
    if c.accept("output") {
        c.flag("output flag")?;
    }
    Ok(e)
}

/// A 1-D linear law (`linear elastic`, `linear viscous`, `linear viscoelastic`, with
/// `prestress` and `prestrain`).
fn scalar_law(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<ScalarLaw, MbdynError> {
    let span = c.here();
    let law = super::laws::linear_law(c, 1, ctx.laws, ctx.drives, ctx.seq)?;
    if law.bistop.is_some() {
        return Err(c.error_at(span, format!("{what}: a bistop law on a genel is not supported by romdyn (MBDyn 1.7.3 runs it) (linear elastic, viscous and viscoelastic laws are)")));
    }
    Ok(ScalarLaw { stiffness: law.stiffness[(0, 0)], viscosity: law.viscosity[(0, 0)], prestrain: law.prestrain[0], prestress: law.prestress[0] })
}

/// One input of a state-space genel (MBDyn's `ReadScalarValue`): `drive, DRIVE` or
/// `[node dof,] DOF`.
fn scalar_input(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<ScalarInput, MbdynError> {
    if c.accept("drive") {
        return Ok(ScalarInput::Drive(callers::drive(c, ctx.drives, ctx.seq)?));
    }
    c.accept("node dof");
    Ok(ScalarInput::Dof(scalar_dof(c, &ctx.nodes.2, what, true)?.0))
}

/// A count of outputs or inputs, 1 to 64.
fn port_count(c: &mut Cursor, what: &str, of: &str) -> Result<usize, MbdynError> {
    let span = c.here();
    let n = c.count(&format!("number of {of}"))?;
    if !(1..=64).contains(&n) {
        return Err(c.error_at(span, format!("{what}: the number of {of} must be 1 to 64, found {n}")));
    }
    Ok(n)
}

/// `scalar filter, OUT, {[node dof,] IN | drive, DRIVE}, [canonical form, …,] ND, a_1 … a_ND,
/// NN, b_0 … b_NN [, gain, G] [, balance, yes|no]`, `state space SISO, OUT, IN, ORDER,
/// matrix A, …, matrix B, …, matrix C, … [, matrix D, D] [, gain, G] [, balance, …]` and
/// `state space MIMO, P, OUT…, M, IN…, ORDER, matrix A, …, matrix B (ORDER × M), …, matrix C
/// (P × ORDER), … [, matrix D (P × M), …] [, gain, G] [, balance, …]` (genel.cc, matrices row
/// by row). `balance` scales the states (MBDyn's dgebal), which changes neither the transfer
/// function nor the outputs: romdyn reads it and keeps the states unscaled.
fn state_space(label: Label, kind: &'static str, c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<Box<dyn Element>, MbdynError> {
    let mimo = kind == "state space MIMO";
    let p = if mimo { port_count(c, what, "outputs")? } else { 1 };
    let mut outputs = Vec::with_capacity(p);
    for _ in 0..p {
        let out_span = c.here();
        let (output, _) = scalar_dof(c, &ctx.nodes.2, what, true)?;
        if output.derivative {
            return Err(c.error_at(out_span, format!("{what}: an output must be a node's algebraic value (romdyn writes the output equation on the value)")));
        }
        outputs.push(output.node);
    }
    let m = if mimo { port_count(c, what, "inputs")? } else { 1 };
    let in_span = c.here();
    let inputs = (0..m).map(|_| scalar_input(c, ctx, what)).collect::<Result<Vec<_>, _>>()?;
    if let Some(node) = inputs.iter().find_map(|i| match i {
        ScalarInput::Dof(d) if outputs.contains(&d.node) => Some(d.node),
        _ => None,
    }) {
        return Err(c.error_at(in_span, format!("{what}: {node} is both an input and an output")));
    }
    let (e, a, b, cc, d) = if kind == "scalar filter" {
        let (a, b, cc, d) = filter(c, what)?;
        (None, a, b, cc, vec![d])
    } else {
        matrices(c, what, p, m)?
    };
    if c.accept("balance") {
        c.flag("balance (yes or no)")?;
    }
    if kind != "scalar filter" && c.accept("value") {
        return Err(c.error(format!("{what}: initial values of the states ('value, …') are not supported by romdyn (MBDyn 1.7.3 runs them) (its genel states start at zero)")));
    }
    Ok(Box::new(StateSpace { label, outputs, inputs, e, a, b, c: cc, d, keyword: kind }))
}

/// `[canonical form, …,] ND, a_1 … a_ND, NN, b_0 … b_NN [, gain, G]` of a `scalar filter`:
/// MBDyn's realization.
fn filter(c: &mut Cursor, what: &str) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>, f64), MbdynError> {
    let observable = if c.accept("canonical form") { c.keyword("the canonical form", &["controllable", "observable"])? == "observable" } else { false };
    let nd_span = c.here();
    let nd = c.count("output order (denominator degree)")?;
    if nd < 1 || nd > 64 {
        return Err(c.error_at(nd_span, format!("{what}: the output order must be 1 to 64, found {nd}")));
    }
    let den = (1..=nd).map(|i| c.real(&format!("denominator coefficient a_{i}"))).collect::<Result<Vec<_>, _>>()?;
    let nn_span = c.here();
    let nn = c.count("input order (numerator degree)")?;
    if nn > nd {
        return Err(c.error_at(nn_span, format!("{what}: the input order {nn} exceeds the output order {nd}: the filter must be proper")));
    }
    let mut num = vec![0.0; nd + 1];
    for (i, slot) in num.iter_mut().enumerate().skip(nd - nn) {
        *slot = c.real(&format!("numerator coefficient b_{}", i - (nd - nn)))?;
    }
    if c.accept("gain") {
        let g = c.real("gain")?;
        num.iter_mut().for_each(|x| *x *= g);
    }
    Ok(if observable { observable_form(&den, &num) } else { controllable_form(&den, &num) })
}

/// The matrices `(E, A, B, C, D)` of a state-space genel, `E` when given.
type Matrices = (Option<Vec<f64>>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// `ORDER, [matrix E, …,] matrix A, …, matrix B, …, matrix C, … [, matrix D, …] [, gain, G]`
/// of a state-space genel with `p` outputs and `m` inputs, row by row (`matrix E`: the
/// descriptor form `E ẋ = A x + B u`); the gain multiplies `C` and `D`.
fn matrices(c: &mut Cursor, what: &str, p: usize, m: usize) -> Result<Matrices, MbdynError> {
    let n_span = c.here();
    let n = c.count("state space order")?;
    if n < 1 || n > 64 {
        return Err(c.error_at(n_span, format!("{what}: the order must be 1 to 64, found {n}")));
    }
    let read = |c: &mut Cursor, name: &'static str, len: usize| -> Result<Vec<f64>, MbdynError> {
        c.keyword(&format!("'{name}'"), &[name])?;
        (0..len).map(|k| c.real(&format!("{name} entry {}", k + 1))).collect()
    };
    let e = if c.peek_keyword().is_some_and(|k| parser::same_keyword(k, "matrix E")) { Some(read(c, "matrix E", n * n)?) } else { None };
    let a = read(c, "matrix A", n * n)?;
    let b = read(c, "matrix B", n * m)?;
    let mut cc = read(c, "matrix C", p * n)?;
    let mut d = if c.accept("matrix D") { (0..p * m).map(|k| c.real(&format!("matrix D entry {}", k + 1))).collect::<Result<Vec<_>, _>>()? } else { vec![0.0; p * m] };
    if c.accept("gain") {
        let g = c.real("gain")?;
        cc.iter_mut().chain(d.iter_mut()).for_each(|x| *x *= g);
    }
    Ok((e, a, b, cc, d))
}

/// `force: LABEL, abstract, NODE, TYPE, DRIVE` after `abstract` (no order: the force acts on
/// the node's equation).
pub fn abstract_force(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let (dof, _) = scalar_dof(c, &ctx.nodes.2, &format!("abstract force {label}"), false)?;
    Ok(Box::new(AbstractForce { label, node: dof.node, value: callers::drive(c, ctx.drives, ctx.seq)? }))
}
