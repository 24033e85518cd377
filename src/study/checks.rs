//! Checks of the linear model that become warnings or error details: equilibrium at the
//! reference (issue 9 point 7), unrestrained motion, ports that carry nothing.

use faer::{c64, Mat};

use crate::dae::{linearize, Assembler, State};
use crate::eigen::{ModalAnalysis, ModeKind};
use crate::linear::LinearDae;
use crate::model::Model;
use crate::rom::{full_static_gain, null_direction};

use super::linear::LinearModel;
use super::{Study, Warning};

/// Whether the reference is an equilibrium or a steady motion, the states whose small
/// perturbations the linear model describes: `F` in the linearization form
/// ([`State::linearization_base`]: angular velocities carried in `W_ref`, `ġ = 0`) with the
/// nodes' velocities and angular velocities held and every other rate (momenta, element
/// states) set to zero. That residual vanishes at rest and in a steady motion (a rotor
/// spinning about its axis of symmetry, a uniform translation), where the Jacobians do not
/// change along the motion; elsewhere the model accelerates and the eigenvalues are those of
/// the Jacobians frozen at that instant ([`Warning::NotInEquilibrium`]). A warning when its
/// max norm exceeds what Newton accepts as converged (1e3 times the problem's tolerance,
/// with a small increment).
pub(super) fn equilibrium_warning(model: &Model, state: &State, tolerance: f64) -> Option<Warning> {
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let velocities: Vec<usize> = asm.dofs.node_first.iter().flat_map(|&f| f..f + 3).collect();
    for (i, x) in st.yp.iter_mut().enumerate() {
        if !velocities.contains(&i) {
            *x = 0.0;
        }
    }
    // Plain constraint rows (eq. 29): the multipliers are in y, as in the static analysis.
    let f = asm.residual(&st, crate::model::ConstraintForm::Plain, 1.0);
    let (i, v) = f.iter().enumerate().fold((0, 0.0f64), |(bi, bv), (i, x)| if x.abs() > bv { (i, x.abs()) } else { (bi, bv) });
    let accepted = 1e3 * tolerance;
    (v > accepted).then(|| Warning::NotInEquilibrium { residual: v, equation: asm.dofs.equation_name(model, i), tolerance: accepted })
}

/// The warning of a static reference with incremental beams ([`Warning::IncrementalBeamsStatic`]):
/// beams whose per-step history is latched (`has_events`) take their static equilibrium as
/// one step.
pub(super) fn incremental_beams_warning(model: &Model, reference: crate::analysis::Reference) -> Option<Warning> {
    if !matches!(reference, crate::analysis::Reference::Static { .. }) {
        return None;
    }
    let beams = model.elements.iter().filter(|e| e.type_name().starts_with("beam") && e.events().is_some()).count();
    (beams > 0).then_some(Warning::IncrementalBeamsStatic { beams })
}

/// The elements whose linearization at `state` is one-sided ([`Warning::OneSided`]) or
/// carries the reaction multipliers' integration noise ([`Warning::ReactionDependent`]), as a
/// run's eigenanalysis reports them.
pub(super) fn smoothness_warnings(model: &Model, state: &State) -> Vec<Warning> {
    let asm = Assembler::new(model);
    let one_sided = asm.non_smooth_elements(state).into_iter().map(|why| Warning::OneSided { why });
    one_sided.chain(asm.reaction_dependent_elements(state).into_iter().map(|why| Warning::ReactionDependent { why })).collect()
}

/// The free direction of a model whose static matrix at its initial state is singular, in
/// words a person recognizes: the whole model's rigid-body motion when it is one
/// ([`whole_model_rigid_motion`]), else its largest node components ("node 2 x, node 2 y").
pub(super) fn unrestrained_motion(model: &Model) -> Option<String> {
    let asm = Assembler::new(model);
    let st = State::initial(model, &asm.dofs);
    let dae = linearize(model, &st, &[], &[], None).ok()?;
    let x = null_direction(&dae.static_matrix())?;
    if let Some(rigid) = whole_model_rigid_motion(model, &x) {
        return Some(rigid);
    }
    let text = largest_components(&x, &dae.unknown_names, &dae.multipliers);
    (!text.is_empty()).then(|| format!("rigid-body motion along {text}"))
}

