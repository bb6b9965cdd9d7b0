//! `rins.Scenario`: a scenario loaded from a file, a built-in (`builtin:NAME`) or a Python dict
//! (the TOML file as a dict), kept with its TOML text so it can travel to other processes
//! (Dask workers) and be loaded there to the same bits.

use std::path::Path;

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rins_scenario::file::BUILTIN;
use rins_scenario::{Scenario, ScenarioError};

use crate::errors::scenario_error;

/// A validated scenario (`Scenario(source)`): `source` is a file path, `builtin:NAME` (see
/// `rins.builtins()`), a dict shaped like the TOML file, or another `Scenario`. Bad input raises
/// `rins.ScenarioError` whose message names the file, line and field and the allowed range.
#[pyclass(module = "rins", name = "Scenario", frozen)]
pub struct PyScenario {
    /// The loaded scenario.
    pub inner: Scenario,
    /// The TOML text it was loaded from.
    pub text: String,
}

impl PyScenario {
    /// Parses `text`; `source` names it in errors.
    pub fn from_text(text: String, source: &str) -> PyResult<Self> {
        let inner = Scenario::from_toml(&text, source).map_err(scenario_error)?;
        Ok(Self { inner, text })
    }

    /// Loads a path or `builtin:NAME` the way `rins run` does (a bare built-in name works when
    /// no file of that name exists).
    pub fn from_path(path: &str) -> PyResult<Self> {
        let name = path.strip_prefix("builtin:").unwrap_or(path);
        let explicit = path.starts_with("builtin:");
        if let Some((n, text)) = BUILTIN
            .iter()
            .find(|(n, _)| *n == name)
            .filter(|_| explicit || !Path::new(path).exists())
        {
            return Self::from_text((*text).to_string(), &format!("builtin:{n}"));
        }
        if explicit {
            // Scenario::load words the error (the list of built-ins).
            return Err(scenario_error(
                Scenario::load(Path::new(path))
                    .err()
                    .unwrap_or_else(|| ScenarioError::Parse {
                        source_name: path.into(),
                        message: "no such built-in scenario".into(),
                    }),
            ));
        }
        let text = std::fs::read_to_string(path).map_err(|e| {
            scenario_error(ScenarioError::Read {
                path: path.into(),
                source: e,
            })
        })?;
        Self::from_text(text, path)
    }

    /// A dict laid out like the TOML file, walked once into TOML text (so the same checks and
    /// messages apply; line numbers then refer to `rins.to_toml(d)`); no JSON in between.
    pub fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Self> {
        let text = dict_to_toml(d)?;
        Self::from_text(text, "dict")
    }

    /// Accepts a `Scenario`, a path / `builtin:NAME` string or a dict.
    pub fn resolve(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(s) = obj.cast::<PyScenario>() {
            // Already read and checked: a copy, not a second parse of its text.
            let s = s.get();
            return Ok(Self {
                inner: s.inner.clone(),
                text: s.text.clone(),
            });
        }
        if let Ok(d) = obj.cast::<PyDict>() {
            return Self::from_dict(d);
        }
        if let Ok(p) = obj.extract::<std::path::PathBuf>() {
            return Self::from_path(&p.to_string_lossy());
        }
        Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "scenario: expected a file path, 'builtin:NAME', a dict or a rins.Scenario, got {}",
            obj.get_type().name()?
        )))
    }
}

/// A `ScenarioError` for the dict's value at `path`.
fn dict_error(path: &str, what: &str) -> PyErr {
    let at = if path.is_empty() {
        String::new()
    } else {
        format!("{path}: ")
    };
    crate::errors::ScenarioError::new_err(format!("dict: {at}{what}"))
}

