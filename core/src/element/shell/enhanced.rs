//! What the 4-node shells and the membrane share about their enhanced-strain parameters
//! `β` (the element's own algebraic unknowns, MBDyn's `DofOrder::ALGEBRAIC`): with `B_i`
//! the strains' derivatives at Gauss point `i` (S strains, Q node coordinates), `P_i` the
//! enhanced-strain matrix and `σ_i` the stress resultants, the internal forces
//! `Σ_i α_i Bᵢᵀ σ_i` on the nodes and `Σ_i α_i P_iᵀ σ_i` on `β`, and the tangent's linear
//! part `Σ_i α_i (Bᵀ D B, Bᵀ D P, Pᵀ D P)` (`α_i` the area factor, Gauss weights 1).

use nalgebra::{SMatrix, SVector};

use super::geometry::EAS;
use crate::element::contract::{Col, JacobianSink, Row};

/// One Gauss point's `B_i`, `P_i`, `σ_i` and `α_i`.
pub struct Sampled<'a, const S: usize, const Q: usize> {
    pub b: &'a SMatrix<f64, S, Q>,
    pub p: &'a SMatrix<f64, S, EAS>,
    pub stress: &'a SVector<f64, S>,
    pub area: f64,
}

/// `(Σ α Bᵀ σ, Σ α Pᵀ σ)`.
pub fn internal_forces<'a, const S: usize, const Q: usize>(points: impl Iterator<Item = Sampled<'a, S, Q>>) -> (SVector<f64, Q>, SVector<f64, EAS>) {
    let mut fq = SVector::<f64, Q>::zeros();
    let mut fb = SVector::<f64, EAS>::zeros();
    for s in points {
        fq += s.b.transpose() * s.stress * s.area;
        fb += s.p.transpose() * s.stress * s.area;
    }
    (fq, fb)
}

/// `(Σ α Bᵀ D B, Σ α Bᵀ D P, Σ α Pᵀ D P)` for the section law `D`.
pub fn linear_tangent<'a, const S: usize, const Q: usize>(d: &SMatrix<f64, S, S>, points: impl Iterator<Item = Sampled<'a, S, Q>>) -> (SMatrix<f64, Q, Q>, SMatrix<f64, Q, EAS>, SMatrix<f64, EAS, EAS>) {
    let mut kqq = SMatrix::<f64, Q, Q>::zeros();
    let mut kqb = SMatrix::<f64, Q, EAS>::zeros();
    let mut kbb = SMatrix::<f64, EAS, EAS>::zeros();
    for s in points {
        let db = d * s.b;
        let dp = d * s.p;
        kqq += s.b.transpose() * db * s.area;
        kqb += s.b.transpose() * dp * s.area;
        kbb += s.p.transpose() * dp * s.area;
    }
    (kqq, kqb, kbb)
}

/// Adds `K_qq` on the nodes' rows and columns (`row(q)`, `col(q)`), `K_qβ` and its
/// transpose `K_βq` (the `β` equations are the derivatives of the same energy) and `K_ββ`,
/// for the first `enhanced` parameters.
pub fn add_tangent<const Q: usize>(out: &mut dyn JacobianSink, (kq, kqb, kbb): (&SMatrix<f64, Q, Q>, &SMatrix<f64, Q, EAS>, &SMatrix<f64, EAS, EAS>), enhanced: usize, row: impl Fn(usize) -> Row, col: impl Fn(usize) -> Col) {
    for r in 0..Q {
        for c in 0..Q {
            out.add(row(r), col(c), kq[(r, c)]);
        }
        for k in 0..enhanced {
            out.add(row(r), Col::Multiplier(k), kqb[(r, k)]);
            out.add(Row::Constraint(k), col(r), kqb[(r, k)]);
        }
    }
    for a in 0..enhanced {
        for b in 0..enhanced {
            out.add(Row::Constraint(a), Col::Multiplier(b), kbb[(a, b)]);
        }
    }
}
