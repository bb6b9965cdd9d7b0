//! # rins-experiments
//!
//! The experiments that drive the plant through the reference navigator: a navigation session
//! ([`session`]: alignment, navigation, δβ compensation, error records against the truth), the
//! paper's system-level calibration runs ([`calibration`], Section 3.2) and the temperature
//! campaign ([`campaign`], Section 4.1). The navigator (rins-navigation) sees only the IMU's samples;
//! the truth is read here, for the error measures.

pub mod calibration;
pub mod campaign;
pub mod montecarlo;
pub mod session;
pub mod tracker;

pub use montecarlo::{Split, run_members, run_members_split, run_seeds};
pub use session::{Alignment, NavRecord, NavRun, NavRunConfig, run};
pub use tracker::Tracker;
