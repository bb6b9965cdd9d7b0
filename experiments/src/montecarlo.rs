//! The Monte Carlo engine: many seeds of one case, each seed's samples feeding several
//! navigators (uncompensated and compensated, say) from one plant run. Seeds whose physics is
//! the same share it ([`rins_plant::SeedBatch`]): the motion, the temperature field and the
//! deterministic sensor errors are computed once per interval for a whole batch, the readout
//! and the navigators once per seed. The seeds are split into one batch per core.
//!
//! A seed's runs are bit-identical to [`crate::run`] of that seed alone with each navigator:
//! the samples are (the batch's guarantee) and each navigator sees them in the same order.

use rayon::prelude::*;
use rins_plant::{PlantConfig, SeedBatch};

use crate::session::{
    Alignment, NavRun, NavRunConfig, SessionError, initial_state, run, tracker_for,
};

/// Samples between progress reports of a batch.
const PROGRESS_EVERY: u64 = 1 << 16;

/// Runs `seeds` of `cfg` for `nav_s` seconds; each seed's samples feed one navigator per
/// entry of `navs`. Returns, per seed in order, one run per navigator. `progress` receives
/// samples done (summed over seeds and navigators, like separate runs would report).
/// Self-alignment steps each navigator's plant through its own alignment, so those runs are
/// made one by one ([`crate::run`]).
pub fn run_seeds(
    cfg: &PlantConfig,
    seeds: &[u64],
    nav_s: f64,
    navs: &[NavRunConfig],
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<Vec<NavRun>>, SessionError> {
    if !(nav_s > 0.0 && navs.iter().all(|n| n.record_every_s > 0.0)) {
        return Err(SessionError::BadTimes(format!(
            "navigation time {nav_s} s and record intervals must be > 0"
        )));
    }
    // The configuration is checked here, once (every plant below is built from it). Seeds
    // that share the physics: one batch per core; seeds that do not: one task per seed, so
    // the cores stay busy to the end.
    let shared = rins_plant::Plant::new(cfg)
        .map_err(|e| {
            SessionError::InvalidConfig(
                e.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join("; "),
            )
        })?
        .shares_physics_across_seeds();
    if navs
        .iter()
        .any(|n| matches!(n.alignment, Alignment::SelfAlign { .. }))
    {
        return seeds
            .par_iter()
            .map(|&seed| {
                navs.iter()
                    .map(|n| {
                        let mut p = rins_plant::Plant::new(&PlantConfig {
                            seed,
                            ..cfg.clone()
                        })
                        .expect("validated configuration");
                        let r = run(&mut p, nav_s, n);
                        progress((nav_s / p.dt_s()).round() as u64);
                        r
                    })
                    .collect()
            })
            .collect();
    }
    let lanes_per_batch = if shared {
        seeds.len().div_ceil(rayon::current_num_threads().max(1))
    } else {
        1
    };
    let batches: Vec<Vec<Vec<NavRun>>> = seeds
        .par_chunks(lanes_per_batch.max(1))
        .map(|chunk| run_batch(cfg, chunk, nav_s, navs, progress))
        .collect();
    Ok(batches.into_iter().flatten().collect())
}

/// One batch: the seeds of `chunk` stepped together, each feeding every navigator of `navs`.
fn run_batch(
    cfg: &PlantConfig,
    chunk: &[u64],
    nav_s: f64,
    navs: &[NavRunConfig],
    progress: &(dyn Fn(u64) + Sync),
) -> Vec<Vec<NavRun>> {
    let mut batch = SeedBatch::new(cfg, chunk).expect("validated configuration");
    let lanes = chunk.len();
    // The navigators start aligned from truth, which is the same for every lane when they
    // share the physics; a plant per seed starts each from its own.
    let mut trackers: Vec<Vec<_>> = (0..lanes)
        .map(|k| {
            let plant = batch.plant(k);
            let init = initial_state(plant);
            navs.iter()
                .map(|n| tracker_for(plant, init, init.height_m, n))
                .collect()
        })
        .collect();
    let dt = batch.first().dt_s();
    let samples = (nav_s / dt).round() as u64;
    let mut records: Vec<Vec<Vec<_>>> = trackers
        .iter()
        .map(|t| {
            t.iter()
                .map(|t| Vec::with_capacity((samples / t.record_interval() + 1) as usize))
                .collect()
        })
        .collect();
    let mut reported = 0;
    for k in 1..=samples {
        batch.step();
        for (lane, s) in batch.samples().iter().enumerate() {
            for (t, rec) in trackers[lane].iter_mut().zip(&mut records[lane]) {
                if let Some(r) = t.push(s, || batch.truth(lane)) {
                    rec.push(r);
                } else if k == samples {
                    rec.push(t.record(&batch.truth(lane)));
                }
            }
        }
        if k % PROGRESS_EVERY == 0 || k == samples {
            progress((k - reported) * (lanes * navs.len()) as u64);
            reported = k;
        }
    }
    trackers
        .into_iter()
        .zip(records)
        .map(|(ts, rs)| {
            ts.into_iter()
                .zip(rs)
                .map(|(t, records)| NavRun {
                    records,
                    alignment: None,
                    up_att_mean_abs_rad: t.up_att_mean_abs_rad(),
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rins_plant::Plant;
    use rins_plant::carrier::{CarrierKind, SpectrumKind};

    /// Each seed's runs through the engine equal `run` of that seed alone with each navigator,
    /// record for record, bit for bit.
    fn check(cfg: &PlantConfig, nav_s: f64) {
        let seeds = [3, 4, 9];
        let navs = [
            NavRunConfig {
                record_every_s: 20.0,
                ..NavRunConfig::default()
            },
            NavRunConfig {
                record_every_s: 30.0,
                compensation: Some(cfg.sensor.gyro.position_bias),
                ..NavRunConfig::default()
            },
        ];
        let got = run_seeds(cfg, &seeds, nav_s, &navs, &|_| {}).unwrap();
        assert_eq!(got.len(), seeds.len());
        for (seed, runs) in seeds.iter().zip(&got) {
            for (n, r) in navs.iter().zip(runs) {
                let mut p = Plant::new(&PlantConfig {
                    seed: *seed,
                    ..cfg.clone()
                })
                .unwrap();
                let alone = run(&mut p, nav_s, n).unwrap();
                assert_eq!(r.records, alone.records, "seed {seed}");
                assert_eq!(r.up_att_mean_abs_rad, alone.up_att_mean_abs_rad);
                assert!(!r.records.is_empty());
            }
        }
        // Different seeds, different errors.
        assert_ne!(got[0][0].end(), got[1][0].end());
    }

    #[test]
    fn an_invalid_configuration_is_refused_naming_the_field() {
        let mut c = rins_plant::presets::paper_16pos_config();
        c.rate_hz = -5.0;
        let e = run_seeds(&c, &[1, 2], 10.0, &[NavRunConfig::default()], &|_| {}).unwrap_err();
        assert!(matches!(e, SessionError::InvalidConfig(_)), "{e:?}");
        assert!(e.to_string().contains("rate_hz"), "{e}");
    }

    #[test]
    fn static_seeds_equal_their_runs_alone() {
        check(&rins_plant::presets::paper_16pos_config(), 400.0);
    }

    #[test]
    fn ship_seeds_equal_their_runs_alone_in_calm_water_and_at_sea() {
        let mut c = rins_plant::presets::paper_16pos_config();
        c.carrier.kind = CarrierKind::Ship;
        check(&c, 120.0);
        c.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        c.carrier.ship.sea.sea_state = 4;
        check(&c, 120.0);
    }
}
