//! The reference navigator on a moving base: an ideal IMU (every error off) on a ship for 24 h
//! at sea state 5 with four heading changes, the table running the 16-position scheme, started
//! aligned from truth. Whatever error remains is the navigator's algorithm (two-sample coning
//! and sculling, first-order frame-rate and gravity/Coriolis terms at 100 Hz) plus the plant's
//! own quadrature (below 1e-13 per step, docs/carrier.md).
//!
//! Bound. The errors are the algorithm's truncation, acting like small sensor errors:
//! * coning: the sea state's roll (a ≈ 0.09 rad) and pitch (b ≈ 0.03 rad) at the spectral peak
//!   ω_p = 2π/9.7 s cone at up to ω_c = ½ω_p·a·b ≈ 9e-4 rad/s; the two-sample algorithm leaves an
//!   O((ω_p h)⁴) fraction of it, (0.0065)⁴ ≈ 1.8e-9, i.e. a drift ε ≈ 1.6e-12 rad/s, 1.4e-7 rad in
//!   24 h;
//! * that tilt moves the position by at most R·δ ≈ 0.9 m (Schuler-bounded) and the heading error
//!   by δ·(533 km sailed) ≈ 0.07 m; the sculling residual is of the same relative order and the
//!   first-order frame-rate terms err by ½(ω_in h)² < 1e-16 rad per step.
//!
//! The test asserts horizontal error < 2 m and attitude error < 5e-7 rad over the day (measured:
//! 0.14 m and 3.2e-8 rad).

use nalgebra::{Rotation3, UnitQuaternion};
use rins_nav::strapdown::{NavState, Strapdown, VerticalChannel};
use rins_plant::carrier::{CarrierKind, LegSpec, SpectrumKind};
use rins_plant::earth::radii_of_curvature;
use rins_plant::{Plant, PlantConfig};

fn ship_day() -> PlantConfig {
    let mut cfg = PlantConfig::default();
    cfg.carrier.kind = CarrierKind::Ship;
    let leg = |heading_deg: f64, speed_kn: f64| LegSpec {
        heading_deg,
        speed_kn,
        duration_s: 4.8 * 3600.0,
    };
    cfg.carrier.ship.legs = vec![
        leg(45.0, 12.0),
        leg(135.0, 14.0),
        leg(225.0, 10.0),
        leg(315.0, 12.0),
        leg(0.0, 12.0),
    ];
    cfg.carrier.ship.sea.spectrum = SpectrumKind::Jonswap;
    cfg.carrier.ship.sea.sea_state = 5;
    cfg
}

#[test]
fn ideal_imu_on_a_ship_at_sea_state_5_for_a_day() {
    let cfg = ship_day();
    let mut plant = Plant::new(&cfg).unwrap();
    let c = plant.truth().carrier;
    let start = NavState {
        q_bn: plant.attitude_q_bn(),
        v_n: c.v_n,
        lat_rad: c.lat_rad,
        lon_rad: c.lon_rad,
        height_m: c.height_m,
    };
    let hold = VerticalChannel::Hold {
        ref_height_m: cfg.carrier.ship.height_m,
    };
    let mut nav = Strapdown::new(start, plant.dt_s(), hold);
    let n = (24.0 * 3600.0 * cfg.rate_hz) as u64;
    let (mut horiz, mut att, mut roll_max) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..n {
        let s = plant.step();
        nav.update(&s.dtheta_rad, &s.dv_mps);
        if k % 100 != 99 {
            continue;
        }
        let (t, e) = (plant.truth().carrier, nav.state());
        let (rm, rn) = radii_of_curvature(t.lat_rad);
        let north = (e.lat_rad - t.lat_rad) * rm;
        let east = (e.lon_rad - t.lon_rad) * rn * t.lat_rad.cos();
        horiz = horiz.max(north.hypot(east));
        let d = e.q_bn * plant.attitude_q_bn().inverse();
        att = att.max(d.angle());
        let (r, _, _) = Rotation3::from(UnitQuaternion::from(t.q_cn)).euler_angles();
        roll_max = roll_max.max(r.abs());
    }
    println!(
        "24 h ship, sea state 5, ideal IMU: max horizontal error {horiz:.3} m, max attitude error {att:.3e} rad ({:.3} arcsec); largest roll-like angle {:.1} deg",
        att.to_degrees() * 3600.0,
        roll_max.to_degrees()
    );
    assert!(roll_max.to_degrees() > 2.0, "the sea state moved the ship");
    assert!(horiz < 2.0, "horizontal error {horiz} m");
    assert!(att < 5e-7, "attitude error {att} rad");
}
