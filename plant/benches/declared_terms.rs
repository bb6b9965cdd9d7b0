//! Cost of declared effects per output sample and per term, for 1, 10, 100 and 1000 terms of
//! mixed signals (up direction, temperatures and their rates, gradients, `time`, north/east,
//! body rate, gimbal angles; degree 1 and 2; bias and scale factor; gyro and accelerometer),
//! and 100 terms that all read `time`.
//!
//! The plant runs on a continuously rotating table (no dwell reuses an interval: every term is
//! evaluated every sample), nav-grade-full sensors, 100 Hz. Each configuration runs
//! `SAMPLES` samples; the configurations are interleaved and repeated, and the best thread CPU
//! time of each is kept (the machine is shared: wall time counts other processes, CPU time
//! does not). The cost of the terms is the difference to the run without declared effects.
//!
//! A second measure calls `Declared::increments` alone (the fast signals and the plan) on
//! changing inputs, without the rest of the plant.
//!
//! Three cases on the default scheme (dwells) show what reading `time` costs there: a dwell
//! reuses one interval's errors unless an effect reads `time`.
//!
//! Before the timings, a hash of every output bit per case (a rewrite of the evaluation must
//! leave them unchanged).
//!
//! `cargo bench -p rins-plant --bench declared_terms` (`-- --hash-only`: the hashes alone)

use nalgebra::Vector3;
use rins_plant::effects::custom::{Axis, CustomKind, CustomSpec, Declared};
use rins_plant::table::{GimbalAngles, SchemeKind};
use rins_plant::{Plant, PlantConfig};
use std::hint::black_box;

/// Samples per timed run (1 h at 100 Hz).
const SAMPLES: u64 = 360_000;
/// Interleaved repeats (best of).
const REPEATS: usize = 7;
/// Calls per timed run of `Declared::increments` alone, times (terms + 25).
const CALLS_TERMS: u64 = 50_000_000;
/// Samples of the run whose outputs are hashed (the bit-identity check of a rewrite).
const HASHED: u64 = 36_000;

/// This thread's CPU time, ns (Linux schedstat).
fn cpu_ns() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
}

/// Regressors of the mixed set, cycled (units follow from the signals).
const MIXED: [(&str, &str); 16] = [
    ("temp:housing*u_z", "K"),
    ("temp:block", "K"),
    ("time", "s"),
    ("n_x", "1"),
    ("e_y*u_z", "1"),
    ("dtemp_dt:block", "K/s"),
    ("grad:gyro_z-housing", "K"),
    ("temp:housing^2", "K^2"),
    ("time*u_x", "s"),
    ("w_z", "deg/s"),
    ("abs_w_x*u_y", "deg/s"),
    ("n_z*e_x", "1"),
    ("gimbal_outer", "deg"),
    ("temp:board*u_y", "K"),
    ("u_y", "1"),
    ("gimbal_inner*e_z", "deg"),
];

/// Regressors that all read `time`, cycled.
const TIMED: [(&str, &str); 6] = [
    ("time", "s"),
    ("time*u_x", "s"),
    ("time^2", "s^2"),
    ("time*temp:block", "K*s"),
    ("time*n_y", "s"),
    ("time*e_z", "s"),
];

/// The mixed set without `time` (a dwell then reuses one interval).
const UNTIMED: [(&str, &str); 6] = [
    ("u_x*u_z", "1"),
    ("temp:block", "K"),
    ("n_x", "1"),
    ("dtemp_dt:block", "K/s"),
    ("temp:housing^2", "K^2"),
    ("grad:gyro_z-housing*e_y", "K"),
];

