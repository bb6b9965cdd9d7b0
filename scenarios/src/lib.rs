//! # rins-scenarios
//!
//! Declarative scenario files for every experiment of Seo et al. (2022), the runner that drives
//! the plant through them, output sinks, and the `rins` command line.

pub mod diagnose;
pub mod file;
pub mod fmu;
pub mod interrupt;
pub mod plots;
pub mod progress;
pub mod report;
pub mod runner;
pub mod sinks;
pub mod spans;
pub mod viz;

pub use file::{Override, Scenario, ScenarioError};
pub use runner::{RunSummary, Sink, run};
