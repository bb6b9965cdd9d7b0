//! SSP parameter sets (`.ssv`) of the IMU FMU for the sensor presets, as shipped in
//! fmi-wrapper/examples/system/ (a test keeps them current). Every `sensor.*` parameter of
//! the preset is listed, so a set is complete whatever was set before it; enumerations are
//! written as their Integer codes (`<name>_code`), which libcosim and ecos can set.

use std::fmt::Write;

use rins_fmi::vars::{Kind, Value};
use rins_plant::params::{self, ParamValue};

use crate::table::table;

/// The `.ssv` document of sensor preset `preset` (`paper-table3`, `nav-grade-full`, …), or
/// `None` for an unknown preset.
pub fn sensor_parameter_set(preset: &str) -> Option<String> {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.sensor = rins_plant::presets::preset(preset)?;
    let t = table();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<ssv:ParameterSet xmlns:ssv=\"http://ssp-standard.org/SSP1/SystemStructureParameterValues\" version=\"1.0\" name=\"{preset}\">\n  <ssv:Parameters>"
    );
    for p in params::flatten(&cfg)
        .into_iter()
        .filter(|p| p.path.starts_with("sensor."))
    {
        let name = rins_fmi_plant::parameter::variable_name(&p.path);
        let slot = t.vars.slot(&name)?;
        let var = &t.vars.scalars[slot];
        let unit = var
            .unit
            .map(|u| format!(" unit=\"{u}\""))
            .unwrap_or_default();
        let (name, value) = match (&p.value, var.kind) {
            (ParamValue::Real(x), _) => (name, format!("<ssv:Real value=\"{x:?}\"{unit}/>")),
            (ParamValue::Integer(u), _) => (name, format!("<ssv:Integer value=\"{u}\"/>")),
            (ParamValue::Bool(b), _) => (name, format!("<ssv:Boolean value=\"{b}\"/>")),
            (ParamValue::Enum(e), Kind::Enumeration { items, .. }) => {
                let i = items.iter().position(|x| x == e)?;
                let code = t
                    .vars
                    .enum_codes
                    .iter()
                    .find(|(_, target)| *target == slot)?
                    .0;
                debug_assert_eq!(
                    t.vars.scalars[code].start,
                    Value::Integer(match var.start {
                        Value::Enumeration(k) => k as u64 + 1,
                        _ => 0,
                    })
                );
                (
                    t.vars.scalars[code].name.clone(),
                    format!("<ssv:Integer value=\"{}\"/>", i + 1),
                )
            }
            (ParamValue::Enum(_), _) => return None,
        };
        let _ = writeln!(
            s,
            "    <ssv:Parameter name=\"{name}\">{value}</ssv:Parameter>"
        );
    }
    s.push_str("  </ssv:Parameters>\n</ssv:ParameterSet>\n");
    Some(s)
}
