//! Monte Carlo over seeds: the end figures `rins paper table4` reports per seed (uncompensated
//! and δβ-compensated navigation, common random numbers), for any list of seeds, and the whole
//! Table 4 study. Both reuse the Monte Carlo engine (`rins_experiments::run_seeds`, through
//! rins-verification's `paper::paired_navs`, `EndFigures::from_run`, `paper::table4`); the seeds run
//! on every core with the GIL released.

use pyo3::prelude::*;
use rins_experiments::{Alignment, NavRunConfig};
use rins_verification::paper::{EndFigures, Table4Options};

use crate::navigation::parse_alignment;
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

/// Checks that the error records the Monte Carlo engine keeps fit in memory, before it runs:
/// `runs` navigation runs (members × navigators) over `duration_s` at `rate_hz`, one record every
/// `NavRunConfig`'s default interval. `MemoryError` naming the bytes otherwise.
pub fn check_records(
    call: &str,
    members: u128,
    what: &str,
    duration_s: f64,
    rate_hz: f64,
    hint: &str,
) -> PyResult<()> {
    let samples = (duration_s * rate_hz).round() as u64;
    let every = ((NavRunConfig::default().record_every_s * rate_hz).round() as u64).max(1);
    let records = u128::from(samples / every + 1);
    let per = size_of::<rins_experiments::NavRecord>() as u128;
    crate::memory::check(
        &format!("{call}: {members} {what} × 2 navigators × {records} error records × {per} bytes"),
        members * 2 * records * per,
        hint,
    )
}

/// The study options of `rins paper table4` for this scenario: self-alignment prepends its
/// time to the table's first dwell, as `--align self` does; the navigators update every
/// `subsamples` intervals, as `--subsamples` says.
fn options(
    sc: &PyScenario,
    runs: usize,
    duration_s: f64,
    alignment: Alignment,
    subsamples: rins_navigation::Subsamples,
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
            subsamples,
            ..NavRunConfig::default()
        },
    })
}

/// Per seed: `(seed, uncompensated, compensated)`, each a tuple of the figures named in
/// `rins.FIGURES` (signed latitude and longitude error, horizontal error and tRMS at the end in
/// nmi, mean |φ_U| in degrees), the numbers `rins paper table4 --json` lists under `per_seed`.
/// `duration_s` defaults to the scenario's; `alignment` is `"truth"` (default) or `"self"`;
/// `subsamples` is the IMU intervals per navigator update (1 to 4; `rins paper table4` uses 4).
/// `seeds`: whole numbers in [0, 2^64 - 1], none twice. Ctrl-C stops it.
#[pyfunction]
#[pyo3(
    signature = (scenario, seeds, duration_s = None, alignment = None, subsamples = None),
    text_signature = "(scenario, seeds, duration_s=None, alignment=None, subsamples=1)"
)]
#[allow(clippy::type_complexity)]
pub fn end_figures(
    py: Python<'_>,
    scenario: &Bound<'_, PyAny>,
    seeds: &Bound<'_, PyAny>,
    duration_s: Option<f64>,
    alignment: Option<&Bound<'_, PyAny>>,
    subsamples: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<(u64, [f64; 5], [f64; 5])>> {
    let seeds = crate::args::seeds(seeds)?;
    let subsamples = match subsamples {
        Some(n) => crate::args::subsamples(n)?,
        None => rins_navigation::Subsamples::ONE,
    };
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
    rins_scenario::new_plant(&opt.plant, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    check_records(
        "rins.montecarlo (end_figures)",
        seeds.len() as u128,
        "seeds",
        opt.duration_s,
        opt.plant.rate_hz,
        "run fewer seeds at a time (on Dask: a smaller seeds_per_task=) or a shorter duration_s=",
    )?;
    // Each seed's samples feed both navigators (the Monte Carlo engine: seeds sharing the
    // physics are read out from one plant); the figures are those of runs made one by one.
    let out = crate::interrupt::run(py, |stop| {
        let navs = rins_verification::paper::paired_navs(&opt, &opt.plant);
        let progress = |_| stop.check();
        rins_experiments::run_seeds(&opt.plant, &seeds, opt.duration_s, &navs, &progress).map(
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
    })?;
    let out = out.map_err(|e| crate::errors::ScenarioError::new_err(e.to_string()))?;
    Ok(out)
}

/// The whole `rins paper table4` study in-process: `runs` seeds from the scenario's seed,
/// uncompensated and compensated, plus the noise-free pair, over `days`; returns the JSON text
/// `rins paper table4 --json` prints (medians, 5-95 % bands, improvements, per-seed figures),
/// its navigators updated every `subsamples` intervals (4, as the CLI's default). `runs`: 1 to
/// the seeds left from the scenario's `run.seed` to 2^64 - 1. Ctrl-C stops it.
#[pyfunction]
#[pyo3(
    signature = (scenario = None, runs = None, days = 7.0, alignment = None, subsamples = None),
    text_signature = "(scenario=None, runs=2, days=7.0, alignment=None, subsamples=4)"
)]
pub fn table4_json(
    py: Python<'_>,
    scenario: Option<&Bound<'_, PyAny>>,
    runs: Option<&Bound<'_, PyAny>>,
    days: f64,
    alignment: Option<&Bound<'_, PyAny>>,
    subsamples: Option<&Bound<'_, PyAny>>,
) -> PyResult<String> {
    let subsamples = match subsamples {
        Some(n) => crate::args::subsamples(n)?,
        None => {
            rins_navigation::Subsamples::new(4).map_err(pyo3::exceptions::PyValueError::new_err)?
        }
    };
    let sc = match scenario {
        Some(s) => PyScenario::resolve(s)?,
        None => PyScenario::from_path("builtin:paper-16pos-week")?,
    };
    // The seeds are run.seed, run.seed + 1, …: the last must be a 64-bit number.
    let most = (u64::MAX - sc.inner.plant.seed).saturating_add(1);
    let runs = crate::args::whole_opt(runs, "runs", 1, most)?.unwrap_or(2);
    let runs = usize::try_from(runs).unwrap_or(usize::MAX);
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
    rins_scenario::new_plant(&opt.plant, &sc.inner.source)
        .map_err(|e| crate::errors::ScenarioError::new_err(format!("{e:#}")))?;
    // The seeds and the noise-free pair, and the first seed's series kept for the figures.
    check_records(
        "rins.table4",
        runs as u128 + 2,
        "runs",
        opt.duration_s,
        opt.plant.rate_hz,
        "run fewer runs= or fewer days=",
    )?;
    let report = crate::interrupt::run(py, |stop| {
        rins_verification::paper::table4(&opt, &|_| stop.check())
    })?;
    serde_json::to_string_pretty(&report)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}
