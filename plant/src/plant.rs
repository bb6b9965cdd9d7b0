//! The plant: a pipeline of stages advanced by whole output intervals. A step reads like the
//! physics: the temperature field's slow update, then per tick the motion (carrier and table)
//! and the deterministic sensor errors, then the readout (noise, quantisation, encoders and
//! temperature sensors) that makes the sample the IMU outputs.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::carrier::own_table::OwnTable;
use crate::carrier::run::CarrierRun;
use crate::carrier::{Carrier, CarrierTruth};
use crate::command::{ActiveCommand, GimbalCommand};
use crate::config::{ConfigError, PlantConfig};
use crate::earth::Site;
use crate::effects::accel::ACCEL_TERMS;
use crate::effects::gyro::GYRO_TERMS;
use crate::effects::{AccelModel, GyroModel};
use crate::output::{ImuSample, Truth};
use crate::stages::clock::Clock;
use crate::stages::dwell_rule::DwellRule;
use crate::stages::interval::Interval;
use crate::stages::lane::Lane;
use crate::stages::motion::Motion;
use crate::stages::readout::{Measured, Readout};
use crate::stages::sensor_errors::{SensorErrors, TickInput};
use crate::stages::temperature::{TemperatureField, ThermalEvent};
use crate::table::{GimbalAngles, Schedule, body_to_nav};
use crate::thermal::node;
use crate::true_attitude::TruthMount;

mod isolated;
mod saved_state;

/// A dwell's interval kept for the rest of the dwell. When a declared effect reads the time,
/// the tick's catalogue errors and true increments are kept too: each later interval redoes
/// only the declared part, tick by tick, in the order the full path adds them.
///
/// Right only for terms whose contribution is the same every tick of a held dwell: each
/// catalogue term declares whether it is (`crate::effects::DwellDependence`), each declared
/// effect too, and [`SensorErrors::dwell_rule`] says from their union what may be kept.
#[derive(Clone, Copy, Debug)]
struct DwellReuse {
    interval: Interval,
    timed: Option<TimedTick>,
}

/// One tick of a dwell, for redoing the declared effects that read the time.
#[derive(Clone, Copy, Debug)]
struct TimedTick {
    /// The tick's catalogue gyro and accelerometer errors (the same every tick of the dwell).
    catalogue: (Vector3<f64>, Vector3<f64>),
    dtheta_rad: Vector3<f64>,
    dv_mps: Vector3<f64>,
}

/// The rotating IMU.
#[derive(Clone, Debug)]
pub struct Plant {
    cfg: PlantConfig,
    clock: Clock,
    motion: Motion,
    temperature: TemperatureField,
    errors: SensorErrors,
    /// This seed's readout and, with azimuth isolation, its own table.
    lane: Lane,
    /// With azimuth isolation: one reference table, each seed's own turned from it
    /// (`crate::carrier::own_table`), rather than each seed moving its own.
    isolation_reference: bool,
    /// The last interval, reused while the table dwells between thermal updates (cleared on
    /// motion, commands and thermal updates).
    dwell: Option<DwellReuse>,
    /// Reuse dwell intervals (tests compare against the path without).
    use_dwell_cache: bool,
    truth: Truth,
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

    /// The plant of `cfg` on the moving carrier `carrier` (e.g. a trajectory already in memory),
    /// replacing the one `cfg.carrier` describes.
    pub fn with_carrier(cfg: &PlantConfig, carrier: Carrier) -> Result<Self, Vec<ConfigError>> {
        cfg.validate()?;
        Ok(Self::build(cfg, Some(carrier)))
    }

