//! The readout stage: what the unit measures of the deterministic interval. Gyro and
//! accelerometer noise (angle and velocity random walk, bias instability, rate random walk),
//! output quantisation with its carried residual, the gimbal encoders and the temperature
//! sensors. Every seed-dependent quantity of the plant is here: the physics before it is the
//! same for every seed.

use nalgebra::Vector3;

use super::interval::Interval;
use crate::config::PlantConfig;
use crate::effects::encoder::Encoders;
use crate::effects::noise::NoiseState;
use crate::effects::quantize::Quantizer;
use crate::effects::temp_sensor::TempSensors;
use crate::effects::{AccelTerm, GyroTerm};
use crate::output::{ImuSample, Truth};
use crate::state::{Reader, StateError, Writer};
use crate::table::GimbalAngles;
use crate::thermal::node;
use crate::units::ARCSEC;

/// The measured increments of one interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Measured {
    /// Angular increment output, rad.
    pub dtheta_rad: Vector3<f64>,
    /// Velocity increment output, m/s.
    pub dv_mps: Vector3<f64>,
}

impl Measured {
    /// No increment yet: what the unit reports before its first sample.
    pub(crate) const NONE: Measured = Measured {
        dtheta_rad: Vector3::new(0.0, 0.0, 0.0),
        dv_mps: Vector3::new(0.0, 0.0, 0.0),
    };
}

/// The readout's contributions to the last interval's error, per term (the truth's noise and
/// quantisation entries).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ReadoutTerms {
    arw_rad: Vector3<f64>,
    bias_instability_rad: Vector3<f64>,
    rrw_rad: Vector3<f64>,
    gyro_quantization_rad: Vector3<f64>,
    vrw_mps: Vector3<f64>,
    accel_quantization_mps: Vector3<f64>,
}

impl ReadoutTerms {
    /// Writes the terms into `truth`'s per-term arrays.
    pub(crate) fn write_into(&self, truth: &mut Truth) {
        let (g, a) = (&mut truth.gyro_terms_rad, &mut truth.accel_terms_mps);
        g[GyroTerm::AngleRandomWalk as usize] = self.arw_rad;
        g[GyroTerm::BiasInstability as usize] = self.bias_instability_rad;
        g[GyroTerm::RateRandomWalk as usize] = self.rrw_rad;
        g[GyroTerm::Quantization as usize] = self.gyro_quantization_rad;
        a[AccelTerm::VelocityRandomWalk as usize] = self.vrw_mps;
        a[AccelTerm::Quantization as usize] = self.accel_quantization_mps;
    }

    /// The terms as `truth` holds them (state restore).
    pub(crate) fn read_from(truth: &Truth) -> Self {
        let (g, a) = (&truth.gyro_terms_rad, &truth.accel_terms_mps);
        Self {
            arw_rad: g[GyroTerm::AngleRandomWalk as usize],
            bias_instability_rad: g[GyroTerm::BiasInstability as usize],
            rrw_rad: g[GyroTerm::RateRandomWalk as usize],
            gyro_quantization_rad: g[GyroTerm::Quantization as usize],
            vrw_mps: a[AccelTerm::VelocityRandomWalk as usize],
            accel_quantization_mps: a[AccelTerm::Quantization as usize],
        }
    }
}

/// Noise, quantisation, encoders and temperature sensors.
#[derive(Clone, Debug)]
pub(crate) struct Readout {
    noise: NoiseState,
    gyro_quant: Quantizer,
    accel_quant: Quantizer,
    encoders: Encoders,
    temp_sensors: TempSensors,
    /// The temperature sensors' last readings (taken at each thermal update, held between), °C.
    temp_readings_c: [f64; node::COUNT],
    /// Seed of the noise streams (the configured seed until [`Readout::reseed`]).
    noise_seed: u64,
    /// The last interval's noise and quantisation, per term.
    terms: ReadoutTerms,
    dt_s: f64,
    sqrt_dt: f64,
}

impl Readout {
    /// The readout of `cfg`, its first temperature reading taken of `nodes_c`.
    pub(crate) fn new(cfg: &PlantConfig, nodes_c: &[f64; node::COUNT]) -> Self {
        let s = &cfg.sensor;
        let quant = |on: bool, p: [f64; 3], unit: f64| {
            Quantizer::new(if on {
                Vector3::from(p) * unit
            } else {
                Vector3::zeros()
            })
        };
        let mut temp_sensors = TempSensors::new(&s.temperature, cfg.seed);
        let temp_readings_c = temp_sensors.read(nodes_c);
        let dt_s = 1.0 / cfg.rate_hz;
        Self {
            noise: NoiseState::new(&s.gyro, &s.accel, cfg.seed),
            gyro_quant: quant(
                s.gyro.quantization.enabled,
                s.gyro.quantization.pulse,
                ARCSEC,
            ),
            accel_quant: quant(
                s.accel.quantization.enabled,
                s.accel.quantization.pulse,
                1.0,
            ),
            encoders: Encoders::new(&s.encoder),
            temp_sensors,
            temp_readings_c,
            noise_seed: cfg.seed,
            terms: ReadoutTerms::default(),
            dt_s,
            sqrt_dt: dt_s.sqrt(),
        }
    }

