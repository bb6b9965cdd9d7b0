//! Unit conversions. Everything inside the plant is SI (rad, s, m, K offsets in °C);
//! these constants convert the units navigation engineers quote in specifications.

use std::f64::consts::PI;

/// Radians per degree.
pub const DEG: f64 = PI / 180.0;
/// Radians per arc-second.
pub const ARCSEC: f64 = DEG / 3600.0;
/// Seconds per hour.
pub const HOUR_S: f64 = 3600.0;
/// rad/s per °/h (gyro bias unit).
pub const DPH: f64 = DEG / HOUR_S;
/// rad/√s per °/√h (angle random walk unit).
pub const DPSH: f64 = DEG / 60.0;
/// rad/s/√s per °/h/√h (rate random walk unit).
pub const DPH_PER_SQRTH: f64 = DPH / 60.0;
/// Dimensionless per part-per-million.
pub const PPM: f64 = 1e-6;
/// Standard gravity used to express accelerometer errors in g, m/s².
pub const G0: f64 = 9.806_65;
/// m/s² per micro-g.
pub const UG: f64 = 1e-6 * G0;
/// Metres per international nautical mile.
pub const NMI_M: f64 = 1852.0;
