//! Times the plant with groups of effects switched off, to see where per-sample time goes.
use rins_plant::{Plant, PlantConfig};
use std::time::Instant;

fn time(label: &str, cfg: &PlantConfig) {
    let n = 3_600_000u64;
    let mut p = Plant::new(cfg).unwrap();
    let t0 = Instant::now();
    let mut acc = 0.0;
    for _ in 0..n {
        acc += p.step().dtheta_rad.z;
    }
    let ns = t0.elapsed().as_secs_f64() * 1e9 / n as f64;
    println!("{label:<28} {ns:6.1} ns/sample  ({acc:.3e})");
}

fn main() {
    let full = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    time("nav-grade-full", &full);
    let mut c = full.clone();
    c.sensor.gyro.angle_random_walk.enabled = false;
    c.sensor.accel.velocity_random_walk.enabled = false;
    time("no white noise", &c);
    let mut c = full.clone();
    c.sensor.gyro.quantization.enabled = false;
    c.sensor.accel.quantization.enabled = false;
    time("no quantisation", &c);
    time("ideal sensors", &PlantConfig::default());
    let mut c = PlantConfig::default();
    c.scheme.kind = rins_plant::table::SchemeKind::Static;
    time("ideal, static table", &c);
}
