//! `--apply`: the model with chosen effects switched on and fitted jointly on the
//! measurements, each coefficient written only when the data determine it, and the model file
//! written back with it.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use rins_plant::PlantConfig;
use rins_plant::effects::{AccelModel, GyroModel};
use rins_plant::params::{self, ParamValue};
use serde::Serialize;

use crate::fit::{self, delta_bic_of, design, wls};
use crate::prepare::Prepared;
use crate::replay::{CHANNELS, Effect, Group};

/// The smallest ratio |correction| / standard error at which a fitted correction is written:
/// below it the 95 % interval of the correction contains zero, the data are consistent with
/// the model's value, and the model's value is kept (a scale factor on an axis that sees only
/// Earth rate is determined to ±10 ppm; writing its fitted value would replace a calibrated
/// number with noise).
pub const MIN_WRITE_Z: f64 = 1.96;

/// What `--apply` did with one coefficient.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Fate {
    /// The fitted value is written.
    Written,
    /// The data are consistent with the model's value (|correction| < 1.96 σ): it is kept.
    Kept,
    /// The data carry no information on it ([`fit::MAX_SE_FILE_UNITS`]): not estimated.
    Null,
}

/// One coefficient of a fitted effect: its value before, the fit, and what was written.
#[derive(Clone, Debug, Serialize)]
pub struct Coefficient {
    /// Scenario key (`sensor.gyro.scale_factor.ppm[2]`).
    pub key: String,
    /// Effect (`gyro.scale_factor`, `custom:NAME`).
    pub effect: String,
    /// Channel.
    pub channel: String,
    /// The model's value, file units.
    pub model: f64,
    /// The fitted value (model + correction), file units; `null` when not identified.
    pub fitted: Option<f64>,
    /// 95 % interval of the fitted value; `null` when not identified.
    pub ci95: Option<[f64; 2]>,
    /// Written, kept or null.
    pub fate: Fate,
    /// Why.
    pub reason: String,
}

/// A model with effects fitted on the measurements.
#[derive(Clone, Debug)]
pub struct Applied {
    /// The model with the effects switched on and their coefficients set.
    pub model: PlantConfig,
    /// The scenario values set (key, value in scenario-file units), in order.
    pub set: Vec<(String, f64)>,
    /// Every coefficient of the fitted effects, written, kept or null, with the reason.
    pub coefficients: Vec<Coefficient>,
}

impl Applied {
    /// The model file `original` (TOML text) with its `[sensor]` replaced by the fitted model's
    /// full sensor specification, headed by the comment `note`.
    pub fn model_file(&self, original: &str, note: &str) -> Result<String, String> {
        model_file(&self.model, original, note)
    }
}

/// The model file `original` (TOML text) with its `[sensor]` replaced by `model`'s full sensor
/// specification, headed by the comment `note`.
pub fn model_file(model: &PlantConfig, original: &str, note: &str) -> Result<String, String> {
    let mut table: toml::Table =
        toml::from_str(original).map_err(|e| format!("model file is not TOML: {e}"))?;
    let mut sensor = toml::Table::try_from(&model.sensor)
        .map_err(|e| format!("serialising the sensor specification: {e}"))?;
    sensor.insert("preset".into(), toml::Value::String("ideal".into()));
    table.insert("sensor".into(), toml::Value::Table(sensor));
    let text =
        toml::to_string_pretty(&table).map_err(|e| format!("serialising the model file: {e}"))?;
    let note = note.replace('\n', " ");
    Ok(format!(
        "# {note}\n# Written by rins diagnose; [sensor] is the complete specification.\n{text}"
    ))
}

/// `model` with `effects` switched on and fitted jointly on every channel they act on (the
/// model as given stays underneath), each at the polynomial order the data support: the
/// `--apply` of `rins diagnose`.
pub(crate) fn apply(
    model: &PlantConfig,
    a: &Prepared,
    effects: &[Effect],
) -> Result<Applied, String> {
    for e in effects {
        if let Some((_, why)) = a.replay.unavailable.iter().find(|(n, _)| *n == e.name()) {
            return Err(format!("cannot fit {}: {why}", e.name()));
        }
    }
    let per_channel: Vec<Vec<Group>> = (0..6)
        .map(|c| {
            effects
                .iter()
                .filter_map(|e| {
                    a.replay
                        .groups
                        .iter()
                        .find(|g| g.channel == c && g.effect == *e)
                })
                .filter_map(|g| lowest_supported_order(a, c, g))
                .collect()
        })
        .collect();
    apply_groups(model, a, effects, &per_channel)
}

/// Of a polynomial's orders, the lowest, or a higher one if its extra terms are significant (as
/// in the ranking).
fn lowest_supported_order(a: &Prepared, c: usize, g: &Group) -> Option<Group> {
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
}

