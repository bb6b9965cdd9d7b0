//! Declared effects (`[[sensor.gyro.custom]]`, `[[sensor.accel.custom]]`) as diagnosis
//! candidates: their identity in an [`crate::Effect`], whether a measured history can form
//! their signals, and the signal frame of each row from what the log measured (temperature
//! readings and their time derivative, encoder angles, the kinematic rate), so the model's
//! declared effects are replayed and tested with the plant's own compiled regressors.

use rins_plant::PlantConfig;
use rins_plant::effects::custom::signals::{self, Frame, SLOTS, Signal};
use rins_plant::effects::custom::{
    CustomKind, CustomModel, FastInputs, MotionClocks, Needs, custom_coefficient_key, fill_fast,
};
use rins_plant::table::GimbalAngles;
use rins_plant::thermal::node;
use rins_plant::units::{DPH, PPM, UG};

use crate::history::{Attitude, History};
use crate::rows::RowsInfo;

/// Half-width of the central difference that gives a temperature reading's rate, s: wide
/// enough to average a quantised, held housekeeping channel, narrow against thermal time
/// constants (tens of minutes).
pub const RATE_HALF_SPAN_S: f64 = 30.0;

/// A declared effect of the model, by sensor and position in its list (Copy, so it can sit in
/// an [`crate::Effect`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CustomRef {
    /// An accelerometer effect (else gyro).
    pub accel: bool,
    /// Index in `sensor.{gyro,accel}.custom`.
    pub index: u16,
    /// Bias or scale factor.
    pub kind: CustomKind,
    /// Axes it acts on, bit i for axis i.
    pub axes: u8,
    name: [u8; 32],
    len: u8,
}

impl CustomRef {
    /// A reference to an effect not (yet) in the model's list: a discovered term that would be
    /// declared at `index` (`name` is cut to 32 bytes).
    pub fn new(accel: bool, index: u16, kind: CustomKind, axes: u8, name: &str) -> Self {
        let mut buf = [0u8; 32];
        let n = name.len().min(32);
        buf[..n].copy_from_slice(&name.as_bytes()[..n]);
        Self {
            accel,
            index,
            kind,
            axes,
            name: buf,
            len: n as u8,
        }
    }

    /// The declared name.
    pub fn name(&self) -> &str {
        std::str::from_utf8(&self.name[..self.len as usize]).unwrap_or("?")
    }

    /// SI size of one file unit of the coefficient (°/h, µg, ppm).
    pub fn file_unit_si(&self) -> f64 {
        match (self.kind, self.accel) {
            (CustomKind::Bias, false) => DPH,
            (CustomKind::Bias, true) => UG,
            (CustomKind::ScaleFactor, _) => PPM,
        }
    }

    /// Scenario key of the coefficient on `axis`.
    pub fn coefficient_key(&self, axis: usize) -> String {
        custom_coefficient_key(self.accel, self.index as usize, axis)
    }

    /// Scenario key of the switch.
    pub fn enabled_key(&self) -> String {
        let s = if self.accel { "accel" } else { "gyro" };
        format!("sensor.{s}.custom[{}].enabled", self.index)
    }
}

/// The declared effects of `model` (gyro first), as references.
pub fn declared(model: &PlantConfig) -> Vec<CustomRef> {
    let mk = |accel: bool, list: &[rins_plant::effects::CustomSpec]| -> Vec<CustomRef> {
        list.iter()
            .enumerate()
            .map(|(i, s)| {
                let mut name = [0u8; 32];
                let n = s.name.len().min(32);
                name[..n].copy_from_slice(&s.name.as_bytes()[..n]);
                CustomRef {
                    accel,
                    index: i as u16,
                    kind: s.kind,
                    axes: s.axes.iter().fold(0, |m, a| m | 1 << a.index()),
                    name,
                    len: n as u8,
                }
            })
            .collect()
    };
    let mut v = mk(false, &model.sensor.gyro.custom);
    v.extend(mk(true, &model.sensor.accel.custom));
    v
}

