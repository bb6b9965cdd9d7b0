//! The per-cycle residual of every effect of a set under one scheme: ∫ C_b^n·δ dt over a
//! cycle in the navigation frame (Δθ for gyros, Δv for accelerometers), by two methods where
//! both exist, split into stationary and rotation phases, and what it does to navigation.

use nalgebra::Vector3;
use rins_verification::quadrature::{NODES, WEIGHTS};
use serde::Serialize;

use crate::cycle::{Cycle, CycleError, Piece, PieceKind};
use crate::effects::{EffectSet, Group, Sensor};
use crate::response::{NavAfter, StaticResponse, periodic_response};
use crate::scheme_file::SchemeFile;
use crate::trig_exact::{CHECK_ANGLES, SAMPLES, TrigPoly};

/// Longest step of the time-resolved navigation input, s (a move lasts 90 s, the Schuler
/// period 84 min).
pub const NAV_STEP_S: f64 = 20.0;

/// Relative agreement under which a sampled polynomial counts as the effect itself.
const EXACT_CHECK_REL: f64 = 1e-11;

/// What to analyse and how to judge it.
#[derive(Clone, Debug)]
pub struct AnalyseOptions {
    /// Latitude of the static navigator, rad.
    pub lat_rad: f64,
    /// Duration of the navigation figures, days.
    pub days: f64,
    /// Drive the navigation model through the cycle ([`EffectResidual::after`] time-resolved);
    /// `false` uses the cycle's mean alone there too (about 50 times faster: the design's
    /// screening).
    pub time_resolved: bool,
}

impl Default for AnalyseOptions {
    /// The paper's site (36.6° N) and week.
    fn default() -> Self {
        Self {
            lat_rad: 36.6_f64.to_radians(),
            days: 7.0,
            time_resolved: true,
        }
    }
}

/// One effect's residual under one scheme.
#[derive(Clone, Debug, Serialize)]
pub struct EffectResidual {
    /// Effect key (`gyro.position_bias`, `general.bz_uz2`, …).
    pub effect: String,
    /// Instrument.
    pub sensor: Sensor,
    /// Where the effect is defined.
    pub group: Group,
    /// The model the figure assumes.
    pub model: String,
    /// ∫ C_b^n·δ dt over one cycle by Gauss–Legendre quadrature of the plant's schedule
    /// (E, N, U): rad (gyro) or m/s (accelerometer).
    pub per_cycle: [f64; 3],
    /// The same by exact integration (dwells: value × time; constant-rate moves: the
    /// trigonometric polynomial's integral), when every move runs at constant rate and the
    /// effect is such a polynomial; `None` otherwise.
    pub per_cycle_exact: Option<[f64; 3]>,
    /// |quadrature − exact| / max(|exact|, 1e-30 · modulated) when both exist.
    pub methods_rel_diff: Option<f64>,
    /// Over the dwells alone.
    pub stationary: [f64; 3],
    /// Over the moves alone.
    pub rotation: [f64; 3],
    /// ∫|C_b^n·δ| dt: the size of the modulated error.
    pub modulated: f64,
    /// |per_cycle| / modulated: the part of the error the cycle leaves.
    pub surviving_fraction: f64,
    /// Mean over the cycle (E, N, U): °/h (gyro) or µg (accelerometer).
    pub mean: [f64; 3],
    /// What the effect does to a static navigator after the analysis's days: the linear error
    /// model driven by C·δ through the whole run, cycle after cycle (time-resolved in steps of at
    /// most [`NAV_STEP_S`]), averaged over the last Schuler period.
    pub after: NavAfter,
    /// The same driven by the cycle's mean alone: what a per-cycle residual says. The
    /// difference from [`EffectResidual::after`] is what happens inside a cycle (an attitude
    /// error built over one move and undone by a later one tilts the navigator meanwhile).
    pub after_mean: NavAfter,
}

/// One scheme's analysis.
#[derive(Clone, Debug, Serialize)]
pub struct SchemeAnalysis {
    /// Scheme name.
    pub scheme: String,
    /// Where it comes from.
    pub reference: String,
    /// Cycle length, s.
    pub cycle_s: f64,
    /// Dwell positions per cycle (0 for continuous rotation).
    pub positions: usize,
    /// Whether every move runs at constant rate (the exact method applies).
    pub constant_rate: bool,
    /// Latitude, °.
    pub lat_deg: f64,
    /// Days of the navigation figures.
    pub days: f64,
    /// Every effect.
    pub effects: Vec<EffectResidual>,
    /// Effects left out, with why.
    pub skipped: Vec<(String, String)>,
}