/// The model's current value of each coefficient of `g` (SI; zero when the effect is off).
fn current_values(model: &PlantConfig, g: &Group) -> Vec<f64> {
    let c = g.channel;
    match g.effect {
        Effect::Gyro(t) => GyroModel::new(&model.sensor.gyro).coefficients(t, c),
        Effect::Accel(t) => AccelModel::new(&model.sensor.accel).coefficients(t, c - 3),
        Effect::Custom(r) => {
            let list = if r.accel {
                &model.sensor.accel.custom
            } else {
                &model.sensor.gyro.custom
            };
            let spec = &list[r.index as usize];
            // A switched-off effect contributes nothing to the replayed model.
            let v = if spec.enabled { spec.coef[c % 3] } else { 0.0 };
            vec![v * r.file_unit_si()]
        }
    }
}

/// Whether `effect` is on in `model`.
fn is_on(model: &PlantConfig, effect: Effect) -> bool {
    match effect {
        Effect::Gyro(t) => model.sensor.gyro.is_enabled(t),
        Effect::Accel(t) => model.sensor.accel.is_enabled(t),
        Effect::Custom(r) => {
            let list = if r.accel {
                &model.sensor.accel.custom
            } else {
                &model.sensor.gyro.custom
            };
            list.get(r.index as usize).is_some_and(|s| s.enabled)
        }
    }
}

/// `model` with the groups `per_channel[c]` fitted jointly on channel c (on top of the model
/// as given) and `switch_on` switched on. A coefficient is written only when the data determine
/// its correction ([`MIN_WRITE_Z`]); otherwise the model's value is kept (or, for an effect the
/// model had off, written as the zero it contributed), and the other coefficients of the channel
/// are fitted again without it.
pub(crate) fn apply_groups(
    model: &PlantConfig,
    a: &Prepared,
    switch_on: &[Effect],
    per_channel: &[Vec<Group>],
) -> Result<Applied, String> {
    let mut pairs: Vec<(String, ParamValue)> = Vec::new();
    let mut set = Vec::new();
    let mut coefficients = Vec::new();
    let mut on: Vec<Effect> = switch_on.to_vec();
    for groups in per_channel {
        for g in groups {
            if !on.contains(&g.effect) {
                on.push(g.effect);
            }
        }
    }
    for e in &on {
        if is_on(model, *e) {
            continue;
        }
        pairs.push((e.enabled_key(), ParamValue::Bool(true)));
        if let Effect::Gyro(rins_plant::effects::GyroTerm::DitherBias) = e {
            for i in 0..3 {
                pairs.push((
                    format!("sensor.gyro.dither_bias.amplitude_change[{i}]"),
                    ParamValue::Real(1.0),
                ));
            }
        }
    }
    for c in 0..6 {
        let groups = &per_channel[c];
        if groups.is_empty() {
            continue;
        }
        let x = design(&a.replay.windows, groups);
        let names: Vec<String> = groups.iter().map(|g| g.effect.name()).collect();
        let not_identifiable = || {
            format!(
                "{} cannot be fitted together on {} with this data (not identifiable)",
                names.join(" + "),
                CHANNELS[c]
            )
        };
        // Columns whose correction the data do not determine are dropped and the rest refitted,
        // until every column left is determined.
        let mut live: Vec<usize> = (0..x.ncols()).collect();
        let mut kept = vec![false; x.ncols()];
        let fit = loop {
            let f = match wls(&x.select(&live), &a.data[c], None) {
                Some(f) => f,
                // Only unidentifiable columns are left after dropping weak ones: none of them
                // is estimated.
                None if live.len() < x.ncols() => {
                    live.clear();
                    break wls(&x.select(&live), &a.data[c], None).ok_or_else(not_identifiable)?;
                }
                None => return Err(not_identifiable()),
            };
            let z = |i: usize| f.theta[i].abs() / f.cov[(i, i)].sqrt();
            // Drop the weakest first: a column can be weak only through another.
            let weakest = (0..live.len())
                .filter(|&i| f.identified(i) && !(z(i) >= MIN_WRITE_Z))
                .min_by(|&i, &j| z(i).total_cmp(&z(j)));
            let Some(i) = weakest else { break f };
            kept[live[i]] = true;
            live.remove(i);
        };
        let mut col = 0;
        for g in groups {
            let current = current_values(model, g);
            let was_on = is_on(model, g.effect);
            for (j, (name, unit)) in g
                .effect
                .coefficient_keys(c)
                .into_iter()
                .take(g.len)
                .enumerate()
            {
                let k = col;
                col += 1;
                let before = current.get(j).copied().unwrap_or(0.0);
                let pos = live.iter().position(|&l| l == k);
                let (fate, fitted, ci95, reason) = match pos {
                    Some(i) if fit.identified(i) && !kept[k] => {
                        let (th, se) = (fit.theta[i], fit.cov[(i, i)].sqrt());
                        let v = (before + th) / unit;
                        (
                            Fate::Written,
                            Some(v),
                            Some([
                                (before + th - 1.96 * se) / unit,
                                (before + th + 1.96 * se) / unit,
                            ]),
                            format!("correction {:.3e} is {:.1} σ", th / unit, th.abs() / se),
                        )
                    }
                    Some(i) if !fit.identified(i) => (
                        Fate::Null,
                        None,
                        None,
                        format!(
                            "not identifiable on this data (standard error above {:.0e} file units)",
                            fit::MAX_SE_FILE_UNITS
                        ),
                    ),
                    None if !kept[k] => (
                        Fate::Null,
                        None,
                        None,
                        "not identifiable on this data".into(),
                    ),
                    _ => (
                        Fate::Kept,
                        None,
                        None,
                        format!(
                            "the data are consistent with the model's value (correction below {MIN_WRITE_Z} σ)"
                        ),
                    ),
                };
                match fate {
                    Fate::Written => {
                        let v = fitted.expect("written has a value");
                        set.push((name.clone(), v));
                        pairs.push((name.clone(), ParamValue::Real(v)));
                    }
                    // An effect the model had off contributed zero: switching it on must not
                    // bring in what its switched-off specification held.
                    _ if !was_on => pairs.push((name.clone(), ParamValue::Real(before / unit))),
                    _ => {}
                }
                coefficients.push(Coefficient {
                    key: name,
                    effect: g.effect.name(),
                    channel: CHANNELS[c].into(),
                    model: before / unit,
                    fitted,
                    ci95,
                    fate,
                    reason,
                });
            }
        }
    }
    let cfg = params::apply(model, pairs.iter().map(|(k, v)| (k.as_str(), v.clone())))
        .map_err(|e| e.to_string())?;
    Ok(Applied {
        model: cfg,
        set,
        coefficients,
    })
}

