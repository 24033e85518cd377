//! A ROM in exportable form ([`RomExport`]): the content every ROM file holds
//! ([`super::rom_file`] writes JSON, `.mat`, `.npz`; [`super::rom_script`] the Octave/MATLAB
//! script) and the header lines they share.

use faer::{c64, Mat};

/// A ROM in exportable form: `E ẋ = A x + B u`, `z = C x + D u`, with what is needed to
/// use and check it.
#[derive(Clone, Debug)]
pub struct RomExport {
    /// `"descriptor"` (D = 0, E possibly singular) or `"ordinary"` (E = I).
    pub kind: &'static str,
    pub e: Mat<f64>,
    pub a: Mat<f64>,
    pub b: Mat<f64>,
    pub c: Mat<f64>,
    pub d: Mat<f64>,
    /// The ROM's own eigenvalues [rad/s].
    pub eigenvalues: Vec<c64>,
    /// The full model's kept eigenvalues [rad/s].
    pub full_eigenvalues: Vec<c64>,
    pub inputs: Vec<String>,
    pub outputs: Vec<String>,
    pub states: Vec<String>,
    pub input_units: Vec<String>,
    pub output_units: Vec<String>,
    pub state_units: Vec<String>,
    /// 1-based modal-table index of each state's mode (0: a static state).
    pub state_modes: Vec<usize>,
    /// `Im λ/2π` of each state's mode [Hz] (NaN for a static state).
    pub state_freq_hz: Vec<f64>,
    /// Time of the reference solution [s] (`None`: a pencil file).
    pub reference_time: Option<f64>,
    pub dcoef: f64,
    pub full_static_gain: Option<Mat<f64>>,
    pub rom_static_gain: Option<Mat<f64>>,
    /// Sampling time of a discrete-time ROM [s] (`None`: continuous time).
    pub sample_time: Option<f64>,
    /// "continuous", or the discretization method ("zoh", "tustin", "matched").
    pub discretization: String,
    /// Hankel singular values of a balanced ROM's stable part (empty: not balanced).
    pub hankel_singular_values: Vec<f64>,
    /// A balanced ROM's bound on `‖G − G_r‖∞`.
    pub error_bound: Option<f64>,
}

impl RomExport {
    /// "continuous: E x' = A x + B u, z = C x + D u", or the discrete-time equations with the
    /// sampling time and method: the header of every format.
    pub fn time_domain(&self) -> String {
        match self.sample_time {
            Some(t) => format!("discrete: x[k+1] = A x[k] + B u[k], z[k] = C x[k] + D u[k], sampling time {t:e} s ({} Hz), {}", 1.0 / t, self.discretization),
            None => "continuous: E x' = A x + B u, z = C x + D u".to_string(),
        }
    }

    pub(crate) fn units_line(&self) -> String {
        let eig = if self.sample_time.is_some() { "eigenvalues in the z-plane (dimensionless), full_eigenvalues in rad/s" } else { "eigenvalues in rad/s" };
        format!("SI: inputs, outputs and states in the units listed; {eig}, frequencies in Hz, times in s")
    }
}
