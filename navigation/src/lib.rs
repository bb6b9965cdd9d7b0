//! # rins-nav
//!
//! The reference "external navigation software" for the rins plant: a strapdown navigator in
//! ENU on WGS-84 consuming Δθ/Δv increments with coning and sculling compensation, coarse and
//! fine self-alignment, real-time compensation of the position-dependent gyro bias δβ, and error
//! measures against the plant's truth (attitude φ, position, tRMS of Eq. 20).

pub mod alignment;
pub mod calibration;
pub mod campaign;
pub mod compensation;
pub mod errors;
pub mod fit;
pub mod session;
pub mod strapdown;

pub use session::{Alignment, NavRecord, NavRun, NavRunConfig, Tracker, run};
pub use strapdown::{NavState, Strapdown, VerticalChannel};
