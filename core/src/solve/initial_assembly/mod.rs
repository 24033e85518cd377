//! MBDyn's initial assembly (dataman2.cc, `DataManager::InitialJointAssembly`): before the
//! run, every node's position, orientation, velocity and angular velocity is moved the least,
//! in the sense of penalty springs, so that the joints hold.
//!
//! MBDyn's unknowns are each node's `x`, `g` (`R = R(g) R₀`), `v`, `ω` and each joint's
//! reaction `λ` and its derivative `λ̇`; its equations (residuals in romdyn's sign):
//!
//! ```text
//! k_p (x − x₀) + f_x(q, λ) = 0,   k_p g + f_θ(q, λ) = 0,   Φ(q, t) = 0              positions
//! k_v (v − v₀) + ḟ_x = 0,   k_v (ω − ω₀) + ḟ_θ = 0,   Φ̇ = Φ_/q u + Φ_/t = 0          velocities
//! ```
//!
//! with `f` the joints' reactions plus, on the position rows only, the elastic forces of
//! deformable joints, rods and beams (vehj*.cc, rodj.cc, beam.cc: `InitialAssRes`), and
//! `ḟ = f_/q u + f_/λ λ̇ + f_/t` the reactions' time derivative (spherj.cc: "derivate delle
//! equazioni di equilibrio"). Bodies, forces and gravity take no part (MBDyn's default).
//! The position rows do not depend on `u` except through viscous deformable elements, and
//! the velocity rows are linear in `(u, λ̇)` at given `(q, λ)`: romdyn alternates a Newton
//! step on `(q, λ)` and the exact solution of the velocity rows, and stops with MBDyn's test
//! `sqrt(|F|² / (1 + |X|²)) ≤ tolerance` on all rows and unknowns, after at most `max
//! iterations` steps (the default, 1, accepts models that need at most one).
//!
//! With `omega rotates: yes`, `ω₀` is MBDyn's `R₀ Rᵀ ω₀` (dataman2.cc, `RDelta*wPrev`).
//! A velocity-level constraint (a constraint row with velocity entries: `linear velocity`,
//! `angular velocity`, `axial rotation`'s spin) has only its velocity row, its reaction on
//! the velocity rows (drvj.cc, `LinearVelocityJoint::InitialAssRes`).

use super::forward_difference::forward_derivatives;
use crate::dae::{SparseLu, State, Triplets};
use crate::element::NodeKinematics;
use crate::kinematics::{gibbs_g, gibbs_rotation, Mat3, Vec3};
use crate::model::{InitialAssembly, Model, NodeAssembly};
use crate::element::UnknownKind;

mod rows;
use rows::{Ctx, Jacobian, Layout, Residual, Unknowns, VelocityProbe};

/// What the initial assembly did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AssemblyReport {
    /// Newton steps (0: the file's configuration already passed MBDyn's test).
    pub iterations: usize,
    /// MBDyn's test `sqrt(|F|² / (1 + |X|²))` at the end.
    pub test: f64,
    /// Largest change of a node's position [m], rotation [rad], velocity [m/s] and angular
    /// velocity [rad/s] from the values written in the file.
    pub moved_position: f64,
    pub moved_rotation: f64,
    pub moved_velocity: f64,
    pub moved_angular_velocity: f64,
}

/// Why the initial assembly stopped.
#[derive(Clone, Debug, thiserror::Error)]
pub enum AssemblyError {
    #[error("initial assembly did not converge in {iterations} iteration(s) (control data 'max iterations'): MBDyn's test sqrt(|F|²/(1+|X|²)) = {test:.3e} is above the tolerance {tolerance:.3e}; the worst equation is {worst} ({value:.3e}); the joints cannot be made to hold near the configuration written in the file (deformable joints, rods and beams also pull the nodes in the assembly), or need more iterations")]
    NotConverged { iterations: usize, test: f64, tolerance: f64, worst: String, value: f64 },
    #[error("initial assembly: the Newton matrix is singular at iteration {iteration} (redundant joints, or a node no joint or penalty holds)")]
    Singular { iteration: usize },
    #[error("initial assembly diverged at iteration {iteration}: the residual is not finite ({detail})")]
    Diverged { iteration: usize, detail: String },
    #[error("{element}: its constraint {constraint} is violated by {value:.3e} in the configuration written in the file, and control data says 'skip initial joint assembly' (without it, MBDyn's initial assembly, which romdyn runs, would make the joint hold)")]
    Violated { element: String, constraint: String, value: f64 },
}

