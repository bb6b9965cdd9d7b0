//! The strapdown navigator alone, per update of one navigator: [`Strapdown`] one at a time
//! against [`StrapdownLanes`] (eight side by side, and two), on the same increments (Earth rate,
//! gravity, small noise-like wobbles), and eight updated once every 4 intervals (per interval).
//! `cargo bench -p rins-navigation --bench strapdown`.

use criterion::{Criterion, Throughput};
use nalgebra::{UnitQuaternion, Vector3};
use rins_navigation::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_navigation::strapdown_lanes::{LANES, StrapdownLanes};
use std::hint::black_box;

/// Updates per measurement and navigator.
const STEPS: u64 = 100_000;

fn navigators() -> Vec<Strapdown> {
    (0..LANES)
        .map(|k| {
            Strapdown::new(
                NavState {
                    q_bn: UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3 * k as f64),
                    v_n: Vector3::zeros(),
                    lat_rad: 0.6388,
                    lon_rad: 2.157,
                    height_m: 0.0,
                },
                0.01,
                VerticalChannel::Hold { ref_height_m: 0.0 },
            )
        })
        .collect()
}

/// Navigator `k`'s increments at step `i`.
fn increments(i: u64, k: usize) -> (Vector3<f64>, Vector3<f64>) {
    let e = ((i * 7 + k as u64 * 13) % 101) as f64 * 1e-9;
    (
        Vector3::new(e, 5.9e-7 + e, 4.3e-7 - e),
        Vector3::new(e * 100.0, -e * 50.0, 0.098 + e),
    )
}

/// `navs` in one lane group over [`STEPS`] intervals; the first one's latitude at the end.
fn lanes_run(navs: Vec<Strapdown>) -> f64 {
    let mut lanes = StrapdownLanes::new(&navs).expect("same navigators");
    let (mut dth, mut dv) = ([Vector3::zeros(); LANES], [Vector3::zeros(); LANES]);
    for i in 0..STEPS {
        for k in 0..LANES {
            (dth[k], dv[k]) = increments(i, k);
        }
        lanes.update(&dth, &dv);
    }
    lanes.state(0).lat_rad
}

fn main() {
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let mut g = c.benchmark_group("strapdown");
    g.throughput(Throughput::Elements(STEPS * LANES as u64));
    g.bench_function("one at a time (per navigator update)", |b| {
        b.iter(|| {
            let mut navs = navigators();
            for i in 0..STEPS {
                for (k, n) in navs.iter_mut().enumerate() {
                    let (a, v) = increments(i, k);
                    n.update(&a, &v);
                }
            }
            black_box(navs[0].state().lat_rad)
        })
    });
    g.bench_function("lanes of 8 (per navigator update)", |b| {
        b.iter(|| black_box(lanes_run(navigators())))
    });
    g.bench_function(
        "lanes of 8, updated every 4 intervals (per navigator interval)",
        |b| {
            b.iter(|| {
                let four = rins_navigation::Subsamples::new(4).expect("in range");
                let navs = navigators().into_iter().map(|n| n.with_subsamples(four));
                black_box(lanes_run(navs.collect()))
            })
        },
    );
    g.finish();
    // Two navigators (a seed's uncompensated and compensated pair at sea): one by one against
    // a pair of lanes.
    let mut g = c.benchmark_group("strapdown pair");
    g.throughput(Throughput::Elements(STEPS * 2));
    g.bench_function("two one at a time (per navigator update)", |b| {
        b.iter(|| {
            let mut navs = navigators();
            navs.truncate(2);
            for i in 0..STEPS {
                for (k, n) in navs.iter_mut().enumerate() {
                    let (a, v) = increments(i, k);
                    n.update(&a, &v);
                }
            }
            black_box(navs[0].state().lat_rad)
        })
    });
    g.bench_function("a pair of lanes (per navigator update)", |b| {
        b.iter(|| {
            let mut lanes = StrapdownLanes::new(&navigators()[..2]).expect("same navigators");
            let (mut dth, mut dv) = ([Vector3::zeros(); 2], [Vector3::zeros(); 2]);
            for i in 0..STEPS {
                for k in 0..2 {
                    (dth[k], dv[k]) = increments(i, k);
                }
                lanes.update(&dth, &dv);
            }
            black_box(lanes.state(0).lat_rad)
        })
    });
    g.finish();
    c.final_summary();
}
