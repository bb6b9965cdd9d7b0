//! The carrier inside the plant: the carrier with its mount, lever arm and Earth switches, the
//! azimuth isolation loop, and the carrier's part of the state codec.

use nalgebra::{Matrix3, Vector3};

use super::Carrier;
use super::carrier_state::CarrierState;
use super::gimbal_trig::GimbalTrig;
use super::isolation::Isolation;
use super::segment::PointEnv;
use super::track::TrackPosition;
use crate::config::PlantConfig;
use crate::state::{Reader, StateError, Writer};
use crate::table::gimbal::body_to_nav;
use crate::table::{GimbalAngles, Schedule};

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
    /// Carrier state at the current tick, except for a ship on the segment rule, whose state
    /// is interpolated only when asked for (see [`CarrierRun::state`]).
    pub(crate) now: CarrierState,
    /// C_c^v, the transpose of the mount C_v^c (`None`: the identity, the default mount).
    pub mount_t: Option<Matrix3<f64>>,
    /// The gimbal angles' sines and cosines held between ticks.
    pub(crate) trig: GimbalTrig,
    /// The azimuth isolation loop (`None`: never switched on, the original moving-base path).
    pub isolation: Option<Isolation>,
}

impl CarrierRun {
    /// Wraps `carrier` with the mount, lever arm and Earth switches of `cfg`.
    pub fn new(mut carrier: Carrier, cfg: &PlantConfig) -> Box<Self> {
        // A ship takes the segment rule (docs/carrier.md) when its motion allows it.
        if let Carrier::Ship(s) = &mut carrier {
            let mount = cfg.vehicle.c_vn();
            s.enable_segments(PointEnv {
                rotation: cfg.earth.rotation,
                gravity: cfg.earth.gravity,
                lever_c_m: Vector3::from(cfg.carrier.lever_arm_m),
                mount_t: (mount != Matrix3::identity()).then(|| mount.transpose()),
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
            mount,
            lever_c_m: Vector3::from(cfg.carrier.lever_arm_m),
            rotation: cfg.earth.rotation,
            gravity: cfg.earth.gravity,
            now,
            mount_t: (mount != Matrix3::identity()).then(|| mount.transpose()),
            trig: Default::default(),
        })
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

    /// The carrier state at the current tick. A ship on the segment rule interpolates it here,
    /// on demand: the increments need only the tick's ω_ic^c, f^c and up axis, so the per-tick
    /// path never builds the full state.
    pub fn state(&self) -> CarrierState {
        match &self.carrier {
            Carrier::Ship(s) => s.segment_state().unwrap_or(self.now),
            _ => self.now,
        }
    }

    /// Latitude (rad), height (m) and velocity (ENU, m/s) now: those fields of
    /// [`CarrierRun::state`], bit for bit, without interpolating the rest.
    pub fn lat_height_velocity(&self) -> (f64, f64, Vector3<f64>) {
        let of_now = || (self.now.lat_rad, self.now.height_m, self.now.v_n);
        match &self.carrier {
            Carrier::Ship(s) => s.segment_lat_height_velocity().unwrap_or_else(of_now),
            _ => of_now(),
        }
    }

    /// C_v^n = C_c^n·C_v^c now.
    pub fn c_vn(&self) -> Matrix3<f64> {
        let c_cn = match &self.carrier {
            Carrier::Ship(s) => s.segment_attitude().unwrap_or(self.now.c_cn),
            _ => self.now.c_cn,
        };
        // The default mount is the identity: no product.
        if self.mount == Matrix3::identity() {
            c_cn
        } else {
            c_cn * self.mount
        }
    }

    /// Switches a ship between the segment rule (`true`) and the exact per-tick evaluation
    /// (`false`); returns the segment length in ticks (`None`: per tick, or not a ship).
    pub(crate) fn set_segments(&mut self, on: bool) -> Option<u64> {
        let Carrier::Ship(s) = &mut self.carrier else {
            return None;
        };
        if on && s.segment_ticks().is_none() {
            s.enable_segments(PointEnv {
                rotation: self.rotation,
                gravity: self.gravity,
                lever_c_m: self.lever_c_m,
                mount_t: self.mount_t,
            });
        } else if !on && s.segment_ticks().is_some() {
            s.disable_segments();
        }
        let m = s.segment_ticks();
        self.now = self.carrier.state_now();
        m
    }

    /// Writes the carrier's integrated state (the ship's mean-track position) and, with
    /// `isolation` (the scenario's own moving carrier), the isolation loop (a flag, then its
    /// state); an external carrier is attached after a restore and never runs the loop.
    pub(crate) fn write(&self, w: &mut Writer, isolation: bool) {
        if let Carrier::Ship(s) = &self.carrier {
            let (tick, p) = s.segment_position().unwrap_or_else(|| s.position());
            w.u64(tick);
            w.f64(p.lat_rad);
            w.f64(p.lon_rad);
        }
        if isolation {
            match &self.isolation {
                Some(i) => {
                    w.u64(1);
                    i.write(w);
                }
                None => w.u64(0),
            }
        }
    }

    /// Reads what [`CarrierRun::write`] wrote and rebuilds the carrier at internal tick `tick`.
    pub(crate) fn read(
        &mut self,
        r: &mut Reader<'_>,
        tick: u64,
        isolation: bool,
    ) -> Result<(), StateError> {
        match &mut self.carrier {
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
        if isolation {
            self.isolation = match r.u64()? {
                0 => None,
                _ => Some(Isolation::read(r)?),
            };
        }
        self.now = self.carrier.state_now();
        Ok(())
    }
}
