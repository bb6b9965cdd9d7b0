//! Self-alignment of the static IMU: analytic coarse alignment, then a Kalman-filter fine
//! alignment on zero velocity (gyrocompassing).

use nalgebra::{Matrix3, SMatrix, SVector, UnitQuaternion, Vector3};
use rins_plant::earth::{OMEGA_IE_RPS, normal_gravity};

/// Coarse alignment from mean specific force f̄ and mean rate ω̄ over a static interval (body
/// axes): up ∥ f̄, east ∥ ω̄ × f̄, north = up × east. Returns C_b^n.
pub fn coarse(f_mean_b: &Vector3<f64>, w_mean_b: &Vector3<f64>) -> Matrix3<f64> {
    let up = f_mean_b.normalize();
    let east = w_mean_b.cross(f_mean_b).normalize();
    let north = up.cross(&east);
    Matrix3::from_columns(&[east, north, up]).transpose()
}

/// Fine-alignment Kalman filter. States x = [φ_E, φ_N, φ_U, δv_E, δv_N] with
/// φ̇ = −ω_ie × φ (+ gyro noise), δv̇_E = −g·φ_N + 2Ω sinL·δv_N, δv̇_N = g·φ_E − 2Ω sinL·δv_E
/// (+ accelerometer noise); measurement: the navigator's velocity (truth is zero).
#[derive(Clone, Debug)]
pub struct FineAlignment {
    p: SMatrix<f64, 5, 5>,
    phi: SMatrix<f64, 5, 5>,
    q: SMatrix<f64, 5, 5>,
    r: f64,
}

impl FineAlignment {
    /// A filter updated every `dt_s` at latitude `lat_rad`, with white gyro noise `arw_rps_per_rthz`
    /// (rad/√s) and accelerometer noise `vrw_mps2_per_rthz`; unmodelled biases are absorbed by a
    /// floor on both.
    pub fn new(lat_rad: f64, dt_s: f64, arw: f64, vrw: f64) -> Self {
        let (sl, cl) = lat_rad.sin_cos();
        let w = Vector3::new(0.0, OMEGA_IE_RPS * cl, OMEGA_IE_RPS * sl);
        let g = normal_gravity(lat_rad, 0.0);
        let mut f = SMatrix::<f64, 5, 5>::zeros();
        f.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&(-w.cross_matrix()));
        f[(3, 1)] = -g;
        f[(4, 0)] = g;
        f[(3, 4)] = 2.0 * OMEGA_IE_RPS * sl;
        f[(4, 3)] = -2.0 * OMEGA_IE_RPS * sl;
        let ft = f * dt_s;
        let phi = SMatrix::<f64, 5, 5>::identity() + ft + ft * ft * 0.5 + ft * ft * ft / 6.0;
        let qg = arw.max(1e-7).powi(2);
        let qa = vrw.max(1e-5).powi(2);
        let q = SMatrix::<f64, 5, 5>::from_diagonal(&SVector::<f64, 5>::from([qg, qg, qg, qa, qa]))
            * dt_s;
        let p = SMatrix::<f64, 5, 5>::from_diagonal(&SVector::<f64, 5>::from([
            1e-6, 1e-6, 1e-3, 1e-2, 1e-2,
        ]));
        Self { p, phi, q, r: 1e-8 }
    }

    /// Propagates one interval and updates with the measured velocity error (E, N); returns the
    /// estimated [φ_E, φ_N, φ_U, δv_E, δv_N] to feed back (the state is then reset to zero).
    pub fn step(&mut self, dv_en: &nalgebra::Vector2<f64>) -> SVector<f64, 5> {
        self.p = self.phi * self.p * self.phi.transpose() + self.q;
        let mut h = SMatrix::<f64, 2, 5>::zeros();
        h[(0, 3)] = 1.0;
        h[(1, 4)] = 1.0;
        let s = h * self.p * h.transpose() + SMatrix::<f64, 2, 2>::identity() * self.r;
        let Some(s_inv) = s.try_inverse() else {
            return SVector::zeros();
        };
        let k = self.p * h.transpose() * s_inv;
        let x = k * dv_en;
        self.p = (SMatrix::<f64, 5, 5>::identity() - k * h) * self.p;
        x
    }

    /// 1σ of the attitude estimate, rad.
    pub fn attitude_sigma(&self) -> Vector3<f64> {
        Vector3::new(
            self.p[(0, 0)].sqrt(),
            self.p[(1, 1)].sqrt(),
            self.p[(2, 2)].sqrt(),
        )
    }
}

/// Applies an attitude correction φ̂ to C_b^n(computed) = (I − [φ×])·C_b^n(true).
pub fn correct_attitude(q_bn: &UnitQuaternion<f64>, phi_hat: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(*phi_hat) * q_bn
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn coarse_alignment_recovers_a_known_attitude() {
        let c_bn = rins_plant::table::gimbal::rot_z(0.3) * rins_plant::table::gimbal::rot_x(0.01);
        let lat: f64 = 0.64;
        let w_n = Vector3::new(0.0, OMEGA_IE_RPS * lat.cos(), OMEGA_IE_RPS * lat.sin());
        let f_n = Vector3::new(0.0, 0.0, 9.8);
        let est = coarse(&(c_bn.transpose() * f_n), &(c_bn.transpose() * w_n));
        assert_relative_eq!(est, c_bn, epsilon = 1e-12);
    }
}

/// How the navigator gets its initial attitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Alignment {
    /// From the plant's truth (a perfect alignment; what a simulation study usually assumes).
    Truth,
    /// Self-alignment on the static IMU: coarse for `coarse_s`, then fine (Kalman) for `fine_s`.
    SelfAlign {
        /// Coarse-alignment averaging time, s.
        coarse_s: f64,
        /// Fine-alignment time, s.
        fine_s: f64,
    },
}
