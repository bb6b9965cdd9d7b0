//! # rins-plant
//!
//! A deterministic, fixed-step plant model of a dual-axis rotational inertial navigation system
//! (RINS) built on ring-laser gyros, after Seo et al., "Analysis of Gyro Bias Depending on the
//! Position of Inertial Measurement Unit in Rotational Inertial Navigation Systems",
//! Sensors 2022, 22, 8355.
//!
//! The plant is pure computation: no I/O, no global state. [`Plant::step`] advances one output
//! interval through the stages kinematics ([`table`], [`earth`]) → [`thermal`] → sensor
//! [`effects`] → noise → quantisation, and returns the Δθ/Δv increments an RLG IMU reports.
//! Time is an integer tick counter; every random term draws from its own named stream of the seed.

mod accessors;
pub mod attitude;
pub mod carrier;
pub mod command;
pub mod config;
pub mod earth;
pub mod effects;
/// An externally driven carrier (a vessel model supplying samples at communication points).
#[path = "carrier/external.rs"]
pub mod external_carrier;
pub mod kinematics;
pub mod params;
pub mod plant;
pub mod presets;
mod simd;
pub mod state;
pub mod table;
pub mod thermal;
mod trig;
pub mod units;

pub use command::GimbalCommand;
pub use config::{ConfigError, PlantConfig, SensorSpec, VehicleSpec};
pub use plant::{ImuSample, Plant, Truth};
