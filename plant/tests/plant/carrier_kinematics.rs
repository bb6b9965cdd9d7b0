//! Moving-base increments against independent closed forms: a meridian leg (transport rate,
//! Coriolis, position along the track), a steady turn (centripetal and Coriolis terms), a roll
//! oscillation under a spinning table (coning), a ship at rest against the static plant, and
//! save/restore on a ship.

use crate::carrier_common::{meridian_arc_m, quad, ship_config, with_sea_state};
use nalgebra::Vector3;
use rins_plant::carrier::{RaoSpec, ShipRaoSpec, SpectrumKind};
use rins_plant::earth::{OMEGA_IE_RPS, normal_gravity, radii_of_curvature};
use rins_plant::table::{GimbalAxis, SchemeKind};
use rins_plant::{Plant, PlantConfig};

const KN: f64 = 1852.0 / 3600.0;

#[test]
fn meridian_leg_position_transport_rate_and_coriolis() {
    let u = 12.0 * KN;
    let cfg = ship_config(&[(0.0, 12.0, 1e5)]); // 617 km north: well inside ±89°
    let mut p = Plant::new(&cfg).unwrap();
    let lat0 = cfg.carrier.ship.lat_deg.to_radians();
    let m0 = meridian_arc_m(lat0);
    // Latitude after travelling `d` metres north: invert the meridian arc by Newton steps.
    let lat_after = |d: f64| {
        let mut lat = lat0 + d / 6.36e6;
        for _ in 0..6 {
            let (rm, _) = radii_of_curvature(lat);
            lat -= (meridian_arc_m(lat) - m0 - d) / rm;
        }
        lat
    };
    let h = p.dt_s();
    let (mut worst_th, mut worst_dv) = (0.0f64, 0.0f64);
    let n = 360_000u64; // one hour
    for k in 0..n {
        let s = p.step();
        if k % 997 != 0 {
            continue;
        }
        // Body = carrier = ENU on a northbound level ship with the table at (0, 0).
        let lat = lat_after(u * (k as f64 + 0.5) * h);
        let (rm, _) = radii_of_curvature(lat);
        let w_ie = Vector3::new(0.0, OMEGA_IE_RPS * lat.cos(), OMEGA_IE_RPS * lat.sin());
        let w_en = Vector3::new(-u / rm, 0.0, 0.0);
        let dth = (w_ie + w_en) * h;
        let f = Vector3::new(
            -2.0 * OMEGA_IE_RPS * lat.sin() * u,
            0.0,
            normal_gravity(lat, 0.0) - u * u / rm,
        );
        worst_th = worst_th.max((s.dtheta_rad - dth).amax());
        worst_dv = worst_dv.max((s.dv_mps - f * h).amax());
    }
    let lat_end = lat_after(u * n as f64 * h);
    let (rm, _) = radii_of_curvature(lat_end);
    let along_m = (p.truth().carrier.lat_rad - lat_end) * rm;
    let east_m = (p.truth().carrier.lon_rad - cfg.carrier.ship.lon_deg.to_radians()) * rm;
    println!(
        "meridian leg 1 h: |dtheta err| {worst_th:.2e} rad, |dv err| {worst_dv:.2e} m/s, along-track {along_m:.2e} m, cross-track {east_m:.2e} m"
    );
    assert!(worst_th < 1e-15, "{worst_th:e}");
    assert!(worst_dv < 1e-12, "{worst_dv:e}");
    assert!(along_m.abs() < 1e-3, "{along_m} m");
    assert!(east_m.abs() < 1e-9, "{east_m} m");
    // The transport term is really there: 12 kn north is −9.7e-9 rad per step about east.
    assert!((p.truth().dtheta_true_rad.x - (-u / rm) * h).abs() < 1e-15);
}

