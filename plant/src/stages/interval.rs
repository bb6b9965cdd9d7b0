//! The deterministic result of one output interval: what the physics gives before anything
//! seed-dependent is added.

use nalgebra::Vector3;

/// True increments and the deterministic sensor errors over one output interval (all
/// substeps). While the table dwells and no thermal update intervenes, every input of it is
/// constant, so the plant reuses one for the rest of the dwell bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Error-free angular increment, rad.
    pub dtheta_true_rad: Vector3<f64>,
    /// Error-free velocity increment, m/s.
    pub dv_true_mps: Vector3<f64>,
    /// Sum of the deterministic gyro errors (catalogue and declared), rad.
    pub gyro_err_rad: Vector3<f64>,
    /// Sum of the deterministic accelerometer errors, m/s.
    pub accel_err_mps: Vector3<f64>,
    /// Mean weight of δβ over the interval (0 Z-up, 1 Z-down, Eq. 9).
    pub position_weight: f64,
}
