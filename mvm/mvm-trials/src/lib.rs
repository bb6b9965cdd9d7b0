//! # rins-mvm-trials: the independent generator of a diagnosis benchmark
//!
//! Writes the measurement logs of randomised trials of `rins diagnose` (see the benchmark note,
//! "Measuring the diagnosis: rates over randomised trials") from closed-form physics with its
//! own code: rotation matrices ([`rotation`]), the table's piecewise-linear gimbal angles
//! ([`table`]), the unit's first-order thermal lags solved exactly on each leg of a
//! piecewise-linear chamber profile ([`exp_poly`], [`thermal`]), the rows integrated exactly or
//! by Gauss–Legendre quadrature on smooth pieces ([`quadrature`], [`row`]) and the hidden
//! effects' formulas ([`hidden`], [`effect_error`]). Of the plant it reads only parameter values
//! (`PlantConfig`) and the site's normal gravity and Earth rate (`earth::Site`); of the
//! diagnosis only the `History` type it fills. A mistake shared with the diagnosis therefore
//! cannot cancel.
//!
//! A trial: [`draw_design`] (or a named [`Design`]), hidden effects scaled to an oracle z band
//! ([`scale_to_z`], [`oracle`]), [`generate`] the log, and [`write_csv`] it, with the model as a scenario
//! file ([`write_model`]), when a trial must be replayed alone.

pub mod bench;
pub mod classes;
pub mod csv;
pub mod design;
pub mod draw;
pub mod effect_error;
pub mod exp_poly;
pub mod expect;
pub mod generate;
pub mod hidden;
pub mod model_file;
pub mod oracle;
pub mod quadrature;
pub mod rotation;
pub mod row;
pub mod table;
pub mod thermal;
pub mod units;

pub use bench::{Outcome, Report, TrialSpec, plan, run, run_trial};
pub use classes::Class;
pub use csv::write_csv;
pub use design::{ChamberLeg, Design, Gimbal, RUN_GAP_S, RunDesign, TableLeg, UnitThermal};
pub use draw::draw_design;
pub use generate::{Truth, check_model, generate};
pub use hidden::{Channel, HiddenEffect, Sensor};
pub use model_file::{model_toml, write_model};
pub use oracle::{
    Nuisance, oracle_z, oracle_z_beyond, oracle_z_per_channel, oracle_z_per_channel_with,
    scale_to_z,
};
