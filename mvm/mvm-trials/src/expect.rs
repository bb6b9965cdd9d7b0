//! What the diagnosis should keep for a hidden effect, and what of its coefficients it should
//! cover: the scoring of one trial (diagnosis-benchmark.md, "What to report").
//!
//! An effect is identified on a channel when a kept term there is the effect, by the
//! catalogue's name or as a declared regressor that is the same function of the signals
//! (a temperature bias as `temp:block`, a dither bias as `u_i^2`: identical on any data up to
//! the bias, which heredity fits with it). A kept term is explained when it identifies a
//! hidden effect, or is a parent of one that does (the constant of its kind, a lower power or
//! factor). Coefficients are compared in the units and reference the tool writes (absolute
//! temperature for a declared regressor, 25 °C for the catalogue's polynomials).

use rins_mvm::Iteration;
use rins_mvm::discover::TauReport;
use rins_plant::PlantConfig;
use serde::Serialize;

use crate::hidden::{HiddenEffect, Sensor};

/// A term the iteration kept.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Kept {
    /// Channel 0–5 (gyro x, y, z, accelerometer x, y, z).
    pub channel: usize,
    /// `gyro.bias`, `custom:NAME`.
    pub effect: String,
    /// The declared regressor (for `custom:` terms).
    pub regressor: Option<String>,
    /// A memory term's time constant.
    pub tau: Option<TauReport>,
    /// The effects the diagnosis named confusable with it on this data.
    pub confusable: Vec<String>,
}

/// The terms the iteration kept, over all its steps.
pub fn kept_terms(it: &Iteration) -> Vec<Kept> {
    let mut out: Vec<Kept> = Vec::new();
    for s in &it.report.steps {
        for a in s.accepted.iter().filter(|a| a.kept) {
            let channel = rins_mvm::CHANNELS
                .iter()
                .position(|c| *c == a.channel)
                .unwrap_or(0);
            let regressor = a.effect.strip_prefix("custom:").and_then(|name| {
                let list = if channel >= 3 {
                    &it.model.sensor.accel.custom
                } else {
                    &it.model.sensor.gyro.custom
                };
                list.iter()
                    .find(|c| c.name == name)
                    .map(|c| c.regressor.replace(' ', ""))
            });
            let k = Kept {
                channel,
                effect: a.effect.clone(),
                regressor,
                tau: a.tau,
                confusable: a.confusable_with.clone(),
            };
            if !out.contains(&k) {
                out.push(k);
            }
        }
    }
    out
}

