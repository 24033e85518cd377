//! Quadratic Lagrange interpolation on ξ ∈ [−1, 1] (node 1 at −1, node 2 at 0, node 3 at
//! +1) and the two finite-volume evaluation points ξ = ∓1/√3 (Ghiringhelli, Masarati,
//! Mantegazza, AIAA J. 38(1), 2000).

/// `ξ` of evaluation points I and II.
pub const EVALUATION_POINTS: [f64; 2] = [-0.577_350_269_189_625_8, 0.577_350_269_189_625_8];

/// `N_i(ξ)`: `ξ(ξ−1)/2`, `1−ξ²`, `ξ(ξ+1)/2`.
pub fn values(xi: f64) -> [f64; 3] {
    [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)]
}

/// `dN_i/dξ`: `ξ−½`, `−2ξ`, `ξ+½`.
pub fn derivatives(xi: f64) -> [f64; 3] {
    [xi - 0.5, -2.0 * xi, xi + 0.5]
}

/// Fraction of an element's length (and of its mass, for uniform beams) in each node's
/// finite volume: `(1 − 1/√3)/2`, `1/√3`, `(1 − 1/√3)/2`.
pub fn volume_fractions() -> [f64; 3] {
    let end = 0.5 * (1.0 + EVALUATION_POINTS[0]);
    [end, 1.0 - 2.0 * end, end]
}
