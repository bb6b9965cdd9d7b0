//! Output quantisation: an RLG or accelerometer counts whole pulses; the fraction of a pulse
//! not yet output is carried to the next interval, so quantisation never accumulates.

use nalgebra::Vector3;

/// Per-axis pulse counter with carried residual.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quantizer {
    pulse: Vector3<f64>,
    inv_pulse: Vector3<f64>,
    /// Accumulated but not yet output, per axis (same unit as the increments).
    pub residual: Vector3<f64>,
}

impl Quantizer {
    /// A quantiser with pulse weights `pulse` (zero disables an axis).
    pub fn new(pulse: Vector3<f64>) -> Self {
        let inv_pulse = pulse.map(|q| if q > 0.0 { 1.0 / q } else { 0.0 });
        Self {
            pulse,
            inv_pulse,
            residual: Vector3::zeros(),
        }
    }

    /// Whether any axis quantises.
    pub fn is_active(&self) -> bool {
        self.pulse != Vector3::zeros()
    }

    /// Quantises `increment`: returns whole pulses times the weight and carries the rest.
    #[inline]
    pub fn apply(&mut self, increment: &Vector3<f64>) -> Vector3<f64> {
        let mut out = *increment;
        for i in 0..3 {
            let q = self.pulse[i];
            if q > 0.0 {
                let total = increment[i] + self.residual[i];
                let pulses = floor_small(total * self.inv_pulse[i]);
                out[i] = pulses * q;
                self.residual[i] = total - out[i];
            }
        }
        out
    }
}

/// floor(x) for |x| < 2⁶³ without a libm call (x86-64 baseline has no SSE4.1 `roundsd`) and
/// without a branch: on a moving carrier the increments change sign from sample to sample, and a
/// mispredicted branch per axis cost more than the whole quantiser.
#[inline]
fn floor_small(x: f64) -> f64 {
    let t = x as i64 as f64;
    // Truncation rounds negative non-integers up: take one off then (t − 0 = t exactly).
    t - f64::from(u8::from(t > x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn floor_small_matches_floor() {
        for x in [
            -2.5,
            -2.0,
            -0.1,
            -0.0,
            0.0,
            0.3,
            1.0,
            7.999_999,
            1e12 + 0.5,
            -1e12 - 0.5,
        ] {
            assert_eq!(floor_small(x), x.floor(), "{x}");
        }
    }

    #[test]
    fn quantised_sum_tracks_true_sum_within_one_pulse() {
        let mut q = Quantizer::new(Vector3::new(0.3, 1.0, 0.0));
        let inc = Vector3::new(0.1234, -0.77, 0.5);
        let mut sum = Vector3::zeros();
        for k in 1..=1000 {
            let out = q.apply(&inc);
            sum += out;
            for i in 0..2 {
                // Output is a whole number of pulses.
                let pulses = out[i] / q.pulse[i];
                assert_relative_eq!(pulses, pulses.round(), epsilon = 1e-9);
                // Sum error stays within one pulse: the residual is carried.
                let err = sum[i] - inc[i] * k as f64;
                assert!(
                    err <= 1e-9 && err > -q.pulse[i] - 1e-9,
                    "axis {i} err {err}"
                );
            }
        }
        assert_relative_eq!(sum[2], 500.0, epsilon = 1e-9);
    }
}
