//! The replay prepared for fitting: per-channel window sums, their noise floors (from the
//! model's noise terms when the data agree, else from the data's Allan deviation) and the
//! cross-validation folds.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use rins_plant::PlantConfig;
use rins_plant::units::{DPSH, UG};

use crate::Options;
use crate::fit::ChannelData;
use crate::replay::{CHANNELS, Effect, Group, Replay, replay};
use crate::report::{NoiseFloor, unit_of};
use crate::rows::{Rows, RowsInfo};
use crate::stats;

/// `model` replayed on a history, with per-channel data for the fits.
pub(crate) struct Prepared {
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
    /// The regressor and kind of every declared candidate (the model's declared effects, and
    /// discovery's proposals once they join the ranking), by sensor and index: what heredity
    /// reads to find a candidate's parents.
    pub declared: Vec<DeclaredCandidate>,
}

/// A declared candidate's identity for heredity.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DeclaredCandidate {
    /// Accelerometer effect (else gyro).
    pub accel: bool,
    /// Index in its sensor's list (a proposal: the index it would be declared at).
    pub index: u16,
    /// Bias or scale factor.
    pub kind: rins_plant::effects::custom::CustomKind,
    /// Regressor text without spaces.
    pub regressor: String,
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

/// Relative resolution below which a residual is rounding, not noise.
const RESOLUTION_REL: f64 = 1e-9;
/// Absolute resolution of increments computed from attitudes of order one (rad, m/s).
const RESOLUTION_ABS: f64 = 1e-15;

/// The smallest white-noise density (SI rate·√s) the data can support per channel: increments
/// are stored and the kinematics computed with ~1e-16 relative rounding (quaternion components
/// and angles of order one: ~1e-16 absolute), so on noise-free data the residual is rounding,
/// and a floor at the rounding level would make a column of rounding noise look informative.
/// The floor, 1e-9 of the RMS increment plus 1e-15, is far below any real sensor's noise.
fn resolution_density(info: &RowsInfo) -> [f64; 6] {
    let dt = info.mean_dt_s;
    let (g, a) = (info.rms_dtheta_rad, info.rms_dv_mps);
    let f = |r: f64| (RESOLUTION_REL * r + RESOLUTION_ABS) / dt.abs().max(1e-9).sqrt();
    [f(g), f(g), f(g), f(a), f(a), f(a)]
}

/// Replays `model` on `rows` (one pass over the rows) and sets up the noise floors and folds.
pub(crate) fn prepare(
    model: &PlantConfig,
    rows: &(impl Rows + ?Sized),
    opts: &Options,
) -> Prepared {
    let rep = replay(model, rows, opts.window_s);
    let info = rows.info();
    let floor = resolution_density(&info);
    let runs = info.run_names.len();
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
        } else if data_n < floor[c] {
            (
                floor[c],
                format!(
                    "the data's noise ({:.2e}) is below the numerical resolution of the increments; the resolution is used",
                    data_n / scale
                ),
            )
        } else if model_n > 0.0 {
            (
                data_n,
                format!(
                    "data: the model's noise density is {:.2}x the data's; the data's is used",
                    model_n / data_n
                ),
            )
        } else {
            (
                data_n,
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
    let declared = [false, true]
        .into_iter()
        .flat_map(|accel| {
            let list = if accel {
                &model.sensor.accel.custom
            } else {
                &model.sensor.gyro.custom
            };
            list.iter()
                .enumerate()
                .map(move |(i, s)| DeclaredCandidate {
                    accel,
                    index: i as u16,
                    kind: s.kind,
                    regressor: s.regressor.replace(' ', ""),
                })
        })
        .collect();
    Prepared {
        run_names: info.run_names,
        replay: rep,
        noise,
        data,
        opts: opts.clone(),
        runs,
        declared,
    }
}

impl Prepared {
    /// Zero predictions (the model as is).
    pub(crate) fn zero_pred(&self) -> Vec<Vec<f64>> {
        vec![vec![0.0; self.replay.windows.len()]; 6]
    }

    /// The parents of candidate `g` ([`crate::heredity`]) as groups of its channel; a parent
    /// with no group there (a lower monomial nobody declared or proposed) is left out.
    pub(crate) fn parent_groups(&self, g: &Group) -> Vec<Group> {
        use crate::heredity::{Parent, parents_of_regressor};
        let c = g.channel;
        let on_channel = |e: Effect| {
            self.replay
                .groups
                .iter()
                .find(|x| x.channel == c && x.effect == e)
                .copied()
        };
        let parents = match g.effect {
            Effect::Custom(r) => match self
                .declared
                .iter()
                .find(|d| d.accel == r.accel && d.index == r.index)
            {
                Some(d) => parents_of_regressor(d.accel, d.kind, &d.regressor),
                None => Vec::new(),
            },
            e => crate::heredity::parents(&rins_plant::PlantConfig::default(), e),
        };
        parents
            .into_iter()
            .filter_map(|p| match p {
                Parent::Effect(e) => on_channel(e),
                Parent::Declare {
                    accel,
                    kind,
                    regressor,
                } => self
                    .replay
                    .groups
                    .iter()
                    .find(|x| {
                        x.channel == c
                            && matches!(x.effect, Effect::Custom(r) if r.accel == accel
                                && r.kind == kind
                                && self.declared.iter().any(|d| d.accel == accel
                                    && d.index == r.index
                                    && d.regressor == regressor))
                    })
                    .copied(),
            })
            .collect()
    }
}
