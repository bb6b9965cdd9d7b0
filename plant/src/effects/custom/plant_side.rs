//! What the plant keeps for the declared effects: both sensors' compiled plans and the slow
//! signals (node temperatures and their rates), which change only at thermal updates.

use nalgebra::Vector3;

use super::CustomModel;
use super::memory::MemoryState;
#[cfg(doc)]
use super::signals::Family;
use super::signals::{self, DTEMP, FAMILIES, FastInputs, Frame, MotionClocks, SLOTS, TEMP};
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
    /// The signal frame in the first [`SLOTS`] entries: true node temperatures (°C) and their
    /// rates over the last thermal step (K/s), the fast slots filled once per interval; then
    /// the gradients and products the plans compute once per interval (shared by their
    /// terms).
    values: Vec<f64>,
    /// What the gyro and accelerometer effects with memory remember between intervals.
    memory: [MemoryState; 2],
    /// Which fast slots the switched-on effects read.
    needs: Needs,
}

/// Which per-interval signals a plan reads (the others are not computed), by family of the
/// signals table.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Needs {
    /// Time: a needed family [`Family::reads_time`] (the plant computes it only then).
    pub time: bool,
    /// North and east directions in body axes: a needed family [`Family::reads_heading`].
    pub heading: bool,
    /// The table's motion clocks: a needed family [`Family::reads_motion`].
    pub motion: bool,
    /// Bit i: row i of [`FAMILIES`] is filled.
    fast: u32,
}

// One bit per family in `Needs::fast`.
const _: () = assert!(FAMILIES.len() <= u32::BITS as usize);

impl Needs {
    /// Everything (the diagnosis fills every slot).
    pub const ALL: Needs = Needs {
        time: true,
        heading: true,
        motion: true,
        fast: u32::MAX,
    };

    /// Whether row `family` of [`FAMILIES`] is filled.
    #[inline]
    pub fn fills(self, family: usize) -> bool {
        self.fast & (1 << family) != 0
    }

