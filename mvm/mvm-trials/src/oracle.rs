//! The oracle z of a hidden effect on a design (docs: diagnosis-benchmark.md): what the true
//! regressor alone achieves against white noise, beside the nuisance columns the model already
//! has.
//!
//! Each run is split into windows of constant table state of at most [`WINDOW_S`] (a dwell cut
//! into 30 s pieces from its start, each move one window; a row belongs to the window that holds
//! its end; the first row of a run, which the diagnosis uses only for the start attitude, is
//! left out). Per channel the window sums of the effect's increment error (the effect as given)
//! and of the nuisance regressors are whitened by the window's noise σ (ARW·√T or VRW·√T, T the
//! window's length); z_c is the norm of what remains of the effect's column after its least
//! squares projection onto the nuisance columns, z = √(Σ_c z_c²).
//!
//! Nuisance columns: gyro axis i: bias (T), scale factor (Σ Δθ_i) and the two misalignment
//! columns (Σ Δθ_j, j ≠ i); accelerometer axis i: bias (T) and scale factor (Σ Δv_i).
//! A catalogue constant that *is* one of these columns (a change of bias, of scale factor, a
//! gyro misalignment element) would have z = 0 against the full set; by default
//! ([`Nuisance::ExcludeOwn`]) its own column is left out, so its z is what it achieves against
//! the other nuisance columns, the question the diagnosis answers when it tests that change.
//! Every other effect is projected off the full set (the constant scale-factor change of
//! [`HiddenEffect::ScaleFactorTempLinear`] thus counts nothing: the model's scale factor
//! absorbs it).

use nalgebra::{DMatrix, DVector};
use rins_plant::PlantConfig;

use crate::design::Design;
use crate::effect_error::row_error;
use crate::generate::{ModelTerms, lag_taus};
use crate::hidden::{Channel, HiddenEffect, Sensor};
use crate::row::{Row, RunRows, Setup};

/// Longest window, s.
pub const WINDOW_S: f64 = 30.0;

/// Which nuisance columns the effect's column is projected off.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Nuisance {
    /// Every nuisance column except the one the effect itself is (for a change of bias, scale
    /// factor or one gyro misalignment element).
    #[default]
    ExcludeOwn,
    /// Every nuisance column.
    All,
}

/// Window sums of one window.
#[derive(Clone, Copy, Debug, Default)]
struct Window {
    dt: f64,
    dtheta: [f64; 3],
    dv: [f64; 3],
    err_gyro: [f64; 3],
    err_accel: [f64; 3],
}

/// The window sums of `effect` on `design`.
fn windows(model: &PlantConfig, design: &Design, effect: &HiddenEffect) -> Vec<Window> {
    let setup = Setup::new(model, design);
    let taus = lag_taus(std::slice::from_ref(effect));
    let mut out = Vec::new();
    let mut row = Row::default();
    for run in &design.runs {
        let mut rows = RunRows::new(setup, design, run, &taus);
        let mut key = None;
        for k in 2..=rows.rows {
            rows.row(k, &mut row);
            let seg = &rows.timeline.segments[row.segment_end];
            let piece = if seg.moving() {
                0
            } else {
                ((row.t1 - seg.t0) / WINDOW_S - 1e-9).floor().max(0.0) as u64
            };
            if key != Some((row.segment_end, piece)) {
                key = Some((row.segment_end, piece));
                out.push(Window::default());
            }
            let (eg, ea) = row_error(effect, &row, &rows.thermal, setup.gravity_mps2);
            let w = out.last_mut().expect("a window was opened");
            w.dt += row.t1 - row.t0;
            for i in 0..3 {
                w.dtheta[i] += row.dtheta[i];
                w.dv[i] += row.dv[i];
                w.err_gyro[i] += eg[i];
                w.err_accel[i] += ea[i];
            }
        }
    }
    out
}

/// The nuisance column an effect is itself, on `channel`: 0 bias, 1 scale factor, 2 + j the
/// misalignment column of axis j.
fn own_column(effect: &HiddenEffect, channel: Channel) -> Option<usize> {
    use HiddenEffect::*;
    match effect {
        GyroBias { .. } | AccelBias { .. } => Some(0),
        GyroScaleFactor { .. } | AccelScaleFactor { .. } => Some(1),
        GyroMisalignment { axis, from, .. } if *axis == channel.axis => Some(2 + from),
        _ => None,
    }
}

/// Norm of the part of `y` orthogonal to the columns of `x` (least squares, through an SVD of
/// the column-normalised matrix, rank-revealing; projected twice for accuracy).
fn residual_norm(x: &DMatrix<f64>, y: &DVector<f64>) -> f64 {
    if x.ncols() == 0 {
        return y.norm();
    }
    let mut xs = x.clone();
    for mut c in xs.column_iter_mut() {
        let n = c.norm();
        if n > 0.0 {
            c /= n;
        }
    }
    let svd = xs.svd(true, false);
    let u = svd.u.expect("U was asked for");
    let smax = svd.singular_values.max();
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|k| svd.singular_values[*k] > 1e-12 * smax)
        .collect();
    let basis = u.select_columns(&keep);
    let mut r = y.clone();
    for _ in 0..2 {
        let p = basis.transpose() * &r;
        r -= &basis * p;
    }
    r.norm()
}

/// The oracle z of `effect` on `design` per channel it acts on, with the nuisance set `nuisance`.
///
/// # Panics
/// If the model has no white noise (ARW or VRW) on a channel the effect acts on: z is then
/// unbounded.
pub fn oracle_z_per_channel_with(
    model: &PlantConfig,
    design: &Design,
    effect: &HiddenEffect,
    nuisance: Nuisance,
) -> Vec<(Channel, f64)> {
    per_channel(model, design, effect, nuisance)
        .into_iter()
        .map(|(c, z, _)| (c, z))
        .collect()
}

