//! Cost of one declared effect of degree 2 (`u_x*u_z`, a gyro bias on all three axes) per
//! output sample: the plant on a continuously rotating table (so no dwell reuses an interval
//! and the term is evaluated every sample), nav-grade-full sensors, 100 Hz, with and without
//! the term. Prints the difference in ns/sample of thread CPU time (best of interleaved repeats).

use criterion::{Criterion, Throughput};
use rins_plant::effects::custom::{Axis, CustomKind, CustomSpec};
use rins_plant::table::SchemeKind;
use rins_plant::{Plant, PlantConfig};
use std::hint::black_box;

/// This thread's CPU time, ns (Linux schedstat): on a shared, oversubscribed machine wall time
/// counts the time other processes ran; CPU time does not.
fn cpu_ns() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
}

fn config(declared: bool) -> PlantConfig {
    let mut c = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    c.scheme.kind = SchemeKind::Continuous;
    if declared {
        c.sensor.gyro.custom = vec![CustomSpec {
            name: "tilt".into(),
            enabled: true,
            kind: CustomKind::Bias,
            regressor: "u_x*u_z".into(),
            unit: "1".into(),
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef: [0.01, -0.02, 0.005],
        }];
    }
    c
}

fn run(cfg: &PlantConfig, samples: u64) -> f64 {
    let mut p = Plant::new(cfg).expect("valid");
    let mut acc = 0.0;
    for _ in 0..samples {
        let s = p.step();
        acc += s.dtheta_rad.z + s.dv_mps.x;
    }
    acc
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let n = 360_000;
    let (plain, declared) = (config(false), config(true));
    let mut g = c.benchmark_group("custom");
    g.throughput(Throughput::Elements(n));
    g.bench_function("continuous_without_declared_1h_100Hz", |b| {
        b.iter(|| black_box(run(&plain, n)))
    });
    g.bench_function("continuous_with_one_degree2_term_1h_100Hz", |b| {
        b.iter(|| black_box(run(&declared, n)))
    });
    g.finish();
    c.final_summary();
    // Interleaved repeats, best of each: the difference is the term's cost per sample.
    let mut best = [f64::INFINITY; 2];
    for _ in 0..7 {
        for (k, cfg) in [&plain, &declared].into_iter().enumerate() {
            let t0 = cpu_ns();
            black_box(run(cfg, n));
            best[k] = best[k].min((cpu_ns() - t0) / n as f64);
        }
    }
    // The term alone: the plan's evaluation per interval (fast signals and the product).
    let spec = config(true).sensor;
    let mut d = rins_plant::effects::custom::Declared::new(&spec.gyro, &spec.accel, &[25.0; 6]);
    let m = 10_000_000;
    let t0 = cpu_ns();
    let mut acc = nalgebra::Vector3::zeros();
    for k in 0..m {
        let a = k as f64 * 1e-6;
        let up = nalgebra::Vector3::new(a, 0.0, 1.0 - a);
        let dth = nalgebra::Vector3::new(1e-5, 2e-5, a * 1e-9);
        let (g, _) = d.increments(
            black_box(&up),
            &[nalgebra::Vector3::y(), nalgebra::Vector3::x()],
            &dth,
            &dth,
            0.01,
            rins_plant::table::GimbalAngles::new(0.0, a),
            a,
            rins_plant::effects::custom::MotionClocks::default(),
        );
        acc += g;
    }
    black_box(acc);
    let per = (cpu_ns() - t0) / m as f64;
    // The same loop without the call: its inputs' cost.
    let t0 = cpu_ns();
    let mut acc = nalgebra::Vector3::zeros();
    for k in 0..m {
        let a = k as f64 * 1e-6;
        let up = nalgebra::Vector3::new(a, 0.0, 1.0 - a);
        acc += black_box(&up) * 0.01 + nalgebra::Vector3::new(1e-5, 2e-5, a * 1e-9);
    }
    black_box(acc);
    let base = (cpu_ns() - t0) / m as f64;
    println!("custom: loop without the call {base:.1} ns");
    println!("custom: plan evaluation alone {per:.1} ns/interval ");
    println!(
        "custom: {:.1} ns/sample without, {:.1} with one degree-2 declared term: +{:.1} ns/sample",
        best[0],
        best[1],
        best[1] - best[0]
    );
}
