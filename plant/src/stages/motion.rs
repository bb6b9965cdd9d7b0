//! The motion stage: the carrier (the static site, a ship, a trajectory or an external vessel
//! model) and the dual-axis table on it, following its scheme or the navigation computer's
//! commands. Per tick it gives the IMU's true increments and up direction; it also answers for
//! the true attitude and the carrier's truth.

mod moving_base;

use nalgebra::{Matrix3, Vector3};

use crate::carrier::isolation::nav_frame_turn;
use crate::carrier::own_table::ReferenceInterval;
use crate::carrier::run::CarrierRun;
use crate::carrier::{Carrier, CarrierState, CarrierTruth};
use crate::command::ActiveCommand;
use crate::config::PlantConfig;
use crate::earth::Site;
use crate::kinematics::{TableIncrements, table_increments};
use crate::state::{Reader, StateError, Writer};
use crate::table::gimbal::GimbalAxis;
use crate::table::gimbal::gimbal_rotation;
use crate::table::scheme::{ResolvedScheme, ResolvedStep};
use crate::table::{Cursor, GimbalAngles, GimbalState, Schedule, body_to_nav};

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

/// Attitude at the last evaluated midpoint, reused while the gimbal angles do not change; the
/// sine and cosine of each angle are cached separately because only one gimbal moves at a time.
#[derive(Clone, Copy, Debug)]
struct MidCache {
    outer_rad: f64,
    inner_rad: f64,
    c_nb: Matrix3<f64>,
    sin_outer: f64,
    cos_outer: f64,
    sin_inner: f64,
    cos_inner: f64,
}

impl MidCache {
    const EMPTY: MidCache = MidCache {
        outer_rad: f64::NAN,
        inner_rad: f64::NAN,
        c_nb: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        sin_outer: 0.0,
        cos_outer: 1.0,
        sin_inner: 0.0,
        cos_inner: 1.0,
    };
}

/// One tick of motion.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TickMotion {
    /// True increments and specific force over the tick.
    pub inc: TableIncrements,
    /// Up direction in body axes (the tick's mean).
    pub up_b: Vector3<f64>,
    /// Table state at the tick's middle.
    pub gimbal_mid: GimbalState,
    /// North and east in body axes (zero unless asked for).
    pub north_east_b: [Vector3<f64>; 2],
    /// A gimbal turned during the tick (its angles at the end differ from those at the start).
    pub moved: bool,
}

/// The carrier and the table.
#[derive(Clone, Debug)]
pub(crate) struct Motion {
    site: Site,
    /// C_v^n of the static carrier (a moving carrier's is [`Motion::vehicle_to_nav`]).
    c_vn: Matrix3<f64>,
    /// Specific force of the static carrier in ENU, m/s².
    f_n: Vector3<f64>,
    /// C_v^n is the identity (the usual level, azimuth-0 mount): skip one matrix product.
    vehicle_level: bool,
    /// The static carrier's truth (the moving carrier's is evaluated when asked for).
    static_truth: CarrierTruth,
    schedule: Schedule,
    /// Segment of the last schedule evaluation.
    cursor: Cursor,
    gimbal_now: GimbalState,
    /// The table holds `gimbal_now` up to this internal tick (end of the current dwell).
    hold_until_tick: u64,
    mid_cache: MidCache,
    /// Motion commanded by the navigation side, replacing the scheme from its start tick.
    command: Option<ActiveCommand>,
    /// The moving carrier; `None` for the static carrier.
    carrier: Option<Box<CarrierRun>>,
    /// The scenario's own carrier is static (an external one may be attached later).
    scenario_static: bool,
    internal_rate_hz: f64,
    substeps: u64,
    dt_s: f64,
    /// The scheme's acceleration limit, for commanded moves, rad/s².
    accel_rps2: f64,
    /// The inner angle at the start of the current output interval (the isolated tables' turn,
    /// [`Motion::reference_interval`]).
    interval_inner_rad: f64,
}

impl Motion {
    /// The motion of `cfg` on `carrier` (`None`: the static site).
    pub(crate) fn new(cfg: &PlantConfig, carrier: Option<Carrier>) -> Self {
        let site = Site::new(&cfg.site, &cfg.earth);
        let carrier = carrier.map(|c| CarrierRun::new(c, cfg));
        let c_vn = match &carrier {
            Some(r) => r.c_vn(),
            None => cfg.vehicle.c_vn(),
        };
        let static_truth = match &carrier {
            Some(r) => r.now.truth(),
            None => CarrierState::at_rest(site.lat_rad, site.lon_rad, site.height_m, c_vn).truth(),
        };
        let schedule = Schedule::new(&cfg.scheme.resolve());
        let internal_rate_hz = cfg.rate_hz * cfg.substeps as f64;
        let gimbal_now = schedule.eval(0.0);
        Self {
            f_n: Vector3::new(0.0, 0.0, site.gravity_mps2),
            site,
            vehicle_level: c_vn == Matrix3::identity(),
            c_vn,
            static_truth,
            gimbal_now,
            interval_inner_rad: gimbal_now.angles.inner_rad,
            hold_until_tick: hold_tick(schedule.eval_hold(0.0).1, internal_rate_hz),
            schedule,
            cursor: Cursor::default(),
            mid_cache: MidCache::EMPTY,
            command: None,
            carrier,
            scenario_static: cfg.carrier.is_static(),
            internal_rate_hz,
            substeps: cfg.substeps as u64,
            dt_s: 1.0 / cfg.rate_hz,
            accel_rps2: cfg.scheme.accel_dps2.to_radians(),
        }
    }