struct Problem<'m> {
    layout: Layout<'m>,
    /// Whether each row is a velocity-level constraint.
    velocity_rows: Vec<bool>,
    settings: Vec<NodeAssembly>,
    x0: Vec<Vec3>,
    r0: Vec<Mat3>,
    v0: Vec<Vec3>,
    w0: Vec<Vec3>,
    t: f64,
}

impl Problem<'_> {
    fn kinematics(&self, u: &Unknowns) -> Vec<NodeKinematics> {
        (0..self.layout.nodes()).map(|i| NodeKinematics { x: u.x[i], r: gibbs_rotation(&u.g[i]) * self.r0[i], xdot: u.v[i], omega: u.w[i] }).collect()
    }

    fn element_residual(&self, k: usize, kin: &[NodeKinematics], lambda: &[f64], t: f64, f: &mut [f64]) {
        let (slots, first) = (&self.layout.slots[k], self.layout.first[k]);
        let m = self.layout.element(k).multipliers().len();
        let ctx = Ctx { model: self.layout.model, kin, slots, scalars: &self.layout.scalars[k], multipliers: &lambda[first - 6 * self.layout.nodes()..][..m], t };
        self.layout.element(k).residual(&ctx, &mut Residual { slots, first, f });
    }

    fn element_jacobian(&self, k: usize, kin: &[NodeKinematics], lambda: &[f64], g_matrix: Option<&[Mat3]>, out: &mut Triplets) {
        let (slots, first) = (&self.layout.slots[k], self.layout.first[k]);
        let m = self.layout.element(k).multipliers().len();
        let ctx = Ctx { model: self.layout.model, kin, slots, scalars: &self.layout.scalars[k], multipliers: &lambda[first - 6 * self.layout.nodes()..][..m], t: self.t };
        self.layout.element(k).jacobian(&ctx, &mut Jacobian { slots, first, g_matrix, velocity_rows: &self.velocity_rows, out });
    }

    /// Position rows and constraint rows at `u`.
    fn position_residual(&self, u: &Unknowns) -> Vec<f64> {
        let kin = self.kinematics(u);
        let mut f = vec![0.0; self.layout.len];
        for i in 0..self.layout.nodes() {
            let kp = self.settings[i].position_stiffness;
            for c in 0..3 {
                f[6 * i + c] = kp * (u.x[i][c] - self.x0[i][c]);
                f[6 * i + 3 + c] = kp * u.g[i][c];
            }
        }
        for k in 0..self.layout.elements.len() {
            self.element_residual(k, &kin, &u.lambda, self.t, &mut f);
        }
        let n6 = 6 * self.layout.nodes();
        for r in (n6..f.len()).filter(|&r| self.velocity_rows[r]) {
            f[r] = u.lambda[r - n6];
        }
        f
    }

    fn position_jacobian(&self, u: &Unknowns) -> Triplets {
        let kin = self.kinematics(u);
        let g: Vec<Mat3> = u.g.iter().map(gibbs_g).collect();
        let mut j = Triplets::new(self.layout.len);
        for i in 0..self.layout.nodes() {
            (0..6).for_each(|c| j.push(6 * i + c, 6 * i + c, self.settings[i].position_stiffness));
        }
        for k in 0..self.layout.elements.len() {
            self.element_jacobian(k, &kin, &u.lambda, Some(&g), &mut j);
        }
        for r in (0..self.layout.len).filter(|&r| self.velocity_rows[r]) {
            j.push(r, r, 1.0);
        }
        j
    }

    /// The velocity rows as `A w − b` with `w = (v, ω, λ̇)`: the matrix `A` and the
    /// right-hand side `b` at the positions and reactions of `u`. Only elements with
    /// multipliers (the joints) have velocity rows; `f_/t` and `Φ_/t` by forward
    /// differences in time.
    fn velocity_system(&self, u: &Unknowns) -> (Triplets, Vec<f64>) {
        let kin = self.kinematics(u);
        let n = self.layout.nodes();
        let mut a = Triplets::new(self.layout.len);
        let mut b = vec![0.0; self.layout.len];
        for i in 0..n {
            let s = self.settings[i];
            let w0 = if s.omega_rotates { self.r0[i] * kin[i].r.transpose() * self.w0[i] } else { self.w0[i] };
            for c in 0..3 {
                a.push(6 * i + c, 6 * i + c, s.velocity_stiffness);
                a.push(6 * i + 3 + c, 6 * i + 3 + c, s.velocity_stiffness);
                b[6 * i + c] = s.velocity_stiffness * self.v0[i][c];
                b[6 * i + 3 + c] = s.velocity_stiffness * w0[c];
            }
        }
        // `f_/t` and `Φ_/t` forward in time, extrapolated (forward_derivatives): drives
        // usually start at the initial time with a kink, where MBDyn's drives give their
        // derivative from t₀ on (`GetP`, e.g. 0 for the cosine).
        let n6 = 6 * n;
        let joints: Vec<usize> = (0..self.layout.elements.len()).filter(|&k| !self.layout.element(k).multipliers().is_empty()).collect();
        for &k in &joints {
            if reaction_rate_without_geometry(self.layout.element(k).type_name()) {
                let mut own = Triplets::new(self.layout.len);
                self.element_jacobian(k, &kin, &u.lambda, None, &mut own);
                for ((&r, &c), &v) in own.rows.iter().zip(&own.cols).zip(&own.values) {
                    if r >= n6 || c >= n6 {
                        a.push(r, c, v);
                    }
                }
            } else {
                self.element_jacobian(k, &kin, &u.lambda, None, &mut a);
            }
        }
        let residual_at = |h: f64| {
            let mut r = vec![0.0; self.layout.len];
            for &k in &joints {
                self.element_residual(k, &kin, &u.lambda, self.t + h, &mut r);
            }
            r
        };
        let rows: Vec<usize> = (0..self.layout.len).collect();
        let rate = forward_derivatives(&rows, self.t, &residual_at(0.0), residual_at);
        for (bi, ri) in b.iter_mut().zip(rate) {
            *bi -= ri;
        }
        if self.velocity_rows.iter().any(|v| *v) {
            // Velocity-level constraints: `−Φ(q, 0, t)` on the right.
            let still: Vec<NodeKinematics> = kin.iter().map(|k| NodeKinematics { xdot: Vec3::zeros(), omega: Vec3::zeros(), ..k.clone() }).collect();
            let mut phi0 = vec![0.0; self.layout.len];
            for k in (0..self.layout.elements.len()).filter(|&k| !self.layout.element(k).multipliers().is_empty()) {
                self.element_residual(k, &still, &u.lambda, self.t, &mut phi0);
            }
            for r in (0..self.layout.len).filter(|&r| self.velocity_rows[r]) {
                b[r] = -phi0[r];
            }
        }
        (a, b)
    }

    fn velocity_unknowns(&self, u: &Unknowns) -> Vec<f64> {
        let mut w = vec![0.0; self.layout.len];
        for i in 0..self.layout.nodes() {
            for c in 0..3 {
                w[6 * i + c] = u.v[i][c];
                w[6 * i + 3 + c] = u.w[i][c];
            }
        }
        w[6 * self.layout.nodes()..].copy_from_slice(&u.lambda_dot);
        w
    }

    fn velocity_residual(&self, u: &Unknowns) -> Vec<f64> {
        let (a, b) = self.velocity_system(u);
        let w = self.velocity_unknowns(u);
        let mut r: Vec<f64> = b.iter().map(|x| -x).collect();
        for k in 0..a.values.len() {
            r[a.rows[k]] += a.values[k] * w[a.cols[k]];
        }
        r
    }

    /// MBDyn's test and the worst row (`true`: a velocity row).
    /// What is not finite: the first such equation, with the drive evaluation that failed
    /// there, if one did (a scalar function or drive out of its domain, named where written).
    fn not_finite(&self, u: &Unknowns, pos: &[f64], vel: &[f64]) -> String {
        let first = |v: &[f64], derivative: bool| v.iter().position(|x| !x.is_finite()).map(|i| format!("{} = {}", self.layout.row_name(i, derivative), v[i]));
        let unknowns = [&u.x, &u.g, &u.v, &u.w].iter().any(|v| v.iter().any(|x| !x.iter().all(|c| c.is_finite())));
        let mut row = first(pos, false).or_else(|| first(vel, true)).unwrap_or_else(|| if unknowns { "the unknowns left the range of doubles".into() } else { "its norm overflows".into() });
        // The element that put it there, each evaluated alone.
        let kin = self.kinematics(u);
        let culprit = (0..self.layout.elements.len()).find(|&k| {
            let mut f = vec![0.0; self.layout.len];
            self.element_residual(k, &kin, &u.lambda, self.t, &mut f);
            f.iter().any(|x| !x.is_finite())
        });
        if let Some(k) = culprit {
            let e = self.layout.elements[k];
            row = format!("{row}, from {}{}", self.layout.model.element_name(e), self.layout.model.element_functions_note(e));
        }
        match crate::element::drive::take_evaluation_failure(self.t) {
            Some(why) => format!("{row}; {why}"),
            None => row,
        }
    }

    fn test(&self, u: &Unknowns, pos: &[f64], vel: &[f64]) -> (f64, (usize, bool, f64)) {
        let sq = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        let sq3 = |v: &[Vec3]| v.iter().map(|x| x.norm_squared()).sum::<f64>();
        let x2 = sq3(&u.x) + sq3(&u.g) + sq3(&u.v) + sq3(&u.w) + sq(&u.lambda) + sq(&u.lambda_dot);
        let test = ((sq(pos) + sq(vel)) / (1.0 + x2)).sqrt();
        let worst = pos.iter().enumerate().map(|(i, v)| (i, false, *v)).chain(vel.iter().enumerate().map(|(i, v)| (i, true, *v))).fold((0, false, 0.0f64), |b, c| if c.2.abs() > b.2.abs() || c.2.is_nan() { c } else { b });
        (test, worst)
    }
}

