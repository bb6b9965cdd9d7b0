//! Cost of the truth attitude q_b^n per output sample, as the CSV and Python sinks take it
//! with `truth = true`: one simulated hour of the paper's 16-position scheme at 100 Hz (Table 3
//! sensors), the plant alone and with the truth record's q_b^n by
//!
//! - the closed form the sinks use now ([`TruthMount::q_bn_of`]),
//! - the former route, C_b^n = C_v^n·R_z·R_x then Shepperd's conversion (`quaternion_of`),
//! - nalgebra's iterative `UnitQuaternion::from_matrix` from the identity, which the Python
//!   docs once described (it stalls at half turns and costs most while a gimbal turns).
//!
//! Prints ns/sample of thread CPU time, best of interleaved repeats (a shared machine's wall
//! time counts other processes).

use nalgebra::UnitQuaternion;
use rins_plant::{Plant, PlantConfig, TruthMount};
use std::hint::black_box;

/// This thread's CPU time, ns (Linux schedstat).
fn cpu_ns() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
}

#[derive(Clone, Copy)]
enum Route {
    /// The plant's step alone (and its truth record).
    None,
    ClosedForm,
    MatrixShepperd,
    MatrixIterative,
}

fn run(cfg: &PlantConfig, samples: u64, route: Route) -> f64 {
    let mut p = Plant::new(cfg).expect("valid");
    let mount = TruthMount::of_config(cfg);
    let c_vn = cfg.vehicle.c_vn();
    let mut acc = 0.0;
    for _ in 0..samples {
        let s = p.step();
        let tr = p.truth();
        let q = match route {
            Route::None => UnitQuaternion::identity(),
            Route::ClosedForm => mount.q_bn_of(&tr),
            Route::MatrixShepperd => rins_plant::attitude::quaternion_of(
                &rins_plant::table::body_to_nav(&c_vn, tr.gimbal.angles),
            ),
            Route::MatrixIterative => UnitQuaternion::from_matrix(&rins_plant::table::body_to_nav(
                &c_vn,
                tr.gimbal.angles,
            )),
        };
        acc += s.dtheta_rad.z + tr.dv_true_mps.x + q.w + q.k;
    }
    acc
}

fn main() {
    let cfg = rins_plant::presets::paper_16pos_config();
    let n = 360_000;
    let routes = [
        ("plant step and truth record", Route::None),
        ("+ closed-form q_bn", Route::ClosedForm),
        ("+ C_b^n, Shepperd", Route::MatrixShepperd),
        ("+ C_b^n, iterative from_matrix", Route::MatrixIterative),
    ];
    let mut best = [f64::INFINITY; 4];
    for _ in 0..5 {
        for (k, (_, r)) in routes.iter().enumerate() {
            let t0 = cpu_ns();
            black_box(run(&cfg, n, *r));
            best[k] = best[k].min((cpu_ns() - t0) / n as f64);
        }
    }
    for (k, (name, _)) in routes.iter().enumerate() {
        println!(
            "truth_attitude: {name}: {:.1} ns/sample (+{:.1})",
            best[k],
            best[k] - best[0]
        );
    }
}
