//! Issue 29 at the FMU edge: sea states beyond physics and legs past the polar limit are
//! refused (at initialisation, or at the step where the last leg, continued, reaches ±89°), and
//! the longitude output wraps across the antimeridian.

use super::*;
use rins_fmi::instance::Instance;
use rins_plant::carrier::track::KNOT_MPS;
use rins_plant::earth::radii_of_curvature;

fn slot(name: &str) -> usize {
    table()
        .vars
        .slot(name)
        .unwrap_or_else(|| panic!("no variable {name}"))
}

fn real(inst: &Instance<RinsCarrier>, name: &str) -> f64 {
    match inst.get_slot(slot(name)) {
        Value::Real(x) => x,
        v => panic!("{name}: {v:?}"),
    }
}

/// An instance with `set` applied, through initialisation (the error of exiting it, if any).
fn start(set: &[(&str, Value)]) -> Result<Instance<RinsCarrier>, String> {
    let mut inst = Instance::<RinsCarrier>::new();
    inst.setup(0.0).unwrap();
    for (n, v) in set {
        inst.set_slot(slot(n), *v).map_err(|e| e.message)?;
    }
    inst.enter_initialization().unwrap();
    inst.exit_initialization().map_err(|e| e.message)?;
    Ok(inst)
}

/// A named set of parameters and the field its refusal must name (`None`: accepted).
type Case = (
    &'static str,
    Vec<(&'static str, Value)>,
    Option<&'static str>,
);

/// Sea states the plant's validation refuses are refused at initialisation naming the field
/// (they gave NaN increments with status OK before); the steepest accepted one runs.
#[test]
fn sea_states_beyond_physics_are_refused_at_initialisation() {
    let r = Value::Real;
    let cases: [Case; 4] = [
        (
            "band reversed",
            vec![
                ("carrier.ship.sea.band[0]", r(3.0)),
                ("carrier.ship.sea.band[1]", r(0.6)),
            ],
            Some("carrier.ship.sea.band"),
        ),
        (
            "band empty",
            vec![
                ("carrier.ship.sea.band[0]", r(1.0)),
                ("carrier.ship.sea.band[1]", r(1.0)),
            ],
            Some("carrier.ship.sea.band"),
        ),
        (
            "Hs 20 m at Tp 2 s",
            vec![
                ("carrier.ship.sea.sea_state", r(0.0)),
                ("carrier.ship.sea.hs_m", r(20.0)),
                ("carrier.ship.sea.tp_s", r(2.0)),
            ],
            Some("carrier.ship.sea.hs_m"),
        ),
        (
            "Hs 0.88 m at Tp 2 s (steepness 0.141)",
            vec![
                ("carrier.ship.sea.sea_state", r(0.0)),
                ("carrier.ship.sea.hs_m", r(0.88)),
                ("carrier.ship.sea.tp_s", r(2.0)),
            ],
            None,
        ),
    ];
    for (name, set, want) in cases {
        match (start(&set), want) {
            (Ok(mut inst), None) => {
                for k in 0..100 {
                    inst.do_step(k as f64 * 0.01, 0.01).unwrap();
                }
                let w = real(&inst, "carrier.omega_nc_c_rps[1]");
                assert!(w.is_finite() && w != 0.0, "{name}: {w}");
            }
            (Err(e), Some(field)) => assert!(e.contains(field), "{name}: {e}"),
            (r, _) => panic!("{name}: {:?}", r.map(|_| "accepted")),
        }
    }
}

/// A leg that reaches the pole within its duration is refused at initialisation; a last leg
/// that gets there after its end (it continues) stops the run at ±89° with an error naming
/// the leg, where the ship had reached 91.055° before.
#[test]
fn the_ship_stops_at_the_polar_limit() {
    let r = Value::Real;
    let north = |dur: f64| {
        vec![
            ("run.rate_hz", r(1.0)),
            ("carrier.ship.sea.spectrum_code", Value::Integer(1)),
            ("carrier.ship.lat_deg", r(80.0)),
            ("carrier.ship.legs[0].heading_deg", r(0.0)),
            ("carrier.ship.legs[0].speed_kn", r(60.0)),
            ("carrier.ship.legs[0].duration_s", r(dur)),
        ]
    };
    let e = start(&north(40_000.0)).map(|_| ()).unwrap_err();
    assert!(
        e.contains("carrier.ship.legs[0]") && e.contains("would reach latitude 91.055"),
        "{e}"
    );
    let mut inst = start(&north(100.0)).unwrap();
    let mut stopped = None;
    for k in 0..50 {
        if let Err(e) = inst.do_step(k as f64 * 1000.0, 1000.0) {
            stopped = Some((k, e.message));
            break;
        }
        assert!(real(&inst, "carrier.lat_deg") <= 89.0);
    }
    let (k, e) = stopped.expect("stopped");
    // 9° of meridian arc (≈ 1.005e6 m) at 30.9 m/s: the 33rd 1000 s step.
    assert_eq!(k, 32, "{e}");
    assert!(e.contains("on leg 0") && e.contains("±89"), "{e}");
}

/// Due east at 30 kn from 179.99° E on the equator: the longitude output wraps to −180° … and
/// follows the closed form v·t/R_N.
#[test]
fn the_longitude_output_wraps_across_the_antimeridian() {
    let r = Value::Real;
    let mut inst = start(&[
        ("carrier.ship.sea.spectrum_code", Value::Integer(1)),
        ("carrier.ship.lat_deg", r(0.0)),
        ("carrier.ship.lon_deg", r(179.99)),
        ("carrier.ship.legs[0].heading_deg", r(90.0)),
        ("carrier.ship.legs[0].speed_kn", r(30.0)),
    ])
    .unwrap();
    let (_, rn) = radii_of_curvature(0.0);
    for k in 0..300u64 {
        inst.do_step(k as f64 * 0.5, 0.5).unwrap();
    }
    let want = 179.99 + (30.0 * KNOT_MPS * 150.0 / rn).to_degrees() - 360.0;
    let got = real(&inst, "carrier.lon_deg");
    assert!(
        want < -179.9 && (got - want).abs() < 1e-9,
        "{got} vs {want}"
    );
}