/// Why data with `info` cannot form the signals of effect `index` of `m`, if they cannot.
pub fn unavailable(m: &CustomModel, index: usize, info: &RowsInfo) -> Option<String> {
    let e = &m.effects()[index];
    for s in e.signals() {
        if s.family().needs_gimbal && !info.gimbal {
            return Some(
                "needs gimbal angles (outer_deg, inner_deg), the log has quaternions".into(),
            );
        }
        for axis in 0..3 {
            for n in s.nodes(m.is_accel(), axis) {
                if n == node::BOARD {
                    return Some(
                        "needs the board temperature, which the log does not carry".into(),
                    );
                }
                if n == node::HOUSING && !info.housing {
                    return Some("needs a housing temperature (temp_housing_c)".into());
                }
            }
        }
    }
    None
}

/// The measured temperature of node `n` on row `k` (board: not measured, 0).
fn reading(h: &History, n: usize, k: usize) -> f64 {
    match n {
        node::GYRO_X..=3 => h.gyro_temp_c[n - node::GYRO_X][k],
        node::ACCEL => h.accel_temp_c[k],
        node::HOUSING => h.housing_temp_c.as_ref().map_or(0.0, |t| t[k]),
        _ => 0.0,
    }
}

/// Per-row slow signals of a history: readings and, for the nodes a declared effect
/// differentiates, their central-difference rates within each segment; and the table's motion
/// clocks per row.
pub struct RowSignals {
    rates: [Option<Vec<f64>>; node::COUNT],
    run_start_s: Vec<f64>,
    since: Vec<MotionClocks>,
}

impl RowSignals {
    /// Prepares the rates the declared effects of `models` read, on chunk `h` of data whose
    /// runs start at `run_start_s` ([`RowsInfo::run_start_s`]).
    pub fn new(models: [&CustomModel; 2], h: &History, run_start_s: &[f64]) -> Self {
        let mut need = [false; node::COUNT];
        for m in models {
            for e in m.effects() {
                for s in e.signals() {
                    if let Signal::TempRate(r) = s {
                        for axis in 0..3 {
                            need[r.resolve(m.is_accel(), axis)] = true;
                        }
                    }
                }
            }
        }
        let rates = std::array::from_fn(|n| need[n].then(|| rate_of(h, n)));
        Self {
            rates,
            since: motion_clocks(h, run_start_s),
            run_start_s: run_start_s.to_vec(),
        }
    }

    /// Prepares the rates of every measured node (the gyro blocks, the accelerometer cluster
    /// and, when measured, the housing): the signals discovery ([`crate::discover`]) reads.
    pub fn all(h: &History, run_start_s: &[f64]) -> Self {
        let mut s = Self::new(
            [&CustomModel::default(), &CustomModel::default()],
            h,
            run_start_s,
        );
        for n in node::GYRO_X..node::COUNT {
            if n != node::HOUSING || h.housing_temp_c.is_some() {
                s.rates[n] = Some(rate_of(h, n));
            }
        }
        s
    }

    /// The frame of row `k` (interval `dt_s`, true increments `dtheta` and `dv`, mid attitude
    /// C_n^b `c_nb`: its columns are east, north and up in body axes): the readings, then
    /// every fast signal from the same inputs the plant fills them from.
    pub fn frame(
        &self,
        h: &History,
        k: usize,
        dt_s: f64,
        c_nb: &nalgebra::Matrix3<f64>,
        dtheta: &nalgebra::Vector3<f64>,
        dv: &nalgebra::Vector3<f64>,
    ) -> Frame {
        let mut f = [0.0; SLOTS];
        for n in 0..node::COUNT {
            f[signals::TEMP + n] = reading(h, n, k);
            if let Some(r) = &self.rates[n] {
                f[signals::DTEMP + n] = r[k];
            }
        }
        let gimbal_mid = match &h.attitude {
            Attitude::Gimbal {
                outer_rad,
                inner_rad,
            } => GimbalAngles::new(
                0.5 * (outer_rad[k - 1] + outer_rad[k]),
                0.5 * (inner_rad[k - 1] + inner_rad[k]),
            ),
            Attitude::Quaternion(_) => GimbalAngles::new(0.0, 0.0),
        };
        let x = FastInputs {
            up_b: c_nb.column(2).into_owned(),
            north_east_b: [c_nb.column(1).into_owned(), c_nb.column(0).into_owned()],
            dtheta_rad: *dtheta,
            dv_mps: *dv,
            h_s: dt_s,
            gimbal_mid,
            t_mid_s: h.t_s[k] - 0.5 * dt_s - self.run_start_s[h.run[k] as usize],
            since_s: self.since[k],
        };
        fill_fast(&mut f, Needs::ALL, &x);
        f
    }
}

