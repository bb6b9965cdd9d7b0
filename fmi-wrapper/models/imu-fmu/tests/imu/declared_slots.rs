//! Declared effects as FMU parameters (issue 15): a scenario's `[[sensor.gyro.custom]]` /
//! `[[sensor.accel.custom]]` blocks, put into the FMU's slots through fmi2SetInteger /
//! fmi2SetReal / fmi2SetBoolean, give increments bit-identical to the in-process plant
//! simulating the same declared effects; bad slot codes are refused with a logged reason
//! naming the variable and the valid range.
//!
//! Needs the cdylib: `cargo build --release -p rins-imu-fmi2`.

use rins_fmi::fmu;
use rins_fmi::standard::FmiVersion;
use rins_fmi::vars::Value;
use rins_fmi_import::{Fmu2, Instance2, parse_model_description};
use rins_imu_fmu::RinsImu;
use rins_imu_fmu::declared::slot_values;
use rins_plant::Plant;
use rins_plant::effects::CustomSpec;
use rins_plant::effects::custom::{Axis, CustomKind};

use crate::common;

fn library() -> Fmu2 {
    let (guid, _, vars) =
        parse_model_description(&fmu::description::<RinsImu>(FmiVersion::V2).0).unwrap();
    Fmu2::load(&common::library_path(FmiVersion::V2), guid, vars).unwrap()
}

fn spec(
    name: &str,
    kind: CustomKind,
    regressor: &str,
    unit: &str,
    axes: &[Axis],
    coef: [f64; 3],
) -> CustomSpec {
    CustomSpec {
        name: name.into(),
        enabled: true,
        kind,
        regressor: regressor.into(),
        unit: unit.into(),
        axes: axes.to_vec(),
        coef,
    }
}

/// The declared effects of the test: a tilt product and a temperature rate on the gyros
/// (degree 2 and 1), a squared up component (bias on y) and a temperature scale factor on the accelerometers.
fn declared() -> (Vec<CustomSpec>, Vec<CustomSpec>) {
    (
        vec![
            spec(
                "tilt",
                CustomKind::Bias,
                "u_x*u_z",
                "1",
                &[Axis::X, Axis::Z],
                [50.0, 0.0, -30.0],
            ),
            spec(
                "temp_rate",
                CustomKind::Bias,
                "dtemp_dt:block",
                "K/s",
                &[Axis::X, Axis::Y, Axis::Z],
                [120.0, 40.0, 80.0],
            ),
            // Memory (issue 42): a transient after each table move, and a lagged block
            // temperature times it.
            spec(
                "transient",
                CustomKind::Bias,
                "exp(-since_move/45)",
                "1",
                &[Axis::X, Axis::Z],
                [0.05, 0.0, -0.03],
            ),
            spec(
                "lag_t",
                CustomKind::Bias,
                "lag(temp:block,600)*exp(-since_start/300)",
                "K",
                &[Axis::Z],
                [0.0, 0.0, 0.002],
            ),
        ],
        vec![
            spec(
                "tilt_sq",
                CustomKind::Bias,
                "u_z^2",
                "1",
                &[Axis::Y],
                [0.0, 200.0, 0.0],
            ),
            spec(
                "temp_sf",
                CustomKind::ScaleFactor,
                "grad:accel-housing",
                "K",
                &[Axis::Z],
                [0.0, 0.0, 3.0],
            ),
            spec(
                "lag_abs_w",
                CustomKind::Bias,
                "lag(abs_w_z,20)",
                "deg/s",
                &[Axis::X],
                [4.0, 0.0, 0.0],
            ),
        ],
    )
}

fn set_slots(fmu: &Fmu2, inst: &Instance2<'_>, values: &[(String, Value)]) {
    for (name, v) in values {
        let vr = [fmu.vr(name).unwrap()];
        match *v {
            Value::Boolean(b) => inst.set_boolean(&vr, &[b]).unwrap(),
            Value::Integer(u) => inst.set_integer(&vr, &[u as i32]).unwrap(),
            Value::Real(x) => inst.set_real(&vr, &[x]).unwrap(),
            Value::Enumeration(_) => unreachable!("slots have no enumerations"),
        }
    }
}

