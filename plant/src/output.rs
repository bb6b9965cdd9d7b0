//! What one step of the plant gives: the sample the IMU outputs (its measured outputs) and the
//! truth beside it (for error measures and verification only).

use nalgebra::{UnitQuaternion, Vector3};

use crate::carrier::CarrierTruth;
use crate::effects::accel::ACCEL_TERMS;
use crate::effects::gyro::GYRO_TERMS;
use crate::table::{GimbalAngles, GimbalState};
use crate::thermal::{Temperatures, node};

/// One IMU output: increments over the interval ending at `t_s`. Its default is all zeros
/// (sample 0 at t = 0, no increments, encoders at 0, sensors reading 0 °C): a sample of the
/// right shape for an importer to overwrite, not a reading the plant gives.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ImuSample {
    /// Output sample number; sample k covers [k·Δt, (k+1)·Δt].
    pub index: u64,
    /// End of the interval, s.
    pub t_s: f64,
    /// Angular increment Δθ, rad.
    pub dtheta_rad: Vector3<f64>,
    /// Velocity increment Δv, m/s.
    pub dv_mps: Vector3<f64>,
    /// Gimbal encoder readings at the end of the interval, rad.
    pub encoder: GimbalAngles,
    /// Temperature-sensor readings (board, gyro x, y, z, accelerometers, housing), °C: the
    /// reading of the last thermal update.
    pub temps_c: [f64; node::COUNT],
}

impl ImuSample {
    /// The gyro block temperature readings (x, y, z), °C.
    pub fn gyro_temps_c(&self) -> Vector3<f64> {
        Vector3::new(self.temps_c[1], self.temps_c[2], self.temps_c[3])
    }

    /// The accelerometer cluster temperature reading, °C.
    pub fn accel_temp_c(&self) -> f64 {
        self.temps_c[node::ACCEL]
    }
}

/// What really happened over the last interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Truth {
    /// Table state at the end of the interval.
    pub gimbal: GimbalState,
    /// Error-free angular increment, rad.
    pub dtheta_true_rad: Vector3<f64>,
    /// Error-free velocity increment, m/s.
    pub dv_true_mps: Vector3<f64>,
    /// Temperatures used over the interval.
    pub temps: Temperatures,
    /// Each gyro term's increment error, rad, indexed like [`crate::effects::GyroTerm::ALL`].
    pub gyro_terms_rad: [Vector3<f64>; GYRO_TERMS],
    /// Each accelerometer term's increment error, m/s, indexed like [`crate::effects::AccelTerm::ALL`].
    pub accel_terms_mps: [Vector3<f64>; ACCEL_TERMS],
    /// Weight of δβ at the interval midpoint (0 Z-up, 1 Z-down).
    pub position_weight: f64,
    /// The declared gyro effects' summed increment error, rad (`[[sensor.gyro.custom]]`).
    pub custom_gyro_rad: Vector3<f64>,
    /// The declared accelerometer effects' summed increment error, m/s.
    pub custom_accel_mps: Vector3<f64>,
    /// The carrier at the end of the interval (the site and `[vehicle]` attitude when static).
    /// [`crate::Plant::truth`] fills it in on a moving carrier.
    pub carrier: CarrierTruth,
}

impl Default for Truth {
    /// A truth of the right shape for an importer to overwrite, not a state the plant passes
    /// through: zeros throughout (the table still at angles 0 on its first step, no increments,
    /// every node and the chamber at 0 °C, no term errors, weight 0) and the carrier at rest at
    /// latitude, longitude and height 0 with the identity attitude.
    fn default() -> Self {
        Self {
            gimbal: GimbalState {
                angles: GimbalAngles::default(),
                outer_rate_rps: 0.0,
                inner_rate_rps: 0.0,
                step_index: 0,
                moving: false,
            },
            dtheta_true_rad: Vector3::zeros(),
            dv_true_mps: Vector3::zeros(),
            temps: Temperatures {
                nodes_c: [0.0; node::COUNT],
                chamber_c: 0.0,
            },
            gyro_terms_rad: [Vector3::zeros(); GYRO_TERMS],
            accel_terms_mps: [Vector3::zeros(); ACCEL_TERMS],
            position_weight: 0.0,
            custom_gyro_rad: Vector3::zeros(),
            custom_accel_mps: Vector3::zeros(),
            carrier: CarrierTruth {
                lat_rad: 0.0,
                lon_rad: 0.0,
                height_m: 0.0,
                v_n: Vector3::zeros(),
                q_cn: UnitQuaternion::identity(),
                omega_nc_c: Vector3::zeros(),
            },
        }
    }
}
