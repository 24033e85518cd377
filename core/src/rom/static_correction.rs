//! Static correction of truncated modes (issue 13 point 3, paper Fig. 7): a ROM of a few
//! modes gets the direct term `D + (G_full − G_rom)`, with `G_full` the full model's static
//! gain (one sparse solve through the static matrix,
//! [`crate::linear::SparseLinearDae::static_gain`]) and `G_rom = D − C A⁻¹ B` its own. The
//! ROM's static gain then equals the full model's without computing the other modes; its
//! dynamics (A, B, C, eigenvalues) are unchanged.

use faer::Mat;

use super::{OrdinaryRom, RomError};

/// The ROM with its static gain corrected to `full_gain` (outputs x inputs).
pub fn with_static_correction(rom: &OrdinaryRom, full_gain: &Mat<f64>) -> Result<OrdinaryRom, RomError> {
    if full_gain.nrows() != rom.d.nrows() || full_gain.ncols() != rom.d.ncols() {
        return Err(RomError::Selection(format!(
            "static correction: the full gain is {}x{}, the ROM has {} outputs and {} inputs",
            full_gain.nrows(),
            full_gain.ncols(),
            rom.d.nrows(),
            rom.d.ncols()
        )));
    }
    let own = rom.static_gain()?;
    let mut out = rom.clone();
    out.d = &rom.d + (full_gain - &own);
    Ok(out)
}
