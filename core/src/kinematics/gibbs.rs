//! Gibbs–Rodrigues parameters `g = 2 tan(φ/2) n`:
//! `R(g) = I + 4/(4 + gᵀg) ([g×] + ½ [g×]²)`, `G(g) = 4/(4 + gᵀg) (I + ½ [g×])`.
//! With `R = R(g) R_ref`, a variation is `δR Rᵀ = [(G δg)×]` and the angular velocity is
//! `ω = G(g) ġ`.

use super::{skew, Mat3, Vec3};

/// `R(g)`.
pub fn gibbs_rotation(g: &Vec3) -> Mat3 {
    let s = 4.0 / (4.0 + g.dot(g));
    let gx = skew(g);
    Mat3::identity() + s * (gx + 0.5 * gx * gx)
}

/// The parameters of the product `R(a) R(b)`: `(a + b + ½ a × b) / (1 − ¼ a·b)` (the
/// quaternions' product); undefined where the product turns by π. Near the identity it is
/// exact to round-off in each term: `R(a) R(b)` with `b ≈ −a` multiplied out as matrices
/// leaves an error of one ulp in each entry, this leaves `a + b`.
pub fn gibbs_compose(a: &Vec3, b: &Vec3) -> Vec3 {
    (a + b + 0.5 * a.cross(b)) / (1.0 - 0.25 * a.dot(b))
}

/// `G(g)`, with `δθ = G δg` and `ω = G ġ`.
pub fn gibbs_g(g: &Vec3) -> Mat3 {
    let s = 4.0 / (4.0 + g.dot(g));
    s * (Mat3::identity() + 0.5 * skew(g))
}

/// `∂(G(g) ġ)/∂g = −(s²/2)(ġ + ½ g×ġ) gᵀ − (s/2) [ġ×]`, `s = 4/(4 + gᵀg)`.
pub fn gibbs_rate_derivative(g: &Vec3, gdot: &Vec3) -> Mat3 {
    let s = 4.0 / (4.0 + g.dot(g));
    -(0.5 * s * s) * (gdot + 0.5 * g.cross(gdot)) * g.transpose() - 0.5 * s * skew(gdot)
}

/// `g` of a rotation matrix (through its quaternion); undefined for rotations by π.
pub fn gibbs_from_rotation(r: &Mat3) -> Vec3 {
    // Shepperd's direct method (from_rotation_matrix), not nalgebra's iterative from_matrix.
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(*r));
    let (w, v) = (q.w, q.imag());
    let v = if w < 0.0 { -v } else { v };
    2.0 * v / w.abs().max(f64::MIN_POSITIVE)
}

/// Rotation vector `φ n` of a rotation matrix. Below a quarter turn from the skew part,
/// `φ = atan2(sin φ, cos φ)` with `sin φ n = ax(R)`, full precision near the identity (an
/// angle from `acos` of the trace loses half the digits there, a residual floor for springs
/// on relative rotations); beyond, nalgebra's axis-angle.
pub fn rotation_vector(r: &Mat3) -> Vec3 {
    let v = axial_of_skew_part(r);
    let (s, c) = (v.norm(), 0.5 * (r.trace() - 1.0));
    if c > 0.0 {
        return if s > 0.0 { v * (s.atan2(c) / s) } else { Vec3::zeros() };
    }
    nalgebra::Rotation3::from_matrix_unchecked(*r).scaled_axis()
}

/// Euler angles `(a, b, c)` of `R = R_x(a) R_y(b) R_z(c)` (MBDyn's "euler123") [rad].
pub fn euler123(r: &Mat3) -> Vec3 {
    let b = r[(0, 2)].clamp(-1.0, 1.0).asin();
    Vec3::new((-r[(1, 2)]).atan2(r[(2, 2)]), b, (-r[(0, 1)]).atan2(r[(0, 0)]))
}

