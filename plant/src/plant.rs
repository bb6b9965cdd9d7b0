//! The plant: advances the rotating IMU by whole output intervals and reports the increments an
//! RLG IMU would output, with the truth and every effect's contribution beside them.

use nalgebra::{Matrix3, Vector3};

use crate::carrier::run::CarrierRun;
use crate::carrier::{Carrier, CarrierState, CarrierTruth};
use crate::command::ActiveCommand;
use crate::config::{ConfigError, PlantConfig};
use crate::earth::Site;
use crate::effects::accel::ACCEL_TERMS;
use crate::effects::custom::Declared;
use crate::effects::encoder::Encoders;
use crate::effects::gyro::{GYRO_TERMS, GyroThermalRates};
use crate::effects::noise::NoiseState;
use crate::effects::quantize::Quantizer;
use crate::effects::temp_sensor::TempSensors;
use crate::effects::{AccelModel, GyroModel, TermContext};
use crate::kinematics::table_increments;
use crate::table::gimbal::gimbal_rotation;
use crate::table::{Cursor, GimbalAngles, GimbalState, Schedule, body_to_nav};
use crate::thermal::{Temperatures, ThermalNetwork, node};
use crate::units::ARCSEC;

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
    /// [`Plant::truth`] fills it in on a moving carrier.
    pub carrier: CarrierTruth,
}

/// Last internal tick at or before `hold_s` (a dwell end); whether the boundary tick itself is
/// held or evaluated does not matter, the table is still there either way.
fn hold_tick(hold_s: f64, internal_rate_hz: f64) -> u64 {
    let t = (hold_s * internal_rate_hz).floor();
    if t.is_finite() && t >= 0.0 {
        t as u64
    } else if t > 0.0 {
        u64::MAX
    } else {
        0
    }
}

/// Deterministic results of one output interval while the table dwells. Between thermal updates
/// every input of the deterministic path is constant during a dwell, so later intervals of the
/// same dwell reuse these bit for bit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DwellCache {
    dtheta_true: Vector3<f64>,
    dv_true: Vector3<f64>,
    gyro_err: Vector3<f64>,
    accel_err: Vector3<f64>,
    weight: f64,
}

/// Attitude at the last evaluated midpoint, reused while the gimbal angles do not change; the
/// sine and cosine of each angle are cached separately because only one gimbal moves at a time.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MidCache {
    outer_rad: f64,
    inner_rad: f64,
    c_nb: Matrix3<f64>,
    sin_outer: f64,
    cos_outer: f64,
    sin_inner: f64,
    cos_inner: f64,
}

/// The rotating IMU.
#[derive(Clone, Debug)]
pub struct Plant {
    pub(crate) cfg: PlantConfig,
    pub(crate) site: Site,
    /// C_v^n of the static carrier (a moving carrier's is [`Plant::vehicle_to_nav`]).
    pub(crate) c_vn: Matrix3<f64>,
    pub(crate) f_n: Vector3<f64>,
    pub(crate) schedule: Schedule,
    pub(crate) thermal: ThermalNetwork,
    pub(crate) gyro: GyroModel,
    pub(crate) accel: AccelModel,
    pub(crate) noise: NoiseState,
    pub(crate) gyro_quant: Quantizer,
    pub(crate) accel_quant: Quantizer,
    pub(crate) internal_rate_hz: f64,
    pub(crate) dt_s: f64,
    pub(crate) sqrt_dt: f64,
    pub(crate) h_s: f64,
    pub(crate) slow_every: u64,
    /// Internal ticks since start (substeps × output samples).
    pub(crate) tick: u64,
    /// Output samples since start.
    pub(crate) samples: u64,
    /// Output samples left before the next thermal / slow-noise update.
    pub(crate) slow_countdown: u64,
    pub(crate) chamber_override_c: Option<f64>,
    /// The chamber override changed since the last sample: the next sample starts with a
    /// thermal update (a chamber input acts at the step it is set for, not at the next grid
    /// update). Transient: set by `set_chamber_temp_c`, consumed by the next `step`.
    pub(crate) chamber_changed: bool,
    /// Temperature-dependent error rates at the current node temperatures.
    pub(crate) gyro_thermal: GyroThermalRates,
    pub(crate) accel_thermal_mps2: Vector3<f64>,
    pub(crate) gimbal_now: GimbalState,
    /// C_v^n is the identity (the usual level, azimuth-0 mount): skip one matrix product.
    pub(crate) vehicle_level: bool,
    /// The table holds `gimbal_now` up to this internal tick (end of the current dwell).
    pub(crate) hold_until_tick: u64,
    pub(crate) mid_cache: MidCache,
    /// Segment of the last schedule evaluation.
    pub(crate) cursor: Cursor,
    /// Reusable deterministic interval while dwelling; cleared on motion and thermal updates.
    pub(crate) dwell_cache: Option<DwellCache>,
    /// Disable the dwell cache (tests compare against the uncached path).
    pub(crate) use_dwell_cache: bool,
    /// Motion commanded by the navigation side, replacing the scheme from its start tick.
    pub(crate) command: Option<ActiveCommand>,
    /// Seed of the noise streams (the configured seed until [`Plant::reseed_noise`]).
    pub(crate) noise_seed: u64,
    pub(crate) truth: Truth,
    /// Gimbal angle encoders.
    pub(crate) encoders: Encoders,
    /// Temperature sensors (read at each thermal update, held in between).
    pub(crate) temp_sensors: TempSensors,
    /// The sensors' last readings, °C.
    pub(crate) temp_readings_c: [f64; node::COUNT],
    /// Declared effects (`[[sensor.*.custom]]`) and their slow signals.
    pub(crate) declared: Declared,
    /// The moving carrier; `None` for the static carrier (the original path).
    pub(crate) carrier: Option<Box<CarrierRun>>,
}

