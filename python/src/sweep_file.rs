//! Sweep files (`rins sweep FILE`, docs/sweeps.md) from Python: `rins._rins.SweepPlan` loads and
//! checks the file with the scenario crate's own loader (so errors name the file, line and key
//! exactly as the CLI's do) and runs it in-process through the sweep engine with the GIL
//! released; for a Dask cluster it hands out each point's plant and takes back the per-seed
//! figures the tasks computed ([`seed_figures`]), from which it makes the same report.
//! The Python side is python/rins/sweep_file.py.

use std::path::PathBuf;

use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rins_plant::PlantConfig;
use rins_sweep::result::SeedResult;
use rins_sweep::spec::Align;
use rins_sweep::{SweepPlan, SweepReport, engine};

use crate::errors::{NavigationError, SweepError};
use crate::montecarlo::{check_records, figures, from_figures};
use crate::scenario::dict_to_toml;

/// One seed's figures as they travel: `(seed, uncompensated, compensated)`, each in the order
/// of `rins.FIGURES` (the tuples `rins.end_figures` returns).
type SeedRow = (u64, [f64; 5], [f64; 5]);

/// A loaded, checked sweep file (`SweepPlan(source)`): `source` is a path (a relative base
/// scenario is taken from the file's folder, as `rins sweep` does) or a dict laid out like the
/// file (written as TOML first: error lines refer to `rins.to_toml(d)`; a relative base
/// scenario is taken from the working folder). A bad file raises `rins.SweepError` naming the
/// file, line, column and key.
#[pyclass(module = "rins", name = "SweepPlan", frozen)]
pub struct PySweepPlan {
    inner: SweepPlan,
}

fn sweep_error(e: rins_sweep::SweepError) -> PyErr {
    SweepError::new_err(e.to_string())
}

