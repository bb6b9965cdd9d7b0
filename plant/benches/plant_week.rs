//! Plant-only throughput on the paper's 16-position scenario at 100 Hz with every effect and the
//! thermal network on (`nav-grade-full`). Criterion measures ns per output sample over one
//! simulated hour; then one full week (60 480 000 samples) is timed end to end.
//! `RINS_BENCH_SKIP_WEEK=1` skips the week.

use criterion::{Criterion, Throughput};
use rins_plant::{Plant, PlantConfig};
use std::hint::black_box;
use std::time::Instant;

fn config() -> PlantConfig {
    PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    }
}

fn run(samples: u64) -> f64 {
    let mut p = Plant::new(&config()).expect("valid");
    let mut acc = 0.0;
    for _ in 0..samples {
        let s = p.step();
        acc += s.dtheta_rad.z + s.dv_mps.x;
    }
    acc
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let hour = 360_000;
    let mut g = c.benchmark_group("plant");
    g.throughput(Throughput::Elements(hour));
    g.bench_function("16pos_nav_grade_full_1h_100Hz", |b| {
        b.iter(|| black_box(run(hour)))
    });
    g.finish();
    c.final_summary();
    if std::env::var_os("RINS_BENCH_SKIP_WEEK").is_none() {
        let week = 7 * 24 * 3600 * 100;
        let t0 = Instant::now();
        black_box(run(week));
        let wall = t0.elapsed().as_secs_f64();
        println!(
            "plant/week: {week} samples in {wall:.2} s = {:.1} ns/sample",
            wall * 1e9 / week as f64
        );
    }
}