impl Plant {
    /// Builds the plant; every parameter is range-checked first.
    pub fn new(cfg: &PlantConfig) -> Result<Self, Vec<ConfigError>> {
        cfg.validate()?;
        let tick_s = 1.0 / (cfg.rate_hz * cfg.substeps as f64);
        let carrier = Carrier::new(&cfg.carrier, cfg.seed, tick_s).map_err(|e| {
            vec![ConfigError {
                path: "carrier.trajectory.file".into(),
                expected: "a readable, valid trajectory file (docs/carrier.md)".into(),
                got: e,
            }]
        })?;
        Ok(Self::build(cfg, carrier))
    }

    pub(crate) fn build(cfg: &PlantConfig, carrier: Option<Carrier>) -> Self {
        let site = Site::new(&cfg.site, &cfg.earth);
        let carrier = carrier.map(|c| CarrierRun::new(c, cfg));
        let c_vn = match &carrier {
            Some(r) => r.c_vn(),
            None => cfg.vehicle.c_vn(),
        };
        let carrier_truth = match &carrier {
            Some(r) => r.now.truth(),
            None => CarrierState::at_rest(site.lat_rad, site.lon_rad, site.height_m, c_vn).truth(),
        };
        let schedule = Schedule::new(&cfg.scheme.resolve());
        let g0 = schedule.eval(0.0);
        let c_bn = body_to_nav(&c_vn, g0.angles);
        let up_b = c_bn.transpose() * Vector3::z();
        let chamber0 = cfg.thermal.chamber.temp_at(0.0);
        let thermal = ThermalNetwork::new(&cfg.thermal, chamber0, &up_b);
        let s = &cfg.sensor;
        let quant = |on: bool, p: [f64; 3], unit: f64| {
            Quantizer::new(if on {
                Vector3::from(p) * unit
            } else {
                Vector3::zeros()
            })
        };
        let dt = 1.0 / cfg.rate_hz;
        let temps = thermal.temperatures();
        let gyro = GyroModel::new(&s.gyro);
        let accel = AccelModel::new(&s.accel);
        let mut temp_sensors = TempSensors::new(&s.temperature, cfg.seed);
        let temp_readings_c = temp_sensors.read(&temps.nodes_c);
        Self {
            declared: Declared::new(&s.gyro, &s.accel, &temps.nodes_c),
            carrier,
            encoders: Encoders::new(&s.encoder),
            temp_sensors,
            temp_readings_c,
            gyro_thermal: gyro.thermal_rates(&temps.gyro_c(), &temps.gyro_gradient_k()),
            accel_thermal_mps2: accel.thermal_bias_mps2(temps.accel_c()),
            site,
            c_vn,
            f_n: Vector3::new(0.0, 0.0, site.gravity_mps2),
            thermal,
            gyro,
            accel,
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
            internal_rate_hz: cfg.rate_hz * cfg.substeps as f64,
            dt_s: dt,
            sqrt_dt: dt.sqrt(),
            h_s: dt / cfg.substeps as f64,
            slow_every: (cfg.thermal.step_s * cfg.rate_hz).round() as u64,
            tick: 0,
            samples: 0,
            slow_countdown: (cfg.thermal.step_s * cfg.rate_hz).round() as u64,
            chamber_override_c: None,
            chamber_changed: false,
            gimbal_now: g0,
            hold_until_tick: hold_tick(
                schedule.eval_hold(0.0).1,
                cfg.rate_hz * cfg.substeps as f64,
            ),
            schedule,
            mid_cache: MidCache {
                outer_rad: f64::NAN,
                inner_rad: f64::NAN,
                c_nb: Matrix3::identity(),
                sin_outer: 0.0,
                cos_outer: 1.0,
                sin_inner: 0.0,
                cos_inner: 1.0,
            },
            vehicle_level: c_vn == Matrix3::identity(),
            dwell_cache: None,
            use_dwell_cache: true,
            command: None,
            noise_seed: cfg.seed,
            cursor: Cursor::default(),
            truth: Truth {
                gimbal: g0,
                dtheta_true_rad: Vector3::zeros(),
                dv_true_mps: Vector3::zeros(),
                temps,
                gyro_terms_rad: [Vector3::zeros(); GYRO_TERMS],
                accel_terms_mps: [Vector3::zeros(); ACCEL_TERMS],
                position_weight: 0.0,
                custom_gyro_rad: Vector3::zeros(),
                custom_accel_mps: Vector3::zeros(),
                carrier: carrier_truth,
            },
            cfg: cfg.clone(),
        }
    }

