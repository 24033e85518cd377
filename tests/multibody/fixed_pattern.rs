//! Newton's Jacobian assembled as values alone on a known pattern (issue 36 point 4): the
//! values are the triplets' own, in their order, and an element whose entries move with
//! the state (same count, another column) is caught by the fingerprint of its calls, so its
//! Jacobian is assembled with positions again instead of landing in the old ones.

use crate::common;

use common::models::link_chain;
use romdyn::dae::{Assembler, Coefficients, Frames, SparseLu, State, Triplets};
use romdyn::element::{Anchor, Col, Element, ElementState, JacobianSink, Joint, ResidualSink, Row};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::{ConstraintForm, Model, ModelBuilder};
use romdyn::solve::{initial_derivatives, static_solution, Integrator, Method, NewtonSettings};

/// Triplets and values alone of `J(c)` at `st`.
fn both(asm: &Assembler, st: &State, c: Coefficients) -> (Triplets, Vec<f64>, romdyn::dae::Shape) {
    let mut frames = Frames::default();
    asm.frames_into(st, &mut frames);
    let mut triplets = Triplets::default();
    asm.jacobian_at(st, &frames, c, &mut triplets);
    let mut values = Vec::new();
    let shape = asm.jacobian_values_at(st, &frames, c, &mut values);
    (triplets, values, shape)
}

#[test]
fn values_alone_are_the_triplets_values_in_their_order() {
    // The stepping benchmark's chain after 50 steps of ms (moving, turned nodes: the
    // rotation and angular-velocity columns carry G(g) and ∂(G ġ)/∂g).
    let model = link_chain(10, Vec3::new(0.1, 0.0, 0.0), ConstraintForm::Scaled);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    let settings = NewtonSettings::default();
    initial_derivatives(&asm, &mut st, &settings).unwrap();
    let mut int = Integrator::new(&asm, st, Method::Ms { rho: 0.6 }, 1e-3, settings);
    for _ in 0..50 {
        int.step().unwrap();
    }
    for form in [ConstraintForm::Scaled, ConstraintForm::Plain] {
        let (triplets, values, shape) = both(&asm, &int.state, Coefficients::newton(1e-3, form));
        assert_eq!(triplets.shape, Some(shape));
        // The same arithmetic: bit for bit.
        assert_eq!(triplets.values, values);
        assert!(values.len() > 3000, "{} entries", values.len());
    }
}

/// A spring to ground on node 1's x, y, z (stiffness `K`, rest point `REST`) and a kink:
/// `a max(x, 0)` on the y equilibrium and `a min(x, 0)` on the z equilibrium, continuous at
/// x = 0. Its Jacobian has one entry for the kink, at (y, x) for x > 0 and at (z, x)
/// otherwise: the same count, another position.
struct KinkedSpring;

const K: f64 = 1.0;
const A: f64 = 3.0;
/// Cubic stiffening on x, so that Newton takes several iterations and crosses the kink.
const CUBIC: f64 = 1.0;
/// Rest point: the equilibrium is x = −1 (`K (x − REST_X) + CUBIC x³ = 0`).
const REST: [f64; 3] = [-2.0, 0.25, -0.5];

impl Element for KinkedSpring {
    fn label(&self) -> u32 {
        7
    }
    fn type_name(&self) -> &'static str {
        "kinked spring"
    }
    fn nodes(&self) -> Vec<u32> {
        vec![1]
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        let x = s.node(0).x;
        for k in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: k }, K * (x[k] - REST[k]));
        }
        out.add(Row::Equilibrium { slot: 0, comp: 0 }, CUBIC * x[0].powi(3));
        out.add(Row::Equilibrium { slot: 0, comp: 1 }, A * x[0].max(0.0));
        out.add(Row::Equilibrium { slot: 0, comp: 2 }, A * x[0].min(0.0));
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        let x = s.node(0).x;
        for k in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: k }, Col::Position { slot: 0, comp: k }, K);
        }
        out.add(Row::Equilibrium { slot: 0, comp: 0 }, Col::Position { slot: 0, comp: 0 }, 3.0 * CUBIC * x[0] * x[0]);
        let kinked = if x[0] > 0.0 { 1 } else { 2 };
        out.add(Row::Equilibrium { slot: 0, comp: kinked }, Col::Position { slot: 0, comp: 0 }, A);
    }
}

