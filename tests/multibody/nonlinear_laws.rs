//! MBDyn's nonlinear constitutive laws in 3-D and 6-D (issue 12, point 3): `nlsf elastic`,
//! `nlsf viscous`, `nlsf viscoelastic` (input manual §nlsf viscoelastic; constltp_nlsf.cc:
//! `f_i = Σ_j k_ij (ε_j − ε_p,j) + f′_i(ε_i − ε_p,i) + Σ_j c_ij ε̇_j + f″_i(ε̇_i) + f_p,i`) and
//! `scalar function elastic isotropic | orthotropic` (ScalarFunctionsImpl.cc: `f_i =
//! F_i(ε_i)`) on the deformable displacement joint and deformable hinge (3-D), the deformable
//! joint and beams (6-D): their Jacobians against finite differences, closed forms (rests where
//! `f(ε) = load`, an undamped swing's energy, a nonlinear damper's decay) and MBDyn 1.7.3's
//! output on the same files.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e, with
//! shared/tools/build-mbdyn.sh), `mbdyn -f tests/mbdyn_files/FILE -o out`, the last rows of
//! `out.mov` (t = 1 s; the files write rotation vectors, `default orientation: orientation
//! vector`, with 16 digits).

use crate::common;

use common::fixtures::Noise;
use common::mbdyn::{assert_jacobians, assert_jacobians_after_run, read_test_file};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::element::drive::ScalarFunction;
use romdyn::element::{Anchor, Beam2, Beam3, BeamNode, DeformableJoint, Element, LawFunctions, LinearViscoelastic, NlsfRod, NodeKinematics, SectionLaw, SectionOrientation};
use romdyn::input::mbdyn::{read_model_text, MbdynModel, SetOverrides};
use romdyn::kinematics::{rotation_vector, Vec3};

/// `F(x) = 10 x + x³`.
fn stiffening() -> ScalarFunction {
    ScalarFunction::Sum(std::sync::Arc::new(ScalarFunction::Multilinear { points: vec![(0.0, 0.0), (1.0, 10.0)], extrapolate: true }), std::sync::Arc::new(ScalarFunction::Pow(3.0)))
}

/// A few functions with nonzero first and second derivatives.
fn some_function(k: usize) -> Option<ScalarFunction> {
    match k % 4 {
        0 => Some(stiffening()),
        1 => Some(ScalarFunction::Exp { multiplier: 0.5, base: std::f64::consts::E, coefficient: 0.8 }),
        2 => None,
        _ => Some(ScalarFunction::Sub(std::sync::Arc::new(ScalarFunction::Pow(3.0)), std::sync::Arc::new(ScalarFunction::Multilinear { points: vec![(-1.0, 2.0), (1.0, -2.0)], extrapolate: true }))),
    }
}

/// Elastic and viscous functions on `dim` components (some `None`).
fn functions(dim: usize, shift: usize, viscous: bool) -> LawFunctions {
    LawFunctions { elastic: (0..dim).map(|i| some_function(i + shift)).collect(), viscous: (0..dim).map(|i| if viscous { some_function(i + shift + 1) } else { None }).collect() }
}

fn node(label: u32, n: &mut Noise) -> Anchor {
    Anchor::Node { label, offset: n.vec(), orientation: n.rotation() }
}

fn ground(n: &mut Noise) -> Anchor {
    Anchor::Ground { position: n.vec(), orientation: n.rotation() }
}

fn law6(n: &mut Noise, viscous: bool, functions: LawFunctions) -> SectionLaw {
    let a = nalgebra::Matrix6::from_fn(|_, _| n.next());
    let v = nalgebra::Matrix6::from_fn(|_, _| n.next());
    let mut law = SectionLaw::viscoelastic(100.0 * (a * a.transpose() + nalgebra::Matrix6::identity()), if viscous { 3.0 * v } else { nalgebra::Matrix6::zeros() }).with_functions(functions);
    law.prestrain = 0.1 * nalgebra::Vector6::from_fn(|_, _| n.next());
    law.prestress = nalgebra::Vector6::from_fn(|_, _| n.next());
    law
}

