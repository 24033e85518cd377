//! The reduction of [`super`]: the substructure's `M`, `K` in node coordinates from its
//! linearization, then the Craig–Bampton transformation and the FEM file's records.

use faer::Mat;
use nalgebra::{Cholesky, DMatrix};

use crate::analysis::Reference;
use crate::dae::{linearize_ports, DofMap};
use crate::input::fem::{FemFile, RigidInertia};
use crate::kinematics::{skew, Mat3, Vec3};
use crate::linear::Jacobians;
use crate::model::{InitialValueProblem, Label, Model, NodeKind};
use crate::study::{checked_reference_state, StudyError};

/// What to reduce: the interface nodes and the number of fixed-interface normal modes.
#[derive(Clone, Debug)]
pub struct CmsRequest {
    /// Structural node labels of the interface (six constraint modes each), in this order.
    pub interfaces: Vec<Label>,
    /// Fixed-interface normal modes kept (the lowest).
    pub modes: usize,
    /// Where the substructure is linearized (at rest).
    pub reference: Reference,
}

/// Why a substructure cannot be reduced.
#[derive(Debug, thiserror::Error)]
pub enum CmsError {
    #[error(transparent)]
    Study(#[from] StudyError),
    #[error(transparent)]
    Port(#[from] crate::dae::PortError),
    /// The model or the request does not fit component mode synthesis.
    #[error("{0}")]
    Unfit(String),
    /// An option of the request that does not fit the substructure: its name as the library
    /// and Python spell it (`interface`, `modes`; the CLI prints its flag) and why.
    #[error("{option}: {message}")]
    Option { option: &'static str, message: String },
}

fn bad_option(option: &'static str, message: String) -> CmsError {
    CmsError::Option { option, message }
}

/// Mass and stiffness of the structural nodes' coordinates `(δx, δθ)` at the reference
/// ([`super`]: `M = −F_/ẏ`, `K = F_/y` on those rows and columns), six per node in the
/// model's node order, and the nodes' reference positions [m] and orientations.
pub struct StructuralMatrices {
    pub mass: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
    pub positions: Vec<Vec3>,
    pub orientations: Vec<Mat3>,
    /// Largest `|F_/ẏ|` entry of the equilibrium rows on the coordinates (viscous damping,
    /// which the FEM file's modes leave out), relative to the largest `|K|` entry.
    pub damping: f64,
    /// `max |K − Kᵀ| / max |K|` (MBDyn's finite-volume beams are not symmetric: 2.4e-3 on
    /// `tests/mbdyn_files/cms_substructure.mbd`; follower loads, prestress).
    pub asymmetry: f64,
    /// The warnings of the run that reached the reference (its derivatives phase, velocities
    /// that violate a joint: [`crate::study::Warning::Run`]).
    pub warnings: Vec<String>,
}

/// A substructure reduced by Craig–Bampton.
pub struct CraigBampton {
    /// The FEM file's contents (records 1, 2, 5–12): modes `0..N` the fixed-interface normal
    /// modes, then six constraint modes per interface node (`x, y, z, rx, ry, rz`).
    pub fem: FemFile,
    /// The fixed-interface normal modes' angular frequencies [rad/s].
    pub fixed_interface_omega: Vec<f64>,
    /// The interface nodes, as requested.
    pub interfaces: Vec<Label>,
    /// Approximations made, in words (damping dropped, a non-symmetric `K`, masses not
    /// diagonal in record 11).
    pub warnings: Vec<String>,
}

fn unfit(message: String) -> CmsError {
    CmsError::Unfit(message)
}

/// `M` and `K` of the substructure at `reference` ([`super`]).
pub fn structural_matrices(model: &Model, problem: &InitialValueProblem, reference: Reference) -> Result<StructuralMatrices, CmsError> {
    if let Some(e) = model.elements.iter().find(|e| !e.multipliers().is_empty()) {
        return Err(unfit(format!("{} {} has unknowns of its own (a joint's reactions, an element's states): a substructure for component mode synthesis is free, made of nodes, bodies, beams and deformable springs; its supports belong to the model that attaches the .fem file", e.type_name(), e.label())));
    }
    if let Some(n) = model.scalar_nodes.first() {
        return Err(unfit(format!("{} is a scalar node: a substructure for component mode synthesis has structural nodes only", n.id)));
    }
    if let Some(l) = model.displacement_nodes.iter().next() {
        return Err(unfit(format!("structural node {l} is a displacement-only node: the FEM file's nodes have six coordinates each")));
    }
    if model.nodes.is_empty() {
        return Err(unfit("the substructure has no structural node".into()));
    }
    let (state, reference_warnings) = checked_reference_state(model, problem, reference, None)?;
    let dofs = DofMap::new(model);
    let mut base = state.clone();
    base.linearization_base(&dofs);
    let frames: Vec<_> = (0..model.nodes.len()).map(|i| base.node_frame(&dofs, i).kin).collect();
    if let Some((i, k)) = frames.iter().enumerate().find(|(_, k)| k.xdot.norm() > 0.0 || k.omega.norm() > 0.0) {
        return Err(unfit(format!("structural node {} moves at the reference (velocity {:.3e} m/s, angular velocity {:.3e} rad/s): component mode synthesis takes M and K at rest", model.nodes[i].label, k.xdot.norm(), k.omega.norm())));
    }
    let dae = linearize_ports(model, &state, &[], &[], None)?;
    let Jacobians::Derivatives { fyd, fy } = &dae.jacobians else {
        unreachable!("linearize_ports without dCoef gives F_/ẏ and F_/y");
    };
    let n = 6 * model.nodes.len();
    let coordinate = |k: usize| dofs.node_first[k / 6] + k % 6;
    let equilibrium = |k: usize| dofs.equilibrium_row(k / 6) + k % 6;
    let mass = DMatrix::from_fn(n, n, |r, c| if dofs.node_kind[r / 6] == NodeKind::Dynamic { -fyd[(dofs.node_first[r / 6] + r % 6, coordinate(c))] } else { 0.0 });
    let raw = DMatrix::from_fn(n, n, |r, c| fy[(equilibrium(r), coordinate(c))]);
    let damped = DMatrix::from_fn(n, n, |r, c| fyd[(equilibrium(r), coordinate(c))]);
    let scale = raw.amax().max(f64::MIN_POSITIVE);
    let asymmetry = (&raw - raw.transpose()).amax() / scale;
    let mass = (&mass + mass.transpose()) * 0.5;
    Ok(StructuralMatrices { mass, stiffness: raw, positions: frames.iter().map(|k| k.x).collect(), orientations: frames.iter().map(|k| k.r).collect(), damping: damped.amax() / scale, asymmetry, warnings: reference_warnings.iter().map(ToString::to_string).collect() })
}

/// Reduces the substructure `model` ([`super`]).
pub fn craig_bampton(model: &Model, problem: &InitialValueProblem, request: &CmsRequest) -> Result<CraigBampton, CmsError> {
    let mut interface_nodes = Vec::new();
    if request.interfaces.is_empty() {
        return Err(bad_option("interface", "give at least one interface node".into()));
    }
    for l in &request.interfaces {
        let i = model.node_index(*l).ok_or_else(|| bad_option("interface", format!("structural node {l} is not defined in the substructure")))?;
        if interface_nodes.contains(&i) {
            return Err(bad_option("interface", format!("node {l} is listed twice")));
        }
        interface_nodes.push(i);
    }
    let s = structural_matrices(model, problem, request.reference)?;
    for &i in &interface_nodes {
        if (s.orientations[i] - Mat3::identity()).amax() > 1e-12 {
            return Err(bad_option("interface", format!("node {} is not oriented as the global frame at the reference; the modal joint clamps each interface node to its FEM node with the FEM frame's orientation (MBDyn 1.7.3 uses no interface orientation), and the FEM file is written in the global frame", model.nodes[i].label)));
        }
    }
    let n = s.mass.nrows();
    let boundary: Vec<usize> = interface_nodes.iter().flat_map(|&i| (0..6).map(move |c| 6 * i + c)).collect();
    let interior: Vec<usize> = (0..n).filter(|k| !boundary.contains(k)).collect();
    if request.modes > interior.len() {
        return Err(bad_option("modes", format!("{}: the substructure has {} coordinates besides its interface's, so at most {} fixed-interface modes", request.modes, interior.len(), interior.len())));
    }
    let sub = |m: &DMatrix<f64>, rows: &[usize], cols: &[usize]| DMatrix::from_fn(rows.len(), cols.len(), |r, c| m[(rows[r], cols[c])]);
    let (k_ii, k_ib, m_ii) = (sub(&s.stiffness, &interior, &interior), sub(&s.stiffness, &interior, &boundary), sub(&s.mass, &interior, &interior));
    let k_sym = (&k_ii + k_ii.transpose()) * 0.5;
    let (psi, psi_left, normal, omega) = if interior.is_empty() {
        (DMatrix::zeros(0, boundary.len()), DMatrix::zeros(0, boundary.len()), (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0)), Vec::new())
    } else {
        Cholesky::new(k_sym).ok_or_else(|| unfit(format!("the substructure is not restrained by its interface nodes {:?}: with them held, its stiffness is not positive definite (a mechanism, a part connected to no interface node, or a missing beam)", request.interfaces)))?;
        let singular = || unfit("the substructure's stiffness with its interface held is singular".into());
        let psi = -k_ii.clone().lu().solve(&k_ib).ok_or_else(singular)?;
        let k_bi = sub(&s.stiffness, &boundary, &interior);
        let psi_left = -k_ii.transpose().lu().solve(&k_bi.transpose()).ok_or_else(singular)?;
        let (normal, normal_left, omega) = two_sided_modes(&k_ii, &m_ii, request.modes)?;
        (psi, psi_left, (normal, normal_left), omega)
    };
    // T: rows = coordinates, columns = normal modes then constraint modes.
    let modes = request.modes + boundary.len();
    let basis = |psi: &DMatrix<f64>, normal: &DMatrix<f64>| {
        let mut t = DMatrix::zeros(n, modes);
        for (r, &k) in interior.iter().enumerate() {
            for j in 0..request.modes {
                t[(k, j)] = normal[(r, j)];
            }
            for j in 0..boundary.len() {
                t[(k, request.modes + j)] = psi[(r, j)];
            }
        }
        for (j, &k) in boundary.iter().enumerate() {
            t[(k, request.modes + j)] = 1.0;
        }
        t
    };
    let (t, t_left) = (basis(&psi, &normal.0), basis(&psi_left, &normal.1));
    let m_cb = t_left.transpose() * &s.mass * &t;
    let k_cb = t_left.transpose() * &s.stiffness * &t;
    let to_faer = |m: &DMatrix<f64>| Mat::from_fn(modes, modes, |r, c| m[(r, c)]);
    let mut warnings = s.warnings.clone();
    if s.damping > 1e-12 {
        warnings.push(format!("the substructure has viscous damping (F/y' on the equilibrium rows up to {:.3e} of its stiffness); the FEM file holds mass and stiffness only: give the modal joint a damping (rayleigh damping, diag damping)", s.damping));
    }
    let (lumped, off_diagonal) = lumped_masses(&s.mass);
    if off_diagonal > 1e-12 {
        warnings.push(format!("the nodes' mass is not diagonal (entries off each node's diagonal up to {off_diagonal:.3e} of the largest: bodies off their nodes, coupled inertia); record 11 holds each node's diagonal, so MBDyn's inertia invariants (gravity on the modes, a moving frame) approximate it, while records 9 and 12 are exact"));
    }
    let fem = FemFile {
        node_labels: model.nodes.iter().map(|n| n.label.to_string()).collect(),
        modal_displacements: vec![0.0; modes],
        modal_velocities: vec![0.0; modes],
        positions: s.positions.iter().map(|p| [p[0], p[1], p[2]]).collect(),
        shapes: (0..modes).map(|j| (0..model.nodes.len()).map(|i| std::array::from_fn(|c| t[(6 * i + c, j)])).collect()).collect(),
        mass: to_faer(&m_cb),
        stiffness: to_faer(&k_cb),
        damping: None,
        lumped_inertia: Some(lumped),
        rigid_inertia: Some(rigid_inertia(&s.mass, &s.positions)),
        warnings: Vec::new(),
    };
    Ok(CraigBampton { fem, fixed_interface_omega: omega, interfaces: request.interfaces.clone(), warnings })
}

/// Right and left fixed-interface modes of the whole (not symmetric) `K_ii`, and their
/// angular frequencies [rad/s]: the right ones the eigenvectors of `A = K_ii⁻¹ M_ii` with
/// the `count` largest `μ = 1/ω²` (unit modal mass, the largest entry positive), the left
/// ones `φ_L = K_ii⁻ᵀ y` with `yᵀ` the matching rows of `V⁻¹` (`V` every right vector: the
/// left eigenvectors of `A`, `yᵀ A = μ yᵀ`, so `φ_Lᵀ K_ii = ω² φ_Lᵀ M_ii`), scaled so that
/// `Φ_Lᵀ M_ii Φ_R = I`.
///
/// The left vectors are not a second eigendecomposition (of `K_ii⁻ᵀ M_ii`): two runs order a
/// double eigenvalue's vectors, or a pair that rounding made complex (`μ ± iδ`, `δ` about
/// `ε ω_max²/ω_min²` of `μ`), each their own way, and the highest modes then did not pair
/// (every interior mode kept was refused). A complex pair's vector `v` enters `V` as its
/// real and imaginary parts, which span the same real plane. With every mode that has mass
/// kept, `Φ_R` spans what `A` does not send to zero, so the reduction is exact ([`super`]).
fn two_sided_modes(k_ii: &DMatrix<f64>, m_ii: &DMatrix<f64>, count: usize) -> Result<(DMatrix<f64>, DMatrix<f64>, Vec<f64>), CmsError> {
    let n = k_ii.nrows();
    let singular = || unfit("the substructure's stiffness with its interface held is singular".into());
    let lu = k_ii.clone().lu();
    let a = lu.solve(m_ii).ok_or_else(singular)?;
    let e = Mat::from_fn(n, n, |r, c| a[(r, c)]).eigen().map_err(|e| unfit(format!("fixed-interface modes: eigendecomposition failed ({e:?})")))?;
    let (mu, u): (Vec<faer::c64>, _) = (e.S().column_vector().iter().copied().collect(), e.U());
    // Largest 1/ω² first; a complex pair's `+iδ` member before its `−iδ` one.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| mu[j].re.total_cmp(&mu[i].re).then(mu[j].im.total_cmp(&mu[i].im)));
    let mu: Vec<faer::c64> = order.iter().map(|&k| mu[k]).collect();
    let largest = mu.iter().map(|m| m.norm()).fold(0.0, f64::max);
    let with_mass = mu.iter().filter(|m| m.re > 1e-12 * largest).count();
    if count > with_mass {
        return Err(bad_option("modes", format!("{count}: the substructure with its interface held has {with_mass} modes that move mass (the other coordinates are massless)")));
    }
    for (j, m) in mu.iter().take(count).enumerate() {
        if m.im.abs() > 1e-6 * m.re {
            return Err(unfit(format!("fixed-interface mode {}: 1/omega^2 = {m} is not real (the substructure's stiffness is not symmetric enough for real modes)", j + 1)));
        }
    }
    if count > 0 && count < n && (mu[count - 1] - mu[count]).norm() <= 1e-9 * mu[count - 1].norm() {
        return Err(bad_option("modes", format!("{count}: fixed-interface modes {count} and {} share a frequency ({:.9e} rad/s): keeping one of them would choose an arbitrary direction of their plane; take one mode more or less", count + 1, 1.0 / mu[count - 1].re.sqrt())));
    }
    // V: real columns, unit modal mass for the kept ones (the largest entry positive), unit
    // length for the others.
    let mut v = DMatrix::from_fn(n, n, |i, j| {
        let x = u[(i, order[j])];
        if mu[j].im < 0.0 { x.im } else { x.re }
    });
    for j in 0..n {
        let c = v.column(j).into_owned();
        let big = c.iter().copied().fold(0.0f64, |b, x| if x.abs() > b.abs() { x } else { b });
        let norm = if j < count { (m_ii * &c).dot(&c).sqrt() } else { c.norm() } * big.signum();
        v.set_column(j, &(c / norm));
    }
    let defective = || bad_option("modes", format!("{count}: the fixed-interface modes of the non-symmetric stiffness do not span the interior coordinates (a defective mode)"));
    let y = v.clone().lu().try_inverse().filter(|y| y.iter().all(|x| x.is_finite()) && y.amax() * v.amax() < 1e12).ok_or_else(defective)?;
    let phi_r = v.columns(0, count).into_owned();
    let left = k_ii.transpose().lu().solve(&y.rows(0, count).transpose()).ok_or_else(singular)?;
    // `leftᵀ M Φ_R = Y A V` restricted to the kept modes: `diag(μ)`, but for a pair's 2 × 2
    // block `[[μ, δ], [−δ, μ]]`; its inverse makes `Φ_Lᵀ M Φ_R = I`.
    let pairing = left.transpose() * m_ii * &phi_r;
    let inverse = pairing.clone().try_inverse().filter(|i| i.iter().all(|x| x.is_finite())).ok_or_else(defective)?;
    let omega = mu.iter().take(count).map(|m| 1.0 / m.re.sqrt()).collect();
    Ok((phi_r, left * inverse.transpose(), omega))
}

/// Record 11: each node's translational masses and rotational inertias (its mass block's
/// diagonal), and the largest entry off those diagonals relative to the largest of `M`.
fn lumped_masses(mass: &DMatrix<f64>) -> (Vec<[f64; 6]>, f64) {
    let scale = mass.amax().max(f64::MIN_POSITIVE);
    let nodes = mass.nrows() / 6;
    let lumped = (0..nodes).map(|i| std::array::from_fn(|c| mass[(6 * i + c, 6 * i + c)])).collect();
    let off = (0..mass.nrows()).flat_map(|r| (0..mass.ncols()).map(move |c| (r, c))).filter(|(r, c)| r != c).map(|(r, c)| mass[(r, c)].abs()).fold(0.0, f64::max);
    (lumped, off / scale)
}

/// Record 12 from `M`: with `R` the six rigid motions about the origin (translations, then
/// rotations `u = θ × p`), `Rᵀ M R = [[m I, −[S×]], [[S×], J_O]]`; the centre of mass is
/// `S/m` and the inertia about it `J_O + m [c×][c×]`.
fn rigid_inertia(mass: &DMatrix<f64>, positions: &[Vec3]) -> RigidInertia {
    let n = mass.nrows();
    let mut r = DMatrix::zeros(n, 6);
    for (i, p) in positions.iter().enumerate() {
        let px = skew(p);
        for c in 0..3 {
            r[(6 * i + c, c)] = 1.0;
            r[(6 * i + 3 + c, 3 + c)] = 1.0;
            for k in 0..3 {
                // θ × p = −[p×] θ.
                r[(6 * i + c, 3 + k)] = -px[(c, k)];
            }
        }
    }
    let mrr = r.transpose() * mass * &r;
    let m = (mrr[(0, 0)] + mrr[(1, 1)] + mrr[(2, 2)]) / 3.0;
    // The block [rotations, translations] is [S×].
    let s = Vec3::new(mrr[(5, 1)], mrr[(3, 2)], mrr[(4, 0)]);
    let c = if m > 0.0 { s / m } else { Vec3::zeros() };
    let j_o = Mat3::from_fn(|a, b| mrr[(3 + a, 3 + b)]);
    let j_c = j_o + m * skew(&c) * skew(&c);
    RigidInertia { mass: m, centre_of_mass: [c[0], c[1], c[2]], inertia: std::array::from_fn(|a| std::array::from_fn(|b| j_c[(a, b)])) }
}

impl CraigBampton {
    /// Fixed-interface normal modes kept.
    pub fn normal_modes(&self) -> usize {
        self.fixed_interface_omega.len()
    }

    /// Constraint modes: six per interface node.
    pub fn constraint_modes(&self) -> usize {
        6 * self.interfaces.len()
    }

    /// Writes the FEM file to `path` (atomically); `source` names the substructure's file
    /// in the file's opening comment.
    pub fn write(&self, path: &std::path::Path, source: &str) -> Result<(), crate::output::atomic::OutputError> {
        let interfaces: Vec<String> = self.interfaces.iter().map(|l| l.to_string()).collect();
        let title = format!(
            "Craig-Bampton model of {source} written by romdyn cms {}: modes 1..{} fixed-interface normal modes\n(unit modal mass), modes {}..{} constraint modes of interface node(s) {} (x, y, z, rx, ry, rz each,\nunit displacement [m] or rotation [rad]). FEM frame = the global frame at the reference; SI units.",
            env!("CARGO_PKG_VERSION"),
            self.normal_modes(),
            self.normal_modes() + 1,
            self.fem.modes(),
            interfaces.join(", ")
        );
        crate::output::fem_file::write_fem(path, &self.fem, &title, self.constraint_modes())
    }

    /// The MBDyn card that attaches the FEM file `fem_name` to the interface nodes of the
    /// same labels (a `clamped` modal joint: [`super`]), every mode used.
    pub fn modal_joint_card(&self, label: Label, fem_name: &str) -> String {
        let mut s = format!("joint: {label}, modal, clamped, {}, from file, no damping, \"{fem_name}\",\n    {}", self.fem.modes(), self.interfaces.len());
        for l in &self.interfaces {
            s.push_str(&format!(",\n    \"{l}\", {l}, null"));
        }
        s.push(';');
        s
    }
}

impl CraigBampton {
    /// What `romdyn cms` prints: the file, its modes, the fixed-interface frequencies and the
    /// card that attaches it.
    pub fn summary(&self, path: &std::path::Path) -> String {
        let mut s = format!("{}: {} FEM nodes, {} modes ({} fixed-interface normal, {} constraint)\n", path.display(), self.fem.nodes(), self.fem.modes(), self.normal_modes(), self.constraint_modes());
        if !self.fixed_interface_omega.is_empty() {
            s.push_str("fixed-interface modes:\n  mode   omega [rad/s]   f [Hz]\n");
            for (j, w) in self.fixed_interface_omega.iter().enumerate() {
                s.push_str(&format!("  {:>4}   {:<14.6e}  {:.6e}\n", j + 1, w, w / std::f64::consts::TAU));
            }
        }
        let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
        s.push_str(&format!("attach it (interface nodes oriented as the global frame):\n{}\n", self.modal_joint_card(1000, &name)));
        s
    }
}
