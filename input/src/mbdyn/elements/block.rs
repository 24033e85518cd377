//! The `elements` block (input manual, "Elements"): `body`, `joint` (see `joints`),
//! `force` and `couple`, `gravity`, `beam3` (see `beams`) and `shell4eas` (see `plates`). Every other element
//! type is named in an error; `automatic structural` (initial momenta, recomputed anyway)
//! and the `inertia` and `output` cards (output only) are accepted and ignored.

use super::beams::beam;
use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::{ElementContext, Parsed};
use crate::mbdyn::drives::callers::{single_term, template_vec3};
use super::joints::joint;
use crate::mbdyn::syntax::parser::{known, Statement};
use crate::mbdyn::syntax::references::Frame;
use crate::element::drive::Drive;
use crate::element::{Couple, Element, Force, ForceFrame, RigidBody, VectorDrive};
use crate::kinematics::{Mat3, Vec3};
use crate::model::Label;
use crate::mbdyn::drives::callers;
use crate::mbdyn::syntax::keywords::{mbdyn_only, read, Keyword, KeywordTable, Support};

/// Every element type of MBDyn 1.7.3's `elements` block, with whether romdyn reads it: the
/// reader accepts the types marked read, and its refusals are written from this table.
pub(in crate::mbdyn) const ELEMENT_TYPES: KeywordTable = KeywordTable {
    what: "element type",
    keywords: &[
        read("body"), read("joint"), read("joint regularization"), read("force"), read("couple"), read("gravity"),
        read("beam"), read("beam2"), read("beam3"), read("automatic structural"), read("inertia"), read("output"),
        read("genel"), read("electric"), read("hydraulic"), read("shell4eas"), read("shell4easans"), read("membrane4eas"),
        Keyword { name: "hbeam", support: Support::Refused(super::beams::HBEAM_REFUSED) },
        Keyword { name: "hbeam2", support: Support::Refused(super::beams::HBEAM_REFUSED) },
        mbdyn_only("aerodynamic beam2"), mbdyn_only("aerodynamic beam3"), mbdyn_only("aerodynamic body"), mbdyn_only("aeromodal"),
        mbdyn_only("aircraft instruments"), mbdyn_only("air properties"), mbdyn_only("induced velocity"), mbdyn_only("thermal"),
        mbdyn_only("stream output"), mbdyn_only("stream motion output"), mbdyn_only("bind"), mbdyn_only("bulk"), mbdyn_only("plate"),
        Keyword { name: "rtai output", support: Support::MbdynRunsWhen("an MBDyn 1.7.3 built with RTAI runs it") },
        Keyword { name: "loadable", support: Support::MbdynRunsWhen("an MBDyn 1.7.3 built with run-time modules runs it, with the module it names loaded") },
        Keyword { name: "user defined", support: Support::MbdynRunsWhen("an MBDyn 1.7.3 built with run-time modules runs it, with the module it names loaded") },
    ],
};

/// The plate elements (`plates` in control data; see `plates`).
const PLATES: [&str; 3] = ["shell4eas", "shell4easans", "membrane4eas"];

/// The element kind counted in control data, by element keyword.
pub fn counted_kind(keyword: &str) -> Option<&'static str> {
    if known(keyword, &PLATES).is_some() {
        return Some("plates");
    }
    match known(keyword, &["body", "joint", "joint regularization", "force", "couple", "beam", "beam2", "beam3", "gravity", "automatic structural", "genel", "electric", "hydraulic"])? {
        "body" => Some("rigid bodies"),
        "electric" => Some("electric elements"),
        "hydraulic" => Some("hydraulic elements"),
        "genel" => Some("genels"),
        "joint regularization" => Some("joint regularizations"),
        "joint" => Some("joints"),
        "force" | "couple" => Some("forces"),
        "gravity" => Some("gravity"),
        "automatic structural" => Some("automatic structural elements"),
        _ => Some("beams"),
    }
}

