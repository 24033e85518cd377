//! Revolute hinge friction (issue 12): MBDyn's `modlugre` friction on a `revolute hinge`
//! (input manual, §Revolute hinge; planej.cc). Its analytic Jacobian against central finite
//! differences of its residual (stick, the breakaway transition, slip and a deflection
//! against the sliding direction; below and above the preload; node 1 a node or the ground;
//! both constraint forms), a wheel turned by a couple on its axle against the closed form
//! (stick: turned by C/(σ₀ N R²) on its bristles; slip: angular acceleration (C − μ N R)/J;
//! the stick's bristle mode) and MBDyn 1.7.3, and the reader.

use crate::common;
use common::mbdyn::test_file as path;

use common::fixtures::{smooth_model, Noise};
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::{Anchor, Joint, RevoluteHingeFriction};
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::kinematics::Vec3;
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;

#[test]
fn revolute_hinge_friction_jacobian_matches_finite_differences() {
    // z as a multiple of z_ss = μ(|v|) sign(v)/σ₀: stick, mid-transition (α = ½ at
    // (1 + κ)/2 = 0.8), slip, and against the sliding direction (α = 0).
    let regimes = [0.3, 0.8, 0.7, 0.95, 1.7, -0.8];
    let radius = 0.7;
    let mut signs = Vec::new();
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        for ground in [false, true] {
            for (lambda_scale, preload) in [(3.0, 0.5), (0.1, 2.0)] {
                for (seed, &factor) in regimes.iter().enumerate() {
                    let mut n = Noise(4242 + seed as u64);
                    let mut b = ModelBuilder::new();
                    b.dynamic_node(1, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec());
                    let hinge = n.rotation();
                    let a = if ground { Anchor::Ground { position: n.vec(), orientation: hinge } } else { Anchor::Node { label: 1, offset: n.vec(), orientation: hinge } };
                    let bside = Anchor::Node { label: 2, offset: n.vec(), orientation: n.rotation() };
                    b.element(RevoluteHingeFriction::new(Joint::revolute_hinge(7, a, bside), radius, preload, smooth_model()));
                    b.constraint_form(form);
                    let model = b.build().unwrap();
                    let asm = Assembler::new(&model);
                    let mut st = State::initial(&model, &asm.dofs);
                    let mut noise = Noise(57 + seed as u64);
                    for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
                        *x += 0.3 * noise.next();
                    }
                    let first = asm.dofs.element_first[0];
                    for k in 0..5 {
                        st.y[first + k] = lambda_scale * noise.next();
                    }
                    // The sliding velocity at this state, and z in the chosen regime.
                    let kin = |label: u32| st.node_frame(&asm.dofs, model.node_index(label).unwrap()).kin;
                    let (e3, w1) = if ground { (hinge.column(2).into_owned(), Vec3::zeros()) } else { ((kin(1).r * hinge).column(2).into_owned(), kin(1).omega) };
                    let v = radius * (w1 - kin(2).omega).dot(&e3);
                    let mu = 0.6 - 0.15 * v.abs();
                    assert!(mu > 0.1, "|v| = {v}: off the line of μ");
                    signs.push(v > 0.0);
                    st.y[first + 5] = factor * mu * v.signum() / 3.0;
                    st.yp[first + 5] = 0.3 * noise.next();
                    assert!(asm.dofs.is_state(first + 5) && !asm.dofs.is_multiplier(first + 5));
                    for w in check_jacobians(&asm, &st, 0.37, form) {
                        assert!(w.relative_error < 1e-6, "{form:?} ground {ground} λ·{lambda_scale} z/z_ss {factor}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
                    }
                }
            }
        }
    }
    // Both sliding directions were checked (f_s and its derivative change sign with v).
    assert!(signs.contains(&true) && signs.contains(&false), "{signs:?}");
}

/// revolute_hinge_friction.mbd with the couple `C`, inertia `J` and the final time set; the
/// final time, node 2's turned angle about z [rad] and angular velocity about z [rad/s].
fn wheel(couple: f64, inertia: f64, final_time: f64) -> (f64, f64, f64) {
    let text = std::fs::read_to_string(path("revolute_hinge_friction.mbd")).unwrap();
    let set = SetOverrides::from([("C".to_string(), couple), ("J".to_string(), inertia)]);
    let mut m = read_model_text(&text, &path("revolute_hinge_friction.mbd"), &set).unwrap_or_else(|e| panic!("{e}"));
    m.problem.final_time = final_time;
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = st.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin;
    (st.t, kin.r[(1, 0)].atan2(kin.r[(0, 0)]), kin.omega.z)
}

