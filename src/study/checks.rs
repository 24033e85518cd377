//! Checks of the linear model that become warnings or error details: equilibrium at the
//! reference (issue 9 point 7), unrestrained motion, ports that carry nothing.

use faer::{c64, Mat};

use crate::dae::{linearize, Assembler, State};
use crate::linear::{LinearDae, ModalAnalysis, ModeKind};
use crate::model::Model;
use crate::rom::{full_static_gain, null_direction};

use super::{Study, Warning};

/// `F(ẏ = 0, y)` at the reference: nonzero when gravity or loads are unbalanced or the
/// model moves; a warning when its max norm exceeds what Newton accepts as converged
/// (1e3 times the problem's tolerance, with a small increment).
pub(super) fn equilibrium_warning(model: &Model, state: &State, tolerance: f64) -> Option<Warning> {
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.yp.iter_mut().for_each(|x| *x = 0.0);
    // Plain constraint rows (eq. 29): the multipliers are in y, as in the static analysis.
    let f = asm.residual(&st, crate::linear::ConstraintForm::Plain, 1.0);
    let (i, v) = f.iter().enumerate().fold((0, 0.0f64), |(bi, bv), (i, x)| if x.abs() > bv { (i, x.abs()) } else { (bi, bv) });
    let accepted = 1e3 * tolerance;
    (v > accepted).then(|| Warning::NotInEquilibrium { residual: v, equation: asm.dofs.equation_name(model, i), tolerance: accepted })
}

/// The free direction of a model whose static matrix at its initial state is singular,
/// named by its largest node components ("node 2 x, node 2 y").
pub(super) fn unrestrained_motion(model: &Model) -> Option<String> {
    let asm = Assembler::new(model);
    let st = State::initial(model, &asm.dofs);
    let dae = linearize(model, &st, &[], &[], None).ok()?;
    let x = null_direction(&dae.static_matrix())?;
    let mut idx: Vec<usize> = (0..x.len()).filter(|i| !dae.multipliers.contains(i) && x[*i].abs() > 1e-3).collect();
    idx.sort_by(|&a, &b| x[b].abs().total_cmp(&x[a].abs()));
    let names: Vec<&str> = idx.iter().take(6).map(|&i| dae.unknown_names[i].as_str()).collect();
    (!names.is_empty()).then(|| names.join(", "))
}

/// Channels (output, input) of the full model whose response is exactly zero at every
/// frequency: zero static gain and zero residue `(C̃_i v)(uᵀ B̃_j)` in every dynamic mode
/// (to 1e-12 of the largest static gain and 1e-10 of the largest residue).
pub fn zero_channels(dae: &LinearDae, modal: &ModalAnalysis) -> Vec<Vec<bool>> {
    zero_channels_of(&dae.b, &dae.c, modal, full_static_gain(dae).ok().as_ref())
}

/// [`zero_channels`] from `B̃`, `C̃`, the modes and the full static gain (`None`: none).
fn zero_channels_of(b: &Mat<f64>, c: &Mat<f64>, modal: &ModalAnalysis, gain: Option<&Mat<f64>>) -> Vec<Vec<bool>> {
    let (no, ni) = (c.nrows(), b.ncols());
    let mut residue = Mat::<f64>::zeros(no, ni);
    for i in modal.of_kind(ModeKind::Dynamic) {
        let m = &modal.modes[i];
        let (Some(v), Some(u)) = (&m.right, &m.left) else { continue };
        let n = v.nrows();
        let cv: Vec<c64> = (0..no).map(|r| (0..n).fold(c64::new(0.0, 0.0), |s, k| s + v[k] * c[(r, k)])).collect();
        let ub: Vec<c64> = (0..ni).map(|j| (0..n).fold(c64::new(0.0, 0.0), |s, k| s + u[k] * b[(k, j)])).collect();
        for r in 0..no {
            for c in 0..ni {
                residue[(r, c)] = residue[(r, c)].max((cv[r] * ub[c]).norm() / m.lambda.norm().max(f64::MIN_POSITIVE));
            }
        }
    }
    let max_res = residue.norm_max();
    let max_gain = gain.map_or(0.0, |g| g.norm_max());
    (0..no)
        .map(|r| {
            (0..ni)
                .map(|c| {
                    let modal_zero = residue[(r, c)] <= 1e-10 * max_res;
                    let static_zero = gain.is_none_or(|g| g[(r, c)].abs() <= 1e-12 * max_gain);
                    modal_zero && static_zero && (max_res > 0.0 || max_gain > 0.0)
                })
                .collect()
        })
        .collect()
}

/// Inputs whose every response is zero, outputs that see no input.
pub(super) fn port_warnings(dae: &LinearDae, modal: &ModalAnalysis) -> Vec<Warning> {
    channel_warnings(&zero_channels(dae, modal), &dae.input_names, &dae.output_names)
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
            None => port_warnings(self.linear.dense(), &self.modal),
            Some(_) => {
                let gain = self.linear.sparse_static_gain().and_then(Result::ok);
                let zero = zero_channels_of(self.linear.b(), self.linear.c(), &self.modal, gain.as_ref());
                channel_warnings(&zero, self.linear.input_names(), self.linear.output_names())
            }
        };
        if let Some(run) = self.sparse.as_ref().filter(|r| !r.certified) {
            w.push(Warning::SparseNotCertified { target: run.describe_target(), reason: run.note.clone().unwrap_or_else(|| "no reason given".into()), damping_covered: run.damping_covered });
        }
        w
    }
}
