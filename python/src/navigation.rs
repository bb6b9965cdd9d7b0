//! `rins.navigate`: the reference navigator run on a scenario's plant (a navigation session of
//! rins-experiments: alignment, navigation, optional δβ compensation), its error records
//! returned as numpy arrays.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rins_experiments::{Alignment, NavRunConfig};

use crate::errors::navigation_error;
use crate::scenario::PyScenario;

/// Parses `alignment`: `"truth"`, or `"self"` (300 s coarse + 600 s fine, as `rins paper
/// table4 --align self`), or a tuple `("self", coarse_s, fine_s)`.
pub fn parse_alignment(a: &Bound<'_, PyAny>) -> PyResult<Alignment> {
    if let Ok(s) = a.extract::<String>() {
        return match s.as_str() {
            "truth" => Ok(Alignment::Truth),
            "self" => Ok(Alignment::SelfAlign {
                coarse_s: 300.0,
                fine_s: 600.0,
            }),
            _ => Err(PyValueError::new_err(format!(
                "alignment: expected 'truth', 'self' or ('self', coarse_s, fine_s), got {s:?}"
            ))),
        };
    }
    if let Ok((s, coarse_s, fine_s)) = a.extract::<(String, f64, f64)>()
        && s == "self"
    {
        return Ok(Alignment::SelfAlign { coarse_s, fine_s });
    }
    Err(PyValueError::new_err(format!(
        "alignment: expected 'truth', 'self' or ('self', coarse_s, fine_s), got {}",
        a.repr()?
    )))
}

/// Runs the reference navigator on `scenario` for `duration_s` of navigation (default: the
/// scenario's duration) and returns its error records every `record_every_s` as numpy arrays:
/// `t_s`, `att_err_rad` (E, N, U), `vehicle_att_err_rad`, `vel_err_mps`, `north_m`, `east_m`,
/// `horizontal_m`, `trms_m`, plus `up_att_mean_abs_rad` and, when self-aligned, `alignment`.
/// `compensated=True` subtracts the plant's own δβ in the navigation computer (Table 4's
/// compensated case). `subsamples` (1 to 4) is the number of IMU intervals per navigator update
/// (`rins paper table4 --subsamples`). The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (scenario, duration_s = None, seed = None, compensated = false, alignment = None, record_every_s = 60.0, subsamples = 1))]
pub fn navigate<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    duration_s: Option<f64>,
    seed: Option<u64>,
    compensated: bool,
    alignment: Option<&Bound<'py, PyAny>>,
    record_every_s: f64,
    subsamples: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let sc = PyScenario::resolve(scenario)?;
    let mut cfg = sc.inner.plant.clone();
    if let Some(s) = seed {
        cfg.seed = s;
    }
    let nav_s = duration_s.unwrap_or(sc.inner.meta.duration_s);
    crate::simulation::samples_of(nav_s, cfg.rate_hz)?;
    let nav = NavRunConfig {
        alignment: match alignment {
            Some(a) => parse_alignment(a)?,
            None => Alignment::Truth,
        },
        compensation: compensated.then_some(cfg.sensor.gyro.position_bias),
        record_every_s,
        subsamples: parse_subsamples(subsamples)?,
        ..NavRunConfig::default()
    };
    let mut plant = rins_scenarios::runner::new_plant(&cfg, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    let out = py
        .detach(|| rins_experiments::run(&mut plant, nav_s, &nav))
        .map_err(navigation_error)?;
    let n = out.records.len();
    let col = |f: &dyn Fn(&rins_experiments::NavRecord) -> f64| {
        PyArray1::from_vec(py, out.records.iter().map(f).collect())
    };
    let mat = |f: &dyn Fn(&rins_experiments::NavRecord) -> [f64; 3]| -> PyResult<_> {
        let v: Vec<f64> = out.records.iter().flat_map(f).collect();
        Ok(Array2::from_shape_vec((n, 3), v)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?
            .into_pyarray(py))
    };
    let d = PyDict::new(py);
    d.set_item("t_s", col(&|r| r.t_s))?;
    d.set_item("att_err_rad", mat(&|r| r.att_err_rad)?)?;
    d.set_item("vehicle_att_err_rad", mat(&|r| r.vehicle_att_err_rad)?)?;
    d.set_item("vel_err_mps", mat(&|r| r.vel_err_mps)?)?;
    d.set_item("north_m", col(&|r| r.north_m))?;
    d.set_item("east_m", col(&|r| r.east_m))?;
    d.set_item("horizontal_m", col(&|r| r.horizontal_m))?;
    d.set_item("trms_m", col(&|r| r.trms_m))?;
    d.set_item("up_att_mean_abs_rad", out.up_att_mean_abs_rad)?;
    if let Some(a) = out.alignment {
        let ad = PyDict::new(py);
        ad.set_item("coarse_err_rad", a.coarse_err_rad.to_vec())?;
        ad.set_item("fine_err_rad", a.fine_err_rad.to_vec())?;
        ad.set_item("fine_sigma_rad", a.fine_sigma_rad.to_vec())?;
        d.set_item("alignment", ad)?;
    }
    Ok(d)
}

/// `subsamples`: IMU intervals per navigator update, or a ValueError naming the range.
pub(crate) fn parse_subsamples(n: i64) -> PyResult<rins_nav::Subsamples> {
    u8::try_from(n)
        .map_err(|_| format!("subsamples {n}: the navigator updates every 1 to 4 IMU intervals"))
        .and_then(rins_nav::Subsamples::new)
        .map_err(pyo3::exceptions::PyValueError::new_err)
}