#[test]
fn steady_turn_centripetal_and_coriolis() {
    // Starboard turn from north to south at 15 kn, peak rate 1 deg/s: the cycloidal profile
    // ψ = Δψ·(x − sin(2πx)/2π), x = (t − 10 s)/T, T = 2Δψ/r = 360 s.
    let u = 15.0 * KN;
    let cfg = ship_config(&[(0.0, 15.0, 10.0), (180.0 - 1e-9, 15.0, 1e6)]);
    let mut p = Plant::new(&cfg).unwrap();
    let h = p.dt_s();
    let r = 1f64.to_radians();
    let (mut worst_th, mut worst_dv) = (0.0f64, 0.0f64);
    let mut lat_prev = p.truth().carrier.lat_rad;
    for k in 0..37_000u64 {
        let s = p.step();
        let lat = 0.5 * (lat_prev + p.truth().carrier.lat_rad);
        lat_prev = p.truth().carrier.lat_rad;
        let t0 = k as f64 * h;
        if !(10.0 + h..369.99).contains(&t0) {
            continue;
        }
        // Closed form inside the turn; body = carrier, C_n^b = R_z(ψ).
        let (rm, rn) = radii_of_curvature(lat);
        let (sl, cl) = lat.sin_cos();
        let body = |t: f64| {
            let (tt, x) = (360.0, (t - 10.0) / 360.0);
            let pi2 = 2.0 * std::f64::consts::PI;
            let psi = std::f64::consts::PI * (x - (pi2 * x).sin() / pi2);
            let r = std::f64::consts::PI * (1.0 - (pi2 * x).cos()) / tt;
            let (sp, cp) = psi.sin_cos();
            let v = Vector3::new(u * sp, u * cp, 0.0);
            let w_ie = Vector3::new(0.0, OMEGA_IE_RPS * cl, OMEGA_IE_RPS * sl);
            let w_en = Vector3::new(-v.y / rm, v.x / rn, v.x * sl / cl / rn);
            let to_b =
                |x: Vector3<f64>| Vector3::new(cp * x.x - sp * x.y, sp * x.x + cp * x.y, x.z);
            let coriolis = (2.0 * w_ie + w_en).cross(&v);
            // Centripetal u·r to starboard (+x), gravity up; Coriolis rotated into the body.
            let f = Vector3::new(u * r, 0.0, normal_gravity(lat, 0.0)) + to_b(coriolis);
            let w = Vector3::new(0.0, 0.0, -r) + to_b(w_ie + w_en);
            (w, f)
        };
        let dth = quad(|t| body(t).0, t0, t0 + h, 4);
        let dv = quad(|t| body(t).1, t0, t0 + h, 4);
        worst_th = worst_th.max((s.dtheta_rad - dth).amax());
        worst_dv = worst_dv.max((s.dv_mps - dv).amax());
        if k == 19_000 {
            // Mid-turn the rate peaks at r: centripetal u·r to starboard.
            let centripetal = s.dv_mps.x / h;
            assert!(
                (centripetal - u * r).abs() < 2e-3,
                "{centripetal} vs {}",
                u * r
            );
        }
    }
    println!("steady turn: |dtheta err| {worst_th:.2e} rad, |dv err| {worst_dv:.2e} m/s");
    assert!(worst_th < 1e-14, "{worst_th:e}");
    assert!(worst_dv < 1e-11, "{worst_dv:e}");
}

/// One wave component driving roll only.
fn roll_only(mut cfg: PlantConfig) -> PlantConfig {
    let off = RaoSpec {
        gain: 0.0,
        natural_period_s: 0.0,
        damping: 0.1,
    };
    let sea = &mut cfg.carrier.ship.sea;
    sea.spectrum = SpectrumKind::PiersonMoskowitz;
    sea.components = 1;
    sea.hs_m = 4.0;
    sea.tp_s = 8.0;
    sea.heading_to_waves_deg = 90.0;
    sea.rao = ShipRaoSpec {
        roll: RaoSpec {
            gain: 3.0,
            natural_period_s: 0.0,
            damping: 0.1,
        },
        pitch: off,
        yaw: off,
        heave: off,
        surge: off,
        sway: off,
    };
    cfg
}

