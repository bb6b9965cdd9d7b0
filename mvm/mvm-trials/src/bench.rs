//! The randomised benchmark of the diagnosis: trials that draw an effect class, a design, a
//! magnitude (from the oracle z) and noise, run `rins diagnose --iterate` on the log, and
//! score what it kept; rates per class with binomial intervals (diagnosis-benchmark.md).
//!
//! Every trial is drawn from its own seed (the benchmark's seed and the trial's index through
//! SplitMix64), on named ChaCha8 streams, so a failing trial is replayed alone with
//! [`run_trial`] of its [`TrialSpec`].

use std::time::Instant;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::SeedableRng;
use rayon::prelude::*;
use rins_mvm::{IterateOptions, Options, iterate};
use rins_plant::PlantConfig;
use serde::Serialize;

use crate::classes::{Class, draw_effect};
use crate::design::Design;
use crate::draw::draw_design;
use crate::expect::{Score, effect_name, score};
use crate::hidden::HiddenEffect;
use crate::{generate, oracle_z_per_channel, scale_to_z};

/// The stream of a trial's draws (design, model, effects, magnitude).
pub const TRIAL_STREAM: u64 = 0x7121_A100;
/// The oracle z band magnitudes are drawn from.
pub const Z_BAND: (f64, f64) = (6.0, 30.0);
/// Oracle z at or above which an effect must be identified on a channel.
pub const MIN_Z_CHANNEL: f64 = 5.0;

/// One trial: its index, class and seed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TrialSpec {
    /// Index in the benchmark.
    pub index: usize,
    /// The class it hides.
    pub class: Class,
    /// Its seed (design, model, effects, magnitude; the noise seed is drawn from it).
    pub seed: u64,
    /// A paired control: the trial of this class and seed drawn as it is (design, model, noise)
    /// with nothing hidden, so the false-claim rate is measured on exactly the designs the
    /// effect trials ran on, as many of them.
    pub paired_control: bool,
}

impl TrialSpec {
    /// Whether nothing is hidden (a drawn control or a paired one).
    pub fn is_control(&self) -> bool {
        self.paired_control || self.class == Class::Control
    }
}

/// SplitMix64: the trial seeds from the benchmark's.
fn splitmix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = x;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// `n` trials cycling through `classes` (a control every time the cycle ends, when the list
/// holds it), seeded from `seed`.
pub fn plan(n: usize, seed: u64, classes: &[Class]) -> Vec<TrialSpec> {
    (0..n)
        .map(|index| TrialSpec {
            index,
            class: classes[index % classes.len()],
            seed: splitmix(seed ^ splitmix(index as u64)),
            paired_control: false,
        })
        .collect()
}

/// `specs` followed by the paired control of each trial that hides something
/// ([`TrialSpec::paired_control`]), indexed on from the last.
pub fn with_paired_controls(specs: Vec<TrialSpec>) -> Vec<TrialSpec> {
    let mut index = specs.iter().map(|s| s.index + 1).max().unwrap_or(0);
    let controls: Vec<TrialSpec> = specs
        .iter()
        .filter(|s| !s.is_control())
        .map(|s| {
            let c = TrialSpec {
                index,
                paired_control: true,
                ..*s
            };
            index += 1;
            c
        })
        .collect();
    specs.into_iter().chain(controls).collect()
}

/// The benchmark's base model drawn for a trial: gyro bias, scale factor and ARW,
/// accelerometer bias, scale factor and VRW (what the generator writes without hidden effects).
fn draw_model(rng: &mut ChaCha8Rng) -> PlantConfig {
    let mut m = PlantConfig::default();
    let g = &mut m.sensor.gyro;
    g.bias.enabled = true;
    g.bias.dph = [(); 3].map(|_| rng.random_range(-0.02..=0.02));
    g.scale_factor.enabled = true;
    g.scale_factor.ppm = [(); 3].map(|_| rng.random_range(-5.0..=5.0));
    g.angle_random_walk.enabled = true;
    g.angle_random_walk.dpsh = [rng.random_range(0.001..=0.005); 3];
    let a = &mut m.sensor.accel;
    a.bias.enabled = true;
    a.bias.ug = [(); 3].map(|_| rng.random_range(-100.0..=100.0));
    a.scale_factor.enabled = true;
    a.scale_factor.ppm = [(); 3].map(|_| rng.random_range(-100.0..=100.0));
    a.velocity_random_walk.enabled = true;
    a.velocity_random_walk.ug_per_sqrthz = [rng.random_range(5.0..=30.0); 3];
    m
}

