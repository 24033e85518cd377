//! What a 4-node shell computes once from its initial configuration (MBDyn 1.7.3's
//! `shell4eas`, after Witkowski, Comput Mech 43 (2009) 307–319): the bilinear shape
//! functions, the nodes' and the 2×2 Gauss points' frames, the derivatives with respect to
//! the local Cartesian coordinates, the area factors and the enhanced-strain matrices `P_i`.
//!
//! Node `n` sits at the natural coordinates `ξ_n` = (1, 1), (−1, 1), (−1, −1), (1, −1)
//! (MBDyn's numbering); the Gauss points at (∓1/√3, ∓1/√3) in the order (−,−), (+,−),
//! (+,+), (−,+), each of weight 1.

use crate::kinematics::{rotation_vector, Mat3, Vec3};

pub const NODE_XI: [[f64; 2]; 4] = [[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]];

const G: f64 = 0.577_350_269_189_625_8;
pub const POINT_XI: [[f64; 2]; 4] = [[-G, -G], [G, -G], [G, G], [-G, G]];

/// `shell4easans`'s tying points A, B, C, D: the midpoints of the edges, where the
/// transverse shear strains are sampled.
pub const TYING_XI: [[f64; 2]; 4] = [[0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [1.0, 0.0]];

/// Number of enhanced-strain parameters of `shell4eas` (MBDyn's `iGetNumDof`).
pub const EAS: usize = 13;

/// The first 7 of them, which enhance the membrane strains only: `shell4easans`'s and
/// `membrane4eas`'s.
pub const MEMBRANE_EAS: usize = 7;

/// `L_n(ξ) = ¼ (1 + ξ₁ ξ₁ₙ)(1 + ξ₂ ξ₂ₙ)`.
pub fn shape(n: usize, xi: [f64; 2]) -> f64 {
    0.25 * (1.0 + xi[0] * NODE_XI[n][0]) * (1.0 + xi[1] * NODE_XI[n][1])
}

/// `∂L_n/∂ξ_a`.
pub fn shape_derivative(n: usize, a: usize, xi: [f64; 2]) -> f64 {
    let b = 1 - a;
    0.25 * NODE_XI[n][a] * (1.0 + xi[b] * NODE_XI[n][b])
}

/// `∂x/∂ξ_a` of the bilinear surface through `x`.
fn surface_tangent(x: &[Vec3; 4], a: usize, xi: [f64; 2]) -> Vec3 {
    (0..4).map(|n| x[n] * shape_derivative(n, a, xi)).sum()
}

/// The orthonormal frame at `ξ`: `t₁` along `∂x/∂ξ₁`, `t₃` normal, `t₂ = t₃ × t₁`.
pub fn surface_frame(x: &[Vec3; 4], xi: [f64; 2]) -> Mat3 {
    let t1 = surface_tangent(x, 0, xi).normalize();
    let t3 = t1.cross(&surface_tangent(x, 1, xi).normalize()).normalize();
    Mat3::from_columns(&[t1, t3.cross(&t1), t3])
}

/// `S_ab = t_a · ∂x/∂ξ_b` in the frame `t` at `ξ`: the Jacobian of local Cartesian
/// coordinates with respect to natural ones.
pub fn metric(x: &[Vec3; 4], t: &Mat3, xi: [f64; 2]) -> nalgebra::Matrix2<f64> {
    nalgebra::Matrix2::from_fn(|a, b| t.column(a).dot(&surface_tangent(x, b, xi)))
}

/// The local Cartesian derivatives `∂L_n/∂s_α` (`[n][α]`) at `ξ` in the frame `t` and the
/// area factor `α = det S`; the area factor itself when it is not positive (a degenerate
/// quadrilateral).
pub fn cartesian_derivatives(x: &[Vec3; 4], t: &Mat3, xi: [f64; 2]) -> Result<([[f64; 2]; 4], f64), f64> {
    let s = metric(x, t, xi);
    let area = s.determinant();
    let Some(s_inv) = s.try_inverse().filter(|_| area > 0.0 && area.is_finite()) else {
        return Err(area);
    };
    let dl = std::array::from_fn(|n| {
        let d = [shape_derivative(n, 0, xi), shape_derivative(n, 1, xi)];
        [d[0] * s_inv[(0, 0)] + d[1] * s_inv[(1, 0)], d[0] * s_inv[(0, 1)] + d[1] * s_inv[(1, 1)]]
    });
    Ok((dl, area))
}

/// The average frame `T̄` of the nodes' frames `F_n`: the rotation of the rotation vector of
/// `Σ F_n / 4` (MBDyn: `RotManip::Rot(RotManip::VecRot(T_avg))`; for a flat element all
/// `F_n` are equal and `T̄` is their frame).
pub fn average_frame(frames: &[Mat3; 4]) -> Mat3 {
    let avg: Mat3 = frames.iter().sum::<Mat3>() / 4.0;
    nalgebra::Rotation3::new(rotation_vector(&avg)).into_inner()
}

/// The rows of `H(ξ)` the shells and the membrane share (Witkowski's semi-EAS): ξ₁, ξ₁ξ₂ on
/// ε₁₁ (row 0); ξ₂, ξ₁ξ₂ on ε₂₂ (row 1); ξ₁, ξ₁ξ₂ on ε₁₂ (row 2); the other rows zero.
fn membrane_interpolation<const R: usize>(xi: [f64; 2]) -> nalgebra::SMatrix<f64, R, EAS> {
    let mut h = nalgebra::SMatrix::<f64, R, EAS>::zeros();
    let t = xi[0] * xi[1];
    for (r, c, v) in [(0, 0, xi[0]), (0, 1, t), (1, 2, xi[1]), (1, 3, t), (2, 4, xi[0]), (2, 5, t)] {
        h[(r, c)] = v;
    }
    h
}

/// The enhanced-strain matrix of Gauss point `xi` (12 × 13): the interpolation `H(ξ)` of
/// the membrane and transverse-shear strains (6 × 13, Witkowski's semi-EAS), mapped by the
/// inverse transpose of the centre's metric (`M₀⁻ᵀ`), scaled by `α₀/αᵢ` (the ratio of area
/// factors), its rows placed as the strains are ordered (ε₁₁, ε₁₂, ε₁₃, ε₂₁, ε₂₂, ε₂₃; the
/// curvatures are not enhanced).
pub fn enhanced_strain_matrix(s0: &nalgebra::Matrix2<f64>, xi: [f64; 2], ratio: f64) -> nalgebra::SMatrix<f64, 12, EAS> {
    let mut h = membrane_interpolation::<6>(xi);
    h[(3, 6)] = xi[1];
    h[(3, 5)] = xi[0] * xi[1];
    let a = 2.0 * xi[0] * (xi[1] * xi[1] - 1.0);
    let b = 2.0 * xi[1] * (xi[0] * xi[0] - 1.0);
    h[(4, 7)] = a;
    h[(4, 8)] = b;
    h[(4, 9)] = a * b;
    h[(5, 10)] = b;
    h[(5, 11)] = a;
    h[(5, 12)] = a * b;
    let s = |a: usize, b: usize| s0[(a, b)];
    // The metric's action on (ε₁₁, ε₂₂, ε₁₂, ε₂₁) and on the transverse shears (ε₁₃, ε₂₃).
    let mut m = nalgebra::Matrix6::<f64>::zeros();
    m[(0, 0)] = s(0, 0) * s(0, 0);
    m[(0, 1)] = s(0, 1) * s(0, 1);
    m[(0, 2)] = s(0, 1) * s(0, 0);
    m[(0, 3)] = s(0, 0) * s(0, 1);
    m[(1, 0)] = s(1, 0) * s(1, 0);
    m[(1, 1)] = s(1, 1) * s(1, 1);
    m[(1, 2)] = s(1, 1) * s(1, 0);
    m[(1, 3)] = s(1, 0) * s(1, 1);
    m[(2, 0)] = s(0, 0) * s(1, 0);
    m[(2, 1)] = s(0, 1) * s(1, 1);
    m[(2, 2)] = s(0, 0) * s(1, 1);
    m[(2, 3)] = s(0, 1) * s(1, 0);
    m[(3, 0)] = s(0, 0) * s(1, 0);
    m[(3, 1)] = s(0, 1) * s(1, 1);
    m[(3, 2)] = s(0, 1) * s(1, 0);
    m[(3, 3)] = s(0, 0) * s(1, 1);
    m[(4, 4)] = s(0, 0);
    m[(4, 5)] = s(0, 1);
    m[(5, 4)] = s(1, 0);
    m[(5, 5)] = s(1, 1);
    let m_inv = m.try_inverse().unwrap_or_else(nalgebra::Matrix6::zeros);
    let mapped = m_inv.transpose() * h;
    // Rows of `mapped` (ε₁₁, ε₂₂, ε₁₂, ε₂₁, ε₁₃, ε₂₃) into the strain order.
    const PLACE: [usize; 6] = [0, 4, 1, 3, 2, 5];
    let mut p = nalgebra::SMatrix::<f64, 12, EAS>::zeros();
    for (r, &row) in PLACE.iter().enumerate() {
        p.set_row(row, &(mapped.row(r) * ratio));
    }
    p
}

/// The enhanced-strain matrix of a membrane's Gauss point `xi` (3 × 13, only the first
/// [`MEMBRANE_EAS`] columns used; MBDyn's membraneeas.cc): the interpolation `H(ξ)` of
/// (ε₁₁, ε₂₂, ε₁₂) (3 × 7: ξ₁, ξ₁ξ₂ on ε₁₁; ξ₂, ξ₁ξ₂ on ε₂₂; ξ₁, ξ₁ξ₂, ξ₂ on ε₁₂), mapped by
/// the inverse transpose of the centre's metric acting on the Green–Lagrange strains
/// (`M₀⁻ᵀ`), scaled by `α₀/αᵢ`.
pub fn membrane_enhanced_strain_matrix(s0: &nalgebra::Matrix2<f64>, xi: [f64; 2], ratio: f64) -> nalgebra::SMatrix<f64, 3, EAS> {
    let mut h = membrane_interpolation::<3>(xi);
    h[(2, 6)] = xi[1];
    let s = |a: usize, b: usize| s0[(a, b)];
    let m = nalgebra::Matrix3::new(
        s(0, 0) * s(0, 0),
        s(0, 1) * s(0, 1),
        s(0, 1) * s(0, 0),
        s(1, 0) * s(1, 0),
        s(1, 1) * s(1, 1),
        s(1, 1) * s(1, 0),
        s(0, 0) * s(1, 0),
        s(0, 1) * s(1, 1),
        s(0, 0) * s(1, 1) + s(0, 1) * s(1, 0),
    );
    m.try_inverse().unwrap_or_else(nalgebra::Matrix3::zeros).transpose() * h * ratio
}
