//! The block of scenario parameters a model exposes as FMU parameters, and the plant
//! configuration their values describe.

use std::ops::Range;

use rins_fmi::vars::{ScalarVar, Value};
use rins_plant::PlantConfig;
use rins_plant::params;

use crate::parameter::{param_var, to_param};

/// Consecutive slots of a variable table holding the scenario parameters a model exposes, with
/// the configuration their start values describe.
#[derive(Clone, Debug, PartialEq)]
pub struct PlantParams {
    /// The configuration of the start values.
    pub defaults: PlantConfig,
    /// Scenario key path of each parameter, in slot order.
    pub paths: Vec<String>,
    /// Their slots.
    pub slots: Range<usize>,
}

impl PlantParams {
    /// Appends to `scalars` one parameter for every scalar of `defaults` whose key path `keep`
    /// accepts, in the parameter table's order.
    pub fn push_vars(
        defaults: PlantConfig,
        keep: impl Fn(&str) -> bool,
        scalars: &mut Vec<ScalarVar>,
    ) -> Self {
        let first = scalars.len();
        let mut paths = Vec::new();
        for p in params::flatten(&defaults)
            .into_iter()
            .filter(|p| keep(&p.path))
        {
            scalars.push(param_var(&p));
            paths.push(p.path);
        }
        Self {
            defaults,
            slots: first..first + paths.len(),
            paths,
        }
    }

    /// `(slot, key path)` of every parameter.
    pub fn iter(&self) -> impl Iterator<Item = (usize, &str)> {
        self.slots
            .clone()
            .zip(self.paths.iter().map(String::as_str))
    }

    /// The key path of slot `slot`, if it is one of these parameters.
    pub fn path(&self, slot: usize) -> Option<&str> {
        self.slots
            .contains(&slot)
            .then(|| self.paths[slot - self.slots.start].as_str())
    }

    /// The configuration the values describe: the defaults with every parameter whose value
    /// differs from its start set through the plant's own parameter table
    /// ([`params::apply`], which sets the typed fields and keeps ±inf, NaN and u64 exactly).
    /// `scalars` and `values` are the whole table's, by slot. Not validated: the plant's
    /// constructors (or [`PlantConfig::validate`]) say which field is out of range.
    pub fn config(&self, scalars: &[ScalarVar], values: &[Value]) -> Result<PlantConfig, String> {
        let changed = self.iter().filter_map(|(slot, path)| {
            let (s, v) = (&scalars[slot], values[slot]);
            (v != s.start).then(|| (path, to_param(s, v)))
        });
        params::apply(&self.defaults, changed).map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_plant::params::ParamValue;

    fn block() -> (PlantParams, Vec<ScalarVar>) {
        let mut scalars = Vec::new();
        let p = PlantParams::push_vars(
            rins_plant::presets::paper_16pos_config(),
            |path| path.starts_with("scheme.") && !path.starts_with("scheme.steps"),
            &mut scalars,
        );
        (p, scalars)
    }

    #[test]
    fn start_values_give_the_defaults_and_a_change_sets_exactly_its_key() {
        let (p, scalars) = block();
        assert_eq!(p.slots, 0..scalars.len());
        let mut values: Vec<Value> = scalars.iter().map(|s| s.start).collect();
        assert_eq!(p.config(&scalars, &values).unwrap(), p.defaults);
        // An infinite acceleration (instantaneous rate change, as in scenario files) is kept.
        let accel = scalars
            .iter()
            .position(|s| s.name == "scheme.accel_dps2")
            .unwrap();
        assert_eq!(p.path(accel), Some("scheme.accel_dps2"));
        values[accel] = Value::Real(f64::INFINITY);
        let kind = scalars
            .iter()
            .position(|s| s.name == "scheme.kind")
            .unwrap();
        values[kind] = Value::Enumeration(1);
        let cfg = p.config(&scalars, &values).unwrap();
        let mut expected = params::set(
            &p.defaults,
            "scheme.kind",
            ParamValue::Enum("eight-position".into()),
        )
        .unwrap();
        expected.scheme.accel_dps2 = f64::INFINITY;
        assert_eq!(cfg, expected);
        assert_eq!(p.path(scalars.len()), None);
    }
}
