//! MBDyn's FEM file of the `modal` joint (input manual, appendix "Modal Element Data",
//! §FEM File Format), written from a [`FemFile`] as [`crate::input::fem`] and MBDyn 1.7.3
//! read it: records 1 (header), 2 (node labels), 5–7 (coordinates [m]), 8 (mode shapes,
//! one `**` line before each mode), 9–10 (modal mass and stiffness, row after row), 11
//! (lumped inertia [kg, kg m²]) and 12 (rigid-body inertia) when present, 13 (damping) when
//! present. Numbers are Rust's shortest round-trip form, so reading the file back gives the
//! same `f64`s. Written atomically.

use std::io::Write;
use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::input::fem::FemFile;

/// Writes `fem` to `path`; `title` goes in the opening comment lines (one `**` line each);
/// the last `constraint` modes are counted as constraint modes in the header, the others
/// as normal modes (MBDyn adds the counts up).
pub fn write_fem(path: &Path, fem: &FemFile, title: &str, constraint: usize) -> Result<(), OutputError> {
    let mut file = AtomicFile::create(path)?;
    file.write_with(|out| write_records(out, fem, title, constraint))?;
    file.commit()
}

fn write_records(out: &mut dyn Write, fem: &FemFile, title: &str, constraint: usize) -> std::io::Result<()> {
    for line in title.lines() {
        writeln!(out, "** {line}")?;
    }
    let modes = fem.modes();
    writeln!(out, "** RECORD GROUP 1, HEADER")?;
    writeln!(out, "**   REVISION.  NODES.  NORMAL.  ATTACHMENT  CONSTRAINT  REJECTED.")?;
    let normal = modes.saturating_sub(constraint);
    let constraint = modes - normal;
    writeln!(out, "REV0 {} {normal} 0 {constraint} 0", fem.nodes())?;
    writeln!(out, "** RECORD GROUP 2, FINITE ELEMENT NODE LIST")?;
    writeln!(out, "{}", fem.node_labels.join(" "))?;
    for (c, axis) in ["X", "Y", "Z"].iter().enumerate() {
        writeln!(out, "** RECORD GROUP {}, NODAL {axis} COORDINATES", 5 + c)?;
        for p in &fem.positions {
            writeln!(out, "{:e}", p[c])?;
        }
    }
    writeln!(out, "** RECORD GROUP 8, MODE SHAPES")?;
    for (j, shape) in fem.shapes.iter().enumerate() {
        let kind = if j < normal { "NORMAL" } else { "CONSTRAINT" };
        writeln!(out, "**    {kind} MODE SHAPE #  {}", j + 1)?;
        for node in shape {
            row(out, node)?;
        }
    }
    let matrix = |out: &mut dyn Write, title: &str, m: &faer::Mat<f64>| -> std::io::Result<()> {
        writeln!(out, "** {title}")?;
        for r in 0..m.nrows() {
            row(out, &(0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<_>>())?;
        }
        Ok(())
    };
    matrix(out, "RECORD GROUP 9, MODAL MASS MATRIX", &fem.mass)?;
    matrix(out, "RECORD GROUP 10, MODAL STIFFNESS MATRIX", &fem.stiffness)?;
    if let Some(lumped) = &fem.lumped_inertia {
        writeln!(out, "** RECORD GROUP 11, DIAGONAL OF LUMPED MASS MATRIX")?;
        for node in lumped {
            row(out, node)?;
        }
    }
    if let Some(r) = &fem.rigid_inertia {
        writeln!(out, "** RECORD GROUP 12, GLOBAL INERTIA PROPERTIES")?;
        writeln!(out, "{:e}", r.mass)?;
        row(out, &r.centre_of_mass)?;
        for line in &r.inertia {
            row(out, line)?;
        }
    }
    if let Some(d) = &fem.damping {
        matrix(out, "RECORD GROUP 13, MODAL DAMPING MATRIX", d)?;
    }
    writeln!(out, "** END OF FILE")
}

fn row(out: &mut dyn Write, values: &[f64]) -> std::io::Result<()> {
    let text: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
    writeln!(out, "{}", text.join(" "))
}
