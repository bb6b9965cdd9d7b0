//! The Monte Carlo engine against its floor, one thread, Table 3 sensors on the paper's
//! 16-position scenario, 100 Hz, one simulated hour per measurement (criterion: time per
//! sample and seed):
//!
//! - `naive`: the floor any engine must beat: a bare loop that makes biased, noisy increments
//!   (constant rate and specific force, bias, white noise from ChaCha8 normals) and integrates
//!   them with the reference strapdown navigator. One navigator.
//! - `plant+1nav`: one seed through the plant and one navigator ([`rins_experiments::run`]).
//! - `engine 1 seed, 2 navs`: one seed, its samples feeding the uncompensated and compensated
//!   navigators ([`rins_experiments::run_seeds`]).
//! - `engine 16 seeds, 2 navs`: sixteen seeds sharing the physics, two navigators each
//!   (per sample and seed).
//! - `isolated ship`: the at-sea study's hardest case, a ship in a sea state 4–5 sea (one sea
//!   for every seed) with azimuth isolation: eight seeds and the noise-free member, two
//!   navigators each, the seeds' tables turned from one reference table (per sample and
//!   member); and, beside it, one seed's plant alone with one navigator.

use criterion::{Criterion, Throughput};
use nalgebra::{UnitQuaternion, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rins_experiments::{NavRunConfig, run, run_seeds};
use rins_navigation::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_plant::Plant;
use std::hint::black_box;

const HOUR_S: f64 = 3600.0;

/// The at-sea study's ship (`ship-16pos-week`'s sea and first legs) with azimuth isolation and
/// one sea for every seed.
fn isolated_ship() -> rins_plant::PlantConfig {
    use rins_plant::carrier::{CarrierKind, LegSpec, SeaRealisation, SpectrumKind};
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.carrier.kind = CarrierKind::Ship;
    cfg.carrier.azimuth_isolation = true;
    cfg.carrier.ship.legs = [(45.0, 12.0), (135.0, 14.0)]
        .map(|(heading_deg, speed_kn)| LegSpec {
            heading_deg,
            speed_kn,
            duration_s: 43_200.0,
        })
        .to_vec();
    let sea = &mut cfg.carrier.ship.sea;
    sea.spectrum = SpectrumKind::Jonswap;
    sea.sea_state = 0;
    sea.hs_m = 2.5;
    sea.tp_s = 9.2;
    sea.realisation = SeaRealisation::Fixed;
    sea.seed = 1;
    cfg
}

const RATE_HZ: f64 = 100.0;

/// The naive loop for `samples` samples; returns the final longitude (kept alive).
fn naive(samples: u64) -> f64 {
    let dt = 1.0 / RATE_HZ;
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let lat = 36.6f64.to_radians();
    let w_ie = 7.292_115e-5;
    let (bias_rps, arw, vrw) = (0.003f64.to_radians() / 3600.0, 1e-6, 2e-5);
    let mut nav = Strapdown::new(
        NavState {
            q_bn: UnitQuaternion::identity(),
            v_n: Vector3::zeros(),
            lat_rad: lat,
            lon_rad: 2.157,
            height_m: 0.0,
        },
        dt,
        VerticalChannel::Hold { ref_height_m: 0.0 },
    );
    let omega = Vector3::new(0.0, w_ie * lat.cos(), w_ie * lat.sin());
    let f = Vector3::new(0.0, 0.0, 9.8);
    let sqrt_dt = dt.sqrt();
    let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
    for _ in 0..samples {
        let dtheta = (omega + Vector3::repeat(bias_rps)) * dt
            + Vector3::new(n(), n(), n()) * (arw * sqrt_dt);
        let dv = f * dt + Vector3::new(n(), n(), n()) * (vrw * sqrt_dt);
        nav.update(&dtheta, &dv);
    }
    nav.state().lon_rad
}

/// This thread's CPU time, ns (Linux schedstat): on a shared machine wall time counts the time
/// other processes ran; CPU time does not.
fn cpu_ns() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
}

