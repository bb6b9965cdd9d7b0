//! Real-time compensation of the position-dependent bias δβ (Section 4.2): the navigation
//! computer subtracts δβ(T)·w(u) from each Δθ, using its own attitude for the gravity direction
//! and the IMU's temperature reading. It uses the plant's own `position_bias` term, so the
//! compensation and the effect share one definition.

use nalgebra::Vector3;
use rins_plant::effects::gyro::{GYRO_TERMS, PositionBiasSpec};
use rins_plant::effects::{GyroModel, GyroSpec, GyroTerm, TermContext};

/// δβ compensation from a (known or fitted) position-bias model.
#[derive(Clone, Debug)]
pub struct PositionBiasCompensation {
    model: GyroModel,
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
        }
    }

    /// The correction to subtract from Δθ over `dt_s`, given the navigator's body up direction
    /// and the gyro block temperatures.
    pub fn correction(
        &self,
        dt_s: f64,
        up_b: &Vector3<f64>,
        gyro_temp_c: &Vector3<f64>,
    ) -> Vector3<f64> {
        let ctx = TermContext {
            dt_s,
            dtheta_rad: Vector3::zeros(),
            dv_mps: Vector3::zeros(),
            f_b_mps2: Vector3::zeros(),
            up_b: *up_b,
            gyro_temp_c: *gyro_temp_c,
            gyro_gradient_k: Vector3::zeros(),
            accel_temp_c: 25.0,
        };
        let mut terms = [Vector3::zeros(); GYRO_TERMS];
        self.model.increment_error(&ctx, &mut terms);
        terms[GyroTerm::PositionBias as usize]
    }
}
