//! Small 3-D kinematics: cross-product matrices and the Gibbs–Rodrigues orientation
//! parameters used for structural nodes (MBDyn's formulation, METHOD §5).

mod gibbs;
mod gibbs_derivatives;

pub use gibbs_derivatives::{gibbs_g_inverse, gibbs_g_inverse_derivative, gibbs_gt_apply, gibbs_gt_derivative, gibbs_gt_derivative_in_a, gibbs_gt_second_derivative};
pub use gibbs::{axial_of_skew_part, euler123, gibbs_compose, gibbs_from_rotation, gibbs_g, gibbs_rotation, gibbs_rate_derivative, rotation_vector, skew_part_jacobian};

/// 3-vector.
pub type Vec3 = nalgebra::Vector3<f64>;
/// 3x3 matrix.
pub type Mat3 = nalgebra::Matrix3<f64>;

/// `[v×]`, the cross-product matrix: `[v×] w = v × w`.
pub fn skew(v: &Vec3) -> Mat3 {
    Mat3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}
