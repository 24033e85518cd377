//! Shared plumbing of romdyn's plots: the embedded font (DejaVu Sans, so plots render on
//! machines without fonts or fontconfig), the colour cycle, and writing one figure as SVG
//! and PNG, each atomically.

use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::{AtomicFile, OutputError};

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

/// `(rows, columns)` of a grid of `n` panels: rows of `row` panels (a transfer matrix's
/// inputs, one row per output) when `row` divides `n` and is at most `max_columns`, else the
/// squarest grid, with at least as many columns as rows. The one layout of romdyn's panel
/// grids (Bode panel pairs, MIMO magnitude grids).
pub fn grid_shape(n: usize, row: Option<usize>, max_columns: usize) -> (usize, usize) {
    let n = n.max(1);
    let cols = match row {
        Some(r) if r > 0 && n % r == 0 && r <= max_columns => r,
        _ => (n as f64).sqrt().ceil() as usize,
    };
    (n.div_ceil(cols), cols)
}

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
    let [svg, png] = stage_figure(figure, size, svg_path, png_path)?;
    svg.commit()?;
    png.commit()
}

/// Renders `figure` at `size` pixels to an SVG and a PNG file under temporary names, to be
/// put in place with the rest of a set ([`super::atomic::commit_set`]). Both are
/// [`AtomicFile`]s: a signal or an error removes them, and a killed process's are swept by
/// the next one writing in their folder. The PNG is rendered into memory and encoded here
/// (the plotting library's own encoder writes to a path of its own).
pub fn stage_figure(figure: &impl Figure, size: (u32, u32), svg_path: &Path, png_path: &Path) -> Result<[AtomicFile; 2], OutputError> {
    ensure_font();
    let invalid = |path: &Path, message: String| OutputError::Invalid { path: path.to_path_buf(), message };
    let mut svg_text = String::new();
    figure.draw(SVGBackend::with_string(&mut svg_text, size).into_drawing_area()).map_err(|m| invalid(svg_path, m))?;
    let mut svg = AtomicFile::create(svg_path)?;
    svg.write_with(|w| w.write_all(svg_text.as_bytes()))?;
    let (width, height) = size;
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    figure.draw(BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area()).map_err(|m| invalid(png_path, m))?;
    let mut png = AtomicFile::create(png_path)?;
    png.write_with(|w| {
        let mut encoder = png::Encoder::new(w, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer.write_image_data(&rgb).map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    })?;
    Ok([svg, png])
}

#[cfg(test)]
mod tests {
    use super::grid_shape;

    #[test]
    fn grids_follow_the_transfer_matrix_or_are_square() {
        // 6 x 6 and 8 x 8 matrices: one row per output.
        assert_eq!(grid_shape(36, Some(6), usize::MAX), (6, 6));
        assert_eq!(grid_shape(64, Some(8), usize::MAX), (8, 8));
        // Bode panel pairs: at most 4 per row, else the squarest grid.
        assert_eq!(grid_shape(6, Some(2), 4), (3, 2));
        assert_eq!(grid_shape(36, Some(6), 4), (6, 6));
        assert_eq!(grid_shape(10, Some(5), 4), (3, 4));
        // A diagonal of 8: 3 x 3 (columns first), one panel: 1 x 1.
        assert_eq!(grid_shape(8, None, usize::MAX), (3, 3));
        assert_eq!(grid_shape(1, None, 4), (1, 1));
        assert_eq!(grid_shape(0, None, 4), (1, 1));
    }
}
