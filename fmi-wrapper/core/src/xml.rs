//! modelDescription.xml for FMI 2.0 and FMI 3.0, generated from the [`VariableTable`] (the model's
//! one source of truth for its variables). The GUID / instantiation token is a hash of the
//! document itself, so a stale binary and a newer description cannot be paired silently.

use std::fmt::Write;

use crate::standard::{FmiVersion, LOG_CATEGORIES};
use crate::vars::{Causality, Kind, ScalarVar, Value, VariableTable};

/// What goes in the header besides the variables.
#[derive(Clone, Debug)]
pub struct Header {
    /// Model name and identifier (the binary's name).
    pub model_identifier: String,
    /// Short description.
    pub description: String,
    /// Tool version string.
    pub generation_tool: String,
    /// Default experiment: stop time, s.
    pub stop_time_s: f64,
    /// Default experiment: communication step, s.
    pub step_size_s: f64,
}

/// Units used by the variables, with their SI base-unit expansion where one exists
/// (factor, offset, exponents of kg m s A K mol cd rad).
const UNITS: &[(&str, f64, f64, [i8; 8])] = &[
    ("rad", 1.0, 0.0, [0, 0, 0, 0, 0, 0, 0, 1]),
    (
        "deg",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, 0, 0, 0, 0, 0, 1],
    ),
    (
        "arcsec",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, 0, 0, 0, 0, 0, 1],
    ),
    ("rad/s", 1.0, 0.0, [0, 0, -1, 0, 0, 0, 0, 1]),
    (
        "deg/s",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, -1, 0, 0, 0, 0, 1],
    ),
    (
        "deg/s2",
        std::f64::consts::PI / 180.0,
        0.0,
        [0, 0, -2, 0, 0, 0, 0, 1],
    ),
    (
        "deg/h",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, 0, 0, 0, 1],
    ),
    (
        "deg/h/K",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -1, 0, 0, 1],
    ),
    (
        "deg/h/K2",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -2, 0, 0, 1],
    ),
    (
        "deg/h/K3",
        std::f64::consts::PI / 648_000.0,
        0.0,
        [0, 0, -1, 0, -3, 0, 0, 1],
    ),
    ("m", 1.0, 0.0, [0, 1, 0, 0, 0, 0, 0, 0]),
    ("m/s", 1.0, 0.0, [0, 1, -1, 0, 0, 0, 0, 0]),
    ("ug", 9.806_65e-6, 0.0, [0, 1, -2, 0, 0, 0, 0, 0]),
    ("ug/K", 9.806_65e-6, 0.0, [0, 1, -2, 0, -1, 0, 0, 0]),
    ("ug/K2", 9.806_65e-6, 0.0, [0, 1, -2, 0, -2, 0, 0, 0]),
    ("ug/K3", 9.806_65e-6, 0.0, [0, 1, -2, 0, -3, 0, 0, 0]),
    ("s", 1.0, 0.0, [0, 0, 1, 0, 0, 0, 0, 0]),
    ("Hz", 1.0, 0.0, [0, 0, -1, 0, 0, 0, 0, 0]),
    ("degC", 1.0, 273.15, [0, 0, 0, 0, 1, 0, 0, 0]),
    ("W", 1.0, 0.0, [1, 2, -3, 0, 0, 0, 0, 0]),
    ("W/K", 1.0, 0.0, [1, 2, -3, 0, -1, 0, 0, 0]),
    ("J/K", 1.0, 0.0, [1, 2, -2, 0, -1, 0, 0, 0]),
    ("ppm", 1e-6, 0.0, [0, 0, 0, 0, 0, 0, 0, 0]),
];

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Shortest round-trip form; infinities as the XML Schema spells them.
fn num(x: f64) -> String {
    if x == f64::INFINITY {
        "INF".into()
    } else if x == f64::NEG_INFINITY {
        "-INF".into()
    } else {
        format!("{x:?}")
    }
}

fn start_text(v: Value) -> String {
    match v {
        Value::Real(x) => num(x),
        Value::Integer(u) => u.to_string(),
        Value::Boolean(b) => b.to_string(),
        Value::Enumeration(i) => (i + 1).to_string(),
    }
}

