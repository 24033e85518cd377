//! Excitation signals of a validation run, sampled at the integrator's step: low-pass
//! filtered random noise (the paper's Fig. 7), a Schroeder-phased multisine and a linear
//! chirp, each faded in from zero (the run starts from the reference solution at rest) and
//! scaled to a given RMS value. The random numbers are a seeded xoshiro256** stream (Blackman
//! and Vigna), seeded through SplitMix64, so a seed gives the same signal on every machine.

use std::f64::consts::PI;

use faer::c64;

/// The shape of the excitation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SignalKind {
    /// Gaussian white noise, low-pass (band-pass) filtered by zeroing its spectrum outside
    /// the band (the paper's "low-pass filtered random input").
    Random,
    /// A sum of sines at the estimator's frequency bins in the band, Schroeder phases.
    Multisine,
    /// A linear frequency sweep across the band, repeated every Welch segment.
    Chirp,
}

/// xoshiro256** seeded by SplitMix64 (Vigna, <https://prng.di.unimi.it>).
pub struct Rng([u64; 4]);

impl Rng {
    pub fn new(seed: u64) -> Self {
        let mut z = seed;
        let mut next = || {
            z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            x ^ (x >> 31)
        };
        Rng([next(), next(), next(), next()])
    }

    pub fn next_u64(&mut self) -> u64 {
        let s = &mut self.0;
        let result = s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

/// In-place radix-2 FFT, `X_k = Σ x_n e^{∓2πikn/N}` (`inverse`: the + sign, no 1/N);
/// `x.len()` must be a power of two.
pub fn fft(x: &mut [c64], inverse: bool) {
    let n = x.len();
    assert!(n.is_power_of_two(), "fft length {n} is not a power of two");
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            x.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let w = c64::new(0.0, sign * 2.0 * PI / len as f64);
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let tw = (w * k as f64).exp();
                let (a, b) = (x[start + k], x[start + k + len / 2] * tw);
                x[start + k] = a + b;
                x[start + k + len / 2] = a - b;
            }
        }
        len <<= 1;
    }
}

/// What to generate: `samples` values at step `dt` [s], spectrum in `band_hz`, RMS `rms`,
/// faded in over `fade` samples; Welch segments of `segment` samples (multisine, chirp).
#[derive(Clone, Copy, Debug)]
pub struct SignalSpec {
    pub kind: SignalKind,
    pub samples: usize,
    pub dt: f64,
    pub band_hz: (f64, f64),
    pub rms: f64,
    pub fade: usize,
    pub segment: usize,
    pub seed: u64,
}

impl SignalSpec {
    /// The signal's samples, `u(k dt)` for `k = 0..samples`.
    pub fn generate(&self) -> Vec<f64> {
        let mut u = match self.kind {
            SignalKind::Random => self.random(),
            SignalKind::Multisine => self.multisine(),
            SignalKind::Chirp => self.chirp(),
        };
        // Raised-cosine fade-in: the run starts at rest with no load step.
        for (k, v) in u.iter_mut().enumerate().take(self.fade) {
            *v *= 0.5 * (1.0 - (PI * k as f64 / self.fade as f64).cos());
        }
        let rms = (u.iter().map(|v| v * v).sum::<f64>() / u.len().max(1) as f64).sqrt();
        if rms > 0.0 {
            u.iter_mut().for_each(|v| *v *= self.rms / rms);
        }
        u
    }

    fn random(&self) -> Vec<f64> {
        let n = self.samples.next_power_of_two();
        let mut rng = Rng::new(self.seed);
        let mut x: Vec<c64> = (0..n).map(|_| c64::new(rng.normal(), 0.0)).collect();
        fft(&mut x, false);
        let df = 1.0 / (n as f64 * self.dt);
        let (lo, hi) = self.band_hz;
        for (k, v) in x.iter_mut().enumerate() {
            let f = k.min(n - k) as f64 * df;
            if f < lo || f > hi || k == 0 {
                *v = c64::new(0.0, 0.0);
            }
        }
        fft(&mut x, true);
        x[..self.samples].iter().map(|v| v.re / n as f64).collect()
    }

    /// The bins `k / (segment dt)` in the band, as frequencies [Hz].
    fn bins(&self) -> Vec<f64> {
        let df = 1.0 / (self.segment as f64 * self.dt);
        (1..self.segment / 2).map(|k| k as f64 * df).filter(|f| *f >= self.band_hz.0 && *f <= self.band_hz.1).collect()
    }

    fn multisine(&self) -> Vec<f64> {
        let f = self.bins();
        let m = f.len() as f64;
        // Schroeder phases φ_k = −π k (k−1)/M keep the crest factor low.
        let phase: Vec<f64> = (0..f.len()).map(|k| -PI * (k * (k + 1)) as f64 / m).collect();
        (0..self.samples).map(|n| {
            let t = n as f64 * self.dt;
            f.iter().zip(&phase).map(|(f, p)| (2.0 * PI * f * t + p).cos()).sum()
        }).collect()
    }

    fn chirp(&self) -> Vec<f64> {
        let period = self.segment as f64 * self.dt;
        let (lo, hi) = self.band_hz;
        (0..self.samples).map(|n| {
            let t = (n as f64 * self.dt) % period;
            (2.0 * PI * (lo * t + 0.5 * (hi - lo) / period * t * t)).sin()
        }).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A DFT by its definition is the FFT's independent reference.
    #[test]
    fn fft_matches_the_definition() {
        let mut rng = Rng::new(7);
        let x: Vec<c64> = (0..16).map(|_| c64::new(rng.normal(), rng.normal())).collect();
        let mut y = x.clone();
        fft(&mut y, false);
        for (k, yk) in y.iter().enumerate() {
            let d: c64 = x.iter().enumerate().map(|(n, xn)| xn * c64::new(0.0, -2.0 * PI * (k * n) as f64 / 16.0).exp()).sum();
            assert!((d - yk).norm() < 1e-12, "bin {k}");
        }
    }

    /// The filtered noise has its spectrum in the band (Parseval: < 1e-20 of the energy
    /// outside), its RMS, and starts at zero.
    #[test]
    fn random_signal_is_band_limited_with_its_rms() {
        let spec = SignalSpec { kind: SignalKind::Random, samples: 4096, dt: 1e-3, band_hz: (0.0, 50.0), rms: 2.0, fade: 100, segment: 1024, seed: 1 };
        let u = spec.generate();
        let rms = (u.iter().map(|v| v * v).sum::<f64>() / 4096.0).sqrt();
        assert!((rms - 2.0).abs() < 1e-12);
        assert_eq!(u[0], 0.0);
        // The fade and the truncation leak a little; above 2x the band almost nothing.
        let mut x: Vec<c64> = u.iter().map(|v| c64::new(*v, 0.0)).collect();
        fft(&mut x, false);
        let total: f64 = x.iter().map(|v| v.norm_sqr()).sum();
        let above: f64 = x.iter().enumerate().filter(|(k, _)| (*k).min(4096 - k) as f64 / 4.096 > 100.0).map(|(_, v)| v.norm_sqr()).sum();
        assert!(above < 1e-3 * total, "{}", above / total);
    }
}
