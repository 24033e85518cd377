//! The curves of a frequency-response plot: the full linear model's `C (jω E − A)⁻¹ B` and
//! any number of ROMs on one frequency grid, written as CSV, SVG and PNG (`PREFIX.csv`,
//! `PREFIX.svg`, `PREFIX.png`; paper Fig. 7).

use std::path::{Path, PathBuf};

use faer::{c64, Mat};

use super::atomic::OutputError;
use super::bode::{write_bode, BodePlot, CurveStyle, ResponseCurve};
use super::prefixed_path;
use super::response_csv::write_response_csv;
use crate::eigen::{ModalAnalysis, ModeKind};
use crate::linear::LinearDae;
use crate::rom::{full_frequency_response, OrdinaryRom};

/// Frequency responses sharing inputs, outputs and a grid [Hz].
pub struct FrequencyResponses {
    freq_hz: Vec<f64>,
    inputs: Vec<String>,
    outputs: Vec<String>,
    curves: Vec<ResponseCurve>,
}

/// A band around the modes of interest [Hz]: a decade below the lowest and above the
/// highest of `focus` (eigenvalues in rad/s), or of all dynamic modes when `focus` is empty.
pub fn default_band(modal: &ModalAnalysis, focus: &[c64]) -> (f64, f64) {
    let hz = |l: &c64| l.norm() / (2.0 * std::f64::consts::PI);
    let mut f: Vec<f64> = if focus.is_empty() { modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].freq_hz()).collect() } else { focus.iter().map(hz).collect() };
    f.retain(|x| x.is_finite() && *x > 0.0);
    let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = f.iter().copied().fold(0.0, f64::max);
    if lo.is_finite() && hi > 0.0 { (lo / 10.0, hi * 10.0) } else { (0.01, 100.0) }
}

fn curves_of(label: &str, style: CurveStyle, freq_hz: &[f64], h: &[Mat<c64>], inputs: &[String], outputs: &[String]) -> Vec<ResponseCurve> {
    let mut out = Vec::new();
    for (i, output) in outputs.iter().enumerate() {
        for (j, input) in inputs.iter().enumerate() {
            let values = h.iter().map(|m| m[(i, j)]).collect();
            out.push(ResponseCurve { label: label.to_string(), input: input.clone(), output: output.clone(), freq_hz: freq_hz.to_vec(), values, style });
        }
    }
    out
}

impl FrequencyResponses {
    /// The full model's response at `freq_hz`.
    pub fn full(dae: &LinearDae, freq_hz: Vec<f64>) -> Self {
        let h = full_frequency_response(dae, &freq_hz);
        let curves = curves_of("full model", CurveStyle::Full, &freq_hz, &h, &dae.input_names, &dae.output_names);
        FrequencyResponses { freq_hz, inputs: dae.input_names.clone(), outputs: dae.output_names.clone(), curves }
    }

    /// The full model's response `h` (outputs × inputs at each of `freq_hz`), computed
    /// elsewhere.
    pub fn from_full(freq_hz: Vec<f64>, h: &[Mat<c64>], inputs: &[String], outputs: &[String]) -> Self {
        let curves = curves_of("full model", CurveStyle::Full, &freq_hz, h, inputs, outputs);
        FrequencyResponses { freq_hz, inputs: inputs.to_vec(), outputs: outputs.to_vec(), curves }
    }

    /// Adds a ROM's response (dashed) under `label`.
    pub fn with_rom(self, label: &str, rom: &OrdinaryRom) -> Self {
        let h = rom.frequency_response(&self.freq_hz);
        self.with_response(label, &h)
    }

    /// Adds a ROM's response `h` on the same grid (dashed) under `label`.
    pub fn with_response(mut self, label: &str, h: &[Mat<c64>]) -> Self {
        self.curves.extend(curves_of(label, CurveStyle::Rom, &self.freq_hz, h, &self.inputs, &self.outputs));
        self
    }

    /// Writes `PREFIX.csv`, `PREFIX.svg` and `PREFIX.png`; returns their paths.
    pub fn write_files(&self, prefix: &Path, title: &str) -> Result<[PathBuf; 3], OutputError> {
        let paths = [prefixed_path(prefix, "csv"), prefixed_path(prefix, "svg"), prefixed_path(prefix, "png")];
        write_response_csv(&self.curves, &paths[0])?;
        let plot = BodePlot { title: title.into(), magnitude_unit: "output unit / input unit (SI)".into(), curves: self.curves.clone() };
        write_bode(&plot, &paths[1], &paths[2])?;
        Ok(paths)
    }
}
