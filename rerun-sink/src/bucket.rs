//! Decimation of per-sample channels into buckets: a week at 100 Hz is 60 M samples, far more
//! than a viewer can draw or a file should hold, so each series is logged once per bucket.

/// Minimum, maximum and mean of `N` channels over one bucket.
#[derive(Clone, Copy, Debug)]
pub struct MinMaxMean<const N: usize> {
    sum: [f64; N],
    min: [f64; N],
    max: [f64; N],
}

impl<const N: usize> Default for MinMaxMean<N> {
    fn default() -> Self {
        Self {
            sum: [0.0; N],
            min: [f64::INFINITY; N],
            max: [f64::NEG_INFINITY; N],
        }
    }
}

impl<const N: usize> MinMaxMean<N> {
    /// Adds one sample of every channel.
    #[inline]
    #[allow(clippy::needless_range_loop, reason = "one index over four arrays")]
    pub fn push(&mut self, v: &[f64; N]) {
        // Plain comparisons (not f64::min/max) so the loop vectorises; the plant emits no NaN.
        for i in 0..N {
            self.sum[i] += v[i];
            self.min[i] = if v[i] < self.min[i] {
                v[i]
            } else {
                self.min[i]
            };
            self.max[i] = if v[i] > self.max[i] {
                v[i]
            } else {
                self.max[i]
            };
        }
    }

    /// `[mean, min, max]` of channel `i` over `n` pushed samples, then the channel restarts.
    pub fn take(&mut self, i: usize, n: u64) -> [f64; 3] {
        let out = [self.sum[i] / n as f64, self.min[i], self.max[i]];
        (self.sum[i], self.min[i], self.max[i]) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        out
    }
}

/// Samples per bucket: `bucket_s` rounded to whole samples, or, when `None`, the run split into
/// at most [`AUTO_BUCKETS`] buckets (never less than one sample).
pub fn samples_per_bucket(bucket_s: Option<f64>, rate_hz: f64, total_samples: u64) -> u64 {
    match bucket_s {
        Some(s) => ((s * rate_hz).round() as u64).max(1),
        None => total_samples.div_ceil(AUTO_BUCKETS).max(1),
    }
}

/// Buckets per series when no bucket length is given: a week at 100 Hz gives 30.24 s buckets,
/// a few tens of MB of recording.
pub const AUTO_BUCKETS: u64 = 20_000;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucket_statistics_match_a_direct_computation() {
        let xs: Vec<[f64; 2]> = (0..7)
            .map(|k| [(k as f64 * 0.7).sin(), -(k as f64)])
            .collect();
        let mut b = MinMaxMean::<2>::default();
        xs.iter().for_each(|x| b.push(x));
        let [mean, min, max] = b.take(0, 7);
        let col: Vec<f64> = xs.iter().map(|x| x[0]).collect();
        assert_eq!(min, col.iter().copied().fold(f64::INFINITY, f64::min));
        assert_eq!(max, col.iter().copied().fold(f64::NEG_INFINITY, f64::max));
        approx::assert_relative_eq!(mean, col.iter().sum::<f64>() / 7.0, max_relative = 1e-15);
        assert_eq!(b.take(1, 7), [-3.0, -6.0, 0.0]);
        // Taken channels restart.
        b.push(&[5.0, 5.0]);
        assert_eq!(b.take(0, 1), [5.0, 5.0, 5.0]);
    }

    #[test]
    fn bucket_length_from_seconds_or_run_length() {
        assert_eq!(samples_per_bucket(Some(30.0), 100.0, 0), 3000);
        assert_eq!(samples_per_bucket(Some(0.001), 100.0, 0), 1);
        assert_eq!(samples_per_bucket(None, 100.0, 60_480_000), 3024);
        assert_eq!(samples_per_bucket(None, 100.0, 500), 1);
    }
}