/// `--apply NAME…`: `model` with the named effects (catalogue, declared, or `custom:NAME` of a
/// term `discovery` proposed, which is declared first) and their parents
/// ([`crate::heredity`]) fitted jointly on every channel each acts on, each at the polynomial
/// order the data support, coefficients written only when determined.
pub fn apply_with_parents(
    model: &PlantConfig,
    h: &(impl crate::Rows + ?Sized),
    opts: &crate::Options,
    names: &[String],
    discovery: Option<&crate::discover::DiscoveryReport>,
) -> Result<Applied, String> {
    let mut m = model.clone();
    for name in names {
        if Effect::parse_in(&m, name).is_some() {
            continue;
        }
        let Some(d) = discovery.filter(|_| name.starts_with("custom:")) else {
            return Err(format!(
                "{name}: not an effect of the catalogue or a declared effect of the model"
            ));
        };
        m = crate::discover::with_proposal(&m, d, name.trim_start_matches("custom:"))?;
    }
    // (channel, effect name, parent?) on every channel each named effect acts on.
    let mut wanted: Vec<(usize, String, bool)> = Vec::new();
    for name in names {
        let e = Effect::parse_in(&m, name).expect("declared above");
        for c in (0..6).filter(|&c| e.acts_on(c)) {
            wanted.push((c, name.clone(), false));
            for p in crate::heredity::parents(&m, e) {
                let pname = match p {
                    crate::heredity::Parent::Effect(pe) => pe.name(),
                    crate::heredity::Parent::Declare {
                        accel,
                        kind,
                        regressor,
                    } => {
                        let (next, n) =
                            crate::heredity::declare(&m, accel, kind, &regressor, c % 3);
                        m = next;
                        n
                    }
                };
                wanted.push((c, pname, true));
            }
        }
    }
    let p = crate::prepare::prepare(&m, h, opts);
    let mut switch_on = Vec::new();
    for name in names {
        let e = Effect::parse_in(&m, name).expect("declared above");
        if let Some((_, why)) = p.replay.unavailable.iter().find(|(n, _)| *n == e.name()) {
            return Err(format!("cannot fit {name}: {why}"));
        }
        switch_on.push(e);
    }
    let mut per_channel: Vec<Vec<Group>> = vec![Vec::new(); 6];
    for (c, name, parent) in &wanted {
        let Some(g) = p
            .replay
            .groups
            .iter()
            .find(|g| g.channel == *c && g.effect.name() == *name)
        else {
            continue;
        };
        if per_channel[*c].iter().any(|x| x.effect == g.effect) {
            continue;
        }
        // A named effect at the order the data support; a parent whole.
        let g = if *parent {
            Some(*g)
        } else {
            lowest_supported_order(&p, *c, g)
        };
        per_channel[*c].extend(g);
    }
    apply_groups(&m, &p, &switch_on, &per_channel)
}
