//! Tests of the carrier model: outputs against the plant's ship advanced directly and against
//! closed forms of the mean track, parameters reaching the ship, state round trips and refused
//! parameters.

use super::*;
use rins_fmi::instance::Instance;
use rins_plant::carrier::track::KNOT_MPS;
use rins_plant::earth::radii_of_curvature;
use rins_plant::params;

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

fn started(set: &[(&str, Value)]) -> Instance<RinsCarrier> {
    let mut inst = Instance::<RinsCarrier>::new();
    inst.setup(0.0).unwrap();
    for (n, v) in set {
        inst.set_slot(slot(n), *v).unwrap();
    }
    inst.enter_initialization().unwrap();
    inst.exit_initialization().unwrap();
    inst
}

#[test]
fn every_ship_key_is_a_parameter_and_the_defaults_round_trip() {
    let d = table::defaults();
    let n = params::flatten(&d)
        .iter()
        .filter(|p| p.path.starts_with("carrier.ship."))
        .count();
    let params = table()
        .roles
        .iter()
        .filter(|r| matches!(r, Role::Param(_)))
        .count();
    assert_eq!(
        params,
        n + 2,
        "carrier.ship.* plus run.seed and run.rate_hz"
    );
    assert_eq!(RinsCarrier::new().config().unwrap(), d);
}

/// The FMU's outputs at every communication point equal the plant's ship advanced tick by
/// tick in process, for communication steps of one and of seven ticks.
#[test]
fn outputs_are_the_ship_advanced_in_process() {
    let cfg = table::defaults();
    for ticks in [1u64, 7] {
        let mut ship = Carrier::new(&cfg.carrier, cfg.seed, 0.01).unwrap().unwrap();
        let mut inst = started(&[]);
        let mut nodes = [ship.state_now(); 2];
        let h = ticks as f64 * 0.01;
        for k in 0..50u64 {
            inst.do_step(k as f64 * h, h).unwrap();
            let mut s = ship.state_now();
            for _ in 0..ticks {
                s = ship.advance(&mut nodes);
            }
            assert_eq!(real(&inst, "carrier.lat_deg"), s.lat_rad.to_degrees());
            assert_eq!(real(&inst, "carrier.v_enu_mps[2]"), s.v_n.z);
            assert_eq!(real(&inst, "carrier.omega_nc_c_rps[1]"), s.omega_nc_c.y);
            let q = table::q_cn(&s);
            assert_eq!(real(&inst, "carrier.q_cn[3]"), q[3]);
        }
    }
}

/// Calm sea: a leg due east at 20 kn moves the longitude by v·t / ((R_N + h)·cos φ) and the
/// velocity output is (v, 0, 0); the attitude is the course (bow east: q = rotation of −90°
/// about up).
#[test]
fn a_calm_leg_east_matches_the_closed_form() {
    let mut inst = started(&[
        ("carrier.ship.sea.spectrum_code", Value::Integer(1)),
        ("carrier.ship.legs[0].heading_deg", Value::Real(90.0)),
        ("carrier.ship.legs[0].speed_kn", Value::Real(20.0)),
    ]);
    let (lat0, lon0) = (
        real(&inst, "carrier.lat_deg"),
        real(&inst, "carrier.lon_deg"),
    );
    let steps = 60_000u64; // 600 s
    for k in 0..steps {
        inst.do_step(k as f64 * 0.01, 0.01).unwrap();
    }
    let v = 20.0 * KNOT_MPS;
    assert!((real(&inst, "carrier.v_enu_mps[0]") - v).abs() < 1e-12);
    assert!(real(&inst, "carrier.v_enu_mps[1]").abs() < 1e-12);
    let (_, rn) = radii_of_curvature(lat0.to_radians());
    let dlon = (v * 600.0 / (rn * lat0.to_radians().cos())).to_degrees();
    let got = real(&inst, "carrier.lon_deg") - lon0;
    // On a parallel the course drifts off the rhumb line only by the meridian convergence
    // over 6 km (1e-4 relative).
    assert!((got - dlon).abs() < 1e-4 * dlon, "{got} vs {dlon}");
    assert!((real(&inst, "carrier.lat_deg") - lat0).abs() < 1e-9);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert!((real(&inst, "carrier.q_cn[0]") - s).abs() < 1e-12);
    assert!((real(&inst, "carrier.q_cn[3]") + s).abs() < 1e-12);
}

