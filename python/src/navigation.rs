//! `rins.navigate`: the reference navigator run on a scenario's plant (a navigation session of
//! rins-experiments: alignment, navigation, optional δβ compensation), its error records
//! returned as numpy arrays.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rins_experiments::{Alignment, NavRecord, NavRunConfig};

use crate::errors::navigation_error;
use crate::memory;
use crate::scenario::PyScenario;

/// The numbers of a record in the arrays `navigate` returns (t_s, three 3-vectors, four
/// distances).
const RECORD_ARRAYS: usize = 1 + 3 * 3 + 4;

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
/// (`rins paper table4 --subsamples`). The GIL is released while it runs; Ctrl-C stops it. The
/// records' bytes are checked first (`MemoryError` where they do not fit).
#[pyfunction]
#[pyo3(
    signature = (scenario, duration_s = None, seed = None, compensated = false, alignment = None, record_every_s = 60.0, subsamples = None),
    text_signature = "(scenario, duration_s=None, seed=None, compensated=False, alignment=None, record_every_s=60.0, subsamples=1)"
)]
#[allow(clippy::too_many_arguments)]
pub fn navigate<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    duration_s: Option<f64>,
    seed: Option<&Bound<'py, PyAny>>,
    compensated: bool,
    alignment: Option<&Bound<'py, PyAny>>,
    record_every_s: f64,
    subsamples: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let seed = crate::args::seed(seed)?;
    let subsamples = match subsamples {
        Some(n) => crate::args::subsamples(n)?,
        None => rins_navigation::Subsamples::ONE,
    };
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
        subsamples,
        ..NavRunConfig::default()
    };
    let mut plant = rins_scenario::new_plant(&cfg, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    // The records the session keeps (as it counts them), then the arrays made from them.
    let samples = (nav_s / plant.dt_s()).round() as u64;
    let every = ((record_every_s / plant.dt_s()).round() as u64).max(1);
    let records = u128::from(samples / every + 1);
    let per = (size_of::<NavRecord>() + RECORD_ARRAYS * size_of::<f64>()) as u128;
    let what = format!("rins.navigate: {records} error records × {per} bytes");
    let hint = "record less often (record_every_s=) or navigate a shorter span (duration_s=)";
    if record_every_s > 0.0 {
        // (Else the session refuses the interval, below.)
        memory::check(&what, records * per, hint)?;
    }
    let out = crate::interrupt::run(py, |stop| {
        rins_experiments::session::run_with_progress(&mut plant, nav_s, &nav, &|_| stop.check())
    })?
    .map_err(navigation_error)?;
    let n = out.records.len();
    let need = n as u128 * per;
    let values = |k: usize| memory::vec::<f64>((n * k) as u128, &what, need, hint);
    let col = |f: &dyn Fn(&NavRecord) -> f64| -> PyResult<_> {
        let mut v = values(1)?;
        v.extend(out.records.iter().map(f));
        Ok(PyArray1::from_vec(py, v))
    };
    let mat = |f: &dyn Fn(&NavRecord) -> [f64; 3]| -> PyResult<_> {
        let mut v = values(3)?;
        v.extend(out.records.iter().flat_map(f));
        Ok(Array2::from_shape_vec((n, 3), v)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?
            .into_pyarray(py))
    };
    let d = PyDict::new(py);
    d.set_item("t_s", col(&|r| r.t_s)?)?;
    d.set_item("att_err_rad", mat(&|r| r.att_err_rad)?)?;
    d.set_item("vehicle_att_err_rad", mat(&|r| r.vehicle_att_err_rad)?)?;
    d.set_item("vel_err_mps", mat(&|r| r.vel_err_mps)?)?;
    d.set_item("north_m", col(&|r| r.north_m)?)?;
    d.set_item("east_m", col(&|r| r.east_m)?)?;
    d.set_item("horizontal_m", col(&|r| r.horizontal_m)?)?;
    d.set_item("trms_m", col(&|r| r.trms_m)?)?;
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
