//! Reading an FMI 2.0 modelDescription.xml, with fmi-schema (the typed definition the exporter
//! writes with): the GUID, model identifier and variables.

use fmi_schema::fmi2::{Fmi2ModelDescription, ScalarVariableElement};
use fmi_schema::minimal::MinModelDescription;
use fmi_schema::traits::FmiModelDescription;

/// A variable as the modelDescription declares it.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Name.
    pub name: String,
    /// Value reference.
    pub vr: u32,
    /// `Real`, `Integer`, `Boolean`, `Enumeration` or `String`.
    pub type_name: String,
    /// `parameter`, `input`, `output`, `local`, …
    pub causality: String,
}

/// The GUID, model identifier and variables of an FMI 2.0 co-simulation modelDescription.
pub fn parse_model_description(xml: &str) -> Result<(String, String, Vec<Variable>), String> {
    // The version first, so that an FMI 3 file is refused for what it is rather than for a
    // missing `guid`.
    let min: MinModelDescription = fmi_schema::deserialize(xml).map_err(|e| e.to_string())?;
    if min.fmi_version != "2.0" {
        return Err(format!(
            "this importer reads FMI 2.0; the FMU says fmiVersion {:?}",
            min.fmi_version
        ));
    }
    let md = Fmi2ModelDescription::deserialize(xml).map_err(|e| e.to_string())?;
    let id = md
        .co_simulation
        .as_ref()
        .map(|cs| cs.model_identifier.clone())
        .ok_or("not a co-simulation FMU")?;
    let vars = md
        .model_variables
        .variables
        .iter()
        .map(|v| Variable {
            name: v.name.clone(),
            vr: v.value_reference,
            type_name: match v.elem {
                ScalarVariableElement::Real(_) => "Real",
                ScalarVariableElement::Integer(_) => "Integer",
                ScalarVariableElement::Boolean(_) => "Boolean",
                ScalarVariableElement::String => "String",
                ScalarVariableElement::Enumeration => "Enumeration",
            }
            .into(),
            causality: v.causality.to_string(),
        })
        .collect();
    Ok((md.guid, id, vars))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_fmi::standard::FmiVersion;
    use rins_fmi::vars::{Causality, Kind, OutputDecl, ScalarVar, Value, VariableTable};
    use rins_fmi::xml::{Header, model_description};

    fn scalar(name: &str, kind: Kind, causality: Causality, start: Value) -> ScalarVar {
        ScalarVar {
            name: name.into(),
            array: name.into(),
            kind,
            causality,
            unit: None,
            start,
            range: None,
            description: format!("{name} <&> \"quoted\""),
        }
    }

    #[test]
    fn it_reads_what_the_exporter_writes() {
        let colour = Kind::Enumeration {
            type_name: "Colour",
            items: &["red", "green"],
        };
        let out = OutputDecl {
            name: "y".into(),
            len: Some(2),
            kind: Kind::Real,
            unit: Some("m"),
            start: vec![Value::Real(0.0)],
            description: "out".into(),
        };
        let mut scalars = vec![
            ScalarVar {
                unit: Some("s"),
                range: Some((0.0, f64::INFINITY)),
                ..scalar("gain", Kind::Real, Causality::Parameter, Value::Real(1.5))
            },
            scalar("n", Kind::Integer, Causality::Input, Value::Integer(3)),
            scalar(
                "on",
                Kind::Boolean,
                Causality::Parameter,
                Value::Boolean(true),
            ),
            scalar("c", colour, Causality::Parameter, Value::Enumeration(1)),
        ];
        scalars.extend(out.scalars());
        let table = VariableTable::with_enum_codes(scalars);
        let h = Header {
            model_identifier: "Probe".into(),
            description: "a probe".into(),
            generation_tool: "test".into(),
            stop_time_s: 1.0,
            step_size_s: 0.1,
        };
        let (xml, token) = model_description(FmiVersion::V2, &table, &h).unwrap();
        let (guid, id, vars) = parse_model_description(&xml).unwrap();
        assert_eq!((guid.as_str(), id.as_str()), (token.as_str(), "Probe"));
        let want: Vec<Variable> = table
            .scalars
            .iter()
            .enumerate()
            .map(|(slot, s)| Variable {
                name: s.name.clone(),
                vr: slot as u32,
                type_name: match s.kind {
                    Kind::Real => "Real",
                    Kind::Integer => "Integer",
                    Kind::Boolean => "Boolean",
                    Kind::Enumeration { .. } => "Enumeration",
                }
                .into(),
                causality: match s.causality {
                    Causality::Parameter => "parameter",
                    Causality::Input => "input",
                    Causality::Output => "output",
                }
                .into(),
            })
            .collect();
        assert_eq!(vars, want);
        // The enumeration's Integer code follows the variables it was made from.
        assert_eq!(vars.last().unwrap().name, "c_code");

        let (xml3, _) = model_description(FmiVersion::V3, &table, &h).unwrap();
        let e = parse_model_description(&xml3).unwrap_err();
        assert!(e.contains("reads FMI 2.0") && e.contains("3.0"), "{e}");
    }
}
