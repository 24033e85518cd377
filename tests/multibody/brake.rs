//! MBDyn's `brake` (input manual, "Elements", §Brake; brake.cc, issue 12): the modlugre
//! friction moment of a revolute hinge with the normal force given by a drive and no
//! constraint of its own. Its analytic Jacobian against central finite differences of its
//! residual (stick, the breakaway transition, slip and against the sliding direction; the
//! drive above and below the preload; node 1 a node or the ground), a spinning wheel braked
//! to rest against the closed form and MBDyn 1.7.3, and the reader.

use crate::common;
use common::mbdyn::test_file as path;

use common::fixtures::{smooth_model, Noise};
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::drive::Drive;
use romdyn::element::{Anchor, Joint, RevoluteHingeFriction};
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::kinematics::Vec3;
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;

#[test]
fn brake_jacobian_matches_finite_differences() {
    // z as a multiple of z_ss = μ(|v|) sign(v)/σ₀: stick, mid-transition, slip, and against
    // the sliding direction; the normal force a drive of time (a ramp through the check's
    // time, 0.37 s) above the preload, or below it (the preload acts).
    let regimes = [0.3, 0.8, 1.7, -0.8];
    let radius = 0.7;
    let mut signs = Vec::new();
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        for ground in [false, true] {
            for (normal, preload) in [(Drive::Ramp { slope: 4.0, t0: 0.0, t1: 1.0, v0: 1.0 }, 0.5), (Drive::Const(0.1), 2.0)] {
                for (seed, &factor) in regimes.iter().enumerate() {
                    let mut n = Noise(977 + seed as u64);
                    let mut b = ModelBuilder::new();
                    b.dynamic_node(1, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec());
                    let hinge = n.rotation();
                    let a = if ground { Anchor::Ground { position: n.vec(), orientation: hinge } } else { Anchor::Node { label: 1, offset: n.vec(), orientation: hinge } };
                    let bside = Anchor::Node { label: 2, offset: n.vec(), orientation: n.rotation() };
                    b.element(RevoluteHingeFriction::brake(Joint::revolute_hinge(7, a, bside), radius, preload, smooth_model(), normal.clone()));
                    b.constraint_form(form);
                    let model = b.build().unwrap();
                    let asm = Assembler::new(&model);
                    let mut st = State::initial(&model, &asm.dofs);
                    let mut noise = Noise(31 + seed as u64);
                    for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
                        *x += 0.3 * noise.next();
                    }
                    // The brake's one unknown, its friction state, in the chosen regime.
                    let z = asm.dofs.element_first[0];
                    assert!(asm.dofs.is_state(z) && !asm.dofs.is_multiplier(z));
                    let kin = |label: u32| st.node_frame(&asm.dofs, model.node_index(label).unwrap()).kin;
                    let (e3, w1) = if ground { (hinge.column(2).into_owned(), Vec3::zeros()) } else { ((kin(1).r * hinge).column(2).into_owned(), kin(1).omega) };
                    let v = radius * (w1 - kin(2).omega).dot(&e3);
                    let mu = 0.6 - 0.15 * v.abs();
                    assert!(mu > 0.1, "|v| = {v}: off the line of μ");
                    signs.push(v > 0.0);
                    st.y[z] = factor * mu * v.signum() / 3.0;
                    st.yp[z] = 0.3 * noise.next();
                    let checked = check_jacobians(&asm, &st, 0.37, form);
                    assert!(!checked.is_empty());
                    for w in checked {
                        assert!(w.relative_error < 1e-6, "{form:?} ground {ground} preload {preload} z/z_ss {factor}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
                    }
                }
            }
        }
    }
    assert!(signs.contains(&true) && signs.contains(&false), "{signs:?}");
}

/// brake.mbd run to `final_time`: node 2's turned angle about z [rad] and its angular
/// velocity about z [rad/s].
fn wheel(final_time: f64) -> (f64, f64) {
    let text = std::fs::read_to_string(path("brake.mbd")).unwrap();
    let mut m = read_model_text(&text, &path("brake.mbd"), &SetOverrides::new()).unwrap_or_else(|e| panic!("{e}"));
    m.problem.final_time = final_time;
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert!((report.final_state.t - final_time).abs() < 1e-9, "ended at {}", report.final_state.t);
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin;
    (kin.r[(1, 0)].atan2(kin.r[(0, 0)]), kin.omega.z)
}

