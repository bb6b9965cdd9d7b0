//! The plant: advances the rotating IMU by whole output intervals and reports the increments an
//! RLG IMU would output, with the truth and every effect's contribution beside them.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::config::{ConfigError, PlantConfig};
use crate::earth::Site;
use crate::effects::accel::ACCEL_TERMS;
use crate::effects::gyro::GYRO_TERMS;
use crate::effects::noise::NoiseState;
use crate::effects::quantize::Quantizer;
use crate::effects::{AccelModel, GyroModel, TermContext};
use crate::table::gimbal::{rot_x, rot_y, rot_z};
use crate::table::{GimbalState, Schedule, body_to_nav};
use crate::thermal::{Temperatures, ThermalNetwork};
use crate::units::{ARCSEC, DEG};

/// One IMU output: increments over the interval ending at `t_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuSample {
    /// Output sample number; sample k covers [k·Δt, (k+1)·Δt].
    pub index: u64,
    /// End of the interval, s.
    pub t_s: f64,
    /// Angular increment Δθ, rad.
    pub dtheta_rad: Vector3<f64>,
    /// Velocity increment Δv, m/s.
    pub dv_mps: Vector3<f64>,
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
}

/// The rotating IMU.
#[derive(Clone, Debug)]
pub struct Plant {
    cfg: PlantConfig,
    site: Site,
    c_vn: Matrix3<f64>,
    f_n: Vector3<f64>,
    schedule: Schedule,
    thermal: ThermalNetwork,
    gyro: GyroModel,
    accel: AccelModel,
    noise: NoiseState,
    gyro_quant: Quantizer,
    accel_quant: Quantizer,
    internal_rate_hz: f64,
    dt_s: f64,
    h_s: f64,
    slow_every: u64,
    /// Internal ticks since start (substeps × output samples).
    tick: u64,
    chamber_override_c: Option<f64>,
    gimbal_now: GimbalState,
    mid_cache: (f64, f64, Matrix3<f64>),
    truth: Truth,
}