/// Every element that takes a nonlinear law, with elastic and viscous functions on some
/// components, linear parts, prestrain and prestress: its analytic Jacobian against central
/// differences of its residual at a random state (`common::mbdyn::assert_jacobians`, 1e-6).
#[test]
fn nonlinear_law_jacobians_match_finite_differences() {
    assert_jacobians(|n| {
        let law3 = |n: &mut Noise| LinearViscoelastic { stiffness: 30.0 * n.matrix(), viscosity: 2.0 * n.matrix() };
        let mut e: Vec<Box<dyn Element>> = vec![
            Box::new(DeformableJoint::displacement(1, node(2, n), node(3, n), &law3(n), 0.1 * n.vec(), n.vec()).with_functions(functions(3, 0, true).placed(0, 6))),
            Box::new(DeformableJoint::displacement(2, ground(n), node(2, n), &LinearViscoelastic::isotropic(0.0, 0.0), Vec3::zeros(), Vec3::zeros()).with_functions(functions(3, 1, false).placed(0, 6))),
            Box::new(DeformableJoint::hinge(3, node(2, n), node(3, n), &law3(n), 0.1 * n.vec(), n.vec()).with_functions(functions(3, 2, true).placed(3, 6))),
            Box::new(DeformableJoint::hinge(4, ground(n), node(3, n), &LinearViscoelastic::isotropic(0.0, 0.0), Vec3::zeros(), Vec3::zeros()).with_functions(functions(3, 3, true).placed(3, 6))),
        ];
        let l = law6(n, true, functions(6, 0, true));
        e.push(Box::new(DeformableJoint::new(5, node(2, n), node(3, n), l)));
        let l = law6(n, false, functions(6, 1, false));
        e.push(Box::new(DeformableJoint::new(6, ground(n), node(2, n), l)));
        // Beams between the three nodes, in any reference configuration (it only sets the
        // unstrained state): beam3 with viscous functions, beam2 with elastic ones (romdyn's
        // beam2 takes elastic laws only).
        let bn = |label: u32, n: &mut Noise| BeamNode::new(label, n.vec(), n.rotation(), 0.3 * n.vec()).with_orientation(n.rotation());
        let nodes = [bn(1, n), bn(2, n), bn(3, n)];
        let laws = [law6(n, true, functions(6, 2, true)), law6(n, false, functions(6, 3, true))];
        e.push(Box::new(Beam3::new(7, nodes, [SectionOrientation::FromNodes, SectionOrientation::Given(n.rotation())], laws).unwrap()));
        let nodes = [bn(1, n), bn(2, n), bn(3, n)];
        let laws = [law6(n, false, functions(6, 0, false)), law6(n, false, functions(6, 1, false))];
        e.push(Box::new(Beam3::new(8, nodes, [SectionOrientation::FromNodes, SectionOrientation::FromNodes], laws).unwrap()));
        let nodes = [bn(2, n), bn(3, n)];
        e.push(Box::new(Beam2::new(9, nodes, SectionOrientation::FromNodes, law6(n, false, functions(6, 2, false))).unwrap()));
        // Rods with 1-D nlsf laws, with offsets.
        e.push(Box::new(NlsfRod { label: 10, a: node(2, n), b: node(3, n), length: 0.8, stiffness: 20.0, viscosity: 3.0, prestrain: 0.05, prestress: 2.0, elastic: some_function(0), viscous: some_function(1) }));
        e.push(Box::new(NlsfRod { label: 11, a: ground(n), b: node(2, n), length: 1.3, stiffness: 0.0, viscosity: 0.0, prestrain: 0.0, prestress: 0.0, elastic: some_function(3), viscous: some_function(0) }));
        e
    });
}

