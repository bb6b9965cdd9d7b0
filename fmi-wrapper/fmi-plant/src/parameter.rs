//! One scenario parameter as one FMU parameter and back: the row of the plant's parameter
//! table ([`rins_plant::params::Param`]) gives the variable's name, type, unit, range and start
//! value; a value set through the FMU goes back to the plant's parameter form.

use rins_fmi::vars::{Causality, Kind, ScalarVar, Value, array_name};
use rins_plant::params::{self, Param, ParamValue};

use crate::enum_types::enum_type_name;

/// The FMI structured name of key path `path`: matrix elements are `a[i,j]` in FMI, `a[i][j]`
/// in the parameter table. The one place that rewrites a path into a variable name.
pub fn variable_name(path: &str) -> String {
    path.replace("][", ",")
}

/// One line for the user: a switch says what it switches, anything else names its scenario key.
fn describe(path: &str) -> String {
    let key = params::key_of(path);
    match path.rsplit('.').next().unwrap_or("") {
        "enabled" => format!("switch: {} on/off", key.trim_end_matches(".enabled")),
        _ => format!("scenario key {key}"),
    }
}

/// The FMU parameter of row `p` of the plant's parameter table.
///
/// Panics if `p` is an enumeration without a type name in
/// [`crate::enum_types::ENUM_TYPES`] or its value is not one of its choices: both are fixed by
/// the code, so a model's table fails to build (and its tests fail) rather than an FMU
/// publishing a wrong type.
pub fn param_var(p: &Param) -> ScalarVar {
    let name = variable_name(&p.path);
    // The FMI 3 variable is the name without its trailing index (`carrier.ship.legs[0].heading_deg`
    // is a scalar of its own).
    let array = array_name(&name).to_string();
    let (kind, start, range) = match &p.value {
        ParamValue::Real(x) => (Kind::Real, Value::Real(*x), p.range),
        ParamValue::Integer(u) => {
            // FMI 2 Integer is 32-bit signed: the range both FMI versions carry.
            let (lo, hi) = p.range.unwrap_or((0.0, f64::INFINITY));
            (
                Kind::Integer,
                Value::Integer(*u),
                Some((lo, hi.min(i32::MAX as f64))),
            )
        }
        ParamValue::Bool(b) => (Kind::Boolean, Value::Boolean(*b), None),
        ParamValue::Enum(item) => {
            let items = params::enum_choices(&p.path).unwrap_or_else(|| {
                panic!(
                    "{}: an enumeration without choices in params::ENUMS",
                    p.path
                )
            });
            let type_name = enum_type_name(&p.path).unwrap_or_else(|| {
                panic!(
                    "{}: an enumeration without an FMI type name in enum_types::ENUM_TYPES",
                    p.path
                )
            });
            let idx = items.iter().position(|c| c == item).unwrap_or_else(|| {
                panic!("{}: start value {item:?} is not one of {items:?}", p.path)
            });
            (
                Kind::Enumeration { type_name, items },
                Value::Enumeration(idx),
                None,
            )
        }
    };
    ScalarVar {
        name,
        array,
        kind,
        causality: Causality::Parameter,
        unit: (p.unit != "1").then_some(p.unit),
        start,
        range,
        description: describe(&p.path),
    }
}

/// The value `v` of parameter `s` in the plant's parameter form.
pub fn to_param(s: &ScalarVar, v: Value) -> ParamValue {
    match (s.kind, v) {
        (_, Value::Real(x)) => ParamValue::Real(x),
        (_, Value::Integer(u)) => ParamValue::Integer(u),
        (_, Value::Boolean(b)) => ParamValue::Bool(b),
        (Kind::Enumeration { items, .. }, Value::Enumeration(i)) => {
            ParamValue::Enum(items[i].to_string())
        }
        (_, Value::Enumeration(i)) => ParamValue::Integer(i as u64),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(path: &str, cfg: &rins_plant::PlantConfig) -> Param {
        params::flatten(cfg)
            .into_iter()
            .find(|p| p.path == path)
            .unwrap_or_else(|| panic!("{path} is no parameter"))
    }

    /// Every kind of row maps to the variable the FMI standards ask for, and each value goes
    /// back to the parameter it came from.
    #[test]
    fn each_kind_of_parameter_maps_to_its_variable_and_back() {
        let cfg = rins_plant::presets::paper_16pos_config();
        let bias = param_var(&row("sensor.gyro.bias.dph[2]", &cfg));
        assert_eq!(bias.name, "sensor.gyro.bias.dph[2]");
        assert_eq!(bias.array, "sensor.gyro.bias.dph");
        assert_eq!(bias.kind, Kind::Real);
        assert_eq!(bias.unit, Some("deg/h"));
        assert_eq!(bias.start, Value::Real(cfg.sensor.gyro.bias.dph[2]));
        assert_eq!(bias.range, Some((-100.0, 100.0)));
        assert_eq!(bias.description, "scenario key sensor.gyro.bias.dph");

        // A u64 seed is carried in the range FMI 2's signed 32-bit Integer holds.
        let seed = param_var(&row("run.seed", &cfg));
        assert_eq!(seed.kind, Kind::Integer);
        assert_eq!(seed.range, Some((0.0, i32::MAX as f64)));
        assert_eq!(to_param(&seed, Value::Integer(7)), ParamValue::Integer(7));

        let kind = param_var(&row("scheme.kind", &cfg));
        let Kind::Enumeration { type_name, items } = kind.kind else {
            panic!("scheme.kind is an enumeration: {:?}", kind.kind)
        };
        assert_eq!(type_name, "SchemeKind");
        assert_eq!(items[0], "sixteen-position");
        assert_eq!(kind.start, Value::Enumeration(0));
        assert_eq!(
            to_param(&kind, Value::Enumeration(1)),
            ParamValue::Enum("eight-position".into())
        );
        let spectrum = param_var(&row("carrier.ship.sea.spectrum", &cfg));
        assert!(matches!(
            spectrum.kind,
            Kind::Enumeration {
                type_name: "WaveSpectrum",
                ..
            }
        ));
        let transition = param_var(&row("sensor.gyro.position_bias.transition", &cfg));
        assert!(matches!(
            transition.kind,
            Kind::Enumeration {
                type_name: "PositionBiasTransition",
                ..
            }
        ));

        let switch = param_var(&row("sensor.gyro.bias.enabled", &cfg));
        assert_eq!(switch.kind, Kind::Boolean);
        assert_eq!(switch.description, "switch: sensor.gyro.bias on/off");
        assert_eq!(
            to_param(&switch, Value::Boolean(false)),
            ParamValue::Bool(false)
        );
    }

    #[test]
    fn matrix_elements_are_named_as_fmi_writes_them() {
        assert_eq!(variable_name("a.b[1][2]"), "a.b[1,2]");
        assert_eq!(variable_name("a.b[0].c"), "a.b[0].c");
    }
}
