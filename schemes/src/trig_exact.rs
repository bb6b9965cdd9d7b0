//! Exact integration of trigonometric polynomials: over a move at constant rate the attitude
//! is C₀·R(θ) with R affine in cos θ and sin θ, so an effect polynomial in the up direction,
//! the body rate and the specific force makes C·δ a trigonometric polynomial in θ. Its
//! coefficients follow exactly from 2D+1 samples over a whole turn (discrete Fourier
//! transform), and its integral from them, independently of the Gauss–Legendre quadrature.

use nalgebra::Vector3;

/// Highest degree integrated exactly (a second-order b(u) times C is degree 3; one more spare).
pub const MAX_DEGREE: usize = 4;
/// Samples per turn: 2·[`MAX_DEGREE`] + 1.
pub const SAMPLES: usize = 2 * MAX_DEGREE + 1;
/// Angles where the fitted polynomial is checked against the effect, rad (not on the sample
/// grid).
pub const CHECK_ANGLES: [f64; 2] = [0.371, 2.117];

/// A vector trigonometric polynomial a₀ + Σₖ aₖ cos kθ + bₖ sin kθ, k ≤ [`MAX_DEGREE`].
#[derive(Clone, Debug, PartialEq)]
pub struct TrigPoly {
    a0: Vector3<f64>,
    a: [Vector3<f64>; MAX_DEGREE],
    b: [Vector3<f64>; MAX_DEGREE],
}

impl TrigPoly {
    /// Interpolates `samples[j]` = f(2πj/[`SAMPLES`]).
    pub fn from_samples(samples: &[Vector3<f64>; SAMPLES]) -> Self {
        let n = SAMPLES as f64;
        let mut a0 = Vector3::zeros();
        let mut a = [Vector3::zeros(); MAX_DEGREE];
        let mut b = [Vector3::zeros(); MAX_DEGREE];
        for (j, f) in samples.iter().enumerate() {
            a0 += f / n;
            let th = std::f64::consts::TAU * j as f64 / n;
            for k in 0..MAX_DEGREE {
                let (s, c) = (((k + 1) as f64) * th).sin_cos();
                a[k] += f * (2.0 * c / n);
                b[k] += f * (2.0 * s / n);
            }
        }
        Self { a0, a, b }
    }

    /// The polynomial at `theta`.
    pub fn value(&self, theta: f64) -> Vector3<f64> {
        let mut v = self.a0;
        for k in 0..MAX_DEGREE {
            let (s, c) = (((k + 1) as f64) * theta).sin_cos();
            v += self.a[k] * c + self.b[k] * s;
        }
        v
    }

    /// ∫₀^Θ p(θ) dθ (Θ may be negative).
    pub fn integral(&self, big_theta: f64) -> Vector3<f64> {
        let mut v = self.a0 * big_theta;
        for k in 0..MAX_DEGREE {
            let kf = (k + 1) as f64;
            let (s, c) = (kf * big_theta).sin_cos();
            v += self.a[k] * (s / kf) + self.b[k] * ((1.0 - c) / kf);
        }
        v
    }

    /// Largest coefficient magnitude (the scale a check is relative to).
    pub fn scale(&self) -> f64 {
        self.a
            .iter()
            .chain(self.b.iter())
            .map(|v| v.amax())
            .fold(self.a0.amax(), f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_cubic_trigonometric_products_exactly() {
        // f = (sin³θ, cos θ·sin²θ, 1 + cos 4θ): ∫₀^π = (4/3, 0, π).
        let f = |t: f64| {
            Vector3::new(
                t.sin().powi(3),
                t.cos() * t.sin().powi(2),
                1.0 + (4.0 * t).cos(),
            )
        };
        let samples = std::array::from_fn(|j| f(std::f64::consts::TAU * j as f64 / SAMPLES as f64));
        let p = TrigPoly::from_samples(&samples);
        let pi = std::f64::consts::PI;
        let v = p.integral(pi);
        assert!((v.x - 4.0 / 3.0).abs() < 1e-14, "{v}");
        assert!(v.y.abs() < 1e-14, "{v}");
        assert!((v.z - pi).abs() < 1e-14, "{v}");
        let w = p.integral(-pi / 2.0);
        // ∫₀^{-π/2} sin³ = -(2/3)... sin³ is odd, its integral from 0 to -π/2 equals ∫₀^{π/2} sin³ = 2/3.
        assert!((w.x - 2.0 / 3.0).abs() < 1e-14, "{w}");
        for t in CHECK_ANGLES {
            assert!((p.value(t) - f(t)).amax() < 1e-14);
        }
    }

    #[test]
    fn a_degree_five_term_fails_the_check() {
        let f = |t: f64| Vector3::new((5.0 * t).cos(), 0.0, 0.0);
        let samples = std::array::from_fn(|j| f(std::f64::consts::TAU * j as f64 / SAMPLES as f64));
        let p = TrigPoly::from_samples(&samples);
        assert!(
            CHECK_ANGLES
                .iter()
                .any(|&t| (p.value(t) - f(t)).amax() > 1e-3)
        );
    }
}
