//! True increments of the table-mounted IMU over one interval: the one definition used by the
//! plant and by the model-vs-measurement replay (rins-mvm), so both integrate the same physics.

use nalgebra::{Matrix3, Vector3};

/// Error-free increments over one interval, with the specific force the effects see.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableIncrements {
    /// ∫ω_ib^b dt, rad.
    pub dtheta_rad: Vector3<f64>,
    /// ∫f^b dt, m/s.
    pub dv_mps: Vector3<f64>,
    /// Specific force at the midpoint, body axes, m/s².
    pub f_b_mps2: Vector3<f64>,
}

/// Increments of an IMU on the dual-axis table with C_b^n = C_v^n·R_z(outer)·R_x(inner), over an
/// interval of `dt_s` in which the gimbals turn by `d_outer_rad` and `d_inner_rad`:
///
/// * gimbal part from the exact angle differences: [Δinner, sin(inner)·Δouter, cos(inner)·Δouter]
///   with the inner angle at the midpoint (exact when one gimbal moves at a time, as the schemes
///   of Eq. 5–6 do);
/// * Earth rate C_n^b·ω_ie^n·Δt and specific force C_n^b·f^n through the midpoint attitude
///   `c_nb_mid` (C_n^b).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn table_increments(
    c_nb_mid: &Matrix3<f64>,
    sin_inner_mid: f64,
    cos_inner_mid: f64,
    d_outer_rad: f64,
    d_inner_rad: f64,
    omega_ie_n: &Vector3<f64>,
    f_n: &Vector3<f64>,
    dt_s: f64,
) -> TableIncrements {
    let gimbal = Vector3::new(
        d_inner_rad,
        sin_inner_mid * d_outer_rad,
        cos_inner_mid * d_outer_rad,
    );
    let f_b = c_nb_mid * f_n;
    TableIncrements {
        dtheta_rad: gimbal + c_nb_mid * omega_ie_n * dt_s,
        dv_mps: f_b * dt_s,
        f_b_mps2: f_b,
    }
}
