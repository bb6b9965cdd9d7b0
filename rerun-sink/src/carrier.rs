//! A moving carrier in the recording: its attitude (a hull with its axes in the 3D table scene,
//! and the table base riding on it), and its track in a local ENU frame around the start
//! (metres, a 3D view of its own: a ship's kilometres would dwarf the one-metre table). Sampled
//! at the bucket rate, sent as column chunks like the series.

use anyhow::Result;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use rerun::{
    Arrows3D, Boxes3D, Color, FillMode, LineStrips3D, Points3D, RecordingStream, Transform3D,
    ViewCoordinates,
};
use rins_plant::carrier::CarrierTruth;
use rins_plant::earth::{WGS84_A_M, WGS84_E2};

use crate::scene::BASE;
use crate::series::{FLUSH_ROWS, SIM_TIME, STEP};

/// The carrier frame (x starboard, y bow, z up) in the table scene: rotation q_c^n.
pub const CARRIER: &str = "world/carrier";
/// Root of the track view (local ENU at the carrier's first logged position, m, Z up).
pub const TRACK: &str = "track";
/// The track so far, one line strip through the bucket-end positions.
pub const TRACK_PATH: &str = "track/path";
/// The carrier's position at each bucket end.
pub const TRACK_SHIP: &str = "track/ship";

fn quat(q: &UnitQuaternion<f64>) -> rerun::datatypes::Quaternion {
    rerun::datatypes::Quaternion::from_xyzw([q.i as f32, q.j as f32, q.k as f32, q.w as f32])
}

/// Earth-centred, Earth-fixed position of a WGS-84 point, m.
pub fn ecef_m(lat_rad: f64, lon_rad: f64, height_m: f64) -> Vector3<f64> {
    let (sl, cl) = lat_rad.sin_cos();
    let (so, co) = lon_rad.sin_cos();
    let n = WGS84_A_M / (1.0 - WGS84_E2 * sl * sl).sqrt();
    Vector3::new(
        (n + height_m) * cl * co,
        (n + height_m) * cl * so,
        (n * (1.0 - WGS84_E2) + height_m) * sl,
    )
}

/// Rows: east, north and up at (lat, lon) in ECEF axes (C_e^n).
fn ecef_to_enu(lat_rad: f64, lon_rad: f64) -> Matrix3<f64> {
    let (sl, cl) = lat_rad.sin_cos();
    let (so, co) = lon_rad.sin_cos();
    Matrix3::new(-so, co, 0.0, -sl * co, -sl * so, cl, cl * co, cl * so, sl)
}

/// The local ENU frame of the track: origin and orientation at one point.
#[derive(Clone, Copy, Debug)]
pub struct LocalEnu {
    origin_ecef_m: Vector3<f64>,
    c_en: Matrix3<f64>,
}

impl LocalEnu {
    /// The tangent frame at `c`'s position.
    pub fn at(c: &CarrierTruth) -> Self {
        Self {
            origin_ecef_m: ecef_m(c.lat_rad, c.lon_rad, c.height_m),
            c_en: ecef_to_enu(c.lat_rad, c.lon_rad),
        }
    }

    /// `c`'s position in this frame (exact: through ECEF, so a long track curves down with the
    /// Earth, about d²/(2R) at distance d), m.
    pub fn enu_m(&self, c: &CarrierTruth) -> Vector3<f64> {
        self.c_en * (ecef_m(c.lat_rad, c.lon_rad, c.height_m) - self.origin_ecef_m)
    }
}

/// Logs the parts that never change: the hull and carrier axes under [`CARRIER`], the track
/// view's axes.
pub fn log_static(rec: &RecordingStream) -> Result<()> {
    rec.log_static(
        "world/carrier/hull",
        &Boxes3D::from_centers_and_half_sizes([[0.0, 0.0, -1.6]], [[1.2, 3.0, 0.3]])
            .with_colors([Color::from_rgb(90, 120, 150)])
            .with_fill_mode(FillMode::MajorWireframe)
            .with_labels(["carrier (bow +y)"]),
    )?;
    rec.log_static(
        "world/carrier/axes",
        &Arrows3D::from_vectors([[2.2, 0.0, 0.0], [0.0, 3.6, 0.0], [0.0, 0.0, 2.2]])
            .with_origins([[0.0, 0.0, -1.6]; 3])
            .with_colors([Color::from_rgb(120, 160, 200); 3])
            .with_labels(["starboard", "bow", "up"]),
    )?;
    rec.log_static(TRACK, &ViewCoordinates::RIGHT_HAND_Z_UP())?;
    Ok(())
}

/// The carrier's poses at each bucket end, buffered and sent in column chunks.
pub struct CarrierColumns {
    /// C_v^c, the table mount in the carrier.
    mount: UnitQuaternion<f64>,
    frame: Option<LocalEnu>,
    steps: Vec<i64>,
    nanos: Vec<i64>,
    carrier: Vec<rerun::datatypes::Quaternion>,
    base: Vec<rerun::datatypes::Quaternion>,
    positions: Vec<[f32; 3]>,
    /// The whole track so far (re-logged as one strip at each flush).
    path: Vec<[f32; 3]>,
}