    fn mid_attitude(&mut self, g: &GimbalState) -> MidCache {
        // Dwells reuse the last attitude: no trigonometry while the table is still.
        let mut m = self.mid_cache;
        let (o, i) = (g.angles.outer_rad, g.angles.inner_rad);
        if m.outer_rad == o && m.inner_rad == i {
            return m;
        }
        if m.outer_rad != o {
            (m.sin_outer, m.cos_outer) = o.sin_cos();
            m.outer_rad = o;
        }
        if m.inner_rad != i {
            (m.sin_inner, m.cos_inner) = i.sin_cos();
            m.inner_rad = i;
        }
        let r = gimbal_rotation(m.sin_outer, m.cos_outer, m.sin_inner, m.cos_inner);
        m.c_nb = if self.vehicle_level {
            r.transpose()
        } else {
            (self.c_vn * r).transpose()
        };
        self.mid_cache = m;
        m
    }

    /// Table state at internal tick `tick` and at the midpoint before it, skipping evaluation
    /// while the table dwells.
    fn gimbal_at(&mut self, tick: u64) -> (GimbalState, GimbalState) {
        if tick <= self.hold_until_tick {
            return (self.gimbal_now, self.gimbal_now);
        }
        let ((g1, hold), gm) = self.schedule.eval_end_and_mid(
            tick as f64 / self.internal_rate_hz,
            (tick as f64 - 0.5) / self.internal_rate_hz,
            &mut self.cursor,
        );
        self.hold_until_tick = hold_tick(hold, self.internal_rate_hz);
        (g1, gm)
    }