/// A static node at `(x, 0, 0)`, its orientation held by a prismatic joint to the ground, on
/// the kinked spring.
fn kinked_model(x: f64) -> Model {
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::new(x, 0.0, 0.0), Mat3::identity());
    b.element(Joint::prismatic(1, Anchor::Ground { position: Vec3::zeros(), orientation: Mat3::identity() }, Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() }));
    b.element(KinkedSpring);
    b.build().expect("valid model")
}

#[test]
fn an_element_whose_entries_move_with_the_state_is_assembled_with_positions_again() {
    let c = Coefficients::static_analysis();
    let at = |x: f64| {
        let model = kinked_model(x);
        let asm = Assembler::new(&model);
        let st = State::initial(&model, &asm.dofs);
        both(&asm, &st, c)
    };
    let (right, right_values, right_shape) = at(0.5);
    let (_, other_values, other_shape) = at(0.3);
    let (left, left_values, left_shape) = at(-0.5);
    // Same count of entries either side of the kink, one of them elsewhere.
    assert_eq!(right_values.len(), left_values.len());
    assert_ne!(right.rows, left.rows);
    assert_eq!(right_shape, other_shape);
    assert_ne!(right_shape, left_shape);

    // The LU set up on x = 0.5 takes the values of x = 0.3, not those of x = −0.5.
    let n = right.n;
    let rhs: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
    let mut lu = SparseLu::new();
    lu.solve(&right, &mut rhs.clone()).unwrap();
    let mut x = rhs.clone();
    assert!(!lu.solve_values(n, &left_values, left_shape, &mut x).unwrap());
    assert_eq!(x, rhs, "a refused solve leaves the right-hand side");
    assert!(lu.solve_values(n, &other_values, other_shape, &mut x).unwrap());
    // The same system through its own triplets: the same solution, bit for bit.
    let (other, _, _) = at(0.3);
    let mut reference = rhs.clone();
    SparseLu::new().solve(&other, &mut reference).unwrap();
    assert_eq!(x, reference);
    // And the left side's values through its triplets solve the left side's system.
    let mut y = rhs.clone();
    SparseLu::new().solve(&left, &mut y).unwrap();
    let dense = left.to_dense();
    for i in 0..n {
        let r: f64 = (0..n).map(|k| dense[(i, k)] * y[k]).sum::<f64>() - rhs[i];
        assert!(r.abs() < 1e-12, "residual {r} in row {i}");
    }
}

#[test]
fn newton_across_the_kink_reaches_the_closed_form_equilibrium() {
    // From x = 1 (entry at (y, x)) to the equilibrium x = −1 (entry at (z, x)): closed form
    // x = −1 (K (x + 2) + x³ = 0), y = REST_y − A max(x, 0)/K = 0.25,
    // z = REST_z − A min(x, 0)/K = −0.5 + 3 = 2.5.
    let model = kinked_model(1.0);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    let settings = NewtonSettings { tolerance: 1e-13, increment_tolerance: 0.0, ..NewtonSettings::default() };
    let iterations = static_solution(&asm, &mut st, 1, &settings).unwrap();
    let f = asm.dofs.node_first[0];
    let expected = [-1.0, 0.25, 2.5];
    for k in 0..3 {
        // Newton's tolerance 1e-13 N on unit stiffness: 1e-12 m.
        assert!((st.y[f + k] - expected[k]).abs() < 1e-12, "x[{k}] = {} against {}", st.y[f + k], expected[k]);
    }
    assert!(iterations > 2, "{iterations} iterations: the kink was not crossed during the iteration");
}
