//! # rins-scenarios
//!
//! The `rins` application: its commands ([`commands`], one module each; the binary only
//! dispatches to them), the runner that drives the plant through a scenario into sinks
//! ([`runner`], [`sinks`]), the FMU build and run glue ([`fmu`]), the simulated measurement logs
//! and report figures of model vs measurements ([`diagnose`]), the Rerun recordings behind the
//! `rerun` feature ([`recordings`]), Ctrl-C and progress bars. The scenario format is
//! `rins-scenario`, sweeps `rins-sweep`, how results are shown `rins-report`.

pub mod commands;
pub mod diagnose;
pub mod fmu;
pub mod interrupt;
pub mod progress;
#[cfg(feature = "rerun")]
pub mod recordings;
pub mod runner;
pub mod sinks;

pub use runner::{RunSummary, Sink, run};