impl SchemeAnalysis {
    /// The residual of `effect`, if analysed.
    pub fn effect(&self, effect: &str) -> Option<&EffectResidual> {
        self.effects.iter().find(|e| e.effect == effect)
    }
}

struct Sums {
    /// Per channel, the mean of C·δ over each step of the cycle.
    bins: Vec<Vec<Vector3<f64>>>,
    bin_s: f64,
    start_s: f64,
    total: Vec<Vector3<f64>>,
    stationary: Vec<Vector3<f64>>,
    rotation: Vec<Vector3<f64>>,
    modulated: Vec<f64>,
}

/// Gauss–Legendre over one piece, every channel at once.
fn quadrature(
    cycle: &Cycle,
    piece: &Piece,
    set: &mut EffectSet,
    sums: &mut Sums,
    dwell_pieces: usize,
) {
    let n = set.channels().len();
    let mut buf = vec![Vector3::zeros(); n];
    let pieces = if piece.moving() {
        piece.gl_pieces
    } else {
        dwell_pieces
    };
    let h = (piece.end_s - piece.start_s) / pieces as f64;
    for k in 0..pieces {
        let mid = piece.start_s + (k as f64 + 0.5) * h;
        let half = 0.5 * h;
        for (x, w) in NODES.iter().zip(WEIGHTS) {
            for t in [mid - half * x, mid + half * x] {
                set.eval(&cycle.state(piece, t), &mut buf);
                let bin = (((t - sums.start_s) / sums.bin_s).floor().max(0.0) as usize)
                    .min(sums.bins[0].len() - 1);
                for (i, v) in buf.iter().enumerate() {
                    let wv = v * (w * half);
                    sums.bins[i][bin] += wv / sums.bin_s;
                    sums.total[i] += wv;
                    if piece.moving() {
                        sums.rotation[i] += wv;
                    } else {
                        sums.stationary[i] += wv;
                    }
                    sums.modulated[i] += v.norm() * w * half;
                }
            }
        }
    }
}

/// Exact integral of one piece per channel (`None` where the effect is not constant over a
/// dwell or not a trigonometric polynomial over a move).
fn exact(cycle: &Cycle, piece: &Piece, set: &mut EffectSet) -> Vec<Option<Vector3<f64>>> {
    let n = set.channels().len();
    let mut buf = vec![Vector3::zeros(); n];
    match piece.kind {
        PieceKind::Dwell { .. } => {
            let dur = piece.end_s - piece.start_s;
            let mut vals = Vec::with_capacity(3);
            for t in [
                piece.start_s,
                0.5 * (piece.start_s + piece.end_s),
                piece.end_s,
            ] {
                set.eval(&cycle.state(piece, t), &mut buf);
                vals.push(buf.clone());
            }
            (0..n)
                .map(|i| {
                    let v = vals[1][i];
                    let scale = v.amax().max(f64::MIN_POSITIVE);
                    let constant = vals
                        .iter()
                        .all(|w| (w[i] - v).amax() <= EXACT_CHECK_REL * scale);
                    constant.then_some(v * dur)
                })
                .collect()
        }
        PieceKind::Cruise(cr) => {
            let mut samples = vec![[Vector3::zeros(); SAMPLES]; n];
            for j in 0..SAMPLES {
                let th = std::f64::consts::TAU * j as f64 / SAMPLES as f64;
                set.eval(&cr.at(th), &mut buf);
                for i in 0..n {
                    samples[i][j] = buf[i];
                }
            }
            let polys: Vec<TrigPoly> = samples.iter().map(TrigPoly::from_samples).collect();
            let mut ok = vec![true; n];
            for th in CHECK_ANGLES {
                set.eval(&cr.at(th), &mut buf);
                for i in 0..n {
                    let scale = polys[i].scale().max(f64::MIN_POSITIVE);
                    if (polys[i].value(th) - buf[i]).amax() > EXACT_CHECK_REL * scale {
                        ok[i] = false;
                    }
                }
            }
            let big_theta = cr.rate_rps * (piece.end_s - piece.start_s);
            (0..n)
                .map(|i| ok[i].then(|| polys[i].integral(big_theta) / cr.rate_rps))
                .collect()
        }
        PieceKind::Ramp { .. } => vec![None; n],
    }
}