    /// The temperature sensors' last readings, °C.
    pub(crate) fn temp_readings_c(&self) -> [f64; node::COUNT] {
        self.temp_readings_c
    }

    /// Seed of the noise streams in use.
    pub(crate) fn noise_seed(&self) -> u64 {
        self.noise_seed
    }

    /// Restarts every noise stream from `seed`, keeping the slow processes' values.
    pub(crate) fn reseed(&mut self, seed: u64) {
        self.noise.reseed(seed);
        self.temp_sensors.reseed(seed);
        self.noise_seed = seed;
    }

    /// A thermal step of `h_s` ended: the slow noise processes advance and the temperature
    /// sensors read the true node temperatures `nodes_c`.
    pub(crate) fn on_thermal_step(&mut self, h_s: f64, nodes_c: &[f64; node::COUNT]) {
        self.noise.step_slow(h_s);
        self.temp_readings_c = self.temp_sensors.read(nodes_c);
    }

    /// The encoders' reading of the true angles.
    pub(crate) fn encoders(&self, angles: GimbalAngles) -> GimbalAngles {
        self.encoders.read(angles)
    }

    /// The sample the unit outputs: the increments `m`, the encoders' reading of the true
    /// angles `angles` and the temperature sensors' last readings, numbered `index` and ending
    /// at `t_s`. Every [`ImuSample`] the plant gives is made here (a measured output the plant
    /// adds is one more field set here), so a plant's, a lane's and an isolated table's samples
    /// cannot differ in how they are put together.
    #[inline(always)]
    pub(crate) fn sample(
        &self,
        index: u64,
        t_s: f64,
        m: &Measured,
        angles: GimbalAngles,
    ) -> ImuSample {
        ImuSample {
            index,
            t_s,
            dtheta_rad: m.dtheta_rad,
            dv_mps: m.dv_mps,
            encoder: self.encoders(angles),
            temps_c: self.temp_readings_c(),
        }
    }

    /// The last interval's noise and quantisation, per term.
    pub(crate) fn terms(&self) -> &ReadoutTerms {
        &self.terms
    }

    /// Sets the per-term contributions (state restore).
    pub(crate) fn set_terms(&mut self, terms: ReadoutTerms) {
        self.terms = terms;
    }

    /// Adds the noise to the deterministic interval and quantises it; each term's contribution
    /// is kept ([`Readout::terms`]).
    #[inline(always)]
    pub(crate) fn measure(&mut self, x: &Interval) -> Measured {
        let dt = self.dt_s;
        let arw = if self.noise.has_arw() {
            self.noise.arw_increment(self.sqrt_dt)
        } else {
            Vector3::zeros()
        };
        let gm = self.noise.gm_bias_rps * dt;
        let rrw = self.noise.rrw_bias_rps * dt;
        let vrw = if self.noise.has_vrw() {
            self.noise.vrw_increment(self.sqrt_dt)
        } else {
            Vector3::zeros()
        };
        let dtheta_analog = x.dtheta_true_rad + x.gyro_err_rad + arw + gm + rrw;
        let dv_analog = x.dv_true_mps + x.accel_err_mps + vrw;
        let dtheta_rad = self.gyro_quant.apply(&dtheta_analog);
        let dv_mps = self.accel_quant.apply(&dv_analog);
        self.terms = ReadoutTerms {
            arw_rad: arw,
            bias_instability_rad: gm,
            rrw_rad: rrw,
            gyro_quantization_rad: dtheta_rad - dtheta_analog,
            vrw_mps: vrw,
            accel_quantization_mps: dv_mps - dv_analog,
        };
        Measured { dtheta_rad, dv_mps }
    }

    /// Writes the seed, the slow processes, the streams' positions, the quantisers' residuals
    /// and the last temperature readings.
    pub(crate) fn write(&self, w: &mut Writer) {
        w.u64(self.noise_seed);
        w.v3(&self.noise.gm_bias_rps);
        w.v3(&self.noise.rrw_bias_rps);
        for s in [
            &self.noise.arw,
            &self.noise.gm,
            &self.noise.rrw,
            &self.noise.vrw,
            &self.temp_sensors.stream,
        ] {
            w.u128(s.word_pos());
        }
        w.v3(&self.gyro_quant.residual);
        w.v3(&self.accel_quant.residual);
        self.temp_readings_c.iter().for_each(|x| w.f64(*x));
    }

    /// Reads what [`Readout::write`] wrote.
    pub(crate) fn read(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        let seed = r.u64()?;
        if seed != self.noise_seed {
            self.reseed(seed);
        }
        self.noise.gm_bias_rps = r.v3()?;
        self.noise.rrw_bias_rps = r.v3()?;
        for s in [
            &mut self.noise.arw,
            &mut self.noise.gm,
            &mut self.noise.rrw,
            &mut self.noise.vrw,
            &mut self.temp_sensors.stream,
        ] {
            s.set_word_pos(r.u128()?);
        }
        self.gyro_quant.residual = r.v3()?;
        self.accel_quant.residual = r.v3()?;
        for x in self.temp_readings_c.iter_mut() {
            *x = r.f64()?;
        }
        Ok(())
    }
}
