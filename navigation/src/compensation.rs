//! Real-time compensation of the position-dependent bias δβ (Section 4.2): the navigation
//! computer subtracts δβ(T)·w(u) from each Δθ, using its own attitude for the gravity direction
//! and the IMU's temperature reading. It uses the plant's own `position_bias` term, so the
//! compensation and the effect share one definition.

use nalgebra::Vector3;
use rins_plant::effects::gyro::PositionBiasSpec;
use rins_plant::effects::{GyroModel, GyroSpec};

/// δβ compensation from a (known or fitted) position-bias model.
#[derive(Clone, Debug)]
pub struct PositionBiasCompensation {
    model: GyroModel,
    /// δβ(T) at the last temperatures asked for: the readings change once per thermal update,
    /// the up direction every sample.
    last: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl PositionBiasCompensation {
    /// Compensates with `spec` (its `enabled` flag is forced on).
    pub fn new(spec: &PositionBiasSpec) -> Self {
        let g = GyroSpec {
            position_bias: PositionBiasSpec {
                enabled: true,
                ..*spec
            },
            ..GyroSpec::default()
        };
        Self {
            model: GyroModel::new(&g),
            last: None,
        }
    }

    /// The correction to subtract from Δθ over `dt_s`, given the navigator's body up direction
    /// and the gyro block temperatures: the position term of
    /// [`GyroModel::increment_error`] alone, δβ(T)·(w(u)·Δt), with its operations (the same
    /// bits; the other terms are off here and need not be evaluated every sample).
    #[inline]
    pub fn correction(
        &mut self,
        dt_s: f64,
        up_b: &Vector3<f64>,
        gyro_temp_c: &Vector3<f64>,
    ) -> Vector3<f64> {
        let rate = match self.last {
            Some((t, rate)) if t == *gyro_temp_c => rate,
            _ => {
                let rate = self.model.position_bias_rps(gyro_temp_c);
                self.last = Some((*gyro_temp_c, rate));
                rate
            }
        };
        rate * (self.model.position_weight(up_b) * dt_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_plant::effects::gyro::{GYRO_TERMS, Transition};
    use rins_plant::effects::{GyroTerm, TermContext};

    /// The correction equals the position term of the whole gyro model's increment error,
    /// bit for bit, for both transition models and up directions all round.
    #[test]
    fn the_correction_is_the_models_position_term() {
        for transition in [Transition::Cosine, Transition::Step] {
            let spec = PositionBiasSpec {
                enabled: true,
                dph: [0.005, -0.003, 0.007],
                dph_per_k: [1e-4, 2e-4, -1e-4],
                dph_per_k3: [1e-7, 0.0, 3e-7],
                transition,
                ..PositionBiasSpec::default()
            };
            let mut comp = PositionBiasCompensation::new(&spec);
            for k in 0..200 {
                let a = k as f64 * 0.1;
                let up_b = Vector3::new(a.sin() * 0.6, a.cos() * 0.6, (a * 0.7).cos()).normalize();
                let temps = Vector3::new(20.0 + a, 31.0 - a * 0.5, 25.0 + a * 0.25);
                let ctx = TermContext {
                    dt_s: 0.01,
                    dtheta_rad: Vector3::zeros(),
                    dv_mps: Vector3::zeros(),
                    f_b_mps2: Vector3::zeros(),
                    up_b,
                    north_b: Vector3::zeros(),
                    east_b: Vector3::zeros(),
                    gyro_temp_c: temps,
                    gyro_gradient_k: Vector3::zeros(),
                    accel_temp_c: 25.0,
                };
                let mut terms = [Vector3::zeros(); GYRO_TERMS];
                comp.model.increment_error(&ctx, &mut terms);
                let whole = terms[GyroTerm::PositionBias as usize];
                assert_eq!(
                    comp.correction(0.01, &up_b, &temps),
                    whole,
                    "{transition:?}, {k}"
                );
                assert!(whole.norm() > 0.0 || up_b.z > 0.0);
            }
        }
    }
}
