//! The sensor-error stage: every deterministic gyro and accelerometer effect, the catalogue's
//! (Eq. 3, 4 and 9 with the temperature terms) and the declared ones (`[[sensor.*.custom]]`),
//! evaluated on a tick's true increments. Its temperature-dependent rates change only at
//! thermal updates.

use nalgebra::Vector3;

use super::dwell_rule::DwellRule;
use crate::config::PlantConfig;
use crate::effects::accel::ACCEL_TERMS;
use crate::effects::custom::{Declared, MotionClocks, Needs};
use crate::effects::gyro::{GYRO_TERMS, GyroThermalRates};
use crate::effects::{AccelModel, GyroModel, TermContext};
use crate::output::Truth;
use crate::state::{Reader, StateError, Writer};
use crate::table::GimbalAngles;
use crate::thermal::Temperatures;

/// What one tick gives the sensor effects.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TickInput {
    /// Tick length, s.
    pub h_s: f64,
    /// True angular increment over the tick, rad.
    pub dtheta_rad: Vector3<f64>,
    /// True velocity increment, m/s.
    pub dv_mps: Vector3<f64>,
    /// Specific force, body axes, m/s².
    pub f_b_mps2: Vector3<f64>,
    /// Up direction in body axes (the tick's mean).
    pub up_b: Vector3<f64>,
    /// North and east in body axes, when a declared effect reads them.
    pub north_east_b: [Vector3<f64>; 2],
    /// Gimbal angles at the tick's middle.
    pub gimbal_mid: GimbalAngles,
    /// Time at the tick's middle, s, when a declared effect reads it.
    pub t_mid_s: f64,
    /// The table's motion clocks at the tick's middle, when a declared effect reads them.
    pub since: MotionClocks,
}

/// When the table last stopped and last started, in internal ticks: the clocks `since_move`
/// and `since_start` of the declared effects, kept in whole ticks so they are exact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct TableClocks {
    /// The tick at whose start the table last stopped (0: the run's start).
    stop_tick: u64,
    /// The tick in which it last started to move (0: the run's start).
    start_tick: u64,
    /// The last tick moved.
    moving: bool,
}

impl TableClocks {
    /// Tick `tick` (of length `h_s`), which moved the table or not: the clocks at its middle.
    #[inline]
    pub(crate) fn tick(&mut self, tick: u64, moved: bool, h_s: f64) -> MotionClocks {
        if moved && !self.moving {
            self.start_tick = tick;
        } else if !moved && self.moving {
            self.stop_tick = tick;
        }
        self.moving = moved;
        self.at(tick, h_s)
    }

    /// The clocks at the middle of tick `tick`, with nothing changed since the last
    /// [`TableClocks::tick`] (a held dwell).
    #[inline]
    pub(crate) fn at(&self, tick: u64, h_s: f64) -> MotionClocks {
        let mid = |from: u64| (tick.saturating_sub(from) as f64 + 0.5) * h_s;
        MotionClocks {
            move_s: if self.moving {
                0.0
            } else {
                mid(self.stop_tick)
            },
            start_s: mid(self.start_tick),
        }
    }
}

/// The deterministic sensor effects.
#[derive(Clone, Debug)]
pub(crate) struct SensorErrors {
    gyro: GyroModel,
    accel: AccelModel,
    /// Temperature-dependent gyro error rates at the current node temperatures.
    gyro_thermal: GyroThermalRates,
    /// Temperature-dependent accelerometer bias at the current temperature, m/s².
    accel_thermal_mps2: Vector3<f64>,
    /// Declared effects and their slow signals.
    declared: Declared,
    /// The table's last stop and start, for the declared effects' motion clocks.
    clocks: TableClocks,
    /// A switched-on catalogue term changes within a dwell
    /// ([`crate::effects::GyroTerm::varies_in_dwell`],
    /// [`crate::effects::AccelTerm::varies_in_dwell`]).
    catalogue_varies_in_dwell: bool,
}

impl SensorErrors {
    /// The effects of `cfg` at the temperatures `temps`.
    pub(crate) fn new(cfg: &PlantConfig, temps: &Temperatures) -> Self {
        let s = &cfg.sensor;
        let gyro = GyroModel::new(&s.gyro);
        let accel = AccelModel::new(&s.accel);
        Self {
            gyro_thermal: gyro.thermal_rates(&temps.gyro_c(), &temps.gyro_gradient_k()),
            accel_thermal_mps2: accel.thermal_bias_mps2(temps.accel_c()),
            declared: Declared::new(&s.gyro, &s.accel, &temps.nodes_c),
            clocks: TableClocks::default(),
            catalogue_varies_in_dwell: s.gyro.enabled_terms().iter().any(|t| t.varies_in_dwell())
                || s.accel.enabled_terms().iter().any(|t| t.varies_in_dwell()),
            gyro,
            accel,
        }
    }

