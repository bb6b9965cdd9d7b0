//! The FMI 3.0 modelDescription: the shared facts of [`super`] as `fmi_schema::fmi3` values,
//! serialised by fmi-schema, then completed where fmi-schema 0.8 has no field for them.

use fmi_schema::fmi3::{
    self, Category, DefaultExperiment, Dimension, EnumerationItem, EnumerationType,
    Fmi3CoSimulation, Fmi3ModelDescription, Fmi3Unit, Fmi3Unknown, FmiBoolean, FmiFloat64,
    FmiInt64, FmiUInt64, LogCategories, ModelStructure, ModelVariables, TypeDefinition,
    TypeDefinitions, UnitDefinitions, Variable, VariableDependency,
};
use fmi_schema::traits::FmiModelDescription;
use fmi_schema::utils::AttrList;

use super::{Declared, Element, Header, base_unit, roles};
use crate::standard::{FmiVersion, LOG_CATEGORIES};
use crate::vars::{Kind, Value, VariableTable};

/// The typed description, with `token` as its instantiation token.
pub(super) fn description(
    table: &VariableTable,
    h: &Header,
    token: &str,
) -> Result<Fmi3ModelDescription, String> {
    let vars = super::declared(FmiVersion::V3, table);
    let unknown = |(vr, deps): &(u32, Vec<u32>)| Fmi3Unknown {
        value_reference: *vr,
        dependencies: Some(AttrList(deps.clone())),
        ..Default::default()
    };
    let unknowns = super::unknowns(FmiVersion::V3, table);
    let time = Variable::Float64(FmiFloat64 {
        name: "time".into(),
        value_reference: 0,
        description: Some("simulation time".into()),
        causality: Some(fmi3::Causality::Independent),
        variability: Some(fmi3::Variability::Continuous),
        ..Default::default()
    });
    let mut variables = vec![time];
    for v in &vars {
        variables.push(variable(v)?);
    }
    Ok(Fmi3ModelDescription {
        fmi_version: "3.0".into(),
        model_name: h.model_identifier.clone(),
        instantiation_token: token.into(),
        description: Some(h.description.clone()),
        version: Some(super::FMU_VERSION.into()),
        copyright: Some(super::COPYRIGHT.into()),
        license: Some(super::LICENSE.into()),
        generation_tool: Some(h.generation_tool.clone()),
        variable_naming_convention: Some(super::NAMING_CONVENTION.into()),
        co_simulation: Some(Fmi3CoSimulation {
            model_identifier: h.model_identifier.clone(),
            needs_execution_tool: Some(false),
            can_be_instantiated_only_once_per_process: Some(false),
            can_get_and_set_fmu_state: Some(true),
            can_serialize_fmu_state: Some(true),
            provides_directional_derivatives: Some(false),
            provides_adjoint_derivatives: Some(false),
            provides_per_element_dependencies: Some(false),
            can_handle_variable_communication_step_size: Some(true),
            max_output_derivative_order: Some(0),
            provides_intermediate_update: Some(false),
            can_return_early_after_intermediate_update: Some(false),
            has_event_mode: Some(false),
            provides_evaluate_discrete_states: Some(false),
            ..Default::default()
        }),
        unit_definitions: Some(UnitDefinitions {
            units: super::units(table)
                .into_iter()
                .map(|(name, si)| Fmi3Unit {
                    name: name.into(),
                    base_unit: si.as_ref().map(|u| base_unit!(fmi3::BaseUnit, u)),
                    ..Default::default()
                })
                .collect(),
        })
        // A list holds one element or more, or is left out (the schema's minOccurs).
        .filter(|u| !u.units.is_empty()),
        type_definitions: Some(TypeDefinitions {
            type_definitions: super::enum_types(table)
                .into_iter()
                .map(|(name, items)| {
                    TypeDefinition::Enumeration(EnumerationType {
                        name: name.into(),
                        description: None,
                        annotations: None,
                        quantity: None,
                        items: items
                            .iter()
                            .enumerate()
                            .map(|(i, item)| EnumerationItem {
                                name: (*item).into(),
                                value: i as i64 + 1,
                                description: None,
                                annotations: None,
                            })
                            .collect(),
                    })
                })
                .collect(),
        })
        .filter(|t| !t.type_definitions.is_empty()),
        log_categories: Some(LogCategories {
            categories: LOG_CATEGORIES
                .iter()
                .map(|(name, d)| Category {
                    name: (*name).into(),
                    description: Some((*d).into()),
                    annotations: None,
                })
                .collect(),
        }),
        default_experiment: Some(DefaultExperiment {
            start_time: Some(0.0),
            stop_time: Some(h.stop_time_s),
            step_size: Some(h.step_size_s),
            ..Default::default()
        }),
        model_variables: ModelVariables { variables },
        model_structure: ModelStructure {
            unknowns: unknowns
                .iter()
                .map(|(vr, _)| VariableDependency::Output(unknown(&(*vr, Vec::new()))))
                .chain(
                    unknowns
                        .iter()
                        .map(|u| VariableDependency::InitialUnknown(unknown(u))),
                )
                .collect(),
        },
        ..Default::default()
    })
}

