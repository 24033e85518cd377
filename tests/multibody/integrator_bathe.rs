//! MBDyn's `Bathe` integrator (later MBDyn versions, stepsol.cc `TunableBatheSolver`; issue
//! 12 point 3) against the closed forms of the ρ∞-Bathe method: a linear oscillator stepped
//! by romdyn equals the method's amplification matrix applied step by step, and a pendulum
//! converges to a reference solution at second order; and its `hybrid, implicit euler`.

use crate::common;

use common::models::{pendulum, G, J, L, M};
use nalgebra::{Matrix2, Vector2};
use romdyn::analysis::run;
use romdyn::dae::{Assembler, State};
use romdyn::element::{Anchor, DeformableDisplacement, LinearViscoelastic, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;
use romdyn::solve::{initial_derivatives, initial_derivatives_with, Integrator, Method, NewtonSettings};

/// The ρ∞-Bathe method's amplification matrix for `ẏ = A y` over one step `h`, from the
/// published sub-steps (G. Noh, K. J. Bathe, "The Bathe time integration method with
/// controllable spectral radius: the ρ∞-Bathe method", Computers & Structures 212 (2019)
/// 299–310): the trapezoidal rule over `γh`, then `y₁ = y₀ + h (q₀ ẏ₀ + q₁ ẏ_γ + q₂ ẏ₁)` with
/// `q₁ = (ρ∞ + 1)/(2γ(ρ∞ − 1) + 4)`, `q₀ = (γ − 1) q₁ + ½`, `q₂ = −γ q₁ + ½`, and MBDyn's
/// `γ = (2 − √(2 + 2ρ∞))/(1 − ρ∞)` (½ at ρ∞ = 1), for which both sub-steps have the same
/// effective matrix.
fn amplification(a: &Matrix2<f64>, h: f64, rho: f64) -> Matrix2<f64> {
    let gamma = if rho == 1.0 { 0.5 } else { (2.0 - (2.0 + 2.0 * rho).sqrt()) / (1.0 - rho) };
    let q1 = (rho + 1.0) / (2.0 * gamma * (rho - 1.0) + 4.0);
    let (q0, q2) = ((gamma - 1.0) * q1 + 0.5, -gamma * q1 + 0.5);
    let i = Matrix2::identity();
    let first = (i - 0.5 * gamma * h * a).try_inverse().unwrap() * (i + 0.5 * gamma * h * a);
    (i - h * q2 * a).try_inverse().unwrap() * (i + h * q0 * a + h * q1 * a * first)
}

fn spectral_radius(m: &Matrix2<f64>) -> f64 {
    m.complex_eigenvalues().iter().map(|l| l.norm()).fold(0.0, f64::max)
}

#[test]
fn the_amplification_closed_form_has_the_published_properties() {
    // What the test's closed form must satisfy, checked from scratch: its spectral radius at
    // ωh → ∞ is ρ∞ (the method's defining property), it is second-order accurate (one step
    // of an undamped oscillator off exp(A h) by O(h³)), and ρ∞ = 1 conserves the amplitude.
    for rho in [0.0, 0.3, 0.6, 1.0] {
        let a = Matrix2::new(0.0, 1.0, -1.0, 0.0);
        let r = spectral_radius(&amplification(&a, 1e7, rho));
        assert!((r - rho).abs() < 1e-6, "ρ∞ = {rho}: spectral radius {r} at ωh = 1e7");
        let exact = |h: f64| Matrix2::new(h.cos(), h.sin(), -h.sin(), h.cos());
        let local = |h: f64| (amplification(&a, h, rho) - exact(h)).norm();
        let ratio = local(0.02) / local(0.01);
        assert!((ratio - 8.0).abs() < 0.1, "ρ∞ = {rho}: local error ratio {ratio} for h halved (third order: 8)");
    }
    let r = spectral_radius(&amplification(&Matrix2::new(0.0, 1.0, -1.0, 0.0), 0.7, 1.0));
    assert!((r - 1.0).abs() < 1e-14, "ρ∞ = 1: {r}");
}

/// A mass `m` on a spring `k` and damper `c` to the ground along x (its rotations free and
/// never loaded), released from `x₀` at `v₀`.
fn oscillator(m: f64, k: f64, c: f64, x0: f64, v0: f64) -> romdyn::model::Model {
    let ground = Anchor::Ground { position: Vec3::zeros(), orientation: Mat3::identity() };
    let node = Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() };
    let mut b = ModelBuilder::new();
    b.dynamic_node(1, Vec3::new(x0, 0.0, 0.0), Mat3::identity(), Vec3::new(v0, 0.0, 0.0), Vec3::zeros())
        .element(RigidBody::new(1, 1, m, Vec3::zeros(), 0.1 * Mat3::identity()))
        .element(DeformableDisplacement { label: 2, a: ground, b: node, law: LinearViscoelastic { stiffness: k * Mat3::identity(), viscosity: c * Mat3::identity() }, rest: Vec3::zeros() });
    b.build().unwrap()
}

