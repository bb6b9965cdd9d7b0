//! Per-doStep overhead of the FMI 2.0 binary through its C ABI against the in-process plant, for
//! a 10 ms communication step (one IMU sample at 100 Hz) of the paper's plant (the FMU default).
//! Needs `cargo build --release -p rins-imu-fmi2`.

// criterion_group! generates an undocumented function.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi_import::{Fmu2, parse_model_description};
use rins_imu_fmu::{RinsImu, library_file};
use rins_plant::Plant;

fn bench(c: &mut Criterion) {
    let exe = std::env::current_exe().unwrap();
    let so = exe
        .parent()
        .and_then(|d| d.parent())
        .unwrap()
        .join(library_file(FmiVersion::V2));
    let (guid, _, vars) =
        parse_model_description(&fmu::description::<RinsImu>(FmiVersion::V2).0).unwrap();
    let lib = Fmu2::load(&so, guid, vars)
        .unwrap_or_else(|e| panic!("{e}: build it with cargo build --release -p rins-imu-fmi2"));

    let mut g = c.benchmark_group("10ms_step");
    let mut plant = Plant::new(&rins_plant::presets::paper_16pos_config()).unwrap();
    g.bench_function("in_process_plant_step", |b| {
        b.iter(|| black_box(plant.step()))
    });

    // The same FMI state machine and model, called directly: separates the C ABI from the glue.
    let mut direct = rins_fmi::instance::Instance::<RinsImu>::new();
    direct.enter_initialization().unwrap();
    direct.exit_initialization().unwrap();
    let mut j: u64 = 0;
    g.bench_function("in_process_fmi_instance_do_step", |b| {
        b.iter(|| {
            direct.do_step(j as f64 / 100.0, 0.01).unwrap();
            j += 1;
        })
    });

    let inst = lib.instantiate("bench", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    let mut k: u64 = 0;
    g.bench_function("fmu_c_abi_do_step", |b| {
        b.iter(|| {
            inst.do_step(k as f64 / 100.0, 0.01).unwrap();
            k += 1;
        })
    });
    let outs: Vec<u32> = [
        "imu.dtheta_rad[0]",
        "imu.dtheta_rad[1]",
        "imu.dtheta_rad[2]",
        "imu.dv_mps[0]",
        "imu.dv_mps[1]",
        "imu.dv_mps[2]",
    ]
    .iter()
    .map(|n| lib.vr(n).unwrap())
    .collect();
    let mut buf = [0.0; 6];
    g.bench_function("fmu_c_abi_do_step_and_get_increments", |b| {
        b.iter(|| {
            inst.do_step(k as f64 / 100.0, 0.01).unwrap();
            inst.get_real(&outs, &mut buf).unwrap();
            k += 1;
            black_box(buf)
        })
    });
    // A 100 ms communication step (10 IMU samples): the fixed per-call cost is amortised.
    g.bench_function("in_process_plant_10_steps", |b| {
        b.iter(|| {
            for _ in 0..10 {
                black_box(plant.step());
            }
        })
    });
    g.bench_function("fmu_c_abi_do_step_100ms", |b| {
        b.iter(|| {
            inst.do_step(k as f64 / 100.0, 0.1).unwrap();
            k += 10;
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
