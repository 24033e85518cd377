//! Exact time simulation of an ordinary ROM `ẋ = A x + B u`, `z = C x + D u` for an input
//! linear between samples (the first-order hold the nonlinear run's load applies): with
//! `M = [[A, B, 0], [0, 0, I], [0, 0, 0]]`, `e^{M T} = [[Φ, Γ₁, Γ₂], …]` and
//! `x_{k+1} = Φ x_k + Γ₁ u_k + Γ₂ (u_{k+1} − u_k)/T` (Franklin, Powell and Workman, *Digital
//! Control of Dynamic Systems*, §6.3.2). The exponential is [`crate::rom::expm`] (Padé(6,6)
//! with scaling and squaring), shared with the discrete-time ROMs.

use faer::Mat;

use crate::rom::{expm, OrdinaryRom};

/// The ROM's outputs `z_k` (rows: samples, one column per output) for the inputs `u`
/// (one column per input) at step `dt` [s], from `x = 0`.
pub fn simulate(rom: &OrdinaryRom, u: &Mat<f64>, dt: f64) -> Mat<f64> {
    let (n, m) = (rom.a.nrows(), rom.b.ncols());
    let size = n + 2 * m;
    let big = Mat::from_fn(size, size, |i, j| {
        if i < n && j < n {
            rom.a[(i, j)] * dt
        } else if i < n && j < n + m {
            rom.b[(i, j - n)] * dt
        } else if i >= n && i < n + m && j == i + m {
            1.0
        } else {
            0.0
        }
    });
    let e = expm(&big);
    let phi = e.get(..n, ..n).to_owned();
    let g1 = e.get(..n, n..n + m).to_owned();
    let g2 = e.get(..n, n + m..).to_owned();
    let steps = u.nrows();
    let mut z = Mat::<f64>::zeros(steps, rom.c.nrows());
    let mut x = Mat::<f64>::zeros(n, 1);
    for k in 0..steps {
        let uk = u.get(k..k + 1, ..).transpose().to_owned();
        let zk = &rom.c * &x + &rom.d * &uk;
        for i in 0..zk.nrows() {
            z[(k, i)] = zk[(i, 0)];
        }
        if k + 1 < steps {
            let du = u.get(k + 1..k + 2, ..).transpose().to_owned() - &uk;
            x = &phi * &x + &g1 * &uk + &g2 * &du;
        }
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ẋ = −a x + u with u(t) = t (linear between samples: the hold is exact) has
    /// x(t) = t/a − (1 − e^{−a t})/a².
    #[test]
    fn first_order_hold_is_exact_for_a_ramp() {
        let a = 3.0;
        let rom = OrdinaryRom { a: Mat::from_fn(1, 1, |_, _| -a), b: Mat::from_fn(1, 1, |_, _| 1.0), c: Mat::from_fn(1, 1, |_, _| 1.0), d: Mat::zeros(1, 1), eigenvalues: Vec::new(), input_names: Vec::new(), output_names: Vec::new() };
        let dt = 0.05;
        let u = Mat::from_fn(41, 1, |k, _| k as f64 * dt);
        let z = simulate(&rom, &u, dt);
        for k in 0..41 {
            let t = k as f64 * dt;
            let exact = t / a - (1.0 - (-a * t).exp()) / (a * a);
            assert!((z[(k, 0)] - exact).abs() < 1e-13, "{t}: {} vs {exact}", z[(k, 0)]);
        }
    }
}