#[test]
fn a_spinning_wheel_is_braked_to_rest_as_the_closed_form_and_mbdyn() {
    // The file's numbers: J = 0.05 kg m², W0 = 10 rad/s, R = 0.5 m, μ = 0.3, N rising as a
    // half cosine to 20 N over T = 0.1 s. Closed form (friction coefficient μ in slip):
    // ω(T) = W0 − μ R N T/(2 J) = 7 rad/s, θ(T) = W0 T − (μ R/J)(N/2)(T²/2 − 2T²/π²) =
    // 0.910793 rad; then ω̇ = −μ R N/J = −60 rad/s² until it stops at t = 0.2167 s, turned
    // by ω(T)² J/(2 μ R N) = 0.408333 rad more: θ = 1.319126 rad, and it rests on its
    // bristles. Differences: the ms integrator on the 0.1 s cosine (5.5e-4 rad/s on ω(T),
    // measured; 1e-3 below) and the bristles' deflection μ/σ₀ = 1.5e-4 m on R, which the
    // wheel gives back when it sticks (3e-4 rad; measured 1.8e-4 rad from the closed form,
    // 4e-4 below).
    let (theta_t, omega_t) = wheel(0.1);
    let (theta, omega) = wheel(0.5);
    assert!((omega_t - 7.0).abs() < 1e-3, "ω(T) = {omega_t}, closed form 7");
    let theta_closed = 1.0 - 3.0 * 10.0 * (0.005 - 0.02 / std::f64::consts::PI.powi(2)) + 49.0 / 120.0;
    assert!((theta - theta_closed).abs() < 4e-4, "θ = {theta}, closed form {theta_closed}");
    assert!(omega.abs() < 1e-6, "ω = {omega}: not at rest");
    // MBDyn 1.7.3 (built from source) on the same file with `output precision: 16;` added to
    // the control data, .mov node 2: at t = 0.1 s θ_z 5.2186197983167119e+01 deg, ω_z
    // 7.0005533916552221 rad/s; at t = 0.5 s θ_z 7.5569864935858917e+01 deg, ω_z
    // 5.4906113053843544e-08 rad/s. Measured: 2.4e-9 rad and 1e-12 rad/s apart (Newton's
    // tolerance; 1e-8 rad and 1e-9 rad/s below).
    let deg = std::f64::consts::PI / 180.0;
    for (got, mbdyn, tolerance) in [(theta_t, 5.2186197983167119e+01 * deg, 1e-8), (omega_t, 7.0005533916552221, 1e-9), (theta, 7.5569864935858917e+01 * deg, 1e-8), (omega, 5.4906113053843544e-08, 1e-9)] {
        assert!((got - mbdyn).abs() < tolerance, "romdyn {got}, MBDyn {mbdyn}");
    }
}

#[test]
fn brake_reader_refuses_what_mbdyn_refuses() {
    let text = std::fs::read_to_string(path("brake.mbd")).unwrap();
    let friction = "\t\tfriction, R,\n\t\t\tpreload, 1e-10,\n\t\t\tmodlugre, 2000., 2.8, 0., .71, \"mu\",\n\t\t\tsimple,\n";
    assert!(text.contains(friction));
    let cases = [
        // joint.cc: "missing keyword \"friction\"".
        (text.replace(friction, ""), "brake: expected 'friction'"),
        (text.replace("friction, R,", "friction, -1.,"), "friction radius"),
        // No normal force (an empty field, `simple, ;`, would read as 0, as MBDyn reads it).
        (text.replace("\t\t\tsimple,\n\t\tcosine, 0., pi/.1, N/2., half, 0.;", "\t\t\tsimple;"), "expected a drive caller"),
    ];
    common::mbdyn::assert_refused("brake.mbd", &text, &cases);
}