/// A drawn trial: the design, the model as given, the hidden effects with their target z.
#[derive(Clone, Debug)]
pub struct Trial {
    /// The spec it was drawn from.
    pub spec: TrialSpec,
    /// The design.
    pub design: Design,
    /// The model as given (the design's mount and rate).
    pub model: PlantConfig,
    /// The hidden effects, scaled to their oracle z.
    pub hidden: Vec<HiddenEffect>,
    /// Each effect's oracle z (the drawn target).
    pub z: Vec<f64>,
    /// Each effect's oracle z per axis of its sensor.
    pub z_channels: Vec<Vec<(usize, f64)>>,
    /// Each effect's twins ([`crate::classes::twins`]) with its oracle z beyond each, per axis.
    pub twin_z: Vec<Vec<(HiddenEffect, Vec<(usize, f64)>)>>,
    /// The noise seed.
    pub noise_seed: u64,
}

/// The single classes a composite trial draws from: every single class but the catalogue's
/// constants (a composite of a constant and another effect is a constant's trial again).
fn composite_pool() -> Vec<Class> {
    Class::SINGLE
        .into_iter()
        .filter(|c| {
            !matches!(
                c,
                Class::GyroBias
                    | Class::GyroScaleFactor
                    | Class::AccelBias
                    | Class::AccelScaleFactor
            )
        })
        .collect()
}

/// Draws the trial of `spec`: the design, then each effect's shape, then its magnitude from a
/// target oracle z in [`Z_BAND`]; an effect the design cannot show (oracle z 0) is drawn again
/// on another axis, and after 20 such draws on a new design.
pub fn draw_trial(spec: TrialSpec) -> Trial {
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    rng.set_stream(TRIAL_STREAM);
    let classes: Vec<Class> = match spec.class {
        Class::Control => Vec::new(),
        Class::Two | Class::Three => {
            let n = if spec.class == Class::Two { 2 } else { 3 };
            let mut pool = composite_pool();
            let mut out = Vec::new();
            for _ in 0..n {
                let i = rng.random_range(0..pool.len());
                out.push(pool.remove(i));
            }
            out
        }
        c => vec![c],
    };
    loop {
        let design = draw_design(&mut rng);
        let model = design.model_for(&draw_model(&mut rng));
        let mut hidden = Vec::new();
        let mut z = Vec::new();
        let mut ok = true;
        for &c in &classes {
            let target = rng.random_range(Z_BAND.0..=Z_BAND.1);
            let scaled = (0..20).find_map(|_| {
                scale_to_z(&model, &design, &draw_effect(c, &mut rng), target)
                    .filter(crate::classes::plausible)
            });
            match scaled {
                Some(e) => {
                    hidden.push(e);
                    z.push(target);
                }
                None => {
                    ok = false;
                    break;
                }
            }
        }
        if !ok {
            continue;
        }
        let z_channels = hidden
            .iter()
            .map(|e| {
                oracle_z_per_channel(&model, &design, e)
                    .into_iter()
                    .map(|(c, z)| (c.axis, z))
                    .collect()
            })
            .collect();
        let twin_z = hidden
            .iter()
            .map(|e| {
                crate::classes::twins(e)
                    .into_iter()
                    .map(|t| {
                        let z = crate::oracle_z_beyond(&model, &design, e, &t)
                            .into_iter()
                            .map(|(c, z)| (c.axis, z))
                            .collect();
                        (t, z)
                    })
                    .collect()
            })
            .collect();
        let noise_seed = rng.random();
        if spec.paired_control {
            return Trial {
                spec,
                design,
                model,
                hidden: Vec::new(),
                z: Vec::new(),
                z_channels: Vec::new(),
                twin_z: Vec::new(),
                noise_seed,
            };
        }
        return Trial {
            twin_z,
            spec,
            design,
            model,
            hidden,
            z,
            z_channels,
            noise_seed,
        };
    }
}

/// What one trial gave.
#[derive(Clone, Debug, Serialize)]
pub struct Outcome {
    /// The trial.
    pub spec: TrialSpec,
    /// Its design.
    pub design: String,
    /// The hidden effects (as drawn and scaled).
    pub hidden: Vec<String>,
    /// Their oracle z.
    pub z: Vec<f64>,
    /// The oracle z of what the scoring demands of each ([`demanded_z`]): its z, or, where the
    /// design tells it from a twin (z beyond the twin at least [`MIN_Z_CHANNEL`]), the z beyond
    /// the twin. The z bands and the strong rate are judged by it.
    pub z_demanded: Vec<f64>,
    /// The scoring.
    pub score: Score,
    /// Every channel at most 1.10× its floor with no cell flagged at the end.
    pub floor: bool,
    /// The iteration claimed the floor while a channel stayed above it.
    pub false_floor: bool,
    /// Steps the iteration took.
    pub steps: usize,
    /// Why it stopped (or the error, or the panic, which count as failures).
    pub stop: String,
    /// Wall time of generate + iterate, s.
    pub wall_s: f64,
}

