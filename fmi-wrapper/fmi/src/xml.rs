//! modelDescription.xml for FMI 2.0 and FMI 3.0, generated from the [`VariableTable`] (the model's
//! one source of truth for its variables) as typed values of the `fmi-schema` crate, which
//! writes them: elements, attributes and escaping come from its definitions of both standards.
//! The GUID / instantiation token is a hash of the document itself, so a stale binary and a
//! newer description cannot be paired silently.
//!
//! What both versions say alike is worked out here once, from the table: each variable's name,
//! value reference, role, start values and range ([`Declared`]), the units, enumeration types
//! and model structure. [`fmi2`] and [`fmi3`] only put it into their version's types, and add
//! by [`tree`] what fmi-schema 0.8 has no field for (each such edit says why where it is made).

mod fmi2;
mod fmi3;
mod tree;
mod units;

#[cfg(test)]
mod tests;

pub use tree::Element;
pub use units::{SiUnit, si_unit};

use crate::standard::FmiVersion;
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

/// Version of the FMUs (the crate's).
const FMU_VERSION: &str = env!("CARGO_PKG_VERSION");
/// Licence of the FMUs.
const LICENSE: &str = "MIT OR Apache-2.0";
/// Copyright line of the FMUs.
const COPYRIGHT: &str = "The rins authors";
/// Names are structured (`a.b[2]`), so tools may show them as a tree and arrays.
const NAMING_CONVENTION: &str = "structured";

/// One variable as a modelDescription declares it, in either version: FMI 2 declares one per
/// slot, FMI 3 one per variable of the table's FMI 3 grouping (arrays, scalars, then the
/// scalar views of array elements).
#[derive(Clone, Debug)]
struct Declared<'a> {
    /// Name.
    name: &'a str,
    /// Value reference.
    vr: u32,
    /// One line for the user.
    description: String,
    /// The (first) slot: kind, causality, unit and range.
    scalar: &'a ScalarVar,
    /// Start values, one per element; none for outputs (computed by the FMU: `calculated`).
    start: Vec<Value>,
    /// Array dimensions (FMI 3 arrays; empty otherwise).
    dims: &'a [usize],
}

impl Declared<'_> {
    /// The finite ends of its range (an open end is left out of the document).
    fn limits(&self) -> (Option<f64>, Option<f64>) {
        match self.scalar.range {
            Some((lo, hi)) => (
                Some(lo).filter(|x| x.is_finite()),
                Some(hi).filter(|x| x.is_finite()),
            ),
            None => (None, None),
        }
    }
}

/// The variables `version` declares, in document order.
fn declared(version: FmiVersion, table: &VariableTable) -> Vec<Declared<'_>> {
    let start = |slots: std::ops::Range<usize>| -> Vec<Value> {
        let s = &table.scalars[slots.start];
        if s.causality == Causality::Output {
            Vec::new()
        } else {
            slots.map(|k| table.scalars[k].start).collect()
        }
    };
    match version {
        FmiVersion::V2 => table
            .scalars
            .iter()
            .enumerate()
            .map(|(slot, s)| Declared {
                name: &s.name,
                vr: slot as u32,
                description: s.description.clone(),
                scalar: s,
                start: start(slot..slot + 1),
                dims: &[],
            })
            .collect(),
        // Value reference 0 is `time`, declared by the FMI 3 writer itself.
        FmiVersion::V3 => table
            .arrays
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let s = &table.scalars[a.slots.start];
                Declared {
                    name: &a.name,
                    vr: i as u32 + 1,
                    description: match a.element_of {
                        Some(array) => format!(
                            "element of {} as a scalar (for masters without arrays; setting either sets both): {}",
                            table.arrays[array].name, s.description
                        ),
                        None => s.description.clone(),
                    },
                    scalar: s,
                    start: start(a.slots.clone()),
                    dims: if a.is_array { &a.dims } else { &[] },
                }
            })
            .collect(),
    }
}

/// The outputs, each with the knowns its initial value depends on, numbered as `version`
/// numbers variables in ModelStructure: FMI 2 by 1-based index in ModelVariables, FMI 3 by
/// value reference. Every output is also an initial unknown; as an output (at communication
/// points) it depends on no known directly: inputs act through the internal steps.
fn unknowns(version: FmiVersion, table: &VariableTable) -> Vec<(u32, Vec<u32>)> {
    match version {
        FmiVersion::V2 => table
            .scalars
            .iter()
            .enumerate()
            .filter(|(_, s)| s.causality == Causality::Output)
            .map(|(slot, _)| {
                let deps = table.initial_dependencies[slot].iter();
                (slot as u32 + 1, deps.map(|k| *k as u32 + 1).collect())
            })
            .collect(),
        FmiVersion::V3 => {
            // Value reference of each slot's variable proper (a known's dependency is on the
            // variable, not on an element's scalar view).
            let mut vr_of = vec![0; table.scalars.len()];
            for (i, a) in table.arrays.iter().enumerate() {
                if a.element_of.is_none() {
                    a.slots.clone().for_each(|k| vr_of[k] = i as u32 + 1);
                }
            }
            table
                .arrays
                .iter()
                .enumerate()
                .filter(|(_, a)| table.scalars[a.slots.start].causality == Causality::Output)
                .map(|(i, a)| {
                    let mut deps: Vec<u32> = a
                        .slots
                        .clone()
                        .flat_map(|k| table.initial_dependencies[k].iter().map(|d| vr_of[*d]))
                        .collect();
                    deps.sort_unstable();
                    deps.dedup();
                    (i as u32 + 1, deps)
                })
                .collect()
        }
    }
}

