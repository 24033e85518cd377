//! Shared plumbing of romdyn's plots: the embedded font (DejaVu Sans, so plots render on
//! machines without fonts or fontconfig), the colour cycle, and writing one figure as SVG
//! and PNG, each atomically.

use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::{write_atomic_bytes, OutputError};

pub const FONT: &str = "dejavu-sans";

pub const COLORS: [RGBColor; 8] = [
    RGBColor(0, 0, 0),
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
];

/// Something that draws itself on any plotters backend.
pub trait Figure {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String>;
}

fn ensure_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded TTF is valid; a failure here would only make text fall back.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// Renders `figure` at `size` pixels to an SVG and a PNG file.
pub fn write_figure(figure: &impl Figure, size: (u32, u32), svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    ensure_font();
    let invalid = |path: &Path, message: String| OutputError::Invalid { path: path.to_path_buf(), message };
    let mut svg = String::new();
    figure.draw(SVGBackend::with_string(&mut svg, size).into_drawing_area()).map_err(|m| invalid(svg_path, m))?;
    write_atomic_bytes(svg_path, svg.as_bytes())?;
    // The PNG encoder writes to a path: render to a temporary file beside the target,
    // then rename it into place.
    let name = png_path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp = png_path.with_file_name(format!(".{name}.tmp-{}.png", std::process::id()));
    let result = figure
        .draw(BitMapBackend::new(&tmp, size).into_drawing_area())
        .map_err(|m| invalid(png_path, m))
        .and_then(|_| std::fs::rename(&tmp, png_path).map_err(|e| OutputError::Io { path: png_path.to_path_buf(), operation: "rename the temporary file onto it", source: e }));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
