//! The 3D view: the IMU body and its axes inside the outer and inner gimbal frames, in the local
//! ENU navigation frame. C_b^n = C_v^n · R_z(outer) · R_x(inner) (Eq. 5): the outer gimbal turns
//! about the vehicle's z axis, the inner about the outer frame's x axis.

use anyhow::Result;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use rerun::{
    Arrows3D, Boxes3D, Color, FillMode, RecordingStream, TextDocument, Transform3D, ViewCoordinates,
};

/// Root of the 3D scene (ENU navigation frame).
pub const WORLD: &str = "world";
/// The vehicle (table base), fixed in the navigation frame by the mount C_v^n (on a moving
/// carrier: C_c^n·C_v^c at each bucket end).
pub const BASE: &str = "world/base";
/// The outer gimbal frame.
pub const OUTER: &str = "world/base/outer";
/// The inner gimbal frame.
pub const INNER: &str = "world/base/outer/inner";
/// The IMU body: a box labelled with the dwell position, and its x/y/z axes.
pub const IMU: &str = "world/base/outer/inner/imu";

fn quat(q: &UnitQuaternion<f64>) -> rerun::datatypes::Quaternion {
    rerun::datatypes::Quaternion::from_xyzw([q.i as f32, q.j as f32, q.k as f32, q.w as f32])
}

/// Logs the parts that never move (static): ENU axes, the base under the mount (`None`: the
/// base rides on a moving carrier and its rotation is logged per bucket,
/// [`crate::carrier::CarrierColumns`]; a static rotation would hide those), the gimbal frames.
pub fn log_static(rec: &RecordingStream, c_vn: Option<&Matrix3<f64>>) -> Result<()> {
    rec.log_static(WORLD, &ViewCoordinates::RIGHT_HAND_Z_UP())?;
    rec.log_static(
        "world/enu",
        &Arrows3D::from_vectors([[1.6, 0.0, 0.0], [0.0, 1.6, 0.0], [0.0, 0.0, 1.6]])
            .with_colors([Color::from_rgb(150, 150, 150); 3])
            .with_labels(["East", "North", "Up"]),
    )?;
    if let Some(c_vn) = c_vn {
        let mount = UnitQuaternion::from_matrix(c_vn);
        rec.log_static(BASE, &Transform3D::from_rotation(quat(&mount)))?;
    }
    rec.log_static(
        "world/base/plate",
        &Boxes3D::from_centers_and_half_sizes([[0.0, 0.0, -1.15]], [[1.3, 1.3, 0.05]])
            .with_colors([Color::from_rgb(110, 110, 120)])
            .with_fill_mode(FillMode::Solid),
    )?;
    rec.log_static(
        "world/base/outer/frame",
        &Boxes3D::from_half_sizes([[1.05, 1.05, 1.0]])
            .with_colors([Color::from_rgb(230, 160, 40)])
            .with_fill_mode(FillMode::MajorWireframe)
            .with_labels(["outer gimbal (z)"]),
    )?;
    rec.log_static(
        "world/base/outer/inner/frame",
        &Boxes3D::from_half_sizes([[0.85, 0.8, 0.8]])
            .with_colors([Color::from_rgb(60, 170, 170)])
            .with_fill_mode(FillMode::MajorWireframe)
            .with_labels(["inner gimbal (x)"]),
    )?;
    rec.log_static(
        "world/base/outer/inner/imu/axes",
        &Arrows3D::from_vectors([[0.8, 0.0, 0.0], [0.0, 0.8, 0.0], [0.0, 0.0, 0.8]])
            .with_colors([
                Color::from_rgb(220, 50, 50),
                Color::from_rgb(50, 180, 50),
                Color::from_rgb(50, 90, 230),
            ])
            .with_labels(["x_b", "y_b", "z_b"]),
    )?;
    Ok(())
}

