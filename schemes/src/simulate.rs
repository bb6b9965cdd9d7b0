//! The analysis's navigation figures from the plant and the navigator themselves: a run with
//! one effect on (everything else ideal, noise off, truth alignment) through a static week,
//! its position error averaged over the last Schuler period, as the analysis averages its
//! linear model.

use rins_experiments::{NavRunConfig, run};
use rins_plant::{Plant, PlantConfig, SensorSpec};
use serde::Serialize;

use crate::scheme_file::SchemeFile;

/// A simulated navigation error.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Simulated {
    /// North error averaged over the last Schuler period, m.
    pub north_m: f64,
    /// East error, likewise, m.
    pub east_m: f64,
    /// East error at the end, nmi (the paper's longitude figure; no averaging).
    pub end_east_nmi: f64,
    /// Wall time, s.
    pub wall_s: f64,
}

/// Runs `scheme` with `sensor` (take the effect of interest alone) for `days` at `rate_hz`,
/// thermal model off, at the paper's site.
pub fn simulate(
    scheme: &SchemeFile,
    sensor: &SensorSpec,
    days: f64,
    rate_hz: f64,
) -> Result<Simulated, String> {
    let t0 = std::time::Instant::now();
    let mut cfg = PlantConfig {
        rate_hz,
        scheme: scheme.scheme.clone(),
        sensor: sensor.clone(),
        ..PlantConfig::default()
    };
    cfg.thermal.enabled = false;
    let cfg = cfg.noise_free();
    let mut plant = Plant::new(&cfg).map_err(|e| format!("{}: {e:?}", scheme.name))?;
    let rec_s = 60.0;
    let r = run(
        &mut plant,
        days * 86_400.0,
        &NavRunConfig {
            record_every_s: rec_s,
            ..NavRunConfig::default()
        },
    )
    .map_err(|e| format!("{}: {e}", scheme.name))?;
    let lat = plant.site().lat_rad;
    let (rm, rn) = rins_plant::earth::radii_of_curvature(lat);
    let g = rins_plant::earth::normal_gravity(lat, 0.0);
    let schuler_s = std::f64::consts::TAU / (g / (rm * rn).sqrt()).sqrt();
    let end = r.end().t_s;
    let window: Vec<_> = r
        .records
        .iter()
        .filter(|x| x.t_s > end - schuler_s)
        .collect();
    let n = window.len().max(1) as f64;
    Ok(Simulated {
        north_m: window.iter().map(|x| x.north_m).sum::<f64>() / n,
        east_m: window.iter().map(|x| x.east_m).sum::<f64>() / n,
        end_east_nmi: r.end().east_m / 1852.0,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