    fn build(cfg: &PlantConfig, carrier: Option<Carrier>) -> Self {
        let clock = Clock::new(cfg);
        let motion = Motion::new(cfg, carrier);
        let g0 = motion.gimbal_now();
        let up_b = body_to_nav(&motion.vehicle_to_nav(), g0.angles).transpose() * Vector3::z();
        let temperature = TemperatureField::new(cfg, &up_b);
        let temps = temperature.temperatures();
        Self {
            errors: SensorErrors::new(cfg, &temps),
            lane: Lane::new(
                Readout::new(cfg, &temps.nodes_c),
                motion
                    .carrier()
                    .and_then(|c| c.isolation.clone())
                    .map(|lp| OwnTable { lp }),
                false,
            ),
            isolation_reference: true,
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
                carrier: motion.static_truth(),
            },
            clock,
            motion,
            temperature,
            dwell: None,
            use_dwell_cache: true,
            cfg: cfg.clone(),
        }
    }

    /// Advances one output interval: temperatures → motion and sensor errors → readout.
    pub fn step(&mut self) -> ImuSample {
        let index = self.clock.begin_sample();
        self.update_temperatures();
        let interval = self.deterministic_interval();
        self.read_out(index, &interval)
    }

    /// The temperature field's slow update when one is due; the stages that depend on the
    /// temperatures follow it. Returns the length of the thermal step taken, if one was.
    #[inline]
    fn update_temperatures(&mut self) -> Option<f64> {
        let (t_s, tick) = (self.clock.time_s(), self.clock.tick());
        let motion = &self.motion;
        let event = self.temperature.begin_sample(t_s, || {
            motion.attitude_c_bn(tick).transpose() * Vector3::z()
        });
        let event = event?;
        let t = self.temperature.temperatures();
        self.dwell = None;
        match event {
            ThermalEvent::ChamberHeld => {
                self.errors.on_temperatures(&t, None);
                None
            }
            ThermalEvent::Stepped { h_s } => {
                self.lane.readout.on_thermal_step(h_s, &t.nodes_c);
                self.errors.on_temperatures(&t, Some(h_s));
                Some(h_s)
            }
        }
    }

    /// The interval's true increments and deterministic errors: the dwell's last interval
    /// again while the table holds still, else every tick of motion and sensor errors.
    /// Inlined into the step with the readout, the worked interval out of line: as three calls
    /// the staged step copied the cached dwell (about 200 bytes) every sample and measured 7 %
    /// slower than the plant before the stages (`plant_week`; +1.2 % now, median of pooled
    /// interleaved runs).
    #[inline(always)]
    fn deterministic_interval(&mut self) -> Interval {
        let held = self
            .motion
            .holds_through(self.clock.tick() + self.clock.substeps());
        // Most samples of a static run: the dwell's interval again, with nothing to redo.
        if held
            && let Some(DwellReuse {
                interval,
                timed: None,
            }) = &self.dwell
        {
            let x = *interval;
            self.clock.advance_interval();
            return x;
        }
        self.deterministic_interval_worked(held)
    }

    /// [`Plant::deterministic_interval`] but for a dwell's plain reuse: the declared effects
    /// that read the time redone over a dwell's interval, or every tick worked out.
    #[inline(never)]
    fn deterministic_interval_worked(&mut self, held: bool) -> Interval {
        if held
            && let Some(DwellReuse {
                interval,
                timed: Some(t),
            }) = self.dwell
        {
            // The per-term contributions of the catalogue in the truth are those of the
            // previous interval of this dwell: unchanged.
            let mut x = interval;
            let h_s = self.clock.h_s();
            for sub in 0..self.clock.substeps() {
                let since = self.errors.table_clocks_held(self.clock.tick(), h_s);
                self.errors.redo_declared(
                    sub == 0,
                    t.catalogue,
                    self.clock.tick_mid_s(),
                    since,
                    &t.dtheta_rad,
                    &t.dv_mps,
                    h_s,
                    &mut self.truth,
                    (&mut x.gyro_err_rad, &mut x.accel_err_mps),
                );
                self.clock.advance_tick();
            }
            return x;
        }
        let temps = self.temperature.temperatures();
        let needs = self.errors.declared_needs();
        let heading = needs.is_some_and(|n| n.heading) || self.errors.gyro().reads_heading();
        // The division only when an effect reads the time.
        let time = needs.is_some_and(|n| n.time);
        let h_s = self.clock.h_s();
        let mut x = Interval {
            dtheta_true_rad: Vector3::zeros(),
            dv_true_mps: Vector3::zeros(),
            gyro_err_rad: Vector3::zeros(),
            accel_err_mps: Vector3::zeros(),
            position_weight: 0.0,
        };
        let mut last_tick = None;
        for sub in 0..self.clock.substeps() {
            let tick = self.clock.tick();
            let m = self.motion.tick(tick, h_s, heading);
            let since = self.errors.table_clocks(tick, m.moved, h_s);
            let input = TickInput {
                h_s,
                dtheta_rad: m.inc.dtheta_rad,
                dv_mps: m.inc.dv_mps,
                f_b_mps2: m.inc.f_b_mps2,
                up_b: m.up_b,
                north_east_b: m.north_east_b,
                gimbal_mid: m.gimbal_mid.angles,
                t_mid_s: if time { self.clock.tick_mid_s() } else { 0.0 },
                since,
            };
            let catalogue = self.errors.tick(
                &input,
                &temps,
                sub == 0,
                &mut self.truth,
                &mut x.gyro_err_rad,
                &mut x.accel_err_mps,
            );
            last_tick = Some(TimedTick {
                catalogue,
                dtheta_rad: m.inc.dtheta_rad,
                dv_mps: m.inc.dv_mps,
            });
            x.position_weight += self.errors.position_weight(&m.up_b);
            x.dtheta_true_rad += m.inc.dtheta_rad;
            x.dv_true_mps += m.inc.dv_mps;
            self.clock.advance_tick();
        }
        x.position_weight /= self.clock.substeps() as f64;
        // What may be kept rests on what every switched-on term declares about a dwell
        // (`DwellDependence` per catalogue term, `varies_in_dwell` per declared effect):
        // `plant/tests/plant/dwell_cache.rs` checks each against the path without the cache.
        self.dwell = if held && self.use_dwell_cache {
            match self.errors.dwell_rule() {
                DwellRule::ReuseWhole => Some(DwellReuse {
                    interval: x,
                    timed: None,
                }),
                DwellRule::RedoDeclared => Some(DwellReuse {
                    interval: x,
                    timed: last_tick,
                }),
                // The redo path keeps the catalogue's errors: with one that varies, keep nothing.
                DwellRule::WorkEveryTick => None,
            }
        } else {
            None
        };
        x
    }

    /// The readout of `x`: the sample the IMU outputs, the truth beside it, and the isolation
    /// loop fed with what was measured.
    #[inline(always)]
    fn read_out(&mut self, index: u64, x: &Interval) -> ImuSample {
        if self.lane.own.is_some() {
            return self.read_out_isolated(index, x, &mut [], &mut []);
        }
        let measured = self.lane.readout.measure(x);
        let tick = self.clock.tick();
        let tr = &mut self.truth;
        tr.gimbal = self.motion.gimbal_truth(tick);
        tr.dtheta_true_rad = x.dtheta_true_rad;
        tr.dv_true_mps = x.dv_true_mps;
        tr.temps = self.temperature.temperatures();
        tr.position_weight = x.position_weight;
        let sample =
            self.lane
                .readout
                .sample(index, self.clock.time_s(), &measured, tr.gimbal.angles);
        self.motion.isolate(&sample.dtheta_rad, tick);
        sample
    }

    /// True when every seed sees the same physics (motion, temperatures, deterministic
    /// errors), so one interval can be read out for many seeds ([`crate::SeedBatch`]): not on
    /// a ship in a seeded sea, nor with the azimuth isolation loop moving this seed's own table
    /// ([`Plant::set_isolation_reference`]`(false)`), which feeds its measured increments back
    /// into the motion; with the reference table each seed's table is turned from it.
    pub fn shares_physics_across_seeds(&self) -> bool {
        match self.motion.carrier() {
            None => true,
            Some(run) => {
                // Isolated tables share it when each is turned from the reference table.
                !run.carrier.depends_on_seed()
                    && (self.lane.own.is_some()
                        || (run.isolation.is_none() && !self.cfg.carrier.azimuth_isolation))
            }
        }
    }

    /// One step for this plant's seed and, from the same interval, one for each of `lanes`
    /// (readouts of other seeds): `out[0]` is this plant's sample, `out[k]` lane k − 1's. Only
    /// when [`Plant::shares_physics_across_seeds`].
    pub(crate) fn step_lanes(&mut self, lanes: &mut [Lane], out: &mut [ImuSample]) {
        debug_assert_eq!(lanes.len() + 1, out.len());
        let index = self.clock.begin_sample();
        if let Some(h_s) = self.update_temperatures() {
            let nodes = self.temperature.temperatures().nodes_c;
            lanes
                .iter_mut()
                .for_each(|l| l.readout.on_thermal_step(h_s, &nodes));
        }
        let interval = self.deterministic_interval();
        if self.lane.own.is_some() {
            out[0] = self.read_out_isolated(index, &interval, lanes, &mut out[1..]);
            return;
        }
        let first = self.read_out(index, &interval);
        out[0] = first;
        let angles = self.truth.gimbal.angles;
        for (lane, o) in lanes.iter_mut().zip(&mut out[1..]) {
            let m = lane.measure(&interval);
            *o = lane.readout.sample(first.index, first.t_s, &m, angles);
        }
    }

    /// The lane of `cfg` (this plant's configuration but for its seed and noise terms, or with
    /// ideal sensors, see [`crate::SeedBatch`]) at the plant's start: a lane of a batch, built
    /// before the first step; on isolated tables it starts with this plant's loop.
    pub(crate) fn lane(&self, cfg: &PlantConfig) -> Lane {
        Lane::new(
            Readout::new(cfg, &self.truth.temps.nodes_c),
            self.lane.own.clone(),
            cfg.sensor == crate::config::SensorSpec::default(),
        )
    }

    /// [`Plant::truth`] on `lane` (its noise and quantisation terms, and its own table).
    pub(crate) fn truth_of_lane(&self, lane: &Lane) -> Truth {
        lane.truth(self.truth())
    }

    /// Applies a table command from the next output interval on (see [`GimbalCommand`]).
    /// Rejects non-finite or out-of-range angles and rates with the reason.
    pub fn command_gimbal(&mut self, cmd: &GimbalCommand) -> Result<(), String> {
        let c = ActiveCommand::new(cmd, self.motion.gimbal_now().angles, self.clock.tick())?;
        self.motion.install_command(c);
        self.dwell = None;
        Ok(())
    }

    /// Puts the plant on an externally driven carrier held at `start` (call after building,
    /// or after restoring a saved state, before the first step).
    pub fn attach_external_carrier(
        &mut self,
        start: &crate::carrier::external::CarrierSample,
    ) -> Result<(), String> {
        let seg = crate::carrier::external::segment(start, start, 1, self.clock.tick_s())?;
        self.motion.set_carrier(CarrierRun::new(seg, &self.cfg));
        Ok(())
    }

    /// Drives the external carrier from `start` to `end` over the next `samples` IMU samples
    /// (see [`crate::carrier::external`]); the plant must be on an external carrier.
    pub fn drive_carrier(
        &mut self,
        start: &crate::carrier::external::CarrierSample,
        end: &crate::carrier::external::CarrierSample,
        samples: u64,
    ) -> Result<(), String> {
        let ticks = samples * self.clock.substeps();
        let seg = crate::carrier::external::segment(start, end, ticks, self.clock.tick_s())?;
        let run = self
            .motion
            .carrier_mut()
            .ok_or("the plant is not on an external carrier")?;
        run.carrier = seg;
        run.now = run.carrier.state_now();
        Ok(())
    }

    /// Switches a ship between the segment rule (`true`, the default when its motion allows it)
    /// and the exact per-tick evaluation (`false`, the reference the tests compare with); only
    /// before the first step. Returns the segment length in ticks (`None`: per tick).
    pub fn set_carrier_segments(&mut self, on: bool) -> Result<Option<u64>, String> {
        if self.clock.tick() != 0 {
            return Err("the carrier's segment rule is switched before the first step".into());
        }
        Ok(self.motion.carrier_mut().and_then(|r| r.set_segments(on)))
    }

    /// Turns the dwell cache off or on. Output is bit-identical either way; only speed differs.
    pub fn set_dwell_cache(&mut self, on: bool) {
        self.use_dwell_cache = on;
        self.dwell = None;
    }

    /// Overrides the chamber temperature (an FMU input); `None` returns to the scenario profile.
    /// A change acts from the next sample: it starts with a thermal update over the time since
    /// the last one (docs/fmu.md, "When an input acts").
    pub fn set_chamber_temp_c(&mut self, temp_c: Option<f64>) {
        self.temperature.set_chamber_override(temp_c);
    }

    /// Restarts every noise stream from `seed` at the current tick, keeping the current
    /// bias-instability and rate-random-walk values. A Monte Carlo can warm the plant up once,
    /// save the state, and give each run its own noise from there.
    pub fn reseed_noise(&mut self, seed: u64) {
        self.lane.readout.reseed(seed);
    }

    /// The configuration the plant was built from.
    pub fn config(&self) -> &PlantConfig {
        &self.cfg
    }

    /// Earth quantities at the site.
    pub fn site(&self) -> &Site {
        self.motion.site()
    }

    /// Output interval Δt, s.
    pub fn dt_s(&self) -> f64 {
        self.clock.dt_s()
    }

    /// Output samples produced so far.
    pub fn samples_done(&self) -> u64 {
        self.clock.samples()
    }

    /// Simulated time, s (from the integer tick counter).
    pub fn time_s(&self) -> f64 {
        self.clock.time_s()
    }

    /// Truth over the last interval. On a moving carrier the carrier's part is evaluated here,
    /// when asked for, not at every tick (it is a copy for that reason).
    pub fn truth(&self) -> Truth {
        let mut t = Truth {
            carrier: self.carrier_truth(),
            ..self.truth
        };
        self.lane.readout.terms().write_into(&mut t);
        t
    }

    /// The carrier's part of [`Plant::truth`] alone (the site and `[vehicle]` attitude when
    /// static), without copying the rest.
    pub fn carrier_truth(&self) -> CarrierTruth {
        self.motion.carrier_truth()
    }

    /// The temperature-sensor readings of the last sample (a measured output), °C.
    pub fn temp_readings_c(&self) -> [f64; node::COUNT] {
        self.lane.readout.temp_readings_c()
    }

    /// What the unit reports now, before its next sample: no increments, the encoders' reading
    /// of the table's true angles in the truth and the temperature sensors' last readings, at
    /// the plant's time (an FMU's outputs before its first step).
    pub fn start_sample(&self) -> ImuSample {
        self.lane.readout.sample(
            self.clock.samples(),
            self.clock.time_s(),
            &Measured::NONE,
            self.truth.gimbal.angles,
        )
    }

    /// The gimbal encoders' readings of the table's true angles in the truth (a measured
    /// output): the last sample's, and before the first step those of the start angles, rad.
    pub fn encoder_readings(&self) -> GimbalAngles {
        self.lane.readout.encoders(self.truth.gimbal.angles)
    }

    /// The chamber temperature over the last interval (the test set-up's, not the unit's), °C.
    pub fn chamber_now_c(&self) -> f64 {
        self.truth.temps.chamber_c
    }

    /// The compiled table schedule.
    pub fn schedule(&self) -> &Schedule {
        self.motion.schedule()
    }

    /// The deterministic gyro model (coefficients and regressors for diagnosis).
    pub fn gyro_model(&self) -> &GyroModel {
        self.errors.gyro()
    }

    /// The deterministic accelerometer model.
    pub fn accel_model(&self) -> &AccelModel {
        self.errors.accel()
    }

    /// Vehicle mount attitude C_v^n now (on a moving carrier, C_c^n·C_v^c).
    pub fn vehicle_to_nav(&self) -> Matrix3<f64> {
        self.motion.vehicle_to_nav()
    }

    /// True IMU attitude C_b^n now (this seed's own table's, with azimuth isolation).
    pub fn attitude_c_bn(&self) -> Matrix3<f64> {
        match &self.lane.own {
            None => self.motion.attitude_c_bn(self.clock.tick()),
            Some(_) => body_to_nav(&self.motion.vehicle_to_nav(), self.true_angles_now()),
        }
    }

    /// The true gimbal angles now, those of [`Plant::attitude_c_bn`]: the scheme's with the
    /// isolation loop's outer offset (this seed's own loop's on an isolated table).
    fn true_angles_now(&self) -> GimbalAngles {
        let tick = self.clock.tick();
        match &self.lane.own {
            None => self.motion.gimbal_truth(tick).angles,
            Some(_) => {
                let mut a = self.motion.gimbal_now().angles;
                a.outer_rad += self.own_offset_rad(tick);
                a
            }
        }
    }

    /// True IMU attitude now as the quaternion q_b^n, in closed form
    /// ([`crate::true_attitude`]): q_c^n·q_v^c·q_z(outer)·q_x(inner) with the carrier's truth
    /// attitude and the gimbal angles of [`Plant::attitude_c_bn`], whose matrix it is to
    /// rounding (to 2e-14 on a ship on the segment rule, whose C_c^n there is interpolated
    /// apart from the truth's by its own rounding). The sinks of the truth compose the same from the truth record
    /// ([`TruthMount::q_bn_of`]); after a step its angles are these, bit for bit, except on an
    /// isolated table, whose record adds the seed's offset to the reference table's (the
    /// angles then agree to rounding).
    pub fn attitude_q_bn(&self) -> UnitQuaternion<f64> {
        self.truth_mount()
            .q_bn(&self.carrier_truth().q_cn, self.true_angles_now())
    }

    /// The mount between the truth's carrier attitude and the table ([`TruthMount`]): the
    /// identity on the static carrier, the `[vehicle]` mount on a moving one (an external
    /// carrier attached after building included).
    pub fn truth_mount(&self) -> TruthMount {
        TruthMount::new(self.motion.is_moving(), &self.cfg.vehicle)
    }

    /// Seed of the noise streams in use.
    pub fn noise_seed(&self) -> u64 {
        self.lane.readout.noise_seed()
    }

    /// True when the table rides a moving carrier (ship, trajectory or an external vessel model).
    pub fn moving_carrier(&self) -> bool {
        self.motion.is_moving()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::custom::{Axis, CustomKind, CustomSpec};

    /// Declared effects that read the time reuse the dwell (only their own part redone per
    /// tick) and give the bits of the path without the dwell cache, truth included, with one
    /// substep and with three.
    #[test]
    fn a_dwell_with_timed_declared_effects_equals_the_uncached_path() {
        for substeps in [1, 3] {
            let mut cfg = crate::presets::paper_16pos_config();
            cfg.substeps = substeps;
            let spec = |name: &str, kind, regressor: &str, unit: &str| CustomSpec {
                name: name.into(),
                enabled: true,
                kind,
                regressor: regressor.into(),
                unit: unit.into(),
                axes: vec![Axis::X, Axis::Y, Axis::Z],
                coef: [1e-6, -2e-6, 3e-7],
            };
            cfg.sensor.gyro.custom = vec![
                spec("drift", CustomKind::Bias, "time", "s"),
                spec("tilt", CustomKind::Bias, "time*u_x", "s"),
                spec("sf", CustomKind::ScaleFactor, "time^2", "s^2"),
                // Memory (issue 42): a transient after each move, a lagged temperature.
                spec("transient", CustomKind::Bias, "exp(-since_move/60)", "1"),
                spec("lagged", CustomKind::Bias, "lag(temp:block,300)*u_z", "K"),
            ];
            cfg.sensor.accel.custom = vec![
                spec("a", CustomKind::Bias, "time*u_z", "s"),
                spec(
                    "b",
                    CustomKind::Bias,
                    "since_start*lag(abs_w_z,5)",
                    "s*deg/s",
                ),
            ];
            let mut cached = Plant::new(&cfg).unwrap();
            let mut plain = Plant::new(&cfg).unwrap();
            plain.set_dwell_cache(false);
            let mut reused = 0;
            // 400 s at 100 Hz: dwells of 180 s and the turns between them.
            for k in 0..40_000 {
                let a = cached.step();
                assert_eq!(a, plain.step(), "substeps {substeps}, sample {k}");
                assert_eq!(
                    cached.truth(),
                    plain.truth(),
                    "substeps {substeps}, sample {k}"
                );
                reused += cached.dwell.is_some_and(|d| d.timed.is_some()) as u32;
            }
            // About 55 % of the samples: the dwells, less each thermal update (every 1 s).
            assert!(reused > 15_000, "the dwell was reused {reused} times");
        }
    }

    /// A transient after each table move, `exp(-since_move/τ)`: over a whole dwell of the
    /// 16-position scheme the plant's declared error sums to A·τ·(1 − e^(−T/τ)) (the clock
    /// starts when the turn ends), and during the turn to A per second; the clock is in whole
    /// ticks, the value at each tick's middle (relative error below (h/τ)²/24).
    #[test]
    fn a_transient_after_each_move_integrates_to_its_closed_form() {
        let mut cfg = crate::presets::paper_16pos_config();
        cfg.sensor = crate::config::SensorSpec::default();
        let (a_dph, tau_s) = (0.05, 40.0);
        cfg.sensor.gyro.custom = vec![CustomSpec {
            name: "transient".into(),
            enabled: true,
            kind: CustomKind::Bias,
            regressor: "exp(-since_move/40)".into(),
            unit: "1".into(),
            axes: vec![Axis::Z],
            coef: [0.0, 0.0, a_dph],
        }];
        let mut p = Plant::new(&cfg).unwrap();
        let h = 1.0 / cfg.rate_hz;
        let a = a_dph * crate::units::DPH;
        // Samples while the table turns, and the dwell after the first turn.
        let (mut moving_sum, mut moving_n, mut dwell, mut in_dwell) = (0.0, 0, Vec::new(), false);
        for _ in 0..40_000 {
            p.step();
            let t = p.truth();
            let e = t.custom_gyro_rad[2];
            if t.gimbal.moving {
                if in_dwell {
                    break;
                }
                moving_sum += e;
                moving_n += 1;
            } else if moving_n > 0 {
                in_dwell = true;
                dwell.push(e);
            }
        }
        assert!(
            moving_n > 100 && dwell.len() > 1000,
            "{moving_n} {}",
            dwell.len()
        );
        // While turning the clock is 0: A per second (the samples the turn starts and ends
        // in are partly still, so the mean lies a little below A).
        let mean = moving_sum / (moving_n as f64 * h);
        assert!((mean / a - 1.0).abs() < 0.02, "{mean} vs {a}");
        // The dwell: samples after the turn's last one, from its stop to the next turn.
        let span = dwell.len() as f64 * h;
        let want = a * tau_s * (1.0 - (-span / tau_s).exp());
        let got: f64 = dwell.iter().sum();
        assert!(
            (got / want - 1.0).abs() < 2.0 * h / span + 1e-6,
            "{got} vs closed form {want}"
        );
    }

    /// The declared effects' memory and motion clocks are part of the saved state: a plant
    /// resumed mid-dwell continues bit for bit.
    #[test]
    fn memory_and_motion_clocks_survive_a_saved_state() {
        let mut cfg = crate::presets::paper_16pos_config();
        cfg.sensor.gyro.custom = vec![CustomSpec {
            name: "m".into(),
            enabled: true,
            kind: CustomKind::Bias,
            regressor: "exp(-since_move/60)*lag(temp:block,200)".into(),
            unit: "K".into(),
            axes: vec![Axis::X, Axis::Z],
            coef: [0.01, 0.0, -0.02],
        }];
        cfg.thermal.start_steady = false;
        let mut a = Plant::new(&cfg).unwrap();
        for _ in 0..25_123 {
            a.step();
        }
        let mut b = Plant::from_serialized_state(&cfg, &a.serialize_state()).unwrap();
        for k in 0..30_000 {
            assert_eq!(a.step(), b.step(), "sample {k} after the restore");
        }
    }
}
