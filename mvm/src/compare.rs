//! The model as given (or with fitted predictions removed) against the measurements: the
//! cell map (channel × table position × temperature bin × time window, flagged at a
//! Bonferroni-corrected bound), residual summaries, whiteness and cross-correlations, the
//! residual's Allan deviation, and navigation on measured vs modelled increments.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use std::collections::BTreeMap;

use crate::prepare::Prepared;
use crate::replay::{CHANNELS, Window};
use crate::report::{Cell, ChannelSummary, CompareReport, Correlation, NavComparison, unit_of};
use crate::stats;

fn position_of(w: &Window) -> &'static str {
    if w.moving {
        "moving"
    } else if w.up_z > 0.5 {
        "z-up"
    } else if w.up_z < -0.5 {
        "z-down"
    } else {
        "tilted"
    }
}

/// Azimuth step of the cell map's orientation label, °: fine enough to separate the 45° and
/// 90° steps of rotation schemes, coarse enough that encoder noise never splits a dwell.
const AZIMUTH_STEP_DEG: f64 = 15.0;

/// The orientation of a static window (`az 90`: body x heading, rounded to 15°); empty while
/// the table moves.
fn orientation_of(w: &Window) -> String {
    if w.moving {
        String::new()
    } else {
        let az = (w.azimuth_deg / AZIMUTH_STEP_DEG).round() * AZIMUTH_STEP_DEG;
        format!("az {:.0}", az.rem_euclid(360.0))
    }
}

/// Bins of the time since the table last stopped, s: a transient after each move shows in the
/// first of them (the last is open).
pub const SINCE_MOVE_BINS_S: [f64; 4] = [0.0, 30.0, 120.0, 600.0];

/// The bin of a static window's time since the last move (`None` while moving).
fn since_move_bin(w: &Window) -> Option<usize> {
    (!w.moving).then(|| {
        SINCE_MOVE_BINS_S
            .iter()
            .rposition(|b| w.since_move_s >= *b)
            .unwrap_or(0)
    })
}

fn temp_of(w: &Window, c: usize) -> f64 {
    if c < 3 {
        w.gyro_temp_c[c]
    } else {
        w.accel_temp_c
    }
}

/// Lags of the residual's autocorrelation, windows.
const AUTO_LAGS: std::ops::RangeInclusive<usize> = 1..=10;
/// Lags of its cross-correlation with each input, windows.
const CROSS_LAGS: std::ops::RangeInclusive<usize> = 0..=10;
/// Inputs it is cross-correlated with (temperature, its rate, gravity along the axis, rotation).
const INPUTS: usize = 4;