    /// Earth quantities at the site.
    pub(crate) fn site(&self) -> &Site {
        &self.site
    }

    /// The compiled table schedule.
    pub(crate) fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// Table state now (the scheme's; see [`Motion::gimbal_truth`] for the isolated one).
    pub(crate) fn gimbal_now(&self) -> GimbalState {
        self.gimbal_now
    }

    /// The moving carrier, if any, to change it.
    pub(crate) fn carrier_mut(&mut self) -> Option<&mut CarrierRun> {
        self.carrier.as_deref_mut()
    }

    /// The moving carrier, if any.
    pub(crate) fn carrier(&self) -> Option<&CarrierRun> {
        self.carrier.as_deref()
    }

    /// Puts the table on `run` (an external carrier attached after building).
    pub(crate) fn set_carrier(&mut self, run: Box<CarrierRun>) {
        self.carrier = Some(run);
    }

    /// True when the table rides a moving carrier.
    pub(crate) fn is_moving(&self) -> bool {
        self.carrier.is_some()
    }

    /// The carrier's truth now (the site and `[vehicle]` attitude when static).
    pub(crate) fn carrier_truth(&self) -> CarrierTruth {
        match &self.carrier {
            Some(c) => c.state().truth(),
            None => self.static_truth,
        }
    }

    /// The static carrier's truth (set at build; a moving carrier's is asked for separately).
    pub(crate) fn static_truth(&self) -> CarrierTruth {
        self.static_truth
    }

    /// Vehicle mount attitude C_v^n now (on a moving carrier, C_c^n·C_v^c).
    pub(crate) fn vehicle_to_nav(&self) -> Matrix3<f64> {
        match &self.carrier {
            Some(c) => c.c_vn(),
            None => self.c_vn,
        }
    }

    /// Outer gimbal offset of the azimuth isolation at internal tick `tick`, rad.
    fn isolation_offset_rad(&self, tick: u64) -> Option<f64> {
        let i = self.carrier.as_ref()?.isolation.as_ref()?;
        Some(i.offset_rad(tick, self.substeps))
    }

    /// True IMU attitude C_b^n at internal tick `tick` (the current one).
    pub(crate) fn attitude_c_bn(&self, tick: u64) -> Matrix3<f64> {
        let mut a = self.gimbal_now.angles;
        // With azimuth isolation the outer gimbal stands off the scheme by the loop's offset.
        if let Some(o) = self.isolation_offset_rad(tick) {
            a.outer_rad += o;
        }
        body_to_nav(&self.vehicle_to_nav(), a)
    }

    /// The table's true state at internal tick `tick`: the scheme's, with the isolation
    /// loop's outer offset and rate on top.
    pub(crate) fn gimbal_truth(&self, tick: u64) -> GimbalState {
        let mut g = self.gimbal_now;
        if let Some(i) = self.carrier.as_ref().and_then(|c| c.isolation.as_ref()) {
            g.angles.outer_rad += i.offset_rad(tick, self.substeps);
            g.outer_rate_rps += i.rate_rps(tick);
        }
        g
    }

    /// True when the table holds still through internal tick `tick_end` on the static carrier,
    /// so an interval of the dwell can be reused.
    pub(crate) fn holds_through(&self, tick_end: u64) -> bool {
        tick_end <= self.hold_until_tick && self.carrier.is_none()
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

    /// Advances the table and carrier over internal tick `tick` (of length `h_s`); `heading`
    /// asks for north and east in body axes.
    pub(crate) fn tick(&mut self, tick: u64, h_s: f64, heading: bool) -> TickMotion {
        let g0 = self.gimbal_now;
        let (g1, gm) = self.gimbal_at(tick + 1);
        let mut north_east_b = [Vector3::zeros(); 2];
        let (inc, up_b) = if self.carrier.is_some() {
            let r = self.carrier_tick(tick, &g0, &g1, &gm, h_s);
            if heading {
                // At the tick's start (the carrier already at its end): columns 1 and 0 of
                // C_n^b (ENU).
                let c_nb = self.attitude_c_bn(tick).transpose();
                north_east_b = [c_nb.column(1).into_owned(), c_nb.column(0).into_owned()];
            }
            r
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
                h_s,
            );
            if heading {
                north_east_b = [m.c_nb.column(1).into_owned(), m.c_nb.column(0).into_owned()];
            }
            (inc, m.c_nb.column(2).into_owned())
        };
        let moved = g1.angles != g0.angles;
        self.gimbal_now = g1;
        TickMotion {
            inc,
            up_b,
            gimbal_mid: gm,
            north_east_b,
            moved,
        }
    }