/// Runs MBDyn's initial assembly on `st` (the model's initial state, `g = 0`), or, with
/// `skip initial joint assembly`, checks that the joints hold as written. On success the
/// state carries the assembled positions, orientations (re-based, `g = 0`), velocities and
/// angular velocities; momenta and multipliers are left to the derivatives phase.
pub fn initial_assembly(model: &Model, st: &mut State, settings: &InitialAssembly) -> Result<AssemblyReport, AssemblyError> {
    let layout = Layout::new(model);
    if layout.elements.is_empty() {
        return Ok(AssemblyReport::default());
    }
    let n = model.nodes.len();
    let dofs = crate::dae::DofMap::new(model);
    let frames: Vec<_> = (0..n).map(|i| st.node_frame(&dofs, i)).collect();
    let velocity_rows = velocity_rows(&layout, &frames.iter().map(|f| f.kin.clone()).collect::<Vec<_>>(), st.t);
    let problem = Problem {
        velocity_rows,
        settings: model.nodes.iter().map(|node| settings.node(node.label)).collect(),
        x0: frames.iter().map(|f| f.kin.x).collect(),
        r0: frames.iter().map(|f| f.kin.r).collect(),
        v0: frames.iter().map(|f| f.kin.xdot).collect(),
        w0: frames.iter().map(|f| f.kin.omega).collect(),
        t: st.t,
        layout,
    };
    let m = problem.layout.len - 6 * n;
    let mut u = Unknowns { x: problem.x0.clone(), g: vec![Vec3::zeros(); n], v: problem.v0.clone(), w: problem.w0.clone(), lambda: vec![0.0; m], lambda_dot: vec![0.0; m] };
    if settings.skip {
        return skipped(&problem, &u);
    }
    let mut pos = problem.position_residual(&u);
    let mut vel = problem.velocity_residual(&u);
    let (mut test, mut worst) = problem.test(&u, &pos, &vel);
    let mut iterations = 0;
    while !(test <= settings.tolerance) {
        if !test.is_finite() {
            return Err(AssemblyError::Diverged { iteration: iterations, detail: problem.not_finite(&u, &pos, &vel) });
        }
        if iterations >= settings.max_iterations {
            let (row, derivative, value) = worst;
            return Err(AssemblyError::NotConverged { iterations, test, tolerance: settings.tolerance, worst: problem.layout.row_name(row, derivative), value });
        }
        iterations += 1;
        newton_step(&problem, &mut u, &pos, iterations)?;
        pos = problem.position_residual(&u);
        vel = problem.velocity_residual(&u);
        (test, worst) = problem.test(&u, &pos, &vel);
    }
    // MBDyn stops at its tolerance; the derivatives phase then divides what the joints
    // still miss by dCoef (1e-9 s by default: 1.4e-6 m left by a test of 6.4e-7 read as 1.4e3
    // on MBDyn's tests/joints/impdisp/imp0, which no derivatives iteration can reduce, since
    // it holds the positions). romdyn's Newton converges quadratically, so, once it has
    // moved the nodes, it takes up to 3 more steps while they reduce the test tenfold: the
    // positions move by less than the tolerance allowed, and the joints then hold to
    // rounding. Not counted in `iterations` (MBDyn's count).
    if iterations > 0 {
        for _ in 0..3 {
            let mut polished = u.clone();
            if newton_step(&problem, &mut polished, &pos, iterations).is_err() {
                break;
            }
            let (p, v) = (problem.position_residual(&polished), problem.velocity_residual(&polished));
            let (t, _) = problem.test(&polished, &p, &v);
            if !(t <= 0.1 * test) {
                break;
            }
            (u, pos, test) = (polished, p, t);
        }
    }
    let mut report = AssemblyReport { iterations, test, ..Default::default() };
    for i in 0..n {
        let r = gibbs_rotation(&u.g[i]) * problem.r0[i];
        report.moved_position = report.moved_position.max((u.x[i] - problem.x0[i]).norm());
        report.moved_rotation = report.moved_rotation.max(crate::kinematics::rotation_vector(&(r * problem.r0[i].transpose())).norm());
        report.moved_velocity = report.moved_velocity.max((u.v[i] - problem.v0[i]).norm());
        report.moved_angular_velocity = report.moved_angular_velocity.max((u.w[i] - problem.w0[i]).norm());
        let f = dofs.node_first[i];
        st.r_ref[i] = r;
        for c in 0..3 {
            st.y[f + c] = u.x[i][c];
            st.y[f + 3 + c] = 0.0;
            st.yp[f + c] = u.v[i][c];
            st.yp[f + 3 + c] = u.w[i][c];
        }
    }
    // Elements' coordinates (a beam slider's abscissa) are configuration: kept with their
    // rates, where multipliers are left to the derivatives phase.
    for (k, &e) in problem.layout.elements.iter().enumerate() {
        let (el, at) = (problem.layout.element(k), problem.layout.first[k] - 6 * n);
        for j in (0..el.multipliers().len()).filter(|&j| el.unknown_kind(j) == UnknownKind::Coordinate) {
            st.y[dofs.element_first[e] + j] = u.lambda[at + j];
            st.yp[dofs.element_first[e] + j] = u.lambda_dot[at + j];
        }
    }
    Ok(report)
}