/// Per channel: z and the norm of the whitened effect column before the projection.
fn per_channel(
    model: &PlantConfig,
    design: &Design,
    effect: &HiddenEffect,
    nuisance: Nuisance,
) -> Vec<(Channel, f64, f64)> {
    let terms = ModelTerms::of(model);
    let wins = windows(model, design, effect);
    effect
        .channels()
        .into_iter()
        .map(|ch| {
            let i = ch.axis;
            let (noise, err, input): (f64, Vec<f64>, Vec<[f64; 3]>) = match ch.sensor {
                Sensor::Gyro => (
                    terms.arw[i],
                    wins.iter().map(|w| w.err_gyro[i]).collect(),
                    wins.iter().map(|w| w.dtheta).collect(),
                ),
                Sensor::Accel => (
                    terms.vrw[i],
                    wins.iter().map(|w| w.err_accel[i]).collect(),
                    wins.iter().map(|w| w.dv).collect(),
                ),
            };
            assert!(
                noise > 0.0,
                "the oracle needs the model's white noise on {ch} (ARW/VRW is zero or off)"
            );
            let mut cols: Vec<usize> = vec![0, 1];
            if ch.sensor == Sensor::Gyro {
                cols.extend((0..3).filter(|j| *j != i).map(|j| 2 + j));
            }
            if nuisance == Nuisance::ExcludeOwn {
                let own = own_column(effect, ch);
                cols.retain(|c| Some(*c) != own);
            }
            let n = wins.len();
            let sigma: Vec<f64> = wins.iter().map(|w| noise * w.dt.sqrt()).collect();
            let x = DMatrix::from_fn(n, cols.len(), |r, c| {
                let v = match cols[c] {
                    0 => wins[r].dt,
                    1 => input[r][i],
                    j => input[r][j - 2],
                };
                v / sigma[r]
            });
            let y = DVector::from_fn(n, |r, _| err[r] / sigma[r]);
            (ch, residual_norm(&x, &y), y.norm())
        })
        .collect()
}

/// [`oracle_z_per_channel_with`] with the default nuisance set ([`Nuisance::ExcludeOwn`]).
pub fn oracle_z_per_channel(
    model: &PlantConfig,
    design: &Design,
    effect: &HiddenEffect,
) -> Vec<(Channel, f64)> {
    oracle_z_per_channel_with(model, design, effect, Nuisance::ExcludeOwn)
}

/// The oracle z of `effect` (as given) on `design`: √(Σ_c z_c²) over its channels.
pub fn oracle_z(model: &PlantConfig, design: &Design, effect: &HiddenEffect) -> f64 {
    oracle_z_per_channel(model, design, effect)
        .iter()
        .map(|(_, z)| z * z)
        .sum::<f64>()
        .sqrt()
}

/// `effect` with its coefficients scaled so that its oracle z on `design` is `z_target` (z is
/// linear in the coefficients); `None` when the effect is invisible on the design: nothing of
/// it (less than 1e-9 of its whitened column, the rounding of the projection) is left beside
/// the nuisance columns.
pub fn scale_to_z(
    model: &PlantConfig,
    design: &Design,
    effect: &HiddenEffect,
    z_target: f64,
) -> Option<HiddenEffect> {
    let ch = per_channel(model, design, effect, Nuisance::ExcludeOwn);
    let z = ch.iter().map(|c| c.1 * c.1).sum::<f64>().sqrt();
    let whole = ch.iter().map(|c| c.2 * c.2).sum::<f64>().sqrt();
    (z > 1e-9 * whole && z.is_finite()).then(|| effect.scaled(z_target / z))
}

/// The oracle z of `effect` per channel beyond `other` too: its column projected off the
/// nuisance columns and `other`'s column on the same channel. What remains is what tells the
/// two apart on the design (a lag of the temperature beyond the temperature itself): below
/// z ≈ 5 the design cannot separate them, and keeping either is identifying it.
pub fn oracle_z_beyond(
    model: &PlantConfig,
    design: &Design,
    effect: &HiddenEffect,
    other: &HiddenEffect,
) -> Vec<(Channel, f64)> {
    let terms = ModelTerms::of(model);
    let wins = windows(model, design, effect);
    let twin = windows(model, design, other);
    effect
        .channels()
        .into_iter()
        .map(|ch| {
            let i = ch.axis;
            let gyro = ch.sensor == Sensor::Gyro;
            let noise = if gyro { terms.arw[i] } else { terms.vrw[i] };
            let n = wins.len();
            let sigma: Vec<f64> = wins.iter().map(|w| noise * w.dt.sqrt()).collect();
            let err = |w: &Window| if gyro { w.err_gyro[i] } else { w.err_accel[i] };
            let input = |w: &Window| if gyro { w.dtheta } else { w.dv };
            // Columns: bias, scale factor, the twin, then the misalignment columns.
            let mut cols: Vec<usize> = vec![0, 1, 2];
            if gyro {
                cols.extend((0..3).filter(|j| *j != i).map(|j| 3 + j));
            }
            let x = DMatrix::from_fn(n, cols.len(), |r, c| {
                let v = match cols[c] {
                    0 => wins[r].dt,
                    1 => input(&wins[r])[i],
                    2 => err(&twin[r]),
                    j => input(&wins[r])[j - 3],
                };
                v / sigma[r]
            });
            let y = DVector::from_fn(n, |r, _| err(&wins[r]) / sigma[r]);
            (ch, residual_norm(&x, &y))
        })
        .collect()
}
