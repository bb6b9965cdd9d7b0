//! Reading an FMI 2.0 modelDescription.xml: the GUID, model identifier and variables.

use std::collections::HashMap;

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

/// Attributes of every `<tag ...>` in `xml`, in order (enough for modelDescription files).
fn tags(xml: &str) -> Vec<(String, HashMap<String, String>)> {
    let mut out = Vec::new();
    let mut rest = xml;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let Some(end) = rest.find('>') else { break };
        let body = rest[..end].trim_end_matches('/');
        rest = &rest[end + 1..];
        if body.starts_with(['?', '!', '/']) {
            continue;
        }
        let (name, mut attrs_text) = body.split_once(char::is_whitespace).unwrap_or((body, ""));
        let mut attrs = HashMap::new();
        while let Some(eq) = attrs_text.find("=\"") {
            let key = attrs_text[..eq].trim().to_string();
            let after = &attrs_text[eq + 2..];
            let Some(close) = after.find('"') else { break };
            let v = after[..close]
                .replace("&quot;", "\"")
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            attrs.insert(key, v);
            attrs_text = &after[close + 1..];
        }
        out.push((name.to_string(), attrs));
    }
    out
}

/// The GUID and variables of an FMI 2.0 modelDescription.
pub fn parse_model_description(xml: &str) -> Result<(String, String, Vec<Variable>), String> {
    let t = tags(xml);
    let root = t
        .iter()
        .find(|(n, _)| n == "fmiModelDescription")
        .ok_or("no fmiModelDescription element")?;
    if root.1.get("fmiVersion").map(String::as_str) != Some("2.0") {
        return Err(format!(
            "this importer reads FMI 2.0; the FMU says fmiVersion {:?}",
            root.1.get("fmiVersion")
        ));
    }
    let guid = root.1.get("guid").cloned().ok_or("no guid")?;
    let id = t
        .iter()
        .find(|(n, _)| n == "CoSimulation")
        .and_then(|(_, a)| a.get("modelIdentifier").cloned())
        .ok_or("not a co-simulation FMU")?;
    let mut vars = Vec::new();
    for (i, (name, attrs)) in t.iter().enumerate() {
        if name != "ScalarVariable" {
            continue;
        }
        let type_name = t.get(i + 1).map(|(n, _)| n.clone()).unwrap_or_default();
        vars.push(Variable {
            name: attrs.get("name").cloned().unwrap_or_default(),
            vr: attrs
                .get("valueReference")
                .and_then(|v| v.parse().ok())
                .ok_or("ScalarVariable without a valueReference")?,
            type_name,
            causality: attrs
                .get("causality")
                .cloned()
                .unwrap_or_else(|| "local".into()),
        });
    }
    Ok((guid, id, vars))
}
