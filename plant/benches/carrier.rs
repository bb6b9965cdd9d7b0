//! Plant ns per output sample on a moving carrier against the static plant: the paper's
//! 16-position scenario at 100 Hz with every effect and the thermal network on
//! (`nav-grade-full`), over one simulated hour, on the static carrier, on a ship in calm water
//! and on a ship at sea state 5 (JONSWAP, 16 wave components). `cargo bench -p rins-plant --bench
//! carrier`.

use criterion::{Criterion, Throughput};
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};
use rins_plant::{Plant, PlantConfig};
use std::hint::black_box;

fn config(kind: CarrierKind, sea: bool) -> PlantConfig {
    let mut cfg = PlantConfig {
        sensor: rins_plant::presets::nav_grade_full(),
        ..PlantConfig::default()
    };
    cfg.carrier.kind = kind;
    cfg.carrier.ship.legs = vec![
        LegSpec {
            heading_deg: 30.0,
            speed_kn: 12.0,
            duration_s: 1800.0,
        },
        LegSpec {
            heading_deg: 120.0,
            speed_kn: 14.0,
            duration_s: 1e6,
        },
    ];
    if sea {
        cfg.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
        cfg.carrier.ship.sea.sea_state = 5;
    }
    cfg
}

fn run(cfg: &PlantConfig, samples: u64, dwell_cache: bool) -> f64 {
    let mut p = Plant::new(cfg).expect("valid");
    p.set_dwell_cache(dwell_cache);
    let mut acc = 0.0;
    for _ in 0..samples {
        let s = p.step();
        acc += s.dtheta_rad.z + s.dv_mps.x;
    }
    acc
}

/// The benchmarked cases: name, carrier, sea state 5 or calm, dwell cache.
const CASES: [(&str, CarrierKind, bool, bool); 4] = [
    ("static_1h_100Hz", CarrierKind::Static, false, true),
    (
        "static_no_dwell_cache_1h_100Hz",
        CarrierKind::Static,
        false,
        false,
    ),
    ("ship_calm_1h_100Hz", CarrierKind::Ship, false, true),
    ("ship_sea_state_5_1h_100Hz", CarrierKind::Ship, true, true),
];

fn main() {
    let hour = 360_000;
    // `RINS_BENCH_ONCE=<name>` runs that case once for an hour and exits: on a shared machine
    // `perf stat -e cycles:u` of that run gives cycles per sample, which load barely moves.
    if let Ok(name) = std::env::var("RINS_BENCH_ONCE") {
        let (_, kind, sea, cache) = CASES
            .iter()
            .find(|c| c.0 == name)
            .expect("RINS_BENCH_ONCE names a case");
        println!("{name}: {}", run(&config(*kind, *sea), hour, *cache));
        return;
    }
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let mut g = c.benchmark_group("carrier");
    g.throughput(Throughput::Elements(hour));
    // The static plant reuses whole intervals while the table dwells; a moving carrier never
    // dwells, so the static plant without that cache is the like-for-like reference.
    for (name, kind, sea, cache) in CASES {
        let cfg = config(kind, sea);
        g.bench_function(name, |b| b.iter(|| black_box(run(&cfg, hour, cache))));
    }
    g.finish();
    c.final_summary();
}