/// One way a kept term identifies an effect.
#[derive(Clone, Debug, PartialEq)]
enum Want {
    /// A catalogue effect by name.
    Catalogue(&'static str),
    /// A declared regressor, exactly.
    Regressor(String),
    /// A declared regressor with this prefix (a memory term, any time constant).
    Prefix(&'static str),
}

/// The name discovery gives a proposal of a bias (or scale factor) with `regressor` of one or
/// two plain factors (`dtemp_dt:block` → `b_dtdt_block`), as its confusable lists name it.
fn proposal_name(scale_factor: bool, regressor: &str) -> Option<String> {
    use rins_mvm::discover::library::Term;
    use rins_plant::effects::custom::{CustomKind, Signal};
    let mut factors = Vec::new();
    for f in regressor.split('*') {
        let (n, p) = f.split_once('^').unwrap_or((f, "1"));
        let s = Signal::parse(n)?;
        for _ in 0..p.parse::<usize>().ok()? {
            factors.push(s);
        }
    }
    let kind = if scale_factor {
        CustomKind::ScaleFactor
    } else {
        CustomKind::Bias
    };
    (factors.len() <= 2).then(|| Term::Product { factors, kind }.name())
}

impl Want {
    fn matches(&self, k: &Kept) -> bool {
        match self {
            Want::Catalogue(n) => k.effect == *n,
            Want::Regressor(r) => k.regressor.as_deref() == Some(r.as_str()),
            Want::Prefix(p) => k.regressor.as_deref().is_some_and(|r| r.starts_with(p)),
        }
    }

    /// Whether `k` names this effect among those confusable with it on the data (a choice
    /// between two explanations the design cannot separate, named as such).
    fn named_confusable(&self, k: &Kept) -> bool {
        k.confusable.iter().any(|c| match self {
            Want::Catalogue(n) => c == n,
            Want::Regressor(r) => [false, true]
                .into_iter()
                .any(|sf| proposal_name(sf, r).is_some_and(|name| *c == format!("custom:{name}"))),
            Want::Prefix(_) => false,
        })
    }
}

fn channel_of(e: &HiddenEffect, axis: usize) -> usize {
    axis + if e.sensor() == Sensor::Accel { 3 } else { 0 }
}

/// What identifies `e` on a channel it acts on, and what may come with it as parents.
fn wants(e: &HiddenEffect) -> (Vec<Want>, Vec<Want>) {
    use HiddenEffect as H;
    let gyro_consts = vec![
        Want::Catalogue("gyro.bias"),
        Want::Catalogue("gyro.scale_factor"),
    ];
    let accel_consts = vec![
        Want::Catalogue("accel.bias"),
        Want::Catalogue("accel.scale_factor"),
    ];
    match e {
        H::GyroBias { .. } => (vec![Want::Catalogue("gyro.bias")], gyro_consts),
        H::GyroScaleFactor { .. } => (vec![Want::Catalogue("gyro.scale_factor")], gyro_consts),
        H::GyroScaleFactorAsymmetry { .. } => (
            vec![Want::Catalogue("gyro.scale_factor_asymmetry")],
            gyro_consts,
        ),
        H::GyroMisalignment { .. } => (vec![Want::Catalogue("gyro.misalignment")], gyro_consts),
        H::GyroTemperatureBias { .. } => (
            vec![
                Want::Catalogue("gyro.temperature_bias"),
                Want::Regressor("temp:block".into()),
                Want::Regressor("temp:block^2".into()),
            ],
            [gyro_consts, vec![Want::Regressor("temp:block".into())]].concat(),
        ),
        H::GyroGradientBias { .. } => (
            vec![
                Want::Catalogue("gyro.temperature_gradient_bias"),
                Want::Regressor("grad:block-housing".into()),
            ],
            gyro_consts,
        ),
        H::GyroGSensitivity { from, .. } => {
            let mut w = vec![
                Want::Catalogue("gyro.g_sensitivity"),
                // A bias ∝ u_j is G_ij·f_j/g₀ by definition.
                Want::Regressor(["u_x", "u_y", "u_z"][*from].into()),
            ];
            if *from == 2 {
                // δβ·(1 − u_z)/2 (the position bias, cosine transition) is the bias and
                // −δβ/2·u_z: G_iz with a bias, by definition.
                w.push(Want::Catalogue("gyro.position_bias"));
            }
            (w, gyro_consts)
        }
        H::GyroPositionBias { .. } => (vec![Want::Catalogue("gyro.position_bias")], gyro_consts),
        H::GyroDitherBias { dph } => {
            let axis = (0..3).find(|i| dph[*i] != 0.0).unwrap_or(0);
            let u = ["u_x", "u_y", "u_z"][axis];
            (
                vec![
                    Want::Catalogue("gyro.dither_bias"),
                    Want::Regressor(format!("{u}^2")),
                ],
                [gyro_consts, vec![Want::Catalogue("gyro.g_sensitivity")]].concat(),
            )
        }
        H::AccelBias { .. } => (vec![Want::Catalogue("accel.bias")], accel_consts),
        H::AccelScaleFactor { .. } => (vec![Want::Catalogue("accel.scale_factor")], accel_consts),
        H::AccelMisalignment { .. } => (vec![Want::Catalogue("accel.misalignment")], accel_consts),
        H::AccelTemperatureBias { .. } => (
            vec![
                Want::Catalogue("accel.temperature_bias"),
                Want::Regressor("temp:block".into()),
            ],
            accel_consts,
        ),
        // The block follows the housing through a lag of minutes and an offset: a term in the
        // housing temperature is the same function to within that lag (counted as identified).
        H::ScaleFactorTempLinear { .. } => (
            vec![
                Want::Regressor("temp:block".into()),
                Want::Regressor("temp:housing".into()),
            ],
            gyro_consts,
        ),
        H::ScaleFactorTempQuadratic { .. } => (
            vec![
                Want::Regressor("temp:block^2".into()),
                Want::Regressor("temp:housing^2".into()),
                Want::Regressor("temp:block*temp:housing".into()),
            ],
            [
                gyro_consts,
                vec![
                    Want::Regressor("temp:block".into()),
                    Want::Regressor("temp:housing".into()),
                ],
            ]
            .concat(),
        ),
        H::TempRateBias { .. } => (vec![Want::Regressor("dtemp_dt:block".into())], gyro_consts),
        H::UpProductBias { a, b, .. } => {
            let u = ["u_x", "u_y", "u_z"];
            let r = if a == b {
                format!("{}^2", u[*a])
            } else {
                format!("{}*{}", u[*a], u[*b])
            };
            (
                vec![Want::Regressor(r)],
                [gyro_consts, vec![Want::Catalogue("gyro.g_sensitivity")]].concat(),
            )
        }
        H::NavFieldBias { .. } => (vec![Want::Catalogue("gyro.nav_field_bias")], gyro_consts),
        H::PostMoveTransient { .. } => (vec![Want::Prefix("exp(-since_move/")], gyro_consts),
        H::LaggedTempBias { .. } => (
            vec![
                Want::Prefix("lag(temp:block,"),
                // A lag of the housing: the block is the housing through a lag of its own.
                Want::Prefix("lag(temp:housing,"),
            ],
            gyro_consts,
        ),
    }
}

/// A true coefficient compared with the tool's interval.
#[derive(Clone, Debug, Serialize)]
pub struct Covered {
    /// What it is (`gyro_z sf temp:block` …).
    pub what: String,
    /// The truth, in the tool's file units.
    pub truth: f64,
    /// The tool's 95 % interval.
    pub ci95: [f64; 2],
    /// Whether it covers the truth.
    pub covers: bool,
}

/// The scoring of one trial.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Score {
    /// Every hidden effect identified on each channel it must be, and nothing unexplained kept.
    pub correct: bool,
    /// Hidden effects (by channel) not identified.
    pub missing: Vec<String>,
    /// Kept terms that explain no hidden effect.
    pub extra: Vec<String>,
    /// The true coefficients compared.
    pub coverage: Vec<Covered>,
    /// Effects kept as another that the diagnosis named confusable with them (identical on
    /// the data): counted as identified.
    pub named_confusable: Vec<String>,
}

/// The last fitted interval the iteration wrote or kept for `key`.
fn interval(it: &Iteration, key: &str) -> Option<[f64; 2]> {
    it.report
        .steps
        .iter()
        .flat_map(|s| &s.coefficients)
        .filter(|c| c.key == key)
        .filter_map(|c| c.ci95)
        .next_back()
}

/// The key of declared effect `name`'s coefficient on `axis` in the final model.
fn declared_key(it: &Iteration, accel: bool, name: &str, axis: usize) -> Option<String> {
    let list = if accel {
        &it.model.sensor.accel.custom
    } else {
        &it.model.sensor.gyro.custom
    };
    let k = list
        .iter()
        .position(|c| format!("custom:{}", c.name) == name)?;
    Some(format!(
        "sensor.{}.custom[{k}].coef[{axis}]",
        if accel { "accel" } else { "gyro" }
    ))
}

/// The primary true coefficients of `e` on `axis` as (scenario key, truth in file units), given
/// the term `k` that identified it.
fn truths(
    e: &HiddenEffect,
    axis: usize,
    k: &Kept,
    model: &PlantConfig,
    it: &Iteration,
) -> Vec<(String, f64)> {
    use HiddenEffect as H;
    // A term in the housing temperature identifies a block-temperature effect, but its
    // coefficients are the housing's: nothing to compare.
    if k.regressor
        .as_deref()
        .is_some_and(|r| r.contains("temp:housing"))
    {
        return Vec::new();
    }
    let declared = k.effect.starts_with("custom:");
    let dk = || declared_key(it, e.sensor() == Sensor::Accel, &k.effect, axis);
    let g = &model.sensor.gyro;
    let a = &model.sensor.accel;
    let on = |enabled: bool, v: f64| if enabled { v } else { 0.0 };
    let pair = |i: usize, j: usize| {
        rins_plant::effects::MISALIGNMENT_PAIRS
            .iter()
            .position(|p| *p == (i, j))
            .unwrap_or(0)
    };
    let mut v: Vec<(String, f64)> = Vec::new();
    match e {
        H::GyroBias { dph } => v.push((
            format!("sensor.gyro.bias.dph[{axis}]"),
            on(g.bias.enabled, g.bias.dph[axis]) + dph[axis],
        )),
        H::GyroScaleFactor { ppm } => v.push((
            format!("sensor.gyro.scale_factor.ppm[{axis}]"),
            on(g.scale_factor.enabled, g.scale_factor.ppm[axis]) + ppm[axis],
        )),
        H::GyroScaleFactorAsymmetry { ppm } => v.push((
            format!("sensor.gyro.scale_factor_asymmetry.ppm[{axis}]"),
            ppm[axis],
        )),
        H::GyroMisalignment {
            axis: i,
            from,
            arcsec,
        } => v.push((
            format!("sensor.gyro.misalignment.arcsec[{}]", pair(*i, *from)),
            *arcsec,
        )),
        H::GyroTemperatureBias { per_k, per_k2 } => {
            if declared {
                if per_k2[axis] == 0.0
                    && let Some(key) = dk()
                {
                    v.push((key, per_k[axis]));
                }
            } else {
                v.push((
                    format!("sensor.gyro.temperature_bias.per_k[{axis}]"),
                    per_k[axis],
                ));
                if per_k2[axis] != 0.0 {
                    v.push((
                        format!("sensor.gyro.temperature_bias.per_k2[{axis}]"),
                        per_k2[axis],
                    ));
                }
            }
        }
        H::GyroGradientBias { dph_per_k } => {
            let key = if declared {
                dk()
            } else {
                Some(format!(
                    "sensor.gyro.temperature_gradient_bias.dph_per_k[{axis}]"
                ))
            };
            v.extend(key.map(|k| (k, dph_per_k[axis])));
        }
        H::GyroGSensitivity {
            axis: i,
            from,
            dph_per_g,
        } => v.push((
            format!("sensor.gyro.g_sensitivity.dph_per_g[{i}][{from}]"),
            *dph_per_g,
        )),
        H::GyroPositionBias { dph, dph_per_k } => {
            v.push((format!("sensor.gyro.position_bias.dph[{axis}]"), dph[axis]));
            v.push((
                format!("sensor.gyro.position_bias.dph_per_k[{axis}]"),
                dph_per_k[axis],
            ));
        }
        H::GyroDitherBias { dph } => {
            if !declared {
                v.push((
                    format!("sensor.gyro.dither_bias.dph_per_amplitude[{axis}]"),
                    dph[axis],
                ));
            } else if let Some(key) = dk() {
                v.push((key, dph[axis]));
            }
        }
        H::AccelBias { ug } => v.push((
            format!("sensor.accel.bias.ug[{axis}]"),
            on(a.bias.enabled, a.bias.ug[axis]) + ug[axis],
        )),
        H::AccelScaleFactor { ppm } => v.push((
            format!("sensor.accel.scale_factor.ppm[{axis}]"),
            on(a.scale_factor.enabled, a.scale_factor.ppm[axis]) + ppm[axis],
        )),
        H::AccelMisalignment {
            axis: i,
            from,
            arcsec,
        } => v.push((
            format!("sensor.accel.misalignment.arcsec[{}]", pair(*i, *from)),
            *arcsec,
        )),
        H::AccelTemperatureBias { ug_per_k } => {
            let key = if declared {
                dk()
            } else {
                Some(format!("sensor.accel.temperature_bias.per_k[{axis}]"))
            };
            v.extend(key.map(|k| (k, ug_per_k[axis])));
        }
        H::ScaleFactorTempLinear { ppm_per_k, .. } => v.extend(dk().map(|k| (k, ppm_per_k[axis]))),
        H::ScaleFactorTempQuadratic { ppm_per_k2 } => v.extend(dk().map(|k| (k, ppm_per_k2[axis]))),
        H::TempRateBias { dph_per_k_per_s } => v.extend(dk().map(|k| (k, dph_per_k_per_s[axis]))),
        H::UpProductBias { dph, .. } => v.extend(dk().map(|k| (k, dph[axis]))),
        H::NavFieldBias {
            dph,
            inclination_deg,
            declination_deg,
        } => {
            let (i, d) = (inclination_deg.to_radians(), declination_deg.to_radians());
            let m = [i.cos() * d.sin(), i.cos() * d.cos(), -i.sin()];
            let keys: Vec<String> = (0..3)
                .map(|j| format!("sensor.gyro.nav_field_bias.dph_enu[{axis}][{j}]"))
                .collect();
            // A component the data cannot separate makes the others combinations: compare
            // only axes whose three components are all determined.
            if keys.iter().all(|k| interval(it, k).is_some()) {
                for (j, key) in keys.into_iter().enumerate() {
                    v.push((key, dph[axis] * m[j]));
                }
            }
        }
        H::PostMoveTransient { dph, .. } => v.extend(dk().map(|k| (k, dph[axis]))),
        H::LaggedTempBias { dph_per_k, .. } => v.extend(dk().map(|k| (k, dph_per_k[axis]))),
    }
    v
}

/// Scores the iteration `it` of a trial with `hidden` effects (each with its per-channel
/// oracle z, `z_channels`) on `model`: it must identify each effect on every channel where its
/// oracle z is at least `min_z`, and keep nothing unexplained.
#[allow(clippy::type_complexity)]
pub fn score(
    it: &Iteration,
    model: &PlantConfig,
    hidden: &[HiddenEffect],
    z_channels: &[Vec<(usize, f64)>],
    twin_z: &[Vec<(HiddenEffect, Vec<(usize, f64)>)>],
    min_z: f64,
) -> Score {
    let kept = kept_terms(it);
    let mut s = Score::default();
    let mut explained = vec![false; kept.len()];
    for ((e, zs), twins) in hidden.iter().zip(z_channels).zip(twin_z) {
        let (own_want, own_parents) = wants(e);
        for &(axis, z) in zs {
            let c = channel_of(e, axis);
            // A twin the design cannot tell from it on this channel identifies it too.
            let (mut want, mut parents) = (own_want.clone(), own_parents.clone());
            for (t, tz) in twins {
                if tz.iter().any(|(a, z)| *a == axis && *z < min_z) {
                    let (w, p) = wants(t);
                    want.extend(w);
                    parents.extend(p);
                }
            }
            let found = kept
                .iter()
                .position(|k| k.channel == c && own_want.iter().any(|w| w.matches(k)));
            let by_twin = found
                .is_none()
                .then(|| {
                    kept.iter()
                        .position(|k| k.channel == c && want.iter().any(|w| w.matches(k)))
                })
                .flatten();
            if let Some(i) = by_twin {
                explained[i] = true;
                s.named_confusable.push(format!(
                    "{} on {} as {} (its oracle z beyond that is below {min_z})",
                    effect_name(e),
                    rins_mvm::CHANNELS[c],
                    kept[i].effect
                ));
            }
            let twin_found = by_twin.is_some();
            // A term that stands in for it and names it as confusable on this data.
            let stand_in = found.is_none().then(|| {
                kept.iter()
                    .position(|k| k.channel == c && own_want.iter().any(|w| w.named_confusable(k)))
            });
            match found {
                None if twin_found => {}
                None if stand_in.flatten().is_some() => {
                    let i = stand_in.flatten().expect("checked");
                    explained[i] = true;
                    s.named_confusable.push(format!(
                        "{} on {} as {}",
                        effect_name(e),
                        rins_mvm::CHANNELS[c],
                        kept[i].effect
                    ));
                }
                Some(i) => {
                    explained[i] = true;
                    for (key, truth) in truths(e, axis, &kept[i], model, it) {
                        if let Some(ci) = interval(it, &key) {
                            s.coverage.push(Covered {
                                what: format!("{} {}", rins_mvm::CHANNELS[c], key),
                                truth,
                                ci95: ci,
                                covers: ci[0] <= truth && truth <= ci[1],
                            });
                        }
                    }
                    let same_node = !kept[i]
                        .regressor
                        .as_deref()
                        .is_some_and(|r| r.contains("housing"));
                    if let (Some(tau), Some(t), true) = (kept[i].tau, hidden_tau(e), same_node) {
                        s.coverage.push(Covered {
                            what: format!("{} {} tau_s", rins_mvm::CHANNELS[c], kept[i].effect),
                            truth: t,
                            ci95: tau.ci95_s,
                            covers: tau.ci95_s[0] <= t && t <= tau.ci95_s[1],
                        });
                    }
                }
                None if z >= min_z => s.missing.push(format!(
                    "{} on {} (oracle z {z:.1})",
                    effect_name(e),
                    rins_mvm::CHANNELS[c]
                )),
                None => {}
            }
            // Its parents and its other forms on its channels are explained too.
            for (k, x) in kept.iter().zip(explained.iter_mut()) {
                if k.channel == c && (want.iter().chain(&parents).any(|w| w.matches(k))) {
                    *x = true;
                }
            }
        }
    }
    for (k, x) in kept.iter().zip(&explained) {
        if !x {
            s.extra.push(format!(
                "{} on {}",
                k.regressor.as_deref().unwrap_or(&k.effect),
                rins_mvm::CHANNELS[k.channel]
            ));
        }
    }
    s.correct = s.missing.is_empty() && s.extra.is_empty();
    s
}

fn hidden_tau(e: &HiddenEffect) -> Option<f64> {
    match e {
        HiddenEffect::PostMoveTransient { tau_s, .. }
        | HiddenEffect::LaggedTempBias { tau_s, .. } => Some(*tau_s),
        _ => None,
    }
}

/// A short name of an effect (its variant).
pub fn effect_name(e: &HiddenEffect) -> String {
    format!("{e:?}")
        .split([' ', '{'])
        .next()
        .unwrap_or("?")
        .to_string()
}
