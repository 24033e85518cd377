//! Screw friction (issue 12): MBDyn's `modlugre` friction with the `screw joint` shape
//! function on a `screw` (screwjoint.cc, friction.h `ScrewJointSh_c`). Its analytic
//! Jacobian against central finite differences of its residual (stick, the breakaway
//! transition, slip and a deflection against the sliding direction; both signs of the
//! reaction; node 1 a node or the ground; both constraint forms), a platform on a vertical
//! screw against the closed form (slip: the angular acceleration of the energy balance;
//! stick: the self-locking friction coefficient) and MBDyn 1.7.3, and the reader.

use crate::common;
use common::mbdyn::test_file as path;

use common::fixtures::{smooth_model, Noise};
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::{Anchor, Screw, ScrewFriction};
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;

/// The thread: radius 0.7 m, half thread angle 0.4 rad, pitch 0.3 m.
const RADIUS: f64 = 0.7;
const HALF_THREAD_ANGLE: f64 = 0.4;
const PITCH: f64 = 0.3;

#[test]
fn screw_friction_jacobian_matches_finite_differences() {
    let regimes = [0.3, 0.8, 0.7, 0.95, 1.7, -0.8];
    let tan_pitch = PITCH / (std::f64::consts::TAU * RADIUS);
    let sliding_radius = RADIUS * (1.0 + tan_pitch * tan_pitch).sqrt();
    let mut signs = Vec::new();
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        for ground in [false, true] {
            for lambda in [2.5, -1.5] {
                for (seed, &factor) in regimes.iter().enumerate() {
                    let mut n = Noise(9090 + seed as u64);
                    let mut b = ModelBuilder::new();
                    b.dynamic_node(1, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec());
                    let axis = n.rotation();
                    let a = if ground { Anchor::Ground { position: n.vec(), orientation: axis } } else { Anchor::Node { label: 1, offset: n.vec(), orientation: axis } };
                    let bside = Anchor::Node { label: 2, offset: n.vec(), orientation: n.rotation() };
                    let screw = Screw { label: 7, a, b: bside, pitch: PITCH, theta0: 0.4, d0: 0.2 };
                    b.element(ScrewFriction::new(screw, smooth_model(), RADIUS, HALF_THREAD_ANGLE));
                    b.constraint_form(form);
                    let model = b.build().unwrap();
                    let asm = Assembler::new(&model);
                    let mut st = State::initial(&model, &asm.dofs);
                    let mut noise = Noise(71 + seed as u64);
                    for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
                        *x += 0.3 * noise.next();
                    }
                    let first = asm.dofs.element_first[0];
                    st.y[first] += 2.0 * std::f64::consts::TAU;
                    st.y[first + 1] = lambda;
                    let kin = |label: u32| st.node_frame(&asm.dofs, model.node_index(label).unwrap()).kin;
                    let (e, w1) = if ground { (axis.column(2).into_owned(), romdyn::kinematics::Vec3::zeros()) } else { ((kin(1).r * axis).column(2).into_owned(), kin(1).omega) };
                    let v = lambda.signum() * sliding_radius * e.dot(&(kin(2).omega - w1));
                    let mu = 0.6 - 0.15 * v.abs();
                    assert!(mu > 0.1, "|v| = {v}: off the line of μ");
                    signs.push(v > 0.0);
                    st.y[first + 2] = factor * mu * v.signum() / 3.0;
                    st.yp[first + 2] = 0.3 * noise.next();
                    assert!(asm.dofs.is_state(first + 2));
                    for w in check_jacobians(&asm, &st, 0.37, form) {
                        assert!(w.relative_error < 1e-6, "{form:?} ground {ground} λ {lambda} z/z_ss {factor}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
                    }
                }
            }
        }
    }
    assert!(signs.contains(&true) && signs.contains(&false), "{signs:?}");
}

/// screw_friction.mbd with `MU` and the final time set: the final time, node 2's height,
/// vertical velocity, turned angle about z [rad] and angular velocity about z [rad/s].
fn platform(mu: f64, final_time: f64) -> (f64, f64, f64, f64, f64) {
    let text = std::fs::read_to_string(path("screw_friction.mbd")).unwrap();
    let mut m = read_model_text(&text, &path("screw_friction.mbd"), &SetOverrides::from([("MU".to_string(), mu)])).unwrap_or_else(|e| panic!("{e}"));
    m.problem.final_time = final_time;
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = st.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin;
    (st.t, kin.x.z, kin.xdot.z, kin.r[(1, 0)].atan2(kin.r[(0, 0)]), kin.omega.z)
}

/// The thread of screw_friction.mbd: lead p/(2π), tan β, sec γ, and the shape coefficient.
fn thread() -> (f64, f64, f64, impl Fn(f64) -> f64) {
    let (p, r, gamma) = (0.109, 0.05, 30f64.to_radians());
    let lead = p / std::f64::consts::TAU;
    let t = p / (std::f64::consts::TAU * r);
    let s = 1.0 / gamma.cos();
    (lead, t, s, move |f: f64| r * f * s * (1.0 + t * t) / (f * s * t - 1.0))
}

