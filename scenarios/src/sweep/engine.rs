//! Runs a sweep: each point's seeds through the Monte Carlo engine
//! ([`rins_experiments::run_seeds`], both cores), every seed's samples feeding the uncompensated
//! and the δβ-compensated navigator exactly as `rins paper table4` does (its navigators,
//! [`rins_verify::paper::paired_navs`], and its end figures, [`EndFigures::from_run`]).

use std::collections::BTreeMap;
use std::time::Instant;

use rins_experiments::NavRunConfig;
use rins_experiments::session::SessionError;
use rins_plant::params::ParamValue;
use rins_verify::paper::{Band, EndFigures, Table4Options};

use super::result::{OutputInfo, ParameterInfo, PointResult, SeedResult, SweepReport};
use super::spec::{Point, SweepPlan};

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
    let opt = Table4Options {
        plant: point.plant.clone(),
        runs: plan.seeds.len(),
        duration_s: plan.duration_s,
        compensation: None,
        nav: NavRunConfig {
            alignment: plan.alignment.nav(),
            ..NavRunConfig::default()
        },
    };
    let navs = rins_verify::paper::paired_navs(&opt, &point.plant);
    let runs =
        rins_experiments::run_seeds(&point.plant, &plan.seeds, plan.duration_s, &navs, progress)?;
    Ok(plan
        .seeds
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
    let mut points = Vec::with_capacity(plan.points.len());
    for point in &plan.points {
        let per_seed = point_figures(plan, point, progress)?;
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
    Ok(SweepReport {
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
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
