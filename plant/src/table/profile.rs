//! Rate-limited, acceleration-limited point-to-point motion of one gimbal axis.

/// Trapezoidal (or, for short moves, triangular) velocity profile for a move of `angle_rad`
/// (sign gives direction) at cruise rate `rate_rps` with acceleration limit `accel_rps2`.
/// An infinite acceleration limit gives the constant-rate motion that Eq. 6 assumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrapezoidProfile {
    sign: f64,
    distance_rad: f64,
    accel_rps2: f64,
    peak_rate_rps: f64,
    accel_time_s: f64,
    cruise_time_s: f64,
}

impl TrapezoidProfile {
    /// Plans the move. `rate_rps` must be > 0 and `accel_rps2` > 0 (may be infinite).
    pub fn new(angle_rad: f64, rate_rps: f64, accel_rps2: f64) -> Self {
        let distance = angle_rad.abs();
        let sign = if angle_rad < 0.0 { -1.0 } else { 1.0 };
        let (peak, t_acc) = if accel_rps2.is_infinite() {
            (rate_rps, 0.0)
        } else if distance >= rate_rps * rate_rps / accel_rps2 {
            (rate_rps, rate_rps / accel_rps2)
        } else {
            let t = (distance / accel_rps2).sqrt();
            (accel_rps2 * t, t)
        };
        let accel_distance = peak * t_acc; // both ramps together
        let cruise = (distance - accel_distance) / peak;
        Self {
            sign,
            distance_rad: distance,
            accel_rps2,
            peak_rate_rps: peak,
            accel_time_s: t_acc,
            cruise_time_s: cruise.max(0.0),
        }
    }

    /// Total duration of the move, s.
    pub fn duration_s(&self) -> f64 {
        2.0 * self.accel_time_s + self.cruise_time_s
    }

    /// Signed angle travelled after `t` seconds (clamped to the move), rad.
    pub fn angle_at(&self, t: f64) -> f64 {
        let (ta, tc) = (self.accel_time_s, self.cruise_time_s);
        let d = if t <= 0.0 {
            0.0
        } else if t < ta {
            0.5 * self.accel_rps2 * t * t
        } else if t < ta + tc {
            0.5 * self.peak_rate_rps * ta + self.peak_rate_rps * (t - ta)
        } else if t < 2.0 * ta + tc {
            let r = 2.0 * ta + tc - t;
            self.distance_rad - 0.5 * self.accel_rps2 * r * r
        } else {
            self.distance_rad
        };
        self.sign * d
    }

    /// Signed rate after `t` seconds, rad/s.
    pub fn rate_at(&self, t: f64) -> f64 {
        let (ta, tc) = (self.accel_time_s, self.cruise_time_s);
        let v = if t <= 0.0 || t >= 2.0 * ta + tc {
            0.0
        } else if t < ta {
            self.accel_rps2 * t
        } else if t < ta + tc {
            self.peak_rate_rps
        } else {
            self.accel_rps2 * (2.0 * ta + tc - t)
        };
        self.sign * v
    }

    /// Times (relative to the move start) where the rate is not smooth; quadrature splits there.
    pub fn breakpoints_s(&self) -> [f64; 4] {
        let (ta, tc) = (self.accel_time_s, self.cruise_time_s);
        [0.0, ta, ta + tc, 2.0 * ta + tc]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn trapezoid_reaches_target_and_rate_integrates_to_angle() {
        let p = TrapezoidProfile::new(-std::f64::consts::PI, 0.035, 0.35);
        assert_relative_eq!(
            p.angle_at(p.duration_s()),
            -std::f64::consts::PI,
            epsilon = 1e-15
        );
        // Duration closed form: angle/rate + rate/accel.
        assert_relative_eq!(
            p.duration_s(),
            std::f64::consts::PI / 0.035 + 0.1,
            epsilon = 1e-12
        );
        // Midpoint integration of the rate reproduces the angle (second method).
        let n = 200_000;
        let h = p.duration_s() / n as f64;
        let sum: f64 = (0..n).map(|k| p.rate_at((k as f64 + 0.5) * h) * h).sum();
        assert_relative_eq!(sum, -std::f64::consts::PI, epsilon = 1e-6);
    }

    #[test]
    fn short_move_is_triangular() {
        let p = TrapezoidProfile::new(0.01, 1.0, 1.0);
        assert_relative_eq!(p.duration_s(), 2.0 * 0.1, epsilon = 1e-12);
        assert_relative_eq!(p.rate_at(0.1), 0.1, epsilon = 1e-12);
    }
}
