//! Model vs measurements: replay a model on measured data, show where it fails, rank the
//! candidate effects that explain the residual, and fit the chosen ones into the model.
//!
//! The steps, each in its own module: [`history`] (the measured rows in SI), [`replay`] (model
//! expectation, residual and regressors per row, summed into windows), [`fit`] (weighted least
//! squares, forward selection, gate, collinearity), [`stats`] (Allan variance, correlations,
//! test distributions). This module turns them into the reports `rins compare` and
//! `rins diagnose` print.

// Six channels indexed in parallel arrays (data, predictions, units): index loops read best.
#![allow(clippy::needless_range_loop)]

pub mod fit;
pub mod history;
pub mod replay;
pub mod stats;

use std::collections::BTreeMap;

use rins_plant::PlantConfig;
use rins_plant::effects::{accel, gyro};
use rins_plant::params::{self, ParamValue};
use rins_plant::units::{DPH, DPSH, UG};
use serde::Serialize;

use fit::{
    ChannelData, Gate, collinearity, contribution, delta_bic_of, design, test_candidates, wls,
};
use history::History;
use replay::{CHANNELS, Effect, Group, Replay, Window, replay};

/// Options of a comparison.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Longest window, s.
    pub window_s: f64,
    /// Width of the temperature bins of the cell map, K.
    pub temp_bin_k: f64,
    /// Length of the time windows of the cell map, s.
    pub time_window_s: f64,
    /// Family-wise level of the cell flags and of the gate.
    pub alpha: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            window_s: 30.0,
            temp_bin_k: 5.0,
            time_window_s: 3600.0,
            alpha: 0.01,
        }
    }
}

/// Display unit of a channel: °/h for gyros, µg for accelerometers.
fn unit_of(channel: usize) -> (&'static str, f64) {
    if channel < 3 {
        ("deg/h", DPH)
    } else {
        ("ug", UG)
    }
}

/// The noise floor of one channel.
#[derive(Clone, Debug, Serialize)]
pub struct NoiseFloor {
    /// Channel.
    pub channel: String,
    /// White-noise density from the model's noise terms (ARW / VRW), display unit·√s (0: none).
    pub model_density: f64,
    /// White-noise density from the residual's Allan deviation at 1 s.
    pub data_density: f64,
    /// Density used for the floor.
    pub used_density: f64,
    /// Which one, and why.
    pub source: String,
}

/// One cell of the discrepancy map.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Channel.
    pub channel: String,
    /// `z-up`, `z-down`, `tilted` or `moving`.
    pub position: String,
    /// Temperature bin, °C.
    pub temp_bin_c: [f64; 2],
    /// Time window since the segment start, s.
    pub time_window_s: [f64; 2],
    /// Mean residual (display unit).
    pub residual: f64,
    /// Its noise floor (1σ, display unit).
    pub noise_floor: f64,
    /// Residual in units of the floor.
    pub z: f64,
    /// Windows in the cell.
    pub windows: usize,
}

/// Residual correlation with an input.
#[derive(Clone, Debug, Serialize)]
pub struct Correlation {
    /// Channel.
    pub channel: String,
    /// `residual` (autocorrelation) or the input name.
    pub with: String,
    /// Largest |ρ| over lags 0–10 (1–10 for the autocorrelation).
    pub max_abs_rho: f64,
    /// Its lag, windows.
    pub lag: usize,
    /// 99 % band.
    pub band99: f64,
    /// |ρ| outside the band.
    pub significant: bool,
}

/// Per-channel residual summary.
#[derive(Clone, Debug, Serialize)]
pub struct ChannelSummary {
    /// Channel.
    pub channel: String,
    /// Unit of the figures.
    pub unit: String,
    /// RMS of the window residual rates.
    pub residual_rms: f64,
    /// RMS the noise alone would give.
    pub noise_floor_rms: f64,
    /// Mean residual rate.
    pub residual_mean: f64,
}

