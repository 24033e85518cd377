//! A frequency-response plot: the full linear model's `C (jω E − A)⁻¹ B` and any number of
//! ROMs on one grid ([`FrequencyResponse`]), written as CSV, SVG and PNG (`PREFIX.csv`,
//! `PREFIX.svg`, `PREFIX.png`; paper Fig. 7), one panel per channel.

use std::path::{Path, PathBuf};

use super::atomic::OutputError;
use super::bode::{every_channel, response_curves, write_bode, BodePlot};
use super::prefixed_path;
use super::response_csv::write_response_csv;
use crate::linear::FrequencyResponse;

/// Writes `PREFIX.csv`, `PREFIX.svg` and `PREFIX.png` of every channel of `response`;
/// returns their paths.
pub fn write_bode_files(response: &FrequencyResponse, prefix: &Path, title: &str) -> Result<[PathBuf; 3], OutputError> {
    let paths = [prefixed_path(prefix, "csv"), prefixed_path(prefix, "svg"), prefixed_path(prefix, "png")];
    let curves = response_curves(response, &every_channel(response));
    write_response_csv(response, &curves, &paths[0])?;
    let plot = BodePlot { title: title.into(), magnitude_unit: "output unit / input unit (SI)".into(), response, curves };
    write_bode(&plot, &paths[1], &paths[2])?;
    Ok(paths)
}