/// The label space of an element keyword: forces and couples share one, as do beams.
pub fn label_space(keyword: &str) -> &'static str {
    if known(keyword, &PLATES).is_some() {
        return "plate";
    }
    match known(keyword, &["body", "joint", "force", "couple", "beam", "beam2", "beam3", "automatic structural", "genel", "electric", "hydraulic"]) {
        Some("body") => "body",
        Some("electric") => "electric",
        Some("hydraulic") => "hydraulic",
        Some("genel") => "genel",
        Some("joint") => "joint",
        Some("force" | "couple") => "force",
        Some("automatic structural") => "automatic structural",
        _ => "beam",
    }
}

/// One statement of the `elements` block (after the label for labelled elements).
pub fn element(st: &Statement, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let Some(kind) = ELEMENT_TYPES.find(&st.keyword).filter(|k| k.support == Support::Read).map(|k| k.name) else {
        return Err(c.error_at(st.span, ELEMENT_TYPES.refusal(&st.keyword)));
    };
    match kind {
        "gravity" => return gravity(c, ctx),
        "inertia" | "output" => {
            c.skip_rest();
            return Ok(Parsed::Ignored);
        }
        _ => {}
    }
    let label = c.label(&format!("{kind} label"))?;
    if c.accept("name") {
        c.string(&format!("{kind} name"))?;
    }
    let parsed = match kind {
        "body" => body(label, c, ctx)?,
        "joint" => match super::total_equation::parts(label, c, ctx)? {
            Some(parsed) => parsed,
            None => Parsed::Element(joint(label, c, ctx)?),
        },
        "joint regularization" => super::total_equation::regularization(label, c)?,
        "force" | "couple" => Parsed::Element(force(kind == "couple", label, c, ctx)?),
        "genel" => Parsed::Element(super::genels::genel(label, c, ctx)?),
        "electric" => Parsed::Element(super::electric::electric(label, c, ctx)?),
        "hydraulic" => Parsed::Element(super::hydraulic::hydraulic(label, c, ctx)?),
        "shell4eas" | "shell4easans" | "membrane4eas" => super::plates::plate(kind, label, c, ctx)?,
        "automatic structural" => {
            ctx.node_with_label(c, label)?;
            c.skip_rest();
            Parsed::Ignored
        }
        _ => beam(kind, label, c, ctx)?,
    };
    if c.accept("output") {
        c.flag("output flag")?;
    }
    Ok(parsed)
}

impl ElementContext<'_> {
    fn node_with_label(&self, c: &Cursor, label: Label) -> Result<(), MbdynError> {
        match self.nodes.find(label) {
            Some(n) if !n.dummy && n.node.kind == crate::model::NodeKind::Dynamic => Ok(()),
            _ => Err(c.error_at(c.statement().span, format!("automatic structural {label}: there is no dynamic structural node {label}"))),
        }
    }
}

