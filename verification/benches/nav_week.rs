//! Plant + reference navigator on the paper's 1-week, 100 Hz, 16-position scenario (Table 3
//! sensors). Criterion: ns per sample over one simulated hour. Then the whole week once (one
//! run), and the paired uncompensated/compensated week on both cores.
//! `RINS_BENCH_SKIP_WEEK=1` skips the week runs.

use criterion::{Criterion, Throughput};
use rins_experiments::{NavRunConfig, run};
use rins_plant::{Plant, PlantConfig};
use std::hint::black_box;
use std::time::Instant;

fn config() -> PlantConfig {
    PlantConfig {
        sensor: rins_plant::presets::paper_table3(),
        ..PlantConfig::default()
    }
}

fn nav(seconds: f64, compensated: bool) -> f64 {
    let cfg = config();
    let mut plant = Plant::new(&cfg).expect("valid");
    let nav = NavRunConfig {
        compensation: compensated.then_some(cfg.sensor.gyro.position_bias),
        ..NavRunConfig::default()
    };
    run(&mut plant, seconds, &nav).expect("run").end().east_m
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let mut g = c.benchmark_group("plant+nav");
    g.throughput(Throughput::Elements(360_000));
    g.bench_function("16pos_table3_1h_100Hz", |b| {
        b.iter(|| black_box(nav(3600.0, false)))
    });
    g.finish();
    c.final_summary();
    if std::env::var_os("RINS_BENCH_SKIP_WEEK").is_none() {
        let week = 7.0 * 86_400.0;
        let n = week * 100.0;
        let t0 = Instant::now();
        black_box(nav(week, false));
        let one = t0.elapsed().as_secs_f64();
        println!(
            "plant+nav/week, one run: {one:.2} s = {:.1} ns/sample",
            one * 1e9 / n
        );
        let t0 = Instant::now();
        black_box(rayon::join(|| nav(week, false), || nav(week, true)));
        let pair = t0.elapsed().as_secs_f64();
        println!("plant+nav/week, uncompensated + compensated pair on 2 cores: {pair:.2} s");
    }
}