fn unit_defs(table: &VariableTable, out: &mut String) {
    let mut used: Vec<&str> = table.scalars.iter().filter_map(|s| s.unit).collect();
    used.sort_unstable();
    used.dedup();
    out.push_str("  <UnitDefinitions>\n");
    for u in used {
        let _ = write!(out, "    <Unit name=\"{}\">", esc(u));
        if let Some((_, factor, offset, e)) = UNITS.iter().find(|(n, ..)| *n == u) {
            out.push_str("<BaseUnit");
            for (name, x) in ["kg", "m", "s", "A", "K", "mol", "cd", "rad"].iter().zip(e) {
                if *x != 0 {
                    let _ = write!(out, " {name}=\"{x}\"");
                }
            }
            if *factor != 1.0 {
                let _ = write!(out, " factor=\"{}\"", num(*factor));
            }
            if *offset != 0.0 {
                let _ = write!(out, " offset=\"{}\"", num(*offset));
            }
            out.push_str("/>");
        }
        out.push_str("</Unit>\n");
    }
    out.push_str("  </UnitDefinitions>\n");
}

fn enum_types(table: &VariableTable) -> Vec<(&'static str, &'static [&'static str])> {
    let mut types: Vec<(&str, &[&str])> = Vec::new();
    for s in &table.scalars {
        if let Kind::Enumeration { type_name, items } = s.kind
            && !types.iter().any(|(n, _)| *n == type_name)
        {
            types.push((type_name, items));
        }
    }
    types
}

fn causality(c: Causality) -> (&'static str, &'static str) {
    match c {
        Causality::Parameter => ("parameter", "fixed"),
        Causality::Input => ("input", "discrete"),
        Causality::Output => ("output", "discrete"),
    }
}

fn range_attrs(s: &ScalarVar) -> String {
    match s.range {
        Some((lo, hi)) => {
            let mut a = String::new();
            if lo.is_finite() {
                let _ = write!(
                    a,
                    " min=\"{}\"",
                    if matches!(s.kind, Kind::Integer) {
                        (lo as i64).to_string()
                    } else {
                        num(lo)
                    }
                );
            }
            if hi.is_finite() {
                let _ = write!(
                    a,
                    " max=\"{}\"",
                    if matches!(s.kind, Kind::Integer) {
                        (hi as u64).to_string()
                    } else {
                        num(hi)
                    }
                );
            }
            a
        }
        None => String::new(),
    }
}

fn header_open(version: FmiVersion, h: &Header, token: &str, out: &mut String) {
    let (v, tok_attr) = match version {
        FmiVersion::V2 => ("2.0", "guid"),
        FmiVersion::V3 => ("3.0", "instantiationToken"),
    };
    let _ = writeln!(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    let _ = writeln!(
        out,
        "<fmiModelDescription fmiVersion=\"{v}\" modelName=\"{id}\" {tok_attr}=\"{token}\" description=\"{d}\" generationTool=\"{g}\" version=\"{ver}\" license=\"MIT OR Apache-2.0\" copyright=\"The rins authors\" variableNamingConvention=\"structured\"{extra}>",
        id = esc(&h.model_identifier),
        d = esc(&h.description),
        g = esc(&h.generation_tool),
        ver = env!("CARGO_PKG_VERSION"),
        extra = if version == FmiVersion::V2 {
            " numberOfEventIndicators=\"0\""
        } else {
            ""
        },
    );
}

fn body_v2(table: &VariableTable, h: &Header, out: &mut String) {
    let _ = writeln!(
        out,
        "  <CoSimulation modelIdentifier=\"{}\" needsExecutionTool=\"false\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\" providesDirectionalDerivative=\"false\"/>",
        esc(&h.model_identifier)
    );
    unit_defs(table, out);
    out.push_str("  <TypeDefinitions>\n");
    for (name, items) in enum_types(table) {
        let _ = writeln!(out, "    <SimpleType name=\"{name}\">\n      <Enumeration>");
        for (i, it) in items.iter().enumerate() {
            let _ = writeln!(
                out,
                "        <Item name=\"{}\" value=\"{}\"/>",
                esc(it),
                i + 1
            );
        }
        out.push_str("      </Enumeration>\n    </SimpleType>\n");
    }
    out.push_str("  </TypeDefinitions>\n  <LogCategories>\n");
    for (n, d) in LOG_CATEGORIES {
        let _ = writeln!(
            out,
            "    <Category name=\"{n}\" description=\"{}\"/>",
            esc(d)
        );
    }
    out.push_str("  </LogCategories>\n");
    let _ = writeln!(
        out,
        "  <DefaultExperiment startTime=\"0.0\" stopTime=\"{}\" stepSize=\"{}\"/>",
        num(h.stop_time_s),
        num(h.step_size_s)
    );
    out.push_str("  <ModelVariables>\n");
    for (vr, s) in table.scalars.iter().enumerate() {
        let (c, var) = causality(s.causality);
        let initial = if s.causality == Causality::Output {
            " initial=\"calculated\""
        } else {
            ""
        };
        let _ = writeln!(
            out,
            "    <!-- index {} -->\n    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" description=\"{}\" causality=\"{c}\" variability=\"{var}\"{initial}>",
            vr + 1,
            esc(&s.name),
            esc(&s.description)
        );
        let start = if s.causality == Causality::Output {
            String::new()
        } else {
            format!(" start=\"{}\"", start_text(s.start))
        };
        let unit = s
            .unit
            .map(|u| format!(" unit=\"{}\"", esc(u)))
            .unwrap_or_default();
        let _ = match s.kind {
            Kind::Real => writeln!(out, "      <Real{unit}{}{start}/>", range_attrs(s)),
            Kind::Integer => writeln!(out, "      <Integer{}{start}/>", range_attrs(s)),
            Kind::Boolean => writeln!(out, "      <Boolean{start}/>"),
            Kind::Enumeration { type_name, .. } => writeln!(
                out,
                "      <Enumeration declaredType=\"{type_name}\"{start}/>"
            ),
        };
        out.push_str("    </ScalarVariable>\n");
    }
    out.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    let outputs: Vec<usize> = table
        .scalars
        .iter()
        .enumerate()
        .filter(|(_, s)| s.causality == Causality::Output)
        .map(|(i, _)| i + 1)
        .collect();
    for i in &outputs {
        let _ = writeln!(out, "      <Unknown index=\"{i}\" dependencies=\"\"/>");
    }
    out.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for i in &outputs {
        let deps: Vec<String> = table.initial_dependencies[i - 1]
            .iter()
            .map(|k| (k + 1).to_string())
            .collect();
        let _ = writeln!(
            out,
            "      <Unknown index=\"{i}\" dependencies=\"{}\"/>",
            deps.join(" ")
        );
    }
    out.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
}

fn body_v3(table: &VariableTable, h: &Header, out: &mut String) {
    let _ = writeln!(
        out,
        "  <CoSimulation modelIdentifier=\"{}\" needsExecutionTool=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\" canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\" providesDirectionalDerivatives=\"false\" providesAdjointDerivatives=\"false\" providesPerElementDependencies=\"false\" canHandleVariableCommunicationStepSize=\"true\" maxOutputDerivativeOrder=\"0\" providesIntermediateUpdate=\"false\" canReturnEarlyAfterIntermediateUpdate=\"false\" hasEventMode=\"false\" providesEvaluateDiscreteStates=\"false\"/>",
        esc(&h.model_identifier)
    );
    unit_defs(table, out);
    out.push_str("  <TypeDefinitions>\n");
    for (name, items) in enum_types(table) {
        let _ = writeln!(out, "    <EnumerationType name=\"{name}\">");
        for (i, it) in items.iter().enumerate() {
            let _ = writeln!(
                out,
                "      <Item name=\"{}\" value=\"{}\"/>",
                esc(it),
                i + 1
            );
        }
        out.push_str("    </EnumerationType>\n");
    }
    out.push_str("  </TypeDefinitions>\n  <LogCategories>\n");
    for (n, d) in LOG_CATEGORIES {
        let _ = writeln!(
            out,
            "    <Category name=\"{n}\" description=\"{}\"/>",
            esc(d)
        );
    }
    out.push_str("  </LogCategories>\n");
    let _ = writeln!(
        out,
        "  <DefaultExperiment startTime=\"0.0\" stopTime=\"{}\" stepSize=\"{}\"/>",
        num(h.stop_time_s),
        num(h.step_size_s)
    );
    out.push_str("  <ModelVariables>\n    <Float64 name=\"time\" valueReference=\"0\" causality=\"independent\" variability=\"continuous\" description=\"simulation time\" unit=\"s\"/>\n");
    let mut outputs = Vec::new();
    for (i, a) in table.arrays.iter().enumerate() {
        let vr = i + 1;
        let s = &table.scalars[a.slots.start];
        let (c, var) = causality(s.causality);
        if s.causality == Causality::Output {
            outputs.push(vr);
        }
        let tag = match s.kind {
            Kind::Real => "Float64",
            Kind::Integer => "UInt64",
            Kind::Boolean => "Boolean",
            Kind::Enumeration { .. } => "Enumeration",
        };
        let start = if s.causality == Causality::Output {
            String::new()
        } else {
            let vals: Vec<String> = a
                .slots
                .clone()
                .map(|k| start_text(table.scalars[k].start))
                .collect();
            format!(" start=\"{}\"", vals.join(" "))
        };
        let unit = s
            .unit
            .map(|u| format!(" unit=\"{}\"", esc(u)))
            .unwrap_or_default();
        let declared = if let Kind::Enumeration { type_name, .. } = s.kind {
            format!(" declaredType=\"{type_name}\"")
        } else {
            String::new()
        };
        let initial = if s.causality == Causality::Output {
            " initial=\"calculated\""
        } else {
            ""
        };
        let range = if matches!(s.kind, Kind::Real | Kind::Integer) {
            range_attrs(s)
        } else {
            String::new()
        };
        let description = match a.element_of {
            Some(i) => format!(
                "element of {} as a scalar (for masters without arrays; setting either sets both): {}",
                table.arrays[i].name, s.description
            ),
            None => s.description.clone(),
        };
        let _ = write!(
            out,
            "    <{tag} name=\"{}\" valueReference=\"{vr}\" description=\"{}\" causality=\"{c}\" variability=\"{var}\"{initial}{declared}{unit}{range}{start}",
            esc(&a.name),
            esc(&description)
        );
        if a.is_array {
            out.push_str(">\n");
            for d in &a.dims {
                let _ = writeln!(out, "      <Dimension start=\"{d}\"/>");
            }
            let _ = writeln!(out, "    </{tag}>");
        } else {
            out.push_str("/>\n");
        }
    }
    out.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    for vr in &outputs {
        let _ = writeln!(
            out,
            "    <Output valueReference=\"{vr}\" dependencies=\"\"/>"
        );
    }
    // FMI 3 value reference of each slot: its variable's index + 1 (a known's dependency is
    // on the variable proper, not on an element's scalar view).
    let mut vr_of = vec![0; table.scalars.len()];
    for (i, a) in table.arrays.iter().enumerate() {
        if a.element_of.is_none() {
            a.slots.clone().for_each(|k| vr_of[k] = i + 1);
        }
    }
    for vr in &outputs {
        let mut deps: Vec<usize> = table.arrays[vr - 1]
            .slots
            .clone()
            .flat_map(|k| table.initial_dependencies[k].iter().map(|d| vr_of[*d]))
            .collect();
        deps.sort_unstable();
        deps.dedup();
        let deps: Vec<String> = deps.iter().map(ToString::to_string).collect();
        let _ = writeln!(
            out,
            "    <InitialUnknown valueReference=\"{vr}\" dependencies=\"{}\"/>",
            deps.join(" ")
        );
    }
    out.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
}

/// 128-bit FNV-1a of `text`, formatted as a braced GUID.
pub fn content_token(text: &str) -> String {
    let fnv = |seed: u64| {
        text.bytes()
            .fold(seed, |h, b| (h ^ b as u64).wrapping_mul(0x0100_0000_01b3))
    };
    let (a, b) = (fnv(0xcbf2_9ce4_8422_2325), fnv(0x6c62_272e_07bb_0142));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// The modelDescription.xml and its token (a hash of the document with an empty token).
pub fn model_description(
    version: FmiVersion,
    table: &VariableTable,
    h: &Header,
) -> (String, String) {
    let render = |token: &str| {
        let mut out = String::with_capacity(256 * 1024);
        header_open(version, h, token, &mut out);
        match version {
            FmiVersion::V2 => body_v2(table, h, &mut out),
            FmiVersion::V3 => body_v3(table, h, &mut out),
        }
        out
    };
    let token = content_token(&render(""));
    (render(&token), token)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vars::OutputDecl;

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
        let (v3, _) = model_description(FmiVersion::V3, &table, &h);
        // The array (value reference 1), then its elements q[0], q[1] (2, 3), all outputs.
        assert!(v3.contains("<Float64 name=\"q\" valueReference=\"1\""));
        assert!(v3.contains("<Float64 name=\"q[0]\" valueReference=\"2\""));
        assert!(v3.contains("<Float64 name=\"q[1]\" valueReference=\"3\""));
        for vr in 1..=3 {
            assert!(v3.contains(&format!("<Output valueReference=\"{vr}\"")));
        }
        assert_eq!(v3.matches("<Dimension").count(), 1);
        // FMI 2 has the elements only, as before.
        let (v2, _) = model_description(FmiVersion::V2, &table, &h);
        assert_eq!(v2.matches("<ScalarVariable").count(), 2);
    }
}