/// A nonlinear law's generalized force and tangents are the manual's formula: component by
/// component against a direct evaluation, and the tangents against central differences.
#[test]
fn a_nonlinear_section_law_is_the_manuals_formula() {
    let mut n = Noise(5);
    let law = law6(&mut n, true, functions(6, 0, true));
    let (e, r) = (0.3 * nalgebra::Vector6::from_fn(|_, _| n.next()), nalgebra::Vector6::from_fn(|_, _| n.next()));
    let (f, k, c) = law.evaluate(&e, Some(&r));
    let linear = law.stiffness * (e - law.prestrain) + law.viscosity * r + law.prestress;
    for i in 0..6 {
        let mut expected = linear[i];
        if let Some(g) = &law.functions.elastic[i] {
            expected += g.value(e[i] - law.prestrain[i]);
        }
        if let Some(g) = &law.functions.viscous[i] {
            expected += g.value(r[i]);
        }
        assert!((f[i] - expected).abs() < 1e-12 * (1.0 + expected.abs()), "component {i}: {} against {expected}", f[i]);
    }
    let h = 1e-6;
    for j in 0..6 {
        let d = nalgebra::Vector6::from_fn(|i, _| if i == j { h } else { 0.0 });
        let fd_k = (law.evaluate(&(e + d), Some(&r)).0 - law.evaluate(&(e - d), Some(&r)).0) / (2.0 * h);
        let fd_c = (law.evaluate(&e, Some(&(r + d))).0 - law.evaluate(&e, Some(&(r - d))).0) / (2.0 * h);
        assert!((fd_k - k.column(j)).norm() < 1e-6 * k.norm() && (fd_c - c.column(j)).norm() < 1e-6 * c.norm(), "column {j}");
    }
}

fn ran(m: &MbdynModel) -> (Vec<NodeKinematics>, Vec<u32>) {
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let labels: Vec<u32> = m.model.nodes.iter().map(|n| n.label).collect();
    ((0..labels.len()).map(|i| report.final_state.node_frame(&asm.dofs, i).kin).collect(), labels)
}

/// The final kinematics of the node labelled `label`.
fn at(nodes: &(Vec<NodeKinematics>, Vec<u32>), label: u32) -> NodeKinematics {
    let i = nodes.1.iter().position(|l| *l == label).unwrap_or_else(|| panic!("no node {label}"));
    nodes.0[i].clone()
}

fn close(a: Vec3, b: [f64; 3], tol: f64, what: &str) {
    let b = Vec3::new(b[0], b[1], b[2]);
    assert!((a - b).norm() < tol, "{what}: {a:?} against {b:?} ({:e})", (a - b).norm());
}

/// `1/v² = (1/v₀² + 1) e^(2t) − 1` of `dv/dt = −v − v³`: the velocity and distance at `t`.
fn cubic_damper(v0: f64, t: f64) -> (f64, f64) {
    let a = 1.0 / (v0 * v0) + 1.0;
    let u = (a * (2.0 * t).exp() - 1.0).sqrt();
    (1.0 / u, u.atan() - (1.0 / v0).atan())
}