/// One Newton step of the assembly: `(q, λ)` from the position rows `pos` at `u`, then the
/// velocity rows solved exactly at the new `(q, λ)` for `(u, λ̇)`.
fn newton_step(problem: &Problem, u: &mut Unknowns, pos: &[f64], iteration: usize) -> Result<(), AssemblyError> {
    let n = problem.layout.nodes();
    let mut delta: Vec<f64> = pos.iter().map(|x| -x).collect();
    SparseLu::new().solve(&problem.position_jacobian(u), &mut delta).map_err(|_| AssemblyError::Singular { iteration })?;
    for i in 0..n {
        u.x[i] += Vec3::new(delta[6 * i], delta[6 * i + 1], delta[6 * i + 2]);
        u.g[i] += Vec3::new(delta[6 * i + 3], delta[6 * i + 4], delta[6 * i + 5]);
    }
    u.lambda.iter_mut().zip(&delta[6 * n..]).for_each(|(l, d)| *l += d);
    let (a, mut w) = problem.velocity_system(u);
    SparseLu::new().solve(&a, &mut w).map_err(|_| AssemblyError::Singular { iteration })?;
    for i in 0..n {
        u.v[i] = Vec3::new(w[6 * i], w[6 * i + 1], w[6 * i + 2]);
        u.w[i] = Vec3::new(w[6 * i + 3], w[6 * i + 4], w[6 * i + 5]);
    }
    u.lambda_dot.copy_from_slice(&w[6 * n..]);
    Ok(())
}