/// The units the variables use, by name, each with its SI expansion where one is known.
fn units(table: &VariableTable) -> Vec<(&'static str, Option<SiUnit>)> {
    let mut used: Vec<&'static str> = table.scalars.iter().filter_map(|s| s.unit).collect();
    used.sort_unstable();
    used.dedup();
    used.into_iter().map(|u| (u, si_unit(u))).collect()
}

/// The enumeration types the variables use, in first-use order: name and items (item `i` has
/// the value `i + 1`).
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

/// A start value as a whole number: an Integer, or an enumeration item's value (1-based).
fn whole(name: &str, v: Value) -> Result<u64, String> {
    match v {
        Value::Integer(u) => Ok(u),
        Value::Enumeration(i) => Ok(i as u64 + 1),
        v => Err(format!("{name}: start value {v:?} is not a whole number")),
    }
}

/// A start value as a Real.
fn real(name: &str, v: Value) -> Result<f64, String> {
    match v {
        Value::Real(x) => Ok(x),
        v => Err(format!("{name}: start value {v:?} is not a Real")),
    }
}

/// A start value as a Boolean.
fn boolean(name: &str, v: Value) -> Result<bool, String> {
    match v {
        Value::Boolean(b) => Ok(b),
        v => Err(format!("{name}: start value {v:?} is not a Boolean")),
    }
}

/// The causality, variability and initial of a variable of `causality`, in the types of the
/// fmi-schema module `$m` (`fmi2` or `fmi3`: both name them alike). Parameters are fixed;
/// inputs and outputs change at communication points only (`discrete`); outputs are computed
/// by the FMU.
macro_rules! roles {
    ($m:ident, $causality:expr) => {{
        use fmi_schema::$m::{Causality as C, Initial, Variability as V};
        match $causality {
            crate::vars::Causality::Parameter => (C::Parameter, V::Fixed, None),
            crate::vars::Causality::Input => (C::Input, V::Discrete, None),
            crate::vars::Causality::Output => (C::Output, V::Discrete, Some(Initial::Calculated)),
        }
    }};
}
use roles;

/// `$unit` ([`SiUnit`]) as the BaseUnit type `$t` of either fmi-schema module (both have the
/// same fields); exponents of 0, a factor of 1 and an offset of 0 are left out, as their
/// defaults.
macro_rules! base_unit {
    ($t:path, $unit:expr) => {{
        let u: &crate::xml::SiUnit = $unit;
        let e = |i: usize| Some(i32::from(u.exponents[i])).filter(|x| *x != 0);
        $t {
            kg: e(0),
            m: e(1),
            s: e(2),
            a: e(3),
            k: e(4),
            mol: e(5),
            cd: e(6),
            rad: e(7),
            factor: Some(u.factor).filter(|f| *f != 1.0),
            offset: Some(u.offset).filter(|o| *o != 0.0),
        }
    }};
}
use base_unit;

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

/// The document fmi-schema serialised (`text`), completed where the library cannot express
/// the standard (`complete`, per version) and with XML Schema's infinities: the last step of
/// both versions' writers.
fn finish(
    text: &str,
    complete: impl FnOnce(&mut Element) -> Result<(), String>,
) -> Result<String, String> {
    let mut doc = Element::parse(text)?;
    complete(&mut doc)?;
    doc.spell_infinities();
    doc.to_document()
}

/// The modelDescription.xml and its token (a hash of the document with an empty token).
///
/// Fails only on a table whose start values do not match their variables' kinds (or exceed
/// FMI 2's Integer range), or if fmi-schema's output could not be read back: both are bugs
/// of the code, not of anything a user supplies.
pub fn model_description(
    version: FmiVersion,
    table: &VariableTable,
    h: &Header,
) -> Result<(String, String), String> {
    let render = |token: &str| match version {
        FmiVersion::V2 => fmi2::document(table, h, token),
        FmiVersion::V3 => fmi3::document(table, h, token),
    };
    let token = content_token(&render("")?);
    Ok((render(&token)?, token))
}