/// `body: LABEL, NODE, [allow negative mass,] MASS, CM, J [, orientation, R]`, or
/// `condense, N, …` with N such masses, lumped into one rigid body about their common
/// centre of mass (input manual, §Body).
fn body(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let span = c.here();
    let (n, point) = ctx.point_node(c, "node of the body")?;
    // body.cc (ReadBody): a mass needs a dynamic displacement node, except in a static model,
    // where every node is static and the mass only weighs (`StaticMass`).
    if point && n.kind == crate::model::NodeKind::Static && !ctx.static_model {
        return Err(c.error_at(span, format!("body {label}: structural node {} is a static displacement node; a mass needs a dynamic displacement node (MBDyn 1.7.3: \"illegal structural node type\")", n.label)));
    }
    let on = ctx.on(n);
    if c.accept("variable mass") {
        return super::variable_body::variable_body(label, n, point, span, c, ctx);
    }
    let mut allow_negative = c.accept("allow negative mass");
    let count = if c.accept("condense") {
        let span = c.here();
        let k = c.count("number of masses")?;
        if k == 0 {
            return Err(c.error_at(span, "condense: at least one mass is needed"));
        }
        allow_negative |= c.accept("allow negative mass");
        k
    } else {
        1
    };
    let mut parts = Vec::new();
    for _ in 0..count {
        let span = c.here();
        let mass = c.real("mass [kg]")?;
        if mass < 0.0 && !allow_negative {
            return Err(c.error_at(span, format!("negative mass {mass} (write 'allow negative mass' if intended)")));
        }
        // body.cc, `ReadBody`: on a displacement node each part is its mass alone.
        if point {
            parts.push((mass, Vec3::zeros(), Mat3::zeros()));
            continue;
        }
        let cm = on.relative_position(c, "centre of mass offset [m]")?;
        let j_span = c.here();
        let mut j = on.relative_matrix(c, "inertia about the centre of mass [kg m^2]")?;
        if !allow_negative {
            // An inertia tensor is symmetric positive semi-definite (principal moments ≥ 0).
            let sym = (j + j.transpose()) * 0.5;
            let moments = sym.symmetric_eigenvalues();
            let (lo, hi) = (moments.min(), moments.amax());
            if (j - j.transpose()).amax() > 1e-12 * hi.max(f64::MIN_POSITIVE) || lo < -1e-12 * hi {
                return Err(c.error_at(j_span, format!("the inertia is not symmetric positive semi-definite (principal moments {:.6e}, {:.6e}, {:.6e} kg m^2)", moments[0], moments[1], moments[2])));
            }
        }
        // `inertial, {node | R}` (body.cc, ReadBody): the frame the inertia is written in.
        if c.accept("inertial") {
            if !c.accept("node") {
                let r = on.relative_orientation(c, "orientation of the inertia")?;
                j = r * j * r.transpose();
            }
        } else if c.accept("orientation") {
            let r = on.relative_orientation(c, "orientation of the inertia")?;
            j = r * j * r.transpose();
        }
        parts.push((mass, cm, j));
    }
    let mass: f64 = parts.iter().map(|p| p.0).sum();
    let cm = if mass != 0.0 { parts.iter().map(|(m, o, _)| *m * o).sum::<Vec3>() / mass } else { Vec3::zeros() };
    let inertia = parts.iter().map(|(m, o, j)| {
        let d = o - cm;
        j + *m * (d.dot(&d) * Mat3::identity() - d * d.transpose())
    });
    Ok(Parsed::Body(RigidBody::new(label, n.label, mass, cm, inertia.sum())))
}