fn json(r: &SweepReport) -> PyResult<String> {
    // Pretty, as `rins sweep --json` prints it (the numbers are shortest round-trip either way).
    serde_json::to_string_pretty(r).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

fn align_of(name: &str) -> PyResult<Align> {
    match name {
        "truth" => Ok(Align::Truth),
        "self" => Ok(Align::SelfAlign),
        other => Err(PyValueError::new_err(format!(
            "alignment: expected \"truth\" or \"self\", got {other:?}"
        ))),
    }
}

#[pymethods]
impl PySweepPlan {
    #[new]
    fn py_new(source: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(d) = source.cast::<PyDict>() {
            let text = dict_to_toml(d)?;
            return SweepPlan::from_toml(&text, "dict", None)
                .map(|inner| Self { inner })
                .map_err(sweep_error);
        }
        if let Ok(p) = source.extract::<PathBuf>() {
            return SweepPlan::load(&p)
                .map(|inner| Self { inner })
                .map_err(sweep_error);
        }
        Err(PyTypeError::new_err(format!(
            "sweep: expected a sweep file path or a dict laid out like one, got {}",
            source.get_type().name()?
        )))
    }

    /// The sweep file's path (`dict` for a dict).
    #[getter]
    fn source(&self) -> &str {
        &self.inner.source
    }

    /// Seeds run at every point.
    #[getter]
    fn seeds(&self) -> Vec<u64> {
        self.inner.seeds.clone()
    }

    /// Navigation time, s.
    #[getter]
    fn duration_s(&self) -> f64 {
        self.inner.duration_s
    }

    /// Initial alignment, `"truth"` or `"self"`.
    #[getter]
    fn alignment(&self) -> &'static str {
        self.inner.alignment.name()
    }

    /// `key = value, …` of each point, in order.
    #[getter]
    fn labels(&self) -> Vec<String> {
        self.inner
            .points
            .iter()
            .map(|p| self.inner.label(p))
            .collect()
    }

    /// Runs every point × seed in-process (the sweep engine `rins sweep` runs, on every core,
    /// GIL released; Ctrl-C stops it); returns the JSON `rins sweep --json` prints.
    fn run_json(&self, py: Python<'_>) -> PyResult<String> {
        let plan = &self.inner;
        if let Some(p) = plan.points.first() {
            check_records(
                "rins.sweep_file",
                plan.seeds.len() as u128,
                "seeds",
                plan.duration_s,
                p.plant.rate_hz,
                "run fewer seeds or fewer days (sweep.seeds, sweep.days)",
            )?;
        }
        let r = crate::interrupt::run(py, |stop| rins_sweep::run(plan, &|_| stop.check()))?
            .map_err(|e| {
                NavigationError::new_err(format!("{}: running the sweep: {e}", self.inner.source))
            })?;
        json(&r)
    }

    /// Each point's plant (the base scenario's with the point's values set, alignment time
    /// prepended) as TOML text, for Dask tasks ([`sweep_seed_figures`]): the one place a plant
    /// is written as text, because it travels. Every plant a sweep can make gives the same
    /// plant back from its text, bit for bit (the test
    /// `every_sweepable_plant_survives_toml_text_bit_for_bit`), so a task computes exactly
    /// what `run_json` would.
    fn point_plants(&self) -> PyResult<Vec<String>> {
        self.inner
            .points
            .iter()
            .enumerate()
            .map(|(k, p)| {
                toml::to_string(&p.plant).map_err(|e| {
                    PyRuntimeError::new_err(format!(
                        "point {k} ({}): writing its plant as TOML: {e}",
                        self.inner.label(p)
                    ))
                })
            })
            .collect()
    }

    /// The report from each point's per-seed rows (one list per point, each in the order of
    /// `seeds`); `wall_s` is the time they took. Returns the JSON `rins sweep --json` prints.
    fn report_json(&self, per_point: Vec<Vec<SeedRow>>, wall_s: f64) -> PyResult<String> {
        let plan = &self.inner;
        if per_point.len() != plan.points.len() {
            return Err(PyValueError::new_err(format!(
                "per_point: expected {} points, got {}",
                plan.points.len(),
                per_point.len()
            )));
        }
        let mut all = Vec::with_capacity(per_point.len());
        for (k, rows) in per_point.into_iter().enumerate() {
            let seeds: Vec<u64> = rows.iter().map(|r| r.0).collect();
            if seeds != plan.seeds {
                return Err(PyValueError::new_err(format!(
                    "per_point[{k}]: expected the seeds {:?} in order, got {seeds:?}",
                    plan.seeds
                )));
            }
            all.push(
                rows.into_iter()
                    .map(|(seed, u, c)| SeedResult {
                        seed,
                        uncompensated: from_figures(u),
                        compensated: from_figures(c),
                    })
                    .collect(),
            );
        }
        json(&engine::report(plan, all, wall_s))
    }

    fn __repr__(&self) -> String {
        format!(
            "rins.SweepPlan({:?}: {} points x {} seeds, {} s)",
            self.inner.source,
            self.inner.points.len(),
            self.inner.seeds.len(),
            self.inner.duration_s
        )
    }
}

/// One Dask task of a sweep: the per-seed figures of one point's plant (TOML text from
/// `SweepPlan.point_plants()`) for `seeds`, through the sweep engine (GIL released; Ctrl-C
/// stops it). Returns `(seed, uncompensated, compensated)` tuples with the figures of
/// `rins.FIGURES`.
#[pyfunction]
pub fn sweep_seed_figures(
    py: Python<'_>,
    plant_toml: &str,
    seeds: &Bound<'_, PyAny>,
    duration_s: f64,
    alignment: &str,
) -> PyResult<Vec<SeedRow>> {
    let seeds = crate::args::seeds(seeds)?;
    let plant: PlantConfig = toml::from_str(plant_toml)
        .map_err(|e| PyValueError::new_err(format!("plant_toml: {e}")))?;
    let align = align_of(alignment)?;
    check_records(
        "sweep_seed_figures",
        seeds.len() as u128,
        "seeds",
        duration_s,
        plant.rate_hz,
        "give each task fewer seeds (seeds_per_task=)",
    )?;
    let rows = crate::interrupt::run(py, |stop| {
        engine::seed_figures(&plant, &seeds, duration_s, align, &|_| stop.check())
    })?
    .map_err(|e| NavigationError::new_err(format!("running the sweep: {e}")))?;
    Ok(rows
        .iter()
        .map(|r| (r.seed, figures(&r.uncompensated), figures(&r.compensated)))
        .collect())
}