#[test]
fn roll_oscillation_under_a_spinning_table_matches_the_exact_integral() {
    // A ship at rest rolling harmonically while the outer gimbal spins at 6 deg/s: the roll axis
    // turns in body axes, the classic coning motion. Earth rate off to isolate it.
    let mut cfg = roll_only(ship_config(&[(0.0, 0.0, 1e6)]));
    cfg.earth.rotation = false;
    cfg.scheme.kind = SchemeKind::Continuous;
    cfg.scheme.axis = GimbalAxis::Outer;
    cfg.scheme.rate_dps = 6.0;
    cfg.scheme.accel_dps2 = f64::INFINITY;
    let mut p = Plant::new(&cfg).unwrap();
    let w = rins_plant::carrier::ship::Ship::new(&cfg.carrier.ship, cfg.seed, 0.01, &[]);
    let waves = w.waves().expect("one component");
    let (om, c) = (waves.omega_rps()[0], waves.coef(0)[0]);
    let eps = waves.phase_rad()[0];
    // φ(t) = Re(c·e^{i(ωt+ε)}) = |c| cos(ωt + ε + arg c).
    let (amp, ph) = (c.norm(), eps + c.arg());
    let spin = 6f64.to_radians();
    let h = p.dt_s();
    let mut worst = 0.0f64;
    let mut cone = 0.0f64;
    for k in 0..30_000u64 {
        let s = p.step();
        let t0 = k as f64 * h;
        // ω_ib^b = R_x(0)ᵀR_z(θ)ᵀ·[0, φ̇, 0] + [0, 0, spin] (carrier rate ω_nc^c = [0, φ̇, 0]).
        let rate = |t: f64| {
            let phid = -amp * om * (om * t + ph).sin();
            let th = spin * t;
            Vector3::new(th.sin() * phid, th.cos() * phid, spin)
        };
        let exact = quad(rate, t0, t0 + h, 4);
        worst = worst.max((s.dtheta_rad - exact).amax());
        cone = cone.max(s.dtheta_rad.xy().norm());
    }
    println!("roll + spin: |dtheta err| {worst:.2e} rad over steps of up to {cone:.2e} rad");
    assert!(amp > 0.02, "roll amplitude {amp} rad");
    assert!(worst < 1e-13, "{worst:e}");
}

#[test]
fn ship_at_rest_reproduces_the_static_plant() {
    // Same physics, other code path: a ship with zero speed at the site, no waves.
    let stat = PlantConfig {
        scheme: rins_plant::table::SchemeSpec::default(),
        ..PlantConfig::default()
    };
    let mut ship = ship_config(&[(0.0, 0.0, 1e6)]);
    ship.scheme = stat.scheme.clone();
    let (mut a, mut b) = (Plant::new(&stat).unwrap(), Plant::new(&ship).unwrap());
    // While the table dwells both are exact; while it turns (rate ω, acceleration α) the static
    // path takes the attitude at the midpoint, whose error the Gauss–Legendre path does not
    // have: |∫C(t)dt − C(mid)·h| ≤ (α + ω²)·h³/24 per unit vector, times g for Δv, Ω for Δθ.
    let h = a.dt_s();
    let w = stat.scheme.rate_dps.to_radians();
    let acc = stat.scheme.accel_dps2.to_radians();
    let mid_dv = (acc + w * w) * h.powi(3) / 24.0 * 9.81;
    let mid_th = (acc + w * w) * h.powi(3) / 24.0 * OMEGA_IE_RPS;
    let mut last = a.truth().gimbal.angles;
    let (mut dwell, mut turn) = ((0.0f64, 0.0f64), (0.0f64, 0.0f64));
    for _ in 0..200_000 {
        let (x, y) = (a.step(), b.step());
        let d = (
            (x.dtheta_rad - y.dtheta_rad).amax(),
            (x.dv_mps - y.dv_mps).amax(),
        );
        let still = a.truth().gimbal.angles == last && !a.truth().gimbal.moving;
        last = a.truth().gimbal.angles;
        let w = if still { &mut dwell } else { &mut turn };
        *w = (w.0.max(d.0), w.1.max(d.1));
        assert_eq!(x.encoder, y.encoder);
    }
    println!(
        "ship at rest vs static: dwell {:.2e} rad {:.2e} m/s; turning {:.2e} rad {:.2e} m/s (midpoint-rule bound {mid_th:.2e} rad {mid_dv:.2e} m/s)",
        dwell.0, dwell.1, turn.0, turn.1
    );
    assert!(dwell.0 < 1e-17 && dwell.1 < 1e-14, "{dwell:?}");
    assert!(turn.0 < 1.2 * mid_th && turn.1 < 1.2 * mid_dv, "{turn:?}");
    assert!(turn.1 > 0.1 * mid_dv, "the comparison saw no turning");
}

