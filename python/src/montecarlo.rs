//! Monte Carlo over seeds: the end figures `rins paper table4` reports per seed (uncompensated
//! and δβ-compensated navigation, common random numbers), for any list of seeds, and the whole
//! Table 4 study. Both reuse the Monte Carlo engine (`rins_experiments::run_seeds`, through
//! rins-verify's `paper::paired_navs`, `EndFigures::from_run`, `paper::table4`); the seeds run
//! on every core with the GIL released.

use pyo3::prelude::*;
use rins_experiments::{Alignment, NavRunConfig};
use rins_verify::paper::{EndFigures, Table4Options};

use crate::navigation::{parse_alignment, parse_subsamples};
use crate::scenario::PyScenario;
use crate::simulation::samples_of;

/// The per-seed figures, in the order `end_figures` returns them.
pub const FIGURES: [&str; 5] = [
    "lat_nm",
    "lon_nm",
    "horizontal_nm",
    "trms_nm",
    "up_att_mean_deg",
];

/// The figures of `e` in the order of [`FIGURES`].
pub fn figures(e: &EndFigures) -> [f64; 5] {
    [
        e.lat_nm,
        e.lon_nm,
        e.horizontal_nm,
        e.trms_nm,
        e.up_att_mean_deg,
    ]
}

/// [`figures`] back to the struct (a Dask task's numbers, exact: the same five `f64`).
pub fn from_figures(f: [f64; 5]) -> EndFigures {
    let [lat_nm, lon_nm, horizontal_nm, trms_nm, up_att_mean_deg] = f;
    EndFigures {
        lat_nm,
        lon_nm,
        horizontal_nm,
        trms_nm,
        up_att_mean_deg,
    }
}

/// The study options of `rins paper table4` for this scenario: self-alignment prepends its
/// time to the table's first dwell, as `--align self` does; the navigators update every
/// `subsamples` intervals, as `--subsamples` says.
fn options(
    sc: &PyScenario,
    runs: usize,
    duration_s: f64,
    alignment: Alignment,
    subsamples: i64,
) -> PyResult<Table4Options> {
    samples_of(duration_s, sc.inner.plant.rate_hz)?;
    let mut plant = sc.inner.plant.clone();
    if let Alignment::SelfAlign { coarse_s, fine_s } = alignment {
        plant.scheme.lead_dwell_s += coarse_s + fine_s;
    }
    Ok(Table4Options {
        plant,
        runs,
        duration_s,
        compensation: None,
        nav: NavRunConfig {
            alignment,
            subsamples: parse_subsamples(subsamples)?,
            ..NavRunConfig::default()
        },
    })
}

/// Per seed: `(seed, uncompensated, compensated)`, each a tuple of the figures named in
/// `rins.FIGURES` (signed latitude and longitude error, horizontal error and tRMS at the end in
/// nmi, mean |φ_U| in degrees), the numbers `rins paper table4 --json` lists under `per_seed`.
/// `duration_s` defaults to the scenario's; `alignment` is `"truth"` (default) or `"self"`;
/// `subsamples` is the IMU intervals per navigator update (1 to 4; `rins paper table4` uses 4).
#[pyfunction]
#[pyo3(signature = (scenario, seeds, duration_s = None, alignment = None, subsamples = 1))]
#[allow(clippy::type_complexity)]
pub fn end_figures(
    py: Python<'_>,
    scenario: &Bound<'_, PyAny>,
    seeds: Vec<u64>,
    duration_s: Option<f64>,
    alignment: Option<&Bound<'_, PyAny>>,
    subsamples: i64,
) -> PyResult<Vec<(u64, [f64; 5], [f64; 5])>> {
    let sc = PyScenario::resolve(scenario)?;
    let align = match alignment {
        Some(a) => parse_alignment(a)?,
        None => Alignment::Truth,
    };
    let opt = options(
        &sc,
        seeds.len(),
        duration_s.unwrap_or(sc.inner.meta.duration_s),
        align,
        subsamples,
    )?;
    rins_scenarios::runner::new_plant(&opt.plant, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    // Each seed's samples feed both navigators (the Monte Carlo engine: seeds sharing the
    // physics are read out from one plant); the figures are those of runs made one by one.
    let out = py.detach(|| {
        let navs = rins_verify::paper::paired_navs(&opt, &opt.plant);
        rins_experiments::run_seeds(&opt.plant, &seeds, opt.duration_s, &navs, &|_| {}).map(
            |runs| {
                seeds
                    .iter()
                    .zip(runs)
                    .map(|(&s, r)| {
                        (
                            s,
                            figures(&EndFigures::from_run(&r[0])),
                            figures(&EndFigures::from_run(&r[1])),
                        )
                    })
                    .collect::<Vec<_>>()
            },
        )
    });
    let out = out.map_err(|e| crate::errors::ScenarioError::new_err(e.to_string()))?;
    Ok(out)
}

/// The whole `rins paper table4` study in-process: `runs` seeds from the scenario's seed,
/// uncompensated and compensated, plus the noise-free pair, over `days`; returns the JSON text
/// `rins paper table4 --json` prints (medians, 5-95 % bands, improvements, per-seed figures),
/// its navigators updated every `subsamples` intervals (4, as the CLI's default).
#[pyfunction]
#[pyo3(signature = (scenario = None, runs = 2, days = 7.0, alignment = None, subsamples = 4))]
pub fn table4_json(
    py: Python<'_>,
    scenario: Option<&Bound<'_, PyAny>>,
    runs: usize,
    days: f64,
    alignment: Option<&Bound<'_, PyAny>>,
    subsamples: i64,
) -> PyResult<String> {
    let sc = match scenario {
        Some(s) => PyScenario::resolve(s)?,
        None => PyScenario::from_path("builtin:paper-16pos-week")?,
    };
    if runs == 0 {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "runs: expected at least 1 seed, got 0",
        ));
    }
    if !(days > 0.0 && days <= 60.0) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "days: expected a number in (0, 60], got {days}"
        )));
    }
    let align = match alignment {
        Some(a) => parse_alignment(a)?,
        None => Alignment::Truth,
    };
    let opt = options(&sc, runs, days * 86_400.0, align, subsamples)?;
    rins_scenarios::runner::new_plant(&opt.plant, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    let report = py.detach(|| rins_verify::paper::table4(&opt, &|_| {}));
    serde_json::to_string_pretty(&report)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}
