//! Overhead of the Rerun sink on the paper's 1-week 16-position scenario at 100 Hz (60 480 000
//! samples, Table 3 sensors): the plant alone against the plant feeding a [`RunRecorder`] that
//! writes an `.rrd` at the default decimation (20 000 buckets), and the file size. Runs
//! alternate, best of `RINS_BENCH_REPS` (default 2) each. `RINS_BENCH_DAYS` shortens the run;
//! `RINS_BENCH_SKIP_NAV=1` skips the run with the reference navigator in the loop.

use std::hint::black_box;
use std::time::Instant;

use rins_plant::Plant;
use rins_rerun_sink::{Recorder, RunOptions, RunRecorder, Target, bucket};

fn plant_only(cfg: &rins_plant::PlantConfig, n: u64) -> f64 {
    let mut p = Plant::new(cfg).expect("valid preset");
    let t0 = Instant::now();
    let mut acc = 0.0;
    for _ in 0..n {
        let s = p.step();
        acc += s.dtheta_rad.z;
    }
    black_box(acc);
    t0.elapsed().as_secs_f64()
}

fn with_rerun(
    cfg: &rins_plant::PlantConfig,
    n: u64,
    path: &std::path::Path,
    navigate: bool,
) -> (f64, u64) {
    let mut p = Plant::new(cfg).expect("valid preset");
    let t0 = Instant::now();
    let rec = Recorder::open(&Target::Save(path.to_path_buf()), "bench").expect("open");
    let bucket_samples = bucket::samples_per_bucket(None, cfg.rate_hz, n);
    let tracker = navigate
        .then(|| rins_experiments::Tracker::at_truth(&p, bucket_samples as f64 / cfg.rate_hz));
    let mut r = RunRecorder::new(
        rec.stream(),
        cfg,
        &p.vehicle_to_nav(),
        RunOptions {
            bucket_samples,
            navigate,
        },
        tracker,
    )
    .expect("recorder");
    for _ in 0..n {
        let s = p.step();
        r.sample(&s, &p.truth()).expect("log");
    }
    r.finish().expect("finish");
    rins_rerun_sink::blueprint::send(
        rec.stream(),
        &rins_rerun_sink::Layout {
            plant: true,
            ..Default::default()
        },
    )
    .expect("blueprint");
    rec.finish().expect("close");
    (t0.elapsed().as_secs_f64(), r.rows())
}

fn main() {
    let days: f64 = std::env::var("RINS_BENCH_DAYS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7.0);
    let reps: usize = std::env::var("RINS_BENCH_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let cfg = rins_plant::presets::paper_16pos_config();
    let n = (days * 86_400.0 * cfg.rate_hz) as u64;
    let path = std::env::temp_dir().join(format!("rins-bench-{}.rrd", std::process::id()));
    let (mut base, mut rr, mut rows) = (f64::MAX, f64::MAX, 0);
    for _ in 0..reps.max(1) {
        base = base.min(plant_only(&cfg, n));
        let (w, r) = with_rerun(&cfg, n, &path, false);
        rr = rr.min(w);
        rows = r;
    }
    let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    println!(
        "rerun sink, {days} days at {} Hz ({n} samples), default decimation ({rows} rows per series), best of {reps}:",
        cfg.rate_hz
    );
    println!(
        "  plant alone        {base:8.2} s  {:6.1} ns/sample",
        base * 1e9 / n as f64
    );
    println!(
        "  plant + rerun sink {rr:8.2} s  {:6.1} ns/sample  overhead {:+.1} %",
        rr * 1e9 / n as f64,
        100.0 * (rr / base - 1.0)
    );
    println!(
        "  recording          {:.1} MB ({size} bytes)",
        size as f64 / 1e6
    );
    if std::env::var_os("RINS_BENCH_SKIP_NAV").is_some() {
        let _ = std::fs::remove_file(&path);
        return;
    }
    let (wn, _) = with_rerun(&cfg, n, &path, true);
    let size_nav = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    println!(
        "  with --nav (reference navigator in the loop): {wn:.2} s, {:.1} MB",
        size_nav as f64 / 1e6
    );
    let _ = std::fs::remove_file(&path);
}