/// Whether the table turned during row `k` of `h` (its attitude at the row's end differs from
/// the one before): the replay's definition of a moving row.
pub fn row_moved(h: &History, k: usize) -> bool {
    match &h.attitude {
        Attitude::Gimbal {
            outer_rad,
            inner_rad,
        } => outer_rad[k] != outer_rad[k - 1] || inner_rad[k] != inner_rad[k - 1],
        Attitude::Quaternion(q) => {
            let (a, b) = (q[k - 1], q[k]);
            // |⟨a, b⟩| = cos(angle/2): the same 1e-12 rad threshold the replay's kinematics use.
            let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]).abs();
            let na = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]).sqrt();
            let nb = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2] + b[3] * b[3]).sqrt();
            2.0 * (dot / (na * nb)).min(1.0).acos() > 1e-12
        }
    }
}

/// The table's motion clocks at each row's middle, as the plant defines them
/// (docs/effects.md): `since_move` is 0 on a row in which the table turned, else the time
/// since the end of the last such row; `since_start` the time since the start of the first row
/// of the last move. Before the first move of a segment both count from the run's start when
/// the segment begins the run (within two rows of it), else from the segment's first row (the
/// table's state before a gap in the log is not known).
fn motion_clocks(h: &History, run_start_s: &[f64]) -> Vec<MotionClocks> {
    let mut out = vec![MotionClocks::default(); h.len()];
    for seg in &h.segments {
        if seg.len() < 2 {
            continue;
        }
        let t0 = h.t_s[seg.start];
        let run_start = run_start_s[h.run[seg.start] as usize];
        let row = h.t_s[seg.start + 1] - t0;
        let origin = if t0 - run_start <= 2.0 * row {
            run_start
        } else {
            t0
        };
        let (mut stop, mut start, mut moving) = (origin, origin, false);
        for k in seg.start + 1..seg.end {
            let moved = row_moved(h, k);
            if moved && !moving {
                start = h.t_s[k - 1];
            } else if !moved && moving {
                stop = h.t_s[k - 1];
            }
            moving = moved;
            let mid = 0.5 * (h.t_s[k - 1] + h.t_s[k]);
            out[k] = MotionClocks {
                move_s: if moving { 0.0 } else { mid - stop },
                start_s: mid - start,
            };
        }
    }
    out
}

/// Central-difference rate of node `n`'s reading over ±[`RATE_HALF_SPAN_S`] within each
/// segment (one-sided at the ends), K/s.
fn rate_of(h: &History, n: usize) -> Vec<f64> {
    let mut out = vec![0.0; h.len()];
    for seg in &h.segments {
        let (mut a, mut b) = (seg.start, seg.start);
        for k in seg.clone() {
            let t = h.t_s[k];
            while h.t_s[a] < t - RATE_HALF_SPAN_S {
                a += 1;
            }
            while b + 1 < seg.end && h.t_s[b + 1] <= t + RATE_HALF_SPAN_S {
                b += 1;
            }
            let span = h.t_s[b] - h.t_s[a];
            out[k] = if span > 0.0 {
                (reading(h, n, b) - reading(h, n, a)) / span
            } else {
                0.0
            };
        }
    }
    out
}

/// The model's declared effects, compiled.
pub(crate) struct Declared {
    pub(crate) gyro: CustomModel,
    pub(crate) accel: CustomModel,
    pub(crate) refs: Vec<CustomRef>,
    pub(crate) any: bool,
}

impl Declared {
    pub(crate) fn new(model: &PlantConfig) -> Self {
        // The model was validated when it was loaded; an invalid list contributes nothing.
        let gyro = CustomModel::new(&model.sensor.gyro.custom, false).unwrap_or_default();
        let accel = CustomModel::new(&model.sensor.accel.custom, true).unwrap_or_default();
        let refs = declared(model);
        Self {
            any: !refs.is_empty(),
            gyro,
            accel,
            refs,
        }
    }

    /// The per-row signals the declared effects read on chunk `h` of data whose runs start at
    /// `run_start_s`.
    pub(crate) fn signals(&self, h: &History, run_start_s: &[f64]) -> RowSignals {
        RowSignals::new([&self.gyro, &self.accel], h, run_start_s)
    }

    pub(crate) fn model(&self, accel: bool) -> &CustomModel {
        if accel { &self.accel } else { &self.gyro }
    }
}
