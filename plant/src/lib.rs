//! # rins-plant
//!
//! A deterministic, fixed-step plant model of a dual-axis rotational inertial navigation system
//! (RINS) built on ring-laser gyros, after Seo et al., "Analysis of Gyro Bias Depending on the
//! Position of Inertial Measurement Unit in Rotational Inertial Navigation Systems",
//! Sensors 2022, 22, 8355.
//!
//! The plant is pure computation: no I/O, no global state. [`Plant::step`] advances one output
//! interval through its stages (see `stages`): the temperature field's slow update
//! ([`thermal`]), per tick the motion (carrier and table: [`carrier`], [`table`], [`earth`])
//! and the deterministic sensor [`effects`], then the readout (noise, quantisation, encoders,
//! temperature sensors). It returns the Δθ/Δv increments an RLG IMU reports and keeps the truth
//! beside them. Time is an integer tick counter; every random term draws from its own named
//! stream of the seed.

pub mod attitude;
mod batch;
pub mod carrier;
pub mod command;
pub mod config;
pub mod earth;
pub mod effects;
pub mod kinematics;
pub mod message;
pub mod output;
pub mod output_columns;
pub mod params;
pub mod plant;
pub mod presets;
pub mod real;
mod simd;
mod stages;
pub mod state;
pub mod table;
pub mod thermal;
pub mod trig;
pub mod true_attitude;
pub mod units;
mod validation;

pub use batch::SeedBatch;
pub use command::GimbalCommand;
pub use config::{ConfigError, PlantConfig, SensorSpec, VehicleSpec};
pub use output::{ImuSample, Truth};
pub use plant::Plant;
pub use true_attitude::TruthMount;
