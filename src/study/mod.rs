//! The ROM workflow as one library type: [`Study`] loads a linear DAE (an MBDyn model
//! linearized at a reference solution, or a pencil file), runs its eigenanalysis, and builds
//! reduced-order models from a [`RomRequest`] with the checks that keep a wrong ROM from
//! looking right (static gains against the full model, warnings).
//!
//! The CLI (`romdyn eig|rom|freq`) only parses arguments into these types and prints what
//! they return; a language binding does the same.
//!
//! ```no_run
//! use romdyn::analysis::Reference;
//! use romdyn::rom::ModeSelection;
//! use romdyn::study::{EigenSettings, Linearization, RomRequest, Study};
//!
//! let lin = Linearization { reference: Reference::Static { load_steps: 10 }, inputs: vec!["5:Fy".parse()?], outputs: vec!["5:y".parse()?] };
//! let study = Study::from_model_file("examples/simply_supported_beam.mbd".as_ref(), &lin, EigenSettings::default())?;
//! let rom = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)))?;
//! println!("{} states", rom.ordinary.a.nrows());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Extension points: new input/output kinds enter through [`Study::from_dae`] (any `B̃`, `C̃`
//! on a model's linear DAE), corrections of the full model go in before the eigenanalysis
//! ([`Study::from_dae`] again), corrections of a ROM are fields of [`RomRequest`].

mod accuracy;
mod application;
mod checks;
mod control;
mod error;
mod export;
mod linear;
mod reduce;
mod response;
mod setting;
mod setup;
mod solver;
mod summary;
mod warning;

pub use accuracy::RomCheck;
pub use application::{parse_imposed, Application, Transmissibility};
pub use checks::zero_channels;
pub use control::{balancing, minimal_tolerance, sampling, Balancing, OrderReduction};
pub use error::StudyError;
pub use export::RomForm;
pub use reduce::{BelowBand, KeptMode, ReducedModel, Residualization, RomRequest, StaticGains, UndampedTwin};
pub use response::{ChannelError, Comparison, FrequencyGrid, GridAccuracy};
pub use setting::{python_spelling, Setting};
pub use setup::{checked_reference_state, EigenSettings, Linearization, Ports, Study};
pub use solver::{needs_every_mode, sparse_target, Solver, SparseRun, DOMINANCE_POOL, SPARSE_DEFAULT_COUNT};
pub use warning::{Response, Warning};