/// Navigation on measured vs modelled increments over one segment.
#[derive(Clone, Debug, Serialize)]
pub struct NavComparison {
    /// Run name.
    pub run: String,
    /// Duration navigated, s.
    pub duration_s: f64,
    /// Final horizontal error navigating on the measurements, m.
    pub measured_final_m: f64,
    /// Final horizontal error navigating on the model's increments, m.
    pub model_final_m: f64,
    /// RMS over the segment of the difference of the two error tracks, m.
    pub difference_rms_m: f64,
}

/// What `rins compare` reports.
#[derive(Clone, Debug, Serialize)]
pub struct CompareReport {
    /// Data file.
    pub source: String,
    /// Rows and windows.
    pub rows: usize,
    /// Windows.
    pub windows: usize,
    /// Runs.
    pub runs: usize,
    /// Per channel.
    pub channels: Vec<ChannelSummary>,
    /// Noise floors.
    pub noise: Vec<NoiseFloor>,
    /// Every cell of the map.
    pub cells: Vec<Cell>,
    /// Cells whose residual exceeds the Bonferroni-corrected 99 % bound.
    pub flagged_cells: Vec<Cell>,
    /// The |z| bound used.
    pub z_critical: f64,
    /// Residual whiteness and cross-correlations.
    pub correlations: Vec<Correlation>,
    /// Allan deviation of the residual per channel: (τ s, ADEV display unit).
    pub allan: BTreeMap<String, Vec<(f64, f64)>>,
    /// Candidates that cannot be tested with this data.
    pub unavailable: Vec<(String, String)>,
    /// Navigation level: static navigation on the measured and on the modelled increments.
    pub navigation: Vec<NavComparison>,
}

/// Replays `model` on `h` and prepares per-channel data.
pub struct Analysis {
    /// Run names.
    pub run_names: Vec<String>,
    /// The replay.
    pub replay: Replay,
    /// Noise floors.
    pub noise: Vec<NoiseFloor>,
    /// Per-channel window data.
    pub data: Vec<ChannelData>,
    /// Options.
    pub opts: Options,
    /// Runs.
    pub runs: usize,
}

fn model_density(model: &PlantConfig, channel: usize) -> f64 {
    let s = &model.sensor;
    if channel < 3 {
        if s.gyro.angle_random_walk.enabled {
            s.gyro.angle_random_walk.dpsh[channel] * DPSH
        } else {
            0.0
        }
    } else if s.accel.velocity_random_walk.enabled {
        s.accel.velocity_random_walk.ug_per_sqrthz[channel - 3] * UG
    } else {
        0.0
    }
}

/// Replays and sets up the noise floors and folds.
pub fn analyse(model: &PlantConfig, h: &History, opts: Options) -> Analysis {
    let rep = replay(model, h, opts.window_s);
    let runs = h.run_names.len();
    let mut noise = Vec::new();
    let mut data = Vec::new();
    // Folds: leave one run out with three runs or more, else five contiguous blocks.
    let n = rep.windows.len();
    let (fold, folds): (Vec<usize>, usize) = if runs >= 3 {
        (rep.windows.iter().map(|w| w.run as usize).collect(), runs)
    } else {
        ((0..n).map(|i| i * 5 / n.max(1)).collect(), 5)
    };
    for c in 0..6 {
        let (unit, scale) = unit_of(c);
        let adev = rep.allan[c].deviation(rep.row_dt_s, 30);
        let data_n = stats::white_density(&adev, 1.0).unwrap_or(0.0);
        let model_n = model_density(model, c);
        let (used, source) = if model_n > 0.0 && data_n <= 1.5 * model_n && data_n >= model_n / 1.5
        {
            (
                model_n,
                "model noise terms (the data's Allan deviation agrees within 1.5x)".to_string(),
            )
        } else if model_n > 0.0 {
            (
                data_n.max(f64::MIN_POSITIVE),
                format!(
                    "data: the model's noise density is {:.2}x the data's; the data's is used",
                    model_n / data_n.max(f64::MIN_POSITIVE)
                ),
            )
        } else {
            (
                data_n.max(f64::MIN_POSITIVE),
                "data: the model has no white-noise term on this channel".to_string(),
            )
        };
        noise.push(NoiseFloor {
            channel: CHANNELS[c].into(),
            model_density: model_n / scale,
            data_density: data_n / scale,
            used_density: used / scale,
            source: format!("{source} ({unit}·√s)"),
        });
        let v: Vec<f64> = rep
            .windows
            .iter()
            .map(|w| used * used * w.duration_s)
            .collect();
        data.push(ChannelData {
            channel: c,
            y: rep.windows.iter().map(|w| w.y[c]).collect(),
            v,
            dur: rep.windows.iter().map(|w| w.duration_s).collect(),
            fold: fold.clone(),
            folds,
        });
    }
    Analysis {
        run_names: h.run_names.clone(),
        replay: rep,
        noise,
        data,
        opts,
        runs,
    }
}

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