/// A dict's value as a TOML value, read in one walk: strings, booleans, whole numbers (within
/// TOML's 64-bit signed range), finite floats, lists and tuples (as arrays) and dicts with
/// string keys (as tables). Anything else is refused naming its dotted path under `path`
/// (`site.lat_deg`, `parameter[0].values[1]`) and what it is.
fn toml_value(v: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    // bool before int: Python's True is an int too.
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if let Ok(i) = v.cast::<PyInt>() {
        return i.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            dict_error(
                path,
                &format!(
                    "expected a whole number in [{}, {}] (TOML's integers), got {i}",
                    i64::MIN,
                    i64::MAX
                ),
            )
        });
    }
    if let Ok(x) = v.cast::<PyFloat>() {
        let x = x.value();
        if !x.is_finite() {
            let shown = if x.is_nan() {
                "NaN".to_string()
            } else {
                x.to_string()
            };
            return Err(dict_error(
                path,
                &format!("expected a finite number, got {shown}"),
            ));
        }
        return Ok(toml::Value::Float(x));
    }
    if let Ok(text) = v.cast::<PyString>() {
        return Ok(toml::Value::String(text.to_str()?.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return toml_table(d, path).map(toml::Value::Table);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .enumerate()
            .map(|(i, x)| toml_value(&x?, &format!("{path}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy's scalars (np.int64, np.float32, …) are numbers though not Python's int or float.
    if v.hasattr("__index__")? {
        let i = v.call_method0("__index__")?;
        return toml_value(&i, path);
    }
    if v.hasattr("__float__")? && !v.is_none() {
        let x = v.call_method0("__float__")?;
        return toml_value(&x, path);
    }
    let kind = if v.is_none() {
        "None, which has no TOML form (leave the key out for its default)".to_string()
    } else {
        format!("a {} (not representable as TOML)", v.get_type().name()?)
    };
    Err(dict_error(
        path,
        &format!("expected a string, number, bool, list or dict, got {kind}"),
    ))
}

/// A dict with string keys as a TOML table (see [`toml_value`]).
fn toml_table(d: &Bound<'_, PyDict>, path: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, x) in d.iter() {
        let Ok(key) = k.cast::<PyString>() else {
            return Err(dict_error(
                path,
                &format!("expected string keys, got the key {}", k.repr()?),
            ));
        };
        let key = key.to_str()?.to_string();
        let sub = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        let value = toml_value(&x, &sub)?;
        table.insert(key, value);
    }
    Ok(table)
}

/// The dict as TOML text, walked once ([`toml_value`]): the scenario parser then reads it as
/// it reads a file, so a dict gets the same checks and messages (lines refer to this text).
pub fn dict_to_toml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    let table = toml_table(d, "")?;
    toml::to_string(&table).map_err(|e| dict_error("", &format!("not representable as TOML: {e}")))
}

#[pymethods]
impl PyScenario {
    #[new]
    fn py_new(source: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::resolve(source)
    }

    /// Parses TOML text; `source` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, source = "text"))]
    fn from_toml(text: String, source: &str) -> PyResult<Self> {
        Self::from_text(text, source)
    }

    /// Where it came from: the file path, `builtin:NAME`, `dict` or `text`.
    #[getter]
    fn source(&self) -> &str {
        &self.inner.source
    }

    /// `[scenario] name`.
    #[getter]
    fn name(&self) -> &str {
        &self.inner.meta.name
    }

    /// `[scenario] duration_s`: the run length when none is given.
    #[getter]
    fn duration_s(&self) -> f64 {
        self.inner.meta.duration_s
    }

    /// `[run] rate_hz`: output samples per second.
    #[getter]
    fn rate_hz(&self) -> f64 {
        self.inner.plant.rate_hz
    }

    /// `[run] seed`.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.plant.seed
    }

    /// The TOML text it was loaded from.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The resolved plant configuration (preset laid under the file's `[sensor]`) as TOML text,
    /// what `rins run` writes to resolved-plant.toml.
    fn resolved_plant_toml(&self) -> PyResult<String> {
        toml::to_string_pretty(&self.inner.plant)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
    }

    /// Pickles as its TOML text (Dask sends scenarios to workers this way).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let ctor = py.get_type::<PyScenario>().getattr("from_toml")?;
        let s = slf.get();
        let args = PyTuple::new(py, [s.text.clone(), s.inner.source.clone()])?;
        PyTuple::new(py, [ctor.into_any(), args.into_any()])
    }

    fn __repr__(&self) -> String {
        format!(
            "rins.Scenario({:?}: {:?}, {} s at {} Hz, seed {})",
            self.inner.source,
            self.inner.meta.name,
            self.inner.meta.duration_s,
            self.inner.plant.rate_hz,
            self.inner.plant.seed
        )
    }
}

/// Names of the built-in scenarios (`builtin:NAME`).
#[pyfunction]
pub fn builtins() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

/// The TOML text of a built-in scenario (`tomllib.loads` of it is a dict `Scenario` accepts).
#[pyfunction]
pub fn builtin_toml(name: &str) -> PyResult<&'static str> {
    let n = name.strip_prefix("builtin:").unwrap_or(name);
    BUILTIN
        .iter()
        .find(|(b, _)| *b == n)
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            crate::errors::ScenarioError::new_err(format!(
                "{name}: no such built-in scenario; built-ins are {:?}",
                builtins()
            ))
        })
}

/// A dict laid out like a scenario file, as the TOML text `Scenario(dict)` parses (error line
/// numbers of a dict scenario refer to this text).
#[pyfunction]
pub fn to_toml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    dict_to_toml(d)
}