    /// Replaces the scheme with a commanded motion from its start tick on.
    pub(crate) fn install_command(&mut self, c: ActiveCommand) {
        self.schedule = Schedule::new(&ResolvedScheme {
            initial: c.initial,
            lead_dwell_s: c.start_tick as f64 / self.internal_rate_hz,
            steps: c.steps.clone(),
            repeat: c.repeat,
            continuous: None,
            accel_rps2: self.accel_rps2,
        });
        self.command = Some(c);
        self.cursor = Cursor::default();
        self.hold_until_tick = 0;
    }

    /// Switches azimuth isolation on or off at internal tick `tick` (see
    /// [`crate::Plant::command_azimuth_isolation`]).
    pub(crate) fn command_azimuth_isolation(&mut self, on: bool, tick: u64) -> Result<(), String> {
        if self.scenario_static {
            // An external carrier (attached after building) keeps no isolation state in the
            // plant's saved state, so it cannot run the loop.
            return Err("azimuth isolation refused: the scenario's carrier is static ([carrier] kind = \"static\"; an external carrier attached to it, such as the carrier FMU, counts as static here), so the plant runs no isolation loop; isolation is allowed only with a moving carrier of the scenario itself: [carrier] kind = \"ship\" or \"trajectory\"".into());
        }
        let c_bn = self.attitude_c_bn(tick);
        let angles = self.gimbal_now.angles;
        let run = self.carrier.as_mut().ok_or(
            "azimuth isolation needs a moving carrier ([carrier] kind = \"ship\" or \"trajectory\")",
        )?;
        run.set_isolation(on, &c_bn, angles, tick);
        self.interval_inner_rad = angles.inner_rad;
        Ok(())
    }

    /// Closes one output interval for the azimuth isolation loop at internal tick `tick`: feeds
    /// it the measured angular increment and the scheme's outer angle.
    pub(crate) fn isolate(&mut self, dtheta_rad: &Vector3<f64>, tick: u64) {
        let (dt, outer) = (self.dt_s, self.gimbal_now.angles.outer_rad);
        let Some(run) = self.carrier.as_mut().filter(|r| r.isolation.is_some()) else {
            return;
        };
        let (lat_rad, height_m, v_n) = run.lat_height_velocity();
        if let Some(i) = run.isolation.as_mut() {
            i.update(dtheta_rad, outer, lat_rad, height_m, &v_n, dt, tick);
        }
    }

    /// What the seeds' own tables need from this (the reference) table over the output interval
    /// that ends at internal tick `tick` ([`ReferenceInterval`]), before its loop is updated;
    /// `None` without the isolation loop.
    pub(crate) fn reference_interval(&mut self, tick: u64) -> Option<ReferenceInterval> {
        let (dt_s, g) = (self.dt_s, self.gimbal_now.angles);
        let start = std::mem::replace(&mut self.interval_inner_rad, g.inner_rad);
        let run = self.carrier.as_mut()?;
        let offset = run.isolation.as_ref()?.interval_offset(dt_s);
        // The inner gimbal mostly rests: its sine and cosine are held.
        let (si, ci) = if start == g.inner_rad {
            run.trig.inner.at(g.inner_rad)
        } else {
            (0.5 * (start + g.inner_rad)).sin_cos()
        };
        let (lat_rad, height_m, v_n) = run.lat_height_velocity();
        Some(ReferenceInterval {
            axis_b: Vector3::new(0.0, si, ci),
            inner_step_rad: g.inner_rad - start,
            offset,
            nav: nav_frame_turn(lat_rad, height_m, &v_n, dt_s),
            scheme_outer_rad: g.outer_rad,
            dt_s,
            tick,
        })
    }

    /// Closes the output interval `r` for the reference table's loop: it takes the table's own
    /// true increment `dtheta_true_rad` (an ideal loop, the same for every seed).
    pub(crate) fn isolate_reference(
        &mut self,
        dtheta_true_rad: &Vector3<f64>,
        r: &ReferenceInterval,
    ) {
        if let Some(i) = self.carrier.as_mut().and_then(|c| c.isolation.as_mut()) {
            i.update_with(dtheta_true_rad, &r.nav, r.scheme_outer_rad, r.dt_s, r.tick);
        }
    }

    /// Writes the commanded motion and the carrier's integrated state.
    pub(crate) fn write(&self, w: &mut Writer) {
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
        if let Some(run) = &self.carrier {
            run.write(w, !self.scenario_static);
        }
    }

    /// Reads what [`Motion::write`] wrote and rebuilds the table and carrier at internal tick
    /// `tick`.
    pub(crate) fn read(&mut self, r: &mut Reader<'_>, tick: u64) -> Result<(), StateError> {
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
        // Derived: the table state at the restored tick; caches start empty.
        self.gimbal_now = self.schedule.eval(tick as f64 / self.internal_rate_hz);
        self.interval_inner_rad = self.gimbal_now.angles.inner_rad;
        self.hold_until_tick = 0;
        self.cursor = Cursor::default();
        let isolation = !self.scenario_static;
        if let Some(run) = self.carrier.as_mut() {
            run.read(r, tick, isolation)?;
        }
        Ok(())
    }
}
