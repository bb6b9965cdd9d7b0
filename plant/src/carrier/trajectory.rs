//! The trajectory-file carrier: CSV rows of time, position, ENU velocity and attitude, read with
//! the strict rules of the measurement format (every problem names the file, row and column) and
//! interpolated consistently:
//!
//! * position: per local axis (north, east, up metres from the segment's first row) the cubic
//!   Hermite interpolant of the rows' positions and velocities, so velocity is its derivative
//!   (continuous, equal to the file's at every row) and acceleration its second derivative
//!   (linear within a segment; ∫a over a segment is exactly v_{k+1} − v_k);
//! * attitude: constant rate between rows, C_c^n(t) = C_k·Exp(τ·φ_k), φ_k = Log(C_kᵀ·C_{k+1}),
//!   so ω_nc^c = φ_k/Δt; the angular acceleration (used only by the lever-arm term) is the
//!   linear interpolant of the row values (φ_k − φ_{k−1})/Δt².
//!
//! Plant time 0 is the first row; past the last row the carrier stops there (the last row's
//! position and attitude, at rest). A scenario refuses a file shorter than its run unless
//! `after_end = "hold"` ([`super::spec::AfterEnd`]).
//!
//! Longitude differences between rows are taken the shortest way (a file may wrap from 179.99°
//! to −179.99°, or write a longitude as −360° or 360°), so a track may cross the antimeridian.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use super::carrier_state::CarrierState;
use super::track::wrap_lon_rad;
pub use super::trajectory_error::TrajectoryError;
use crate::earth::radii_of_curvature;
use crate::message::Num;
use crate::units::DEG;

/// Columns, in any order.
pub const COLUMNS: [&str; 11] = [
    "t_s", "lat_deg", "lon_deg", "height_m", "v_e_mps", "v_n_mps", "v_u_mps", "q_cn_w", "q_cn_x",
    "q_cn_y", "q_cn_z",
];

/// Largest |‖q‖ − 1| accepted.
pub const QUAT_NORM_TOL: f64 = 1e-6;
/// Relative tolerance of the time step.
pub const STEP_REL_TOL: f64 = 1e-6;
/// A row's displacement may differ from the trapezoidal integral of the two rows' velocities by
/// this many metres plus [`JUMP_REL_TOL`] of the displacement.
pub const JUMP_ABS_TOL_M: f64 = 0.1;
/// See [`JUMP_ABS_TOL_M`].
pub const JUMP_REL_TOL: f64 = 0.01;

/// One row.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Row {
    lat_rad: f64,
    lon_rad: f64,
    height_m: f64,
    v_n: Vector3<f64>,
    q: UnitQuaternion<f64>,
}

/// A parsed, checked trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    t0_s: f64,
    dt_s: f64,
    rows: Vec<Row>,
    /// Rotation vector φ_k of each segment, carrier axes, rad.
    phi: Vec<Vector3<f64>>,
}

/// Local metres per radian of latitude and longitude at a row.
fn metres_per_rad(lat: f64, h: f64) -> (f64, f64) {
    let (rm, rn) = radii_of_curvature(lat);
    (rm + h, (rn + h) * lat.cos())
}