/// Per hidden effect, the oracle z of what the scoring asks of it. Keeping a twin identifies an
/// effect on a channel where the design cannot tell the two apart (z beyond the twin below
/// [`MIN_Z_CHANNEL`]); elsewhere the effect itself must be kept, against the twin, and the
/// evidence for that choice is the z beyond the twin, not the effect's whole z (a quadratic
/// scale factor of z 11 may be 95 % its linear twin, with z 5 of its own).
pub fn demanded_z(trial: &Trial) -> Vec<f64> {
    trial
        .z
        .iter()
        .zip(&trial.twin_z)
        .map(|(&z, twins)| {
            twins
                .iter()
                .flat_map(|(_, per_axis)| per_axis.iter().map(|(_, zb)| *zb))
                .filter(|zb| *zb >= MIN_Z_CHANNEL)
                .fold(z, f64::min)
        })
        .collect()
}

/// Draws, generates and diagnoses one trial, and scores it.
pub fn run_trial(spec: TrialSpec) -> Outcome {
    let t0 = Instant::now();
    let trial = draw_trial(spec);
    let base = Outcome {
        spec,
        design: trial.design.name.clone(),
        hidden: trial.hidden.iter().map(|e| format!("{e:?}")).collect(),
        z: trial.z.clone(),
        z_demanded: demanded_z(&trial),
        score: Score::default(),
        floor: false,
        false_floor: false,
        steps: 0,
        stop: String::new(),
        wall_s: 0.0,
    };
    let run = std::panic::catch_unwind(|| {
        let h = generate(&trial.model, &trial.design, &trial.hidden, trial.noise_seed);
        iterate(
            &trial.model,
            &h,
            &Options::default(),
            &IterateOptions::default(),
        )
    });
    let mut out = base;
    match run {
        Ok(Ok(it)) => {
            out.score = score(
                &it,
                &trial.model,
                &trial.hidden,
                &trial.z_channels,
                &trial.twin_z,
                MIN_Z_CHANNEL,
            );
            let last = it.report.steps.last();
            out.floor = last
                .is_some_and(|s| s.levels.iter().all(|l| l.ratio <= 1.10) && s.flagged_cells == 0);
            out.false_floor = it.report.reached_floor && !out.floor;
            out.steps = it.report.steps.len();
            out.stop = it.report.stop.clone();
        }
        Ok(Err(e)) => {
            out.score.missing = trial.hidden.iter().map(effect_name).collect();
            out.stop = format!("error: {e}");
        }
        Err(_) => {
            out.score.missing = trial.hidden.iter().map(effect_name).collect();
            out.stop = "panicked".into();
        }
    }
    out.wall_s = t0.elapsed().as_secs_f64();
    out
}

/// A rate with its count and 95 % Wilson interval.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Rate {
    /// Successes.
    pub hits: usize,
    /// Trials.
    pub n: usize,
    /// hits / n.
    pub rate: f64,
    /// 95 % Wilson score interval.
    pub ci95: [f64; 2],
}

impl Rate {
    /// The rate of `hits` in `n`.
    pub fn of(hits: usize, n: usize) -> Rate {
        let z = 1.959_963_984_540_054_f64;
        if n == 0 {
            return Rate {
                hits,
                n,
                rate: f64::NAN,
                ci95: [f64::NAN; 2],
            };
        }
        let nf = n as f64;
        let p = hits as f64 / nf;
        let d = 1.0 + z * z / nf;
        let c = (p + z * z / (2.0 * nf)) / d;
        let h = z * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt() / d;
        Rate {
            hits,
            n,
            rate: p,
            ci95: [(c - h).max(0.0), (c + h).min(1.0)],
        }
    }

    /// `47/50 (0.94 [0.84, 0.98])`.
    pub fn text(&self) -> String {
        if self.n == 0 {
            return "–".into();
        }
        format!(
            "{}/{} ({:.2} [{:.2}, {:.2}])",
            self.hits, self.n, self.rate, self.ci95[0], self.ci95[1]
        )
    }
}

/// The rates of one class (and z band).
#[derive(Clone, Debug, Serialize)]
pub struct ClassRates {
    /// The class.
    pub class: String,
    /// The oracle z band (`all`, `6–8`, `8–15`, `15–30`).
    pub band: String,
    /// Correct identification (controls: nothing kept).
    pub correct: Rate,
    /// Correct identification of the trials whose weakest hidden effect has an oracle z of
    /// at least [`STRONG_Z`] (controls: all of them), the bar of 95 %.
    pub correct_strong: Rate,
    /// True coefficients inside the 95 % intervals.
    pub coverage: Rate,
    /// Every channel at its floor at the end.
    pub floor: Rate,
    /// Controls with anything kept (controls only).
    pub false_claims: Option<Rate>,
    /// Trials that claimed the floor above it.
    pub false_floor: usize,
    /// Mean wall time per trial, s.
    pub mean_wall_s: f64,
}