    /// The gyro model (coefficients and regressors).
    pub(crate) fn gyro(&self) -> &GyroModel {
        &self.gyro
    }

    /// The accelerometer model.
    pub(crate) fn accel(&self) -> &AccelModel {
        &self.accel
    }

    /// Which per-tick signals the declared effects read (`None`: no declared effect is on).
    pub(crate) fn declared_needs(&self) -> Option<Needs> {
        self.declared.is_active().then(|| self.declared.needs())
    }

    /// Tick `tick` of length `h_s` moved the table or not: the motion clocks at its middle
    /// (kept only when a declared effect reads them; zeros otherwise).
    #[inline]
    pub(crate) fn table_clocks(&mut self, tick: u64, moved: bool, h_s: f64) -> MotionClocks {
        if self.declared.needs().motion {
            self.clocks.tick(tick, moved, h_s)
        } else {
            MotionClocks::default()
        }
    }

    /// The motion clocks at tick `tick` of a held dwell.
    #[inline]
    pub(crate) fn table_clocks_held(&self, tick: u64, h_s: f64) -> MotionClocks {
        if self.declared.needs().motion {
            self.clocks.at(tick, h_s)
        } else {
            MotionClocks::default()
        }
    }

    /// How much of a held dwell's interval the plant may keep for the next, from the union of
    /// the switched-on terms that change within a dwell: a catalogue term that says so
    /// ([`crate::effects::DwellDependence::WithinDwell`]) keeps nothing; a declared effect that
    /// reads the time or a motion clock, or has memory, keeps the catalogue's part and has its
    /// own redone per tick; with neither the interval is kept whole. The noise and
    /// quantisation terms are not asked: the readout applies them to every sample after the
    /// deterministic interval, cached or not.
    pub(crate) fn dwell_rule(&self) -> DwellRule {
        if self.catalogue_varies_in_dwell {
            DwellRule::WorkEveryTick
        } else if self.declared.varies_in_dwell() {
            DwellRule::RedoDeclared
        } else {
            DwellRule::ReuseWhole
        }
    }

    /// New temperatures: the temperature-dependent rates follow them; after a step of `h_s`
    /// the declared effects' slow signals (temperatures and their rates) too.
    pub(crate) fn on_temperatures(&mut self, t: &Temperatures, stepped_h_s: Option<f64>) {
        if let Some(h_s) = stepped_h_s {
            self.declared.thermal_update(&t.nodes_c, h_s);
        }
        self.refresh_rates(t);
    }

    fn refresh_rates(&mut self, t: &Temperatures) {
        self.gyro_thermal = self.gyro.thermal_rates(&t.gyro_c(), &t.gyro_gradient_k());
        self.accel_thermal_mps2 = self.accel.thermal_bias_mps2(t.accel_c());
    }

    /// Adds the gyro and accelerometer errors over one tick at temperatures `temps` to the
    /// interval's sums `gyro_err` and `accel_err` (set on the interval's first tick, `first`).
    /// Each term's contribution goes to `truth` the same way. The catalogue's sum is added
    /// before the declared effects', in that order, so the sums do not depend on grouping.
    /// Returns the tick's catalogue errors (gyro, accelerometer).
    pub(crate) fn tick(
        &mut self,
        x: &TickInput,
        temps: &Temperatures,
        first: bool,
        truth: &mut Truth,
        gyro_err: &mut Vector3<f64>,
        accel_err: &mut Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let ctx = TermContext {
            dt_s: x.h_s,
            dtheta_rad: x.dtheta_rad,
            dv_mps: x.dv_mps,
            f_b_mps2: x.f_b_mps2,
            up_b: x.up_b,
            north_b: x.north_east_b[0],
            east_b: x.north_east_b[1],
            gyro_temp_c: temps.gyro_c(),
            gyro_gradient_k: temps.gyro_gradient_k(),
            accel_temp_c: temps.accel_c(),
        };
        let catalogue;
        if first {
            catalogue = (
                self.gyro
                    .increment_error_with(&ctx, &self.gyro_thermal, &mut truth.gyro_terms_rad),
                self.accel.increment_error_with(
                    &ctx,
                    &self.accel_thermal_mps2,
                    &mut truth.accel_terms_mps,
                ),
            );
            (*gyro_err, *accel_err) = catalogue;
        } else {
            let mut gterm = [Vector3::zeros(); GYRO_TERMS];
            let mut aterm = [Vector3::zeros(); ACCEL_TERMS];
            catalogue = (
                self.gyro
                    .increment_error_with(&ctx, &self.gyro_thermal, &mut gterm),
                self.accel
                    .increment_error_with(&ctx, &self.accel_thermal_mps2, &mut aterm),
            );
            *gyro_err += catalogue.0;
            *accel_err += catalogue.1;
            truth
                .gyro_terms_rad
                .iter_mut()
                .zip(gterm)
                .for_each(|(a, b)| *a += b);
            truth
                .accel_terms_mps
                .iter_mut()
                .zip(aterm)
                .for_each(|(a, b)| *a += b);
        }
        if self.declared.is_active() {
            let (g, a) = self.declared.increments(
                &x.up_b,
                &x.north_east_b,
                &x.dtheta_rad,
                &x.dv_mps,
                x.h_s,
                x.gimbal_mid,
                x.t_mid_s,
                x.since,
            );
            (truth.custom_gyro_rad, truth.custom_accel_mps) = if first {
                (g, a)
            } else {
                (truth.custom_gyro_rad + g, truth.custom_accel_mps + a)
            };
            *gyro_err += g;
            *accel_err += a;
        }
        catalogue
    }