#[test]
fn ship_state_save_restore_is_bit_identical() {
    let cfg = with_sea_state(ship_config(&[(30.0, 12.0, 300.0), (120.0, 14.0, 1e5)]), 5);
    let mut a = Plant::new(&cfg).unwrap();
    for _ in 0..25_000 {
        a.step();
    }
    let bytes = a.serialize_state();
    let mut b = Plant::from_serialized_state(&cfg, &bytes).unwrap();
    for _ in 0..20_000 {
        let (x, y) = (a.step(), b.step());
        assert_eq!(x, y);
        assert_eq!(a.truth(), b.truth());
    }
    // Restores at, just before and just after the resynchronisation ticks of the carried sines
    // (every 64) and of the wave phasors (every 4096 = 2⁶·64): 45 056 = 704·64, 49 152 = 12·4096.
    for at in [45_002u64, 45_056, 49_151, 49_152, 49_153] {
        let mut a = Plant::new(&cfg).unwrap();
        for _ in 0..at {
            a.step();
        }
        let mut b = Plant::from_serialized_state(&cfg, &a.serialize_state()).unwrap();
        for _ in 0..130 {
            let (x, y) = (a.step(), b.step());
            assert_eq!(x, y, "restored at sample {at}");
            assert_eq!(a.truth(), b.truth(), "restored at sample {at}");
        }
    }
}

/// Meridian arc from `lat0` to `lat`, m: composite Gauss–Legendre quadrature of R_M (a second
/// method beside the plant's tick-by-tick integration; defined past the pole as well).
fn arc_m(lat0: f64, lat: f64) -> f64 {
    quad(
        |l| Vector3::new(radii_of_curvature(l).0, 0.0, 0.0),
        lat0,
        lat,
        200,
    )
    .x
}

/// The latitude `d` metres of meridian arc from `lat0` (Newton steps on [`arc_m`]).
fn lat_after_arc(lat0: f64, d: f64) -> f64 {
    let mut lat = lat0 + d / 6.36e6;
    for _ in 0..8 {
        lat -= (arc_m(lat0, lat) - d) / radii_of_curvature(lat).0;
    }
    lat
}

/// Isometric latitude on the ellipsoid, ψ(L) = atanh(sin L) − e·atanh(e·sin L): a rhumb line of
/// course χ has Δλ = tan χ·Δψ.
fn isometric(lat: f64) -> f64 {
    let e = (rins_plant::earth::WGS84_E2).sqrt();
    lat.sin().atanh() - e * (e * lat.sin()).atanh()
}

