//! The FMI 2.0 modelDescription: the shared facts of [`super`] as `fmi_schema::fmi2` values,
//! serialised by fmi-schema, then completed where fmi-schema 0.8 has no field for them.

use fmi_schema::fmi2::{
    self, Category, CoSimulation, DefaultExperiment, Fmi2ModelDescription, Fmi2Unit,
    Fmi2VariableDependency, InitialUnknowns, LogCategories, ModelStructure, ModelVariables,
    Outputs, ScalarVariable, ScalarVariableElement, SimpleType, SimpleTypeElement, TypeDefinitions,
    UnitDefinitions,
};
use fmi_schema::traits::FmiModelDescription;

use super::{Declared, Element, Header, base_unit, roles};
use crate::standard::{FmiVersion, LOG_CATEGORIES};
use crate::vars::{Kind, VariableTable};

/// Children of fmiModelDescription in the order FMI 2.0's schema requires (an `xs:sequence`):
/// fmi-schema 0.8 writes LogCategories and DefaultExperiment before UnitDefinitions, which a
/// validating reader refuses.
const ROOT_ORDER: [&str; 9] = [
    "ModelExchange",
    "CoSimulation",
    "UnitDefinitions",
    "TypeDefinitions",
    "LogCategories",
    "DefaultExperiment",
    "VendorAnnotations",
    "ModelVariables",
    "ModelStructure",
];

/// The typed description, with `token` as its GUID.
pub(super) fn description(
    table: &VariableTable,
    h: &Header,
    token: &str,
) -> Result<Fmi2ModelDescription, String> {
    let vars = super::declared(FmiVersion::V2, table);
    let unknowns = super::unknowns(FmiVersion::V2, table);
    let dependency = |(index, deps): &(u32, Vec<u32>)| Fmi2VariableDependency {
        index: *index,
        dependencies: deps.clone(),
        dependencies_kind: Vec::new(),
    };
    Ok(Fmi2ModelDescription {
        fmi_version: "2.0".into(),
        model_name: h.model_identifier.clone(),
        guid: token.into(),
        description: Some(h.description.clone()),
        version: Some(super::FMU_VERSION.into()),
        copyright: Some(super::COPYRIGHT.into()),
        license: Some(super::LICENSE.into()),
        generation_tool: Some(h.generation_tool.clone()),
        variable_naming_convention: Some(super::NAMING_CONVENTION.into()),
        number_of_event_indicators: Some(0),
        co_simulation: Some(CoSimulation {
            model_identifier: h.model_identifier.clone(),
            needs_execution_tool: Some(false),
            can_handle_variable_communication_step_size: Some(true),
            can_interpolate_inputs: Some(false),
            max_output_derivative_order: Some(0),
            can_run_asynchronuously: Some(false),
            can_be_instantiated_only_once_per_process: Some(false),
            can_not_use_memory_management_functions: Some(true),
            can_get_and_set_fmu_state: Some(true),
            can_serialize_fmu_state: Some(true),
            provides_directional_derivative: Some(false),
            source_files: None,
        }),
        log_categories: Some(LogCategories {
            categories: LOG_CATEGORIES
                .iter()
                .map(|(name, d)| Category {
                    name: (*name).into(),
                    description: Some((*d).into()),
                })
                .collect(),
        }),
        default_experiment: Some(DefaultExperiment {
            start_time: Some(0.0),
            stop_time: Some(h.stop_time_s),
            tolerance: None,
            step_size: Some(h.step_size_s),
        }),
        unit_definitions: Some(UnitDefinitions {
            units: super::units(table)
                .into_iter()
                .map(|(name, si)| Fmi2Unit {
                    name: name.into(),
                    base_unit: si.as_ref().map(|u| base_unit!(fmi2::BaseUnit, u)),
                    display_unit: Vec::new(),
                })
                .collect(),
        })
        // A list holds one element or more, or is left out (the schema's minOccurs).
        .filter(|u| !u.units.is_empty()),
        // The items are added after serialising ([`complete`]).
        type_definitions: Some(TypeDefinitions {
            types: super::enum_types(table)
                .into_iter()
                .map(|(name, _)| SimpleType {
                    name: name.into(),
                    description: None,
                    elem: SimpleTypeElement::Enumeration,
                })
                .collect(),
        })
        .filter(|t| !t.types.is_empty()),
        model_variables: ModelVariables {
            variables: vars.iter().map(variable).collect::<Result<_, _>>()?,
        },
        model_structure: ModelStructure {
            outputs: Outputs {
                unknowns: unknowns
                    .iter()
                    .map(|(i, _)| dependency(&(*i, Vec::new())))
                    .collect(),
            },
            initial_unknowns: InitialUnknowns {
                unknowns: unknowns.iter().map(dependency).collect(),
            },
            ..Default::default()
        },
        ..Default::default()
    })
}