/// One variable. An Enumeration is written as an Int64 (the type its values travel as) with
/// the same declaredType and start, since fmi-schema 0.8 has no Enumeration variable, and
/// renamed in [`complete`].
fn variable(v: &Declared<'_>) -> Result<Variable, String> {
    let (causality, variability, initial) = roles!(fmi3, v.scalar.causality);
    let dimensions: Vec<Dimension> = v.dims.iter().map(|d| Dimension::Fixed(*d as u64)).collect();
    let (lo, hi) = v.limits();
    let (name, description) = (v.name.to_string(), Some(v.description.clone()));
    Ok(match v.scalar.kind {
        Kind::Real => Variable::Float64(FmiFloat64 {
            name,
            value_reference: v.vr,
            description,
            causality: Some(causality),
            variability: Some(variability),
            initial,
            dimensions,
            start: starts(v, super::real)?,
            min: lo,
            max: hi,
            ..Default::default()
        }),
        Kind::Integer => Variable::UInt64(FmiUInt64 {
            name,
            value_reference: v.vr,
            description,
            causality: Some(causality),
            variability: Some(variability),
            initial,
            dimensions,
            start: starts(v, super::whole)?,
            min: lo.map(|x| x as u64),
            max: hi.map(|x| x as u64),
            ..Default::default()
        }),
        Kind::Boolean => Variable::Boolean(FmiBoolean {
            name,
            value_reference: v.vr,
            description,
            causality: Some(causality),
            variability: Some(variability),
            initial,
            dimensions,
            start: starts(v, super::boolean)?,
            ..Default::default()
        }),
        Kind::Enumeration { type_name, .. } => Variable::Int64(FmiInt64 {
            name,
            value_reference: v.vr,
            description,
            causality: Some(causality),
            variability: Some(variability),
            initial,
            dimensions,
            declared_type: Some(type_name.into()),
            start: starts(v, |n, s| super::whole(n, s).map(|u| u as i64))?,
            ..Default::default()
        }),
    })
}

/// The start values of `v` as `convert` reads each, as the attribute's list (none for an
/// output).
fn starts<T>(
    v: &Declared<'_>,
    convert: impl Fn(&str, Value) -> Result<T, String>,
) -> Result<Option<AttrList<T>>, String> {
    let s = v.start.iter().map(|s| convert(v.name, *s));
    let s: Vec<T> = s.collect::<Result<_, _>>()?;
    Ok(Some(AttrList(s)).filter(|s| !s.is_empty()))
}

/// Adds to the serialised document what fmi-schema 0.8 cannot say in FMI 3.0.
fn complete(doc: &mut Element, table: &VariableTable) -> Result<(), String> {
    let missing = |what: &str| format!("fmi-schema wrote no {what}");
    // fmi-schema 0.8 spells BaseUnit's ampere and kelvin exponents `a` and `k`; the standard
    // (and its own FMI 2 module) spells them `A` and `K`.
    if let Some(units) = doc.child_mut("UnitDefinitions") {
        for base in units
            .children
            .iter_mut()
            .filter_map(|u| u.child_mut("BaseUnit"))
        {
            base.rename_attr("a", "A");
            base.rename_attr("k", "K");
        }
    }
    // fmi-schema 0.8's Float64 has no unit; its variables lack Enumeration (written as Int64).
    let model_variables = doc
        .child_mut("ModelVariables")
        .ok_or_else(|| missing("ModelVariables"))?;
    let mut elements = model_variables.children.iter_mut();
    let time = elements.next().ok_or_else(|| missing("time"))?;
    time.set("unit", "s");
    for (el, v) in elements.zip(super::declared(FmiVersion::V3, table)) {
        match v.scalar.kind {
            Kind::Real => {
                if let Some(u) = v.scalar.unit {
                    el.set("unit", u);
                }
            }
            Kind::Enumeration { .. } => el.tag = "Enumeration".into(),
            Kind::Integer | Kind::Boolean => {}
        }
    }
    Ok(())
}

/// The document, with `token` as its instantiation token.
pub(super) fn document(table: &VariableTable, h: &Header, token: &str) -> Result<String, String> {
    let text = description(table, h, token)?
        .serialize()
        .map_err(|e| e.to_string())?;
    super::finish(&text, |doc| complete(doc, table))
}
