//! The package's exceptions: `rins.ScenarioError` (a `ValueError` whose message names the file,
//! line and field and the allowed range), `rins.SweepError` (a `ScenarioError` for a sweep
//! file) and `rins.NavigationError` (a navigation run that could not be made, e.g. the table
//! moved during self-alignment).

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    rins,
    ScenarioError,
    PyValueError,
    "A scenario could not be loaded: the message names the file, line and field and the allowed range."
);

create_exception!(
    rins,
    SweepError,
    ScenarioError,
    "A sweep file could not be loaded: the message names the file, line, column and key and what is allowed, as `rins sweep` words it."
);

create_exception!(
    rins,
    NavigationError,
    PyRuntimeError,
    "A navigation run could not be made (the message says why)."
);

/// A scenario error as `rins.ScenarioError`, with the scenario crate's message.
pub fn scenario_error(e: rins_scenario::ScenarioError) -> PyErr {
    ScenarioError::new_err(e.to_string())
}

/// A navigation session error as `rins.NavigationError`.
pub fn navigation_error(e: rins_experiments::session::SessionError) -> PyErr {
    NavigationError::new_err(e.to_string())
}
