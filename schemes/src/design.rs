//! `rins schemes design`: a search over schemes built from the table's moves for the ones whose
//! worst case over an effect class is smallest, with every constant error of Eq. 3 and Eq. 4
//! still cancelled over a cycle.
//!
//! Two families are searched. The first is the paper's group-structured schemes (the
//! 16-position scheme and `mirror-32`) started at an inner-gimbal offset φ₀: that is the same
//! gimbal trajectory with the IMU turned by φ₀ about its x axis, so Eq. 8 holds unchanged
//! (C·R_x(φ₀)·δ sums to zero wherever C·δ does, for every constant error), while the up
//! direction the gyros see over a cycle changes. The second is free: a candidate is a half cycle H of moves (outer or inner gimbal, ±90° or ±180°, at the
//! table's rate and acceleration, each followed by the same dwell) completed by its time
//! mirror (H in reverse order with reversed senses), so every candidate closes with no net
//! turn of either gimbal (no cable wind-up) whatever H is. The search is random restarts of a
//! hill climb on H, every candidate judged by the full analysis ([`crate::analyse_scheme`])
//! and the class's worst case ([`crate::bound::class_bound`]); restarts run on every core,
//! each with its own seeded stream, so the result does not depend on the scheduling.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use rins_plant::table::{GimbalAxis, RotationStep, SchemeKind, SchemeSpec};
use serde::Serialize;

use crate::analyse::{AnalyseOptions, SchemeAnalysis, analyse_scheme};
use crate::bound::{CLASSES, ClassBound, class_bound};
use crate::effects::{EffectSet, Sensor};
use crate::library::mirrored;
use crate::response::StaticResponse;
use crate::scheme_file::SchemeFile;

/// What a constant error may leave of itself over a cycle and still count as cancelled.
pub const CANCELLED_FRACTION: f64 = 1e-9;

/// Search settings.
#[derive(Clone, Debug, Serialize)]
pub struct DesignOptions {
    /// Class to minimise: one of [`CLASSES`].
    pub class: String,
    /// Bound on every coefficient of the class, °/h.
    pub bound_dph: f64,
    /// Positions per cycle to search (even; each half is mirrored).
    pub positions: Vec<usize>,
    /// Dwell after every move, s.
    pub dwell_s: f64,
    /// Table rate, °/s.
    pub rate_dps: f64,
    /// Table acceleration, °/s².
    pub accel_dps2: f64,
    /// Longest cycle allowed, s.
    pub max_cycle_s: f64,
    /// Move angles allowed, ° (each with both senses).
    pub angles_deg: Vec<f64>,
    /// Step of the inner-gimbal offsets tried on the group-structured schemes, °.
    pub offset_step_deg: f64,
    /// Restarts of the hill climb per position count.
    pub restarts: usize,
    /// Mutations tried per restart.
    pub steps_per_restart: usize,
    /// Seed of the search.
    pub seed: u64,
    /// How many designs to report.
    pub top: usize,
    /// Latitude and days of the navigation figures.
    #[serde(skip)]
    pub analysis: AnalyseOptions,
}

impl Default for DesignOptions {
    fn default() -> Self {
        Self {
            class: "general-anisotropic".into(),
            bound_dph: 0.01,
            positions: vec![8, 16, 32],
            dwell_s: 180.0,
            rate_dps: 2.0,
            accel_dps2: 20.0,
            max_cycle_s: 4.0 * 3600.0,
            angles_deg: vec![90.0, 180.0],
            offset_step_deg: 5.0,
            restarts: 4,
            steps_per_restart: 40,
            seed: 1,
            top: 3,
            analysis: AnalyseOptions::default(),
        }
    }
}

/// Why a search was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignError {
    /// A setting out of range (the message names it and the range).
    #[error("{0}")]
    Setting(String),
}

/// A scheme with its figures.
#[derive(Clone, Debug, Serialize)]
pub struct Candidate {
    /// The scheme as a file the plant runs.
    pub file: SchemeFile,
    /// Cycle length, s.
    pub cycle_s: f64,
    /// Worst case over every class ([`CLASSES`] order).
    pub bounds: Vec<ClassBound>,
    /// Worst case of the searched class, m.
    pub score_m: f64,
    /// Largest fraction a constant error leaves over a cycle (0 when all cancel).
    pub constants_max_fraction: f64,
}

