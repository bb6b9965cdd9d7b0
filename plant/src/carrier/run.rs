//! The carrier inside the plant: one tick of moving-base increments, and the carrier's part of
//! the state codec.

use nalgebra::{Matrix3, Vector3};

use super::state::CarrierState;
use super::track::TrackPosition;
use super::{Carrier, GL_OFFSETS};
use crate::config::{ConfigError, PlantConfig};
use crate::kinematics::{TableIncrements, carrier_points, moving_base_increments};
use crate::plant::Plant;
use crate::state::{Reader, StateError, Writer};
use crate::table::gimbal::body_to_nav;
use crate::table::{GimbalAngles, GimbalState};

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
}

impl CarrierRun {
    /// Wraps `carrier` with the mount, lever arm and Earth switches of `cfg`.
    pub fn new(mut carrier: Carrier, cfg: &PlantConfig) -> Box<Self> {
        let now = carrier.state_now();
        Box::new(Self {
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

    /// C_v^n = C_c^n·C_v^c now.
    pub fn c_vn(&self) -> Matrix3<f64> {
        self.now.c_cn * self.mount
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
        let run = self.carrier.as_mut().expect("moving carrier");
        let mut nodes = [run.now; 2];
        let end = run.carrier.advance(&mut nodes);
        let pts = carrier_points(
            &run.carrier,
            &nodes,
            run.rotation,
            run.gravity,
            &run.lever_c_m,
        );
        let c_bc = angles.map(|a| run.body_to_carrier(a));
        run.now = end;
        let (si, ci) = gm.angles.inner_rad.sin_cos();
        let gimbal = Vector3::new(
            g1.angles.inner_rad - g0.angles.inner_rad,
            si * (g1.angles.outer_rad - g0.angles.outer_rad),
            ci * (g1.angles.outer_rad - g0.angles.outer_rad),
        );
        let inc = moving_base_increments(&c_bc, &pts, gimbal, h);
        let up_b = 0.5
            * (c_bc[0].transpose() * nodes[0].c_cn.row(2).transpose()
                + c_bc[1].transpose() * nodes[1].c_cn.row(2).transpose());
        self.c_vn = run.c_vn();
        (inc, up_b)
    }

    /// Writes the carrier's integrated state (the ship's mean-track position).
    pub(crate) fn write_carrier_state(&self, w: &mut Writer) {
        if let Some(Carrier::Ship(s)) = self.carrier.as_ref().map(|r| &r.carrier) {
            let (tick, p) = s.position();
            w.u64(tick);
            w.f64(p.lat_rad);
            w.f64(p.lon_rad);
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
                s.set_position(t, pos);
            }
            Carrier::Trajectory { tick: t, .. } => *t = tick,
        }
        run.now = run.carrier.state_now();
        self.c_vn = run.c_vn();
        self.truth.carrier = run.now.truth();
        Ok(())
    }
}