impl Trajectory {
    /// Parses the CSV text `text` (named `source_name` in errors).
    pub fn parse(text: &str, source_name: &str) -> Result<Self, TrajectoryError> {
        let err = |row: usize, column: &str, message: String| TrajectoryError {
            source_name: source_name.into(),
            row,
            column: column.into(),
            message,
        };
        let mut lines = text
            .lines()
            .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let header: Vec<String> = lines
            .next()
            .ok_or_else(|| err(0, "", "empty file: expected a header row".into()))?
            .split(',')
            .map(|s| s.trim().to_string())
            .collect();
        let mut idx = [usize::MAX; 11];
        for (i, h) in header.iter().enumerate() {
            let Some(c) = COLUMNS.iter().position(|c| c == h) else {
                return Err(err(0, h, format!("unknown column; expected {COLUMNS:?}")));
            };
            if idx[c] != usize::MAX {
                return Err(err(0, h, "duplicate column".into()));
            }
            idx[c] = i;
        }
        if let Some(c) = idx.iter().position(|&i| i == usize::MAX) {
            return Err(err(0, COLUMNS[c], "missing required column".into()));
        }
        let mut times = Vec::new();
        let mut rows: Vec<Row> = Vec::new();
        for (r, line) in lines.enumerate() {
            let row = r + 1;
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() < header.len() {
                // A short row: the first column it lacks.
                return Err(err(
                    row,
                    &header[fields.len()],
                    format!(
                        "missing: the row ends before this column ({} fields, the header has {})",
                        fields.len(),
                        header.len()
                    ),
                ));
            }
            if fields.len() > header.len() {
                return Err(err(
                    row,
                    "",
                    format!(
                        "{} fields, the header has {} (the last is {})",
                        fields.len(),
                        header.len(),
                        crate::message::quote(&header[header.len() - 1])
                    ),
                ));
            }
            let mut v = [0.0; 11];
            for (c, x) in v.iter_mut().enumerate() {
                let f = fields[idx[c]];
                *x = f
                    .parse::<f64>()
                    .map_err(|_| err(row, COLUMNS[c], format!("not a number: {f:?}")))?;
                if !x.is_finite() {
                    return Err(err(
                        row,
                        COLUMNS[c],
                        format!("{} is not a finite number", Num(*x)),
                    ));
                }
            }
            let lat_max = super::track::MAX_LAT_DEG;
            if !(-lat_max..=lat_max).contains(&v[1]) {
                return Err(err(
                    row,
                    "lat_deg",
                    format!("expected [-{lat_max}, {lat_max}], got {}", Num(v[1])),
                ));
            }
            let q = Quaternion::new(v[7], v[8], v[9], v[10]);
            if (q.norm() - 1.0).abs() > QUAT_NORM_TOL {
                return Err(err(
                    row,
                    "q_cn_w",
                    format!(
                        "quaternion (q_cn_w, q_cn_x, q_cn_y, q_cn_z) has norm {}, expected 1 within {QUAT_NORM_TOL}",
                        Num(q.norm())
                    ),
                ));
            }
            let mut q = UnitQuaternion::new_normalize(q);
            // q and −q are one attitude: keep consecutive rows in one hemisphere.
            if rows.last().is_some_and(|p| p.q.coords.dot(&q.coords) < 0.0) {
                q = UnitQuaternion::new_unchecked(-q.into_inner());
            }
            times.push(v[0]);
            rows.push(Row {
                lat_rad: v[1] * DEG,
                lon_rad: v[2] * DEG,
                height_m: v[3],
                v_n: Vector3::new(v[4], v[5], v[6]),
                q,
            });
        }
        if rows.len() < 2 {
            return Err(err(
                0,
                "",
                format!("need at least two data rows, got {}", rows.len()),
            ));
        }
        let dt = times[1] - times[0];
        if dt <= 0.0 {
            return Err(err(
                2,
                "t_s",
                format!(
                    "time not increasing: {} after {}",
                    Num(times[1]),
                    Num(times[0])
                ),
            ));
        }
        for k in 1..rows.len() {
            let d = times[k] - times[k - 1];
            if (d - dt).abs() > STEP_REL_TOL * dt {
                return Err(err(
                    k + 1,
                    "t_s",
                    format!(
                        "time step {} s, expected the file's uniform step {} s",
                        Num(d),
                        Num(dt)
                    ),
                ));
            }
            let (a, b) = (&rows[k - 1], &rows[k]);
            let (mn, me) = metres_per_rad(a.lat_rad, a.height_m);
            let moved = [
                (wrap_lon_rad(b.lon_rad - a.lon_rad) * me, "lon_deg", 0),
                ((b.lat_rad - a.lat_rad) * mn, "lat_deg", 1),
                (b.height_m - a.height_m, "height_m", 2),
            ];
            for (d_m, col, i) in moved {
                let expect = 0.5 * (a.v_n[i] + b.v_n[i]) * dt;
                if (d_m - expect).abs() > JUMP_ABS_TOL_M + JUMP_REL_TOL * expect.abs() {
                    return Err(err(
                        k + 1,
                        col,
                        format!(
                            "position jump: moved {:.3} m since the previous row, the velocities give {:.3} m (tolerance {JUMP_ABS_TOL_M} m + {} %)",
                            Num(d_m),
                            Num(expect),
                            JUMP_REL_TOL * 100.0
                        ),
                    ));
                }
            }
        }
        let phi = rows
            .windows(2)
            .map(|w| (w[0].q.inverse() * w[1].q).scaled_axis())
            .collect();
        Ok(Self {
            t0_s: times[0],
            dt_s: dt,
            rows,
            phi,
        })
    }

