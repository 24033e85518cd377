//! Derivatives of the Gibbs–Rodrigues maps needed by elements that interpolate rotations
//! (the 3-node beam): the inverse map `Γ(g) = G(g)⁻¹`, the transposed map `Gᵀ(g)`, and
//! their derivatives with respect to `g`.
//!
//! With `s = 4/(4 + gᵀg)`: `G(g) = s (I + ½[g×])`, `Gᵀ(g) a = s (a − ½ g × a)`,
//! `Γ(g) = I − ½[g×] + ¼ g gᵀ`.

use super::{skew, Mat3, Vec3};

fn s_of(g: &Vec3) -> f64 {
    4.0 / (4.0 + g.dot(g))
}

/// `Γ(g) = G(g)⁻¹ = I − ½[g×] + ¼ g gᵀ`: `δg = Γ δθ`, `ġ = Γ ω`.
pub fn gibbs_g_inverse(g: &Vec3) -> Mat3 {
    Mat3::identity() - 0.5 * skew(g) + 0.25 * g * g.transpose()
}

/// `∂(Γ(g) w)/∂g = ½[w×] + ¼ (gᵀw I + g wᵀ)`.
pub fn gibbs_g_inverse_derivative(g: &Vec3, w: &Vec3) -> Mat3 {
    0.5 * skew(w) + 0.25 * (g.dot(w) * Mat3::identity() + g * w.transpose())
}

/// `Gᵀ(g) a = s (a − ½ g × a)`.
pub fn gibbs_gt_apply(g: &Vec3, a: &Vec3) -> Vec3 {
    s_of(g) * (a - 0.5 * g.cross(a))
}

/// `∂(Gᵀ(g) a)/∂g = (s/2)[a×] − (s²/2)(a − ½ g × a) gᵀ`.
pub fn gibbs_gt_derivative(g: &Vec3, a: &Vec3) -> Mat3 {
    let s = s_of(g);
    0.5 * s * skew(a) - 0.5 * s * s * (a - 0.5 * g.cross(a)) * g.transpose()
}

/// `∂/∂g [∂(Gᵀ(g) a)/∂g · b]` for fixed `a`, `b`:
/// `−(s²/4)(a × b) gᵀ + (s³/2)(gᵀb) u gᵀ − (s²/2) u bᵀ − (s²/4)(gᵀb)[a×]`, `u = a − ½ g × a`.
pub fn gibbs_gt_second_derivative(g: &Vec3, a: &Vec3, b: &Vec3) -> Mat3 {
    let s = s_of(g);
    let u = a - 0.5 * g.cross(a);
    let gb = g.dot(b);
    -0.25 * s * s * a.cross(b) * g.transpose() + 0.5 * s.powi(3) * gb * u * g.transpose() - 0.5 * s * s * u * b.transpose() - 0.25 * s * s * gb * skew(a)
}

/// `∂/∂a [∂(Gᵀ(g) a)/∂g · b] = −(s/2)[b×] − (s²/2)(gᵀb)(I − ½[g×])`.
pub fn gibbs_gt_derivative_in_a(g: &Vec3, b: &Vec3) -> Mat3 {
    let s = s_of(g);
    -0.5 * s * skew(b) - 0.5 * s * s * g.dot(b) * (Mat3::identity() - 0.5 * skew(g))
}

#[cfg(test)]
mod tests {
    use super::super::{gibbs_g, gibbs_rotation};
    use super::*;

    const H: f64 = 1e-6;

    /// Central difference of `f` along each coordinate: a 3x3 Jacobian (error O(h²)).
    fn fd(f: impl Fn(&Vec3) -> Vec3, at: &Vec3) -> Mat3 {
        let mut m = Mat3::zeros();
        for k in 0..3 {
            let e = Vec3::ith(k, H);
            m.set_column(k, &((f(&(at + e)) - f(&(at - e))) / (2.0 * H)));
        }
        m
    }

    fn data() -> (Vec3, Vec3, Vec3) {
        (Vec3::new(0.4, -0.3, 0.7), Vec3::new(1.2, -0.5, 0.3), Vec3::new(-0.2, 0.9, 0.6))
    }

    #[test]
    fn inverse_map_inverts_g() {
        let (g, _, _) = data();
        assert!((gibbs_g_inverse(&g) * gibbs_g(&g) - Mat3::identity()).norm() < 1e-14);
    }

    #[test]
    fn transposed_map_is_rotation_transpose_times_g() {
        // Rᵀ(g) G(g) = Gᵀ(g): the identity behind the curvature measure of the beam.
        let (g, a, _) = data();
        let rt_g = gibbs_rotation(&g).transpose() * gibbs_g(&g);
        assert!((rt_g - gibbs_g(&g).transpose()).norm() < 1e-14);
        assert!((gibbs_gt_apply(&g, &a) - gibbs_g(&g).transpose() * a).norm() < 1e-14);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (g, a, b) = data();
        let tol = 1e-8;
        let d = fd(|x| gibbs_g_inverse(x) * a, &g);
        assert!((d - gibbs_g_inverse_derivative(&g, &a)).norm() < tol);
        let d = fd(|x| gibbs_gt_apply(x, &a), &g);
        assert!((d - gibbs_gt_derivative(&g, &a)).norm() < tol);
        let d = fd(|x| gibbs_gt_derivative(x, &a) * b, &g);
        assert!((d - gibbs_gt_second_derivative(&g, &a, &b)).norm() < tol);
        let d = fd(|x| gibbs_gt_derivative(&g, x) * b, &a);
        assert!((d - gibbs_gt_derivative_in_a(&g, &b)).norm() < tol);
    }
}