#[test]
fn a_linear_oscillator_steps_as_the_amplification_matrix() {
    // The node's unknowns x and β (momentum) obey ẋ = β/m, β̇ = −k x − c β/m: y = (x, β),
    // ẏ = A y. A linear problem: Newton solves each sub-step exactly (to the tolerance
    // 1e-13), whatever the predictor, so romdyn's steps are the amplification matrix's to
    // rounding: 1e-12 relative over 40 steps, at ωh = 0.35 and at ωh = 7 (where ρ∞ rules).
    let (m, k, c, x0, v0) = (2.0, 100.0, 1.0, 0.1, -0.3);
    let a = Matrix2::new(0.0, 1.0 / m, -k, -c / m);
    let settings = NewtonSettings { tolerance: 1e-13, increment_tolerance: 1e-15, max_iterations: 10, ..Default::default() };
    for rho in [0.0, 0.6, 1.0] {
        for h in [0.05, 1.0] {
            let model = oscillator(m, k, c, x0, v0);
            let asm = Assembler::new(&model);
            let mut st = State::initial(&model, &asm.dofs);
            initial_derivatives_with(&asm, &mut st, &settings, 1e-9).unwrap();
            let f = asm.dofs.node_first[0];
            let mut y = Vector2::new(st.y[f], st.y[f + 6]);
            assert!((y - Vector2::new(x0, m * v0)).norm() < 1e-14);
            let amp = amplification(&a, h, rho);
            let mut int = Integrator::new(&asm, st, Method::Bathe { rho }, h, settings);
            for step in 1..=40 {
                int.step().unwrap();
                y = amp * y;
                let got = Vector2::new(int.state.y[f], int.state.y[f + 6]);
                let scale = Vector2::new(x0, m * v0).norm();
                assert!((got - y).norm() < 1e-12 * scale, "ρ∞ = {rho}, h = {h}, step {step}: romdyn {got:?}, amplification matrix {y:?}");
                // The rotations are never loaded: they stay at rest.
                assert!(int.state.node_frame(&asm.dofs, 0).kin.omega.norm() < 1e-15);
            }
        }
    }
}

/// The pendulum's angle from the downward vertical at `t_end`, released from rest at
/// `theta0`, stepped by `method` with step `h`.
fn pendulum_angle(theta0: f64, method: Method, h: f64, t_end: f64) -> f64 {
    let model = pendulum(theta0, false, ConstraintForm::Scaled);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    let settings = NewtonSettings { tolerance: 1e-12, ..Default::default() };
    initial_derivatives(&asm, &mut st, &settings).unwrap();
    let mut int = Integrator::new(&asm, st, method, h, settings);
    let steps = (t_end / h).round() as usize;
    for _ in 0..steps {
        int.step().unwrap();
    }
    assert!((int.state.t - t_end).abs() < 1e-9);
    let f = asm.dofs.node_first[1];
    int.state.y[f].atan2(-int.state.y[f + 1])
}