/// Sea state 5 moves the ship: roll, pitch and heave rates are non-zero and differ with the
/// seed; the initial outputs in initialization mode are the state at time 0.
#[test]
fn the_sea_seed_and_initial_outputs_reach_the_ship() {
    let a = started(&[]);
    let mut b = Instance::<RinsCarrier>::new();
    b.setup(0.0).unwrap();
    b.set_slot(slot("run.seed"), Value::Integer(7)).unwrap();
    b.enter_initialization().unwrap();
    let before = real(&b, "carrier.omega_nc_c_rps[1]");
    b.exit_initialization().unwrap();
    assert_eq!(before, real(&b, "carrier.omega_nc_c_rps[1]"));
    assert!(real(&a, "carrier.omega_nc_c_rps[1]").abs() > 1e-5);
    assert_ne!(real(&a, "carrier.omega_nc_c_rps[1]"), before);
}

#[test]
fn a_saved_state_continues_bit_for_bit() {
    let mut a = started(&[]);
    for k in 0..300 {
        a.do_step(k as f64 * 0.01, 0.01).unwrap();
    }
    let bytes = a.serialize();
    let mut b = Instance::<RinsCarrier>::deserialize(&bytes).unwrap();
    for k in 300..700 {
        a.do_step(k as f64 * 0.01, 0.01).unwrap();
        b.do_step(k as f64 * 0.01, 0.01).unwrap();
    }
    for o in outputs() {
        for i in 0..o.decl.count() {
            let n = o.decl.element_name(i);
            assert_eq!(real(&a, &n), real(&b, &n), "{n}");
        }
    }
    // A truncated state is refused, not half applied.
    assert!(Instance::<RinsCarrier>::deserialize(&bytes[..bytes.len() - 4]).is_err());
}

#[test]
fn out_of_range_parameters_are_refused_naming_the_range() {
    let mut inst = Instance::<RinsCarrier>::new();
    inst.setup(0.0).unwrap();
    let e = inst
        .set_slot(slot("carrier.ship.lat_deg"), Value::Real(85.0))
        .unwrap_err();
    assert!(e.message.contains("80"), "{}", e.message);
}

/// The reference results are what a fresh run gives (the CSV has 2001 rows and every output).
#[test]
fn reference_results_have_every_output_and_point() {
    let (opt, csv) = reference::reference_results().unwrap();
    assert!(opt.contains("StopTime,     20.0"));
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 2001);
    assert_eq!(lines[0].split(',').count(), 1 + 3 + 3 + 4 + 3 + 3);
    assert!(lines[2001].starts_with("20.0,"));
}

/// Issue 29: FMI 3 array names are their elements' names without the trailing index, so an
/// element view `a[i]` always belongs to the array `a`; a leg field, whose index sits inside
/// the name, is a scalar variable of its FMI 2 name (it was a scalar `legs.heading_deg`
/// described as the array of `legs[0].heading_deg`).
#[test]
fn fmi3_array_names_are_their_elements_names_without_the_index() {
    let t = &table().vars;
    let mut views = Vec::new();
    for v in &t.arrays {
        if let Some(i) = v.element_of {
            let a = &t.arrays[i];
            let k = v.slots.start - a.slots.start;
            assert_eq!(v.name, format!("{}[{k}]", a.name), "{v:?}");
            views.push(v.name.as_str());
        }
    }
    // The element views are exactly the scalars whose names end in an index `[k]`, in slot
    // order (the output vectors, `carrier.ship.sea.band[0..2]`), and no leg field.
    let indexed: Vec<&str> = t
        .scalars
        .iter()
        .map(|s| s.name.as_str())
        .filter(|n| {
            n.strip_suffix(']')
                .and_then(|m| m.rsplit_once('['))
                .is_some_and(|(_, k)| k.parse::<usize>().is_ok())
        })
        .collect();
    assert_eq!(views, indexed);
    assert!(
        views.contains(&"carrier.q_cn[3]") && views.len() >= 13,
        "{views:?}"
    );
    for field in ["heading_deg", "speed_kn", "duration_s"] {
        let name = format!("carrier.ship.legs[0].{field}");
        let v = t.arrays.iter().find(|a| a.name == name).unwrap();
        assert!(
            !v.is_array && v.element_of.is_none() && v.dims.is_empty(),
            "{v:?}"
        );
        let old = format!("carrier.ship.legs.{field}");
        assert!(t.arrays.iter().all(|a| a.name != old), "{old} is gone");
    }
    let xml = &rins_fmi::fmu::description::<RinsCarrier>(FmiVersion::V3).0;
    assert!(xml.contains("name=\"carrier.ship.legs[0].heading_deg\""));
    // (The description still names the scenario key `carrier.ship.legs.heading_deg`.)
    assert!(!xml.contains("name=\"carrier.ship.legs.heading_deg\""));
}