/// `n` declared effects cycling through `set`: even ones on the gyros, odd ones on the
/// accelerometers (all on the gyros when `gyro_only`); every third a scale factor;
/// coefficients on all three axes. On a continuously rotating table when `continuous`, else
/// the default scheme (dwells).
fn config(n: usize, set: &[(&str, &str)], continuous: bool, gyro_only: bool) -> PlantConfig {
    let mut c = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    if continuous {
        c.scheme.kind = SchemeKind::Continuous;
    }
    for k in 0..n {
        let (regressor, unit) = set[k % set.len()];
        let spec = CustomSpec {
            name: format!("t{k}"),
            enabled: true,
            kind: if k % 3 == 2 {
                CustomKind::ScaleFactor
            } else {
                CustomKind::Bias
            },
            regressor: regressor.into(),
            unit: unit.into(),
            axes: vec![Axis::X, Axis::Y, Axis::Z],
            coef: [1e-6, -2e-6, 5e-7].map(|c| c * (1.0 + k as f64 * 1e-3)),
        };
        if k % 2 == 0 || gyro_only {
            c.sensor.gyro.custom.push(spec);
        } else {
            c.sensor.accel.custom.push(spec);
        }
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

/// A hash of every bit of the outputs and of the declared effects' truth over `samples`.
fn hash(cfg: &PlantConfig, samples: u64) -> u64 {
    let mut p = Plant::new(cfg).expect("valid");
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for _ in 0..samples {
        let s = p.step();
        let t = p.truth();
        for v in [
            s.dtheta_rad,
            s.dv_mps,
            t.custom_gyro_rad,
            t.custom_accel_mps,
        ] {
            for x in v.iter() {
                h = (h ^ x.to_bits()).wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    h
}

/// `Declared::increments` alone, ns per call, on inputs that change every call.
fn increments_alone(cfg: &PlantConfig, calls: u64) -> f64 {
    let s = &cfg.sensor;
    let temps = [20.0, 31.0, 32.0, 33.0, 28.0, 22.0];
    let mut d = Declared::new(&s.gyro, &s.accel, &temps);
    d.thermal_update(&temps.map(|t| t + 0.01), 1.0);
    let t0 = cpu_ns();
    let mut acc = Vector3::zeros();
    for k in 0..calls {
        let a = k as f64 * 1e-7;
        let up = Vector3::new(a, 0.1, 1.0 - a);
        let ne = [Vector3::new(0.0, 1.0, a), Vector3::new(1.0, a, 0.0)];
        let dth = Vector3::new(1e-5, 2e-5, a * 1e-9);
        let (g, v) = d.increments(
            black_box(&up),
            black_box(&ne),
            &dth,
            &dth,
            0.01,
            GimbalAngles::new(a, 2.0 * a),
            a,
            rins_plant::effects::custom::MotionClocks::default(),
        );
        acc += g + v;
    }
    black_box(acc);
    (cpu_ns() - t0) / calls as f64
}

fn main() {
    // (name, terms, configuration, index of the case without terms it is compared with).
    let cases: Vec<(String, usize, PlantConfig, usize)> = [
        ("none", 0, &MIXED[..], true, 0),
        ("1 mixed", 1, &MIXED[..], true, 0),
        ("10 mixed", 10, &MIXED[..], true, 0),
        ("100 mixed", 100, &MIXED[..], true, 0),
        ("100 time", 100, &TIMED[..], true, 0),
        ("100 gyro only", 100, &MIXED[..], true, 0),
        ("1000 mixed", 1000, &MIXED[..], true, 0),
        ("dwell none", 0, &UNTIMED[..], false, 7),
        ("dwell 100 untimed", 100, &UNTIMED[..], false, 7),
        ("dwell 100 time", 100, &TIMED[..], false, 7),
    ]
    .into_iter()
    .map(|(name, n, set, cont, base)| {
        let cfg = config(n, set, cont, name.contains("gyro only"));
        (name.to_string(), n, cfg, base)
    })
    .collect();
    for (name, _, cfg, _) in &cases {
        println!(
            "declared_terms: {name:>18}: output hash {:016x}",
            hash(cfg, HASHED)
        );
    }
    if std::env::args().any(|a| a == "--hash-only") {
        return;
    }
    let mut best = vec![f64::INFINITY; cases.len()];
    let mut alone = vec![f64::INFINITY; cases.len()];
    for _ in 0..REPEATS {
        for (k, (_, n, cfg, _)) in cases.iter().enumerate() {
            let samples = SAMPLES * 100 / (*n as u64).max(100);
            let t0 = cpu_ns();
            black_box(run(cfg, samples));
            best[k] = best[k].min((cpu_ns() - t0) / samples as f64);
            alone[k] = alone[k].min(increments_alone(cfg, CALLS_TERMS / (*n as u64 + 25)));
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "declared_terms: thread CPU time, best of {REPEATS} interleaved repeats, {SAMPLES} samples at 100 Hz, continuous rotation; load average {}",
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    println!(
        "{:>18} {:>12} {:>12} {:>10} {:>15} {:>10}",
        "case", "ns/sample", "+ns/sample", "+ns/term", "increments ns", "ns/term"
    );
    for (k, (name, n, _, base)) in cases.iter().enumerate() {
        let extra = best[k] - best[*base];
        let per = |x: f64| {
            if *n == 0 {
                "-".to_string()
            } else {
                format!("{:.2}", x / *n as f64)
            }
        };
        println!(
            "{:>18} {:>12.1} {:>12.1} {:>10} {:>15.1} {:>10}",
            name,
            best[k],
            extra,
            per(extra),
            alone[k],
            per(alone[k] - alone[*base])
        );
    }
}