/// `tests/mbdyn_files/nlsf_displacement.mbd`: deformable displacement joints with `nlsf
/// elastic` (prestrain, prestress), `scalar function elastic orthotropic` and `isotropic`
/// rest where the law equals the load; `nlsf viscoelastic` and `nlsf viscous` dampers brake a
/// mass as `dv/dt = −v − v³`; MBDyn 1.7.3 on the same file.
#[test]
fn nonlinear_displacement_joints_rest_and_brake_as_the_closed_form_and_mbdyn() {
    let mut m = read_test_file("nlsf_displacement.mbd");
    let nodes = ran(&m);
    // Closed forms: Newton's tolerance (1e-10 N) with stiffnesses of 1 to 38 N/m bounds the
    // rests at 1e-9 m.
    close(at(&nodes, 2).x, [1.1, 2.0, 1.0], 1e-9, "node 2 (nlsf elastic, prestrain, prestress)");
    close(at(&nodes, 3).x, [1.0, 2.0, 3.0], 1e-9, "node 3 (orthotropic)");
    close(at(&nodes, 4).x, [1.0, 2.0, 3.0], 1e-9, "node 4 (isotropic)");
    // The damper: ms ρ∞ = 0.6 at h = 1 ms measured 1.87e-6 m, 1.08e-6 m/s from the closed
    // form (the integrator's error); 5e-6 m and 2e-6 m/s bound it. Both dampers, nlsf viscoelastic and nlsf
    // viscous, follow the manual's formula.
    let (v, x) = cubic_damper(2.0, 1.0);
    for label in [5, 6] {
        let k = at(&nodes, label);
        close(k.x, [x, 0.0, 0.0], 5e-6, &format!("node {label} position"));
        close(k.xdot, [v, 0.0, 0.0], 2e-6, &format!("node {label} velocity"));
    }
    // MBDyn 1.7.3: the rests to 1e-15 (node 2: 1.1000000000000001, 2, 0.99999999999999989);
    // node 5 at 7.7185863458460457e-01 m, 3.4844324455845477e-01 m/s. romdyn measured
    // 0.77185863459400 m (9.4e-12 from MBDyn; the same integrator): 1e-10 bounds it.
    close(at(&nodes, 2).x, [1.1000000000000001, 2.0, 0.99999999999999989], 1e-12, "node 2 against MBDyn");
    close(at(&nodes, 3).x, [1.0, 2.0, 3.0], 1e-12, "node 3 against MBDyn");
    close(at(&nodes, 5).x, [7.7185863458460457e-01, 0.0, 0.0], 1e-10, "node 5 against MBDyn");
    close(at(&nodes, 5).xdot, [3.4844324455845477e-01, 0.0, 0.0], 1e-10, "node 5 velocity against MBDyn");
    // Node 6's `nlsf viscous` law has no elastic part: MBDyn 1.7.3 drops its f″ in 3-D and 6-D
    // (constltp_nlsf.cc tests the elastic flag before adding a viscous function; its 1-D law
    // tests the viscous one) and gives the linear damper's 2 (1 − e⁻¹) = 1.2642411891977030 m,
    // 2 e⁻¹ = 7.3575880880342759e-01 m/s; romdyn follows the manual (above), as for node 5.
    let linear = 2.0 * (1.0 - (-1.0f64).exp());
    assert!((at(&nodes, 6).x.x - linear).abs() > 0.4, "node 6 follows MBDyn's dropped term");
    assert_jacobians_after_run(&mut m, None, 0.1);
}

