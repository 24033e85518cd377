//! X–Y line plots (e.g. a frequency against a load, paper Fig. 5) as SVG and PNG, and their
//! points as CSV.

use std::io::Write;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::{write_atomic, OutputError};
use super::figure::{write_figure, Figure, COLORS, FONT};

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeriesStyle {
    Line,
    /// Markers joined by a thin line (computed points).
    Markers,
}

#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: SeriesStyle,
}

/// A plot of one or more series on linear axes; labels carry their units.
#[derive(Clone, Debug)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

fn span(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v.filter(|x| x.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(hi.abs() * 1e-3).max(1e-12);
    (lo - pad, hi + pad)
}

impl Figure for LinePlot {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let (x, y) = (span(points().map(|p| p.0)), span(points().map(|p| p.1)));
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, (FONT, 28))
            .margin(20)
            .x_label_area_size(55)
            .y_label_area_size(90)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .axis_desc_style((FONT, 22))
            .label_style((FONT, 18))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| err(&e))?;
        for (k, s) in self.series.iter().enumerate() {
            let color = COLORS[k % COLORS.len()];
            let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: 2 };
            let drawn = chart.draw_series(LineSeries::new(s.points.iter().copied(), if s.style == SeriesStyle::Line { style } else { style.stroke_width(1) })).map_err(|e| err(&e))?;
            drawn.label(&s.label).legend(move |(x, y)| PathElement::new(vec![(x - 5, y), (x + 15, y)], style));
            if s.style == SeriesStyle::Markers {
                chart.draw_series(s.points.iter().map(|p| Circle::new(*p, 5, style.filled()))).map_err(|e| err(&e))?;
            }
        }
        chart.configure_series_labels().position(SeriesLabelPosition::UpperRight).label_font((FONT, 18)).background_style(WHITE.mix(0.85)).border_style(BLACK).draw().map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))
    }
}

/// Writes the plot as SVG and PNG (each atomically).
pub fn write_line_plot(plot: &LinePlot, svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    if plot.series.iter().all(|s| s.points.is_empty()) {
        return Err(OutputError::Invalid { path: svg_path.to_path_buf(), message: "no point to plot".into() });
    }
    write_figure(plot, (1200, 800), svg_path, png_path)
}

/// Writes every series' points as `series,x,y` rows under a header naming the axes.
pub fn write_series_csv(plot: &LinePlot, path: &Path) -> Result<(), OutputError> {
    write_atomic(path, |w: &mut dyn Write| {
        writeln!(w, "series,{},{}", plot.x_label, plot.y_label)?;
        for s in &plot.series {
            for (x, y) in &s.points {
                writeln!(w, "\"{}\",{x:.12e},{y:.12e}", s.label)?;
            }
        }
        Ok(())
    })
}
