//! Orientation matrices as written in the input (input manual, "General", §Orientation
//! Matrix): `eye`; `matr` and nine values by rows; `euler`/`euler123`/`euler313`/
//! `euler321` with three angles in radians, or in degrees after `degrees`; `vector` and a
//! rotation vector (`R = exp(v×)`); or two vectors each after its axis index,
//! `i, v_i, j, {v_j | guess}`: axis `i` along `v_i`, axis `j` in the plane of `v_i, v_j`.
//! `null` is rejected, as MBDyn does: a zero matrix is not a rotation.

use nalgebra::{Rotation3, Unit};

use super::cursor::Cursor;
use super::diagnostic::MbdynError;
use crate::kinematics::{Mat3, Vec3};

/// Deviation from orthogonality (`|RᵀR − I|`, Frobenius) accepted in a `matr`: entries
/// written with about five digits; the matrix is then replaced by the nearest rotation.
const MATR_TOLERANCE: f64 = 1e-4;

fn about(axis: Vec3, angle: f64) -> Mat3 {
    *Rotation3::from_axis_angle(&Unit::new_unchecked(axis), angle).matrix()
}

/// An orientation matrix (without a `reference` prefix: see `references`).
pub fn orientation_values(c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
    if c.peek_keyword().is_some_and(|w| w == "null") {
        return Err(c.error(format!("{what}: an orientation cannot be 'null' (a zero matrix is not a rotation); write 'eye' for no rotation")));
    }
    if c.accept("eye") {
        return Ok(Mat3::identity());
    }
    if c.accept("matr") {
        let span = c.here();
        let mut v = [0.0; 9];
        for x in &mut v {
            *x = c.real(&format!("{what}: an orientation matrix entry"))?;
        }
        return orthogonal(Mat3::from_row_slice(&v)).ok_or_else(|| c.error_at(span, format!("{what}: the 'matr' orientation is not a rotation matrix (RᵀR differs from the identity by more than {MATR_TOLERANCE}, or det R < 0)")));
    }
    if let Some(kind) = c.accept_any(&["euler123", "euler313", "euler321", "euler"]) {
        let scale = if c.accept("degrees") { std::f64::consts::PI / 180.0 } else { 1.0 };
        let unit = if scale == 1.0 { "rad" } else { "deg" };
        let axes = match kind {
            "euler313" => ["z", "x", "z"],
            "euler321" => ["z", "y", "x"],
            _ => ["x", "y", "z"],
        };
        let mut a = [0.0; 3];
        for (x, axis) in a.iter_mut().zip(axes) {
            *x = scale * c.real(&format!("{what}: angle about {axis} [{unit}]"))?;
        }
        let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
        return Ok(match kind {
            "euler313" => about(z, a[0]) * about(x, a[1]) * about(z, a[2]),
            "euler321" => about(z, a[0]) * about(y, a[1]) * about(x, a[2]),
            _ => about(x, a[0]) * about(y, a[1]) * about(z, a[2]),
        });
    }
    if c.accept("vector") {
        let v = c.vec3_values(&format!("{what}: rotation vector component [rad]"))?;
        return Ok(*Rotation3::new(v).matrix());
    }
    two_vectors(c, what)
}

/// The rotation nearest to `m` if `m` is close enough to one.
fn orthogonal(m: Mat3) -> Option<Mat3> {
    if !m.iter().all(|x| x.is_finite()) || ((m.transpose() * m) - Mat3::identity()).norm() > MATR_TOLERANCE || m.determinant() <= 0.0 {
        return None;
    }
    let svd = m.svd(true, true);
    Some(svd.u? * svd.v_t?)
}

fn axis_index(c: &mut Cursor, what: &str) -> Result<usize, MbdynError> {
    let span = c.here();
    let k = c.real(&format!("{what}: 'eye', 'matr', 'euler…', 'vector' or an axis index (1, 2 or 3)"))?;
    if ![1.0, 2.0, 3.0].contains(&k) {
        return Err(c.error_at(span, format!("{what}: axis index must be 1, 2 or 3, found {k}")));
    }
    Ok(k as usize - 1)
}

/// `i, v_i, j, v_j`: `e_i = v_i/|v_i|`, the third axis `k` normal to both, `e_j` completing
/// a right-handed frame (input manual, figure "Construction of 3x3 orientation matrix from
/// two non-parallel vectors"); `guess` picks a `v_j` orthogonal to `v_i`.
fn two_vectors(c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
    let i = axis_index(c, what)?;
    let vi_span = c.here();
    let vi = c.vec3_values(&format!("{what}: component of the vector of axis {}", i + 1))?;
    let j_span = c.here();
    let j = axis_index(c, what)?;
    if i == j {
        return Err(c.error_at(j_span, format!("{what}: the two axis indices must differ, both are {}", i + 1)));
    }
    let vj_span = c.here();
    let vj = if c.accept("guess") { guess(&vi) } else { c.vec3_values(&format!("{what}: component of the vector of axis {}", j + 1))? };
    let Some(ei) = vi.try_normalize(1e-300) else {
        return Err(c.error_at(vi_span, format!("{what}: the two vectors are null or parallel (the vector of axis {} is null)", i + 1)));
    };
    let k = 3 - i - j;
    // (i, j, k) cyclic: e_k = e_i × v_j; otherwise the opposite.
    let sign = if (j + 3 - i) % 3 == 1 { 1.0 } else { -1.0 };
    let Some(ek) = (sign * ei.cross(&vj)).try_normalize(1e-12 * vj.norm().max(1e-300)) else {
        return Err(c.error_at(vj_span, format!("{what}: the two vectors are null or parallel (axes {} and {})", i + 1, j + 1)));
    };
    let ej = sign * ek.cross(&ei);
    let mut m = Mat3::zeros();
    m.set_column(i, &ei);
    m.set_column(j, &ej);
    m.set_column(k, &ek);
    Ok(m)
}

/// MBDyn's guess: 1 at the smallest component of `v`, `−v_min/v_max` at the largest, 0 at
/// the other.
fn guess(v: &Vec3) -> Vec3 {
    let (mut small, mut large) = (0, 0);
    for k in 1..3 {
        if v[k].abs() < v[small].abs() {
            small = k;
        }
        if v[k].abs() >= v[large].abs() {
            large = k;
        }
    }
    if small == large {
        large = (small + 1) % 3;
    }
    let mut g = Vec3::zeros();
    g[small] = 1.0;
    if v[large] != 0.0 {
        g[large] = -v[small] / v[large];
    }
    g
}