/// `tests/mbdyn_files/nlsf_hinge_joint.mbd`: a deformable hinge with `nlsf elastic` and a
/// deformable joint with a 6-D `nlsf elastic` law (prestrain, prestress, by `reference`) rest
/// where the law equals the load; a body on a 6-D `scalar function elastic isotropic` joint
/// swings keeping its energy; a hinge with `nlsf viscoelastic` brakes a spinning body as
/// `dω/dt = −ω − ω³`; MBDyn 1.7.3 on the same file.
#[test]
fn nonlinear_hinges_and_deformable_joints_rest_swing_and_brake_as_the_closed_form_and_mbdyn() {
    let mut m = read_test_file("nlsf_hinge_joint.mbd");
    let nodes = ran(&m);
    close(rotation_vector(&at(&nodes, 2).r), [1.0, 2.0, 1.0], 1e-9, "node 2 (hinge) rotation");
    close(at(&nodes, 3).x, [1.1, 2.0, 1.0], 1e-9, "node 3 (6-D) position");
    close(rotation_vector(&at(&nodes, 3).r), [1.0, 2.0, 1.0], 1e-9, "node 3 (6-D) rotation");
    // Node 4's energy ½ (|v|² + |ω|²) + V(x) + V(y) + V(θ_z), V = 5 e² + e⁴/4, started at
    // 2.625 J: Crank–Nicolson measured 1.6e-9 J off at t = 1 s (4.5e-8 J at 0.5 s); 1e-6 J
    // bounds it.
    let k = at(&nodes, 4);
    let theta = rotation_vector(&k.r);
    let v = |e: f64| 5.0 * e * e + e.powi(4) / 4.0;
    let energy = 0.5 * (k.xdot.norm_squared() + k.omega.norm_squared()) + v(k.x.x) + v(k.x.y) + v(theta.z);
    assert!((energy - 2.625).abs() < 1e-6, "node 4 energy {energy} J against 2.625 J");
    assert!(k.x.z.abs() < 1e-12 && theta.x.abs() < 1e-12 && theta.y.abs() < 1e-12, "node 4 left its plane: {:?} {theta:?}", k.x);
    // Node 5: the brake's angle and spin, Crank–Nicolson's error measured 1.5e-6 rad.
    let (w, angle) = cubic_damper(2.0, 1.0);
    let k5 = at(&nodes, 5);
    close(rotation_vector(&k5.r), [0.0, 0.0, angle], 5e-6, "node 5 angle");
    close(k5.omega, [0.0, 0.0, w], 2e-6, "node 5 spin");
    // MBDyn 1.7.3 (its Newton stops within 1e-10 of the load, 4.4e-12 rad from the rest).
    close(rotation_vector(&at(&nodes, 2).r), [1.0000000000044011, 2.0000000000001394, 9.9999999999927214e-01], 1e-10, "node 2 against MBDyn");
    close(at(&nodes, 3).x, [1.1000000000000887, 2.0000000000020672, 1.0000000000000022], 1e-10, "node 3 against MBDyn");
    close(k.x, [-1.0223827054123363e-02, -3.7342368636752790e-03, 0.0], 1e-12, "node 4 against MBDyn");
    close(theta, [0.0, 0.0, -4.1618126526091731e-02], 1e-9, "node 4 rotation against MBDyn");
    close(k.xdot, [-9.9947722739866851e-01, -4.9986053520106100e-01, 0.0], 1e-12, "node 4 velocity against MBDyn");
    // romdyn measured 0.77185895961 rad, 3.3e-10 from MBDyn: 1e-9 bounds it.
    close(rotation_vector(&k5.r), [0.0, 0.0, 7.7185895994057041e-01], 1e-9, "node 5 against MBDyn");
    close(k5.omega, [0.0, 0.0, 3.4844341400535894e-01], 1e-9, "node 5 spin against MBDyn");
    // dCoef 0.1: the differences move ẏ by about 1e-5 (with 1e-3, by 1e-3, and the cubic
    // damper's truncation error, h², reaches 7e-7).
    assert_jacobians_after_run(&mut m, None, 0.1);
}

