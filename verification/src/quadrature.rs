//! Composite Gauss–Legendre quadrature for vector integrands over time.

use nalgebra::Vector3;

/// 10-point Gauss–Legendre nodes on [-1, 1] (positive half); [`WEIGHTS`] are their weights.
pub const NODES: [f64; 5] = [
    0.148_874_338_981_631_2,
    0.433_395_394_129_247_2,
    0.679_409_568_299_024_4,
    0.865_063_366_688_984_5,
    0.973_906_528_517_171_7,
];
/// Weights of [`NODES`].
pub const WEIGHTS: [f64; 5] = [
    0.295_524_224_714_752_9,
    0.269_266_719_309_996_4,
    0.219_086_362_515_982,
    0.149_451_349_150_580_6,
    0.066_671_344_308_688_1,
];

/// ∫_a^b f(t) dt with `pieces` equal sub-intervals of 10-point Gauss–Legendre (exact for
/// polynomials of degree 19 per piece; spectrally accurate for the smooth trigonometric
/// integrands between motion breakpoints).
pub fn integrate<F: FnMut(f64) -> Vector3<f64>>(
    a: f64,
    b: f64,
    pieces: usize,
    mut f: F,
) -> Vector3<f64> {
    if b <= a {
        return Vector3::zeros();
    }
    let h = (b - a) / pieces as f64;
    let mut sum = Vector3::zeros();
    for k in 0..pieces {
        let mid = a + (k as f64 + 0.5) * h;
        let half = 0.5 * h;
        for (x, w) in NODES.iter().zip(WEIGHTS) {
            sum += (f(mid - half * x) + f(mid + half * x)) * (w * half);
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn integrates_trigonometric_closed_forms() {
        let pi = std::f64::consts::PI;
        let v = integrate(0.0, pi, 8, |t| {
            Vector3::new(t.sin(), t.cos().powi(2), t.powi(19))
        });
        assert_relative_eq!(v.x, 2.0, epsilon = 1e-14);
        assert_relative_eq!(v.y, pi / 2.0, epsilon = 1e-14);
        assert_relative_eq!(v.z, pi.powi(20) / 20.0, max_relative = 1e-13);
    }
}