/// The rows of velocity-level constraints, from where the elements' Jacobians have
/// velocity entries.
fn velocity_rows(layout: &Layout, kin: &[NodeKinematics], t: f64) -> Vec<bool> {
    let mut rows = vec![false; layout.len];
    let lambda = vec![0.0; layout.len - 6 * layout.nodes()];
    for k in 0..layout.elements.len() {
        let (slots, first) = (&layout.slots[k], layout.first[k]);
        let m = layout.element(k).multipliers().len();
        let ctx = Ctx { model: layout.model, kin, slots, scalars: &layout.scalars[k], multipliers: &lambda[first - 6 * layout.nodes()..][..m], t };
        layout.element(k).jacobian(&ctx, &mut VelocityProbe { first, rows: &mut rows });
    }
    rows
}

/// `skip initial joint assembly`: the constraints must hold as written (to 1e-6 of the
/// model's size), since nothing will move the nodes onto them.
fn skipped(problem: &Problem, u: &Unknowns) -> Result<AssemblyReport, AssemblyError> {
    let n = problem.layout.nodes();
    let scale = problem.x0.iter().fold(1.0f64, |m, x| m.max(x.norm()));
    let f = problem.position_residual(u);
    // Velocity-level constraints are checked against the written velocities by the run.
    match (6 * n..f.len()).filter(|&i| !problem.velocity_rows[i]).map(|i| (i, f[i])).find(|(_, v)| !(v.abs() <= 1e-6 * scale)) {
        Some((i, value)) => {
            let k = problem.layout.first.iter().rposition(|&first| first <= i).unwrap_or(0);
            let e = problem.layout.element(k);
            Err(AssemblyError::Violated { element: format!("{} {}", e.type_name(), e.label()), constraint: e.multipliers().get(i - problem.layout.first[k]).cloned().unwrap_or_default(), value })
        }
        None => Ok(AssemblyReport::default()),
    }
}

/// Joints whose velocity rows MBDyn writes with the reaction's rate alone, `f_/λ λ̇`, without
/// the turning of its arm with the nodes, `f_/q u` (drvdisp.cc: `DriveDisplacementJoint` and
/// `DriveDisplacementPinJoint::InitialAssRes` add `F'` and `d × F'` only, where spherj.cc
/// adds `(ω × d) × F` too).
fn reaction_rate_without_geometry(type_name: &str) -> bool {
    matches!(type_name, "drive displacement" | "drive displacement pin")
}
