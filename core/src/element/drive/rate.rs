//! Time derivatives of drives, for the elements that need `ḋ(t)` (the variable-mass body's
//! `ṁ`, the rates of its centre of mass and inertia: MBDyn's `DriveCaller::dGetP`, which a
//! `variable body` requires, body_vm.cc `ReadVariableBody`). romdyn differentiates the
//! drives below analytically; others are refused by the reader.

use super::Drive;

impl Drive {
    /// `dv/dt` at `t`, or `None` for a drive romdyn does not differentiate. Where the drive
    /// has a kink (a ramp's ends, a sine's last cycle) the derivative of the piece that
    /// holds at `t` is taken, the side the value is computed on.
    pub fn time_derivative(&self, t: f64) -> Option<f64> {
        Some(match self {
            Drive::Const(_) | Drive::Step { .. } => 0.0,
            Drive::Time => 1.0,
            Drive::Ramp { slope, t0, t1, .. } => if t > *t0 && t < *t1 { *slope } else { 0.0 },
            Drive::Sine { t0, omega, amplitude, cycles, .. } => match phase(t, *t0, *omega, *cycles) {
                Some(p) => amplitude * omega * p.cos(),
                None => 0.0,
            },
            Drive::Cosine { t0, omega, amplitude, cycles, .. } => match phase(t, *t0, *omega, *cycles) {
                Some(p) => amplitude * omega * p.sin(),
                None => 0.0,
            },
            Drive::Polynomial(c) => c.iter().enumerate().skip(1).rev().fold(0.0, |acc, (k, ck)| acc * t + k as f64 * ck),
            Drive::Exponential { amplitude, tau, t0, .. } => if t < *t0 { 0.0 } else { amplitude / tau * (-(t - t0) / tau).exp() },
            Drive::Tanh { t0, amplitude, slope, .. } => amplitude * slope / (slope * (t - t0)).cosh().powi(2),
            Drive::Sum(drives) => drives.iter().map(|d| d.time_derivative(t)).sum::<Option<f64>>()?,
            Drive::Product(a, b) => a.time_derivative(t)? * b.value(t) + a.value(t) * b.time_derivative(t)?,
            _ => return None,
        })
    }
}

/// The running phase `ω (t − t0)` of a sine or cosine, `None` before `t0` and after its last
/// cycle (where the value is held).
fn phase(t: f64, t0: f64, omega: f64, cycles: Option<f64>) -> Option<f64> {
    let p = omega * (t - t0);
    let end = cycles.map_or(f64::INFINITY, |n| 2.0 * std::f64::consts::PI * n);
    (p >= 0.0 && p < end).then_some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each differentiated drive against a central difference of its value.
    #[test]
    fn derivatives_match_central_differences() {
        let drives = [
            Drive::Const(2.0),
            Drive::Time,
            Drive::Ramp { slope: 3.0, t0: 0.1, t1: 2.0, v0: 1.0 },
            Drive::Sine { t0: 0.1, omega: 5.0, amplitude: 2.0, cycles: None, v0: 1.0 },
            Drive::Cosine { t0: 0.1, omega: 5.0, amplitude: 2.0, cycles: Some(10.0), v0: 1.0 },
            Drive::Polynomial(vec![1.0, -0.5, 0.25, 2.0]),
            Drive::Exponential { amplitude: 2.0, tau: 0.3, t0: 0.1, v0: 1.0 },
            Drive::Tanh { t0: 0.2, amplitude: 2.0, slope: 3.0, v0: 1.0 },
            Drive::Sum(vec![Drive::Time, Drive::Polynomial(vec![0.0, 0.0, 1.0])]),
            Drive::Product(Box::new(Drive::Time), Box::new(Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 1.0, cycles: None, v0: 0.0 })),
        ];
        let h = 1e-6;
        for d in &drives {
            for t in [0.37, 0.9, 1.3] {
                let fd = (d.value(t + h) - d.value(t - h)) / (2.0 * h);
                let an = d.time_derivative(t).unwrap();
                assert!((an - fd).abs() < 1e-8 * (1.0 + an.abs()), "{d:?} at {t}: {an} vs {fd}");
            }
        }
        assert!(Drive::PiecewiseLinear(vec![(0.0, 0.0), (1.0, 1.0)]).time_derivative(0.5).is_none());
    }
}
