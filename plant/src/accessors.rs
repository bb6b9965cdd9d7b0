//! Read-only views of a [`Plant`] and its small setters (configuration, site, truth, readings,
//! attitude, dwell cache, chamber override, noise reseed): kept apart from the step pipeline.

use nalgebra::{Matrix3, UnitQuaternion};

use crate::carrier::CarrierTruth;
use crate::config::PlantConfig;
use crate::earth::Site;
use crate::effects::{AccelModel, GyroModel};
use crate::plant::{Plant, Truth};
use crate::table::{Schedule, body_to_nav};
use crate::thermal::node;

impl Plant {
    /// The configuration the plant was built from.
    pub fn config(&self) -> &PlantConfig {
        &self.cfg
    }

    /// Earth quantities at the site.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// Output interval Δt, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Output samples produced so far.
    pub fn samples_done(&self) -> u64 {
        self.samples
    }

    /// Simulated time, s (from the integer tick counter).
    pub fn time_s(&self) -> f64 {
        self.tick as f64 / self.internal_rate_hz
    }

    /// Truth over the last interval. On a moving carrier the carrier's part is evaluated here,
    /// when asked for, not at every tick (it is a copy for that reason).
    pub fn truth(&self) -> Truth {
        Truth {
            carrier: self.carrier_truth(),
            ..self.truth
        }
    }

    /// The carrier's part of [`Plant::truth`] alone (the site and `[vehicle]` attitude when
    /// static), without copying the rest.
    pub fn carrier_truth(&self) -> CarrierTruth {
        match &self.carrier {
            Some(c) => c.state().truth(),
            None => self.truth.carrier,
        }
    }

    /// The temperature-sensor readings of the last sample (a measured output), °C.
    pub fn temp_readings_c(&self) -> [f64; node::COUNT] {
        self.temp_readings_c
    }

    /// The chamber temperature over the last interval (the test set-up's, not the unit's), °C.
    pub fn chamber_now_c(&self) -> f64 {
        self.truth.temps.chamber_c
    }

    /// The compiled table schedule.
    pub fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// The deterministic gyro model (coefficients and regressors for diagnosis).
    pub fn gyro_model(&self) -> &GyroModel {
        &self.gyro
    }

    /// The deterministic accelerometer model.
    pub fn accel_model(&self) -> &AccelModel {
        &self.accel
    }

    /// Vehicle mount attitude C_v^n now (on a moving carrier, C_c^n·C_v^c).
    pub fn vehicle_to_nav(&self) -> Matrix3<f64> {
        match &self.carrier {
            Some(c) => c.c_vn(),
            None => self.c_vn,
        }
    }

    /// True IMU attitude C_b^n now.
    pub fn attitude_c_bn(&self) -> Matrix3<f64> {
        let mut a = self.gimbal_now.angles;
        // With azimuth isolation the outer gimbal stands off the scheme by the loop's offset.
        if let Some(i) = self.carrier.as_ref().and_then(|c| c.isolation.as_ref()) {
            a.outer_rad += i.offset_rad(self.tick, self.cfg.substeps as u64);
        }
        body_to_nav(&self.vehicle_to_nav(), a)
    }

    /// True IMU attitude now as the quaternion q_b^n.
    pub fn attitude_q_bn(&self) -> UnitQuaternion<f64> {
        crate::attitude::quaternion_of(&self.attitude_c_bn())
    }

    /// Turns the dwell cache off or on. Output is bit-identical either way; only speed differs.
    pub fn set_dwell_cache(&mut self, on: bool) {
        self.use_dwell_cache = on;
        self.dwell_cache = None;
    }

    /// Overrides the chamber temperature (an FMU input); `None` returns to the scenario profile.
    /// A change acts from the next sample: it starts with a thermal update over the time since
    /// the last one (docs/fmu.md, "When an input acts").
    pub fn set_chamber_temp_c(&mut self, temp_c: Option<f64>) {
        self.chamber_changed |= temp_c != self.chamber_override_c;
        self.chamber_override_c = temp_c;
    }

    /// Restarts every noise stream from `seed` at the current tick, keeping the current
    /// bias-instability and rate-random-walk values. A Monte Carlo can warm the plant up once,
    /// save the state, and give each run its own noise from there.
    pub fn reseed_noise(&mut self, seed: u64) {
        self.noise.reseed(seed);
        self.temp_sensors.reseed(seed);
        self.noise_seed = seed;
    }

    /// Seed of the noise streams in use.
    pub fn noise_seed(&self) -> u64 {
        self.noise_seed
    }

    pub(crate) fn chamber_c(&self, t_s: f64) -> f64 {
        self.chamber_override_c
            .unwrap_or_else(|| self.cfg.thermal.chamber.temp_at(t_s))
    }
}
