//! Statistics the diagnosis needs: streaming Allan variance, auto/cross-correlation with their
//! 99 % bands, and the distributions of the tests.

use statrs::distribution::{ChiSquared, ContinuousCDF, FisherSnedecor, Normal};

/// Non-overlapping Allan variance at octave cluster sizes (1, 2, 4, … rows), accumulated in
/// one pass; segments are accumulated separately and merged, so no difference spans a gap.
#[derive(Clone, Debug, Default)]
pub struct AllanAcc {
    /// Per level: partial block sum, rows in it, mean of the previous block.
    levels: Vec<(f64, u64, Option<f64>)>,
    /// Per level: Σ (mean_k − mean_{k−1})² and the number of differences.
    sums: Vec<(f64, u64)>,
}

const MAX_LEVELS: usize = 26;

impl AllanAcc {
    /// Empty accumulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the next value (a rate).
    pub fn push(&mut self, v: f64) {
        self.feed(0, v, 1);
    }

    fn feed(&mut self, level: usize, sum: f64, count: u64) {
        if level >= MAX_LEVELS {
            return;
        }
        if self.levels.len() <= level {
            self.levels.resize(level + 1, (0.0, 0, None));
            self.sums.resize(level + 1, (0.0, 0));
        }
        let lv = &mut self.levels[level];
        lv.0 += sum;
        lv.1 += count;
        if lv.1 == 1u64 << level {
            let s = lv.0;
            let mean = s / lv.1 as f64;
            if let Some(p) = lv.2 {
                self.sums[level].0 += (mean - p) * (mean - p);
                self.sums[level].1 += 1;
            }
            lv.2 = Some(mean);
            lv.0 = 0.0;
            lv.1 = 0;
            self.feed(level + 1, s, 1u64 << level);
        }
    }

    /// Adds another segment's accumulations.
    pub fn merge(&mut self, other: &AllanAcc) {
        if self.sums.len() < other.sums.len() {
            self.sums.resize(other.sums.len(), (0.0, 0));
        }
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            a.0 += b.0;
            a.1 += b.1;
        }
    }

    /// (τ, Allan deviation) for every level with at least `min_diffs` differences, τ = 2^j·dt.
    pub fn deviation(&self, dt_s: f64, min_diffs: u64) -> Vec<(f64, f64)> {
        self.sums
            .iter()
            .enumerate()
            .filter(|(_, (_, n))| *n >= min_diffs)
            .map(|(j, (s, n))| ((1u64 << j) as f64 * dt_s, (s / (2.0 * *n as f64)).sqrt()))
            .collect()
    }
}

/// White-noise density (rate·√s) from an Allan curve, read at the τ nearest `tau_s` where
/// white noise dominates (ADEV(τ) = N/√τ).
pub fn white_density(adev: &[(f64, f64)], tau_s: f64) -> Option<f64> {
    adev.iter()
        .min_by(|a, b| {
            (a.0.ln() - tau_s.ln())
                .abs()
                .total_cmp(&(b.0.ln() - tau_s.ln()).abs())
        })
        .map(|(t, a)| a * t.sqrt())
}

/// Normalised correlation of `x` and `y` at `lag` (y shifted later), over the overlap.
pub fn correlation(x: &[f64], y: &[f64], lag: usize) -> f64 {
    let n = x.len().min(y.len());
    if n <= lag + 2 {
        return 0.0;
    }
    let mx = x[..n].iter().sum::<f64>() / n as f64;
    let my = y[..n].iter().sum::<f64>() / n as f64;
    let sx = x[..n].iter().map(|a| (a - mx).powi(2)).sum::<f64>().sqrt();
    let sy = y[..n].iter().map(|a| (a - my).powi(2)).sum::<f64>().sqrt();
    if sx == 0.0 || sy == 0.0 {
        return 0.0;
    }
    (0..n - lag)
        .map(|k| (x[k] - mx) * (y[k + lag] - my))
        .sum::<f64>()
        / (sx * sy)
}

/// Half-width of the 99 % band of a correlation estimate from `n` white samples.
pub fn band99(n: usize) -> f64 {
    2.575_829_3 / (n.max(1) as f64).sqrt()
}

/// Half-width of the band a correlation estimate from `n` white samples stays inside with
/// family-wise probability 1 − `alpha` over `tests` estimates (Bonferroni: the two-sided
/// z of alpha / tests, over √n).
pub fn band_family(n: usize, alpha: f64, tests: usize) -> f64 {
    z_critical(alpha, tests) / (n.max(1) as f64).sqrt()
}

/// Upper-tail probability of an F(d1, d2) statistic.
pub fn f_sf(f: f64, d1: f64, d2: f64) -> f64 {
    if !(f > 0.0) {
        return 1.0;
    }
    FisherSnedecor::new(d1, d2.max(1.0)).map_or(1.0, |d| d.sf(f))
}

/// Upper-tail probability of a χ²(k) statistic.
pub fn chi2_sf(x: f64, k: f64) -> f64 {
    if !(x > 0.0) {
        return 1.0;
    }
    ChiSquared::new(k).map_or(1.0, |d| d.sf(x))
}

/// Two-sided critical z for family-wise level `alpha` over `m` tests (Bonferroni).
pub fn z_critical(alpha: f64, m: usize) -> f64 {
    Normal::standard().inverse_cdf(1.0 - alpha / (2.0 * m.max(1) as f64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    #[test]
    fn allan_of_white_noise_falls_as_one_over_root_tau() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut acc = AllanAcc::new();
        let sigma = 2.0;
        for _ in 0..(1 << 18) {
            let x: f64 = StandardNormal.sample(&mut rng);
            acc.push(sigma * x);
        }
        let dev = acc.deviation(0.01, 100);
        // ADEV(τ) = σ/√m for white noise of per-sample σ averaged over m samples.
        for (tau, a) in &dev {
            let m = tau / 0.01;
            let expect = sigma / m.sqrt();
            let n_diffs = (1u64 << 18) as f64 / m;
            assert!(
                (a / expect - 1.0).abs() < 4.0 / n_diffs.sqrt() + 0.01,
                "τ = {tau}: {a} vs {expect}"
            );
        }
        let n = white_density(&dev, 1.0).unwrap();
        assert!((n / (sigma * 0.1) - 1.0).abs() < 0.05, "{n}");
    }

    #[test]
    fn test_distributions_match_tables() {
        // F(1, 100) upper 1 % point is 6.895; χ²(1) upper 5 % point is 3.841.
        assert!((f_sf(6.895, 1.0, 100.0) - 0.01).abs() < 2e-4);
        assert!((chi2_sf(3.841, 1.0) - 0.05).abs() < 2e-4);
        assert!((z_critical(0.05, 1) - 1.95996).abs() < 1e-4);
    }
}
