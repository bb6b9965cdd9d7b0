use super::*;
use crate::vars::OutputDecl;
use crate::vars::{Causality, ScalarVar};

#[test]
fn fmi3_declares_each_array_element_as_a_scalar_output_too() {
    let d = OutputDecl {
        name: "q".into(),
        len: Some(2),
        kind: Kind::Real,
        unit: None,
        start: vec![Value::Real(0.0)],
        description: "d".into(),
    };
    let table = VariableTable::new(d.scalars().collect());
    let h = Header {
        model_identifier: "M".into(),
        description: String::new(),
        generation_tool: String::new(),
        stop_time_s: 1.0,
        step_size_s: 0.1,
    };
    let (v3, _) = model_description(FmiVersion::V3, &table, &h).unwrap();
    // The array (value reference 1), then its elements q[0], q[1] (2, 3), all outputs.
    assert!(v3.contains("<Float64 name=\"q\" valueReference=\"1\""));
    assert!(v3.contains("<Float64 name=\"q[0]\" valueReference=\"2\""));
    assert!(v3.contains("<Float64 name=\"q[1]\" valueReference=\"3\""));
    for vr in 1..=3 {
        assert!(v3.contains(&format!("<Output valueReference=\"{vr}\"")));
    }
    assert_eq!(v3.matches("<Dimension").count(), 1);
    // FMI 2 has the elements only, as before.
    let (v2, _) = model_description(FmiVersion::V2, &table, &h).unwrap();
    assert_eq!(v2.matches("<ScalarVariable").count(), 2);
}

/// A small model with one variable of every kind, a unit with a kelvin exponent, ranges, an
/// enumeration (and its Integer code) and an array output depending on a parameter.
fn probe() -> (VariableTable, Header) {
    let var = |name: &str, kind: Kind, causality: Causality, start: Value| ScalarVar {
        name: name.into(),
        array: name.into(),
        kind,
        causality,
        unit: None,
        start,
        range: None,
        description: format!("{name}: a < b & \"c\""),
    };
    let out = OutputDecl {
        name: "y".into(),
        len: Some(2),
        kind: Kind::Real,
        unit: Some("W/K"),
        start: vec![Value::Real(0.0)],
        description: "out".into(),
    };
    let mut scalars = vec![
        ScalarVar {
            unit: Some("deg/h/K"),
            range: Some((-1.5, f64::INFINITY)),
            ..var("gain", Kind::Real, Causality::Parameter, Value::Real(0.25))
        },
        ScalarVar {
            range: Some((1.0, 9.0)),
            ..var("n", Kind::Integer, Causality::Input, Value::Integer(3))
        },
        var(
            "on",
            Kind::Boolean,
            Causality::Parameter,
            Value::Boolean(true),
        ),
        var(
            "colour",
            Kind::Enumeration {
                type_name: "Colour",
                items: &["red", "green"],
            },
            Causality::Parameter,
            Value::Enumeration(1),
        ),
    ];
    scalars.extend(out.scalars());
    let mut table = VariableTable::with_enum_codes(scalars);
    table.initial_dependencies[4] = vec![0];
    let h = Header {
        model_identifier: "Probe".into(),
        description: "a probe".into(),
        generation_tool: "test".into(),
        stop_time_s: 2.0,
        step_size_s: 0.01,
    };
    (table, h)
}

#[test]
fn both_typed_descriptions_round_trip_through_fmi_schemas_reader() {
    use fmi_schema::fmi2::Fmi2ModelDescription;
    use fmi_schema::fmi3::Fmi3ModelDescription;
    use fmi_schema::traits::FmiModelDescription;
    let (table, h) = probe();
    let d2 = fmi2::description(&table, &h, "{t}").unwrap();
    let back = Fmi2ModelDescription::deserialize(&d2.serialize().unwrap()).unwrap();
    // fmi-schema 0.8's FMI 2 description has no PartialEq; its Debug shows every field.
    assert_eq!(format!("{back:?}"), format!("{d2:?}"));
    let d3 = fmi3::description(&table, &h, "{t}").unwrap();
    let back = Fmi3ModelDescription::deserialize(&d3.serialize().unwrap()).unwrap();
    assert_eq!(back, d3);
}