#[test]
fn a_platform_screws_down_against_thread_friction_as_the_closed_form_and_mbdyn() {
    // M = 100 kg, J = 1 kg m², lead ℓ = p/(2π): the screw's reaction does no work, so
    // (M ℓ² + J) θ̈ = −M g ℓ + M_f, with the friction moment M_f = c(f) λ on the platform
    // and λ = M (g + ℓ θ̈) its axial balance: θ̈ = M g (c − ℓ)/(M ℓ² + J − c M ℓ). Sliding
    // down (θ̇ < 0, λ > 0, v < 0) the friction coefficient settles at −μ = −0.1: θ̈ =
    // −10.710 rad/s², constant once the bristles' transient is over. ω(1) − ω(0.5) is
    // 6.4e-7 relative off it in romdyn and in MBDyn 1.7.3 alike (−10.7103216 rad/s² both, from
    // the .mov below and at t = 0.5 s −5.3912622981331744 rad/s): the orientation is
    // integrated in Gibbs parameters per step (0.01 rad a step at 10 rad/s), exact for a
    // constant ġ, not for a constant ω̇; 2e-6 below.
    let (lead, _, _, c) = thread();
    let (m, j, g) = (100.0, 1.0, 9.81);
    let shape = c(-0.1);
    let closed = m * g * (shape - lead) / (m * lead * lead + j - shape * m * lead);
    let (t1, _, _, _, w1) = platform(0.1, 0.4995);
    let (t2, z2, zd2, th2, w2) = platform(0.1, 0.9995);
    assert!((t1 - 0.5).abs() < 1e-9 && (t2 - 1.0).abs() < 1e-9, "ended at {t1}, {t2}");
    assert!(((w2 - w1) / 0.5 - closed).abs() < 2e-6 * closed.abs(), "θ̈ = {}, closed form {closed}", (w2 - w1) / 0.5);
    // MBDyn 1.7.3 (built from source) on the same file (MU = .1, `output precision: 16;`
    // added to the control data), .mov node 2 at t = 1 s: z 9.0647452477735457e-01 m, ż
    // −1.8643133450598781e-01 m/s, θ_z 5.1108522200437150e+01 deg (past −180°), ω_z
    // −1.0746423107773925e+01 rad/s. The tolerances: Newton's (1e-8) over the transient.
    let theta_mbdyn = (5.1108522200437150e+01f64 - 360.0).to_radians();
    let turned = (th2 - theta_mbdyn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    for (got, mbdyn, tolerance) in [(z2, 9.0647452477735457e-01, 1e-8), (zd2, -1.8643133450598781e-01, 1e-8), (w2, -1.0746423107773925e+01, 1e-7)] {
        assert!((got - mbdyn).abs() < tolerance, "romdyn {got}, MBDyn {mbdyn}");
    }
    assert!(turned.abs() < 1e-7, "θ_z: romdyn {th2}, MBDyn {theta_mbdyn} (mod 2π)");
}

#[test]
fn a_platform_on_a_self_locking_thread_rests_on_its_bristles_as_the_closed_form_and_mbdyn() {
    // MU = 0.9: holding the platform takes c(f) = ℓ, f* = −ℓ/(sec γ (r (1 + tan²β) − ℓ tan β))
    // = −0.30047 (the thread self-locks for μ above it), below the breakaway κ μ = 0.639
    // even at the first overshoot (2 f*), so α = 0 throughout and the bristle deflection is
    // z = f*/σ₀ = (r/cos β) θ: θ = −2.8387e-3 rad. The bristles' oscillation has decayed to
    // 3e-8 rad/s by t = 4 s (MBDyn alike); 1e-9 rad below. What is left of it moves the
    // friction coefficient by its angular acceleration over λ c'(f): z by 4.4e-11 m
    // (3e-7 relative), 1e-10 below.
    let (lead, t, s, _) = thread();
    let r = 0.05;
    let f_star = -lead / (s * (r * (1.0 + t * t) - lead * t));
    let closed = f_star / 2000.0 / (r * (1.0 + t * t).sqrt());
    let text = std::fs::read_to_string(path("screw_friction.mbd")).unwrap();
    let mut m = read_model_text(&text, &path("screw_friction.mbd"), &SetOverrides::from([("MU".to_string(), 0.9)])).unwrap_or_else(|e| panic!("{e}"));
    m.problem.final_time = 3.9995;
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = st.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin;
    let theta = kin.r[(1, 0)].atan2(kin.r[(0, 0)]);
    let screw = (0..m.model.elements.len()).find(|&e| m.model.elements[e].type_name() == "screw").unwrap();
    let z = st.y[asm.dofs.element_first[screw] + 2];
    assert!((theta - closed).abs() < 1e-9, "θ = {theta}, closed form {closed}");
    assert!((z - f_star / 2000.0).abs() < 1e-10, "z = {z}, closed form {}", f_star / 2000.0);
    // MBDyn 1.7.3 (same file, MU = .9, final time 4, output precision 16), .mov node 2 at
    // t = 4 s: θ_z −1.6264750426760513e-01 deg.
    let mbdyn = (-1.6264750426760513e-01f64).to_radians();
    assert!((theta - mbdyn).abs() < 1e-9, "romdyn {theta}, MBDyn {mbdyn}");
}

#[test]
fn screw_friction_reader_refuses_what_romdyn_cannot_honour() {
    let text = std::fs::read_to_string(path("screw_friction.mbd")).unwrap();
    let shape = "screw joint,\n\t\t\t\tradius, R,\n\t\t\t\thalf thread angle, GAMMA;";
    assert!(text.contains(shape));
    let cases = [
        (text.replace(shape, "simple;"), "MBDyn's screw joint accepts only 'screw joint'"),
        (text.replace("modlugre, 2000., 2.8, 0., .71, \"mu\",", "discrete coulomb, \"mu\","), "friction model 'discrete coulomb' is not supported"),
        (text.replace("half thread angle, GAMMA;", "half thread angle, 2.;"), "half thread angle must be below pi/2"),
        (text.replace("radius, R,", "radius, 0.,"), "thread radius"),
    ];
    common::mbdyn::assert_refused("screw_friction.mbd", &text, &cases);
}
