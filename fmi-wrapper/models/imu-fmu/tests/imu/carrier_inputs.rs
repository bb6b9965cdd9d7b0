//! The IMU FMU's carrier inputs driven by the RinsCarrier model, through the generic FMI state
//! machine in process: ignored unless `carrier.external_inputs`; fed the ship's state at the
//! end of every step, the true increments follow the plant on the same ship within the
//! interpolation bound; bad samples are refused with the reason; a saved state continues bit
//! for bit.

use rins_carrier_fmu::RinsCarrier;
use rins_fmi::instance::Instance;
use rins_fmi::model::Model;
use rins_fmi::vars::Value;
use rins_imu_fmu::RinsImu;
use rins_imu_fmu::carrier_inputs::{INPUTS, SWITCH};
use rins_plant::Plant;
use rins_plant::carrier::{CarrierKind, SpectrumKind};

const STEP: f64 = 0.01;

fn slot<M: Model>(name: &str) -> usize {
    M::table()
        .slot(name)
        .unwrap_or_else(|| panic!("no variable {name}"))
}

fn real<M: Model>(inst: &Instance<M>, name: &str) -> f64 {
    match inst.get_slot(slot::<M>(name)) {
        Value::Real(x) => x,
        v => panic!("{name}: {v:?}"),
    }
}

/// Copies the carrier outputs onto the IMU's inputs (the connections of the system files).
fn connect(c: &Instance<RinsCarrier>, imu: &mut Instance<RinsImu>) -> Result<(), String> {
    for name in INPUTS.map(|row| row.name) {
        imu.set_slot(slot::<RinsImu>(name), Value::Real(real(c, name)))
            .map_err(|e| e.message)?;
    }
    Ok(())
}

fn carrier() -> Instance<RinsCarrier> {
    let mut c = Instance::<RinsCarrier>::new();
    c.setup(0.0).unwrap();
    c.enter_initialization().unwrap();
    c.exit_initialization().unwrap();
    c
}

fn started_imu(external: bool, c: Option<&Instance<RinsCarrier>>) -> Instance<RinsImu> {
    let mut imu = Instance::<RinsImu>::new();
    imu.setup(0.0).unwrap();
    imu.set_slot(slot::<RinsImu>(SWITCH), Value::Boolean(external))
        .unwrap();
    if let Some(c) = c {
        connect(c, &mut imu).unwrap();
    }
    imu.enter_initialization().unwrap();
    imu.exit_initialization().unwrap();
    imu
}

const DTHETA: [&str; 3] = [
    "truth.dtheta_rad[0]",
    "truth.dtheta_rad[1]",
    "truth.dtheta_rad[2]",
];
const DV: [&str; 3] = ["truth.dv_mps[0]", "truth.dv_mps[1]", "truth.dv_mps[2]"];

#[test]
fn without_the_switch_the_carrier_inputs_change_nothing() {
    let c = carrier();
    let mut a = started_imu(false, None);
    let mut b = started_imu(false, Some(&c));
    for k in 0..500 {
        b.set_slot(
            slot::<RinsImu>("carrier.lat_deg"),
            Value::Real(10.0 + k as f64 * 0.01),
        )
        .unwrap();
        a.do_step(k as f64 * STEP, STEP).unwrap();
        b.do_step(k as f64 * STEP, STEP).unwrap();
        for n in DTHETA
            .iter()
            .chain(&DV)
            .chain(&["imu.dtheta_rad[2]", "imu.dv_mps[0]"])
        {
            assert_eq!(
                real(&a, n).to_bits(),
                real(&b, n).to_bits(),
                "{n} at step {k}"
            );
        }
    }
}

/// The carrier FMU's state at the end of each step drives the IMU; the plant on the same ship
/// in process (the ship's exact in-tick states) is the reference. They differ by the trajectory
/// interpolation over one 10 ms step h: the cubic position keeps ∫a = Δv exactly, so the
/// velocity increments differ by the attitude interpolation error (constant rate, at most
/// h²·|ω̇|/8 mid-step) times the specific force over the step, g·h·h²·|ω̇|/8 ≈ 1.2e-7 m/s for
/// |ω̇| ≲ 0.1 rad/s² (sea state 5); the angle increments by the constant-rate rule's
/// h³·|ω̈|/12 ≈ 1e-8 rad for |ω̈| ≲ 0.1 rad/s³. Increments are of order 1e-3.
#[test]
fn driven_by_the_carrier_fmu_the_increments_follow_the_ship() {
    let mut c = carrier();
    let mut imu = started_imu(true, Some(&c));
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.carrier.kind = CarrierKind::Ship;
    cfg.carrier.ship.sea.spectrum = SpectrumKind::PiersonMoskowitz;
    cfg.carrier.ship.sea.sea_state = 5;
    let mut plant = Plant::new(&cfg).unwrap();
    let (mut worst_th, mut worst_v, mut scale) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..3000 {
        c.do_step(k as f64 * STEP, STEP).unwrap();
        connect(&c, &mut imu).unwrap();
        imu.do_step(k as f64 * STEP, STEP).unwrap();
        plant.step();
        let t = plant.truth();
        for i in 0..3 {
            worst_th = worst_th.max((real(&imu, DTHETA[i]) - t.dtheta_true_rad[i]).abs());
            worst_v = worst_v.max((real(&imu, DV[i]) - t.dv_true_mps[i]).abs());
            scale = scale.max(t.dtheta_true_rad[i].abs());
        }
    }
    eprintln!(
        "worst |d dtheta| {worst_th:e} rad, |d dv| {worst_v:e} m/s, |dtheta| up to {scale:e}"
    );
    assert!(scale > 1e-4, "the ship moves the table: {scale}");
    assert!(
        worst_th < 3e-6 && worst_v < 3e-6,
        "{worst_th:e} {worst_v:e}"
    );
}