/// The search's result.
#[derive(Clone, Debug, Serialize)]
pub struct DesignReport {
    /// Settings.
    pub options: DesignOptions,
    /// The paper's 16-position scheme at the same dwell, rate and acceleration.
    pub reference: Candidate,
    /// The best designs, best first.
    pub best: Vec<Candidate>,
    /// Candidates judged.
    pub evaluated: usize,
    /// Of those, refused because a constant error survived or the cycle was too long.
    pub refused: usize,
    /// The general class's invariant member's error (b_i = B·u_i), m: no scheme's worst case
    /// over `general-b(u)` is below it.
    pub invariant_m: f64,
    /// Lower bound of the worst case over `general-anisotropic` on this table, m: its inner
    /// axis is body x, so u_x = 0 always and ⟨u_y²⟩ + ⟨u_z²⟩ = 1, which leaves at least half
    /// of the invariant member's figure (b_z = B·u_z against b_y = −B·u_y, or the reverse).
    pub anisotropic_floor_m: f64,
    /// Wall time, s.
    pub wall_s: f64,
}

/// The effects every candidate is judged on: the constant errors per axis (Table 3
/// magnitudes), the general b(u) basis and the plant's δβ per axis. Without the Earth rate:
/// "cancelled" is Eq. 8's sense (the table's motion alone); a scale factor on the Earth rate
/// is rectified in part by any scheme and shows in `rins schemes analyse`.
pub fn judging_set(gravity_mps2: f64) -> EffectSet {
    let sensor = rins_plant::presets::paper_table3();
    EffectSet::empty(gravity_mps2)
        .with_constant_axes(&sensor)
        .with_general()
        .with_delta_beta_axes(&sensor.gyro.position_bias)
}

