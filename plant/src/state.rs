//! Plant state by value: everything that evolves, as bytes, so a run can be saved and resumed
//! bit-identically in another process (FMU state serialisation, transport restarts).
//!
//! Layout: magic `RINSPS02`, a fingerprint of the configuration (the state only restores into
//! the plant it came from), then little-endian u64/f64 fields in a fixed order. Caches (dwell,
//! attitude, schedule cursor) are not saved: they are rebuilt and give the same bits.

use nalgebra::Vector3;

use crate::command::ActiveCommand;
use crate::config::PlantConfig;
use crate::plant::Plant;
use crate::table::scheme::{GimbalAxis, ResolvedStep};
use crate::table::{Cursor, GimbalAngles};

const MAGIC: &[u8; 8] = b"RINSPS02";

/// Why a state could not be restored.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StateError {
    /// Not a plant state, or from another version.
    #[error("not a rins plant state (bad header)")]
    BadHeader,
    /// The state belongs to a plant with another configuration.
    #[error(
        "the state was saved from a plant with another configuration (fingerprint {saved:#018x}, this plant {current:#018x})"
    )]
    ConfigMismatch {
        /// Fingerprint in the state.
        saved: u64,
        /// Fingerprint of the configuration given.
        current: u64,
    },
    /// Truncated or trailing bytes.
    #[error("plant state has {got} bytes, expected {expected}")]
    Length {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
    /// The configuration itself is invalid.
    #[error("invalid configuration: {0}")]
    Config(String),
}

