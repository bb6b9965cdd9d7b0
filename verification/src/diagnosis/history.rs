//! A measured history in SI units: what the model is replayed on.

use std::ops::Range;

/// IMU attitude over the history.
#[derive(Clone, Debug, PartialEq)]
pub enum Attitude {
    /// Gimbal angles at the end of each row, rad (C_b^n = C_v^n R_z(outer) R_x(inner)).
    Gimbal {
        /// Outer (azimuth) angle.
        outer_rad: Vec<f64>,
        /// Inner angle.
        inner_rad: Vec<f64>,
    },
    /// Body-to-ENU quaternion (w, x, y, z) at the end of each row.
    Quaternion(Vec<[f64; 4]>),
}

/// Measured rows (row k covers (t_{k-1}, t_k]), one vector per quantity and axis (the columns
/// of the file, moved rather than copied).
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// End time of each row, s.
    pub t_s: Vec<f64>,
    /// Angular increments per axis, rad.
    pub dtheta_rad: [Vec<f64>; 3],
    /// Velocity increments per axis, m/s.
    pub dv_mps: [Vec<f64>; 3],
    /// Attitude at the end of each row.
    pub attitude: Attitude,
    /// Gyro block temperatures per axis, °C (the one measured temperature on every axis when
    /// the file has no per-gyro columns).
    pub gyro_temp_c: [Vec<f64>; 3],
    /// Housing temperature, °C, when measured: the gradient across gyro block i is
    /// `gyro_temp_c[i] − housing_temp_c`.
    pub housing_temp_c: Option<Vec<f64>>,
    /// Accelerometer temperature, °C.
    pub accel_temp_c: Vec<f64>,
    /// Run index of each row (into `run_names`).
    pub run: Vec<u32>,
    /// Run names.
    pub run_names: Vec<String>,
    /// Row ranges of the segments (rows of one run and segment label, time increasing).
    pub segments: Vec<Range<usize>>,
    /// Where the data came from (file name), for messages.
    pub source: String,
}

impl History {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}
