//! Navigation error measures: attitude φ, position, tRMS (Eq. 20) and the error record of a run.

use nalgebra::{Matrix3, Vector3};
use rins_plant::earth::radii_of_curvature;
use rins_plant::units::NMI_M;

use crate::strapdown::NavState;

/// Attitude error φ (ENU, rad) defined by C_b^n(computed) = (I − [φ×])·C_b^n(true), the
/// convention of Eq. 1 (φ̇ = −ω_in × φ − ε).
pub fn attitude_error(c_bn_nav: &Matrix3<f64>, c_bn_true: &Matrix3<f64>) -> Vector3<f64> {
    let e = c_bn_nav * c_bn_true.transpose();
    let a = (e - e.transpose()) * 0.5;
    -Vector3::new(a[(2, 1)], a[(0, 2)], a[(1, 0)])
}

/// Position error of `nav` against the true site, m: (north, east).
pub fn position_error_m(
    nav: &NavState,
    lat_true_rad: f64,
    lon_true_rad: f64,
    height_m: f64,
) -> (f64, f64) {
    let (rm, rn) = radii_of_curvature(lat_true_rad);
    let north = (nav.lat_rad - lat_true_rad) * (rm + height_m);
    let east = (nav.lon_rad - lon_true_rad) * (rn + height_m) * lat_true_rad.cos();
    (north, east)
}

/// Metres to nautical miles.
pub fn nmi(m: f64) -> f64 {
    m / NMI_M
}

/// Time-RMS of the horizontal error (Eq. 20): sqrt(Σ E_i² / n) over the samples so far.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Trms {
    sum_sq: f64,
    n: u64,
}

impl Trms {
    /// Adds one horizontal error sample E_i, m.
    pub fn push(&mut self, e_m: f64) {
        self.sum_sq += e_m * e_m;
        self.n += 1;
    }
    /// tRMS(t_n), m.
    pub fn value(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            (self.sum_sq / self.n as f64).sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn small_rotation_error_recovered() {
        let phi = Vector3::new(1e-4, -2e-4, 3e-4);
        let truth = rins_plant::table::gimbal::rot_z(0.7) * rins_plant::table::gimbal::rot_x(2.0);
        let nav = (Matrix3::identity() - phi.cross_matrix()) * truth;
        assert_relative_eq!(attitude_error(&nav, &truth), phi, epsilon = 1e-10);
    }

    #[test]
    fn trms_is_eq20() {
        let mut t = Trms::default();
        for e in [3.0, 4.0] {
            t.push(e);
        }
        assert_relative_eq!(t.value(), (12.5f64).sqrt());
    }
}

/// Navigation errors at one instant.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct NavRecord {
    /// Time since navigation start, s.
    pub t_s: f64,
    /// Attitude error φ (E, N, U), rad.
    pub att_err_rad: [f64; 3],
    /// Carrier (vehicle) attitude error (E, N, U), rad: the navigator's C_b^n with the gimbal
    /// encoder angles removed, C_v^n = C_b^n·(C_b^v)ᵀ, against the true mount.
    pub vehicle_att_err_rad: [f64; 3],
    /// Velocity error (E, N, U), m/s.
    pub vel_err_mps: [f64; 3],
    /// Latitude error as north distance, m.
    pub north_m: f64,
    /// Longitude error as east distance, m.
    pub east_m: f64,
    /// Horizontal error, m.
    pub horizontal_m: f64,
    /// tRMS of the horizontal error so far (Eq. 20), m.
    pub trms_m: f64,
}

/// The carrier (vehicle) attitude C_v^n from the navigator's IMU attitude and the gimbal
/// encoder angles: C_v^n = C_b^n·(R_z(outer)·R_x(inner))ᵀ.
pub fn vehicle_attitude(
    c_bn: &nalgebra::Matrix3<f64>,
    gimbal: rins_plant::table::GimbalAngles,
) -> nalgebra::Matrix3<f64> {
    c_bn * rins_plant::table::body_to_nav(&nalgebra::Matrix3::identity(), gimbal).transpose()
}
