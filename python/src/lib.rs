//! # rins-python
//!
//! The compiled part (`rins._rins`) of the `rins` Python package: scenarios loaded from files,
//! built-ins or dicts ([`scenario`]), the plant run to numpy arrays in chunks ([`simulation`]),
//! the reference navigator ([`navigation`]) and Monte Carlo seeds with the figures of
//! `rins paper table4` ([`montecarlo`]), and sweep files as `rins sweep` runs them
//! ([`sweep_file`]). Rust runs with the GIL released, and long calls stop on Ctrl-C
//! ([`interrupt`]); errors arrive as Python exceptions ([`errors`]): whole-number arguments are
//! checked by [`args`], the memory a call's arrays need by [`memory`], before they are made. The Dask helpers are Python (python/rins/montecarlo.py,
//! python/rins/sweep_file.py).
//! Docs: docs/python.md.

pub mod args;
pub mod errors;
pub mod interrupt;
pub mod memory;
pub mod montecarlo;
pub mod navigation;
pub mod scenario;
pub mod simulation;
pub mod sweep_file;

use pyo3::prelude::*;

/// The extension module `rins._rins` (re-exported by the `rins` package).
#[pymodule]
fn _rins(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ScenarioError", py.get_type::<errors::ScenarioError>())?;
    m.add("SweepError", py.get_type::<errors::SweepError>())?;
    m.add("NavigationError", py.get_type::<errors::NavigationError>())?;
    m.add("POSITION_LABELS", simulation::POSITION_LABELS.to_vec())?;
    m.add("FIGURES", montecarlo::FIGURES.to_vec())?;
    m.add("TEMP_NODES", rins_plant::thermal::node::NAMES.to_vec())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scenario::PyScenario>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<sweep_file::PySweepPlan>()?;
    m.add_function(wrap_pyfunction!(scenario::builtins, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::builtin_toml, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::run, m)?)?;
    m.add_function(wrap_pyfunction!(navigation::navigate, m)?)?;
    m.add_function(wrap_pyfunction!(montecarlo::end_figures, m)?)?;
    m.add_function(wrap_pyfunction!(montecarlo::table4_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_file::sweep_seed_figures, m)?)?;
    m.add_function(wrap_pyfunction!(args::py_whole, m)?)?;
    m.add_function(wrap_pyfunction!(args::py_seeds, m)?)?;
    Ok(())
}
