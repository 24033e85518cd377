//! Frequency responses as a CSV table.
//!
//! Layout: `#` comment lines (units), a header row, then one row per frequency:
//! `freq_hz`, and for each curve four columns `<label>: <output> / <input> re`, `… im`,
//! `… mag`, `… phase_deg` (phase unwrapped along the curve, each channel's curves from a common reference).

use std::path::Path;

use super::atomic::{write_atomic, OutputError};
use super::bode::{common_reference_phases, ResponseCurve};
use crate::linear::FrequencyResponse;

fn quote(s: &str) -> String {
    if s.contains([',', '"', '\n']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() }
}

/// Writes the curves of `response` atomically.
pub fn write_response_csv(response: &FrequencyResponse, curves: &[ResponseCurve], path: &Path) -> Result<(), OutputError> {
    let invalid = |message: &str| OutputError::Invalid { path: path.to_path_buf(), message: message.into() };
    if curves.is_empty() {
        return Err(invalid("no curve to write"));
    }
    if curves.iter().any(|c| c.values.len() != response.freq_hz.len()) {
        return Err(invalid("every curve must have a value at each frequency of the grid"));
    }
    // Each channel's curves from a common reference, as the Bode plot draws them.
    let mut phases: Vec<Vec<f64>> = vec![Vec::new(); curves.len()];
    for (k, c) in curves.iter().enumerate() {
        if !phases[k].is_empty() {
            continue;
        }
        let same: Vec<usize> = (k..curves.len()).filter(|&j| curves[j].output == c.output && curves[j].input == c.input).collect();
        let refs: Vec<&ResponseCurve> = same.iter().map(|&j| &curves[j]).collect();
        for (j, p) in same.into_iter().zip(common_reference_phases(&refs)) {
            phases[j] = p;
        }
    }
    write_atomic(path, |w| {
        writeln!(w, "# romdyn frequency response z/u; frequency in Hz; re, im and magnitude in output units per input unit (SI); phase in degrees")?;
        let mut header = vec!["freq_hz".to_string()];
        for c in curves {
            let name = format!("{}: {} / {}", c.label, response.outputs[c.output].label(), response.inputs[c.input].label());
            header.extend(["re", "im", "mag", "phase_deg"].map(|k| quote(&format!("{name} {k}"))));
        }
        writeln!(w, "{}", header.join(","))?;
        for (k, f) in response.freq_hz.iter().enumerate() {
            write!(w, "{f:.10e}")?;
            for (c, p) in curves.iter().zip(&phases) {
                let v = c.values[k];
                write!(w, ",{:.10e},{:.10e},{:.10e},{:.6}", v.re, v.im, v.norm(), p[k])?;
            }
            writeln!(w)?;
        }
        Ok(())
    })
}
