//! # rins-scenario
//!
//! The scenario file format of `rins`: a TOML file (or a built-in, `builtin:NAME`) naming a
//! sensor preset, the plant's parameters, the scheme, the carrier and the run, read strictly
//! (every error names the file, line and column and the expected range), and the plant it
//! describes ([`new_plant`]). Everything that runs, sweeps or shows a scenario is built on this
//! crate; it knows nothing of them (docs/scenario-format.md).

pub mod file;
mod new_plant;
pub mod spans;

pub use file::{BUILTIN, Override, Scenario, ScenarioError};
pub use new_plant::new_plant;