fn temp_of(w: &Window, c: usize) -> f64 {
    if c < 3 {
        w.gyro_temp_c[c]
    } else {
        w.accel_temp_c
    }
}

impl Analysis {
    /// Residual sums per channel after removing `pred` (per-channel predictions).
    fn cells(&self, pred: &[Vec<f64>]) -> (Vec<Cell>, f64) {
        let o = &self.opts;
        // (channel, position, temperature bin, time window) -> (residual sum, variance, duration, windows)
        type Key<'a> = (usize, &'a str, i64, i64);
        let mut map: BTreeMap<Key, (f64, f64, f64, usize)> = BTreeMap::new();
        for (i, w) in self.replay.windows.iter().enumerate() {
            for c in 0..6 {
                let tb = (temp_of(w, c) / o.temp_bin_k).floor() as i64;
                let tw = (w.t_run_s / o.time_window_s).floor() as i64;
                let e = map.entry((c, position_of(w), tb, tw)).or_default();
                e.0 += self.data[c].y[i] - pred[c][i];
                e.1 += self.data[c].v[i];
                e.2 += w.duration_s;
                e.3 += 1;
            }
        }
        let zc = stats::z_critical(o.alpha, map.len());
        let cells = map
            .into_iter()
            .map(|((c, pos, tb, tw), (r, v, d, n))| {
                let (_, scale) = unit_of(c);
                Cell {
                    channel: CHANNELS[c].into(),
                    position: pos.into(),
                    temp_bin_c: [tb as f64 * o.temp_bin_k, (tb + 1) as f64 * o.temp_bin_k],
                    time_window_s: [
                        tw as f64 * o.time_window_s,
                        (tw + 1) as f64 * o.time_window_s,
                    ],
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
            let band = stats::band99(z.len());
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
            push("residual", &z, 1..=10);
            push("temperature", &temp, 0..=10);
            push("temperature_rate", &rate, 0..=10);
            push("gravity_along_axis", &grav, 0..=10);
            push("rotation_rate", &rot, 0..=10);
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
    pub fn compare_report(&self, source: &str, pred: &[Vec<f64>]) -> CompareReport {
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

    /// Zero predictions (the model as is).
    pub fn zero_pred(&self) -> Vec<Vec<f64>> {
        vec![vec![0.0; self.replay.windows.len()]; 6]
    }
}

/// `rins compare`.
pub fn compare(model: &PlantConfig, h: &History, opts: Options) -> CompareReport {
    let a = analyse(model, h, opts);
    a.compare_report(&h.source, &a.zero_pred())
}

/// A candidate in the ranking.
#[derive(Clone, Debug, Serialize)]
pub struct RankedEffect {
    /// `gyro.<term>` / `accel.<term>`.
    pub effect: String,
    /// Channel.
    pub channel: String,
    /// BIC change when added to the model (negative favours it).
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated RMSE gain, % (leave one run out, or 5 blocks with fewer than 3 runs).
    pub cv_rmse_gain_pct: f64,
    /// Fitted coefficients in scenario-file units, keyed like the scenario file.
    pub coefficient: Vec<f64>,
    /// Their 95 % intervals.
    pub ci95: Vec<[f64; 2]>,
    /// Scenario keys of the coefficients.
    pub keys: Vec<String>,
    /// Condition number of the fit.
    pub condition_number: f64,
    /// Other effects that explain the same residual on this data.
    pub confusable_with: Vec<Confusable>,
    /// Passes the gate (ΔBIC < −10, Bonferroni p < 0.01, CV gain > 0).
    pub passes_gate: bool,
}

/// An effect that cannot be told apart from another on this data.
#[derive(Clone, Debug, Serialize)]
pub struct Confusable {
    /// The other effect.
    pub effect: String,
    /// Its ΔBIC minus this one's (below 10: nearly as good).
    pub delta_bic_gap: f64,
    /// Correlation of the two fitted contributions.
    pub correlation: f64,
    /// Variance inflation of this effect's coefficients with the other in the model.
    pub vif: f64,
    /// What experiment would separate them.
    pub separate_by: String,
}

/// What `rins diagnose` reports.
#[derive(Clone, Debug, Serialize)]
pub struct DiagnoseReport {
    /// Data file.
    pub source: String,
    /// Every candidate against the model as given, best first.
    pub ranking: Vec<RankedEffect>,
    /// Effects accepted by forward selection, in order, per channel.
    pub accepted: Vec<RankedEffect>,
    /// Residual RMS per channel before (display units).
    pub residual_rms_before: BTreeMap<String, f64>,
    /// … and after the accepted effects.
    pub residual_rms_after: BTreeMap<String, f64>,
    /// Noise floor RMS per channel.
    pub noise_floor_rms: BTreeMap<String, f64>,
    /// Flagged cells before.
    pub flagged_cells: Vec<Cell>,
    /// Flagged cells the accepted effects leave: where the best model still fails.
    pub flagged_cells_after: Vec<Cell>,
    /// Plain-language summary of the unexplained remainder.
    pub unexplained: Vec<String>,
    /// Candidates that cannot be tested with this data.
    pub unavailable: Vec<(String, String)>,
}

fn keys_of(e: Effect, channel: usize) -> Vec<(String, f64)> {
    match e {
        Effect::Gyro(t) => gyro::coefficient_keys(t, channel),
        Effect::Accel(t) => accel::coefficient_keys(t, channel - 3),
    }
}

/// How to separate two confusable effects.
pub fn separating_experiment(a: &str, b: &str) -> String {
    let has = |k: &str| a.contains(k) || b.contains(k);
    if has("temperature_bias") && has("temperature_gradient_bias") {
        "hold the chamber at two or more steady temperatures (the gradient settles to its steady value while the temperature differs) and add a fast chamber step: the temperature bias follows T, the gradient bias follows the transient".into()
    } else if has("position_bias") && (has("g_sensitivity") || has("dither_bias")) {
        "dwell at tilted positions (inner gimbal at ±45° and ±90°): δβ switches with Z-up/Z-down, g-sensitivity is linear and dither bias quadratic in the gravity component".into()
    } else if has("position_bias") && has(".bias")
        || has("position_bias") && has("temperature_bias")
    {
        "dwell at both Z-up and Z-down at each temperature: δβ appears only at Z-down".into()
    } else if has("scale_factor_asymmetry") && has("scale_factor") {
        "rotate in both directions at the same rate: the scale factor changes sign with the rate, the asymmetry does not".into()
    } else if has("misalignment") {
        "rotate about each body axis in turn: misalignment shows on the cross axes only".into()
    } else if has("temperature") {
        "runs at several chamber temperatures spanning the range of interest".into()
    } else {
        "a run that changes the input the two depend on differently (temperature, table position or rotation direction)".into()
    }
}

fn ranked(
    a: &Analysis,
    c: &fit::Candidate,
    others: &[fit::Candidate],
    gate: &Gate,
) -> RankedEffect {
    let ch = c.group.channel;
    let mut keys = keys_of(c.group.effect, ch);
    keys.truncate(c.group.len);
    let (coefficient, ci95): (Vec<f64>, Vec<[f64; 2]>) = keys
        .iter()
        .enumerate()
        .map(|(k, (_, unit))| {
            let i = c.theta_offset + k;
            let (th, se) = (c.fit.theta[i], c.fit.cov[(i, i)].sqrt());
            if se.is_finite() {
                (
                    th / unit,
                    [(th - 1.96 * se) / unit, (th + 1.96 * se) / unit],
                )
            } else {
                (th / unit, [f64::NAN, f64::NAN])
            }
        })
        .unzip();
    // Another effect is confusable when it (with a bias correction, which any calibration
    // re-estimates) explains the same residual nearly as well and the two fitted contributions
    // are nearly collinear.
    let ws = &a.replay.windows;
    let d = &a.data[ch];
    let bias = a
        .replay
        .groups
        .iter()
        .find(|g| {
            g.channel == ch
                && matches!(
                    g.effect,
                    Effect::Gyro(rins_plant::effects::GyroTerm::Bias)
                        | Effect::Accel(rins_plant::effects::AccelTerm::Bias)
                )
        })
        .copied();
    let own = contribution(
        ws,
        d,
        std::slice::from_ref(&c.group),
        &c.fit.theta[c.theta_offset..],
    );
    let confusable_with = others
        .iter()
        .filter(|o| o.group.effect != c.group.effect && c.delta_bic < -10.0)
        .take(8)
        .filter_map(|o| {
            let mut alt = vec![o.group];
            if let Some(b) =
                bias.filter(|b| b.effect != o.group.effect && b.effect != c.group.effect)
            {
                alt.push(b);
            }
            let (dbic, fit) = delta_bic_of(ws, d, &[], &alt)?;
            if dbic - c.delta_bic >= 10.0 {
                return None;
            }
            let theirs = contribution(ws, d, &alt, &fit.theta);
            let (rho, vif) = collinearity(&own, &theirs, ws, d, &alt);
            (rho.abs() > 0.9).then(|| Confusable {
                effect: if alt.len() > 1 {
                    format!("{} (with a bias correction)", o.group.effect.name())
                } else {
                    o.group.effect.name()
                },
                delta_bic_gap: dbic - c.delta_bic,
                correlation: rho,
                vif,
                separate_by: separating_experiment(&c.group.effect.name(), &o.group.effect.name()),
            })
        })
        .collect();
    RankedEffect {
        effect: c.group.effect.name(),
        channel: CHANNELS[ch].into(),
        delta_bic: c.delta_bic,
        p_value: c.p_value,
        cv_rmse_gain_pct: c.cv_gain_pct,
        coefficient,
        ci95,
        keys: keys.into_iter().map(|(k, _)| k).collect(),
        condition_number: c.fit.condition,
        confusable_with,
        passes_gate: gate.passes(c),
    }
}

/// Predictions of `groups` fitted on channel `c`.
fn predict(a: &Analysis, c: usize, groups: &[Group]) -> Vec<f64> {
    let x = design(&a.replay.windows, groups);
    let fit = wls(&x, &a.data[c], None).expect("accepted model fits");
    (0..x.nrows())
        .map(|r| (0..x.ncols()).map(|k| x[(r, k)] * fit.theta[k]).sum())
        .collect()
}

/// Per-channel window predictions of the `selected` groups (zeros where none), fitted jointly.
pub fn predictions(a: &Analysis, selected: &[Vec<Group>]) -> Vec<Vec<f64>> {
    (0..6)
        .map(|c| {
            if selected[c].is_empty() {
                vec![0.0; a.replay.windows.len()]
            } else {
                predict(a, c, &selected[c])
            }
        })
        .collect()
}

/// `rins diagnose`: rank the catalogue's effects against the residual and select by the gate.
pub fn diagnose(
    model: &PlantConfig,
    h: &History,
    opts: Options,
) -> (DiagnoseReport, Analysis, Vec<Vec<Group>>) {
    let a = analyse(model, h, opts);
    let tests = a.replay.groups.len();
    let gate = Gate {
        max_delta_bic: -10.0,
        alpha: opts.alpha,
        tests,
        min_cv_gain_pct: 0.0,
    };
    let mut ranking = Vec::new();
    let mut accepted = Vec::new();
    let mut selected: Vec<Vec<Group>> = vec![Vec::new(); 6];
    for c in 0..6 {
        let pool: Vec<Group> = a
            .replay
            .groups
            .iter()
            .filter(|g| g.channel == c)
            .copied()
            .collect();
        let (_, _, first) = test_candidates(&a.replay.windows, &a.data[c], &[], &pool);
        ranking.extend(first.iter().map(|cand| ranked(&a, cand, &first, &gate)));
        // Forward selection: add the best candidate while it passes the gate.
        loop {
            let rest: Vec<Group> = pool
                .iter()
                .filter(|g| !selected[c].iter().any(|s| s.effect == g.effect))
                .copied()
                .collect();
            if rest.is_empty() {
                break;
            }
            let (_, _, cands) = test_candidates(&a.replay.windows, &a.data[c], &selected[c], &rest);
            match cands.first() {
                Some(best) if gate.passes(best) => {
                    accepted.push(ranked(&a, best, &cands, &gate));
                    selected[c].push(best.group);
                }
                _ => break,
            }
        }
    }
    ranking.sort_by(|x, y| x.delta_bic.total_cmp(&y.delta_bic));
    let zero = a.zero_pred();
    let pred = predictions(&a, &selected);
    let before = a.compare_report(&h.source, &zero);
    let after = a.compare_report(&h.source, &pred);
    let mut unexplained = Vec::new();
    if after.flagged_cells.is_empty() {
        if !before.flagged_cells.is_empty() {
            unexplained.push("the accepted effects clear every flagged cell".into());
        }
    } else {
        let mut by: BTreeMap<(String, String), usize> = BTreeMap::new();
        for c in &after.flagged_cells {
            *by.entry((c.channel.clone(), c.position.clone()))
                .or_default() += 1;
        }
        let claim = if accepted.is_empty() {
            "no candidate in the catalogue passes the gate"
        } else {
            "the accepted effects do not explain all of it"
        };
        unexplained.push(format!(
            "{claim}; {} cells stay outside ±{:.2}σ",
            after.flagged_cells.len(),
            after.z_critical
        ));
        for ((ch, pos), n) in by {
            let worst = after
                .flagged_cells
                .iter()
                .filter(|c| c.channel == ch && c.position == pos)
                .max_by(|a, b| a.z.abs().total_cmp(&b.z.abs()))
                .expect("non-empty");
            unexplained.push(format!(
                "{ch} at {pos}: {n} cells, worst {:.4} {} (z = {:.1}) at {:.0}–{:.0} °C, {:.0}–{:.0} s",
                worst.residual,
                unit_of(CHANNELS.iter().position(|x| *x == ch).unwrap_or(0)).0,
                worst.z,
                worst.temp_bin_c[0],
                worst.temp_bin_c[1],
                worst.time_window_s[0],
                worst.time_window_s[1]
            ));
        }
        for corr in after
            .correlations
            .iter()
            .filter(|c| c.significant && c.with != "residual")
        {
            unexplained.push(format!(
                "{}: residual correlates with {} (|ρ| = {:.2} > {:.2} at lag {})",
                corr.channel, corr.with, corr.max_abs_rho, corr.band99, corr.lag
            ));
        }
    }
    let map = |r: &CompareReport| {
        r.channels
            .iter()
            .map(|c| (c.channel.clone(), c.residual_rms))
            .collect()
    };
    let report = DiagnoseReport {
        source: h.source.clone(),
        ranking,
        accepted,
        residual_rms_before: map(&before),
        residual_rms_after: map(&after),
        noise_floor_rms: before
            .channels
            .iter()
            .map(|c| (c.channel.clone(), c.noise_floor_rms))
            .collect(),
        flagged_cells: before.flagged_cells,
        flagged_cells_after: after.flagged_cells,
        unexplained,
        unavailable: a.replay.unavailable.clone(),
    };
    (report, a, selected)
}

/// `model` with `effects` switched on and fitted jointly on every channel they act on (the
/// model as given stays underneath): the `--apply` of `rins diagnose`. Returns the new model and
/// the scenario values set.
pub fn apply(
    model: &PlantConfig,
    a: &Analysis,
    effects: &[Effect],
) -> Result<(PlantConfig, Vec<(String, f64)>), String> {
    let mut pairs: Vec<(String, ParamValue)> = Vec::new();
    let mut set = Vec::new();
    for e in effects {
        if let Some((_, why)) = a.replay.unavailable.iter().find(|(n, _)| *n == e.name()) {
            return Err(format!("cannot fit {}: {why}", e.name()));
        }
        pairs.push((
            format!("sensor.{}.enabled", e.name()),
            ParamValue::Bool(true),
        ));
        if let Effect::Gyro(rins_plant::effects::GyroTerm::DitherBias) = e {
            for i in 0..3 {
                pairs.push((
                    format!("sensor.gyro.dither_bias.amplitude_change[{i}]"),
                    ParamValue::Real(1.0),
                ));
            }
        }
    }
    let (gm, am) = (
        rins_plant::effects::GyroModel::new(&model.sensor.gyro),
        rins_plant::effects::AccelModel::new(&model.sensor.accel),
    );
    for c in 0..6 {
        // Each effect at the polynomial order BIC prefers on this channel.
        let groups: Vec<Group> = effects
            .iter()
            .filter_map(|e| {
                a.replay
                    .groups
                    .iter()
                    .find(|g| g.channel == c && g.effect == *e)
            })
            .filter_map(|g| {
                // Lowest order first; a higher one only if its extra terms are significant (as in the ranking).
                let mut best: Option<(fit::Fit, Group)> = None;
                for o in g.orders() {
                    if let Some((_, f)) = delta_bic_of(&a.replay.windows, &a.data[c], &[], &[o]) {
                        match &best {
                            Some((lo, _)) if !fit::higher_order_significant(lo, &f) => {}
                            _ => best = Some((f, o)),
                        }
                    }
                }
                best.map(|(_, o)| o)
            })
            .collect();
        if groups.is_empty() {
            continue;
        }
        let x = design(&a.replay.windows, &groups);
        let names: Vec<String> = groups.iter().map(|g| g.effect.name()).collect();
        let fit = wls(&x, &a.data[c], None).ok_or_else(|| {
            format!(
                "{} cannot be fitted together on {} with this data (not identifiable)",
                names.join(" + "),
                CHANNELS[c]
            )
        })?;
        let mut k = 0;
        for g in &groups {
            // The model may already carry this effect: the fit is a correction on top.
            let current = match g.effect {
                Effect::Gyro(t) => gm.coefficients(t, c),
                Effect::Accel(t) => am.coefficients(t, c - 3),
            };
            for (j, (name, unit)) in keys_of(g.effect, c).into_iter().take(g.len).enumerate() {
                let v = (current.get(j).copied().unwrap_or(0.0) + fit.theta[k]) / unit;
                k += 1;
                set.push((name.clone(), v));
                pairs.push((name, ParamValue::Real(v)));
            }
        }
    }
    let cfg = params::apply(model, pairs.iter().map(|(k, v)| (k.as_str(), v.clone())))
        .map_err(|e| e.to_string())?;
    Ok((cfg, set))
}
