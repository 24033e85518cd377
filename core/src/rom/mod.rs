//! Reduced-order models (paper §7): mode selection, projection onto right and adjoint
//! eigenvectors (descriptor form, eqs. 41–50, 64–67), SVD residualization to an ordinary
//! state-space model (eqs. 51–63), frequency responses and static gains.

mod balanced;
mod damping;
mod dense;
mod descriptor;
mod discrete;
mod dominance;
mod error;
mod imposed;
mod lyapunov;
mod matched;
mod null_space;
mod ordinary;
mod response;
mod select;
mod springs;
mod static_correction;
mod units;

pub use balanced::{BalancedMethod, BalancedOrder, BalancedReduction};
pub use damping::{DampingChange, ModalDamping};
pub use descriptor::DescriptorRom;
pub use discrete::{expm, DiscreteRom, Discretization, Sampling};
pub use dominance::{Dominance, NEGLIGIBLE_DOMINANCE};
pub use error::RomError;
pub use imposed::{transmissibility, ImposedModel};
pub use springs::{with_spring_ports, without_elements, SpringFeedback};
pub use null_space::null_direction;
pub use ordinary::OrdinaryRom;
pub use response::{frequency_grid, full_frequency_response, full_static_gain, full_static_gain_and_scale, full_static_gain_or_free_direction, log_frequencies};
pub use select::{select_dominant_modes, select_modes, ModeSelection, Ranking, Selection};
pub use units::{mode_units, unit_of, REAL_PAIR_TOLERANCE};
pub use static_correction::with_static_correction;