/// Issue 29, legs: a ship on one rhumb line (constant course) against the closed form, for
/// tracks that cross the antimeridian (either way) and pass within a degree of a pole. The
/// latitude is the meridian arc's (u·cos χ·t of arc), the longitude λ₀ + tan χ·(ψ(L) − ψ(L₀)) (on
/// a parallel, λ₀ + u·t/(R_N·cos L)), wrapped into [−180°, 180°]. Bound: the rounding of the
/// N additions to latitude and longitude, N·½ulp(π)·R (the integration error of the two-point
/// rule at the mid-tick radii is below 1e-10 rad here).
#[test]
fn rhumb_lines_across_the_antimeridian_and_near_the_poles_follow_the_closed_form() {
    use rins_plant::carrier::{Carrier, track::Track};
    // (name, start lat °, start lon °, course °, speed kn, duration s)
    let cases = [
        (
            "NE from 80 N to 88.6 N across 180",
            80.0,
            120.0,
            45.0,
            60.0,
            44_000.0,
        ),
        (
            "SW from 80 S to 88.6 S across -180",
            -80.0,
            -150.0,
            225.0,
            60.0,
            44_000.0,
        ),
        (
            "east along the equator across 180",
            0.0,
            179.0,
            90.0,
            30.0,
            20_000.0,
        ),
        (
            "east along 80 N across 180",
            80.0,
            150.0,
            90.0,
            60.0,
            40_000.0,
        ),
        (
            "west along 70 S across -180",
            -70.0,
            -175.0,
            270.0,
            40.0,
            20_000.0,
        ),
        ("NW from 75 N, 20 kn", 75.0, -170.0, 300.0, 20.0, 30_000.0),
    ];
    let tick = 0.1;
    for (name, lat0_deg, lon0_deg, course_deg, kn, dur) in cases {
        let cfg = ship_config(&[(course_deg, kn, dur)]);
        let mut spec = cfg.carrier.clone();
        spec.ship.lat_deg = lat0_deg;
        spec.ship.lon_deg = lon0_deg;
        let (lat0, lon0, chi, u) = (
            lat0_deg.to_radians(),
            lon0_deg.to_radians(),
            course_deg.to_radians(),
            kn * KN,
        );
        let track = Track::new(&spec.ship);
        assert!(
            track.polar_excursion(lat0, 0.0, dur).is_none(),
            "{name}: refused"
        );
        let mut c = Carrier::new(&spec, 1, tick).unwrap().unwrap();
        let mut nodes = [c.state_now(); 2];
        let n = (dur / tick) as u64;
        let (mut worst_n, mut worst_e, mut lat_max) = (0.0f64, 0.0f64, 0.0f64);
        for k in 1..=n {
            let s = c.advance(&mut nodes).truth();
            if k % 1000 != 0 && k != n {
                continue;
            }
            let t = k as f64 * tick;
            let lat = lat_after_arc(lat0, u * chi.cos() * t);
            let dlon = if chi.cos().abs() < 1e-12 {
                let (_, rn) = radii_of_curvature(lat0);
                u * chi.sin() * t / (rn * lat0.cos())
            } else {
                chi.tan() * (isometric(lat) - isometric(lat0))
            };
            let lon = lon0 + dlon;
            assert!(
                s.lon_rad.abs() <= std::f64::consts::PI,
                "{name}: {}",
                s.lon_rad
            );
            let (rm, rn) = radii_of_curvature(lat);
            let d_lon = (s.lon_rad - lon + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            worst_n = worst_n.max(((s.lat_rad - lat) * rm).abs());
            worst_e = worst_e.max((d_lon * rn * lat.cos()).abs());
            lat_max = lat_max.max(s.lat_rad.abs().to_degrees());
        }
        let bound = n as f64 * 0.5 * f64::EPSILON * std::f64::consts::PI * 6.4e6;
        println!(
            "{name}: furthest latitude {lat_max:.3} deg; error north {worst_n:.2e} m, east {worst_e:.2e} m (bound {bound:.1e} m)"
        );
        assert!(
            worst_n < bound && worst_e < bound,
            "{name}: {worst_n:e} {worst_e:e} m"
        );
        assert!(lat_max < 89.0, "{name}: {lat_max}");
    }
}

/// Issue 29, legs: a leg that would take the ship beyond ±89° is refused, naming the leg and
/// the latitude it would reach (the closed-form meridian arc: 80° N due north at 60 kn for
/// 40 000 s would end at 91.05°, past the pole); legs that stay inside are accepted.
#[test]
fn legs_beyond_89_degrees_are_refused_naming_the_leg_and_latitude() {
    use rins_plant::carrier::track::Track;
    use rins_plant::carrier::track::polar_problem;
    let u = 60.0 * KN;
    let lat80 = 80f64.to_radians();
    // Durations due north at 60 kn from 80° N to 88.99° and 89.01°.
    let to = |lat_deg: f64| arc_m(lat80, lat_deg.to_radians()) / u;
    // (name, start lat, legs, run length, refused leg and the latitude it would reach)
    type Case = (
        &'static str,
        f64,
        Vec<(f64, f64, f64)>,
        Option<(usize, f64)>,
    );
    let cases: Vec<Case> = vec![
        (
            "north past the pole",
            80.0,
            vec![(0.0, 60.0, 40_000.0)],
            Some((0, lat_after_arc(lat80, u * 40_000.0))),
        ),
        (
            "south past the pole",
            -80.0,
            vec![(180.0, 60.0, 40_000.0)],
            Some((0, -lat_after_arc(lat80, u * 40_000.0))),
        ),
        ("north to 88.99", 80.0, vec![(0.0, 60.0, to(88.99))], None),
        (
            "north to 89.01",
            80.0,
            vec![(0.0, 60.0, to(89.01))],
            Some((0, 89.01f64.to_radians())),
        ),
        (
            "east, then north on the second leg",
            80.0,
            vec![(90.0, 20.0, 3600.0), (0.0, 60.0, 40_000.0)],
            Some((1, f64::NAN)),
        ),
        (
            "east along 80 N for a day",
            80.0,
            vec![(90.0, 60.0, 86_400.0)],
            None,
        ),
    ];
    for (name, lat0, legs, want) in cases {
        let mut cfg = ship_config(&legs);
        cfg.carrier.ship.lat_deg = lat0;
        let errs = cfg.validate().err().unwrap_or_default();
        let x = Track::new(&cfg.carrier.ship).polar_excursion(
            lat0.to_radians(),
            0.0,
            legs.iter().map(|l| l.2).sum(),
        );
        match want {
            None => {
                assert!(errs.is_empty() && x.is_none(), "{name}: {errs:?}");
            }
            Some((leg, lat)) => {
                let x = x.unwrap_or_else(|| panic!("{name}: accepted"));
                assert_eq!(x.leg, leg, "{name}");
                if lat.is_finite() {
                    assert!(
                        (x.lat_deg - lat.to_degrees()).abs() < 1e-6,
                        "{name}: {} vs closed form {}",
                        x.lat_deg,
                        lat.to_degrees()
                    );
                }
                assert_eq!(errs.len(), 1, "{name}: {errs:?}");
                let e = errs[0].to_string();
                println!("{name}: {e}");
                assert!(e.starts_with(&format!("carrier.ship.legs[{leg}]:")), "{e}");
                assert!(
                    e.contains(&format!("would reach latitude {:.3}", x.lat_deg)),
                    "{e}"
                );
            }
        }
    }
    // The last leg continues to the end of the run: 10 kn north from 80° N is inside for its
    // 100 s, past 89° if the run lasts 2e5 s.
    let cfg = ship_config(&[(0.0, 10.0, 100.0)]);
    let mut ship = cfg.carrier.ship.clone();
    ship.lat_deg = 80.0;
    assert!(polar_problem(&ship, 100.0).is_none());
    let (path, _, got) = polar_problem(&ship, 2e5).expect("refused over the run");
    assert_eq!(path, "carrier.ship.legs[0]");
    assert!(
        got.contains("continued to the end of the run at 200000 s"),
        "{got}"
    );
}

/// Issue 29, sea state: at the steepest sea the validation accepts (H_s just below λ_p/7) the
/// carrier's truth quaternion keeps unit norm (within `Q_NORM_KEEP`) and is the same attitude at 100 Hz and 1000 Hz
/// (the 100 Hz run's truth against the 1000 Hz run's at the same instants: both are the
/// closed-form composition, exact or interpolated within the segment rule's 1e-10).
#[test]
fn the_steepest_accepted_sea_keeps_a_unit_quaternion_at_any_rate() {
    for tp in [2.0, 4.0, 9.0] {
        let lambda = 9.806_65 * tp * tp / (2.0 * std::f64::consts::PI);
        let mut cfg = ship_config(&[(30.0, 12.0, 20.0), (100.0, 15.0, 1e4)]);
        let sea = &mut cfg.carrier.ship.sea;
        (sea.spectrum, sea.hs_m, sea.tp_s) = (SpectrumKind::Jonswap, 0.99 * lambda / 7.0, tp);
        let mut fast_cfg = cfg.clone();
        fast_cfg.rate_hz = 1000.0;
        let (mut slow, mut fast) = (Plant::new(&cfg).unwrap(), Plant::new(&fast_cfg).unwrap());
        let (mut norm, mut diff, mut roll) = (0.0f64, 0.0f64, 0.0f64);
        for _ in 0..3000 {
            slow.step();
            for _ in 0..10 {
                fast.step();
            }
            let (a, b) = (slow.truth().carrier.q_cn, fast.truth().carrier.q_cn);
            norm = norm
                .max((a.as_ref().norm() - 1.0).abs())
                .max((b.as_ref().norm() - 1.0).abs());
            diff = diff.max(a.angle_to(&b));
            roll = roll.max(a.euler_angles().0.abs());
        }
        println!(
            "Tp {tp} s, Hs {:.3} m: largest roll {roll:.3} rad, |‖q‖ − 1| ≤ {norm:.1e}, 100 Hz vs 1000 Hz ≤ {diff:.1e} rad",
            0.99 * lambda / 7.0
        );
        assert!(roll > 1e-3, "the sea moved the ship: {roll}");
        // Kept as converted while within Q_NORM_KEEP of 1 (existing outputs keep their bits),
        // normalised beyond.
        assert!(
            norm <= rins_plant::carrier::carrier_state::Q_NORM_KEEP,
            "{norm:e}"
        );
        assert!(diff < 1e-9, "Tp {tp}: {diff:e} rad");
    }
}

/// Issue 29: a ship crossing the antimeridian at sea state 5 on the segment rule (nodes on
/// both sides of 180° in one segment) against the exact path: the same increments and the
/// same wrapped truth longitude.
#[test]
fn the_segment_rule_crosses_the_antimeridian_like_the_exact_path() {
    let mut cfg = with_sea_state(ship_config(&[(90.0, 30.0, 3600.0)]), 5);
    (cfg.carrier.ship.lat_deg, cfg.carrier.ship.lon_deg) = (0.0, 179.99);
    let mut seg = Plant::new(&cfg).unwrap();
    let mut exact = Plant::new(&cfg).unwrap();
    assert!(seg.set_carrier_segments(true).unwrap().is_some());
    exact.set_carrier_segments(false).unwrap();
    let (mut th, mut dv, mut lon) = (0.0f64, 0.0f64, 0.0f64);
    let mut crossed = false;
    for _ in 0..15_000 {
        let (a, b) = (seg.step(), exact.step());
        th = th.max((a.dtheta_rad - b.dtheta_rad).amax());
        dv = dv.max((a.dv_mps - b.dv_mps).amax());
        let (la, lb) = (seg.truth().carrier.lon_rad, exact.truth().carrier.lon_rad);
        assert!(la.abs() <= std::f64::consts::PI && lb.abs() <= std::f64::consts::PI);
        let d = (la - lb + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        lon = lon.max(d.abs());
        crossed |= la < 0.0;
    }
    println!(
        "across 180 on segments vs exact: {th:.1e} rad, {dv:.1e} m/s, longitude {lon:.1e} rad"
    );
    assert!(crossed, "the ship crossed 180°");
    assert!(th < 1e-12 && dv < 1e-11, "{th:e} {dv:e}");
    // The exact path adds a longitude step every tick, each rounding by up to ½ulp(π) near
    // 180°; the segment rule adds once per segment (as in `carrier_segment.rs`).
    let rounding = 15_000.0 * 0.5 * f64::EPSILON * std::f64::consts::PI;
    assert!(
        lon < rounding,
        "{lon:e} rad (rounding bound {rounding:.1e})"
    );
}