#[test]
fn a_wheel_turned_past_breakaway_spins_up_as_the_closed_form_and_mbdyn() {
    // M = 10 kg, N = M g = 98.1 N, μ = 0.3, R = 0.05 m: the friction moment μ N R = 1.4715
    // N m; C = 2 N m, J = 0.5 kg m²: after the bristles' transient the friction coefficient
    // is μ (σ₂ = 0, ż = 0), so ω̇ = (C − μ N R)/J = 1.057 rad/s², constant; the ms
    // integrator is exact for it: ω(2) − ω(1) to Newton's tolerance (1e-6 N m on 0.5 kg m²
    // over 1 s: 2e-6 rad/s; measured 1e-12).
    let (t1, th1, w1) = wheel(2.0, 0.5, 0.9995);
    let (t2, th2, w2) = wheel(2.0, 0.5, 1.9995);
    assert!((t1 - 1.0).abs() < 1e-9 && (t2 - 2.0).abs() < 1e-9, "ended at {t1}, {t2}");
    let a = (2.0 - 0.3 * 98.1 * 0.05) / 0.5;
    assert!((w2 - w1 - a).abs() < 1e-8, "ω(2) − ω(1) = {}, closed form {a}", w2 - w1);
    // The angle: each step integrates the orientation's Gibbs parameters measured from the
    // previous step's orientation, exact for constant ġ, not for a constant ω̇ (the angle is
    // 2 atan(g/2)): 8.5e-7 rad over the second (0.4 rad/s² … 2.2 rad/s at h = 1e-3 s).
    assert!((th2 - th1 - w1 - a / 2.0).abs() < 2e-6, "θ(2) − θ(1) = {}, closed form {}", th2 - th1, w1 + a / 2.0);
    // MBDyn 1.7.3 (built from source) on the same file (C = 2, `output precision: 16;`
    // added to the control data), .mov node 2 at t = 1 s: θ_z 3.4752323639640530e+01 deg,
    // ω_z 1.1363526461759659; t = 2 s: 1.3014140223887460e+02 deg, 2.1933526461758390.
    // The two part in the bristles' first milliseconds, within Newton's tolerance: ω by
    // 5.4e-9 rad/s from then on (1e-8 below), which the angle integrates (2.7e-8 rad at
    // t = 1 s, 3.3e-8 at 2 s; 5e-8 below).
    let deg = std::f64::consts::PI / 180.0;
    for (got, mbdyn, tolerance) in [(th1, 3.4752323639640530e+01 * deg, 5e-8), (w1, 1.1363526461759659, 1e-8), (th2, 1.3014140223887460e+02 * deg, 5e-8), (w2, 2.1933526461758390, 1e-8)] {
        assert!((got - mbdyn).abs() < tolerance, "romdyn {got}, MBDyn {mbdyn}");
    }
}

#[test]
fn a_wheel_turned_below_breakaway_sticks_on_its_bristles_as_the_closed_form_and_mbdyn() {
    // C = 0.4 N m, J = 0.01 kg m²: the bristle deflection C/(σ₀ N R) stays below the breakaway
    // deflection κ μ/σ₀ even at the first overshoot (2 C = 0.8 < κ μ N R = 1.045 N m), so
    // the wheel never slips and rests where the bristles hold C: θ = C/(σ₀ N R²) =
    // 8.1549e-4 rad. The bristle oscillation (σ₀ N R²/J = (221 rad/s)², damping ratio
    // σ₁ N R²/(2 √(σ₀ N R² J)) = 0.155) has decayed by t = 2 s; what is left is the
    // integration noise within the tolerance (ω about 1e-7 rad/s in romdyn and MBDyn
    // alike, both 2e-6 relative off θ), hence 3e-6 relative.
    let (_, theta, omega) = wheel(0.4, 0.01, 1.9995);
    let closed = 0.4 / (2000.0 * 98.1 * 0.05 * 0.05);
    assert!((theta - closed).abs() < 3e-6 * closed, "θ = {theta}, closed form {closed}");
    assert!(omega.abs() < 1e-6, "ω = {omega}");
    // MBDyn 1.7.3 (same file, C = 0.4, J = .01, output precision 16), .mov node 2 at t = 2 s:
    // θ_z 4.6724378454168533e-02 deg (.jnt friction moment −0.39999 N m); the two differ by
    // the noise above (measured 5e-8 deg).
    let mbdyn = 4.6724378454168533e-02 * std::f64::consts::PI / 180.0;
    assert!((theta - mbdyn).abs() < 3e-6 * closed, "romdyn {theta}, MBDyn {mbdyn}");
}

