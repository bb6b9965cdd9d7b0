//! What the IMU FMU outputs before its first step, through the generic FMI state machine in
//! process (the one both binaries wrap; `master_fixes` reads the same through the FMI 2 and
//! FMI 3 binaries): in initialization mode, after the parameters are set, the unit's readings
//! (temperature sensors, encoders) are those of the initial state and the true attitude is the
//! plant's, bit for bit; and while stepping `truth.q_bn` carries the plant's closed-form
//! attitude bit for bit, on the static site with a tilted mount and on a ship with a tilted mount.

use rins_fmi::instance::Instance;
use rins_fmi::model::Model;
use rins_fmi::vars::Value;
use rins_imu_fmu::RinsImu;
use rins_plant::thermal::node;
use rins_plant::{Plant, PlantConfig};

fn slot(name: &str) -> usize {
    RinsImu::table()
        .slot(name)
        .unwrap_or_else(|| panic!("no variable {name}"))
}

fn real(inst: &Instance<RinsImu>, name: &str) -> f64 {
    match inst.get_slot(slot(name)) {
        Value::Real(x) => x,
        v => panic!("{name}: {v:?}"),
    }
}

fn set_real(inst: &mut Instance<RinsImu>, name: &str, x: f64) {
    inst.set_slot(slot(name), Value::Real(x)).unwrap();
}

/// The readings and attitude outputs, in the order [`plant_values`] gives them.
fn readings(inst: &Instance<RinsImu>) -> Vec<u64> {
    node::NAMES
        .iter()
        .map(|n| format!("imu.temp_{n}_c"))
        .chain(["imu.encoder_outer_rad", "imu.encoder_inner_rad"].map(String::from))
        .chain((0..4).map(|i| format!("truth.q_bn[{i}]")))
        .map(|n| real(inst, &n).to_bits())
        .collect()
}

/// The same of the in-process plant now.
fn plant_values(p: &Plant) -> Vec<u64> {
    let e = p.encoder_readings();
    let q = p.attitude_q_bn();
    p.temp_readings_c()
        .into_iter()
        .chain([e.outer_rad, e.inner_rad])
        .chain([q.w, q.i, q.j, q.k])
        .map(f64::to_bits)
        .collect()
}

/// The defaults (the paper's 16-position scheme) with a 30 °C chamber, a tilted mount and
/// biased, quantised sensors, as the FMU's parameters and as the plant's configuration; with
/// `held_at_c` the table holds position C instead (outer and inner at π: the half turn).
fn configured(held_at_c: bool) -> (Instance<RinsImu>, PlantConfig) {
    let mut inst = Instance::<RinsImu>::new();
    inst.setup(0.0).unwrap();
    if held_at_c {
        // The items of scheme.kind from 0: 3 is `static`.
        inst.set_slot(slot("scheme.kind"), Value::Enumeration(3))
            .unwrap();
        set_real(&mut inst, "scheme.initial_outer_deg", 180.0);
        set_real(&mut inst, "scheme.initial_inner_deg", 180.0);
    }
    let reals = [
        ("thermal.chamber.temp_c", 30.0),
        ("vehicle.azimuth_deg", 47.0),
        ("vehicle.pitch_deg", -3.0),
        ("vehicle.roll_deg", 2.0),
        ("sensor.temperature.offset.k[5]", 0.75),
        ("sensor.encoder.offset.arcsec[0]", 20.0),
    ];
    for (n, x) in reals {
        set_real(&mut inst, n, x);
    }
    for n in [
        "sensor.temperature.offset.enabled",
        "sensor.temperature.resolution.enabled",
        "sensor.encoder.offset.enabled",
        "sensor.encoder.quantization.enabled",
    ] {
        inst.set_slot(slot(n), Value::Boolean(true)).unwrap();
    }
    let cfg = inst.model().config().unwrap();
    assert_eq!(cfg.thermal.chamber.temp_c, 30.0);
    assert_eq!(cfg.sensor.temperature.offset.k[5], 0.75);
    (inst, cfg)
}

#[test]
fn outputs_read_in_initialization_mode_are_the_initial_states_readings() {
    let (mut inst, cfg) = configured(true);
    assert_eq!(cfg.scheme.kind, rins_plant::table::SchemeKind::Static);
    let plant = Plant::new(&cfg).unwrap();
    let want = plant_values(&plant);
    let housing = plant.temp_readings_c()[node::HOUSING];
    // The housing sensor reads the self-heated steady state plus its offset: far from 0.
    assert!(housing > 30.0, "{housing}");
    inst.enter_initialization().unwrap();
    assert_eq!(real(&inst, "imu.temp_housing_c"), housing);
    assert_eq!(readings(&inst), want, "initialization mode");
    // The encoders read the start angles (π) through their offset (20″) and resolution.
    let outer = real(&inst, "imu.encoder_outer_rad");
    assert_eq!(real(&inst, "gimbal.outer_rad"), std::f64::consts::PI);
    let offset_arcsec = (outer - std::f64::consts::PI).to_degrees() * 3600.0;
    assert!((offset_arcsec - 20.0).abs() < 0.4, "{offset_arcsec}″");
    inst.exit_initialization().unwrap();
    assert_eq!(readings(&inst), want, "after initialization");
    // The increments of a sample not yet taken stay 0.
    assert_eq!(real(&inst, "imu.dtheta_rad[0]"), 0.0);
}

#[test]
fn truth_q_bn_is_the_plants_closed_form_attitude_bit_for_bit() {
    for ship in [false, true] {
        let (mut inst, mut cfg) = configured(false);
        if ship {
            let kind = slot("carrier.kind");
            let code = match inst.get_slot(kind) {
                Value::Enumeration(_) => Value::Enumeration(1),
                v => panic!("carrier.kind: {v:?}"),
            };
            inst.set_slot(kind, code).unwrap();
            cfg = inst.model().config().unwrap();
            assert_eq!(cfg.carrier.kind, rins_plant::carrier::CarrierKind::Ship);
        }
        let mut plant = Plant::new(&cfg).unwrap();
        inst.enter_initialization().unwrap();
        inst.exit_initialization().unwrap();
        let mut moving = 0;
        for k in 0..20_000 {
            inst.do_step(k as f64 * 0.01, 0.01).unwrap();
            plant.step();
            let q = plant.attitude_q_bn();
            let want = [q.w, q.i, q.j, q.k].map(f64::to_bits);
            let got: [u64; 4] =
                std::array::from_fn(|i| real(&inst, &format!("truth.q_bn[{i}]")).to_bits());
            assert_eq!(got, want, "ship {ship}, step {k}");
            // What a sink composes from the truth record (the CSV's route) is the same.
            let c = plant.truth_mount().q_bn_of(&plant.truth());
            assert_eq!([c.w, c.i, c.j, c.k].map(f64::to_bits), want);
            moving += plant.truth().gimbal.moving as u32;
        }
        assert!(moving > 1000, "the table turned: {moving}");
    }
}
