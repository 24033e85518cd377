//! Rigid body on a structural node: mass, centre-of-mass offset and inertia, plus its
//! weight in the gravity field (METHOD §5).
//!
//! With `f = R o` (offset in the global frame), `S = m f` and `J = R J₀ Rᵀ`,
//! `J₀ = J_cm + m (oᵀo I − o oᵀ)` (inertia about the node, node frame), it adds
//! `−(m ẋ + ω × S)` and `−(S × ẋ + J ω)` to the node's momentum definitions and
//! `−m g`, `−S × g` to its equilibrium (moments about the node). On a static node, which
//! has no momentum rows, only the weight acts.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};
use super::contract::Label;
use crate::element::Outputs;

/// A rigid body attached to a node.
#[derive(Clone, Debug)]
pub struct RigidBody {
    pub label: Label,
    pub node: Label,
    /// Mass [kg].
    pub mass: f64,
    /// Centre of mass in the node frame [m].
    pub offset: Vec3,
    /// Inertia about the centre of mass, node frame [kg m²].
    pub inertia: Mat3,
    /// The model's moving reference frame (MBDyn's `rigid body kinematics`): its transport
    /// terms act on the body ([`super::frame_motion`]).
    pub frame: Option<std::sync::Arc<super::FrameMotion>>,
}

impl RigidBody {
    pub fn new(label: Label, node: Label, mass: f64, offset: Vec3, inertia: Mat3) -> Self {
        RigidBody { label, node, mass, offset, inertia, frame: None }
    }

    /// Inertia about the node, node frame.
    pub fn inertia_about_node(&self) -> Mat3 {
        let o = self.offset;
        self.inertia + self.mass * (o.dot(&o) * Mat3::identity() - o * o.transpose())
    }
}

impl Element for RigidBody {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "body"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = st.node(0);
        let s = self.mass * (n.r * self.offset);
        let g = st.gravity();
        add_vec(out, Row::force(0), &(-self.mass * g));
        add_vec(out, Row::moment(0), &(-s.cross(&g)));
        let j = n.r * self.inertia_about_node() * n.r.transpose();
        add_vec(out, Row::linear_momentum(0), &(-(self.mass * n.xdot + n.omega.cross(&s))));
        add_vec(out, Row::angular_momentum(0), &(-(s.cross(&n.xdot) + j * n.omega)));
        if let Some(f) = &self.frame {
            super::frame_motion::body_residual(&f.at(st.time()), self.mass, &s, &j, st, out);
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = st.node(0);
        let s = self.mass * (n.r * self.offset);
        let (sx, g) = (skew(&s), st.gravity());
        // δS = −[S×] δθ.
        add_block(out, Row::moment(0), Col::rotation(0), &(-skew(&g) * sx));
        let j = n.r * self.inertia_about_node() * n.r.transpose();
        // Each momentum row's three blocks at once (the sink maps the rows once).
        let cols = [Col::velocity(0), Col::angular_velocity(0), Col::rotation(0)];
        out.add_blocks(Row::linear_momentum(0), &cols, &[-self.mass * Mat3::identity(), sx, skew(&n.omega) * sx]);
        out.add_blocks(Row::angular_momentum(0), &cols, &[-sx, -j, -skew(&n.xdot) * sx + skew(&(j * n.omega)) - j * skew(&n.omega)]);
        if let Some(f) = &self.frame {
            super::frame_motion::body_jacobian(&f.at(st.time()), self.mass, &s, &j, st, out);
        }
    }
}

impl Outputs for RigidBody {
    /// body.cc, `Body::dGetPrivData`: "E" the kinetic energy `½ (m v_G·v_G + Ωᵀ J_cm Ω)`
    /// (v_G the centre of mass's velocity, Ω the angular velocity in the node frame), "V"
    /// the potential energy `−m x_G·g` (zero without gravity, and while MBDyn reads the
    /// file, before it links the gravity element), "m" the mass.
    fn private_data(&self, name: &str) -> Option<super::contract::PrivateDatum> {
        let (node, body) = (self.node, self.clone());
        let datum: super::contract::PrivateDatum = match name {
            "E" => super::contract::PrivateDatum::new(move |st: &dyn ElementState| {
                let n = st.structural_node(node)?;
                let v = n.xdot + n.omega.cross(&(n.r * body.offset));
                let w = n.r.transpose() * n.omega;
                Some(0.5 * (body.mass * v.dot(&v) + w.dot(&(body.inertia * w))))
            }),
            "V" => super::contract::PrivateDatum::new(move |st: &dyn ElementState| {
                let n = st.structural_node(node)?;
                Some(-body.mass * (n.x + n.r * body.offset).dot(&st.gravity()))
            }),
            "m" => super::contract::PrivateDatum::new(move |_: &dyn ElementState| Some(body.mass)),
            _ => return None,
        };
        Some(datum)
    }
}