/// The whole benchmark.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Its seed.
    pub seed: u64,
    /// Every trial.
    pub outcomes: Vec<Outcome>,
    /// Rates per class and band.
    pub rates: Vec<ClassRates>,
    /// Wall time of the whole run, s.
    pub wall_s: f64,
}

/// The oracle z from which an effect counts as strong: every single class must be
/// identified in 95 % of its trials there (below it, z 6–8, the rate is reported apart).
pub const STRONG_Z: f64 = 8.0;

/// The name of the row of paired controls ([`TrialSpec::paired_control`]).
pub const PAIRED_CONTROLS: &str = "paired controls";

fn rates(class: &str, band: &str, outs: &[&Outcome]) -> ClassRates {
    let n = outs.len();
    let control = outs.iter().all(|o| o.spec.is_control());
    let correct = outs.iter().filter(|o| o.score.correct).count();
    let strong: Vec<&&Outcome> = outs
        .iter()
        .filter(|o| o.z_demanded.iter().all(|z| *z >= STRONG_Z))
        .collect();
    let cov: Vec<bool> = outs
        .iter()
        .flat_map(|o| o.score.coverage.iter().map(|c| c.covers))
        .collect();
    ClassRates {
        class: class.into(),
        band: band.into(),
        correct: Rate::of(correct, n),
        correct_strong: Rate::of(
            strong.iter().filter(|o| o.score.correct).count(),
            strong.len(),
        ),
        coverage: Rate::of(cov.iter().filter(|c| **c).count(), cov.len()),
        floor: Rate::of(outs.iter().filter(|o| o.floor).count(), n),
        false_claims: control.then(|| Rate::of(n - correct, n)),
        false_floor: outs.iter().filter(|o| o.false_floor).count(),
        mean_wall_s: outs.iter().map(|o| o.wall_s).sum::<f64>() / n.max(1) as f64,
    }
}

/// The rates per class (all bands, then for single classes each band).
pub fn aggregate(outcomes: &[Outcome]) -> Vec<ClassRates> {
    let mut out = Vec::new();
    // By the demanded z: below 6 only an effect that must be told from its twin.
    let bands: [(&str, f64, f64); 4] = [
        ("5–6", 5.0, 6.0),
        ("6–8", 6.0, 8.0),
        ("8–15", 8.0, 15.0),
        ("15–30", 15.0, 30.1),
    ];
    for class in Class::all() {
        let of: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.spec.class == class && !o.spec.paired_control)
            .collect();
        if of.is_empty() {
            continue;
        }
        out.push(rates(class.name(), "all", &of));
    }
    let paired: Vec<&Outcome> = outcomes.iter().filter(|o| o.spec.paired_control).collect();
    if !paired.is_empty() {
        out.push(rates(PAIRED_CONTROLS, "all", &paired));
    }
    // Every trial that hides something: the coverage the intervals are judged by.
    let hiding: Vec<&Outcome> = outcomes.iter().filter(|o| !o.spec.is_control()).collect();
    if !hiding.is_empty() {
        out.push(rates("every effect trial", "all", &hiding));
    }
    // Single classes together, by band of the effect's oracle z.
    for (name, lo, hi) in bands {
        let of: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| {
                Class::SINGLE.contains(&o.spec.class)
                    && !o.spec.paired_control
                    && o.z_demanded.first().is_some_and(|z| *z >= lo && *z < hi)
            })
            .collect();
        if !of.is_empty() {
            out.push(rates("single (all classes)", name, &of));
        }
    }
    out
}

/// Runs `specs` on both cores (each trial's iteration uses them too), calling `done` after each
/// trial (for a progress bar).
pub fn run(specs: &[TrialSpec], seed: u64, done: &(dyn Fn(&Outcome) + Sync)) -> Report {
    let t0 = Instant::now();
    let outcomes: Vec<Outcome> = specs
        .par_iter()
        .map(|s| {
            let o = run_trial(*s);
            done(&o);
            o
        })
        .collect();
    Report {
        seed,
        rates: aggregate(&outcomes),
        outcomes,
        wall_s: t0.elapsed().as_secs_f64(),
    }
}

/// The rates as a Markdown table.
pub fn markdown(r: &Report) -> String {
    let mut s = String::from(
        "| class | z band | correct identification | correct at z ≥ 8 | 95 % coverage | floor reached | false claims | false floor | s/trial |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for c in &r.rates {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.1} |\n",
            c.class,
            c.band,
            c.correct.text(),
            c.correct_strong.text(),
            c.coverage.text(),
            c.floor.text(),
            c.false_claims.map_or("–".into(), |f| f.text()),
            c.false_floor,
            c.mean_wall_s
        ));
    }
    s
}
