//! # rins-scenarios
//!
//! Declarative scenario files for every experiment of Seo et al. (2022), the runner that drives
//! the plant through them, output sinks, the figures and terminal text of the results, and the
//! `rins` commands ([`commands`]; the binary only dispatches to them).

pub mod commands;
pub mod diagnose;
pub mod figures;
pub mod file;
pub mod fmu;
pub mod html;
pub mod interrupt;
pub mod iteration;
pub mod progress;
pub mod report;
pub mod runner;
pub mod sinks;
pub mod spans;
pub mod sweep;
pub mod truth;

/// The plotting helpers under their former path (`crate::diagnose` draws with them).
pub use figures::plot as plots;
pub use file::{Override, Scenario, ScenarioError};
pub use runner::{RunSummary, Sink, run};