/// Largest fraction a constant error leaves (accelerometers: horizontal part only; the
/// vertical part of a scale factor on gravity is rectified by any scheme, Eq. 8's note).
pub fn constants_fraction(a: &SchemeAnalysis) -> f64 {
    a.effects
        .iter()
        .filter(|e| e.effect.starts_with("const."))
        .map(|e| {
            let r = match e.sensor {
                Sensor::Gyro => nalgebra::Vector3::from(e.per_cycle).norm(),
                Sensor::Accel => e.per_cycle[0].hypot(e.per_cycle[1]),
            };
            if e.modulated > 0.0 {
                r / e.modulated
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// Judges `file` on every class.
pub fn judge(
    file: &SchemeFile,
    set: &EffectSet,
    opt: &DesignOptions,
    resp: &StaticResponse,
) -> Option<Candidate> {
    let a = analyse_scheme(file, set, &opt.analysis, resp).ok()?;
    let bounds: Vec<ClassBound> = CLASSES
        .iter()
        .map(|c| class_bound(&a, c, opt.bound_dph).expect("the judging set holds every class"))
        .collect();
    let k = CLASSES.iter().position(|c| *c == opt.class)?;
    Some(Candidate {
        score_m: bounds[k].worst_horizontal_m,
        cycle_s: a.cycle_s,
        constants_max_fraction: constants_fraction(&a),
        bounds,
        file: file.clone(),
    })
}

fn scheme_of(half: &[(GimbalAxis, f64)], opt: &DesignOptions, name: String) -> SchemeFile {
    let steps: Vec<RotationStep> = half
        .iter()
        .map(|&(axis, angle_deg)| RotationStep {
            axis,
            angle_deg,
            rate_dps: opt.rate_dps,
            dwell_s: opt.dwell_s,
        })
        .collect();
    SchemeFile {
        description: format!(
            "{} positions found by `rins schemes design` (class {}, bound {} deg/h, seed {}): a half cycle and its time mirror, {} s dwells, {} deg/s, {} deg/s^2",
            2 * half.len(),
            opt.class,
            opt.bound_dph,
            opt.seed,
            opt.dwell_s,
            opt.rate_dps,
            opt.accel_dps2
        ),
        reference: "rins schemes design (this project); see docs/schemes.md".into(),
        name,
        scheme: SchemeSpec {
            kind: SchemeKind::Steps,
            accel_dps2: opt.accel_dps2,
            repeat: true,
            steps: mirrored(&steps),
            ..SchemeSpec::default()
        },
    }
}

/// The 16-position scheme (`n` = 16) or `mirror-32` (`n` = 32) as gimbal moves, started at
/// inner angle `offset_deg`, at the search's dwell, rate and acceleration.
pub fn offset_scheme(n: usize, offset_deg: f64, opt: &DesignOptions) -> SchemeFile {
    let base: Vec<RotationStep> = SchemeSpec::default()
        .resolve()
        .steps
        .iter()
        .map(|s| RotationStep {
            axis: s.axis,
            angle_deg: s.angle_rad.to_degrees().round(),
            rate_dps: opt.rate_dps,
            dwell_s: opt.dwell_s,
        })
        .collect();
    let steps = if n == 32 { mirrored(&base) } else { base };
    SchemeFile {
        name: String::new(),
        reference: "rins schemes design (this project); see docs/schemes.md".into(),
        description: format!(
            "The {} scheme started at inner angle {offset_deg} deg (the IMU turned by {offset_deg} deg about x on the same gimbal path), found by `rins schemes design` (class {}, bound {} deg/h): {} s dwells, {} deg/s, {} deg/s^2",
            if n == 32 { "mirror-32" } else { "16-position" },
            opt.class,
            opt.bound_dph,
            opt.dwell_s,
            opt.rate_dps,
            opt.accel_dps2
        ),
        scheme: SchemeSpec {
            kind: SchemeKind::Steps,
            accel_dps2: opt.accel_dps2,
            initial_inner_deg: offset_deg,
            repeat: true,
            steps,
            ..SchemeSpec::default()
        },
    }
}

fn check(opt: &DesignOptions) -> Result<(), DesignError> {
    let bad = |what: &str, range: &str, got: String| {
        Err(DesignError::Setting(format!(
            "{what}: expected {range}, got {got}"
        )))
    };
    if !CLASSES.contains(&opt.class.as_str()) {
        return bad("--class", &CLASSES.join(", "), opt.class.clone());
    }
    if !(opt.bound_dph.is_finite() && opt.bound_dph > 0.0) {
        return bad(
            "--bound-dph",
            "a finite value > 0",
            opt.bound_dph.to_string(),
        );
    }
    for &n in &opt.positions {
        if n < 4 || n % 2 != 0 || n > 128 {
            return bad("--positions", "even counts in [4, 128]", n.to_string());
        }
    }
    if !(opt.dwell_s.is_finite() && opt.dwell_s >= 0.0) {
        return bad("--dwell-s", "a finite value >= 0", opt.dwell_s.to_string());
    }
    if !(opt.rate_dps > 0.0 && opt.rate_dps <= 100.0) {
        return bad("--rate-dps", "(0, 100]", opt.rate_dps.to_string());
    }
    if !(opt.accel_dps2 > 0.0) {
        return bad(
            "--accel-dps2",
            "> 0 (inf for constant-rate moves)",
            opt.accel_dps2.to_string(),
        );
    }
    if !(opt.offset_step_deg > 0.0 && opt.offset_step_deg <= 90.0) {
        return bad(
            "--offset-step-deg",
            "(0, 90]",
            opt.offset_step_deg.to_string(),
        );
    }
    if opt.angles_deg.is_empty() || opt.angles_deg.iter().any(|a| !(*a > 0.0 && *a <= 360.0)) {
        return bad(
            "--angles-deg",
            "values in (0, 360]",
            format!("{:?}", opt.angles_deg),
        );
    }
    Ok(())
}

/// Runs the search; `progress` receives the number of candidates judged so far.
pub fn design(
    opt: &DesignOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<DesignReport, DesignError> {
    check(opt)?;
    let t0 = std::time::Instant::now();
    let set = judging_set(rins_plant::earth::normal_gravity(opt.analysis.lat_rad, 0.0));
    let resp = StaticResponse::new(opt.analysis.lat_rad, opt.analysis.days);
    let reference_file = SchemeFile {
        name: "sixteen-position".into(),
        reference: "Seo et al., Sensors 2022, 22, 8355, Eq. 5-7".into(),
        description: "the paper's scheme at the search's dwell, rate and acceleration".into(),
        scheme: SchemeSpec {
            dwell_s: opt.dwell_s,
            rate_dps: opt.rate_dps,
            accel_dps2: opt.accel_dps2,
            ..SchemeSpec::default()
        },
    };
    let reference =
        judge(&reference_file, &set, opt, &resp).expect("the 16-position scheme analyses");
    // Candidates are screened on the cycle's mean (fast); the best are judged again
    // time-resolved, which is what is reported.
    let screening = DesignOptions {
        analysis: AnalyseOptions {
            time_resolved: false,
            ..opt.analysis.clone()
        },
        ..opt.clone()
    };
    let opt_full = opt;
    let opt = &screening;
    let moves: Vec<(GimbalAxis, f64)> = [GimbalAxis::Outer, GimbalAxis::Inner]
        .into_iter()
        .flat_map(|ax| {
            opt.angles_deg
                .iter()
                .flat_map(move |a| [(ax, *a), (ax, -*a)])
        })
        .collect();
    let done = std::sync::atomic::AtomicU64::new(0);
    let jobs: Vec<(usize, usize)> = opt
        .positions
        .iter()
        .flat_map(|&n| (0..opt.restarts).map(move |r| (n, r)))
        .collect();
    let results: Vec<(Vec<Candidate>, usize, usize)> = jobs
        .par_iter()
        .map(|&(n, r)| {
            let mut rng = ChaCha8Rng::seed_from_u64(opt.seed ^ ((n as u64) << 32) ^ r as u64);
            let half = n / 2;
            let mut h: Vec<(GimbalAxis, f64)> = (0..half)
                .map(|_| moves[rng.random_range(0..moves.len())])
                .collect();
            let (mut evaluated, mut refused) = (0usize, 0usize);
            let mut kept: Vec<Candidate> = Vec::new();
            let eval = |h: &[(GimbalAxis, f64)], evaluated: &mut usize, refused: &mut usize| {
                *evaluated += 1;
                done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                progress(done.load(std::sync::atomic::Ordering::Relaxed));
                let c = judge(&scheme_of(h, opt, String::new()), &set, opt, &resp)?;
                if c.constants_max_fraction > CANCELLED_FRACTION || c.cycle_s > opt.max_cycle_s {
                    *refused += 1;
                    return None;
                }
                Some(c)
            };
            let mut current = eval(&h, &mut evaluated, &mut refused);
            for _ in 0..opt.steps_per_restart {
                let mut trial = h.clone();
                let i = rng.random_range(0..half);
                trial[i] = moves[rng.random_range(0..moves.len())];
                if rng.random_bool(0.3) {
                    let j = rng.random_range(0..half);
                    trial.swap(i, j);
                }
                if let Some(c) = eval(&trial, &mut evaluated, &mut refused) {
                    let better = current
                        .as_ref()
                        .is_none_or(|cur| c.score_m < cur.score_m * (1.0 - 1e-9));
                    if better {
                        h = trial;
                        current = Some(c);
                    }
                }
            }
            if let Some(c) = current {
                kept.push(c);
            }
            (kept, evaluated, refused)
        })
        .collect();
    let offsets: Vec<(usize, f64)> = [16usize, 32]
        .into_iter()
        .filter(|n| opt.positions.contains(n))
        .flat_map(|n| {
            let count = (180.0 / opt.offset_step_deg).round().max(1.0) as usize;
            (0..count).map(move |k| (n, k as f64 * 180.0 / count as f64))
        })
        .collect();
    let family: Vec<Option<Candidate>> = offsets
        .par_iter()
        .map(|&(n, phi)| {
            done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            progress(done.load(std::sync::atomic::Ordering::Relaxed));
            let c = judge(&offset_scheme(n, phi, opt), &set, opt, &resp)?;
            (c.constants_max_fraction <= CANCELLED_FRACTION && c.cycle_s <= opt.max_cycle_s)
                .then_some(c)
        })
        .collect();
    let evaluated = results.iter().map(|r| r.1).sum::<usize>() + family.len();
    let refused =
        results.iter().map(|r| r.2).sum::<usize>() + family.iter().filter(|c| c.is_none()).count();
    let mut all: Vec<Candidate> = results
        .into_iter()
        .flat_map(|r| r.0)
        .chain(family.into_iter().flatten())
        .collect();
    all.sort_by(|a, b| {
        a.score_m
            .total_cmp(&b.score_m)
            .then(a.cycle_s.total_cmp(&b.cycle_s))
    });
    all.dedup_by(|a, b| a.file.scheme == b.file.scheme);
    all.truncate(3 * opt.top);
    let mut all: Vec<Candidate> = all
        .par_iter()
        .filter_map(|c| judge(&c.file, &set, opt_full, &resp))
        .collect();
    // Scores within 0.1 % of the reference's worst case count as equal: the shorter cycle wins.
    let grain = 1e-3 * reference.score_m.max(f64::MIN_POSITIVE);
    all.sort_by_key(|c| ((c.score_m / grain).round() as i64, (c.cycle_s * 1e3) as i64));
    all.truncate(opt.top);
    for (k, c) in all.iter_mut().enumerate() {
        c.file.name = format!(
            "designed-{}-{}-{}",
            opt.class.replace("(u)", "").replace("plant-", ""),
            c.file.scheme.steps.len(),
            k + 1
        );
    }
    let invariant_m = reference.bounds[0].invariant_horizontal_m;
    Ok(DesignReport {
        options: opt_full.clone(),
        reference,
        best: all,
        evaluated,
        refused,
        invariant_m,
        anisotropic_floor_m: 0.5 * invariant_m,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
