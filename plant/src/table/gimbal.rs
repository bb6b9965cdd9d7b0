//! Dual-axis table kinematics: gimbal angles to IMU attitude and body rate.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// One of the two table axes. The outer axis is the vehicle's vertical (azimuth) axis; the
/// inner axis is carried by the outer gimbal and is the IMU's x axis: C_b^v = R_z(outer)·R_x(inner).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GimbalAxis {
    /// Azimuth axis, fixed to the vehicle.
    Outer,
    /// Axis carried by the outer gimbal, along body x.
    Inner,
}

/// Outer (azimuth) and inner gimbal angles, rad.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GimbalAngles {
    /// Outer gimbal angle about the vehicle's z axis, rad.
    pub outer_rad: f64,
    /// Inner gimbal angle about the IMU's x axis, rad.
    pub inner_rad: f64,
}

impl GimbalAngles {
    /// Angles in rad.
    pub fn new(outer_rad: f64, inner_rad: f64) -> Self {
        Self {
            outer_rad,
            inner_rad,
        }
    }

    /// The angles after moving `axis` by `angle_rad`.
    pub fn moved(self, axis: GimbalAxis, angle_rad: f64) -> Self {
        match axis {
            GimbalAxis::Outer => Self {
                outer_rad: self.outer_rad + angle_rad,
                ..self
            },
            GimbalAxis::Inner => Self {
                inner_rad: self.inner_rad + angle_rad,
                ..self
            },
        }
    }
}

/// Rotation about x by `a` (active, right-handed).
pub fn rot_x(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Rotation about y by `a`.
pub fn rot_y(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// Rotation about z by `a`.
pub fn rot_z(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// IMU attitude C_b^n = C_v^n · R_z(outer) · R_x(inner). With a level vehicle at azimuth 0 this
/// gives Eq. 5's positions A (0,0), B (180°,0), C (180°,180°), D (0,180°) and Table 2's matrices.
pub fn body_to_nav(c_vn: &Matrix3<f64>, g: GimbalAngles) -> Matrix3<f64> {
    c_vn * rot_z(g.outer_rad) * rot_x(g.inner_rad)
}

/// R_z(outer)·R_x(inner) from the sines and cosines of the gimbal angles.
#[inline]
pub fn gimbal_rotation(
    sin_outer: f64,
    cos_outer: f64,
    sin_inner: f64,
    cos_inner: f64,
) -> Matrix3<f64> {
    let (so, co, si, ci) = (sin_outer, cos_outer, sin_inner, cos_inner);
    Matrix3::new(co, -so * ci, so * si, so, co * ci, -co * si, 0.0, si, ci)
}

/// The gimbals' part of C_b^v = R_z(outer)·R_x(inner), kept as the angles' sines and cosines:
/// its transpose applied to a vector is two plane rotations (8 products), cheaper than building
/// the matrix when the angles change every tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GimbalFrame {
    /// sin and cos of the outer angle.
    pub sin_outer: f64,
    /// See `sin_outer`.
    pub cos_outer: f64,
    /// sin and cos of the inner angle.
    pub sin_inner: f64,
    /// See `sin_inner`.
    pub cos_inner: f64,
}

impl GimbalFrame {
    /// From (sin, cos) of the outer and of the inner angle.
    #[inline]
    pub fn from_sin_cos(
        (sin_outer, cos_outer): (f64, f64),
        (sin_inner, cos_inner): (f64, f64),
    ) -> Self {
        Self {
            sin_outer,
            cos_outer,
            sin_inner,
            cos_inner,
        }
    }

    /// At the gimbal angles `a` (libm sines and cosines).
    pub fn at(a: GimbalAngles) -> Self {
        Self::from_sin_cos(a.outer_rad.sin_cos(), a.inner_rad.sin_cos())
    }

    /// C_v^b·v = R_x(inner)ᵀ·R_z(outer)ᵀ·v.
    #[inline]
    pub fn to_body(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.inner_to(&self.outer_to(v))
    }

    /// R_z(outer)ᵀ·v: the outer gimbal's plane rotation alone.
    #[inline]
    pub fn outer_to(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let (so, co) = (self.sin_outer, self.cos_outer);
        Vector3::new(co * v.x + so * v.y, co * v.y - so * v.x, v.z)
    }

    /// R_x(inner)ᵀ·v: the inner gimbal's plane rotation alone.
    #[inline]
    pub fn inner_to(&self, v: &Vector3<f64>) -> Vector3<f64> {
        let (si, ci) = (self.sin_inner, self.cos_inner);
        Vector3::new(v.x, ci * v.y + si * v.z, ci * v.z - si * v.y)
    }
}

/// Body rate of the IMU relative to the vehicle, ω_vb^b = R_x(inner)ᵀ·(0, 0, ȯuter) + (ịnner, 0, 0).
pub fn gimbal_body_rate(inner_rad: f64, outer_rate: f64, inner_rate: f64) -> Vector3<f64> {
    let (s, c) = inner_rad.sin_cos();
    Vector3::new(inner_rate, s * outer_rate, c * outer_rate)
}

/// Dwell label of the IMU from the gimbal angles: A/B/C/D of Eq. 5, or `moving`.
pub fn position_label(outer_rad: f64, inner_rad: f64, moving: bool) -> &'static str {
    if moving {
        return "moving";
    }
    let near = |a: f64, b: f64| {
        ((a - b).rem_euclid(std::f64::consts::TAU)).min((b - a).rem_euclid(std::f64::consts::TAU))
            < 1e-6
    };
    let pi = std::f64::consts::PI;
    match (
        near(outer_rad, 0.0),
        near(outer_rad, pi),
        near(inner_rad, 0.0),
        near(inner_rad, pi),
    ) {
        (true, _, true, _) => "A",
        (_, true, true, _) => "B",
        (_, true, _, true) => "C",
        (true, _, _, true) => "D",
        _ if inner_rad.cos() > 0.0 => "z-up",
        _ => "z-down",
    }
}
