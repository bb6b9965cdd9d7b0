//! What the plant keeps for the declared effects: both sensors' compiled plans and the slow
//! signals (node temperatures and their rates), which change only at thermal updates.

use nalgebra::Vector3;

use super::CustomModel;
use super::signals::{self, DTEMP, Frame, SLOTS, TEMP, wrap_deg};
use crate::effects::{AccelSpec, GyroSpec};
use crate::table::GimbalAngles;
use crate::thermal::node;

/// The plant's declared effects.
#[derive(Clone, Debug, PartialEq)]
pub struct Declared {
    /// Gyro effects.
    pub gyro: CustomModel,
    /// Accelerometer effects.
    pub accel: CustomModel,
    /// True node temperatures (°C) and their rates over the last thermal step (K/s); the
    /// fast slots are filled per interval.
    frame: Frame,
    /// Which fast slots the switched-on effects read.
    needs: Needs,
}

/// Which per-interval signals a plan reads (the others are not computed).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Needs {
    /// Up direction.
    pub up: bool,
    /// Body rate or its magnitude.
    pub rate: bool,
    /// Gimbal angles.
    pub gimbal: bool,
    /// Time.
    pub time: bool,
    /// North and east directions in body axes.
    pub heading: bool,
}

impl Needs {
    /// Everything (the diagnosis fills every slot).
    pub const ALL: Needs = Needs {
        up: true,
        rate: true,
        gimbal: true,
        time: true,
        heading: true,
    };

    fn of(models: [&CustomModel; 2]) -> Self {
        let mut n = Needs::default();
        for m in models {
            for e in m.effects().iter().filter(|e| e.enabled) {
                for s in e.signals() {
                    use super::Signal as S;
                    match s {
                        S::Up(_) => n.up = true,
                        S::Rate(_) | S::AbsRate(_) => n.rate = true,
                        S::Outer | S::Inner => n.gimbal = true,
                        S::Time => n.time = true,
                        S::North(_) | S::East(_) => n.heading = true,
                        _ => {}
                    }
                }
            }
        }
        n
    }
}

impl Declared {
    /// Compiles both lists (already validated with the configuration) at the initial node
    /// temperatures; the temperature rates start at 0 (nothing is known before the first
    /// thermal step).
    pub fn new(gyro: &GyroSpec, accel: &AccelSpec, temps_c: &[f64; node::COUNT]) -> Self {
        let gyro = CustomModel::new(&gyro.custom, false).unwrap_or_default();
        let accel = CustomModel::new(&accel.custom, true).unwrap_or_default();
        let mut d = Self {
            needs: Needs::of([&gyro, &accel]),
            gyro,
            accel,
            frame: [0.0; SLOTS],
        };
        d.frame[TEMP..TEMP + node::COUNT].copy_from_slice(temps_c);
        d
    }

    /// Whether any declared effect contributes.
    #[inline]
    pub fn is_active(&self) -> bool {
        self.gyro.is_active() || self.accel.is_active()
    }

    /// Which per-interval signals the switched-on effects read.
    #[inline]
    pub fn needs(&self) -> Needs {
        self.needs
    }

    /// Whether a contribution changes within a dwell (an effect reads `time`).
    pub fn varies_in_dwell(&self) -> bool {
        self.gyro.uses_time() || self.accel.uses_time()
    }

    /// After a thermal step of `h_s` from the current temperatures to `new_c`.
    pub fn thermal_update(&mut self, new_c: &[f64; node::COUNT], h_s: f64) {
        for (n, t) in new_c.iter().enumerate() {
            self.frame[DTEMP + n] = (t - self.frame[TEMP + n]) / h_s;
            self.frame[TEMP + n] = *t;
        }
    }

    /// The temperature rates, K/s (part of the plant state).
    pub fn rates_k_per_s(&self) -> [f64; node::COUNT] {
        std::array::from_fn(|n| self.frame[DTEMP + n])
    }

    /// Restores temperatures and rates (state restore).
    pub fn restore(&mut self, temps_c: &[f64; node::COUNT], rates: &[f64; node::COUNT]) {
        self.frame[TEMP..TEMP + node::COUNT].copy_from_slice(temps_c);
        self.frame[DTEMP..DTEMP + node::COUNT].copy_from_slice(rates);
    }

    /// Gyro and accelerometer increment errors over one interval of `h_s` with true
    /// increments `dtheta`/`dv`, body up direction `up_b`, body north and east directions
    /// `north_east_b` (read only when [`Needs::heading`]), mid gimbal angles `mid` and mid time
    /// `t_mid_s`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn increments(
        &mut self,
        up_b: &Vector3<f64>,
        north_east_b: &[Vector3<f64>; 2],
        dtheta: &Vector3<f64>,
        dv: &Vector3<f64>,
        h_s: f64,
        mid: GimbalAngles,
        t_mid_s: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        fill_fast(
            &mut self.frame,
            self.needs,
            up_b,
            north_east_b,
            dtheta,
            h_s,
            mid,
            t_mid_s,
        );
        let z = Vector3::zeros();
        (
            if self.gyro.is_active() {
                self.gyro.increment_error(&self.frame, h_s, dtheta)
            } else {
                z
            },
            if self.accel.is_active() {
                self.accel.increment_error(&self.frame, h_s, dv)
            } else {
                z
            },
        )
    }
}

/// Fills the per-interval slots of `f` that `needs` asks for: up direction, north and east
/// directions, body rate (from the increment over `h_s`), its magnitude per axis, gimbal
/// angles and time.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn fill_fast(
    f: &mut Frame,
    needs: Needs,
    up_b: &Vector3<f64>,
    north_east_b: &[Vector3<f64>; 2],
    dtheta: &Vector3<f64>,
    h_s: f64,
    mid: GimbalAngles,
    t_mid_s: f64,
) {
    if needs.up {
        f[signals::UP..signals::UP + 3].copy_from_slice(up_b.as_slice());
    }
    if needs.heading {
        f[signals::NORTH..signals::NORTH + 3].copy_from_slice(north_east_b[0].as_slice());
        f[signals::EAST..signals::EAST + 3].copy_from_slice(north_east_b[1].as_slice());
    }
    if needs.rate {
        let to_dps = 180.0 / std::f64::consts::PI / h_s;
        for i in 0..3 {
            let w = dtheta[i] * to_dps;
            f[signals::RATE + i] = w;
            f[signals::ABS_RATE + i] = w.abs();
        }
    }
    if needs.gimbal {
        f[signals::OUTER] = wrap_deg(mid.outer_rad.to_degrees());
        f[signals::INNER] = wrap_deg(mid.inner_rad.to_degrees());
    }
    if needs.time {
        f[signals::TIME] = t_mid_s;
    }
}