#[test]
fn bad_carrier_samples_are_refused_with_the_reason() {
    let c = carrier();
    let mut imu = started_imu(true, Some(&c));
    // Out of the declared range: refused by the setter.
    let e = imu
        .set_slot(slot::<RinsImu>("carrier.lat_deg"), Value::Real(95.0))
        .unwrap_err();
    assert!(e.message.contains("89"), "{}", e.message);
    // A quaternion off norm 1: refused at the step, naming the column.
    let mut bad = started_imu(true, Some(&c));
    bad.set_slot(slot::<RinsImu>("carrier.q_cn[0]"), Value::Real(0.5))
        .unwrap();
    let e = bad.do_step(0.0, STEP).unwrap_err();
    assert!(
        e.message.contains("q_cn_w") && e.message.contains("norm"),
        "{}",
        e.message
    );
    // A 1 km jump in one step that the velocities do not explain.
    let mut jump = started_imu(true, Some(&c));
    let lat = real(&c, "carrier.lat_deg");
    jump.set_slot(slot::<RinsImu>("carrier.lat_deg"), Value::Real(lat + 0.01))
        .unwrap();
    let e = jump.do_step(0.0, STEP).unwrap_err();
    assert!(e.message.contains("position jump"), "{}", e.message);
}

#[test]
fn a_saved_state_with_carrier_inputs_continues_bit_for_bit() {
    let mut c = carrier();
    let mut a = started_imu(true, Some(&c));
    for k in 0..200 {
        c.do_step(k as f64 * STEP, STEP).unwrap();
        connect(&c, &mut a).unwrap();
        a.do_step(k as f64 * STEP, STEP).unwrap();
    }
    let mut b = Instance::<RinsImu>::deserialize(&a.serialize()).unwrap();
    for k in 200..400 {
        c.do_step(k as f64 * STEP, STEP).unwrap();
        connect(&c, &mut a).unwrap();
        connect(&c, &mut b).unwrap();
        a.do_step(k as f64 * STEP, STEP).unwrap();
        b.do_step(k as f64 * STEP, STEP).unwrap();
        for n in DTHETA.iter().chain(&DV) {
            assert_eq!(
                real(&a, n).to_bits(),
                real(&b, n).to_bits(),
                "{n} at step {k}"
            );
        }
    }
}

/// Issue 29: a carrier of the FMU's own (`carrier.kind` ship, code 2) beside
/// `carrier.external_inputs = true` cannot be honoured: leaving initialization mode is refused
/// naming both parameters (the ship was silently replaced by the inputs). Static with the
/// inputs, and the ship without them, start.
#[test]
fn a_carrier_kind_the_inputs_replace_is_refused_naming_the_parameters() {
    let c = carrier();
    for (code, external, refused) in [(1, true, false), (2, true, true), (2, false, false)] {
        let mut imu = Instance::<RinsImu>::new();
        imu.setup(0.0).unwrap();
        imu.set_slot(slot::<RinsImu>("carrier.kind_code"), Value::Integer(code))
            .unwrap();
        imu.set_slot(slot::<RinsImu>(SWITCH), Value::Boolean(external))
            .unwrap();
        connect(&c, &mut imu).unwrap();
        imu.enter_initialization().unwrap();
        let r = imu.exit_initialization();
        let ctx = format!("kind_code {code}, external {external}");
        if !refused {
            r.expect(&ctx);
            imu.do_step(0.0, STEP).expect(&ctx);
            continue;
        }
        let e = r.expect_err(&ctx).message;
        assert!(
            e.contains(
                "carrier.kind = ship (carrier.kind_code = 2) with carrier.external_inputs = true"
            ) && e.contains("set carrier.kind = static (carrier.kind_code = 1)")
                && e.contains("or carrier.external_inputs = false"),
            "{e}"
        );
        assert!(imu.do_step(0.0, STEP).is_err(), "no step after the refusal");
    }
}
