//! The plant configuration the FMU parameters describe.
//!
//! Finite values go through the plant's parameter table ([`params::apply`], which edits the
//! configuration's JSON form). JSON has no infinity, yet `scheme.accel_dps2 = inf` is a valid
//! value (an instantaneous rate change, as in scenario files): non-finite values are set on the
//! TOML form of the configuration instead, which carries ±inf exactly as a scenario file does.

use rins_plant::PlantConfig;
use rins_plant::params::{self, ParamValue};

/// `defaults` with every `(key path, value)` set.
pub fn apply<'a>(
    defaults: &PlantConfig,
    values: impl IntoIterator<Item = (&'a str, ParamValue)>,
) -> Result<PlantConfig, String> {
    let (finite, infinite): (Vec<_>, Vec<_>) = values
        .into_iter()
        .partition(|(_, v)| !matches!(v, ParamValue::Real(x) if !x.is_finite()));
    let cfg = params::apply(defaults, finite).map_err(|e| e.to_string())?;
    if infinite.is_empty() {
        return Ok(cfg);
    }
    let mut doc = toml::Value::try_from(&cfg).map_err(|e| format!("configuration as TOML: {e}"))?;
    for (path, v) in infinite {
        let ParamValue::Real(x) = v else {
            unreachable!("partitioned on non-finite reals")
        };
        *node(&mut doc, path)? = toml::Value::Float(x);
    }
    doc.try_into()
        .map_err(|e: toml::de::Error| format!("parameters: {}", e.message()))
}

/// The node at scenario key path `path` (`scheme.accel_dps2`, `sensor.gyro.bias.dph[2]`) of the
/// configuration's serialised form; `run.rate_hz`/`substeps`/`seed` are top-level fields there.
fn node<'v>(doc: &'v mut toml::Value, path: &str) -> Result<&'v mut toml::Value, String> {
    let inner = path
        .strip_prefix("run.")
        .filter(|p| ["rate_hz", "substeps", "seed"].contains(p))
        .unwrap_or(path);
    let unknown = || format!("unknown parameter {path:?}");
    let mut n = doc;
    for part in inner.split('.') {
        let (name, idx) = part.split_once('[').unwrap_or((part, ""));
        n = n.get_mut(name).ok_or_else(unknown)?;
        for ix in idx.split(['[', ']']).filter(|s| !s.is_empty()) {
            let i: usize = ix.parse().map_err(|_| unknown())?;
            n = n.get_mut(i).ok_or_else(unknown)?;
        }
    }
    if n.is_float() || n.is_integer() {
        Ok(n)
    } else {
        Err(format!("{path} is not a number"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn infinite_acceleration_is_set_and_finite_values_are_unchanged() {
        let d = rins_plant::presets::paper_16pos_config();
        let cfg = apply(
            &d,
            [
                ("scheme.accel_dps2", ParamValue::Real(f64::INFINITY)),
                ("sensor.gyro.bias.dph[2]", ParamValue::Real(0.02)),
            ],
        )
        .unwrap();
        assert_eq!(cfg.scheme.accel_dps2, f64::INFINITY);
        assert_eq!(cfg.sensor.gyro.bias.dph[2], 0.02);
        // Everything else as through the plant's own parameter table.
        let mut expected =
            params::set(&d, "sensor.gyro.bias.dph[2]", ParamValue::Real(0.02)).unwrap();
        expected.scheme.accel_dps2 = f64::INFINITY;
        assert_eq!(cfg, expected);
        assert!(
            apply(&d, [("scheme.nope", ParamValue::Real(f64::INFINITY))])
                .unwrap_err()
                .contains("scheme.nope")
        );
    }
}
