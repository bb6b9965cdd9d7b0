//! Inputs (and model-own parameters) declared as rows of a table rather than built by hand:
//! name, type, unit, start, range and description of each scalar in one line each.

use rins_fmi::vars::{Causality, Kind, ScalarVar, Value, array_name};
use rins_plant::PlantConfig;

/// One scalar variable that is not a scenario parameter.
#[derive(Clone, Copy, Debug)]
pub struct InputRow {
    /// FMI 2 structured name (`a.b[2]` for an element of the FMI 3 array `a.b`).
    pub name: &'static str,
    /// Type.
    pub kind: Kind,
    /// [`Causality::Input`], or [`Causality::Parameter`] for a model's own switch.
    pub causality: Causality,
    /// Unit symbol (`None` when dimensionless).
    pub unit: Option<&'static str>,
    /// Start value, from the model's default configuration where it follows one.
    pub start: fn(&PlantConfig) -> Value,
    /// Valid range of numbers.
    pub range: Option<(f64, f64)>,
    /// One line for the user.
    pub description: &'static str,
}

impl InputRow {
    /// The row's variable, its start value from `defaults`.
    pub fn var(&self, defaults: &PlantConfig) -> ScalarVar {
        ScalarVar {
            name: self.name.into(),
            array: array_name(self.name).into(),
            kind: self.kind,
            causality: self.causality,
            unit: self.unit,
            start: (self.start)(defaults),
            range: self.range,
            description: self.description.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_is_its_variable_with_the_start_from_the_defaults() {
        let row = InputRow {
            name: "input.v[1]",
            kind: Kind::Real,
            causality: Causality::Input,
            unit: Some("m/s"),
            start: |c| Value::Real(c.site.lat_deg),
            range: Some((-1.0, 1.0)),
            description: "d",
        };
        let cfg = rins_plant::presets::paper_16pos_config();
        let v = row.var(&cfg);
        assert_eq!(v.array, "input.v");
        assert_eq!(v.start, Value::Real(cfg.site.lat_deg));
        assert_eq!(
            (v.kind, v.causality, v.unit, v.range),
            (Kind::Real, Causality::Input, Some("m/s"), Some((-1.0, 1.0)))
        );
    }
}
