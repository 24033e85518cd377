//! Derivatives in time by one-sided differences, extrapolated: the rate of a constraint at
//! the initial state (`Φ_/t`, `Φ_/q q̇ + Φ_/t`) for MBDyn's initial assembly and for the
//! check of written velocities. Forward in time: drives usually start with a kink at the
//! initial time (a cosine held at its initial value before t₀), where a central difference
//! would see half the kink and MBDyn's drives give their derivative from t₀ on (`GetP`).

/// Largest step [s]: a drive's time scale is rarely shorter.
const FIRST_STEP: f64 = 4e-5;
/// Steps halved this many times: down to 4e-5 / 2¹¹ ≈ 2e-8 s, where rounding of a
/// residual of order 10 (10 m) reaches about 1e-7 per s.
const HALVINGS: usize = 11;

/// `d g_i / ds` at `s = 0` for each of `rows`, from forward differences
/// `(g(h) − g(0)) / h` at `h ≈ 4e-5 s / 2ᵏ` (each `h` what `t + h` represents, so the
/// time moves by `h` exactly), extrapolated to `h → 0` by Neville's tableau (Ridders' method, for one-sided
/// differences whose error is a series in `h`, `h²`, …). Each row keeps the entry whose
/// two neighbours in the tableau agree best, and stops when the tableau's diagonal moves
/// by twice that disagreement (rounding has taken over).
///
/// A drive that changes within 1e-5 s (a half cosine over 1 ms, whose fourth derivative at
/// its start is ω⁴ A ≈ 1e14 A per s⁴) is resolved to rounding: a fixed second-order
/// difference at 1e-6 s left A ω⁴ ε³ / 4 (1.2e-6 m/s for A = 5 cm), a third-order one at
/// 1e-5 s 1.6 per s for A = 50.
pub(crate) fn forward_derivatives(rows: &[usize], t: f64, g0: &[f64], g: impl Fn(f64) -> Vec<f64>) -> Vec<f64> {
    const WIDTH: usize = HALVINGS + 1;
    // Row r's last tableau column in previous[r * WIDTH ..]; its best entry and that
    // entry's disagreement with its neighbours.
    let mut previous = vec![0.0; rows.len() * WIDTH];
    let mut best: Vec<(f64, f64)> = vec![(f64::INFINITY, 0.0); rows.len()];
    let mut done = vec![false; rows.len()];
    let mut column = [0.0; WIDTH];
    let mut steps = Vec::with_capacity(WIDTH);
    let mut nominal = FIRST_STEP;
    for level in 0..WIDTH {
        let h = (t + nominal) - t;
        if h <= 0.0 || steps.last().is_some_and(|&last| h >= last) {
            break;
        }
        steps.push(h);
        let gh = g(h);
        for (r, &i) in rows.iter().enumerate() {
            if done[r] {
                continue;
            }
            let old_column = &mut previous[r * WIDTH..(r + 1) * WIDTH];
            column[0] = (gh[i] - g0[i]) / h;
            if level == 0 {
                best[r].1 = column[0];
            }
            for j in 1..=level {
                // Neville: the polynomial in h through steps[level − j ..= level] at h = 0.
                let (new, old) = (column[j - 1], old_column[j - 1]);
                let far = steps[level - j];
                let extrapolated = (far * new - h * old) / (far - h);
                let error = (extrapolated - new).abs().max((extrapolated - old).abs());
                if error <= best[r].0 {
                    best[r] = (error, extrapolated);
                }
                column[j] = extrapolated;
            }
            if level > 0 && (column[level] - old_column[level - 1]).abs() >= 2.0 * best[r].0 {
                done[r] = true;
            }
            old_column[..=level].copy_from_slice(&column[..=level]);
        }
        if done.iter().all(|&d| d) {
            break;
        }
        nominal /= 2.0;
    }
    best.into_iter().map(|(_, v)| v).collect()
}

#[cfg(test)]
mod tests {
    use super::forward_derivatives;

    /// Closed forms: a half cosine over 1 ms, `A (1 − cos ωt)` with ω = π / 1 ms, has rate 0
    /// at t = 0; a sine `A sin ωt` rate `A ω`; a ramp its slope; one row held constant 0.
    #[test]
    fn rates_of_fast_drives_from_one_side() {
        let omega = std::f64::consts::PI / 1e-3;
        let g = |t: f64| vec![50.0 * (1.0 - (omega * t).cos()), 0.05 * (omega * t).sin(), 3.0 + 250.0 * t, 7.0];
        let d = forward_derivatives(&[0, 1, 2, 3], 0.0, &g(0.0), g);
        // 1e-7 per s: 50 (1 − cos ωh) is rounded to 50 · 1.1e-16 = 5.6e-15, which is 1e-7
        // per s at h = 5e-8 s (measured 5.3e-9; one third-order difference at 1e-5 s: 1.6).
        assert!(d[0].abs() < 1e-7, "half cosine: {:e}", d[0]);
        assert!((d[1] - 0.05 * omega).abs() < 1e-9 * 0.05 * omega, "sine: {:e}", d[1]);
        assert!((d[2] - 250.0).abs() < 1e-9 * 250.0, "ramp: {:e}", d[2]);
        assert_eq!(d[3], 0.0);
        // Far from t = 0 the steps are rounded to what t + h can represent: a ramp from
        // t = 1e4 s still gives its slope (relative 1e-9).
        let t0 = 1e4;
        let late = |s: f64| vec![250.0 * s];
        let d = forward_derivatives(&[0], t0, &late(0.0), late);
        assert!((d[0] - 250.0).abs() < 1e-9 * 250.0, "late ramp: {:e}", d[0]);
    }
}