impl Plant {
    /// Builds the plant; every parameter is range-checked first.
    pub fn new(cfg: &PlantConfig) -> Result<Self, Vec<ConfigError>> {
        cfg.validate()?;
        let site = Site::new(&cfg.site, &cfg.earth);
        let v = &cfg.vehicle;
        let c_vn = rot_z(v.azimuth_deg * DEG) * rot_x(v.pitch_deg * DEG) * rot_y(v.roll_deg * DEG);
        let schedule = Schedule::new(&cfg.scheme.resolve());
        let g0 = schedule.eval(0.0);
        let c_bn = body_to_nav(&c_vn, g0.angles);
        let up_b = c_bn.transpose() * Vector3::z();
        let chamber0 = cfg.thermal.chamber.temp_at(0.0);
        let thermal = ThermalNetwork::new(&cfg.thermal, chamber0, &up_b);
        let s = &cfg.sensor;
        let quant = |on: bool, p: [f64; 3], unit: f64| Quantizer::new(if on { Vector3::from(p) * unit } else { Vector3::zeros() });
        let dt = 1.0 / cfg.rate_hz;
        let temps = thermal.temperatures();
        Ok(Self {
            site,
            c_vn,
            f_n: Vector3::new(0.0, 0.0, site.gravity_mps2),
            schedule,
            thermal,
            gyro: GyroModel::new(&s.gyro),
            accel: AccelModel::new(&s.accel),
            noise: NoiseState::new(&s.gyro, &s.accel, cfg.seed),
            gyro_quant: quant(s.gyro.quantization.enabled, s.gyro.quantization.pulse, ARCSEC),
            accel_quant: quant(s.accel.quantization.enabled, s.accel.quantization.pulse, 1.0),
            internal_rate_hz: cfg.rate_hz * cfg.substeps as f64,
            dt_s: dt,
            h_s: dt / cfg.substeps as f64,
            slow_every: (cfg.thermal.step_s * cfg.rate_hz).round() as u64,
            tick: 0,
            chamber_override_c: None,
            gimbal_now: g0,
            mid_cache: (f64::NAN, f64::NAN, Matrix3::identity()),
            truth: Truth {
                gimbal: g0,
                dtheta_true_rad: Vector3::zeros(),
                dv_true_mps: Vector3::zeros(),
                temps,
                gyro_terms_rad: [Vector3::zeros(); GYRO_TERMS],
                accel_terms_mps: [Vector3::zeros(); ACCEL_TERMS],
                position_weight: 0.0,
            },
            cfg: cfg.clone(),
        })
    }

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
        self.tick / self.cfg.substeps as u64
    }

    /// Simulated time, s (from the integer tick counter).
    pub fn time_s(&self) -> f64 {
        self.tick as f64 / self.internal_rate_hz
    }

    /// Truth over the last interval.
    pub fn truth(&self) -> &Truth {
        &self.truth
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

    /// Vehicle mount attitude C_v^n.
    pub fn vehicle_to_nav(&self) -> &Matrix3<f64> {
        &self.c_vn
    }

    /// True IMU attitude C_b^n now.
    pub fn attitude_c_bn(&self) -> Matrix3<f64> {
        body_to_nav(&self.c_vn, self.gimbal_now.angles)
    }

    /// True IMU attitude now as the quaternion q_b^n.
    pub fn attitude_q_bn(&self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_matrix(&self.attitude_c_bn())
    }

    /// Overrides the chamber temperature (an FMU input); `None` returns to the scenario profile.
    pub fn set_chamber_temp_c(&mut self, temp_c: Option<f64>) {
        self.chamber_override_c = temp_c;
    }

    fn chamber_c(&self, t_s: f64) -> f64 {
        self.chamber_override_c.unwrap_or_else(|| self.cfg.thermal.chamber.temp_at(t_s))
    }

    fn c_bn_at(&mut self, g: &GimbalState) -> Matrix3<f64> {
        // Dwells reuse the last attitude: no trigonometry while the table is still.
        let (o, i, c) = self.mid_cache;
        if o == g.angles.outer_rad && i == g.angles.inner_rad {
            return c;
        }
        let c = body_to_nav(&self.c_vn, g.angles);
        self.mid_cache = (g.angles.outer_rad, g.angles.inner_rad, c);
        c
    }

    /// Advances one output interval: kinematics → thermal → sensor effects → noise → quantisation.
    pub fn step(&mut self) -> ImuSample {
        let index = self.samples_done();
        if index > 0 && index % self.slow_every == 0 {
            let h = self.cfg.thermal.step_s;
            let t = self.time_s();
            let up_b = self.attitude_c_bn().transpose() * Vector3::z();
            let ch = self.chamber_c(t);
            self.thermal.step(h, ch, &up_b);
            self.noise.step_slow(h);
        }
        let temps = self.thermal.temperatures();
        let (gyro_temp, gradient, accel_temp) = (temps.gyro_c(), temps.gyro_gradient_k(), temps.accel_c());

        let mut dtheta_true = Vector3::zeros();
        let mut dv_true = Vector3::zeros();
        let mut gyro_err = Vector3::zeros();
        let mut accel_err = Vector3::zeros();
        let mut gyro_terms = [Vector3::zeros(); GYRO_TERMS];
        let mut accel_terms = [Vector3::zeros(); ACCEL_TERMS];
        let mut gterm = [Vector3::zeros(); GYRO_TERMS];
        let mut aterm = [Vector3::zeros(); ACCEL_TERMS];
        let mut weight = 0.0;
        let h = self.h_s;
        for _ in 0..self.cfg.substeps {
            let g0 = self.gimbal_now;
            let g1 = self.schedule.eval((self.tick + 1) as f64 / self.internal_rate_hz);
            let gm = self.schedule.eval((self.tick as f64 + 0.5) / self.internal_rate_hz);
            let c_nb = self.c_bn_at(&gm).transpose();
            // Gimbal part from exact angle differences (one axis moves at a time); Earth rate
            // and specific force at the midpoint.
            let d_outer = g1.angles.outer_rad - g0.angles.outer_rad;
            let d_inner = g1.angles.inner_rad - g0.angles.inner_rad;
            let (si, ci) = gm.angles.inner_rad.sin_cos();
            let gimbal_inc = Vector3::new(d_inner, si * d_outer, ci * d_outer);
            let dtheta = gimbal_inc + c_nb * self.site.omega_ie_n * h;
            let up_b = c_nb.column(2).into_owned();
            let f_b = c_nb * self.f_n;
            let dv = f_b * h;
            let ctx = TermContext {
                dt_s: h,
                dtheta_rad: dtheta,
                dv_mps: dv,
                f_b_mps2: f_b,
                up_b,
                gyro_temp_c: gyro_temp,
                gyro_gradient_k: gradient,
                accel_temp_c: accel_temp,
            };
            gyro_err += self.gyro.increment_error(&ctx, &mut gterm);
            accel_err += self.accel.increment_error(&ctx, &mut aterm);
            for k in 0..GYRO_TERMS {
                gyro_terms[k] += gterm[k];
            }
            for k in 0..ACCEL_TERMS {
                accel_terms[k] += aterm[k];
            }
            weight += self.gyro.position_weight(&up_b) / self.cfg.substeps as f64;
            dtheta_true += dtheta;
            dv_true += dv;
            self.gimbal_now = g1;
            self.tick += 1;
        }

        let dt = self.dt_s;
        use crate::effects::{AccelTerm as A, GyroTerm as G};
        let arw = if self.noise.has_arw() { self.noise.arw_increment(dt) } else { Vector3::zeros() };
        let gm = self.noise.gm_bias_rps * dt;
        let rrw = self.noise.rrw_bias_rps * dt;
        let vrw = if self.noise.has_vrw() { self.noise.vrw_increment(dt) } else { Vector3::zeros() };
        gyro_terms[G::AngleRandomWalk as usize] = arw;
        gyro_terms[G::BiasInstability as usize] = gm;
        gyro_terms[G::RateRandomWalk as usize] = rrw;
        accel_terms[A::VelocityRandomWalk as usize] = vrw;

        let dtheta_analog = dtheta_true + gyro_err + arw + gm + rrw;
        let dv_analog = dv_true + accel_err + vrw;
        let dtheta_out = self.gyro_quant.apply(&dtheta_analog);
        let dv_out = self.accel_quant.apply(&dv_analog);
        gyro_terms[G::Quantization as usize] = dtheta_out - dtheta_analog;
        accel_terms[A::Quantization as usize] = dv_out - dv_analog;

        self.truth = Truth {
            gimbal: self.gimbal_now,
            dtheta_true_rad: dtheta_true,
            dv_true_mps: dv_true,
            temps,
            gyro_terms_rad: gyro_terms,
            accel_terms_mps: accel_terms,
            position_weight: weight,
        };
        ImuSample { index, t_s: self.time_s(), dtheta_rad: dtheta_out, dv_mps: dv_out }
    }
}
