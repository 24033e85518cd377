//! One 3-node beam element (issue 36 point 4: the 1000-element cantilever's hot spot): its
//! residual, and its residual and Jacobian together (what a Newton iteration with a new
//! factorization asks of each element), for both rotation updates and for an elastic and a
//! viscoelastic section law, on a bent, twisted and moving state.
//! `cargo bench --bench beam_element`.

use nalgebra::{Matrix6, Vector6};
use romdyn::element::{Beam3, BeamNode, BeamUpdate, Col, Element, ElementState, JacobianSink, Latched, NodeKinematics, ResidualSink, Row, SectionLaw, SectionOrientation};
use romdyn::kinematics::{gibbs_rotation, Mat3, Vec3};

fn main() {
    divan::main();
}

/// Three nodes with their kinematics, the time and a latched history.
struct Nodes {
    nodes: [NodeKinematics; 3],
    latched: Option<Latched>,
}

impl ElementState for Nodes {
    fn node(&self, slot: usize) -> &NodeKinematics {
        &self.nodes[slot]
    }
    fn multiplier(&self, _k: usize) -> f64 {
        0.0
    }
    fn time(&self) -> f64 {
        0.0
    }
    fn gravity(&self) -> Vec3 {
        Vec3::zeros()
    }
    fn load_factor(&self) -> f64 {
        1.0
    }
    fn latched(&self) -> Option<&(dyn std::any::Any + Send + Sync)> {
        self.latched.as_deref()
    }
}

/// Sums what it receives (so that nothing is optimized away).
#[derive(Default)]
struct Sum(f64);

impl ResidualSink for Sum {
    fn add(&mut self, _row: Row, value: f64) {
        self.0 += value;
    }
}

impl JacobianSink for Sum {
    fn add(&mut self, _row: Row, _col: Col, value: f64) {
        self.0 += value;
    }
}

/// A 0.1 m beam along x (the bench cantilever's element length is 1 mm; the size does not
/// change the work) with EA = GA = 1e8 N, GJ = EJ = 1e3 N m², viscous when asked.
fn beam(update: BeamUpdate, viscous: bool) -> Beam3 {
    let node = |label, x: f64| BeamNode::new(label, Vec3::new(x, 0.0, 0.0), Mat3::identity(), Vec3::zeros());
    let stiffness = Matrix6::from_diagonal(&Vector6::new(1e8, 1e8, 1e8, 1e3, 1e3, 1e3));
    let law = if viscous { SectionLaw::viscoelastic(stiffness, 1e-3 * stiffness) } else { SectionLaw::elastic(stiffness) };
    let beam = Beam3::new(1, [node(1, 0.0), node(2, 0.05), node(3, 0.1)], [SectionOrientation::Given(Mat3::identity()), SectionOrientation::Given(Mat3::identity())], [law.clone(), law]).unwrap();
    beam.with_update(update).unwrap()
}

/// The nodes bent, twisted and moving; the incremental update's history latched from the
/// initial configuration.
fn state(beam: &Beam3) -> Nodes {
    let moved = |i: usize| {
        let s = i as f64;
        NodeKinematics {
            x: Vec3::new(0.05 * s, 1e-3 * s * s, -2e-4 * s),
            r: gibbs_rotation(&Vec3::new(0.01 * s, -0.003 * s, 0.02 * s)),
            xdot: Vec3::new(0.1, -0.2 * s, 0.05),
            omega: Vec3::new(0.3 * s, 0.1, -0.2),
        }
    };
    let initial = Nodes { nodes: std::array::from_fn(|i| NodeKinematics { x: Vec3::new(0.05 * i as f64, 0.0, 0.0), r: Mat3::identity(), xdot: Vec3::zeros(), omega: Vec3::zeros() }), latched: None };
    let mut now = Nodes { nodes: std::array::from_fn(moved), latched: None };
    now.latched = beam.events().and_then(|e| e.latch(&now, &initial));
    now
}

const CASES: [(&str, BeamUpdate, bool); 3] = [("incremental", BeamUpdate::Incremental, false), ("path-independent", BeamUpdate::PathIndependent, false), ("viscous", BeamUpdate::PathIndependent, true)];

fn case(name: &str) -> (Beam3, Nodes) {
    let (_, update, viscous) = CASES.iter().find(|c| c.0 == name).copied().unwrap();
    let beam = beam(update, viscous);
    let st = state(&beam);
    (beam, st)
}

#[divan::bench(args = ["incremental", "path-independent", "viscous"])]
fn residual(bencher: divan::Bencher, name: &str) {
    let (beam, st) = case(name);
    bencher.bench_local(|| {
        let mut sum = Sum::default();
        beam.residual(&st, &mut sum);
        sum.0
    });
}

#[divan::bench(args = ["incremental", "path-independent", "viscous"])]
fn residual_and_jacobian(bencher: divan::Bencher, name: &str) {
    let (beam, st) = case(name);
    bencher.bench_local(|| {
        let mut sum = Sum::default();
        beam.residual(&st, &mut sum);
        beam.jacobian(&st, &mut sum);
        sum.0
    });
}