impl Prepared {
    /// Residual sums per channel after removing `pred` (per-channel predictions).
    fn cells(&self, pred: &[Vec<f64>]) -> (Vec<Cell>, f64) {
        let o = &self.opts;
        // (channel, position, orientation, temperature bin, time window, since-move bin) ->
        // (residual sum, variance, duration, windows)
        type Key<'a> = (usize, &'a str, String, i64, i64, Option<usize>);
        let mut map: BTreeMap<Key, (f64, f64, f64, usize)> = BTreeMap::new();
        for (i, w) in self.replay.windows.iter().enumerate() {
            for c in 0..6 {
                let tb = (temp_of(w, c) / o.temp_bin_k).floor() as i64;
                let tw = (w.t_run_s / o.time_window_s).floor() as i64;
                let e = map
                    .entry((
                        c,
                        position_of(w),
                        orientation_of(w),
                        tb,
                        tw,
                        since_move_bin(w),
                    ))
                    .or_default();
                e.0 += self.data[c].y[i] - pred[c][i];
                e.1 += self.data[c].v[i];
                e.2 += w.duration_s;
                e.3 += 1;
            }
        }
        let zc = stats::z_critical(o.alpha, map.len());
        let cells = map
            .into_iter()
            .map(|((c, pos, orientation, tb, tw, sm), (r, v, d, n))| {
                let (_, scale) = unit_of(c);
                Cell {
                    channel: CHANNELS[c].into(),
                    position: pos.into(),
                    orientation,
                    temp_bin_c: [tb as f64 * o.temp_bin_k, (tb + 1) as f64 * o.temp_bin_k],
                    time_window_s: [
                        tw as f64 * o.time_window_s,
                        (tw + 1) as f64 * o.time_window_s,
                    ],
                    since_move_s: sm.map_or([0.0, 0.0], |b| {
                        [
                            SINCE_MOVE_BINS_S[b],
                            SINCE_MOVE_BINS_S
                                .get(b + 1)
                                .copied()
                                .unwrap_or(f64::INFINITY),
                        ]
                    }),
                    residual: r / d / scale,
                    noise_floor: v.sqrt() / d / scale,
                    z: r / v.sqrt(),
                    windows: n,
                }
            })
            .collect();
        (cells, zc)
    }

    fn summaries(&self, pred: &[Vec<f64>]) -> Vec<ChannelSummary> {
        (0..6)
            .map(|c| {
                let (unit, scale) = unit_of(c);
                let d = &self.data[c];
                let n = d.y.len().max(1) as f64;
                let rates: Vec<f64> = (0..d.y.len())
                    .map(|i| (d.y[i] - pred[c][i]) / d.dur[i] / scale)
                    .collect();
                ChannelSummary {
                    channel: CHANNELS[c].into(),
                    unit: unit.into(),
                    residual_rms: (rates.iter().map(|r| r * r).sum::<f64>() / n).sqrt(),
                    noise_floor_rms: ((0..d.y.len())
                        .map(|i| d.v[i] / (d.dur[i] * d.dur[i]))
                        .sum::<f64>()
                        / n)
                        .sqrt()
                        / scale,
                    residual_mean: rates.iter().sum::<f64>() / n,
                }
            })
            .collect()
    }

    fn correlations(&self, pred: &[Vec<f64>]) -> Vec<Correlation> {
        let ws = &self.replay.windows;
        let mut out = Vec::new();
        // Family-wise band: each flag is the largest |ρ| over several lags, inputs and
        // channels, so the per-test 99 % band would flag a clean control several times; the
        // bound is Bonferroni over every (channel, input, lag) tested, at the options' level.
        let tests = 6 * (AUTO_LAGS.clone().count() + INPUTS * CROSS_LAGS.clone().count());
        let band = stats::band_family(ws.len(), self.opts.alpha, tests);
        for c in 0..6 {
            let d = &self.data[c];
            let z: Vec<f64> = (0..d.y.len())
                .map(|i| (d.y[i] - pred[c][i]) / d.v[i].sqrt())
                .collect();
            let temp: Vec<f64> = ws.iter().map(|w| temp_of(w, c)).collect();
            let rate: Vec<f64> = (0..ws.len())
                .map(|i| {
                    if i == 0 || ws[i].run != ws[i - 1].run {
                        0.0
                    } else {
                        (temp[i] - temp[i - 1]) / (ws[i].t_mid_s - ws[i - 1].t_mid_s)
                    }
                })
                .collect();
            let grav: Vec<f64> = ws.iter().map(|w| w.f_b_g[c % 3]).collect();
            let rot: Vec<f64> = ws.iter().map(|w| w.rotation_rps).collect();
            let mut push = |with: &str, x: &[f64], lags: std::ops::RangeInclusive<usize>| {
                let (lag, rho) = lags
                    .map(|l| (l, stats::correlation(x, &z, l)))
                    .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                    .unwrap_or((0, 0.0));
                out.push(Correlation {
                    channel: CHANNELS[c].into(),
                    with: with.into(),
                    max_abs_rho: rho.abs(),
                    lag,
                    band99: band,
                    significant: rho.abs() > band,
                });
            };
            push("residual", &z, AUTO_LAGS);
            push("temperature", &temp, CROSS_LAGS);
            push("temperature_rate", &rate, CROSS_LAGS);
            push("gravity_along_axis", &grav, CROSS_LAGS);
            push("rotation_rate", &rot, CROSS_LAGS);
        }
        out
    }

    fn allan(&self) -> BTreeMap<String, Vec<(f64, f64)>> {
        (0..6)
            .map(|c| {
                let (_, scale) = unit_of(c);
                (
                    CHANNELS[c].to_string(),
                    self.replay.allan[c]
                        .deviation(self.replay.row_dt_s, 10)
                        .into_iter()
                        .map(|(t, a)| (t, a / scale))
                        .collect(),
                )
            })
            .collect()
    }

    /// The comparison report with per-channel predictions `pred` removed (zeros: the model as is).
    pub(crate) fn compare_report(&self, source: &str, pred: &[Vec<f64>]) -> CompareReport {
        let (cells, zc) = self.cells(pred);
        let flagged_cells = cells.iter().filter(|c| c.z.abs() > zc).cloned().collect();
        CompareReport {
            source: source.into(),
            rows: self.replay.rows,
            windows: self.replay.windows.len(),
            runs: self.runs,
            channels: self.summaries(pred),
            noise: self.noise.clone(),
            cells,
            flagged_cells,
            z_critical: zc,
            correlations: self.correlations(pred),
            allan: self.allan(),
            unavailable: self.replay.unavailable.clone(),
            column_map: self.opts.column_map.clone(),
            navigation: self
                .replay
                .nav
                .iter()
                .filter(|t| !t.t_s.is_empty())
                .map(|t| {
                    let n = t.t_s.len() as f64;
                    NavComparison {
                        run: self
                            .run_names
                            .get(t.run as usize)
                            .cloned()
                            .unwrap_or_default(),
                        duration_s: *t.t_s.last().expect("non-empty"),
                        measured_final_m: *t.measured_m.last().expect("non-empty"),
                        model_final_m: *t.model_m.last().expect("non-empty"),
                        difference_rms_m: (t
                            .measured_m
                            .iter()
                            .zip(&t.model_m)
                            .map(|(a, b)| (a - b).powi(2))
                            .sum::<f64>()
                            / n)
                            .sqrt(),
                    }
                })
                .collect(),
        }
    }
}
