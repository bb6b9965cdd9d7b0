//! The plant's stages, in the order [`crate::Plant::step`] runs them. Each owns its state, its
//! part of the saved state and its part of the truth; none reads another's fields.
//!
//! - [`clock::Clock`]: the integer tick and sample counters, the only time there is.
//! - [`motion::Motion`]: the carrier (static site, ship, trajectory or external) and the
//!   dual-axis table with its scheme or commands: true increments and attitude per tick.
//! - [`temperature::TemperatureField`]: the chamber and the unit's thermal network, advanced on
//!   the slow grid (and early when the chamber input changes).
//! - [`sensor_errors::SensorErrors`]: every deterministic gyro and accelerometer effect (the
//!   catalogue of Eq. 3, 4 and 9 and the declared effects) on the true increments.
//! - [`readout::Readout`]: what the unit measures: noise, quantisation, encoders and
//!   temperature sensors. Everything seed-dependent lives here, so one deterministic interval
//!   can feed many seeds.

pub(crate) mod clock;
pub(crate) mod dwell_rule;
pub(crate) mod interval;
pub(crate) mod lane;
pub(crate) mod motion;
pub(crate) mod readout;
pub(crate) mod sensor_errors;
pub(crate) mod temperature;
