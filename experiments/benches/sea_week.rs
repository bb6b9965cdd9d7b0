//! Plant + reference navigator for the at-sea week (`builtin:ship-16pos-week`'s setup: the
//! paper's 16-position scheme and Table 3 sensors with the thermal network, a ship at 10-15 kn
//! with course changes every 12 h in sea state 4-5, navigator aligned from truth, errors
//! recorded every 60 s). Wall time and ns per sample, without and with azimuth isolation.
//! `cargo bench -p rins-experiments --bench sea_week` runs the whole week;
//! `SEA_WEEK_HOURS=12` runs a shorter part of it (ns/sample is the same figure).

use rins_experiments::{NavRunConfig, run};
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};
use rins_plant::{Plant, PlantConfig};

fn ship_week(isolation: bool) -> PlantConfig {
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.carrier.kind = CarrierKind::Ship;
    cfg.carrier.azimuth_isolation = isolation;
    let legs = [
        (45.0, 12.0),
        (135.0, 14.0),
        (225.0, 10.0),
        (315.0, 15.0),
        (0.0, 11.0),
        (90.0, 13.0),
        (180.0, 12.0),
        (270.0, 14.0),
        (60.0, 10.0),
        (150.0, 15.0),
        (240.0, 12.0),
        (330.0, 13.0),
        (20.0, 11.0),
        (200.0, 12.0),
    ];
    cfg.carrier.ship.legs = legs
        .iter()
        .map(|&(heading_deg, speed_kn)| LegSpec {
            heading_deg,
            speed_kn,
            duration_s: 43_200.0,
        })
        .collect();
    let sea = &mut cfg.carrier.ship.sea;
    sea.spectrum = SpectrumKind::Jonswap;
    sea.sea_state = 0;
    sea.hs_m = 2.5;
    sea.tp_s = 9.2;
    cfg
}

fn main() {
    let hours: f64 = std::env::var("SEA_WEEK_HOURS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(168.0);
    for isolation in [false, true] {
        let cfg = ship_week(isolation);
        let mut plant = Plant::new(&cfg).expect("valid");
        let t0 = std::time::Instant::now();
        let r = run(&mut plant, hours * 3600.0, &NavRunConfig::default()).expect("run");
        let wall = t0.elapsed().as_secs_f64();
        let samples = hours * 3600.0 * cfg.rate_hz;
        println!(
            "sea_week: {hours} h at 100 Hz, isolation {}: wall {wall:.1} s, {:.0} ns/sample (plant + navigator), end horizontal error {:.3} nmi",
            if isolation { "on" } else { "off" },
            wall / samples * 1e9,
            rins_navigation::errors::nmi(r.end().horizontal_m)
        );
    }
}