/// `force: LABEL, {absolute | follower}, NODE, position, ARM, VALUE` and
/// `couple: LABEL, {absolute | follower}, NODE, [position, ARM,] VALUE` (input manual,
/// §Structural force, §Structural couple). VALUE is a 3-vector template drive caller: a
/// follower's components are in the node frame, an absolute one's in the global frame
/// unless written `single, reference, FRAME, v, …`. (The manual's "Known issues" says the
/// node frame for both; MBDyn 1.7.3 reads absolute values with `ReadDCVecAbs`, strforce.cc,
/// and moves a node turned 90° about z along global x under `absolute, …, 1., 0., 0.`:
/// tests/mbdyn_files/absolute_force_direction.mbd.)
fn force(couple: bool, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let what = if couple { "couple" } else { "force" };
    let span = c.here();
    if !couple && let Some(k) = c.accept_any(&["absolute internal displacement", "absolute displacement"]) {
        return super::forces::displacement(k == "absolute internal displacement", label, c, ctx);
    }
    match c.accept_any(&["absolute internal", "conservative internal", "follower internal", "total internal"]) {
        Some("follower internal") => return super::forces::internal(couple, ForceFrame::Follower, label, c, ctx),
        Some("total internal") if !couple => return super::forces::total_internal(label, c, ctx),
        Some("total internal") => return Err(c.error_at(span, "'total internal' is a force type (its couple is its 'moment' value), not a couple type")),
        Some(_) => return super::forces::internal(couple, ForceFrame::Absolute, label, c, ctx),
        None => {}
    }
    if c.accept("total") {
        return Err(c.error_at(span, format!("{what} type 'total' (on one node) is not implemented by MBDyn 1.7.3 (force.cc builds only 'total internal'); use a follower force and a follower couple, or 'total internal' with a second node")));
    }
    if !couple && c.accept("abstract") {
        return super::genels::abstract_force(label, c, ctx);
    }
    let unsupported = ["absolute displacement", "absolute internal displacement", "abstract internal", "modal", "external structural", "external modal", "external structural mapping", "external modal mapping"];
    if let Some(k) = c.accept_any(&unsupported) {
        return Err(c.error_at(span, format!("{what} type '{k}' is not supported by romdyn (MBDyn 1.7.3 runs it) (supported: absolute, follower, absolute internal, follower internal, total internal, absolute displacement, absolute internal displacement, abstract)")));
    }
    let frame = match c.keyword(&format!("the {what} type"), &["absolute", "conservative", "follower"])? {
        "follower" => ForceFrame::Follower,
        _ => ForceFrame::Absolute,
    };
    let n = ctx.node(c, &format!("node of the {what}"))?;
    let on = ctx.on(n);
    let basis = Mat3::identity();
    let direction = |c: &mut Cursor| match frame {
        ForceFrame::Absolute => on.vector_in(c, &format!("{what} direction"), Frame::global()),
        ForceFrame::Follower => on.relative_vector(c, &format!("{what} direction")),
    };
    let mut offset = Vec3::zeros();
    let terms = if c.accept("position") {
        offset = on.relative_position(c, "arm [m]")?;
        template_vec3(c, ctx.drives, ctx.seq, &basis, &direction)?
    } else if couple {
        template_vec3(c, ctx.drives, ctx.seq, &basis, &direction)?
    } else {
        // MBDyn's older syntax: unit direction, arm, drive.
        let dir_span = c.here();
        let dir = direction(c)?.try_normalize(0.0).ok_or_else(|| c.error_at(dir_span, "the force direction is null"))?;
        offset = on.relative_position(c, "arm [m]")?;
        vec![(dir, callers::drive(c, ctx.drives, ctx.seq)?)]
    };
    // Terms that add up to one direction times one drive are merged; components with
    // different drives stay a sum.
    let value = VectorDrive(match single_term(terms.clone()) {
        Some(term) => vec![term],
        None => terms,
    });
    if frame == ForceFrame::Follower {
        c.accept("output relative");
    }
    Ok(if couple { Box::new(Couple { label, node: n.label, frame, value }) } else { Box::new(Force { label, node: n.label, frame, value, offset }) })
}

/// `gravity: [uniform,] VALUE` with a 3-vector template drive in the global frame (a
/// constant, or one direction times one drive), or
/// `gravity: central, [origin, X0,] mass, M, G, {si | G}` (input manual, §Gravity Element).
fn gravity(c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let span = c.here();
    if c.accept("central") {
        // gravity.cc, ReadGravity: `[origin, X0,] mass, M, G, {si | G}`, M and G above the
        // machine epsilon.
        let origin = if c.accept("origin") { ctx.global().position(c, "origin of the central gravity field [m]")? } else { Vec3::zeros() };
        c.keyword("'mass'", &["mass"])?;
        let positive = |c: &mut Cursor, what: &str| -> Result<f64, MbdynError> {
            let at = c.here();
            let x = c.real(what)?;
            if !(x > f64::EPSILON) {
                return Err(c.error_at(at, format!("central gravity: {what} must be positive, found {x}")));
            }
            Ok(x)
        };
        let mass = positive(c, "central mass [kg]")?;
        c.keyword("'G'", &["G"])?;
        // 6.67384e-11 m³ kg⁻¹ s⁻² (MBDyn's value for `si`, NIST CODATA 2010).
        let g = if c.accept("si") { 6.67384e-11 } else { positive(c, "gravitational constant [m^3 kg^-1 s^-2]")? };
        return Ok(Parsed::CentralGravity { origin, gm: g * mass });
    }
    c.accept("uniform");
    let g = ctx.global();
    let terms = template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| g.vector_in(c, "gravity direction", Frame::global()))?;
    match single_term(terms) {
        Some((dir, Drive::Const(x))) => Ok(Parsed::Gravity(dir * x)),
        Some((direction, drive)) => Ok(Parsed::DrivenGravity { direction, drive }),
        None => Err(c.error_at(span, "romdyn's time-varying gravity is one direction times one drive: this value combines components with different drives")),
    }
}