/// FNV-1a over the configuration's JSON form: equal configurations, equal fingerprints.
pub fn fingerprint(cfg: &PlantConfig) -> u64 {
    let text = serde_json::to_string(cfg).expect("PlantConfig serialises");
    text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Appends fields to a byte buffer.
#[derive(Default)]
pub(crate) struct Writer(pub Vec<u8>);

impl Writer {
    pub fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    pub fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    pub fn v3(&mut self, v: &Vector3<f64>) {
        v.iter().for_each(|x| self.f64(*x));
    }
    pub fn u128(&mut self, v: u128) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
}

/// Reads fields back in the same order.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], StateError> {
        let end = self.pos + N;
        let s = self.bytes.get(self.pos..end).ok_or(StateError::Length {
            got: self.bytes.len(),
            expected: end,
        })?;
        self.pos = end;
        Ok(s.try_into().expect("length checked"))
    }
    pub fn u64(&mut self) -> Result<u64, StateError> {
        Ok(u64::from_le_bytes(self.take::<8>()?))
    }
    pub fn f64(&mut self) -> Result<f64, StateError> {
        Ok(f64::from_le_bytes(self.take::<8>()?))
    }
    pub fn v3(&mut self) -> Result<Vector3<f64>, StateError> {
        Ok(Vector3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    pub fn u128(&mut self) -> Result<u128, StateError> {
        Ok(u128::from_le_bytes(self.take::<16>()?))
    }
}

impl Plant {
    /// The plant's evolving state as bytes (see the module notes for the layout).
    pub fn serialize_state(&self) -> Vec<u8> {
        let mut w = Writer(MAGIC.to_vec());
        w.u64(fingerprint(self.config()));
        self.write_state(&mut w);
        w.0
    }

    /// A plant built from `cfg` and resumed from `bytes` (from [`Plant::serialize_state`] of a
    /// plant with the same configuration): it continues bit-identically.
    pub fn from_serialized_state(cfg: &PlantConfig, bytes: &[u8]) -> Result<Plant, StateError> {
        if bytes.len() < 16 || &bytes[..8] != MAGIC {
            return Err(StateError::BadHeader);
        }
        let mut r = Reader { bytes, pos: 8 };
        let saved = r.u64()?;
        let current = fingerprint(cfg);
        if saved != current {
            return Err(StateError::ConfigMismatch { saved, current });
        }
        let mut plant = Plant::new(cfg).map_err(|e| {
            StateError::Config(
                e.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join("; "),
            )
        })?;
        plant.read_state(&mut r)?;
        if r.pos != bytes.len() {
            return Err(StateError::Length {
                got: bytes.len(),
                expected: r.pos,
            });
        }
        Ok(plant)
    }
}

impl Plant {
    /// Writes every evolving field (caches excluded) for [`crate::state`].
    pub(crate) fn write_state(&self, w: &mut Writer) {
        w.u64(self.tick);
        w.u64(self.samples);
        w.u64(self.slow_countdown);
        w.u64(self.chamber_override_c.is_some() as u64);
        w.f64(self.chamber_override_c.unwrap_or(0.0));
        let t = self.thermal.temperatures();
        t.nodes_c.iter().for_each(|x| w.f64(*x));
        w.f64(t.chamber_c);
        w.v3(&self.noise.gm_bias_rps);
        w.v3(&self.noise.rrw_bias_rps);
        for s in [
            &self.noise.arw,
            &self.noise.gm,
            &self.noise.rrw,
            &self.noise.vrw,
        ] {
            w.u128(s.word_pos());
        }
        w.v3(&self.gyro_quant.residual);
        w.v3(&self.accel_quant.residual);
        let tr = &self.truth;
        w.v3(&tr.dtheta_true_rad);
        w.v3(&tr.dv_true_mps);
        tr.temps.nodes_c.iter().for_each(|x| w.f64(*x));
        w.f64(tr.temps.chamber_c);
        tr.gyro_terms_rad.iter().for_each(|v| w.v3(v));
        tr.accel_terms_mps.iter().for_each(|v| w.v3(v));
        w.f64(tr.position_weight);
        w.u64(self.command.is_some() as u64);
        if let Some(c) = &self.command {
            w.u64(c.start_tick);
            w.f64(c.initial.outer_rad);
            w.f64(c.initial.inner_rad);
            w.u64(c.repeat as u64);
            w.u64(c.steps.len() as u64);
            for s in &c.steps {
                w.u64(matches!(s.axis, GimbalAxis::Inner) as u64);
                w.f64(s.angle_rad);
                w.f64(s.rate_rps);
                w.f64(s.dwell_s);
            }
        }
        w.u64(self.noise_seed);
        self.temp_readings_c.iter().for_each(|x| w.f64(*x));
        w.u128(self.temp_sensors.stream.word_pos());
        self.write_carrier_state(w);
    }

    /// Reads what [`Plant::write_state`] wrote into a freshly built plant of the same
    /// configuration, then rebuilds the derived quantities.
    pub(crate) fn read_state(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        self.tick = r.u64()?;
        self.samples = r.u64()?;
        self.slow_countdown = r.u64()?;
        let has_override = r.u64()? != 0;
        let ov = r.f64()?;
        self.chamber_override_c = has_override.then_some(ov);
        let mut nodes = [0.0; 6];
        for n in nodes.iter_mut() {
            *n = r.f64()?;
        }
        let chamber = r.f64()?;
        self.thermal.set_state(nodes, chamber);
        self.noise.gm_bias_rps = r.v3()?;
        self.noise.rrw_bias_rps = r.v3()?;
        let mut word_pos = [0u128; 4];
        for w in word_pos.iter_mut() {
            *w = r.u128()?;
        }
        self.gyro_quant.residual = r.v3()?;
        self.accel_quant.residual = r.v3()?;
        self.truth.dtheta_true_rad = r.v3()?;
        self.truth.dv_true_mps = r.v3()?;
        for n in self.truth.temps.nodes_c.iter_mut() {
            *n = r.f64()?;
        }
        self.truth.temps.chamber_c = r.f64()?;
        for v in self.truth.gyro_terms_rad.iter_mut() {
            *v = r.v3()?;
        }
        for v in self.truth.accel_terms_mps.iter_mut() {
            *v = r.v3()?;
        }
        self.truth.position_weight = r.f64()?;
        if r.u64()? != 0 {
            let start_tick = r.u64()?;
            let initial = GimbalAngles::new(r.f64()?, r.f64()?);
            let repeat = r.u64()? != 0;
            let n = r.u64()?;
            let mut steps = Vec::new();
            for _ in 0..n {
                let axis = if r.u64()? != 0 {
                    GimbalAxis::Inner
                } else {
                    GimbalAxis::Outer
                };
                steps.push(ResolvedStep {
                    axis,
                    angle_rad: r.f64()?,
                    rate_rps: r.f64()?,
                    dwell_s: r.f64()?,
                });
            }
            self.install_command(ActiveCommand {
                start_tick,
                initial,
                steps,
                repeat,
            });
        }
        let noise_seed = r.u64()?;
        if noise_seed != self.noise_seed {
            self.noise.reseed(noise_seed);
            self.temp_sensors.reseed(noise_seed);
            self.noise_seed = noise_seed;
        }
        for x in self.temp_readings_c.iter_mut() {
            *x = r.f64()?;
        }
        let temp_word_pos = r.u128()?;
        self.temp_sensors.stream.set_word_pos(temp_word_pos);
        for (s, w) in [
            &mut self.noise.arw,
            &mut self.noise.gm,
            &mut self.noise.rrw,
            &mut self.noise.vrw,
        ]
        .into_iter()
        .zip(word_pos)
        {
            s.set_word_pos(w);
        }
        // Derived: table state at the current tick, temperature-dependent rates; caches reset.
        let t = self.time_s();
        self.gimbal_now = self.schedule.eval(t);
        self.truth.gimbal = self.gimbal_now;
        self.hold_until_tick = 0;
        self.dwell_cache = None;
        self.cursor = Cursor::default();
        let temps = self.thermal.temperatures();
        self.gyro_thermal = self
            .gyro
            .thermal_rates(&temps.gyro_c(), &temps.gyro_gradient_k());
        self.accel_thermal_mps2 = self.accel.thermal_bias_mps2(temps.accel_c());
        self.read_carrier_state(r)
    }
}