impl CarrierColumns {
    /// Columns for a table mounted with C_v^c = `mount` (the `[vehicle]` attitude).
    pub fn new(mount: &Matrix3<f64>) -> Self {
        Self {
            mount: UnitQuaternion::from_matrix(mount),
            frame: None,
            steps: Vec::new(),
            nanos: Vec::new(),
            carrier: Vec::new(),
            base: Vec::new(),
            positions: Vec::new(),
            path: Vec::new(),
        }
    }

    /// Adds the carrier at output sample `step`, time `t_ns`. The first call fixes the track's
    /// local ENU frame at the carrier's position then.
    pub fn push(
        &mut self,
        rec: &RecordingStream,
        step: u64,
        t_ns: i64,
        c: &CarrierTruth,
    ) -> Result<()> {
        let frame = *self.frame.get_or_insert_with(|| LocalEnu::at(c));
        let p = frame.enu_m(c);
        let p = [p.x as f32, p.y as f32, p.z as f32];
        self.steps.push(step as i64);
        self.nanos.push(t_ns);
        self.carrier.push(quat(&c.q_cn));
        // The table base rides on the carrier: C_v^n = C_c^n·C_v^c.
        self.base.push(quat(&(c.q_cn * self.mount)));
        self.positions.push(p);
        self.path.push(p);
        if self.steps.len() >= FLUSH_ROWS {
            self.flush(rec)?;
        }
        Ok(())
    }

    /// Sends the buffered poses and the track so far (as of the last buffered step).
    pub fn flush(&mut self, rec: &RecordingStream) -> Result<()> {
        let n = self.steps.len();
        let Some(&last_step) = self.steps.last() else {
            return Ok(());
        };
        let last_ns = *self.nanos.last().expect("as many as steps");
        let index = || {
            [
                rerun::TimeColumn::new_sequence(STEP, self.steps.iter().copied()),
                rerun::TimeColumn::new_duration_nanos(SIM_TIME, self.nanos.iter().copied()),
            ]
        };
        let ones = || std::iter::repeat_n(1, n);
        let carrier = Transform3D::update_fields()
            .with_many_quaternion(self.carrier.drain(..))
            .columns(ones())?;
        rec.send_columns(CARRIER, index(), carrier)?;
        let base = Transform3D::update_fields()
            .with_many_quaternion(self.base.drain(..))
            .columns(ones())?;
        rec.send_columns(BASE, index(), base)?;
        let ship = Points3D::update_fields()
            .with_positions(self.positions.drain(..))
            .columns(ones())?;
        rec.send_columns(TRACK_SHIP, index(), ship)?;
        let path = LineStrips3D::new([self.path.clone()])
            .with_colors([Color::from_rgb(40, 110, 200)])
            .columns([1])?;
        rec.send_columns(
            TRACK_PATH,
            [
                rerun::TimeColumn::new_sequence(STEP, [last_step]),
                rerun::TimeColumn::new_duration_nanos(SIM_TIME, [last_ns]),
            ],
            path,
        )?;
        self.steps.clear();
        self.nanos.clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(lat_deg: f64, lon_deg: f64, h: f64) -> CarrierTruth {
        CarrierTruth {
            lat_rad: lat_deg.to_radians(),
            lon_rad: lon_deg.to_radians(),
            height_m: h,
            v_n: Vector3::zeros(),
            q_cn: UnitQuaternion::identity(),
            omega_nc_c: Vector3::zeros(),
        }
    }

    #[test]
    fn the_local_frame_measures_small_offsets_by_the_radii_of_curvature() {
        // 1e-4 rad north and east of 36.6° N: R_M·dφ north, (R_N+h)·cos φ·dλ east, and the
        // drop below the tangent plane d²/(2R) (independent: the textbook radii).
        let f = LocalEnu::at(&at(36.6, 123.6, 10.0));
        let lat = 36.6f64.to_radians();
        let w = (1.0 - WGS84_E2 * lat.sin().powi(2)).sqrt();
        let (r_m, r_n) = (WGS84_A_M * (1.0 - WGS84_E2) / w.powi(3), WGS84_A_M / w);
        let d = 1e-4f64;
        let north = f.enu_m(&at(36.6 + d.to_degrees(), 123.6, 10.0));
        assert!((north.y - (r_m + 10.0) * d).abs() < 1e-3, "{north:?}");
        assert!(north.x.abs() < 1e-9);
        let drop = -north.y * north.y / (2.0 * (r_m + 10.0));
        assert!((north.z - drop).abs() < 2e-3, "{} vs {drop}", north.z);
        let east = f.enu_m(&at(36.6, 123.6 + d.to_degrees(), 10.0));
        assert!(
            (east.x - (r_n + 10.0) * lat.cos() * d).abs() < 1e-3,
            "{east:?}"
        );
        let up = f.enu_m(&at(36.6, 123.6, 110.0));
        assert!((up - Vector3::new(0.0, 0.0, 100.0)).norm() < 1e-8, "{up:?}");
    }
}