#[test]
fn a_sticking_wheel_linearizes_to_the_bristle_spring_and_damper() {
    // C = 0.4 N m, J = 0.01 kg m², at rest in stick (α = 0) at t = 1.9 s: the linearized
    // friction is the torsional bristle spring k = σ₀ N R² and damper c = σ₁ N R² about the
    // axle, so the wheel's mode is λ = −c/(2J) ± j √(k/J − (c/2J)²) (closed form). At the
    // file's tolerance the normal force carries the integration noise (see
    // tests/multibody/joint_friction.rs), so the tolerance is 1e-10 here and the closed form holds to
    // 1e-9 (the eigensolver's accuracy); the eigenanalysis names the dependence.
    let text = std::fs::read_to_string(path("revolute_hinge_friction.mbd")).unwrap();
    let changed = text.replace("\tfinal time: 2.;", "\tfinal time: 2.;\n\teigenanalysis: 1.9, parameter, 1.e-3;").replace("\ttolerance: 1e-6;", "\ttolerance: 1e-10;");
    assert!(changed.contains("eigenanalysis") && changed.contains("1e-10"));
    let set = SetOverrides::from([("C".to_string(), 0.4), ("J".to_string(), 0.01)]);
    let m = read_model_text(&changed, &path("revolute_hinge_friction.mbd"), &set).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let e = &report.eigenanalyses[0];
    assert!(e.non_smooth.is_empty(), "{:?}", e.non_smooth);
    assert!(e.reaction_dependent.len() == 1 && e.reaction_dependent[0].starts_with("revolute hinge 2: its friction moment"), "{:?}", e.reaction_dependent);
    let (n, r, j): (f64, f64, f64) = (98.1, 0.05, 0.01);
    let (k, c) = (2000.0 * n * r * r, 2.8 * n * r * r);
    let expected = romdyn::c64::new(-c / (2.0 * j), (k / j - (c / (2.0 * j)).powi(2)).sqrt());
    let found = *e.dynamic.iter().filter(|l| l.im > 1.0).min_by(|a, b| (**a - expected).norm().total_cmp(&(**b - expected).norm())).unwrap_or_else(|| panic!("no oscillating mode in {:?}", e.dynamic));
    assert!((found - expected).norm() < 1e-9 * expected.norm(), "λ = {found}, closed form {expected} ({:e} relative)", (found - expected).norm() / expected.norm());
}

#[test]
fn revolute_hinge_friction_reader_refuses_what_romdyn_cannot_honour() {
    let text = std::fs::read_to_string(path("revolute_hinge_friction.mbd")).unwrap();
    let model = "modlugre, 2000., 2.8, 0., .71, \"mu\",\n\t\t\tsimple;";
    assert!(text.contains(model));
    let cases = [
        (text.replace(model, "discrete coulomb, \"mu\";"), "friction model 'discrete coulomb' is not supported"),
        (text.replace(model, "modlugre, 2000., 2.8, 0., .71, \"mu\", simple plane hinge, .1;"), "shape function 'simple plane hinge' on a 'revolute hinge' joint is not supported by romdyn (MBDyn 1.7.3 runs it"),
        (text.replace("friction, R,", "friction, -1.,"), "friction radius"),
        (text.replace("\t\tfriction, R,\n", "\t\tfriction,\n"), "friction radius"),
    ];
    common::mbdyn::assert_refused("revolute_hinge_friction.mbd", &text, &cases);
}