/// `ax(M) = ½ (M − Mᵀ)^∨`, the axial vector of the skew-symmetric part of `M`.
pub fn axial_of_skew_part(m: &Mat3) -> Vec3 {
    0.5 * Vec3::new(m[(2, 1)] - m[(1, 2)], m[(0, 2)] - m[(2, 0)], m[(1, 0)] - m[(0, 1)])
}

/// `P(M) = ½ (tr M I − M)`: `ax([a×] M) = P(M) a`.
pub fn skew_part_jacobian(m: &Mat3) -> Mat3 {
    0.5 * (m.trace() * Mat3::identity() - m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rot(axis: Vec3, angle: f64) -> Mat3 {
        *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
    }

    #[test]
    fn composed_parameters_give_the_product_of_the_rotations() {
        // R(a ∘ b) = R(a) R(b) to rounding (1e-15), for turns of 0.9 and 1.7 rad about
        // different axes; and a tiny rotation composed with its inverse is the identity
        // exactly (what the integrator's composition relies on).
        let (a, b) = (Vec3::new(0.3, -0.5, 0.2), Vec3::new(-1.1, 0.4, 0.9));
        let d = gibbs_rotation(&gibbs_compose(&a, &b)) - gibbs_rotation(&a) * gibbs_rotation(&b);
        assert!(d.abs().max() < 1e-15, "{d}");
        let tiny = Vec3::new(-3.6e-31, -3.4e-16, 6.3e-31);
        assert_eq!(gibbs_compose(&tiny, &-tiny), Vec3::zeros());
    }

    #[test]
    fn gibbs_rotation_matches_axis_angle() {
        // g = 2 tan(φ/2) n (definition): R(g) equals the axis-angle rotation to rounding.
        let (n, phi) = (Vec3::new(1.0, -2.0, 0.5).normalize(), 0.9_f64);
        let g = 2.0 * (phi / 2.0).tan() * n;
        assert!((gibbs_rotation(&g) - rot(n, phi)).norm() < 1e-14);
        assert!((gibbs_from_rotation(&rot(n, phi)) - g).norm() < 1e-13);
        assert!((rotation_vector(&rot(n, phi)) - phi * n).norm() < 1e-14);
    }

    #[test]
    fn euler123_inverts_its_definition() {
        let (a, b, c) = (0.3, -0.7, 1.2);
        let r = rot(Vec3::x(), a) * rot(Vec3::y(), b) * rot(Vec3::z(), c);
        assert!((euler123(&r) - Vec3::new(a, b, c)).norm() < 1e-14);
    }

    #[test]
    fn variation_is_g_times_dg() {
        // δR Rᵀ = [(G δg)×], checked by central differences (h = 1e-6, error O(h²)).
        let g = Vec3::new(0.3, -0.2, 0.4);
        let h = 1e-6;
        for k in 0..3 {
            let e = Vec3::ith(k, h);
            let dr = (gibbs_rotation(&(g + e)) - gibbs_rotation(&(g - e))) / (2.0 * h);
            let w = dr * gibbs_rotation(&g).transpose();
            let want = gibbs_g(&g) * Vec3::ith(k, 1.0);
            assert!((w - skew(&want)).norm() < 1e-8, "{k}");
        }
    }

    #[test]
    fn rate_derivative_matches_finite_differences() {
        let (g, gd) = (Vec3::new(0.3, -0.2, 0.4), Vec3::new(1.0, 2.0, -0.7));
        let h = 1e-6;
        let d = gibbs_rate_derivative(&g, &gd);
        for k in 0..3 {
            let e = Vec3::ith(k, h);
            let fd = (gibbs_g(&(g + e)) * gd - gibbs_g(&(g - e)) * gd) / (2.0 * h);
            assert!((fd - d.column(k)).norm() < 1e-8, "{k}");
        }
    }

    #[test]
    fn skew_part_jacobian_is_exact() {
        let m = rot(Vec3::new(0.2, 1.0, -0.3), 1.1) * 1.3;
        let a = Vec3::new(0.7, -0.4, 0.9);
        assert!((axial_of_skew_part(&(skew(&a) * m)) - skew_part_jacobian(&m) * a).norm() < 1e-14);
    }
}
