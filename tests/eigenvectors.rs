//! Right and adjoint eigenvectors satisfy eqs. 10 and 11, with the normalization the ROM
//! projection relies on.

mod common;

use faer::{c64, Col, Mat};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::Jacobians;

fn apply(m: &Mat<f64>, v: &Col<c64>, transpose: bool) -> Col<c64> {
    let n = m.nrows();
    Col::from_fn(n, |i| (0..n).fold(c64::new(0.0, 0.0), |s, j| s + v[j] * if transpose { m[(j, i)] } else { m[(i, j)] }))
}

fn norm(v: &Col<c64>) -> f64 {
    v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

/// A damped 3-DOF chain in first-order form with a non-symmetric (gyroscopic-like) term,
/// so that left and right vectors differ.
fn gyroscopic() -> Jacobians {
    let n = 6;
    let mut fyd = Mat::<f64>::zeros(n, n);
    let mut fy = Mat::<f64>::zeros(n, n);
    let (m, k, c, g) = ([1.0, 2.0, 3.0], [[300.0, -100.0, 0.0], [-100.0, 250.0, -150.0], [0.0, -150.0, 150.0]], 0.4, 5.0);
    for i in 0..3 {
        fyd[(i, i)] = m[i];
        fy[(i, 3 + i)] = -m[i];
        fyd[(3 + i, 3 + i)] = m[i];
        fyd[(3 + i, i)] = c;
        for j in 0..3 {
            fy[(3 + i, j)] = k[i][j];
        }
    }
    fyd[(3, 4)] = g;
    fyd[(4, 3)] = -g;
    Jacobians::Derivatives { fyd, fy }
}

#[test]
fn vectors_solve_the_right_and_adjoint_problems() {
    for route in [EigenRoute::Direct, EigenRoute::Lambda] {
        let jac = gyroscopic();
        let (fyd, fy) = jac.derivatives();
        let modal = ModalAnalysis::compute(&jac, route).unwrap();
        assert_eq!(modal.count(ModeKind::Dynamic), 6, "{route:?}");
        for (k, m) in modal.modes.iter().enumerate() {
            let (v, u) = (m.right.as_ref().unwrap(), m.left.as_ref().unwrap());
            let (fv, kv) = (apply(&fyd, v, false), apply(&fy, v, false));
            let right = Col::from_fn(v.nrows(), |i| m.lambda * fv[i] + kv[i]);
            let (fu, ku) = (apply(&fyd, u, true), apply(&fy, u, true));
            let left = Col::from_fn(u.nrows(), |i| m.lambda * fu[i] + ku[i]);
            // Backward-stable QZ: residuals at rounding level relative to ‖F‖ ‖v‖ (1e-12 with margin).
            let scale = fy.norm_l2() + m.lambda.norm() * fyd.norm_l2();
            assert!(norm(&right) < 1e-12 * scale * norm(v), "{route:?} mode {k}: right residual {}", norm(&right));
            assert!(norm(&left) < 1e-12 * scale * norm(u), "{route:?} mode {k}: left residual {}", norm(&left));
            // Normalization: ‖v‖ = 1 and uᵀ F_yd v = 1.
            assert!((norm(v) - 1.0).abs() < 1e-12);
            let p = u.iter().zip(fv.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b);
            assert!((p - c64::new(1.0, 0.0)).norm() < 1e-10, "{route:?} mode {k}: uᵀ F_yd v = {p}");
            // Pairs are adjacent and conjugate.
            if let Some(p) = m.partner {
                assert_eq!(modal.modes[p].lambda, m.lambda.conj());
                assert_eq!(modal.modes[p].partner, Some(k));
            }
        }
    }
}
