//! Removing soft grounding ("dummy") springs from a ROM (paper eqs. 92–95).
//!
//! The sign. romdyn's inputs are applied forces, `−ΔF = B̃ u` (eq. 38): the linear DAE is
//! `F_yd Δẏ + F_y Δy = B̃ u`. A spring's own part of the residual is
//! `B̃_e (K C̃_e Δy + C_v C̃_e Δẏ)` ([`ElementPart`]), so the model without it is
//! `F_yd Δẏ + F_y Δy = B̃ u + B̃_e (K z_e + C_v ż_e)` with `z_e = C̃_e Δy`: removing a spring
//! means feeding its force back with a plus sign, `u_s = +K z_e + C_v ż_e`. On a descriptor ROM
//! (`B_e = Wᵀ B̃_e`, `C_e = C̃_e V`):
//!
//! ```text
//! (E − B_e C_v C_e) ẋ = (A + B_e K C_e) x + B u
//! ```
//!
//! The paper's eq. 95, `A − B K C_e`, is written for `u_s = −K z_e` being the spring's force
//! *added* as an input; applied to a ROM whose inputs are applied forces it adds the spring a
//! second time (doubles it) instead of removing it.

use faer::Mat;

use super::{DescriptorRom, RomError};
use crate::dae::ElementPart;
use crate::linear::{Jacobians, LinearDae};

/// The springs' coordinates, appended to a linear DAE as its last inputs and outputs, and
/// their stiffness and viscosity (block diagonal over the springs).
#[derive(Clone, Debug)]
pub struct SpringFeedback {
    pub elements: Vec<String>,
    pub k: Mat<f64>,
    pub viscosity: Mat<f64>,
    /// Number of appended inputs (= outputs).
    pub coordinates: usize,
}

fn block_diagonal(blocks: &[&Mat<f64>]) -> Mat<f64> {
    let n: usize = blocks.iter().map(|b| b.nrows()).sum();
    let mut out = Mat::zeros(n, n);
    let mut o = 0;
    for b in blocks {
        for i in 0..b.nrows() {
            for j in 0..b.ncols() {
                out[(o + i, o + j)] = b[(i, j)];
            }
        }
        o += b.nrows();
    }
    out
}

fn stack_columns(a: &Mat<f64>, extra: &[&Mat<f64>]) -> Mat<f64> {
    let total = a.ncols() + extra.iter().map(|m| m.ncols()).sum::<usize>();
    let mut cols: Vec<(&Mat<f64>, usize)> = (0..a.ncols()).map(|j| (a, j)).collect();
    for m in extra {
        cols.extend((0..m.ncols()).map(|j| (*m, j)));
    }
    Mat::from_fn(a.nrows(), total, |i, j| cols[j].0[(i, cols[j].1)])
}

fn stack_rows(a: &Mat<f64>, extra: &[&Mat<f64>]) -> Mat<f64> {
    let total = a.nrows() + extra.iter().map(|m| m.nrows()).sum::<usize>();
    let mut rows: Vec<(&Mat<f64>, usize)> = (0..a.nrows()).map(|i| (a, i)).collect();
    for m in extra {
        rows.extend((0..m.nrows()).map(|i| (*m, i)));
    }
    Mat::from_fn(total, a.ncols(), |i, j| rows[i].0[(rows[i].1, j)])
}

/// `dae` with the springs' coordinates appended as inputs (`B̃_e`) and outputs (`C̃_e`),
/// and the feedback that removes them from a ROM projected from it.
pub fn with_spring_ports(dae: &LinearDae, parts: &[ElementPart]) -> (LinearDae, SpringFeedback) {
    let bs: Vec<&Mat<f64>> = parts.iter().map(|p| &p.b).collect();
    let cs: Vec<&Mat<f64>> = parts.iter().map(|p| &p.c).collect();
    let m: usize = parts.iter().map(|p| p.k.nrows()).sum();
    let mut out = dae.clone();
    out.b = stack_columns(&dae.b, &bs);
    out.c = stack_rows(&dae.c, &cs);
    out.c_rate = dae.c_rate.as_ref().map(|cv| stack_rows(cv, &[&Mat::zeros(m, cv.ncols())]));
    for p in parts {
        out.input_names.extend(p.coordinates.iter().map(|c| format!("{} force on {c}", p.element)));
        out.output_names.extend(p.coordinates.iter().map(|c| format!("{} {c}", p.element)));
    }
    let feedback = SpringFeedback {
        elements: parts.iter().map(|p| p.element.clone()).collect(),
        k: block_diagonal(&parts.iter().map(|p| &p.k).collect::<Vec<_>>()),
        viscosity: block_diagonal(&parts.iter().map(|p| &p.viscosity).collect::<Vec<_>>()),
        coordinates: m,
    };
    (out, feedback)
}

/// The full linear DAE without the elements: `F_y − B̃_e K C̃_e`, `F_yd − B̃_e C_v C̃_e`.
pub fn without_elements(dae: &LinearDae, parts: &[ElementPart]) -> LinearDae {
    let mut out = dae.clone();
    for p in parts {
        let dk = &p.b * &p.k * &p.c;
        let dv = &p.b * &p.viscosity * &p.c;
        out.jacobians = match &out.jacobians {
            Jacobians::Derivatives { fyd, fy } => Jacobians::Derivatives { fyd: fyd - &dv, fy: fy - &dk },
            Jacobians::Coefficient { j, jstar, dcoef } => {
                let c = *dcoef;
                Jacobians::Coefficient { j: j - (&dv + &dk * faer::Scale(c)), jstar: jstar - (&dv - &dk * faer::Scale(c)), dcoef: c }
            }
        };
    }
    out
}

impl DescriptorRom {
    /// Closes the spring-removal feedback on a ROM projected from [`with_spring_ports`]'s
    /// DAE and drops the springs' inputs and outputs. The eigenvalues are recomputed from
    /// the ordinary form: rigid-body (zero) and unstable (positive real) ones included.
    pub fn without_springs(&self, fb: &SpringFeedback) -> Result<DescriptorRom, RomError> {
        let m = fb.coordinates;
        let (ni, no) = (self.b.ncols() - m, self.c.nrows() - m);
        let be = self.b.get(.., ni..).to_owned();
        let ce = self.c.get(no.., ..).to_owned();
        let mut rom = self.clone();
        rom.e = &self.e - &be * &fb.viscosity * &ce;
        rom.a = &self.a + &be * &fb.k * &ce;
        rom.b = self.b.get(.., ..ni).to_owned();
        rom.c = self.c.get(..no, ..).to_owned();
        rom.c_rate = self.c_rate.as_ref().map(|cv| cv.get(..no, ..).to_owned());
        rom.input_names.truncate(ni);
        rom.output_names.truncate(no);
        let ordinary = rom.to_ordinary()?;
        let mut eig = ordinary.a.eigenvalues().map_err(|_| RomError::SingularStatic("A of the corrected ROM (its eigenvalues did not converge)"))?;
        eig.sort_by(|a, b| a.norm().total_cmp(&b.norm()).then(b.im.total_cmp(&a.im)));
        rom.eigenvalues = eig;
        Ok(rom)
    }
}
