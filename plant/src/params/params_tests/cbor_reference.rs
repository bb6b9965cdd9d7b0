//! The parameter table's former implementation, kept verbatim (issue 27) as the independent
//! reference of the typed walk: the configuration serialised to a CBOR value tree, the tree
//! walked for the table, values set in the tree and the tree read back. `section_of` moved
//! here from params.rs with it; only the `use` lines and this header are new.

use ciborium::Value;

use crate::config::PlantConfig;
use crate::params::{Param, ParamError, ParamValue, enum_choices, range_for, unit_for};

/// Scenario-file path of a top-level `PlantConfig` field (`rate_hz` lives in `[run]`).
fn section_of(field: &str) -> String {
    match field {
        "rate_hz" | "substeps" | "seed" => format!("run.{field}"),
        _ => field.to_string(),
    }
}

/// The configuration as a value tree. CBOR's data model keeps what JSON cannot: NaN and ±inf
/// (`scheme.accel_dps2 = inf`) and the whole u64 range (`run.seed`), so the tree round-trips
/// every configuration exactly.
fn tree(cfg: &PlantConfig) -> Value {
    Value::serialized(cfg).expect("PlantConfig serialises")
}

fn walk(prefix: &str, v: &Value, out: &mut Vec<Param>) {
    let number = |value: ParamValue| Param {
        path: prefix.into(),
        value,
        unit: unit_for(prefix),
        range: range_for(prefix),
    };
    match v {
        Value::Map(m) => {
            for (k, v) in m {
                let k = k.as_text().unwrap_or_default();
                let p = if prefix.is_empty() {
                    section_of(k)
                } else {
                    format!("{prefix}.{k}")
                };
                walk(&p, v, out);
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                walk(&format!("{prefix}[{i}]"), v, out);
            }
        }
        Value::Bool(b) => out.push(Param {
            path: prefix.into(),
            value: ParamValue::Bool(*b),
            unit: "1",
            range: None,
        }),
        // A declared effect's name, kind, regressor, unit and axes are its structure, fixed
        // when the model is built (like `scheme.steps`); its switch and coefficients are
        // parameters.
        Value::Text(_) if prefix.contains(".custom[") => {}
        // A file name (and what to do after its end) is no parameter an FMU or a sweep can set
        // (the trajectory is data).
        Value::Text(_) if prefix.starts_with("carrier.trajectory.") => {}
        Value::Text(s) => out.push(Param {
            path: prefix.into(),
            value: ParamValue::Enum(s.clone()),
            unit: "1",
            range: None,
        }),
        Value::Integer(i) => out.push(number(match u64::try_from(*i) {
            Ok(u)
                if matches!(
                    prefix,
                    "run.seed" | "run.substeps" | "carrier.ship.sea.seed"
                ) =>
            {
                ParamValue::Integer(u)
            }
            _ => ParamValue::Real(i128::from(*i) as f64),
        })),
        Value::Float(x) => out.push(number(ParamValue::Real(*x))),
        // Nothing in a PlantConfig serialises to anything else.
        _ => {}
    }
}

/// Every scalar parameter of `cfg`, in a stable order.
pub fn flatten(cfg: &PlantConfig) -> Vec<Param> {
    let mut out = Vec::new();
    walk("", &tree(cfg), &mut out);
    out
}

/// `cfg` with the parameter at `path` set to `value` (range-checked by [`PlantConfig::validate`]).
pub fn set(cfg: &PlantConfig, path: &str, value: ParamValue) -> Result<PlantConfig, ParamError> {
    apply(cfg, std::iter::once((path, value)))
}

/// `cfg` with every `(path, value)` set, in one pass (an FMU sets all its parameters at once).
pub fn apply<'a>(
    cfg: &PlantConfig,
    values: impl IntoIterator<Item = (&'a str, ParamValue)>,
) -> Result<PlantConfig, ParamError> {
    let mut v = tree(cfg);
    let mut last = String::new();
    for (path, value) in values {
        set_node(&mut v, path, value)?;
        last = path.to_string();
    }
    v.deserialized().map_err(|e| ParamError::Invalid {
        path: last,
        message: e.to_string(),
    })
}

fn set_node(v: &mut Value, path: &str, value: ParamValue) -> Result<(), ParamError> {
    let inner = path
        .strip_prefix("run.")
        .filter(|p| ["rate_hz", "substeps", "seed"].contains(p))
        .unwrap_or(path);
    let mut node = v;
    for part in inner.split('.') {
        let (name, idx) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        node = match node {
            Value::Map(m) => m
                .iter_mut()
                .find(|(k, _)| k.as_text() == Some(name))
                .map(|(_, v)| v),
            _ => None,
        }
        .ok_or_else(|| ParamError::Unknown(path.into()))?;
        for ix in idx.split(']').filter(|s| !s.is_empty()) {
            let i: usize = ix
                .trim_start_matches('[')
                .parse()
                .map_err(|_| ParamError::Unknown(path.into()))?;
            node = match node {
                Value::Array(a) => a.get_mut(i),
                _ => None,
            }
            .ok_or_else(|| ParamError::Unknown(path.into()))?;
        }
    }
    let kind_ok = matches!(
        (&*node, &value),
        (
            Value::Integer(_) | Value::Float(_),
            ParamValue::Real(_) | ParamValue::Integer(_)
        ) | (Value::Bool(_), ParamValue::Bool(_))
            | (Value::Text(_), ParamValue::Enum(_))
    );
    if !kind_ok {
        let like = match &*node {
            Value::Bool(_) => "a switch (true/false)",
            Value::Text(_) => "an enumeration name",
            Value::Integer(_) | Value::Float(_) => "a number",
            _ => "a scalar",
        };
        return Err(ParamError::Invalid {
            path: path.into(),
            message: format!("expected {like}, got {value:?}"),
        });
    }
    if let (ParamValue::Enum(name), Some(choices)) = (&value, enum_choices(path))
        && !choices.contains(&name.as_str())
    {
        return Err(ParamError::Invalid {
            path: path.into(),
            message: format!("unknown variant {name:?}, expected one of {choices:?}"),
        });
    }
    *node = match (value, &*node) {
        // A whole-number field (`run.seed`, `run.substeps`) given as a real: only whole values.
        (ParamValue::Real(x), Value::Integer(_)) => {
            if !(x >= 0.0 && x.fract() == 0.0 && x <= u64::MAX as f64) {
                return Err(ParamError::Invalid {
                    path: path.into(),
                    message: format!("expected a whole number ≥ 0, got {x}"),
                });
            }
            Value::Integer((x as u64).into())
        }
        (ParamValue::Real(x), _) => Value::Float(x),
        (ParamValue::Integer(u), Value::Integer(_)) => Value::Integer(u.into()),
        (ParamValue::Integer(u), _) => Value::Float(u as f64),
        (ParamValue::Bool(b), _) => Value::Bool(b),
        (ParamValue::Enum(s), _) => Value::Text(s),
    };
    Ok(())
}