/// Analyses `file`'s scheme against `set` (the set is cloned: its declared effects keep
/// per-evaluation state).
pub fn analyse_scheme(
    file: &SchemeFile,
    set: &EffectSet,
    opt: &AnalyseOptions,
    response: &StaticResponse,
) -> Result<SchemeAnalysis, CycleError> {
    let cycle = Cycle::new(&file.scheme)?;
    let mut set = set.clone();
    let n = set.channels().len();
    let bins = (cycle.period_s / NAV_STEP_S).ceil().max(1.0) as usize;
    let mut sums = Sums {
        bins: vec![vec![Vector3::zeros(); bins]; n],
        bin_s: cycle.period_s / bins as f64,
        start_s: cycle.start_s,
        total: vec![Vector3::zeros(); n],
        stationary: vec![Vector3::zeros(); n],
        rotation: vec![Vector3::zeros(); n],
        modulated: vec![0.0; n],
    };
    // A dwell is one Gauss–Legendre piece unless an effect reads a motion clock.
    let dwell_pieces = if set.channels().iter().any(|c| c.model.contains("since_")) {
        16
    } else {
        1
    };
    let mut exact_sum: Vec<Option<Vector3<f64>>> =
        vec![cycle.constant_rate.then(Vector3::zeros); n];
    for piece in &cycle.pieces {
        quadrature(&cycle, piece, &mut set, &mut sums, dwell_pieces);
        if cycle.constant_rate {
            for (acc, e) in exact_sum.iter_mut().zip(exact(&cycle, piece, &mut set)) {
                *acc = match (*acc, e) {
                    (Some(a), Some(e)) => Some(a + e),
                    _ => None,
                };
            }
        }
    }
    let inputs: Vec<Vec<[f64; 5]>> = set
        .channels()
        .iter()
        .zip(&sums.bins)
        .map(|(ch, b)| {
            b.iter()
                .map(|v| match ch.sensor {
                    Sensor::Gyro => [v.x, v.y, v.z, 0.0, 0.0],
                    Sensor::Accel => [0.0, 0.0, 0.0, v.x, v.y],
                })
                .collect()
        })
        .collect();
    let resolved = if opt.time_resolved {
        periodic_response(opt.lat_rad, opt.days, sums.bin_s, &inputs)
    } else {
        Vec::new()
    };
    let effects = set
        .channels()
        .iter()
        .enumerate()
        .map(|(i, ch)| {
            let total = sums.total[i];
            let mean_si = total / cycle.period_s;
            let (eps, acc) = match ch.sensor {
                Sensor::Gyro => (mean_si, Vector3::zeros()),
                Sensor::Accel => (Vector3::zeros(), mean_si),
            };
            let ex = exact_sum[i];
            EffectResidual {
                effect: ch.key.clone(),
                sensor: ch.sensor,
                group: ch.group,
                model: ch.model.clone(),
                per_cycle: total.into(),
                per_cycle_exact: ex.map(Into::into),
                methods_rel_diff: ex.map(|e| {
                    (total - e).norm()
                        / e.norm()
                            .max(1e-30 * sums.modulated[i])
                            .max(f64::MIN_POSITIVE)
                }),
                stationary: sums.stationary[i].into(),
                rotation: sums.rotation[i].into(),
                modulated: sums.modulated[i],
                surviving_fraction: if sums.modulated[i] > 0.0 {
                    total.norm() / sums.modulated[i]
                } else {
                    0.0
                },
                mean: (mean_si / ch.sensor.unit_si()).into(),
                after: resolved
                    .get(i)
                    .copied()
                    .unwrap_or_else(|| response.apply(&eps, &acc)),
                after_mean: response.apply(&eps, &acc),
            }
        })
        .collect();
    Ok(SchemeAnalysis {
        scheme: file.name.clone(),
        reference: file.reference.clone(),
        cycle_s: cycle.period_s,
        positions: cycle.positions,
        constant_rate: cycle.constant_rate,
        lat_deg: opt.lat_rad.to_degrees(),
        days: opt.days,
        effects,
        skipped: set.skipped.clone(),
    })
}
