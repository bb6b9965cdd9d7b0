//! The plant configuration the FMU parameters describe: every value goes through the plant's
//! own parameter table ([`params::apply`]), whose value tree keeps ±inf (`scheme.accel_dps2 =
//! inf`, an instantaneous rate change as in scenario files), NaN and u64 exactly.

use rins_plant::PlantConfig;
use rins_plant::params::{self, ParamValue};

/// `defaults` with every `(key path, value)` set.
pub fn apply<'a>(
    defaults: &PlantConfig,
    values: impl IntoIterator<Item = (&'a str, ParamValue)>,
) -> Result<PlantConfig, String> {
    params::apply(defaults, values).map_err(|e| e.to_string())
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