    /// Kinematics and deterministic sensor effects over one output interval (all substeps):
    /// returns (Δθ_true, Δv_true, gyro error, accelerometer error, mean δβ weight) and writes
    /// each term's contribution into the truth.
    fn integrate_interval(
        &mut self,
        gyro_temp: Vector3<f64>,
        gradient: Vector3<f64>,
        accel_temp: f64,
    ) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>, f64) {
        let mut dtheta_true = Vector3::zeros();
        let mut dv_true = Vector3::zeros();
        let mut gyro_err = Vector3::zeros();
        let mut accel_err = Vector3::zeros();
        let mut weight = 0.0;
        let h = self.h_s;
        let substeps = self.cfg.substeps;
        for sub in 0..substeps {
            let g0 = self.gimbal_now;
            let (g1, gm) = self.gimbal_at(self.tick + 1);
            let (inc, up_b) = if self.carrier.is_some() {
                self.carrier_tick(&g0, &g1, &gm, h)
            } else {
                let m = self.mid_attitude(&gm);
                // Gimbal part from exact angle differences (one axis moves at a time); Earth
                // rate and specific force at the midpoint.
                let inc = table_increments(
                    &m.c_nb,
                    m.sin_inner,
                    m.cos_inner,
                    g1.angles.outer_rad - g0.angles.outer_rad,
                    g1.angles.inner_rad - g0.angles.inner_rad,
                    &self.site.omega_ie_n,
                    &self.f_n,
                    h,
                );
                (inc, m.c_nb.column(2).into_owned())
            };
            let (dtheta, dv, f_b) = (inc.dtheta_rad, inc.dv_mps, inc.f_b_mps2);
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
            let (gyro_terms, accel_terms) = (
                &mut self.truth.gyro_terms_rad,
                &mut self.truth.accel_terms_mps,
            );
            if sub == 0 {
                gyro_err = self
                    .gyro
                    .increment_error_with(&ctx, &self.gyro_thermal, gyro_terms);
                accel_err =
                    self.accel
                        .increment_error_with(&ctx, &self.accel_thermal_mps2, accel_terms);
            } else {
                let mut gterm = [Vector3::zeros(); GYRO_TERMS];
                let mut aterm = [Vector3::zeros(); ACCEL_TERMS];
                gyro_err += self
                    .gyro
                    .increment_error_with(&ctx, &self.gyro_thermal, &mut gterm);
                accel_err +=
                    self.accel
                        .increment_error_with(&ctx, &self.accel_thermal_mps2, &mut aterm);
                gyro_terms.iter_mut().zip(gterm).for_each(|(a, b)| *a += b);
                accel_terms.iter_mut().zip(aterm).for_each(|(a, b)| *a += b);
            }
            if self.declared.is_active() {
                // The division only when an effect reads the time.
                let t_mid = if self.declared.needs().time {
                    (self.tick as f64 + 0.5) / self.internal_rate_hz
                } else {
                    0.0
                };
                // North and east in body axes only when an effect reads them: columns 1 and 0
                // of C_n^b (ENU), at the interval's middle on a static carrier, at its start
                // on a moving one.
                let north_east_b = if self.declared.needs().heading {
                    let c_nb = if self.carrier.is_some() {
                        self.attitude_c_bn().transpose()
                    } else {
                        self.mid_attitude(&gm).c_nb
                    };
                    [c_nb.column(1).into_owned(), c_nb.column(0).into_owned()]
                } else {
                    [Vector3::zeros(); 2]
                };
                let (g, a) = self.declared.increments(
                    &up_b,
                    &north_east_b,
                    &dtheta,
                    &dv,
                    h,
                    gm.angles,
                    t_mid,
                );
                let tr = &mut self.truth;
                (tr.custom_gyro_rad, tr.custom_accel_mps) = if sub == 0 {
                    (g, a)
                } else {
                    (tr.custom_gyro_rad + g, tr.custom_accel_mps + a)
                };
                gyro_err += g;
                accel_err += a;
            }
            weight += self.gyro.position_weight(&up_b);
            dtheta_true += dtheta;
            dv_true += dv;
            self.gimbal_now = g1;
            self.tick += 1;
        }
        weight /= substeps as f64;

        (dtheta_true, dv_true, gyro_err, accel_err, weight)
    }

    /// Advances one output interval: kinematics → thermal → sensor effects → noise → quantisation.
    pub fn step(&mut self) -> ImuSample {
        let index = self.samples;
        self.samples += 1;
        // A changed chamber input ends the thermal step early: the update runs now over the time
        // since the last one, and the grid restarts here. Untouched inputs: the 1 s grid as ever.
        let elapsed = self.slow_every - self.slow_countdown;
        let split = std::mem::take(&mut self.chamber_changed) && self.slow_countdown != 0;
        if split && elapsed == 0 {
            // No time since the last update (the very first sample): only the chamber changes.
            let ch = self.chamber_c(self.time_s());
            self.thermal.hold_chamber(ch);
            // Nodes move only when the network is off (they follow the chamber): refresh the
            // rates that depend on them (no noise drawn; unchanged values otherwise).
            let t = self.thermal.temperatures();
            self.gyro_thermal = self.gyro.thermal_rates(&t.gyro_c(), &t.gyro_gradient_k());
            self.accel_thermal_mps2 = self.accel.thermal_bias_mps2(t.accel_c());
            self.dwell_cache = None;
        } else if self.slow_countdown == 0 || split {
            self.slow_countdown = self.slow_every;
            let h = if split {
                elapsed as f64 / self.cfg.rate_hz
            } else {
                self.cfg.thermal.step_s
            };
            let t = self.time_s();
            let up_b = self.attitude_c_bn().transpose() * Vector3::z();
            let ch = self.chamber_c(t);
            self.thermal.step(h, ch, &up_b);
            self.noise.step_slow(h);
            let t = self.thermal.temperatures();
            self.declared.thermal_update(&t.nodes_c, h);
            self.temp_readings_c = self.temp_sensors.read(&t.nodes_c);
            self.gyro_thermal = self.gyro.thermal_rates(&t.gyro_c(), &t.gyro_gradient_k());
            self.accel_thermal_mps2 = self.accel.thermal_bias_mps2(t.accel_c());
            self.dwell_cache = None;
        }
        self.slow_countdown -= 1;
        let temps = self.thermal.temperatures();
        let (gyro_temp, gradient, accel_temp) =
            (temps.gyro_c(), temps.gyro_gradient_k(), temps.accel_c());

        let substeps = self.cfg.substeps as u64;
        let held = self.tick + substeps <= self.hold_until_tick && self.carrier.is_none();
        let (dtheta_true, dv_true, gyro_err, accel_err, weight) = match self.dwell_cache {
            Some(c) if held => {
                // The per-term contributions in `self.truth` are those of the previous interval
                // of this dwell: unchanged.
                self.tick += substeps;
                (c.dtheta_true, c.dv_true, c.gyro_err, c.accel_err, c.weight)
            }
            _ => {
                let r = self.integrate_interval(gyro_temp, gradient, accel_temp);
                let reuse = held && self.use_dwell_cache && !self.declared.varies_in_dwell();
                self.dwell_cache = reuse.then_some(DwellCache {
                    dtheta_true: r.0,
                    dv_true: r.1,
                    gyro_err: r.2,
                    accel_err: r.3,
                    weight: r.4,
                });
                r
            }
        };

        let dt = self.dt_s;
        use crate::effects::{AccelTerm as A, GyroTerm as G};
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
        let tr = &mut self.truth;
        tr.gyro_terms_rad[G::AngleRandomWalk as usize] = arw;
        tr.gyro_terms_rad[G::BiasInstability as usize] = gm;
        tr.gyro_terms_rad[G::RateRandomWalk as usize] = rrw;
        tr.accel_terms_mps[A::VelocityRandomWalk as usize] = vrw;

        let dtheta_analog = dtheta_true + gyro_err + arw + gm + rrw;
        let dv_analog = dv_true + accel_err + vrw;
        let dtheta_out = self.gyro_quant.apply(&dtheta_analog);
        let dv_out = self.accel_quant.apply(&dv_analog);
        tr.gyro_terms_rad[G::Quantization as usize] = dtheta_out - dtheta_analog;
        tr.accel_terms_mps[A::Quantization as usize] = dv_out - dv_analog;
        tr.gimbal = self.gimbal_now;
        tr.dtheta_true_rad = dtheta_true;
        tr.dv_true_mps = dv_true;
        tr.temps = temps;
        tr.position_weight = weight;
        if let Some(c) = &self.carrier {
            // The carrier's own truth is filled in by `Plant::truth` when asked for.
            if let Some(i) = &c.isolation {
                // Azimuth isolation turns the outer gimbal on top of the scheme.
                tr.gimbal.angles.outer_rad += i.offset_rad(self.tick, self.cfg.substeps as u64);
                tr.gimbal.outer_rate_rps += i.rate_rps(self.tick);
            }
        }
        let sample = ImuSample {
            index,
            t_s: self.time_s(),
            dtheta_rad: dtheta_out,
            dv_mps: dv_out,
            encoder: self.encoders.read(self.truth.gimbal.angles),
            temps_c: self.temp_readings_c,
        };
        self.isolate(&sample);
        sample
    }
}