/// `tests/mbdyn_files/nlsf_beams.mbd`: cantilevers of beam3 (`nlsf elastic`) and beam2
/// (`scalar function elastic isotropic`, `orthotropic`) stretched by a tip force and bent by
/// a tip couple; MBDyn 1.7.3 on the same file.
#[test]
fn nonlinear_beams_stretch_and_bend_as_the_closed_form_and_mbdyn() {
    let mut m = read_test_file("nlsf_beams.mbd");
    let nodes = ran(&m);
    // Stretched: the strain is uniform, 100 e + e³ = 20.008 (beam3) and 10 e + e³ = 2.008
    // (beam2 orthotropic), e = 0.2, tips at 1.2 m to Newton's tolerance.
    close(at(&nodes, 9).x, [1.2, 0.0, 0.0], 1e-10, "beam3 stretched");
    close(at(&nodes, 39).x, [1.2, 3.0, 0.0], 1e-10, "beam2 stretched");
    // Bent by a couple: uniform moment, curvature κ + κ³ = 0.625 (beam3) and 10 κ + κ³ = 5.125
    // (beam2), κ = 0.5 1/m. The beam2 chain is exact for it: each element's chord keeps its
    // length ℓ = 1/8 m (no axial or shear force) along its middle frame, turned by κℓ per
    // element, so the tip is Σ ℓ (cos, sin)((j + ½) κ ℓ) and turned by κ = 0.5 rad.
    let (kappa, l) = (0.5f64, 0.125f64);
    let tip = (0..8).fold(Vec3::new(0.0, 2.0, 0.0), |p, j| p + l * Vec3::new(((j as f64 + 0.5) * kappa * l).cos(), ((j as f64 + 0.5) * kappa * l).sin(), 0.0));
    let c = at(&nodes, 29);
    close(c.x, [tip.x, tip.y, tip.z], 1e-10, "beam2 bent");
    close(rotation_vector(&c.r), [0.0, 0.0, kappa], 1e-10, "beam2 tip rotation");
    // The beam3 chain approximates the arc (sin κ/κ, (1 − cos κ)/κ) from its root: measured
    // 3.3e-7 m off (four elements of 0.125 rad); 1e-6 m bounds it.
    let b = at(&nodes, 19);
    close(b.x, [kappa.sin() / kappa, 1.0 + (1.0 - kappa.cos()) / kappa, 0.0], 1e-6, "beam3 bent");
    close(rotation_vector(&b.r), [0.0, 0.0, kappa], 1e-7, "beam3 tip rotation");
    // MBDyn 1.7.3: stretched tips 1.2000000000000002 and 1.2 m; bent, beam3 tip
    // (9.5885100838405457e-01, 1.2448348585216877) m, 5.0000000027035840e-01 rad, beam2 tip
    // (9.5900669908770630e-01, 2.2448760604834535) m, 4.9999859187585599e-01 rad. MBDyn's beams
    // accumulate the curvature step by step (docs/src/mbdyn/beams.md; tests/multibody/beam_rotation.rs), romdyn's
    // are functions of the nodes' state: measured 2.6e-7 m, 4.2e-8 rad (beam3) and 1.3e-6 m,
    // 1.4e-6 rad (beam2, whose own closed form romdyn meets to 1e-10 above) apart.
    close(at(&nodes, 9).x, [1.2000000000000002, 0.0, 0.0], 1e-12, "beam3 stretched against MBDyn");
    close(at(&nodes, 39).x, [1.2, 3.0, 0.0], 1e-12, "beam2 stretched against MBDyn");
    close(b.x, [9.5885100838405457e-01, 1.2448348585216877, 0.0], 5e-7, "beam3 bent against MBDyn");
    close(rotation_vector(&b.r), [0.0, 0.0, 5.0000000027035840e-01], 1e-7, "beam3 rotation against MBDyn");
    close(c.x, [9.5900669908770630e-01, 2.2448760604834535, 0.0], 2e-6, "beam2 bent against MBDyn");
    close(rotation_vector(&c.r), [0.0, 0.0, 4.9999859187585599e-01], 2e-6, "beam2 rotation against MBDyn");
    assert_jacobians_after_run(&mut m, None, 0.05);
}

