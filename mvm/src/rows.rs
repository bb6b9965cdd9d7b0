//! Measured rows as the analysis walks them: in order, a few whole segments at a time, so the
//! data need not be held in memory at once. A [`History`] in memory is one chunk; a file read
//! for a comparison is streamed into a row cache ([`crate::row_cache::RowCache`]) and walked
//! back from it chunk by chunk. Each pass (the replay, the discovery library, every step of
//! `--iterate`) walks the chunks again; what a pass needs of the whole data before its first
//! row (the runs, the median row interval, the RMS increments) is in [`RowsInfo`].

use crate::history::{Attitude, History};

/// What the whole data hold, known before any chunk is walked.
#[derive(Clone, Debug, PartialEq)]
pub struct RowsInfo {
    /// Where the data came from (file name), for messages.
    pub source: String,
    /// Run names; a chunk's `run` indexes this list.
    pub run_names: Vec<String>,
    /// Rows in all.
    pub rows: usize,
    /// The attitude is given as gimbal angles (else as quaternions).
    pub gimbal: bool,
    /// A housing temperature is measured.
    pub housing: bool,
    /// Median interval between consecutive rows of a segment, s (1 without any).
    pub median_dt_s: f64,
    /// (last time − first time) / (rows − 1), s: the mean row interval the resolution floor
    /// is scaled with.
    pub mean_dt_s: f64,
    /// RMS of the angular increment's norm over all rows, rad.
    pub rms_dtheta_rad: f64,
    /// RMS of the velocity increment's norm over all rows, m/s.
    pub rms_dv_mps: f64,
    /// Per run, the start of its earliest segment (its first row's time less one interval), s:
    /// declared effects' time signal counts from it.
    pub run_start_s: Vec<f64>,
}

/// Measured rows walked in order, in chunks of whole segments.
pub trait Rows: Sync {
    /// What the whole data hold.
    fn info(&self) -> RowsInfo;

    /// Calls `f` with every chunk in order. A chunk is a [`History`] of whole segments whose
    /// `run` indexes `info().run_names`; its `run_names` and `source` are the whole data's.
    fn for_each_chunk(&self, f: &mut dyn FnMut(&History));
}

/// Running sums of the [`RowsInfo`] figures, fed chunk after chunk in row order (so the sums
/// are those of one pass over all rows, bit for bit).
#[derive(Clone, Debug, Default)]
pub(crate) struct InfoSums {
    rows: usize,
    first_t_s: Option<f64>,
    last_t_s: f64,
    sum_sq_dtheta: f64,
    sum_sq_dv: f64,
    run_start_s: Vec<f64>,
    /// Count of each distinct row interval (by its bits): evenly sampled data have few
    /// distinct intervals, so the exact median costs little memory.
    intervals: std::collections::BTreeMap<u64, u64>,
}

impl InfoSums {
    /// Adds the rows of chunk `h`.
    pub(crate) fn add(&mut self, h: &History) {
        let n = h.len();
        if n == 0 {
            return;
        }
        self.first_t_s.get_or_insert(h.t_s[0]);
        self.last_t_s = h.t_s[n - 1];
        self.rows += n;
        let (g, a) = (&h.dtheta_rad, &h.dv_mps);
        for k in 0..n {
            self.sum_sq_dtheta += g[0][k] * g[0][k] + g[1][k] * g[1][k] + g[2][k] * g[2][k];
            self.sum_sq_dv += a[0][k] * a[0][k] + a[1][k] * a[1][k] + a[2][k] * a[2][k];
        }
        for seg in &h.segments {
            for k in seg.start + 1..seg.end {
                let d = h.t_s[k] - h.t_s[k - 1];
                *self.intervals.entry(order_key(d)).or_default() += 1;
            }
            if seg.is_empty() {
                continue;
            }
            let r = h.run[seg.start] as usize;
            if self.run_start_s.len() <= r {
                self.run_start_s.resize(r + 1, f64::NAN);
            }
            let dt0 = if seg.len() > 1 {
                h.t_s[seg.start + 1] - h.t_s[seg.start]
            } else {
                0.0
            };
            let t0 = h.t_s[seg.start] - dt0;
            if !(self.run_start_s[r] <= t0) {
                self.run_start_s[r] = t0;
            }
        }
    }

    /// The figures of every row added, of data from `source` with runs `run_names`, gimbal
    /// angles or quaternions (`gimbal`) and a housing temperature or not (`housing`).
    pub(crate) fn info(
        &self,
        source: &str,
        run_names: &[String],
        gimbal: bool,
        housing: bool,
    ) -> RowsInfo {
        let n = self.rows.max(1) as f64;
        let mut run_start_s = self.run_start_s.clone();
        run_start_s.resize(run_names.len().max(1), f64::NAN);
        RowsInfo {
            source: source.into(),
            run_names: run_names.to_vec(),
            rows: self.rows,
            gimbal,
            housing,
            median_dt_s: self.median_interval(),
            mean_dt_s: (self.last_t_s - self.first_t_s.unwrap_or(0.0))
                / self.rows.saturating_sub(1).max(1) as f64,
            rms_dtheta_rad: (self.sum_sq_dtheta / n).sqrt(),
            rms_dv_mps: (self.sum_sq_dv / n).sqrt(),
            run_start_s,
        }
    }

    /// The median interval: the value at position count/2 of the sorted intervals (the one
    /// `select_nth_unstable` picks), 1 s without any.
    fn median_interval(&self) -> f64 {
        let total: u64 = self.intervals.values().sum();
        if total == 0 {
            return 1.0;
        }
        let mid = total / 2;
        let mut seen = 0;
        for (bits, count) in &self.intervals {
            seen += count;
            if seen > mid {
                return from_order_key(*bits);
            }
        }
        unreachable!("the counts sum to the total")
    }
}

/// A key whose unsigned order is `f64::total_cmp`'s order of the values (the sign bit flipped
/// for positive values, every bit for negative ones), so a map keyed by it sorts the values.
fn order_key(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 { !b } else { b | 1 << 63 }
}

/// The value of an [`order_key`].
fn from_order_key(k: u64) -> f64 {
    f64::from_bits(if k >> 63 == 1 { k & !(1 << 63) } else { !k })
}

impl Rows for History {
    fn info(&self) -> RowsInfo {
        let mut s = InfoSums::default();
        s.add(self);
        s.info(
            &self.source,
            &self.run_names,
            matches!(self.attitude, Attitude::Gimbal { .. }),
            self.housing_temp_c.is_some(),
        )
    }

    fn for_each_chunk(&self, f: &mut dyn FnMut(&History)) {
        f(self)
    }
}
