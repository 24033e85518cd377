//! Reduced-order models (paper §7): mode selection, projection onto right and adjoint
//! eigenvectors (descriptor form, eqs. 41–50, 64–67), SVD residualization to an ordinary
//! state-space model (eqs. 51–63), frequency responses and static gains.

mod dense;
mod descriptor;
mod error;
mod ordinary;
mod response;
mod select;

pub use descriptor::DescriptorRom;
pub use error::RomError;
pub use ordinary::OrdinaryRom;
pub use response::{frequency_grid, full_frequency_response, full_static_gain, log_frequencies};
pub use select::{select_modes, ModeSelection, Selection};
