//! Runs a sweep: each point's seeds through the Monte Carlo engine
//! ([`rins_experiments::run_seeds`], both cores), every seed's samples feeding the uncompensated
//! and the δβ-compensated navigator exactly as `rins paper table4` does (its navigators,
//! [`rins_verification::paper::paired_navs`], and its end figures, [`EndFigures::from_run`]).

use std::collections::BTreeMap;
use std::time::Instant;

use rins_experiments::NavRunConfig;
use rins_experiments::session::SessionError;
use rins_plant::PlantConfig;
use rins_plant::params::ParamValue;
use rins_verification::paper::{Band, EndFigures, Table4Options};

use super::result::{OutputInfo, ParameterInfo, PointResult, SeedResult, SweepReport};
use super::spec::{Align, Point, SweepPlan};

/// A swept value in the JSON: a number, a switch or a name.
pub fn json_value(v: &ParamValue) -> serde_json::Value {
    match v {
        ParamValue::Real(x) => serde_json::json!(x),
        ParamValue::Integer(u) => serde_json::json!(u),
        ParamValue::Bool(b) => serde_json::json!(b),
        ParamValue::Enum(s) => serde_json::json!(s),
    }
}

/// Each seed's end figures at `point`, in the order of `plan.seeds`. `progress` receives
/// samples done (summed over seeds and both navigators).
pub fn point_figures(
    plan: &SweepPlan,
    point: &Point,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<SeedResult>, SessionError> {
    seed_figures(
        &point.plant,
        &plan.seeds,
        plan.duration_s,
        plan.alignment,
        progress,
    )
}

/// Each seed's end figures for one point's plant (a [`Point::plant`], alignment time already
/// prepended), in the order of `seeds`. A seed's figures do not depend on the other seeds run
/// with it, so the seeds of a point may be split into batches run anywhere (the Python
/// package's Dask tasks) and give the same bits as [`point_figures`].
pub fn seed_figures(
    plant: &PlantConfig,
    seeds: &[u64],
    duration_s: f64,
    alignment: Align,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<SeedResult>, SessionError> {
    let opt = Table4Options {
        plant: plant.clone(),
        runs: seeds.len(),
        duration_s,
        compensation: None,
        nav: NavRunConfig {
            alignment: alignment.nav(),
            ..NavRunConfig::default()
        },
    };
    let navs = rins_verification::paper::paired_navs(&opt, plant);
    let runs = rins_experiments::run_seeds(plant, seeds, duration_s, &navs, progress)?;
    Ok(seeds
        .iter()
        .zip(runs)
        .map(|(&seed, r)| SeedResult {
            seed,
            uncompensated: EndFigures::from_run(&r[0]),
            compensated: EndFigures::from_run(&r[1]),
        })
        .collect())
}

/// Runs every point of `plan` in order; `progress` receives samples done.
pub fn run(plan: &SweepPlan, progress: &(dyn Fn(u64) + Sync)) -> Result<SweepReport, SessionError> {
    let t0 = Instant::now();
    let per_point = plan
        .points
        .iter()
        .map(|point| point_figures(plan, point, progress))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(report(plan, per_point, t0.elapsed().as_secs_f64()))
}

/// The report of `plan` from each point's per-seed figures (one list per entry of
/// `plan.points`, each in the order of `plan.seeds`, as [`point_figures`] returns them): the
/// medians and bands of the chosen outputs, the swept values and the file's settings.
/// `wall_s` is the time the runs took.
///
/// # Panics
/// If `per_point` does not have one list per point (a caller's mistake, not an input's).
pub fn report(plan: &SweepPlan, per_point: Vec<Vec<SeedResult>>, wall_s: f64) -> SweepReport {
    assert_eq!(
        per_point.len(),
        plan.points.len(),
        "one list of seed figures per point"
    );
    let mut points = Vec::with_capacity(plan.points.len());
    for (point, per_seed) in plan.points.iter().zip(per_point) {
        let bands = |nav: usize| -> BTreeMap<String, Band> {
            plan.outputs
                .iter()
                .map(|o| {
                    let xs: Vec<f64> = per_seed.iter().map(|s| (o.get)(s.figures(nav))).collect();
                    (o.name.to_string(), Band::of(&xs))
                })
                .collect()
        };
        points.push(PointResult {
            label: plan.label(point),
            values: point.values.iter().map(json_value).collect(),
            uncompensated: bands(0),
            compensated: bands(1),
            per_seed,
        });
    }
    SweepReport {
        name: plan.name.clone(),
        description: plan.description.clone(),
        sweep_file: plan.source.clone(),
        scenario: plan.scenario.source.clone(),
        duration_s: plan.duration_s,
        days: plan.duration_s / 86_400.0,
        alignment: plan.alignment.name().into(),
        combine: plan.combine.name().into(),
        seeds: plan.seeds.clone(),
        parameters: plan
            .parameters
            .iter()
            .map(|p| ParameterInfo {
                key: p.key.clone(),
                unit: p.unit.into(),
                values: p.values.iter().map(json_value).collect(),
            })
            .collect(),
        outputs: plan
            .outputs
            .iter()
            .map(|o| OutputInfo {
                name: o.name.into(),
                what: o.what.into(),
                unit: o.unit.into(),
            })
            .collect(),
        points,
        wall_s,
    }
}
