//! The carrier inside the plant: one tick of moving-base increments, and the carrier's part of
//! the state codec.

use nalgebra::{Matrix3, Vector3};

use super::isolation::Isolation;
use super::segment::{PointEnv, TickPoints};
use super::state::CarrierState;
use super::track::TrackPosition;
use super::{Carrier, GL_OFFSETS};
use crate::config::{ConfigError, PlantConfig};
use crate::kinematics::{CarrierPoint, TableIncrements, carrier_points, moving_base_increments};
use crate::plant::Plant;
use crate::state::{Reader, StateError, Writer};
use crate::table::gimbal::body_to_nav;
use crate::table::{GimbalAngles, GimbalState, Schedule};

/// A moving carrier with what the plant needs around it.
#[derive(Clone, Debug)]
pub struct CarrierRun {
    /// The carrier.
    pub carrier: Carrier,
    /// Table mount in the carrier, C_v^c (the `[vehicle]` attitude).
    pub mount: Matrix3<f64>,
    /// IMU position from the carrier reference point, carrier axes, m.
    pub lever_c_m: Vector3<f64>,
    /// Earth rotation and gravity switches.
    pub rotation: bool,
    /// See `rotation`.
    pub gravity: bool,
    /// Carrier state at the current tick.
    pub now: CarrierState,
    /// Last gimbal angles and their C_b^c.
    pub c_bc_cache: (GimbalAngles, Matrix3<f64>),
    /// The azimuth isolation loop (`None`: never switched on, the original moving-base path).
    pub isolation: Option<Isolation>,
}

impl CarrierRun {
    /// Wraps `carrier` with the mount, lever arm and Earth switches of `cfg`.
    pub fn new(mut carrier: Carrier, cfg: &PlantConfig) -> Box<Self> {
        // A ship takes the segment rule (docs/carrier.md) when its motion allows it.
        if let Carrier::Ship(s) = &mut carrier {
            s.enable_segments(PointEnv {
                rotation: cfg.earth.rotation,
                gravity: cfg.earth.gravity,
                lever_c_m: Vector3::from(cfg.carrier.lever_arm_m),
            });
        }
        let now = carrier.state_now();
        let mount = cfg.vehicle.c_vn();
        let isolation = cfg.carrier.azimuth_isolation.then(|| {
            let g0 = Schedule::new(&cfg.scheme.resolve()).eval(0.0).angles;
            let c_bn = body_to_nav(&(now.c_cn * mount), g0);
            Isolation::new(&c_bn, g0.inner_rad, g0.outer_rad, 0.0, 0)
        });
        Box::new(Self {
            isolation,
            carrier,
            mount: cfg.vehicle.c_vn(),
            lever_c_m: Vector3::from(cfg.carrier.lever_arm_m),
            rotation: cfg.earth.rotation,
            gravity: cfg.earth.gravity,
            now,
            c_bc_cache: (GimbalAngles::new(f64::NAN, f64::NAN), Matrix3::identity()),
        })
    }

    /// C_b^c = C_v^c·R_z(outer)·R_x(inner), cached while the gimbals dwell.
    fn body_to_carrier(&mut self, a: GimbalAngles) -> Matrix3<f64> {
        if self.c_bc_cache.0 != a {
            self.c_bc_cache = (a, body_to_nav(&self.mount, a));
        }
        self.c_bc_cache.1
    }

    /// Outer gimbal offset of the azimuth isolation at internal tick `tick` (`ticks` per output
    /// interval), rad (0 without isolation).
    pub fn isolation_rad(&self, tick: u64, ticks: u64) -> f64 {
        self.isolation
            .as_ref()
            .map_or(0.0, |i| i.offset_rad(tick, ticks))
    }

    /// Switches azimuth isolation on (restarting its loop from the body attitude `c_bn`, inner
    /// angle and scheme outer angle now, at internal tick `tick`) or off (the outer offset is
    /// held where it is).
    pub fn set_isolation(
        &mut self,
        on: bool,
        c_bn: &Matrix3<f64>,
        angles: GimbalAngles,
        tick: u64,
    ) {
        let offset = self.isolation_rad(tick, 1);
        match (&mut self.isolation, on) {
            (Some(i), false) => i.active = false,
            (None, false) => {}
            (_, true) => {
                self.isolation = Some(Isolation::new(
                    c_bn,
                    angles.inner_rad,
                    angles.outer_rad,
                    offset,
                    tick,
                ))
            }
        }
    }

    /// C_v^n = C_c^n·C_v^c now.
    pub fn c_vn(&self) -> Matrix3<f64> {
        // The default mount is the identity: no product per tick.
        if self.mount == Matrix3::identity() {
            self.now.c_cn
        } else {
            self.now.c_cn * self.mount
        }
    }
}