    /// Reads and parses `path` (the plant's one file read, done when it is built). Lines are
    /// bounded and must be text ([`super::trajectory_text`]), so `/dev/zero` or a binary file is
    /// refused at its first line, in bounded memory.
    pub fn read(path: &str) -> Result<Self, TrajectoryError> {
        let file = std::fs::File::open(path).map_err(|e| TrajectoryError {
            source_name: path.into(),
            row: 0,
            column: String::new(),
            message: format!("cannot read: {e}"),
        })?;
        let text = super::trajectory_text::read_text(file, path)?;
        Self::parse(&text, path)
    }

    /// Row interval, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Time of the first row in the file, s (plant time 0).
    pub fn t0_s(&self) -> f64 {
        self.t0_s
    }

    /// Plant time of the last row, s.
    pub fn end_s(&self) -> f64 {
        (self.rows.len() - 1) as f64 * self.dt_s
    }

    /// Angular acceleration at row k (the lever-arm term only).
    fn alpha_row(&self, k: usize) -> Vector3<f64> {
        let n = self.phi.len();
        let (a, b) = (
            self.phi[k.saturating_sub(1).min(n - 1)],
            self.phi[k.min(n - 1)],
        );
        (b - a) / (self.dt_s * self.dt_s)
    }

    /// The carrier state at plant time `t_s` (see the module notes).
    pub fn state_at(&self, t_s: f64) -> CarrierState {
        let n = self.rows.len();
        let x = (t_s / self.dt_s).max(0.0);
        // Past the last row (beyond rounding of the time): stopped there.
        if x > (n - 1) as f64 + 1e-6 {
            let r = &self.rows[n - 1];
            return CarrierState::at_rest(
                r.lat_rad,
                r.lon_rad,
                r.height_m,
                r.q.to_rotation_matrix().into_inner(),
            );
        }
        let (k, tau) = if x >= (n - 1) as f64 {
            (n - 2, 1.0)
        } else {
            let k = x.floor() as usize;
            (k, x - k as f64)
        };
        let (a, b) = (&self.rows[k], &self.rows[k + 1]);
        let h = self.dt_s;
        let (mn, me) = metres_per_rad(a.lat_rad, a.height_m);
        let p1 = Vector3::new(
            wrap_lon_rad(b.lon_rad - a.lon_rad) * me,
            (b.lat_rad - a.lat_rad) * mn,
            b.height_m - a.height_m,
        );
        // Cubic Hermite on [0, 1]: p(τ) = h01·p1 + h10·h·v0 + h11·h·v1 (p0 = 0).
        let (t2, t3) = (tau * tau, tau * tau * tau);
        let (h10, h01, h11) = (t3 - 2.0 * t2 + tau, -2.0 * t3 + 3.0 * t2, t3 - t2);
        let (d10, d01, d11) = (
            3.0 * t2 - 4.0 * tau + 1.0,
            -6.0 * t2 + 6.0 * tau,
            3.0 * t2 - 2.0 * tau,
        );
        let (e10, e01, e11) = (6.0 * tau - 4.0, -12.0 * tau + 6.0, 6.0 * tau - 2.0);
        let p = h01 * p1 + (h10 * a.v_n + h11 * b.v_n) * h;
        let v = d01 * p1 / h + d10 * a.v_n + d11 * b.v_n;
        let acc = (e01 * p1 / h + e10 * a.v_n + e11 * b.v_n) / h;
        let q = a.q * UnitQuaternion::from_scaled_axis(self.phi[k] * tau);
        let alpha = (1.0 - tau) * self.alpha_row(k) + tau * self.alpha_row(k + 1);
        CarrierState {
            lat_rad: a.lat_rad + p.y / mn,
            lon_rad: a.lon_rad + p.x / me,
            height_m: a.height_m + p.z,
            v_n: v,
            a_n: acc,
            c_cn: q.to_rotation_matrix().into_inner(),
            omega_nc_c: self.phi[k] / h,
            alpha_nc_c: alpha,
        }
    }
}
