//! A transfer matrix as a grid of Bode-magnitude panels (paper Figs. 9 and 10: one panel per
//! output/input pair, or the diagonal only), the full model solid and the ROM dashed, and a
//! log-log transmissibility plot (paper Fig. 11). Each panel names its pair with units;
//! magnitudes are |H| in SI units (log axis), frequencies in Hz (log axis). A CSV with the
//! same numbers is written beside the figure.

use std::path::{Path, PathBuf};

use faer::{c64, Mat};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::OutputError;
use super::bode::{log_tick_label, response_curves};
use super::response_csv::write_response_csv;
use super::figure::{write_figure, Figure, COLORS, FONT};
use super::prefixed_path;
use crate::linear::FrequencyResponse;

/// A transfer matrix of the full model and of a ROM (the response's first reduced model,
/// if any) on one grid.
#[derive(Clone, Debug)]
pub struct MimoPlot {
    pub title: String,
    pub response: FrequencyResponse,
    /// Only the panels `(i, i)`.
    pub diagonal: bool,
}

impl MimoPlot {
    fn panels(&self) -> Vec<(usize, usize)> {
        if self.diagonal {
            (0..self.response.outputs.len().min(self.response.inputs.len())).map(|i| (i, i)).collect()
        } else {
            super::bode::every_channel(&self.response)
        }
    }

    /// Columns and rows of the grid: the transfer matrix's (one row per output), or the
    /// squarest grid for the diagonal.
    fn shape(&self) -> (usize, usize) {
        let n = self.panels().len();
        let row = (!self.diagonal).then_some(self.response.inputs.len());
        let (rows, cols) = super::figure::grid_shape(n, row, usize::MAX);
        (cols, rows)
    }

    /// Pixel size: panels of at least 360 x 260 px.
    pub fn size(&self) -> (u32, u32) {
        let (c, r) = self.shape();
        ((c as u32 * 380).max(800), (r as u32 * 280 + 90).max(500))
    }

    fn points(&self, h: &[Mat<c64>], i: usize, j: usize) -> Vec<(f64, f64)> {
        self.response.freq_hz.iter().zip(h).filter_map(|(f, m)| {
            let v = m[(i, j)].norm();
            (v > 0.0 && v.is_finite() && *f > 0.0).then_some((*f, v))
        }).collect()
    }

    /// Writes `PREFIX.csv` (complex values, magnitude and phase of every panel's curves: the
    /// layout of [`write_response_csv`]), `PREFIX.svg`, `PREFIX.png`.
    pub fn write_files(&self, prefix: &Path) -> Result<[PathBuf; 3], OutputError> {
        let paths = [prefixed_path(prefix, "csv"), prefixed_path(prefix, "svg"), prefixed_path(prefix, "png")];
        write_response_csv(&self.response, &response_curves(&self.response, &self.panels()), &paths[0])?;
        write_figure(self, self.size(), &paths[1], &paths[2])?;
        Ok(paths)
    }
}

impl Figure for MimoPlot {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let legend = if !self.response.rom().is_empty() { "   (solid: full model, dashed: ROM)" } else { "" };
        let root = root.titled(&format!("{}{legend}", self.title), (FONT, 26)).map_err(|e| err(&e))?;
        let (cols, rows) = self.shape();
        let areas = root.split_evenly((rows, cols));
        let (flo, fhi) = (self.response.freq_hz.first().copied().unwrap_or(0.01), self.response.freq_hz.last().copied().unwrap_or(100.0));
        // Largest magnitude of each row and column: a panel far below both is rounding noise
        // of a pair that does not couple, and is labelled so instead of drawn as a curve.
        let peak = |i: usize, j: usize| self.response.full.iter().map(|m| m[(i, j)].norm()).filter(|v| v.is_finite()).fold(0.0, f64::max);
        let (no, ni) = (self.response.outputs.len(), self.response.inputs.len());
        let row_max: Vec<f64> = (0..no).map(|i| (0..ni).map(|j| peak(i, j)).fold(0.0, f64::max)).collect();
        let col_max: Vec<f64> = (0..ni).map(|j| (0..no).map(|i| peak(i, j)).fold(0.0, f64::max)).collect();
        for (k, (i, j)) in self.panels().into_iter().enumerate() {
            let area = &areas[k];
            if peak(i, j) <= 1e-7 * row_max[i].max(col_max[j]) {
                let text = format!("{} / {}", self.response.outputs[i].label(), self.response.inputs[j].label());
                area.draw(&Text::new(text, (10, 10), (FONT, 15))).map_err(|e| err(&e))?;
                area.draw(&Text::new(format!("no coupling: |H| < 1e-7 of its row and column (max {:.0e})", peak(i, j)), (10, 40), (FONT, 13))).map_err(|e| err(&e))?;
                continue;
            }
            let full = self.points(&self.response.full, i, j);
            let rom = self.points(self.response.rom(), i, j);
            let (lo, hi) = full.iter().chain(&rom).fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
            let (lo, hi) = if lo.is_finite() && hi > 0.0 { (lo / 2.0, hi * 2.0) } else { (1e-12, 1.0) };
            let title = format!("{} / {}", self.response.outputs[i].label(), self.response.inputs[j].label());
            let mut chart = ChartBuilder::on(area)
                .caption(&title, (FONT, 15))
                .margin(6)
                // Room for half the last frequency label ("100") in the rightmost column.
                .margin_right(16)
                .x_label_area_size(30)
                .y_label_area_size(58)
                .build_cartesian_2d((flo..fhi).log_scale(), (lo..hi).log_scale())
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_labels(5)
                .y_labels(5)
                .x_label_formatter(&|x| log_tick_label(*x, (fhi / flo).log10()))
                .y_label_formatter(&|y| format!("{y:.0e}"))
                .label_style((FONT, 12))
                .x_desc(if i + 1 == no || self.diagonal { "Hz" } else { "" })
                .axis_desc_style((FONT, 12))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(|e| err(&e))?;
            let solid = ShapeStyle { color: COLORS[0].to_rgba(), filled: false, stroke_width: 2 };
            let dashed = ShapeStyle { color: COLORS[1].to_rgba(), filled: false, stroke_width: 2 };
            chart.draw_series(LineSeries::new(full, solid)).map_err(|e| err(&e))?;
            if !rom.is_empty() {
                chart.draw_series(DashedLineSeries::new(rom, 8, 6, dashed)).map_err(|e| err(&e))?;
            }
        }
        root.present().map_err(|e| err(&e))
    }
}