#[test]
fn the_fmi2_document_reads_back_as_the_typed_description_with_what_fmi_schema_cannot_say() {
    use fmi_schema::fmi2::{Fmi2ModelDescription, ScalarVariableElement};
    use fmi_schema::traits::FmiModelDescription;
    let (table, h) = probe();
    let (xml, token) = model_description(FmiVersion::V2, &table, &h).unwrap();
    let typed = fmi2::description(&table, &h, &token).unwrap();
    let mut back = Fmi2ModelDescription::deserialize(&xml).unwrap();
    // What fmi-schema reads of the completed document is the typed value, but for the
    // Enumeration written as an Integer (its reader drops an Enumeration's attributes) and
    // the Derivatives list it writes empty and the document leaves out.
    for (b, t) in back
        .model_variables
        .variables
        .iter_mut()
        .zip(&typed.model_variables.variables)
    {
        if matches!(b.elem, ScalarVariableElement::Enumeration) {
            b.elem = t.elem.clone();
        }
    }
    assert_eq!(format!("{back:?}"), format!("{typed:?}"));
    // And the document says what fmi-schema cannot.
    for needle in [
        r#"<Real start="0.25" unit="deg/h/K" min="-1.5"/>"#,
        r#"<Integer start="3" min="1" max="9"/>"#,
        r#"<Enumeration declaredType="Colour" start="2"/>"#,
        r#"<Item name="green" value="2"/>"#,
        r#"<Unknown index="5" dependencies=""/>"#,
        r#"<Unknown index="5" dependencies="1"/>"#,
        r#"<Unknown index="6" dependencies=""/>"#,
        r#"<BaseUnit s="-1" K="-1" rad="1" factor="0.00000484813681109536"/>"#,
        "<!-- index 7 -->",
        "gain: a &lt; b &amp; &quot;c&quot;",
    ] {
        assert!(xml.contains(needle), "{needle} not in\n{xml}");
    }
    assert!(!xml.contains("Derivatives"), "{xml}");
    let tags: Vec<String> = Element::parse(&xml)
        .unwrap()
        .children
        .into_iter()
        .map(|c| c.tag)
        .collect();
    assert_eq!(
        tags,
        [
            "CoSimulation",
            "UnitDefinitions",
            "TypeDefinitions",
            "LogCategories",
            "DefaultExperiment",
            "ModelVariables",
            "ModelStructure"
        ]
    );
}

#[test]
fn the_fmi3_document_adds_units_enumerations_and_base_unit_spelling_to_fmi_schemas() {
    use fmi_schema::fmi3::Fmi3ModelDescription;
    use fmi_schema::traits::FmiModelDescription;
    let (table, h) = probe();
    let (xml, token) = model_description(FmiVersion::V3, &table, &h).unwrap();
    let typed = fmi3::description(&table, &h, &token).unwrap();
    // The document is fmi-schema's but for these edits: undone, it reads back as the typed
    // value.
    let undone = xml
        .replace(" unit=\"s\"", "")
        .replace(" unit=\"deg/h/K\"", "")
        .replace(" unit=\"W/K\"", "")
        .replace("<Enumeration ", "<Int64 ")
        .replace(" K=\"-1\"", " k=\"-1\"");
    assert_eq!(Fmi3ModelDescription::deserialize(&undone).unwrap(), typed);
    for needle in [
        r#"<Float64 name="time" valueReference="0" description="simulation time" causality="independent" variability="continuous" unit="s"/>"#,
        r#"min="-1.5" unit="deg/h/K"/>"#,
        r#"<Enumeration name="colour" valueReference="4""#,
        r#"<UInt64 name="n" valueReference="2" description="n: a &lt; b &amp; &quot;c&quot;" causality="input" variability="discrete" start="3" min="1" max="9"/>"#,
        r#"<Output valueReference="5" dependencies=""/>"#,
        r#"<InitialUnknown valueReference="5" dependencies="1"/>"#,
        r#"<InitialUnknown valueReference="8" dependencies=""/>"#,
        r#"K="-1""#,
    ] {
        assert!(xml.contains(needle), "{needle} not in\n{xml}");
    }
    // fmi-schema 0.8 cannot read the standard's `K` on a BaseUnit nor `unit` on a Float64:
    // when this starts to fail, the edits of `fmi3::complete` can go to the typed value.
    let e = Fmi3ModelDescription::deserialize(&xml)
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"K\"") || e.contains("\"unit\""), "{e}");
    let e = Fmi3ModelDescription::deserialize(&xml.replace(" K=\"-1\"", " k=\"-1\""));
    assert!(e.unwrap_err().to_string().contains("\"unit\""));
}