/// `steps` increments (x, y, z gyro then accel) of the FMU with `values` set.
fn fmu_run(fmu: &Fmu2, values: &[(String, Value)], steps: u64) -> Vec<[f64; 6]> {
    let inst = fmu.instantiate("slots", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    // A cold start: the unit warms up, so the temperature rates are not zero.
    inst.set_boolean(&[fmu.vr("thermal.start_steady").unwrap()], &[false])
        .unwrap();
    set_slots(fmu, &inst, values);
    inst.enter_initialization_mode().unwrap();
    inst.exit_initialization_mode().unwrap();
    let vrs: Vec<u32> = (0..3)
        .map(|i| format!("imu.dtheta_rad[{i}]"))
        .chain((0..3).map(|i| format!("imu.dv_mps[{i}]")))
        .map(|n| fmu.vr(&n).unwrap())
        .collect();
    (0..steps)
        .map(|k| {
            inst.do_step(k as f64 / 100.0, 0.01).unwrap();
            let mut v = [0.0; 6];
            inst.get_real(&vrs, &mut v).unwrap();
            v
        })
        .collect()
}

#[test]
fn declared_effects_in_fmu_slots_are_bit_identical_to_the_plant() {
    let fmu = library();
    let (gyro, accel) = declared();
    let values = slot_values(&gyro, &accel).unwrap();
    // 120 s: the first positions of the 16-position scheme (the table turns at 60 s), thermal
    // updates every second.
    let n = 12_000;
    let got = fmu_run(&fmu, &values, n);
    let mut cfg = rins_plant::presets::paper_16pos_config();
    cfg.thermal.start_steady = false;
    cfg.sensor.gyro.custom = gyro;
    cfg.sensor.accel.custom = accel;
    let mut plant = Plant::new(&cfg).unwrap();
    let want: Vec<[f64; 6]> = (0..n)
        .map(|_| {
            let s = plant.step();
            [
                s.dtheta_rad[0],
                s.dtheta_rad[1],
                s.dtheta_rad[2],
                s.dv_mps[0],
                s.dv_mps[1],
                s.dv_mps[2],
            ]
        })
        .collect();
    let first_diff = got.iter().zip(&want).position(|(a, b)| a != b);
    assert_eq!(first_diff, None, "FMU slots vs in-process declared effects");
    // The slots do act: without them every axis changes.
    let plain = fmu_run(&fmu, &[], n);
    for i in 0..6 {
        let d: f64 = got.iter().zip(&plain).map(|(a, b)| a[i] - b[i]).sum();
        assert!(d != 0.0, "axis {i} unchanged by the slots");
    }
    // Gyro y carries only temp_rate: the sum of its differences is the coefficient times the
    // rate integrated over the run, i.e. 40 °/h per K/s × (ΔT of block y) within quantisation.
    let dy: f64 = got.iter().zip(&plain).map(|(a, b)| a[1] - b[1]).sum();
    let t_y0 = rins_plant::Plant::new(&cfg).unwrap().truth().temps.nodes_c[2];
    let t_y1 = plant.truth().temps.nodes_c[2];
    let expected = 40.0 * rins_plant::units::DPH * (t_y1 - t_y0);
    let quantum = cfg.sensor.gyro.quantization.pulse[1] * rins_plant::units::ARCSEC;
    assert!(
        expected.abs() > 100.0 * quantum,
        "the unit warms: {expected:e}"
    );
    println!("gyro y shift over {n} samples: {dy:e} rad; 40 deg/h/(K/s) x dT = {expected:e} rad");
    assert!(
        (dy - expected).abs() <= 2.0 * quantum + 1e-3 * expected.abs(),
        "gyro y shift {dy:e} vs 40 deg/h/(K/s) × ΔT {expected:e}"
    );
}

#[test]
fn bad_slot_codes_are_refused_naming_the_variable_and_the_range() {
    let fmu = library();
    // Out of a variable's range: refused when set.
    let inst = fmu.instantiate("bad", false).unwrap();
    let e = inst
        .set_integer(&[fmu.vr("sensor.gyro.slot[1].signal[0]").unwrap()], &[14])
        .expect_err("signal 14");
    assert!(
        e.log
            .iter()
            .any(|l| l.contains("sensor.gyro.slot[1].signal[0] = 14") && l.contains("[0, 13]")),
        "{:?}",
        e.log
    );
    // In range but not valid for its signal (u has axes 0…2): refused at the end of
    // initialisation, naming the variable and the valid values.
    let inst = fmu.instantiate("bad2", false).unwrap();
    inst.setup_experiment(0.0, None).unwrap();
    let mut values = slot_values(&declared().0, &[]).unwrap();
    for (name, v) in values.iter_mut() {
        if name == "sensor.gyro.slot[0].node_or_axis[0]" {
            *v = Value::Integer(5);
        }
    }
    set_slots(&fmu, &inst, &values);
    inst.enter_initialization_mode().unwrap();
    let e = inst.exit_initialization_mode().expect_err("axis 5");
    assert!(
        e.log
            .iter()
            .any(|l| l.contains("sensor.gyro.slot[0].node_or_axis[0] = 5") && l.contains("0…2")),
        "{:?}",
        e.log
    );
}
