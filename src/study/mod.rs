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
//! use romdyn::study::{RomRequest, Study, StudySource};
//!
//! let study = Study::builder(StudySource::model_file("examples/simply_supported_beam.mbd"))
//!     .reference(Reference::Static { load_steps: 10 })
//!     .node_ports(vec!["5:Fy".parse()?], vec!["5:y".parse()?])
//!     .build()?;
//! let rom = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)))?;
//! println!("{} states", rom.ordinary.a.nrows());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every front end builds its study the same way, [`Study::builder`] with a [`StudySource`]
//! (an MBDyn file, a model, a pencil file, a linear DAE), its options checked once there.
//! Extension points: new input/output kinds enter as [`StudySource::Dae`] (any `B̃`, `C̃`
//! on a model's linear DAE), corrections of the full model go in before the eigenanalysis
//! (a [`StudySource::Dae`] again), corrections of a ROM are fields of [`RomRequest`].

mod accuracy;
mod application;
mod builder;
mod checks;
mod control;
mod error;
mod export;
mod free;
mod linear;
mod names;
mod reduce;
mod report;
mod response;
mod setting;
mod setup;
mod solver;
mod summary;
mod warning;

pub use accuracy::RomCheck;
pub use application::{parse_imposed, Application};
pub use builder::{StudyBuilder, StudySource};
pub use checks::zero_channels;
pub use control::{balancing, minimal_tolerance, sampling, Balancing, OrderReduction, DISCRETIZATIONS};
pub use error::StudyError;
pub use export::RomForm;
pub use free::{FreeEigenvalue, FreeEigenvalues, FreeKind};
pub use reduce::{BelowBand, KeptMode, ReducedModel, Residualization, RomRequest, StaticGains, UndampedTwin};
pub use response::{default_band, ChannelError, FrequencyGrid, GridAccuracy};
pub use names::{value_names, Named};
pub use setting::{python_spelling, Setting, COMMAND_LINE_ONLY};
pub use setup::{checked_reference_state, EigenSettings, Ports, Study};
pub use solver::{needs_every_mode, sparse_target, Solver, SparseRun, DOMINANCE_POOL, SPARSE_DEFAULT_COUNT};
pub use warning::{Response, Warning};