    /// One tick of a dwell again, for declared effects that change within it: adds the tick's
    /// `catalogue` errors (unchanged within the dwell) and the declared effects at `t_mid_s`
    /// and motion clocks `since` to `sums`, as [`SensorErrors::tick`] would (the frame's other
    /// signals are the dwell's; the memory advances by the tick).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn redo_declared(
        &mut self,
        first: bool,
        catalogue: (Vector3<f64>, Vector3<f64>),
        t_mid_s: f64,
        since: MotionClocks,
        dtheta_rad: &Vector3<f64>,
        dv_mps: &Vector3<f64>,
        h_s: f64,
        truth: &mut Truth,
        sums: (&mut Vector3<f64>, &mut Vector3<f64>),
    ) {
        let (gyro_err, accel_err) = sums;
        if first {
            (*gyro_err, *accel_err) = catalogue;
        } else {
            *gyro_err += catalogue.0;
            *accel_err += catalogue.1;
        }
        let (g, a) = self
            .declared
            .increments_at(t_mid_s, since, dtheta_rad, dv_mps, h_s);
        (truth.custom_gyro_rad, truth.custom_accel_mps) = if first {
            (g, a)
        } else {
            (truth.custom_gyro_rad + g, truth.custom_accel_mps + a)
        };
        *gyro_err += g;
        *accel_err += a;
    }

    /// Weight of δβ at body up direction `up_b` (0 Z-up, 1 Z-down; Eq. 9).
    pub(crate) fn position_weight(&self, up_b: &Vector3<f64>) -> f64 {
        self.gyro.position_weight(up_b)
    }

    /// Writes the declared effects' temperature rates (only when there are declared effects:
    /// states of plants without them keep their length), and, when they have them, their
    /// motion clocks and memory.
    pub(crate) fn write(&self, w: &mut Writer, truth: &Truth) {
        if self.declared.is_active() {
            self.declared.rates_k_per_s().iter().for_each(|x| w.f64(*x));
            w.v3(&truth.custom_gyro_rad);
            w.v3(&truth.custom_accel_mps);
        }
        if self.declared.needs().motion {
            w.u64(self.clocks.stop_tick);
            w.u64(self.clocks.start_tick);
            w.u64(self.clocks.moving as u64);
        }
        if self.declared.has_memory() {
            self.declared.lag_ends().iter().for_each(|x| w.f64(*x));
        }
    }

    /// Reads what [`SensorErrors::write`] wrote and rebuilds the rates at `temps`.
    pub(crate) fn read(
        &mut self,
        r: &mut Reader<'_>,
        temps: &Temperatures,
        truth: &mut Truth,
    ) -> Result<(), StateError> {
        if self.declared.is_active() {
            let mut rates = [0.0; 6];
            for x in rates.iter_mut() {
                *x = r.f64()?;
            }
            self.declared.restore(&temps.nodes_c, &rates);
            truth.custom_gyro_rad = r.v3()?;
            truth.custom_accel_mps = r.v3()?;
        }
        if self.declared.needs().motion {
            self.clocks.stop_tick = r.u64()?;
            self.clocks.start_tick = r.u64()?;
            self.clocks.moving = r.u64()? != 0;
        }
        if self.declared.has_memory() {
            let mut ends = self.declared.lag_ends();
            for x in ends.iter_mut() {
                *x = r.f64()?;
            }
            self.declared.restore_lag_ends(&ends);
        }
        self.refresh_rates(temps);
        Ok(())
    }
}