fn main() {
    let cfg = rins_plant::presets::paper_16pos_config();
    let samples = (HOUR_S * RATE_HZ) as u64;
    let navs = [
        NavRunConfig::default(),
        NavRunConfig {
            compensation: Some(cfg.sensor.gyro.position_bias),
            ..NavRunConfig::default()
        },
    ];
    // One thread: the figures are per core.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let mut g = c.benchmark_group("montecarlo");
    g.throughput(Throughput::Elements(samples));
    g.bench_function("naive", |b| b.iter(|| black_box(naive(samples))));
    g.bench_function("plant+1nav", |b| {
        b.iter(|| {
            let mut p = Plant::new(&cfg).expect("valid");
            black_box(run(&mut p, HOUR_S, &navs[0]).expect("run").end())
        })
    });
    g.bench_function("engine 1 seed, 2 navs", |b| {
        b.iter(|| {
            pool.install(|| black_box(run_seeds(&cfg, &[1], HOUR_S, &navs, &|_| {}).expect("run")))
        })
    });
    let seeds: Vec<u64> = (1..=16).collect();
    g.throughput(Throughput::Elements(samples * seeds.len() as u64));
    g.bench_function("engine 16 seeds, 2 navs (per seed)", |b| {
        b.iter(|| {
            pool.install(|| {
                black_box(run_seeds(&cfg, &seeds, HOUR_S, &navs, &|_| {}).expect("run"))
            })
        })
    });
    // Table 4's navigators as the paper study runs them: updated every 4 intervals.
    let navs4 = navs.clone().map(|n| NavRunConfig {
        subsamples: rins_navigation::Subsamples::new(4).expect("in range"),
        ..n
    });
    g.bench_function(
        "engine 16 seeds, 2 navs every 4 intervals (per seed)",
        |b| {
            b.iter(|| {
                pool.install(|| {
                    black_box(run_seeds(&cfg, &seeds, HOUR_S, &navs4, &|_| {}).expect("run"))
                })
            })
        },
    );
    let ship = isolated_ship();
    let members: Vec<rins_plant::PlantConfig> = (1..=8)
        .map(|k| ship.with_seed(k))
        .chain(std::iter::once(ship.noise_free()))
        .collect();
    let ship_navs = [
        NavRunConfig::default(),
        NavRunConfig {
            compensation: Some(ship.sensor.gyro.position_bias),
            ..NavRunConfig::default()
        },
    ];
    g.throughput(Throughput::Elements(samples * members.len() as u64));
    g.bench_function(
        "isolated ship, 8 seeds + noise-free, 2 navs (per member)",
        |b| {
            b.iter(|| {
                pool.install(|| {
                    black_box(
                        rins_experiments::run_members(&members, HOUR_S, &ship_navs, &|_| {})
                            .expect("run"),
                    )
                })
            })
        },
    );
    g.finish();
    c.final_summary();
    // Thread CPU time per sample and seed, best of 3 interleaved repeats (robust to load).
    // (name, seeds, one run of the case).
    type Case<'a> = (&'a str, u64, Box<dyn Fn() + Sync + 'a>);
    let cases: [Case; 7] = [
        (
            "naive (1 navigator)",
            1,
            Box::new(|| {
                black_box(naive(samples));
            }),
        ),
        (
            "plant + 1 navigator",
            1,
            Box::new(|| {
                let mut p = Plant::new(&cfg).expect("valid");
                black_box(run(&mut p, HOUR_S, &navs[0]).expect("run").end());
            }),
        ),
        (
            "engine, 1 seed x 2 navigators",
            1,
            Box::new(|| {
                black_box(run_seeds(&cfg, &[1], HOUR_S, &navs, &|_| {}).expect("run"));
            }),
        ),
        (
            "engine, 16 seeds x 2 navigators",
            16,
            Box::new(|| {
                black_box(run_seeds(&cfg, &seeds, HOUR_S, &navs, &|_| {}).expect("run"));
            }),
        ),
        (
            "engine, 16 seeds x 2 navigators updated every 4 intervals (the paper study's)",
            16,
            Box::new(|| {
                black_box(run_seeds(&cfg, &seeds, HOUR_S, &navs4, &|_| {}).expect("run"));
            }),
        ),
        (
            "engine, isolated ship, 8 seeds + noise-free x 2 navigators (one reference table)",
            members.len() as u64,
            Box::new(|| {
                black_box(
                    rins_experiments::run_members(&members, HOUR_S, &ship_navs, &|_| {})
                        .expect("run"),
                );
            }),
        ),
        (
            "isolated ship, plant + 1 navigator",
            1,
            Box::new(|| {
                let mut p = Plant::new(&members[0]).expect("valid");
                black_box(run(&mut p, HOUR_S, &ship_navs[0]).expect("run").end());
            }),
        ),
    ];
    let mut best = [f64::INFINITY; 7];
    for _ in 0..3 {
        for (k, (_, _, f)) in cases.iter().enumerate() {
            let ns = pool.install(|| {
                let t0 = cpu_ns();
                f();
                cpu_ns() - t0
            });
            best[k] = best[k].min(ns);
        }
    }
    for (k, (name, lanes, _)) in cases.iter().enumerate() {
        println!(
            "{name}: {:.1} ns per sample and seed (thread CPU time, best of 3)",
            best[k] / (samples * lanes) as f64
        );
    }
}