    fn of(models: [&CustomModel; 2]) -> Self {
        let mut n = Needs::default();
        for m in models {
            for e in m.effects().iter().filter(|e| e.enabled) {
                for s in e.signals() {
                    let i = s.parts().0;
                    let f = &FAMILIES[i];
                    if f.fill.is_some() {
                        n.fast |= 1 << i;
                        n.time |= f.reads_time;
                        n.heading |= f.reads_heading;
                        n.motion |= f.reads_motion;
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
            values: vec![0.0; gyro.values_len().max(accel.values_len())],
            memory: [gyro.memory_state(), accel.memory_state()],
            gyro,
            accel,
        };
        d.values[TEMP..TEMP + node::COUNT].copy_from_slice(temps_c);
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

    /// Whether a contribution changes within a dwell (an effect reads `time` or a motion
    /// clock, or has memory).
    pub fn varies_in_dwell(&self) -> bool {
        self.gyro.varies_in_dwell() || self.accel.varies_in_dwell()
    }

    /// Whether an effect has memory (lags to save with the plant's state).
    pub fn has_memory(&self) -> bool {
        self.gyro.has_memory() || self.accel.has_memory()
    }

    /// The lag outputs of both sensors' effects (gyro first), for a saved plant state.
    pub fn lag_ends(&self) -> Vec<f64> {
        self.memory
            .iter()
            .flat_map(|m| m.lag_ends().iter().copied())
            .collect()
    }

    /// Restores what [`Declared::lag_ends`] gave.
    pub fn restore_lag_ends(&mut self, ends: &[f64]) {
        let n = self.memory[0].lag_ends().len();
        self.memory[0].restore_lag_ends(&ends[..n]);
        self.memory[1].restore_lag_ends(&ends[n..]);
    }

    /// After a thermal step of `h_s` from the current temperatures to `new_c`.
    pub fn thermal_update(&mut self, new_c: &[f64; node::COUNT], h_s: f64) {
        for (n, t) in new_c.iter().enumerate() {
            self.values[DTEMP + n] = (t - self.values[TEMP + n]) / h_s;
            self.values[TEMP + n] = *t;
        }
    }

    /// The temperature rates, K/s (part of the plant state).
    pub fn rates_k_per_s(&self) -> [f64; node::COUNT] {
        std::array::from_fn(|n| self.values[DTEMP + n])
    }

    /// Restores temperatures and rates (state restore).
    pub fn restore(&mut self, temps_c: &[f64; node::COUNT], rates: &[f64; node::COUNT]) {
        self.values[TEMP..TEMP + node::COUNT].copy_from_slice(temps_c);
        self.values[DTEMP..DTEMP + node::COUNT].copy_from_slice(rates);
    }

    /// Gyro and accelerometer increment errors over one interval of `h_s` with true
    /// increments `dtheta`/`dv`, body up direction `up_b`, body north and east directions
    /// `north_east_b` (read only when [`Needs::heading`]), mid gimbal angles `mid`, mid time
    /// `t_mid_s` and the table's motion clocks `since` (read only when [`Needs::motion`]).
    /// Advances the effects' memory: call once per interval.
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
        since: MotionClocks,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let frame: &mut Frame = (&mut self.values[..SLOTS])
            .try_into()
            .expect("the value array starts with the frame");
        let x = FastInputs {
            up_b: *up_b,
            north_east_b: *north_east_b,
            dtheta_rad: *dtheta,
            dv_mps: *dv,
            h_s,
            gimbal_mid: mid,
            t_mid_s,
            since_s: since,
        };
        fill_fast(frame, self.needs, &x);
        self.evaluate(dtheta, dv, h_s)
    }

    /// The next interval's increment errors at mid time `t_mid_s` and motion clocks `since`,
    /// every other signal as [`Declared::increments`] last set it: for a held dwell, where only
    /// the clocks and the memory change from one interval to the next (the plant can then
    /// reuse the rest of the interval instead of integrating it again). `dtheta`, `dv` and
    /// `h_s` are those of that call; the result is then the same bits as
    /// [`Declared::increments`] with `t_mid_s` and `since`. Advances the memory.
    #[inline]
    pub fn increments_at(
        &mut self,
        t_mid_s: f64,
        since: MotionClocks,
        dtheta: &Vector3<f64>,
        dv: &Vector3<f64>,
        h_s: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        if self.needs.time {
            self.values[signals::TIME] = t_mid_s;
        }
        if self.needs.motion {
            self.values[signals::SINCE_MOVE] = since.move_s;
            self.values[signals::SINCE_START] = since.start_s;
        }
        self.evaluate(dtheta, dv, h_s)
    }

    /// Both plans over the filled frame.
    #[inline]
    fn evaluate(
        &mut self,
        dtheta: &Vector3<f64>,
        dv: &Vector3<f64>,
        h_s: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let z = Vector3::zeros();
        let [gm, am] = &mut self.memory;
        (
            if self.gyro.is_active() {
                self.gyro.evaluate(&mut self.values, gm, h_s, dtheta)
            } else {
                z
            },
            if self.accel.is_active() {
                self.accel.evaluate(&mut self.values, am, h_s, dv)
            } else {
                z
            },
        )
    }
}

/// Fills the per-interval slots of `f` that `needs` asks for, each family with its own fill
/// from the signals table over the inputs `x`: a new fast signal changes no caller.
#[inline]
pub fn fill_fast(f: &mut Frame, needs: Needs, x: &FastInputs) {
    for (i, family) in FAMILIES.iter().enumerate() {
        if let Some(fill) = family.fill
            && needs.fills(i)
        {
            fill(x, f);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::custom::{Axis, CustomKind, CustomSpec};

    fn spec(name: &str, regressor: &str, unit: &str, kind: CustomKind) -> CustomSpec {
        CustomSpec {
            name: name.into(),
            enabled: true,
            kind,
            regressor: regressor.into(),
            unit: unit.into(),
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef: [0.3, -1.1, 2.5],
        }
    }

    /// A dwell re-evaluated at a later time: the same bits as a full evaluation there, and
    /// not those of the earlier time.
    #[test]
    fn increments_at_a_later_time_equal_a_full_evaluation() {
        let mut s = crate::presets::nav_grade_full();
        s.gyro.custom = vec![
            spec("a", "time*u_x", "s", CustomKind::Bias),
            spec("b", "temp:block*n_y", "K", CustomKind::Bias),
            spec("c", "time^2*w_z", "s^2*deg/s", CustomKind::ScaleFactor),
            spec(
                "f",
                "exp(-since_move/30)*lag(temp:block,300)",
                "K",
                CustomKind::Bias,
            ),
        ];
        s.accel.custom = vec![
            spec("d", "time*gimbal_outer", "s*deg", CustomKind::Bias),
            spec("e", "abs_w_x*e_z", "deg/s", CustomKind::ScaleFactor),
            spec(
                "g",
                "since_start*lag(abs_w_x,2)",
                "s*deg/s",
                CustomKind::Bias,
            ),
        ];
        let temps = [20.0, 31.0, 32.0, 33.0, 28.0, 22.0];
        let mut d = Declared::new(&s.gyro, &s.accel, &temps);
        d.thermal_update(&temps.map(|t| t + 0.25), 1.0);
        let up = Vector3::new(0.1, -0.2, 0.97);
        let ne = [Vector3::new(0.3, 0.9, 0.1), Vector3::new(0.95, -0.3, 0.0)];
        let (dth, dv) = (
            Vector3::new(1e-6, -2e-6, 3e-4),
            Vector3::new(0.01, 0.02, 0.098),
        );
        let mid = GimbalAngles::new(0.7, -1.2);
        let h = 0.01;
        let since = |t: f64| MotionClocks {
            move_s: t - 40.0,
            start_s: t - 45.0,
        };
        let first = d.increments(&up, &ne, &dth, &dv, h, mid, 100.005, since(100.005));
        let again = d.increments_at(250.005, since(250.005), &dth, &dv, h);
        let mut fresh = Declared::new(&s.gyro, &s.accel, &temps);
        fresh.thermal_update(&temps.map(|t| t + 0.25), 1.0);
        // The memory has had one interval in `d`: the same in `fresh` before comparing.
        fresh.increments(&up, &ne, &dth, &dv, h, mid, 100.005, since(100.005));
        let full = fresh.increments(&up, &ne, &dth, &dv, h, mid, 250.005, since(250.005));
        for k in 0..3 {
            assert_eq!(again.0[k].to_bits(), full.0[k].to_bits());
            assert_eq!(again.1[k].to_bits(), full.1[k].to_bits());
        }
        assert_ne!(first, full);
    }
}