impl Plant {
    /// The plant of `cfg` on the moving carrier `carrier` (e.g. a trajectory already in memory),
    /// replacing the one `cfg.carrier` describes.
    pub fn with_carrier(cfg: &PlantConfig, carrier: Carrier) -> Result<Self, Vec<ConfigError>> {
        cfg.validate()?;
        Ok(Self::build(cfg, Some(carrier)))
    }

    /// One tick on the moving carrier from table state `g0` to `g1`: the increments (two-point
    /// Gauss–Legendre on the carrier part, exact angle differences for the gimbal part) and the
    /// up axis in body axes (the mean of the two points').
    pub(crate) fn carrier_tick(
        &mut self,
        g0: &GimbalState,
        g1: &GimbalState,
        gm: &GimbalState,
        h: f64,
    ) -> (TableIncrements, Vector3<f64>) {
        let tick = self.tick;
        let moving = g0.angles != g1.angles;
        let angles: [GimbalAngles; 2] = if moving {
            GL_OFFSETS.map(|f| {
                self.schedule
                    .eval((tick as f64 + f) / self.internal_rate_hz)
                    .angles
            })
        } else {
            [g1.angles; 2]
        };
        let ticks = self.cfg.substeps as f64;
        let run = self.carrier.as_mut().expect("moving carrier");
        // Azimuth isolation: the outer offset at the tick's ends and quadrature points.
        let dt = self.dt_s;
        let iso = run.isolation.as_ref().map(|i| {
            let at = |f: f64| i.offset_at(tick as f64 + f, ticks, dt);
            let rate = |f: f64| i.rate_at(tick as f64 + f, ticks, dt);
            (at(0.0), at(1.0), GL_OFFSETS.map(at), GL_OFFSETS.map(rate))
        });
        let angles = match iso {
            Some((_, _, nodes, _)) => {
                let mut a = angles;
                a.iter_mut().zip(nodes).for_each(|(a, o)| a.outer_rad += o);
                a
            }
            None => angles,
        };
        // One cached C_b^c while the table dwells (both points have the same angles).
        let turning = angles[0] != angles[1];
        let c0 = run.body_to_carrier(angles[0]);
        let c_bc = if turning {
            [c0, run.body_to_carrier(angles[1])]
        } else {
            [c0; 2]
        };
        let pts = match &mut run.carrier {
            Carrier::Ship(s) if s.segment_ticks().is_some() => {
                s.advance_points(turning, &mut run.now)
            }
            _ => {
                let mut nodes = [run.now; 2];
                let end = run.carrier.advance(&mut nodes);
                let pts = carrier_points(
                    &run.carrier,
                    &nodes,
                    run.rotation,
                    run.gravity,
                    &run.lever_c_m,
                );
                let up = |i: usize| nodes[i].c_cn.row(2).transpose();
                run.now = end;
                TickPoints::Nodes([
                    [pts[0].omega_ic_c, pts[0].f_c, up(0)],
                    [pts[1].omega_ic_c, pts[1].f_c, up(1)],
                ])
            }
        };
        let d_outer = g1.angles.outer_rad - g0.angles.outer_rad;
        // No sine while the outer gimbal rests (most ticks): its terms are zero then.
        let (si, ci) = if d_outer == 0.0 {
            (0.0, 0.0)
        } else {
            gm.angles.inner_rad.sin_cos()
        };
        let gimbal = Vector3::new(
            g1.angles.inner_rad - g0.angles.inner_rad,
            si * d_outer,
            ci * d_outer,
        );
        let gimbal = match iso {
            // The offset turns the outer axis, [0, sin i, cos i] in body axes: the exact
            // angle difference while the inner gimbal dwells, else two-point Gauss–Legendre of
            // the offset rate times the axis.
            Some((o0, o1, _, rates)) => {
                if angles[0].inner_rad == angles[1].inner_rad {
                    let (si, ci) = angles[0].inner_rad.sin_cos();
                    gimbal + (o1 - o0) * Vector3::new(0.0, si, ci)
                } else {
                    let v = angles
                        .iter()
                        .zip(rates)
                        .fold(Vector3::zeros(), |v, (a, r)| {
                            let (si, ci) = a.inner_rad.sin_cos();
                            v + r * Vector3::new(0.0, si, ci)
                        });
                    gimbal + 0.5 * h * v
                }
            }
            None => gimbal,
        };
        let (inc, up_b) = match pts {
            // The segment rule while the table dwells: the tick's mean ω_ic^c, f^c and up axis.
            TickPoints::Mean([w, f, up]) => {
                let f_b = c_bc[0].tr_mul(&f);
                let inc = TableIncrements {
                    dtheta_rad: gimbal + h * c_bc[0].tr_mul(&w),
                    dv_mps: h * f_b,
                    f_b_mps2: f_b,
                };
                (inc, c_bc[0].tr_mul(&up))
            }
            TickPoints::Nodes(p) => {
                let pts = p.map(|[w, f, _]| CarrierPoint {
                    omega_ic_c: w,
                    f_c: f,
                });
                let inc = moving_base_increments(&c_bc, &pts, gimbal, h);
                let up_b = 0.5 * (c_bc[0].transpose() * p[0][2] + c_bc[1].transpose() * p[1][2]);
                (inc, up_b)
            }
        };
        self.c_vn = run.c_vn();
        (inc, up_b)
    }