/// One ScalarVariable. An Enumeration is written as an Integer with the same declaredType and
/// start (fmi-schema 0.8's Enumeration element has no attributes) and renamed in [`complete`].
fn variable(v: &Declared<'_>) -> Result<ScalarVariable, String> {
    let (causality, variability, initial) = roles!(fmi2, v.scalar.causality);
    let start = v.start.first().copied();
    let integer = |declared_type: Option<&str>| -> Result<ScalarVariableElement, String> {
        let start = start
            .map(|s| {
                let u = super::whole(v.name, s)?;
                i32::try_from(u)
                    .map_err(|_| format!("{}: start {u} exceeds FMI 2's Integer", v.name))
            })
            .transpose()?;
        Ok(ScalarVariableElement::Integer(fmi2::Integer {
            declared_type: declared_type.map(Into::into),
            start,
        }))
    };
    let elem = match v.scalar.kind {
        Kind::Real => ScalarVariableElement::Real(fmi2::Real {
            start: start.map(|s| super::real(v.name, s)).transpose()?,
            ..Default::default()
        }),
        Kind::Integer => integer(None)?,
        Kind::Boolean => ScalarVariableElement::Boolean(fmi2::Boolean {
            declared_type: None,
            start: start.map(|s| super::boolean(v.name, s)).transpose()?,
        }),
        Kind::Enumeration { type_name, .. } => integer(Some(type_name))?,
    };
    Ok(ScalarVariable {
        name: v.name.into(),
        value_reference: v.vr,
        description: Some(v.description.clone()),
        causality,
        variability: Some(variability),
        initial,
        elem,
    })
}

/// Adds to the serialised document what fmi-schema 0.8 cannot say in FMI 2.0.
fn complete(doc: &mut Element, table: &VariableTable) -> Result<(), String> {
    let missing = |what: &str| format!("fmi-schema wrote no {what}");
    doc.children.sort_by_key(|c| {
        ROOT_ORDER
            .iter()
            .position(|t| *t == c.tag)
            .unwrap_or(ROOT_ORDER.len())
    });
    // SimpleType's Enumeration has no items in fmi-schema 0.8.
    let types = match doc.child_mut("TypeDefinitions") {
        Some(t) => t.children.as_mut_slice(),
        None => &mut [],
    };
    for (ty, (_, items)) in types.iter_mut().zip(super::enum_types(table)) {
        let e = ty
            .child_mut("Enumeration")
            .ok_or_else(|| missing("SimpleType Enumeration"))?;
        e.children = items
            .iter()
            .enumerate()
            .map(|(i, item)| {
                let mut it = Element::new("Item");
                it.set("name", *item);
                it.set("value", (i + 1).to_string());
                it
            })
            .collect();
    }
    // fmi-schema 0.8's Real has no unit, min or max, and its Integer no min or max.
    let vars = super::declared(FmiVersion::V2, table);
    let model_variables = doc
        .child_mut("ModelVariables")
        .ok_or_else(|| missing("ModelVariables"))?;
    for (i, (sv, v)) in model_variables.children.iter_mut().zip(&vars).enumerate() {
        // ModelStructure names variables by this index: said beside each for readers.
        sv.comment = Some(format!("index {}", i + 1));
        let ty = sv
            .children
            .first_mut()
            .ok_or_else(|| missing("ScalarVariable type"))?;
        let (lo, hi) = v.limits();
        match v.scalar.kind {
            Kind::Real => {
                if let Some(u) = v.scalar.unit {
                    ty.set("unit", u);
                }
                lo.into_iter().for_each(|x| ty.set("min", x.to_string()));
                hi.into_iter().for_each(|x| ty.set("max", x.to_string()));
            }
            Kind::Integer => {
                lo.into_iter()
                    .for_each(|x| ty.set("min", (x as i64).to_string()));
                hi.into_iter()
                    .for_each(|x| ty.set("max", (x as u64).to_string()));
            }
            Kind::Enumeration { .. } => ty.tag = "Enumeration".into(),
            Kind::Boolean => {}
        }
    }
    // An Unknown without `dependencies` depends on every known; fmi-schema 0.8 leaves an empty
    // list out, so "depends on none" is written back. It also writes empty lists (Derivatives
    // here, always), where the schema wants at least one Unknown or no list.
    let structure = doc
        .child_mut("ModelStructure")
        .ok_or_else(|| missing("ModelStructure"))?;
    structure.children.retain(|list| !list.children.is_empty());
    for list in &mut structure.children {
        for u in &mut list.children {
            if u.attr("dependencies").is_none() {
                u.set("dependencies", "");
            }
        }
    }
    Ok(())
}

/// The document, with `token` as its GUID.
pub(super) fn document(table: &VariableTable, h: &Header, token: &str) -> Result<String, String> {
    let text = description(table, h, token)?
        .serialize()
        .map_err(|e| e.to_string())?;
    super::finish(&text, |doc| complete(doc, table))
}