/// `θ̈ = −(m g L / I_O) sin θ`, `I_O = J + m L²`, from rest at `theta0`: classical RK4 with
/// 100000 steps (error about 1e-16 rad).
fn reference_angle(theta0: f64, t_end: f64) -> f64 {
    let w2 = M * G * L / (J + M * L * L);
    let f = |s: [f64; 2]| [s[1], -w2 * s[0].sin()];
    let n = 100_000;
    let h = t_end / n as f64;
    let mut s = [theta0, 0.0];
    for _ in 0..n {
        let k1 = f(s);
        let k2 = f([s[0] + 0.5 * h * k1[0], s[1] + 0.5 * h * k1[1]]);
        let k3 = f([s[0] + 0.5 * h * k2[0], s[1] + 0.5 * h * k2[1]]);
        let k4 = f([s[0] + h * k3[0], s[1] + h * k3[1]]);
        for i in 0..2 {
            s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    s[0]
}

#[test]
fn a_pendulum_converges_at_second_order() {
    // The paper's pendulum released at 1 rad, its angle at t = 1 s against the reference:
    // halving h divides the error by 4 (second order). Measured ratios from h = 20 ms down to
    // 0.625 ms: ρ∞ = 0: 4.44, 4.24, 4.12, 4.06, 4.03; ρ∞ = 0.6: 5.03, 4.72, 4.42, 4.22, 4.12
    // (the next order fading); ρ∞ = 1: 4.004, 4.001, 4.0002, …. Here h = 5, 2.5, 1.25 ms,
    // ratios within 3.7–4.5, and the error at 5 ms below 2e-5 rad (measured 1.7e-5).
    let (theta0, t_end) = (1.0, 1.0);
    let reference = reference_angle(theta0, t_end);
    for rho in [0.0, 0.6, 1.0] {
        let errors: Vec<f64> = [0.005, 0.0025, 0.00125].iter().map(|&h| (pendulum_angle(theta0, Method::Bathe { rho }, h, t_end) - reference).abs()).collect();
        let ratios = [errors[0] / errors[1], errors[1] / errors[2]];
        eprintln!("ρ∞ = {rho}: errors {errors:?} rad, ratios {ratios:.3?}");
        assert!(errors[0] < 2e-5, "ρ∞ = {rho}: error {:e} at h = 5 ms", errors[0]);
        for r in ratios {
            assert!((3.7..4.5).contains(&r), "ρ∞ = {rho}: error ratio {r} for h halved (errors {errors:?})");
        }
    }
}

#[test]
fn with_rho_one_a_step_is_two_trapezoidal_half_steps() {
    // ρ∞ = 1: γ = ½, (b₀, b₁, b₂) = h (¼, ½, ¼), the trapezoidal rule over each half of the
    // step: the pendulum after 1 s with h = 10 ms as Crank–Nicolson with 5 ms (measured
    // 1.09205886e-4 and 1.09205906e-4 rad from the reference at 20 ms and 10 ms), to the
    // Newton tolerance.
    let bathe = pendulum_angle(1.0, Method::Bathe { rho: 1.0 }, 0.01, 1.0);
    let trapezoidal = pendulum_angle(1.0, Method::CrankNicolson, 0.005, 1.0);
    assert!((bathe - trapezoidal).abs() < 1e-9, "{bathe} against {trapezoidal}");
}


#[test]
fn hybrid_implicit_euler_starts_with_a_trapezoidal_step() {
    // MBDyn's `hybrid, implicit euler` (later MBDyn, solver.cc): a Crank–Nicolson first step,
    // `(I − hA/2)⁻¹ (I + hA/2)`, then implicit Euler, `(I − hA)⁻¹`; the oscillator as those
    // matrices to 1e-12 relative (the plain `implicit euler` differs from the first step on).
    let (m, k, c, x0, v0) = (2.0, 100.0, 1.0, 0.1, -0.3);
    let a = Matrix2::new(0.0, 1.0 / m, -k, -c / m);
    let h: f64 = 0.05;
    let i: Matrix2<f64> = Matrix2::identity();
    let trapezoidal = (i - 0.5 * h * a).try_inverse().unwrap() * (i + 0.5 * h * a);
    let euler = (i - h * a).try_inverse().unwrap();
    let settings = NewtonSettings { tolerance: 1e-13, increment_tolerance: 1e-15, max_iterations: 10, ..Default::default() };
    for (method, first) in [(Method::HybridImplicitEuler, trapezoidal), (Method::ImplicitEuler, euler)] {
        let model = oscillator(m, k, c, x0, v0);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        initial_derivatives_with(&asm, &mut st, &settings, 1e-9).unwrap();
        let f = asm.dofs.node_first[0];
        let mut y = Vector2::new(st.y[f], st.y[f + 6]);
        let mut int = Integrator::new(&asm, st, method, h, settings);
        for step in 1..=20 {
            int.step().unwrap();
            y = if step == 1 { first * y } else { euler * y };
            let got = Vector2::new(int.state.y[f], int.state.y[f + 6]);
            assert!((got - y).norm() < 1e-12 * Vector2::new(x0, m * v0).norm(), "{method:?}, step {step}: romdyn {got:?}, closed form {y:?}");
        }
    }
}

/// `θ̈ = (m g L / I_O) cos θ` from rest at θ = 0 (θ downward from +x): the angle at `t_end`,
/// classical RK4 with 100000 steps.
fn horizontal_release(w2: f64, t_end: f64) -> f64 {
    let f = |s: [f64; 2]| [s[1], w2 * s[0].cos()];
    let n = 100_000;
    let h = t_end / n as f64;
    let mut s = [0.0, 0.0];
    for _ in 0..n {
        let k1 = f(s);
        let k2 = f([s[0] + 0.5 * h * k1[0], s[1] + 0.5 * h * k1[1]]);
        let k3 = f([s[0] + 0.5 * h * k2[0], s[1] + 0.5 * h * k2[1]]);
        let k4 = f([s[0] + h * k3[0], s[1] + h * k3[1]]);
        for i in 0..2 {
            s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    s[0]
}

/// The file's node 2 angle below +x at its final time, with the method line replaced.
fn file_pendulum_angle(method: &str) -> (f64, romdyn::kinematics::Vec3) {
    let path = common::mbdyn::test_file("bathe_pendulum.mbd");
    let text = std::fs::read_to_string(&path).unwrap().replace("method: Bathe, .6;", &format!("method: {method};"));
    let m = common::mbdyn::read(&text);
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!((report.final_state.t - 1.0).abs() < 1e-12);
    let asm = Assembler::new(&m.model);
    let x = report.final_state.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin.x;
    ((-x.y).atan2(x.x), x)
}

#[test]
fn an_mbdyn_file_with_bathe_runs_as_the_reference_and_hybrid_ms_as_ms() {
    // bathe_pendulum.mbd (`method: Bathe, .6`, h = 1 ms): the angle after 1 s against the
    // reference (I_O = 1.001 kg m²; measured error −3.06e-6 rad, the method's at this step,
    // `ms, .6`: −6.96e-6 rad), within 6e-6 rad, and the point stays 1 m from the hinge (to
    // the Newton tolerance on the scaled rows).
    let reference = horizontal_release(9.81 / 1.001, 1.0);
    let (bathe, x) = file_pendulum_angle("Bathe, .6");
    let (ms, _) = file_pendulum_angle("ms, .6");
    eprintln!("Bathe {:.3e} rad, ms {:.3e} rad from the reference", bathe - reference, ms - reference);
    assert!((bathe - reference).abs() < 6e-6, "Bathe: {bathe} against {reference}");
    assert!((x.norm() - 1.0).abs() < 1e-9);
    // `hybrid, ms, .6`: every unknown with ms after the Crank–Nicolson first step, which is
    // MBDyn's `ms` (the same first step): the same numbers bit for bit.
    let (hybrid, _) = file_pendulum_angle("hybrid, ms, .6");
    assert_eq!(hybrid, ms);
}
