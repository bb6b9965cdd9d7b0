//! Rotation matrices of the gimbal table and the vehicle mount, by their documented definitions
//! (docs/effects.md and docs/scenario-format.md): active, right-handed rotations; C_b^n =
//! C_v^n·R_z(outer)·R_x(inner) with C_v^n = R_z(azimuth)·R_x(pitch)·R_y(roll) in ENU.

use nalgebra::Matrix3;

/// Active right-handed rotation about x by `a` rad.
pub fn rot_x(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Active right-handed rotation about y by `a` rad.
pub fn rot_y(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// Active right-handed rotation about z by `a` rad.
pub fn rot_z(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The vehicle mount C_v^n = R_z(azimuth)·R_x(pitch)·R_y(roll), angles in degrees: azimuth
/// about up (counter-clockwise from east), pitch about the vehicle x axis, roll about the
/// vehicle y axis.
pub fn mount(azimuth_deg: f64, pitch_deg: f64, roll_deg: f64) -> Matrix3<f64> {
    rot_z(azimuth_deg.to_radians()) * rot_x(pitch_deg.to_radians()) * rot_y(roll_deg.to_radians())
}

/// Body-to-navigation C_b^n = C_v^n·R_z(outer)·R_x(inner), gimbal angles in rad.
pub fn body_to_nav(c_vn: &Matrix3<f64>, outer_rad: f64, inner_rad: f64) -> Matrix3<f64> {
    c_vn * rot_z(outer_rad) * rot_x(inner_rad)
}
