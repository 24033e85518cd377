//! Scalar functions of time that drive forces and couples (MBDyn's drive callers).

/// A drive `v(t)`.
#[derive(Clone, Debug, PartialEq)]
pub enum Drive {
    /// `v`.
    Const(f64),
    /// `t` itself.
    Time,
    /// `v0` before `t0`, `v0 + slope (t − t0)` until `t1`, constant after.
    Ramp { slope: f64, t0: f64, t1: f64, v0: f64 },
    /// `v0` before `t0`, `v0 + value` from `t0` on.
    Step { t0: f64, value: f64, v0: f64 },
    /// `v0 + A sin(ω (t − t0))` from `t0` on, for `cycles` periods (`None`: forever), then
    /// held at its final value.
    Sine { t0: f64, omega: f64, amplitude: f64, cycles: Option<f64>, v0: f64 },
    /// `v0 + A (1 − cos(ω (t − t0)))` from `t0` on (MBDyn's cosine), for `cycles` periods.
    Cosine { t0: f64, omega: f64, amplitude: f64, cycles: Option<f64>, v0: f64 },
    /// Linear interpolation between `(t, v)` points, constant outside.
    PiecewiseLinear(Vec<(f64, f64)>),
}

impl Drive {
    pub fn value(&self, t: f64) -> f64 {
        match self {
            Drive::Const(v) => *v,
            Drive::Time => t,
            Drive::Ramp { slope, t0, t1, v0 } => v0 + slope * (t.clamp(*t0, *t1) - t0),
            Drive::Step { t0, value, v0 } => v0 + if t >= *t0 { *value } else { 0.0 },
            Drive::Sine { t0, omega, amplitude, cycles, v0 } => v0 + amplitude * periodic(t, *t0, *omega, *cycles).sin(),
            Drive::Cosine { t0, omega, amplitude, cycles, v0 } => v0 + amplitude * (1.0 - periodic(t, *t0, *omega, *cycles).cos()),
            Drive::PiecewiseLinear(points) => piecewise(points, t),
        }
    }
}

/// Phase `ω (t − t0)`, zero before `t0` and frozen after the last cycle.
fn periodic(t: f64, t0: f64, omega: f64, cycles: Option<f64>) -> f64 {
    let phase = omega * (t - t0).max(0.0);
    match cycles {
        Some(n) => phase.min(2.0 * std::f64::consts::PI * n),
        None => phase,
    }
}

fn piecewise(points: &[(f64, f64)], t: f64) -> f64 {
    match points {
        [] => 0.0,
        [(_, v)] => *v,
        _ => {
            if t <= points[0].0 {
                return points[0].1;
            }
            for w in points.windows(2) {
                let ((ta, va), (tb, vb)) = (w[0], w[1]);
                if t <= tb {
                    return if tb > ta { va + (vb - va) * (t - ta) / (tb - ta) } else { vb };
                }
            }
            points[points.len() - 1].1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drives_follow_their_definitions() {
        assert_eq!(Drive::Const(2.5).value(7.0), 2.5);
        let ramp = Drive::Ramp { slope: 2.0, t0: 1.0, t1: 3.0, v0: 1.0 };
        assert_eq!([ramp.value(0.0), ramp.value(2.0), ramp.value(5.0)], [1.0, 3.0, 5.0]);
        let step = Drive::Step { t0: 1.0, value: 4.0, v0: -1.0 };
        assert_eq!([step.value(0.5), step.value(1.0)], [-1.0, 3.0]);
        let pi = std::f64::consts::PI;
        let sine = Drive::Sine { t0: 0.0, omega: pi, amplitude: 2.0, cycles: Some(1.0), v0: 0.0 };
        assert!((sine.value(0.5) - 2.0).abs() < 1e-15 && sine.value(10.0).abs() < 1e-12);
        let cosine = Drive::Cosine { t0: 0.0, omega: pi, amplitude: 1.0, cycles: None, v0: 0.0 };
        assert!((cosine.value(1.0) - 2.0).abs() < 1e-15);
        let pl = Drive::PiecewiseLinear(vec![(0.0, 0.0), (1.0, 10.0), (2.0, 0.0)]);
        assert_eq!([pl.value(-1.0), pl.value(0.5), pl.value(1.5), pl.value(9.0)], [0.0, 5.0, 5.0, 0.0]);
    }
}
