//! `body: LABEL, NODE, variable mass, MASS, CM, J_MASS, J_GEOMETRY;` (input manual §Body,
//! "Variable mass"; body_vm.cc `ReadVariableBody`): MASS a drive caller, CM a 3-vector
//! template drive caller (node frame), J_MASS and J_GEOMETRY 3x3 template drive callers
//! (node frame, about the centre of mass), all of time. The element is
//! [`crate::element::VariableBody`].

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::mbdyn::drives::callers::{drive, template_vec3};
use super::context::{ElementContext, Parsed};
use crate::mbdyn::drives::templates::{template, TemplateDim};
use crate::element::VariableBody;
use crate::element::drive::Drive;
use crate::kinematics::Mat3;
use crate::model::{Label, NodeKind, StructuralNode};

/// Reads what follows `variable mass` on the body `label` of node `n` (`point`: a
/// displacement node; `node_span`: where the node is named).
pub fn variable_body(label: Label, n: &StructuralNode, point: bool, node_span: Span, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    // body_vm.cc (ReadVariableBody): in a static model every node is static and MBDyn
    // builds a `StaticVariableBody` (its weight only), which romdyn does not have.
    if ctx.static_model && !point {
        return Err(c.error_at(node_span, format!("variable body {label} in a static model ('model: static') is not supported by romdyn (MBDyn 1.7.3 runs it as a static variable body, its weight only)")));
    }
    if point || n.kind != NodeKind::Dynamic {
        return Err(c.error_at(node_span, format!("variable body {label}: structural node {} is not a dynamic node; a variable-mass body needs one (MBDyn 1.7.3: \"illegal structural node type\")", n.label)));
    }
    let differentiable = |c: &Cursor, span, what: &str, drives: Vec<&Drive>| {
        match drives.into_iter().find(|d| d.time_derivative(0.0).is_none()) {
            Some(_) => Err(c.error_at(span, format!("variable body {label}: the {what} must be differentiable in time; romdyn differentiates const, time, linear/parabolic/cubic, ramp, step, sine, cosine, exponential, tanh and their sums and products, not this one"))),
            None => Ok(()),
        }
    };
    let span = c.here();
    let mass = drive(c, ctx.drives, ctx.seq)?;
    differentiable(c, span, "mass drive", vec![&mass])?;
    let span = c.here();
    let offset = template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("centre of mass [m]"))?;
    differentiable(c, span, "centre of mass drive", offset.iter().map(|(_, d)| d).collect())?;
    let inertia = |c: &mut Cursor, what: &str| -> Result<Vec<(Mat3, Drive)>, MbdynError> {
        let span = c.here();
        let terms: Vec<(Mat3, Drive)> = template(c, ctx.drives, ctx.seq, TemplateDim::Mat3x3)?.into_iter().map(|(v, d)| (Mat3::from_row_slice(&v), d)).collect();
        differentiable(c, span, what, terms.iter().map(|(_, d)| d).collect())?;
        Ok(terms)
    };
    let inertia_mass = inertia(c, "mass-related inertia drive")?;
    let inertia_geometry = inertia(c, "geometry-related inertia drive")?;
    Ok(Parsed::Element(Box::new(VariableBody { label, node: n.label, mass, offset, inertia_mass, inertia_geometry, mbdyn_frames: false })))
}