    /// Switches a ship between the segment rule (`true`, the default when its motion allows it)
    /// and the exact per-tick evaluation (`false`, the reference the tests compare with); only
    /// before the first step. Returns the segment length in ticks (`None`: per tick).
    pub fn set_carrier_segments(&mut self, on: bool) -> Result<Option<u64>, String> {
        if self.tick != 0 {
            return Err("the carrier's segment rule is switched before the first step".into());
        }
        let Some(run) = self.carrier.as_mut() else {
            return Ok(None);
        };
        let Carrier::Ship(s) = &mut run.carrier else {
            return Ok(None);
        };
        if on && s.segment_ticks().is_none() {
            s.enable_segments(PointEnv {
                rotation: run.rotation,
                gravity: run.gravity,
                lever_c_m: run.lever_c_m,
            });
        } else if !on && s.segment_ticks().is_some() {
            s.disable_segments();
        }
        let m = s.segment_ticks();
        run.now = run.carrier.state_now();
        self.c_vn = run.c_vn();
        self.truth.carrier = run.now.truth();
        Ok(m)
    }

    /// True when the table rides a moving carrier (ship, trajectory or an external vessel model).
    pub fn moving_carrier(&self) -> bool {
        self.carrier.is_some()
    }

    /// Closes one output interval for the azimuth isolation loop: feeds it the sample just
    /// output (measured increments and encoder reading) and the scheme's commanded outer angle.
    pub(crate) fn isolate(&mut self, s: &crate::plant::ImuSample) {
        let (tick, dt, outer) = (self.tick, self.dt_s, self.gimbal_now.angles.outer_rad);
        let Some(run) = self.carrier.as_mut() else {
            return;
        };
        if let Some(i) = run.isolation.as_mut() {
            let now = &run.now;
            i.update(
                &s.dtheta_rad,
                s.encoder.inner_rad,
                outer,
                now.lat_rad,
                now.height_m,
                &now.v_n,
                dt,
                tick,
            );
        }
    }

    /// Writes the carrier's integrated state (the ship's mean-track position).
    pub(crate) fn write_carrier_state(&self, w: &mut Writer) {
        if let Some(Carrier::Ship(s)) = self.carrier.as_ref().map(|r| &r.carrier) {
            let (tick, p) = s.segment_position().unwrap_or_else(|| s.position());
            w.u64(tick);
            w.f64(p.lat_rad);
            w.f64(p.lon_rad);
        }
        // The isolation loop (a flag, then its state), for the scenario's own moving carrier;
        // an external carrier is attached after a restore and never runs the loop.
        if let Some(run) = self
            .carrier
            .as_ref()
            .filter(|_| !self.cfg.carrier.is_static())
        {
            match &run.isolation {
                Some(i) => {
                    w.u64(1);
                    i.write(w);
                }
                None => w.u64(0),
            }
        }
    }

    /// Reads what [`Plant::write_carrier_state`] wrote and rebuilds the carrier at the plant's
    /// tick (call after the tick is restored).
    pub(crate) fn read_carrier_state(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        let tick = self.tick;
        let Some(run) = self.carrier.as_mut() else {
            return Ok(());
        };
        match &mut run.carrier {
            Carrier::Ship(s) => {
                let t = r.u64()?;
                let pos = TrackPosition {
                    lat_rad: r.f64()?,
                    lon_rad: r.f64()?,
                };
                if s.segment_ticks().is_some() {
                    s.restore_segment(t, pos, tick)
                        .map_err(StateError::Config)?;
                } else {
                    s.set_position(t, pos);
                }
            }
            Carrier::Trajectory { tick: t, .. } => *t = tick,
        }
        if !self.cfg.carrier.is_static() {
            run.isolation = match r.u64()? {
                0 => None,
                _ => Some(Isolation::read(r)?),
            };
        }
        run.now = run.carrier.state_now();
        self.c_vn = run.c_vn();
        self.truth.carrier = run.now.truth();
        Ok(())
    }
}
