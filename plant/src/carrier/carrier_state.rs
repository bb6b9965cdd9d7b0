//! The carrier's state at one instant and the quintic Hermite interpolation used inside a tick.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Carrier reference point and attitude at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarrierState {
    /// Geodetic latitude, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Ellipsoidal height, m.
    pub height_m: f64,
    /// Ground velocity, ENU, m/s.
    pub v_n: Vector3<f64>,
    /// Time derivative of `v_n` (ENU components), m/s².
    pub a_n: Vector3<f64>,
    /// Attitude C_c^n: carrier axes (x starboard, y bow, z up) to ENU.
    pub c_cn: Matrix3<f64>,
    /// Rate of the carrier relative to the ENU frame, carrier axes, ω_nc^c, rad/s.
    pub omega_nc_c: Vector3<f64>,
    /// Its derivative, rad/s².
    pub alpha_nc_c: Vector3<f64>,
}

impl CarrierState {
    /// At rest at (lat, lon, h) with attitude `c_cn`.
    pub fn at_rest(lat_rad: f64, lon_rad: f64, height_m: f64, c_cn: Matrix3<f64>) -> Self {
        Self {
            lat_rad,
            lon_rad,
            height_m,
            v_n: Vector3::zeros(),
            a_n: Vector3::zeros(),
            c_cn,
            omega_nc_c: Vector3::zeros(),
            alpha_nc_c: Vector3::zeros(),
        }
    }

    /// What the truth records of it: the longitude wrapped into [−180°, 180°]
    /// ([`super::track::wrap_lon_rad`]) and the attitude as a unit quaternion
    /// ([`CarrierState::q_cn`]).
    pub fn truth(&self) -> CarrierTruth {
        CarrierTruth {
            lat_rad: self.lat_rad,
            lon_rad: super::track::wrap_lon_rad(self.lon_rad),
            height_m: self.height_m,
            v_n: self.v_n,
            q_cn: self.q_cn(),
            omega_nc_c: self.omega_nc_c,
        }
    }

    /// The attitude q_c^n, of unit norm. The quaternion of C_c^n (Shepperd's method) is kept
    /// as it is, bit for bit, while its norm is 1 within [`Q_NORM_KEEP`] (C_c^n orthonormal to
    /// rounding, as every exact or interpolated attitude of ordinary motion is); beyond that (an
    /// interpolated attitude that left orthonormality) it is the rotation nearest C_c^n.
    pub fn q_cn(&self) -> UnitQuaternion<f64> {
        let q = crate::attitude::quaternion_of(&self.c_cn);
        if (q.as_ref().norm() - 1.0).abs() <= Q_NORM_KEEP {
            q
        } else {
            // The rotation nearest C_c^n (Müller's iteration from the normalised conversion):
            // Shepperd's formulas are not scale-invariant, so normalising alone would turn
            // the attitude.
            let guess = UnitQuaternion::new_normalize(q.into_inner());
            UnitQuaternion::from_matrix_eps(&self.c_cn, f64::EPSILON, 100, guess)
        }
    }
}

/// How far the norm of C_c^n's quaternion may be from 1 before [`CarrierState::q_cn`]
/// replaces it by the nearest rotation (a few hundred ulps: rounding never gets there).
pub const Q_NORM_KEEP: f64 = 1e-13;

/// The carrier in the plant's truth, at the end of the last interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarrierTruth {
    /// Latitude of the reference point, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Height, m.
    pub height_m: f64,
    /// Ground velocity ENU, m/s.
    pub v_n: Vector3<f64>,
    /// Attitude q_c^n (carrier to ENU).
    pub q_cn: UnitQuaternion<f64>,
    /// ω_nc^c, rad/s.
    pub omega_nc_c: Vector3<f64>,
}

/// Quintic Hermite basis on [0, 1] at τ and its first and second derivatives (with respect to τ):
/// p(τ) = H₀p₀ + H₁p₀′ + H₂p₀″ + H₃p₁ + H₄p₁′ + H₅p₁″ matches value, slope and curvature at both
/// ends; for a sinusoid of angular frequency ω over an interval h it errs by O((ωh)⁶).
pub fn quintic_basis(t: f64) -> [[f64; 6]; 3] {
    let (t2, t3, t4, t5) = (t * t, t * t * t, t.powi(4), t.powi(5));
    [
        [
            1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5,
            t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5,
            0.5 * t2 - 1.5 * t3 + 1.5 * t4 - 0.5 * t5,
            10.0 * t3 - 15.0 * t4 + 6.0 * t5,
            -4.0 * t3 + 7.0 * t4 - 3.0 * t5,
            0.5 * t3 - t4 + 0.5 * t5,
        ],
        [
            -30.0 * t2 + 60.0 * t3 - 30.0 * t4,
            1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4,
            t - 4.5 * t2 + 6.0 * t3 - 2.5 * t4,
            30.0 * t2 - 60.0 * t3 + 30.0 * t4,
            -12.0 * t2 + 28.0 * t3 - 15.0 * t4,
            1.5 * t2 - 4.0 * t3 + 2.5 * t4,
        ],
        [
            -60.0 * t + 180.0 * t2 - 120.0 * t3,
            -36.0 * t + 96.0 * t2 - 60.0 * t3,
            1.0 - 9.0 * t + 18.0 * t2 - 10.0 * t3,
            60.0 * t - 180.0 * t2 + 120.0 * t3,
            -24.0 * t + 84.0 * t2 - 60.0 * t3,
            3.0 * t - 12.0 * t2 + 10.0 * t3,
        ],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    /// An orthonormal C_c^n keeps its quaternion's bits; one that left orthonormality (scaled
    /// by 1 + 1.6e-3, the figure) gives a unit quaternion of the same attitude.
    #[test]
    fn the_truth_quaternion_has_unit_norm() {
        let r = Rotation3::from_euler_angles(0.3, -0.2, 2.5).into_inner();
        let at = |c: Matrix3<f64>| CarrierState::at_rest(0.1, 0.2, 0.0, c);
        let plain = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r));
        assert_eq!(at(r).q_cn(), plain);
        let raw = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
            r * (1.0 + 1.6e-3),
        ));
        assert!(
            (raw.as_ref().norm() - 1.0).abs() > 1e-4,
            "the raw conversion is off"
        );
        let q = at(r * (1.0 + 1.6e-3)).q_cn();
        assert!((q.as_ref().norm() - 1.0).abs() < 1e-15);
        assert!(q.angle_to(&plain) < 1e-12, "{}", q.angle_to(&plain));
    }

    #[test]
    fn quintic_reproduces_a_fifth_degree_polynomial() {
        // p(τ) = τ⁵ − 2τ³ + τ: ends p(0)=0, p'(0)=1, p''(0)=0; p(1)=0, p'(1)=0, p''(1)=8.
        let y = [0.0, 1.0, 0.0, 0.0, 0.0, 8.0];
        for t in [0.1, 0.3, 0.77] {
            let b = quintic_basis(t);
            let p: f64 = (0..6).map(|i| b[0][i] * y[i]).sum();
            let d: f64 = (0..6).map(|i| b[1][i] * y[i]).sum();
            let dd: f64 = (0..6).map(|i| b[2][i] * y[i]).sum();
            assert!((p - (t.powi(5) - 2.0 * t.powi(3) + t)).abs() < 1e-14);
            assert!((d - (5.0 * t.powi(4) - 6.0 * t * t + 1.0)).abs() < 1e-13);
            assert!((dd - (20.0 * t.powi(3) - 12.0 * t)).abs() < 1e-12);
        }
    }
}
