//! # rins-fmi-plant
//!
//! The one adapter between the rins plant's parameter table ([`rins_plant::params`]) and the
//! generic FMI layer ([`rins_fmi`]), shared by every FMU model built on the plant (the IMU and
//! the carrier): scenario parameters as FMU parameters ([`parameter`], with the enumerations'
//! type names from [`enum_types`]), the block of them a model exposes and the plant
//! configuration their values describe ([`plant_params`]), and inputs declared as rows of a
//! table ([`input_row`]). `rins-fmi` stays model-agnostic: everything that knows the plant is
//! here or in the model crates.
//!
//! A model built on it declares its variable table (which keys are parameters, its input and
//! output rows) and implements [`rins_fmi::model::Model`]; `tests/one_axis` is such a model in
//! one file.

pub mod enum_types;
pub mod input_row;
pub mod parameter;
pub mod plant_params;

pub use input_row::InputRow;
pub use parameter::{param_var, to_param};
pub use plant_params::PlantParams;