/// `tests/mbdyn_files/nlsf_beam_damper.mbd`: a tip mass on a beam3 whose `nlsf viscoelastic`
/// law damps the axial strain rate as `ε̇ + ε̇³`: the massless beam's strain is uniform, so
/// the tip follows `ẍ = −(100 (x − 1) + ẋ + ẋ³)`, integrated here with RK4 at 1e-5 s (its
/// error far below 1e-10); MBDyn 1.7.3 on the same file.
#[test]
fn a_beam_with_a_nonlinear_damper_follows_its_equation_of_motion_and_mbdyn() {
    let mut m = read_test_file("nlsf_beam_damper.mbd");
    let nodes = ran(&m);
    let f = |x: f64, v: f64| (v, -(100.0 * (x - 1.0) + v + v.powi(3)));
    let (mut x, mut v, h) = (1.0f64, 1.0f64, 1e-5);
    for _ in 0..100_000 {
        let k1 = f(x, v);
        let k2 = f(x + h / 2.0 * k1.0, v + h / 2.0 * k1.1);
        let k3 = f(x + h / 2.0 * k2.0, v + h / 2.0 * k2.1);
        let k4 = f(x + h * k3.0, v + h * k3.1);
        x += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
    }
    // ms ρ∞ = 0.6 at h = 1 ms measured 3.6e-6 m, 3.5e-5 m/s from it (ω h = 1e-2).
    let tip = at(&nodes, 3);
    close(tip.x, [x, 0.0, 0.0], 1e-5, "tip position");
    close(tip.xdot, [v, 0.0, 0.0], 1e-4, "tip velocity");
    close(at(&nodes, 2).x, [0.5 * tip.x.x, 0.0, 0.0], 1e-12, "middle node (uniform strain)");
    // MBDyn 1.7.3: tip at 9.7338274511777945e-01 m, −4.0666741369027071e-01 m/s, 1.8e-5 m and
    // 2.8e-4 m/s from romdyn's 0.97340104293 m, −0.40638510959 m/s. Not the nonlinear law: with
    // the cubic term removed (a linear viscoelastic beam) the two differ alike, 1.66e-5 m and
    // 2.6e-4 m/s (MBDyn 0.96759002804 m, romdyn 0.96760659256 m, RK4 0.96760204469 m): MBDyn
    // 1.2e-5 m from the equation of motion, romdyn 4.5e-6 m; at h = 0.1 ms the two differ by
    // 1.7e-6 m, so MBDyn's difference is first order in h (its static middle node's velocity).
    // 2.5e-5 m and 4e-4 m/s bound it.
    close(tip.x, [9.7338274511777945e-01, 0.0, 0.0], 2.5e-5, "tip against MBDyn");
    close(tip.xdot, [-4.0666741369027071e-01, 0.0, 0.0], 4e-4, "tip velocity against MBDyn");
    assert_jacobians_after_run(&mut m, None, 0.1);
}

/// What is still refused names the law and where it is accepted: nonlinear laws on elements
/// that take linear ones only, `nlsf` on a rod with a prestrain that changes in time, and the
/// bare `scalar function elastic` in 3-D and 6-D (MBDyn 1.7.3 registers it in 1-D only).
#[test]
fn nonlinear_laws_where_romdyn_or_mbdyn_has_none_are_refused_by_name() {
    let nodes = "structural: 1, static, null, eye, null, null; structural: 2, dynamic, 1., 0., 0., eye, null, null;";
    let cases = [
        ("joint: 2, invariant deformable hinge, 1, 2, nlsf elastic, eye, null, null, \"f\";", "constitutive law 'nlsf elastic' is supported by romdyn on the deformable displacement joint"),
        ("joint: 2, viscous body, 2, null, nlsf viscous, eye, null, null, null, null, null, \"f\";", "'nlsf viscous' is supported by romdyn on"),
        ("joint: 2, rod, 1, 2, from nodes, nlsf elastic, 1., \"f\", prestrain, sine, 0., 1., 1., forever, 0.;", "prestrain that changes in time on an 'nlsf elastic' law"),
        ("joint: 2, deformable displacement joint, 1, null, 2, null, scalar function elastic, \"f\";", "in 1-D only"),
        ("joint: 2, deformable joint, 1, null, 2, null, scalar function elastic, \"f\";", "in 6-D write 'scalar function elastic isotropic'"),
        ("joint: 2, deformable hinge, 1, 2, scalar function elastic, \"f\";", "in 3-D write 'scalar function elastic isotropic'"),
        ("joint: 2, deformable displacement joint, 1, null, 2, null, nlsf elastic, eye, \"f\", null;", "expected"),
    ];
    for (element, message) in cases {
        let text = common::mbdyn::file("structural nodes: 2; joints: 1;", nodes, element).replace("begin: elements;", "scalar function: \"f\", pow, 3.;\nbegin: elements;");
        let err = read_model_text(&text, std::path::Path::new("m.mbd"), &SetOverrides::default()).err().unwrap_or_else(|| panic!("accepted: {element}")).to_string();
        assert!(err.contains(message) && err.starts_with("m.mbd:"), "{element}: {err}");
    }
}