/// Logs the gimbal angles as the two frame rotations (at the current time).
pub fn log_gimbal(rec: &RecordingStream, outer_rad: f64, inner_rad: f64) -> Result<()> {
    rec.log(
        OUTER,
        &Transform3D::from_rotation(quat(&UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            outer_rad,
        ))),
    )?;
    rec.log(
        INNER,
        &Transform3D::from_rotation(quat(&UnitQuaternion::from_axis_angle(
            &Vector3::x_axis(),
            inner_rad,
        ))),
    )?;
    Ok(())
}

/// The gimbal rotations at each bucket end, sent as column chunks like the series (one `log`
/// per row would cost more than the plant itself on a week-long run).
#[derive(Default)]
pub struct PoseColumns {
    steps: Vec<i64>,
    nanos: Vec<i64>,
    outer: Vec<rerun::datatypes::Quaternion>,
    inner: Vec<rerun::datatypes::Quaternion>,
}

impl PoseColumns {
    /// Adds the pose at output sample `step`, time `t_ns`.
    pub fn push(
        &mut self,
        rec: &RecordingStream,
        step: u64,
        t_ns: i64,
        outer_rad: f64,
        inner_rad: f64,
    ) -> Result<()> {
        self.steps.push(step as i64);
        self.nanos.push(t_ns);
        self.outer.push(quat(&UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            outer_rad,
        )));
        self.inner.push(quat(&UnitQuaternion::from_axis_angle(
            &Vector3::x_axis(),
            inner_rad,
        )));
        if self.steps.len() >= crate::series::FLUSH_ROWS {
            self.flush(rec)?;
        }
        Ok(())
    }

    /// Sends the buffered poses.
    pub fn flush(&mut self, rec: &RecordingStream) -> Result<()> {
        let n = self.steps.len();
        if n == 0 {
            return Ok(());
        }
        let index = || {
            [
                rerun::TimeColumn::new_sequence(crate::series::STEP, self.steps.iter().copied()),
                rerun::TimeColumn::new_duration_nanos(
                    crate::series::SIM_TIME,
                    self.nanos.iter().copied(),
                ),
            ]
        };
        let outer = Transform3D::update_fields()
            .with_many_quaternion(self.outer.drain(..))
            .columns(std::iter::repeat_n(1, n))?;
        rec.send_columns(OUTER, index(), outer)?;
        let inner = Transform3D::update_fields()
            .with_many_quaternion(self.inner.drain(..))
            .columns(std::iter::repeat_n(1, n))?;
        rec.send_columns(INNER, index(), inner)?;
        self.steps.clear();
        self.nanos.clear();
        Ok(())
    }
}

/// Logs the IMU body box with the dwell label (at the current time).
pub fn log_imu_label(rec: &RecordingStream, label: &str) -> Result<()> {
    let color = if label.contains("down") {
        Color::from_rgb(200, 70, 70)
    } else {
        Color::from_rgb(70, 110, 200)
    };
    rec.log(
        IMU,
        &Boxes3D::from_half_sizes([[0.45, 0.35, 0.3]])
            .with_colors([color])
            .with_fill_mode(FillMode::Solid)
            .with_labels([label]),
    )?;
    Ok(())
}

/// Human label of a dwell: `A (Z-up)`, `D (Z-down)`, `moving`; the A–D letters are Eq. 5's.
pub fn dwell_label(position: &str, inner_rad: f64) -> String {
    match position {
        "moving" => "moving".into(),
        "z-up" | "z-down" => position.replace('z', "Z"),
        p => format!(
            "{p} ({})",
            if inner_rad.cos() > 0.0 {
                "Z-up"
            } else {
                "Z-down"
            }
        ),
    }
}

/// Logs a markdown document (static).
pub fn log_doc(rec: &RecordingStream, path: &str, markdown: &str) -> Result<()> {
    rec.log_static(path, &TextDocument::from_markdown(markdown))?;
    Ok(())
}