/// The largest components of a direction in the unknowns, e.g. "node 2 x, node 2 y"
/// (multipliers left out).
pub(super) fn largest_components(x: &[f64], names: &[String], multipliers: &[usize]) -> String {
    let mut idx: Vec<usize> = (0..x.len()).filter(|i| !multipliers.contains(i) && x[*i].abs() > 1e-3).collect();
    idx.sort_by(|&a, &b| x[b].abs().total_cmp(&x[a].abs()));
    let names: Vec<&str> = idx.iter().take(6).map(|&i| names.get(i).map_or("?", String::as_str)).collect();
    names.join(", ")
}

/// A free direction `x` of a static matrix (unknowns as the model numbers them) in words a
/// person recognizes, when its node components are a rigid-body motion of all the nodes
/// that move in it (`t + θ × p` and `θ`, least squares to 1e-2 of `‖x‖`: the reference
/// positions, not the deformed ones, set the lever arms): "rigid-body motion of the whole
/// model (its 11 nodes but node 100, at rest, move together), here rotation about z, …"
/// (one direction of what may be a larger free space); `None` otherwise.
pub(super) fn whole_model_rigid_motion(model: &Model, x: &[f64]) -> Option<String> {
    let dofs = crate::dae::DofMap::new(model);
    if dofs.len != x.len() || model.nodes.len() < 2 {
        return None;
    }
    // Nodes at rest in this direction (a clamped ground node) are left out.
    let top = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let moving: Vec<usize> = (0..model.nodes.len()).filter(|&k| (0..6).any(|c| x[dofs.node_first[k] + c].abs() > 1e-9 * top)).collect();
    if moving.len() < 2 {
        return None;
    }
    let at_rest: Vec<String> = (0..model.nodes.len()).filter(|k| !moving.contains(k)).map(|k| model.nodes[k].label.to_string()).collect();
    let centre = moving.iter().fold([0.0; 3], |c, &k| { let p = &model.nodes[k].position; [c[0] + p[0], c[1] + p[1], c[2] + p[2]] }).map(|c| c / moving.len() as f64);
    let size = moving.iter().map(|&k| (0..3).map(|i| (model.nodes[k].position[i] - centre[i]).powi(2)).sum::<f64>().sqrt()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    // Rows: the 6 motion unknowns of every node; columns: translations x, y, z and rotations
    // about x, y, z (scaled by the model's size so both have lengths' units).
    let mut rows: Vec<(usize, [f64; 6])> = Vec::new();
    for &k in &moving {
        let node = &model.nodes[k];
        let p: Vec<f64> = (0..3).map(|i| node.position[i] - centre[i]).collect();
        let first = dofs.node_first[k];
        for c in 0..3 {
            let mut r = [0.0; 6];
            r[c] = 1.0;
            // (θ × p)_c = θ_{c+1} p_{c+2} − θ_{c+2} p_{c+1}
            r[3 + (c + 1) % 3] = p[(c + 2) % 3] / size;
            r[3 + (c + 2) % 3] = -p[(c + 1) % 3] / size;
            rows.push((first + c, r));
            let mut g = [0.0; 6];
            g[3 + c] = 1.0 / size;
            rows.push((first + 3 + c, g));
        }
    }
    let r = Mat::from_fn(rows.len(), 6, |i, j| rows[i].1[j]);
    let b = Mat::from_fn(rows.len(), 1, |i, _| x[rows[i].0]);
    let norm = b.norm_l2();
    if norm == 0.0 {
        return None;
    }
    use faer::linalg::solvers::SolveLstsq;
    let coef = r.qr().solve_lstsq(&b);
    if (&r * &coef - &b).norm_l2() > 1e-2 * norm {
        return None;
    }
    const MOTIONS: [&str; 6] = ["translation along x", "translation along y", "translation along z", "rotation about x", "rotation about y", "rotation about z"];
    let big = (0..6).map(|j| coef[(j, 0)].abs()).fold(0.0, f64::max);
    let parts: Vec<&str> = (0..6).filter(|&j| coef[(j, 0)].abs() > 0.1 * big).map(|j| MOTIONS[j]).collect();
    let rest = match at_rest.len() {
        0 => String::new(),
        1 => format!(" but node {}, at rest", at_rest[0]),
        _ => format!(" but nodes {}, at rest", at_rest.join(", ")),
    };
    let together = if at_rest.is_empty() { format!("its {} nodes move together", moving.len()) } else { format!("its {} nodes{rest}, move together", moving.len()) };
    Some(format!("rigid-body motion of the whole model ({together}), here {}", parts.join(", ")))
}

/// Channels (output, input) of the full model whose response is exactly zero at every
/// frequency: zero static gain and zero residue `((C̃_i + λ C̃_v,i) v)(uᵀ B̃_j)` in every
/// dynamic mode (a rate output `z = C̃ Δy + C̃_v Δẏ` reads the mode through `λ C̃_v`: its
/// `C̃` row is zero, its response is not). Zero means, against the largest channel, 1e-12 of
/// the largest static gain and 1e-10 of the largest residue; and, for a model whose every
/// channel is rounding (a force on a clamped ground node alone gives 1e-22 m/N), against the
/// channel's own rounding floor: a mode's residue below 1e-10 of `‖C̃_i‖ ‖v‖ ‖u‖ ‖B̃_j‖` (what
/// the vectors would give were they aligned; the eigenvectors are accurate to about 1e-12 of
/// their norms), a static gain below 1e-12 of that bound's largest over the modes, `/|λ|`
/// (the modes' `uᵀ F_yd v = 1` give it the channel's units).
///
/// Units (issue 34): the largest channel is the largest of the same output and input units
/// (a piston's metres are not rounding next to its chambers' pascals), and the vectors'
/// norms in the rounding floor run over the unknowns of the port's own kind (mechanical, or
/// scalar nodes and their elements' unknowns: `classes`, `true` for the latter, by index;
/// `None`: one kind).
pub fn zero_channels(dae: &LinearDae, modal: &ModalAnalysis, classes: Option<&[bool]>) -> Vec<Vec<bool>> {
    zero_channels_of(&dae.b, &dae.c, dae.c_rate.as_ref(), modal, full_static_gain(dae).ok().as_ref(), classes, &units(&dae.output_names, &dae.input_names))
}

/// [`zero_channels`] from `B̃`, `C̃`, `C̃_v`, the modes and the full static gain (`None`: none).
pub(super) fn zero_channels_of(b: &Mat<f64>, c: &Mat<f64>, c_rate: Option<&Mat<f64>>, modal: &ModalAnalysis, gain: Option<&Mat<f64>>, classes: Option<&[bool]>, units: &Units) -> Vec<Vec<bool>> {
    let sums = modal_sums(b, c, c_rate, modal, classes);
    zero_from_sums(&sums, gain, units)
}

/// The outputs' and the inputs' units, as their ports have them ([`Port::from_label`]).
pub(super) type Units = (Vec<String>, Vec<String>);

pub(super) fn units(outputs: &[String], inputs: &[String]) -> Units {
    let unit = |name: &String| crate::linear::Port::from_label(name).unit;
    (outputs.iter().map(unit).collect(), inputs.iter().map(unit).collect())
}

/// The port's kind when every unknown (or equation) it touches is of one (`Some(true)`:
/// non-mechanical), `None` when mixed or without classes.
fn port_class(entries: &[(usize, f64)], classes: Option<&[bool]>) -> Option<bool> {
    let classes = classes?;
    let first = classes.get(entries.first()?.0).copied()?;
    entries.iter().all(|e| classes.get(e.0) == Some(&first)).then_some(first)
}

/// Per channel (outputs × inputs), over the dynamic modes: the largest static contribution
/// `|(C̃_i v)(uᵀ B̃_j)| / |λ|` above the vectors' rounding, the largest aligned bound
/// `‖C̃_i‖ ‖v‖ ‖u‖ ‖B̃_j‖ / |λ|`, and the sum of every mode's contribution `Σ |…| / |λ|`.
pub(super) struct ModalSums {
    residue: Mat<f64>,
    bound: Mat<f64>,
    /// `Σ_k |(C̃_i v_k)(u_kᵀ B̃_j)| / |λ_k|`: the size of the terms whose sum is the static
    /// gain (their cancellation sets its rounding).
    pub absolute: Mat<f64>,
}

pub(super) fn modal_sums(b: &Mat<f64>, c: &Mat<f64>, c_rate: Option<&Mat<f64>>, modal: &ModalAnalysis, classes: Option<&[bool]>) -> ModalSums {
    let (no, ni) = (c.nrows(), b.ncols());
    let mut residue = Mat::<f64>::zeros(no, ni);
    let mut bound = Mat::<f64>::zeros(no, ni);
    let mut absolute = Mat::<f64>::zeros(no, ni);
    // The non-zeros of C̃'s rows and B̃'s columns (a port touches a few unknowns): the sums
    // below skip only zero terms, so they are those over every unknown.
    let nonzeros = |len: usize, at: &dyn Fn(usize) -> f64| -> Vec<(usize, f64)> { (0..len).map(|k| (k, at(k))).filter(|e| e.1 != 0.0).collect() };
    let c_rows: Vec<Vec<(usize, f64)>> = (0..no).map(|r| nonzeros(c.ncols(), &|k| c[(r, k)])).collect();
    let rate_rows: Vec<Vec<(usize, f64)>> = (0..no).map(|r| c_rate.map_or(Vec::new(), |cv| nonzeros(cv.ncols(), &|k| cv[(r, k)]))).collect();
    let b_cols: Vec<Vec<(usize, f64)>> = (0..ni).map(|j| nonzeros(b.nrows(), &|k| b[(k, j)])).collect();
    let l2 = |e: &[(usize, f64)]| e.iter().map(|x| x.1 * x.1).sum::<f64>().sqrt();
    let (c_norm, rate_norm, b_norm): (Vec<f64>, Vec<f64>, Vec<f64>) = (c_rows.iter().map(|r| l2(r)).collect(), rate_rows.iter().map(|r| l2(r)).collect(), b_cols.iter().map(|r| l2(r)).collect());
    // Each port's kind: the vectors' norms in its rounding floor run over that kind only.
    let out_class: Vec<Option<bool>> = c_rows.iter().zip(&rate_rows).map(|(r, v)| port_class(&[&r[..], &v[..]].concat(), classes)).collect();
    let in_class: Vec<Option<bool>> = b_cols.iter().map(|col| port_class(col, classes)).collect();
    let in_kind = |k: usize, kind: Option<bool>| kind.is_none_or(|m| classes.and_then(|c| c.get(k)).copied().unwrap_or(m) == m);
    let vec_norm = |x: &faer::Col<c64>, kind: Option<bool>| x.iter().enumerate().filter(|(k, _)| in_kind(*k, kind)).map(|(_, z)| z.norm_sqr()).sum::<f64>().sqrt();
    for i in modal.of_kind(ModeKind::Dynamic) {
        let m = &modal.modes[i];
        let (Some(v), Some(u)) = (&m.right, &m.left) else { continue };
        let lam = m.lambda.norm().max(f64::MIN_POSITIVE);
        let kinds = [None, Some(false), Some(true)];
        let norms = |x: &faer::Col<c64>| kinds.map(|k| vec_norm(x, k));
        let (nv, nu) = (norms(v), norms(u));
        let index = |kind: Option<bool>| kinds.iter().position(|k| *k == kind).unwrap_or(0);
        let read = |row: &[(usize, f64)]| row.iter().fold(c64::new(0.0, 0.0), |s, &(k, x)| s + v[k] * x);
        let cv: Vec<c64> = c_rows.iter().zip(&rate_rows).map(|(row, rate)| read(row) + m.lambda * read(rate)).collect();
        let ub: Vec<c64> = b_cols.iter().map(|col| col.iter().fold(c64::new(0.0, 0.0), |s, &(k, x)| s + u[k] * x)).collect();
        for r in 0..no {
            for c in 0..ni {
                let aligned = (c_norm[r] + m.lambda.norm() * rate_norm[r]) * nv[index(out_class[r])] * nu[index(in_class[c])] * b_norm[c] / lam;
                bound[(r, c)] = bound[(r, c)].max(aligned);
                let contribution = (cv[r] * ub[c]).norm() / lam;
                absolute[(r, c)] += contribution;
                // Below the vectors' own rounding: not a contribution.
                if contribution > 1e-10 * aligned {
                    residue[(r, c)] = residue[(r, c)].max(contribution);
                }
            }
        }
    }
    ModalSums { residue, bound, absolute }
}

fn zero_from_sums(sums: &ModalSums, gain: Option<&Mat<f64>>, units: &Units) -> Vec<Vec<bool>> {
    let (residue, bound) = (&sums.residue, &sums.bound);
    let (no, ni) = (residue.nrows(), residue.ncols());
    let max_bound = bound.norm_max();
    let any = residue.norm_max() > 0.0 || gain.is_some_and(|g| g.norm_max() > 0.0) || max_bound > 0.0;
    // The largest channel of the same units as (r, c).
    let unit = |names: &[String], k: usize| names.get(k).map_or("", String::as_str).to_string();
    let same = |r: usize, c: usize| {
        let (mut max_res, mut max_gain) = (0.0f64, 0.0f64);
        for i in (0..no).filter(|&i| unit(&units.0, i) == unit(&units.0, r)) {
            for j in (0..ni).filter(|&j| unit(&units.1, j) == unit(&units.1, c)) {
                max_res = max_res.max(residue[(i, j)]);
                max_gain = max_gain.max(gain.map_or(0.0, |g| g[(i, j)].abs()));
            }
        }
        (max_res, max_gain)
    };
    (0..no)
        .map(|r| {
            (0..ni)
                .map(|c| {
                    let (max_res, max_gain) = same(r, c);
                    let modal_zero = residue[(r, c)] <= 1e-10 * max_res;
                    let static_zero = gain.is_none_or(|g| g[(r, c)].abs() <= 1e-12 * max_gain || g[(r, c)].abs() <= 1e-12 * bound[(r, c)]);
                    modal_zero && static_zero && any
                })
                .collect()
        })
        .collect()
}

/// Inputs whose every response is zero, outputs that see no input (the dense DAE of
/// `linear`, its static gain computed once there).
pub(super) fn port_warnings(linear: &LinearModel, modal: &ModalAnalysis, classes: Option<&[bool]>) -> Vec<Warning> {
    let dae = linear.dense();
    if dae.b.ncols() == 0 || dae.c.nrows() == 0 {
        // No port pair to judge: the full static gain (one n x n factorization) is not needed.
        return Vec::new();
    }
    let zero = zero_channels_of(&dae.b, &dae.c, dae.c_rate.as_ref(), modal, linear.dense_static_gain().ok(), classes, &units(&dae.output_names, &dae.input_names));
    channel_warnings(&zero, &dae.input_names, &dae.output_names)
}

fn channel_warnings(zero: &[Vec<bool>], inputs: &[String], outputs: &[String]) -> Vec<Warning> {
    let mut w = Vec::new();
    if zero.is_empty() {
        return w;
    }
    for (j, name) in inputs.iter().enumerate() {
        if zero.iter().all(|row| row[j]) {
            w.push(Warning::InputMovesNothing { input: name.clone() });
        }
    }
    for (i, name) in outputs.iter().enumerate() {
        if zero[i].iter().all(|&z| z) && !inputs.is_empty() {
            w.push(Warning::OutputSeesNothing { output: name.clone() });
        }
    }
    w
}

impl Study {
    /// The warnings of the study's linear model on its route: ports that carry nothing (the
    /// static gain by sparse LU on the sparse route, residues of the modes found) and a
    /// sparse eigenanalysis that is not certified.
    pub(super) fn linear_warnings(&self) -> Vec<Warning> {
        let mut w = match &self.sparse {
            None => port_warnings(&self.linear, &self.modal, self.unit_classes().as_deref()),
            Some(_) => channel_warnings(&self.zero_channels(), self.linear.input_names(), self.linear.output_names()),
        };
        w.extend(self.sparse_warning());
        w.extend(label_warnings(&self.modal));
        w
    }

    /// [`zero_channels`] of the study's full model (outputs × inputs; the static gain by
    /// sparse LU on the sparse route): the channels whose every response is zero to rounding.
    pub fn zero_channels(&self) -> Vec<Vec<bool>> {
        self.channel_sums().0
    }

    /// [`Study::zero_channels`] and the modal sums it came from.
    pub(super) fn channel_sums(&self) -> (Vec<Vec<bool>>, ModalSums) {
        let sums = modal_sums(self.linear.b(), self.linear.c(), self.linear.c_rate(), &self.modal, self.unit_classes().as_deref());
        let units = units(self.linear.output_names(), self.linear.input_names());
        if self.sparse.is_none() {
            return (zero_from_sums(&sums, self.linear.dense_static_gain().ok(), &units), sums);
        }
        let gain = self.linear.sparse_static_gain().and_then(Result::ok);
        (zero_from_sums(&sums, gain.as_ref(), &units), sums)
    }

    /// The unknowns' kinds for the port checks (`true`: non-mechanical), when the model is
    /// known and numbers the linear model's unknowns.
    pub(super) fn unit_classes(&self) -> Option<Vec<bool>> {
        let mask = crate::eigen::ModalEnergy::non_mechanical_mask(self.model.as_ref()?);
        (mask.len() == self.linear.dim()).then_some(mask)
    }

    /// The warning that the sparse eigenanalysis is not certified, when it is not.
    pub(super) fn sparse_warning(&self) -> Option<Warning> {
        self.sparse.as_ref().filter(|r| !r.certified).map(|run| Warning::SparseNotCertified { target: run.describe_target(), reason: run.note.clone().unwrap_or_else(|| "no reason given".into()), damping_covered: run.damping_covered })
    }
}

/// Warnings about labels the error estimates decided (issue 30, finding 4).
fn label_warnings(modal: &crate::eigen::ModalAnalysis) -> Vec<Warning> {
    let unresolved: Vec<_> = modal.unresolved().map(|(i, m)| (i + 1, m.lambda, m.error, m.kind.name())).collect();
    let zeros: Vec<_> = modal.doubtful_zeros().map(|(i, m)| (i + 1, m.lambda, m.error)).collect();
    let mut w = Vec::new();
    if !unresolved.is_empty() {
        w.push(Warning::UnresolvedEigenvalues { modes: unresolved });
    }
    if !zeros.is_empty() {
        w.push(Warning::DoubtfulZeros { modes: zeros });
    }
    w
}

/// The modes' error estimates refined by units where the model mixes them
/// ([`crate::eigen::componentwise::refine_errors_by_units`]; issue 34: the hydraulic
/// actuator's ±1414 rad/s pair, right to 1e-10, read 2.2e-2 rad/s).
pub(super) fn refine_errors(modal: &mut ModalAnalysis, linear: &LinearModel, model: Option<&Model>) {
    let Some(model) = model else { return };
    let classes = crate::eigen::ModalEnergy::non_mechanical_mask(model);
    if !classes.iter().any(|c| *c) || classes.len() != linear.dim() {
        return;
    }
    let (fyd, fy) = match linear.sparse() {
        Some(s) => (s.fyd.clone(), s.fy.clone()),
        None => {
            let (fyd, fy) = linear.dense().jacobians.derivatives();
            (crate::linear::SparseMatrix::from_dense(&fyd), crate::linear::SparseMatrix::from_dense(&fy))
        }
    };
    crate::eigen::componentwise::refine_errors_by_units(modal, &fyd, &fy, &classes);
}
