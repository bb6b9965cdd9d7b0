//! The plant's complete parameter set and the error its validation reports
//! ([`PlantConfig::validate`], in `validation.rs`).

use serde::{Deserialize, Serialize};

use crate::carrier::CarrierSpec;
use crate::earth::{EarthSpec, SiteSpec};
use crate::effects::encoder::EncoderSpec;
use crate::effects::temp_sensor::TempSensorSpec;
use crate::effects::{AccelSpec, GyroSpec};
use crate::table::SchemeSpec;
use crate::thermal::ThermalSpec;

/// Static vehicle attitude: C_v^n = R_z(azimuth)·R_x(pitch)·R_y(roll), ENU, azimuth counter-clockwise
/// from east. Zero gives the paper's level mount where position A is C_b^n = I (Eq. 5).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VehicleSpec {
    /// Rotation about up, degrees.
    pub azimuth_deg: f64,
    /// Rotation about the vehicle x axis, degrees, in [-89, 89].
    pub pitch_deg: f64,
    /// Rotation about the vehicle y axis, degrees, in [-180, 180].
    pub roll_deg: f64,
}

impl VehicleSpec {
    /// The mount rotation C_v^n.
    pub fn c_vn(&self) -> nalgebra::Matrix3<f64> {
        use crate::table::gimbal::{rot_x, rot_y, rot_z};
        use crate::units::DEG;
        rot_z(self.azimuth_deg * DEG) * rot_x(self.pitch_deg * DEG) * rot_y(self.roll_deg * DEG)
    }
}

/// Gyro and accelerometer error terms.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorSpec {
    /// Gyro terms (Eq. 3, 9 and the RLG effects).
    pub gyro: GyroSpec,
    /// Accelerometer terms (Eq. 4).
    pub accel: AccelSpec,
    /// Gimbal angle encoders.
    pub encoder: EncoderSpec,
    /// Temperature sensors.
    pub temperature: TempSensorSpec,
}

/// Everything the plant needs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlantConfig {
    /// IMU output rate, Hz, in [1, 10000].
    pub rate_hz: f64,
    /// Internal integration steps per output interval, in [1, 1000].
    pub substeps: u32,
    /// Seed of every random stream.
    pub seed: u64,
    /// Geodetic site.
    pub site: SiteSpec,
    /// Vehicle mount attitude.
    pub vehicle: VehicleSpec,
    /// Earth switches.
    pub earth: EarthSpec,
    /// Rotation scheme.
    pub scheme: SchemeSpec,
    /// Sensor errors.
    pub sensor: SensorSpec,
    /// Thermal network.
    pub thermal: ThermalSpec,
    /// The carrier (static by default).
    pub carrier: CarrierSpec,
}

impl Default for PlantConfig {
    fn default() -> Self {
        Self {
            rate_hz: 100.0,
            substeps: 1,
            seed: 1,
            site: SiteSpec::default(),
            vehicle: VehicleSpec::default(),
            earth: EarthSpec::default(),
            scheme: SchemeSpec::default(),
            sensor: SensorSpec::default(),
            thermal: ThermalSpec::default(),
            carrier: CarrierSpec::default(),
        }
    }
}

/// A parameter outside its valid range. `path` uses the scenario-file key path.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{path}: expected {expected}, got {got}")]
pub struct ConfigError {
    /// Dotted key path, e.g. `sensor.gyro.bias.dph`.
    pub path: String,
    /// The valid range or form.
    pub expected: String,
    /// The offending value.
    pub got: String,
}

impl PlantConfig {
    /// Output interval, s.
    pub fn dt_s(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// This configuration run with seed `seed` (a member of a Monte Carlo case).
    pub fn with_seed(&self, seed: u64) -> PlantConfig {
        PlantConfig {
            seed,
            ..self.clone()
        }
    }

    /// This configuration with its stochastic terms off: gyro angle random walk, bias
    /// instability and rate random walk (Eq. 3's ε_g), accelerometer velocity random walk
    /// (Eq. 4's ε_a). Every deterministic error, the quantisation and the temperature sensors
    /// stay as they are: the paper's noise-free pair (Table 4). These are exactly the terms a
    /// member of a [`crate::SeedBatch`] may switch off and still share the seeds' physics.
    pub fn noise_free(&self) -> PlantConfig {
        use crate::effects::GyroTerm;
        let mut c = self.clone();
        for t in [
            GyroTerm::AngleRandomWalk,
            GyroTerm::BiasInstability,
            GyroTerm::RateRandomWalk,
        ] {
            c.sensor.gyro.set_enabled(t, false);
        }
        c.sensor.accel.velocity_random_walk.enabled = false;
        c
    }
}
