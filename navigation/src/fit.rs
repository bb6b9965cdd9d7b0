//! Drift estimation for calibration: y(t) = α + β·t + random walk + white noise, by generalised
//! least squares with the covariance those noises imply, so the standard error is honest for
//! the strongly correlated residuals of navigation errors.

use nalgebra::{DMatrix, DVector};

/// A fitted drift.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct DriftFit {
    /// Slope β.
    pub slope: f64,
    /// Standard error of β.
    pub se: f64,
    /// Number of samples.
    pub n: usize,
    /// Normalised residual χ²/(n − 2) (≈ 1 when the noise model is right).
    pub chi2_per_dof: f64,
}

/// Fits y_k = α + β t_k + w(t_k) + e_k with w a random walk of intensity `q` (variance growth
/// per second, started at the first sample) and e white with variance `r`. With q = r = 0
/// (noise-free data) it falls back to ordinary least squares with the residual variance.
pub fn fit_drift(t: &[f64], y: &[f64], q: f64, r: f64) -> Option<DriftFit> {
    let n = t.len();
    if n < 3 || y.len() != n {
        return None;
    }
    let t0 = t[0];
    let x = DMatrix::from_fn(n, 2, |i, j| if j == 0 { 1.0 } else { t[i] - t0 });
    let yv = DVector::from_column_slice(y);
    let ols = |x: &DMatrix<f64>, yv: &DVector<f64>| -> Option<DriftFit> {
        let xtx = (x.transpose() * x).try_inverse()?;
        let b = &xtx * x.transpose() * yv;
        let res = yv - x * &b;
        let s2 = res.norm_squared() / (n - 2) as f64;
        Some(DriftFit {
            slope: b[1],
            se: (s2 * xtx[(1, 1)]).sqrt(),
            n,
            chi2_per_dof: f64::NAN,
        })
    };
    if q <= 0.0 && r <= 0.0 {
        return ols(&x, &yv);
    }
    // Σ_ij = q·min(t_i, t_j) + r·δ_ij, times measured from the first sample (the walk's value
    // there is absorbed by α). A floor on r keeps Σ positive definite.
    let r = r.max(q * 1e-9).max(1e-300);
    let sigma = DMatrix::from_fn(n, n, |i, j| {
        q * (t[i.min(j)] - t0) + if i == j { r } else { 0.0 }
    });
    let chol = sigma.cholesky()?;
    let xs = chol.solve(&x);
    let xtsx = (x.transpose() * &xs).try_inverse()?;
    let b = &xtsx * (xs.transpose() * &yv);
    let res = &yv - &x * &b;
    let chi2 = res.dot(&chol.solve(&res)) / (n - 2) as f64;
    Some(DriftFit {
        slope: b[1],
        se: xtsx[(1, 1)].sqrt(),
        n,
        chi2_per_dof: chi2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    #[test]
    fn standard_error_matches_monte_carlo_spread_for_a_random_walk() {
        // 300 synthetic series of drift 2 + random walk + white noise: the spread of the slope
        // estimates must match the reported standard error.
        let (q, r, beta): (f64, f64, f64) = (0.04, 0.01, 2.0);
        let t: Vec<f64> = (0..400).map(|k| k as f64).collect();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut slopes = Vec::new();
        let mut se = 0.0;
        for _ in 0..300 {
            let mut w = 0.0;
            let y: Vec<f64> = t
                .iter()
                .enumerate()
                .map(|(k, &tk)| {
                    if k > 0 {
                        let n: f64 = StandardNormal.sample(&mut rng);
                        w += (q).sqrt() * n;
                    }
                    let e: f64 = StandardNormal.sample(&mut rng);
                    3.0 + beta * tk + w + r.sqrt() * e
                })
                .collect();
            let f = fit_drift(&t, &y, q, r).unwrap();
            slopes.push(f.slope);
            se = f.se;
        }
        let m = slopes.iter().sum::<f64>() / 300.0;
        let sd = (slopes.iter().map(|s| (s - m).powi(2)).sum::<f64>() / 299.0).sqrt();
        assert!((m - beta).abs() < 3.0 * sd / 300f64.sqrt(), "unbiased: {m}");
        let ratio = sd / se;
        assert!(
            (0.85..1.15).contains(&ratio),
            "MC spread / reported SE = {ratio}"
        );
    }
}
