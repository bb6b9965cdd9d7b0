//! # rins-navigation
//!
//! The reference "external navigation software" for the rins plant: a strapdown navigator in
//! ENU on WGS-84 consuming Δθ/Δv increments with coning and sculling compensation, coarse and
//! fine self-alignment, real-time compensation of the position-dependent gyro bias δβ, and error
//! measures (attitude φ, position, tRMS of Eq. 20), and the calibration maths (Eq. 13–19, the
//! δβ(T) fit). It sees only what the IMU outputs; the experiments that drive a plant through it
//! are in rins-experiments.

pub mod alignment;
#[cfg(target_arch = "x86_64")]
mod avx512_lanes;
pub mod calibration;
pub mod campaign;
pub mod compensation;
pub mod errors;
pub mod fit;
mod mechanisation;
pub mod strapdown;
pub mod strapdown_lanes;
pub mod subsamples;

pub use alignment::Alignment;
pub use errors::NavRecord;
pub use strapdown::{NavState, Strapdown, VerticalChannel};
pub use strapdown_lanes::StrapdownLanes;
pub use subsamples::Subsamples;