/// `tests/mbdyn_files/nlsf_rod.mbd`: a rod with `nlsf elastic` (prestrain, prestress) rests
/// where the law equals the load, one with `nlsf viscous` brakes a mass as `dv/dt = −v − v³`;
/// MBDyn 1.7.3 on the same file.
#[test]
fn nlsf_rods_rest_and_brake_as_the_closed_form_and_mbdyn() {
    let mut m = read_test_file("nlsf_rod.mbd");
    let nodes = ran(&m);
    // (ε − .1) + (ε − .1)³ + .101 = 2.101: ε = 1.1, Newton's tolerance bounds it.
    close(at(&nodes, 2).x, [2.1, 0.0, 0.0], 1e-9, "node 2 (nlsf elastic rod)");
    // The brake, from x = 1 m: ms ρ∞ = 0.6 at h = 1 ms, 1.8e-6 m from the closed form.
    let (v, x) = cubic_damper(2.0, 1.0);
    close(at(&nodes, 3).x, [1.0 + x, 2.0, 0.0], 5e-6, "node 3 (nlsf viscous rod)");
    close(at(&nodes, 3).xdot, [v, 0.0, 0.0], 2e-6, "node 3 velocity");
    // MBDyn 1.7.3: node 2 at 2.1000000000000001 m; node 3 at 1.7718586345940497 m,
    // 3.4844324456015929e-01 m/s. romdyn measured 2e-15 m from it: 1e-12 bounds it.
    close(at(&nodes, 2).x, [2.1000000000000001, 0.0, 0.0], 1e-12, "node 2 against MBDyn");
    close(at(&nodes, 3).x, [1.7718586345940497, 2.0, 0.0], 1e-12, "node 3 against MBDyn");
    close(at(&nodes, 3).xdot, [3.4844324456015929e-01, 0.0, 0.0], 1e-12, "node 3 velocity against MBDyn");
    assert_jacobians_after_run(&mut m, None, 0.1);
}

/// A 1-D `scalar function elastic` law on a `constitutive law:` card is the inline one (a rod
/// by `reference`), and on a deformable axial joint it is `nlsf elastic, null, F` (MBDyn's
/// 1-D `isotropic` and `orthotropic` read one function alike).
#[test]
fn one_d_scalar_function_laws_by_reference_and_on_axial_joints_are_the_inline_laws() {
    let nodes = "structural: 1, static, null, eye, null, null; structural: 2, dynamic, 1., .2, 0., eye, .1, .2, .3, .4, .5, .6;";
    let with = |element: &str| {
        common::mbdyn::file("structural nodes: 2; joints: 2;", nodes, &format!("joint: 1, clamp, 1, node, node; {element}"))
            .replace("begin: elements;", "scalar function: \"f\", exp, coefficient, 2., .5;\nconstitutive law: 7, 1, scalar function elastic, \"f\";\nbegin: elements;")
    };
    let inline = common::mbdyn::read(&with("joint: 2, rod, 1, 2, from nodes, scalar function elastic, \"f\";")).model;
    common::mbdyn::assert_same_physics(&with("joint: 2, rod, 1, 2, from nodes, reference, 7;"), inline);
    let nlsf = || common::mbdyn::read(&with("joint: 2, deformable axial joint, 1, 2, nlsf elastic, null, \"f\";")).model;
    for law in ["scalar function elastic isotropic, \"f\"", "scalar function elastic orthotropic, \"f\"", "reference, 7"] {
        common::mbdyn::assert_same_physics(&with(&format!("joint: 2, deformable axial joint, 1, 2, {law};")), nlsf());
    }
}
