//! Stochastic terms. Each draws from its own named ChaCha8 stream of the run seed, so switching
//! one term on or off leaves every other term's realisation unchanged (common random numbers).

use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use super::accel::AccelSpec;
use super::gyro::GyroSpec;
use crate::units::{DPH, DPH_PER_SQRTH, DPSH, UG};

/// Stream numbers of the named random sources. Stable across versions: changing one changes
/// every recorded realisation.
pub mod stream {
    /// Gyro angle random walk.
    pub const GYRO_ARW: u64 = 1;
    /// Gyro bias instability.
    pub const GYRO_BIAS_INSTABILITY: u64 = 2;
    /// Gyro rate random walk.
    pub const GYRO_RRW: u64 = 3;
    /// Accelerometer velocity random walk.
    pub const ACCEL_VRW: u64 = 4;
    /// Temperature-sensor reading noise.
    pub const TEMP_SENSOR: u64 = 5;
}

/// A seeded normal source on one named stream.
#[derive(Clone, Debug)]
pub struct NormalStream {
    rng: ChaCha8Rng,
}

impl NormalStream {
    /// Stream `stream` of `seed`.
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(stream);
        Self { rng }
    }

    /// Three independent standard normal draws.
    #[inline]
    pub fn vec3(&mut self) -> Vector3<f64> {
        let mut n = || -> f64 { StandardNormal.sample(&mut self.rng) };
        Vector3::new(n(), n(), n())
    }

    /// Position in the stream (word offset), for state save/restore.
    pub fn word_pos(&self) -> u128 {
        self.rng.get_word_pos()
    }

    /// Seeks the stream to `pos` (from [`NormalStream::word_pos`]).
    pub fn set_word_pos(&mut self, pos: u128) {
        self.rng.set_word_pos(pos);
    }
}

/// The stochastic state of the sensors.
#[derive(Clone, Debug)]
pub struct NoiseState {
    arw_sigma: Vector3<f64>,
    vrw_sigma: Vector3<f64>,
    arw_on: bool,
    vrw_on: bool,
    gm_sigma: Vector3<f64>,
    gm_tau: Vector3<f64>,
    rrw_sigma: Vector3<f64>,
    /// Current Gauss–Markov bias, rad/s.
    pub gm_bias_rps: Vector3<f64>,
    /// Current rate-random-walk bias, rad/s.
    pub rrw_bias_rps: Vector3<f64>,
    /// Named sources.
    pub arw: NormalStream,
    /// Bias-instability source.
    pub gm: NormalStream,
    /// Rate-random-walk source.
    pub rrw: NormalStream,
    /// Velocity-random-walk source.
    pub vrw: NormalStream,
}

impl NoiseState {
    /// Restarts the four named streams from `seed` (stream positions 0); process states kept.
    pub fn reseed(&mut self, seed: u64) {
        self.arw = NormalStream::new(seed, stream::GYRO_ARW);
        self.gm = NormalStream::new(seed, stream::GYRO_BIAS_INSTABILITY);
        self.rrw = NormalStream::new(seed, stream::GYRO_RRW);
        self.vrw = NormalStream::new(seed, stream::ACCEL_VRW);
    }

    /// Builds the noise state. The Gauss–Markov bias starts from its stationary distribution.
    pub fn new(gyro: &GyroSpec, accel: &AccelSpec, seed: u64) -> Self {
        let on = |flag: bool, v: [f64; 3], unit: f64| {
            if flag {
                Vector3::from(v) * unit
            } else {
                Vector3::zeros()
            }
        };
        let gm_sigma = on(
            gyro.bias_instability.enabled,
            gyro.bias_instability.sigma_dph,
            DPH,
        );
        let mut gm = NormalStream::new(seed, stream::GYRO_BIAS_INSTABILITY);
        let gm0 = if gyro.bias_instability.enabled {
            gm_sigma.component_mul(&gm.vec3())
        } else {
            Vector3::zeros()
        };
        let arw_sigma = on(
            gyro.angle_random_walk.enabled,
            gyro.angle_random_walk.dpsh,
            DPSH,
        );
        let vrw_sigma = on(
            accel.velocity_random_walk.enabled,
            accel.velocity_random_walk.ug_per_sqrthz,
            UG,
        );
        Self {
            arw_on: arw_sigma != Vector3::zeros(),
            vrw_on: vrw_sigma != Vector3::zeros(),
            arw_sigma,
            vrw_sigma,
            gm_sigma,
            gm_tau: Vector3::from(gyro.bias_instability.tau_s),
            rrw_sigma: on(
                gyro.rate_random_walk.enabled,
                gyro.rate_random_walk.dph_per_sqrth,
                DPH_PER_SQRTH,
            ),
            gm_bias_rps: gm0,
            rrw_bias_rps: Vector3::zeros(),
            arw: NormalStream::new(seed, stream::GYRO_ARW),
            gm,
            rrw: NormalStream::new(seed, stream::GYRO_RRW),
            vrw: NormalStream::new(seed, stream::ACCEL_VRW),
        }
    }

    /// Whether the angle random walk is on (skip drawing when off).
    pub fn has_arw(&self) -> bool {
        self.arw_on
    }

    /// Whether the velocity random walk is on.
    pub fn has_vrw(&self) -> bool {
        self.vrw_on
    }

    /// Angle-random-walk increment over an interval of √dt = `sqrt_dt`: N·√dt·w, rad.
    // Always inlined: as a call its Vector3 came back through the stack in three stores and was
    // read as a pair, a store-forwarding stall per sample (10 % of the batch's readout time).
    #[inline(always)]
    pub fn arw_increment(&mut self, sqrt_dt: f64) -> Vector3<f64> {
        self.arw_sigma.component_mul(&self.arw.vec3()) * sqrt_dt
    }

    /// Velocity-random-walk increment over an interval of √dt = `sqrt_dt`, m/s (inlined as
    /// [`NoiseState::arw_increment`] is).
    #[inline(always)]
    pub fn vrw_increment(&mut self, sqrt_dt: f64) -> Vector3<f64> {
        self.vrw_sigma.component_mul(&self.vrw.vec3()) * sqrt_dt
    }

    /// Advances the slow processes by `h_s`: exact discrete Gauss–Markov,
    /// b⁺ = e^(−h/τ)·b + σ·√(1 − e^(−2h/τ))·w, and random walk b⁺ = b + K·√h·w.
    pub fn step_slow(&mut self, h_s: f64) {
        if self.gm_sigma != Vector3::zeros() {
            let w = self.gm.vec3();
            for i in 0..3 {
                let phi = (-h_s / self.gm_tau[i]).exp();
                self.gm_bias_rps[i] =
                    phi * self.gm_bias_rps[i] + self.gm_sigma[i] * (1.0 - phi * phi).sqrt() * w[i];
            }
        }
        if self.rrw_sigma != Vector3::zeros() {
            self.rrw_bias_rps += self.rrw_sigma.component_mul(&self.rrw.vec3()) * h_s.sqrt();
        }
    }
}
