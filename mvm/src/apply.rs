//! `--apply`: the model with chosen effects switched on and fitted on the measurements, and
//! the model file written back with it.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use rins_plant::PlantConfig;
use rins_plant::params::{self, ParamValue};

use crate::fit::{self, delta_bic_of, design, wls};
use crate::prepare::Prepared;
use crate::replay::{CHANNELS, Effect, Group};

/// A model with effects fitted on the measurements.
#[derive(Clone, Debug)]
pub struct Applied {
    /// The model with the effects switched on and their coefficients set.
    pub model: PlantConfig,
    /// The scenario values set (key, value in scenario-file units), in order.
    pub set: Vec<(String, f64)>,
}

impl Applied {
    /// The model file `original` (TOML text) with its `[sensor]` replaced by the fitted model's
    /// full sensor specification, headed by the comment `note`.
    pub fn model_file(&self, original: &str, note: &str) -> Result<String, String> {
        let mut table: toml::Table =
            toml::from_str(original).map_err(|e| format!("model file is not TOML: {e}"))?;
        let mut sensor = toml::Table::try_from(&self.model.sensor)
            .map_err(|e| format!("serialising the sensor specification: {e}"))?;
        sensor.insert("preset".into(), toml::Value::String("ideal".into()));
        table.insert("sensor".into(), toml::Value::Table(sensor));
        let text = toml::to_string_pretty(&table)
            .map_err(|e| format!("serialising the model file: {e}"))?;
        Ok(format!(
            "# {note}\n# Written by rins diagnose --apply; [sensor] is the complete specification.\n{text}"
        ))
    }
}

/// `model` with `effects` switched on and fitted jointly on every channel they act on (the
/// model as given stays underneath): the `--apply` of `rins diagnose`. Returns the new model and
/// the scenario values set.
pub(crate) fn apply(
    model: &PlantConfig,
    a: &Prepared,
    effects: &[Effect],
) -> Result<Applied, String> {
    let mut pairs: Vec<(String, ParamValue)> = Vec::new();
    let mut set = Vec::new();
    for e in effects {
        if let Some((_, why)) = a.replay.unavailable.iter().find(|(n, _)| *n == e.name()) {
            return Err(format!("cannot fit {}: {why}", e.name()));
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
            };
            for (j, (name, unit)) in g
                .effect
                .coefficient_keys(c)
                .into_iter()
                .take(g.len)
                .enumerate()
            {
                let v = (current.get(j).copied().unwrap_or(0.0) + fit.theta[k]) / unit;
                k += 1;
                // A coefficient the data cannot identify is never written.
                if !fit.identified(k - 1) {
                    continue;
                }
                set.push((name.clone(), v));
                pairs.push((name, ParamValue::Real(v)));
            }
        }
    }
    let cfg = params::apply(model, pairs.iter().map(|(k, v)| (k.as_str(), v.clone())))
        .map_err(|e| e.to_string())?;
    Ok(Applied { model: cfg, set })
}
