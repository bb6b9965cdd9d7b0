//! Temperature sensors: one per thermal node (board, gyro x/y/z, accelerometers, housing), the
//! readings a navigation computer uses for temperature compensation (δβ(T) of Eq. 9, the
//! calibration campaign). Like a real IMU's housekeeping channel they are sampled at the thermal
//! update interval (`thermal.step_s`) and held in between:
//!
//! T_measured = round_lsb(T_true + b + σ·n), n ~ N(0, 1) from its own named random stream.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::noise::{NormalStream, stream};
use crate::thermal::node;

/// Temperature-sensor error terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TempSensorTerm {
    /// Constant offset b per sensor (K).
    Offset,
    /// White reading noise σ per sensor (K, 1σ per reading).
    Noise,
    /// Rounding to the converter's least significant bit (K).
    Resolution,
}

impl TempSensorTerm {
    /// All terms in application order.
    pub const ALL: [TempSensorTerm; 3] = [
        TempSensorTerm::Offset,
        TempSensorTerm::Noise,
        TempSensorTerm::Resolution,
    ];

    /// Key of the term under `[sensor.temperature]`.
    pub fn key(self) -> &'static str {
        match self {
            TempSensorTerm::Offset => "offset",
            TempSensorTerm::Noise => "noise",
            TempSensorTerm::Resolution => "resolution",
        }
    }
}

/// Per-sensor values in node order (board, gyro x, gyro y, gyro z, accelerometers, housing).
pub type PerSensor = [f64; node::COUNT];

/// Sensor offsets.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TempOffsetSpec {
    /// Term on.
    pub enabled: bool,
    /// Offset per sensor, K.
    pub k: PerSensor,
}

/// Reading noise.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TempNoiseSpec {
    /// Term on.
    pub enabled: bool,
    /// 1σ per reading and sensor, K.
    pub sigma_k: PerSensor,
}

/// Converter resolution.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TempResolutionSpec {
    /// Term on.
    pub enabled: bool,
    /// Least significant bit, K (a 12-bit sensor over 256 K: 0.0625 K).
    pub lsb_k: f64,
}

impl Default for TempResolutionSpec {
    fn default() -> Self {
        Self {
            enabled: false,
            lsb_k: 0.0625,
        }
    }
}

/// The temperature-sensor errors; every term off by default (the paper's presets).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TempSensorSpec {
    /// Offsets.
    pub offset: TempOffsetSpec,
    /// Reading noise.
    pub noise: TempNoiseSpec,
    /// Resolution.
    pub resolution: TempResolutionSpec,
}

impl TempSensorSpec {
    /// Whether `term` is switched on.
    pub fn is_enabled(&self, term: TempSensorTerm) -> bool {
        match term {
            TempSensorTerm::Offset => self.offset.enabled,
            TempSensorTerm::Noise => self.noise.enabled,
            TempSensorTerm::Resolution => self.resolution.enabled,
        }
    }

    /// The terms switched on, in application order.
    pub fn enabled_terms(&self) -> Vec<TempSensorTerm> {
        TempSensorTerm::ALL
            .into_iter()
            .filter(|t| self.is_enabled(*t))
            .collect()
    }
}

/// The sensors with their noise source.
#[derive(Clone, Debug)]
pub struct TempSensors {
    offset_k: PerSensor,
    sigma_k: PerSensor,
    lsb_k: f64,
    noisy: bool,
    ideal: bool,
    /// Reading-noise source (stream [`stream::TEMP_SENSOR`] of the seed).
    pub stream: NormalStream,
}

impl TempSensors {
    /// The sensors of `spec`, drawing noise from `seed`.
    pub fn new(spec: &TempSensorSpec, seed: u64) -> Self {
        let noisy = spec.noise.enabled;
        Self {
            offset_k: if spec.offset.enabled {
                spec.offset.k
            } else {
                [0.0; node::COUNT]
            },
            sigma_k: if noisy {
                spec.noise.sigma_k
            } else {
                [0.0; node::COUNT]
            },
            lsb_k: if spec.resolution.enabled {
                spec.resolution.lsb_k
            } else {
                0.0
            },
            noisy,
            ideal: TempSensorTerm::ALL.iter().all(|t| !spec.is_enabled(*t)),
            stream: NormalStream::new(seed, stream::TEMP_SENSOR),
        }
    }

    /// Restarts the noise source from `seed` (see `Plant::reseed_noise`).
    pub fn reseed(&mut self, seed: u64) {
        self.stream = NormalStream::new(seed, stream::TEMP_SENSOR);
    }

    /// One reading of every sensor for the true node temperatures `true_c`, °C.
    pub fn read(&mut self, true_c: &PerSensor) -> PerSensor {
        if self.ideal {
            return *true_c;
        }
        let mut noise = [0.0; node::COUNT];
        if self.noisy {
            // Two three-draw blocks keep the stream's draw order fixed: six draws per reading.
            let (a, b): (Vector3<f64>, Vector3<f64>) = (self.stream.vec3(), self.stream.vec3());
            noise = [a.x, a.y, a.z, b.x, b.y, b.z];
        }
        let mut out = [0.0; node::COUNT];
        for k in 0..node::COUNT {
            let y = true_c[k] + self.offset_k[k] + self.sigma_k[k] * noise[k];
            out[k] = if self.lsb_k > 0.0 {
                (y / self.lsb_k).round() * self.lsb_k
            } else {
                y
            };
        }
        out
    }
}
