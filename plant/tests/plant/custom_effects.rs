//! Declared effects (`[[sensor.gyro.custom]]`, `[[sensor.accel.custom]]`) against closed forms
//! computed here from the geometry and the truth, with the plant otherwise ideal.

use approx::assert_relative_eq;
use rins_plant::effects::custom::{Axis, CustomKind, CustomSpec};
use rins_plant::table::{GimbalAxis, RotationStep, SchemeKind, SchemeSpec};
use rins_plant::units::{DPH, PPM, UG};
use rins_plant::{Plant, PlantConfig};

fn ideal(outer_deg: f64, inner_deg: f64) -> PlantConfig {
    let mut c = PlantConfig::default();
    c.earth.rotation = false;
    c.thermal.enabled = false;
    c.scheme = SchemeSpec {
        kind: SchemeKind::Static,
        initial_outer_deg: outer_deg,
        initial_inner_deg: inner_deg,
        ..SchemeSpec::default()
    };
    c
}

fn declared(
    name: &str,
    kind: CustomKind,
    regressor: &str,
    unit: &str,
    axis: Axis,
    c: f64,
) -> CustomSpec {
    let mut coef = [0.0; 3];
    coef[axis.index()] = c;
    CustomSpec {
        name: name.into(),
        enabled: true,
        kind,
        regressor: regressor.into(),
        unit: unit.into(),
        axes: vec![axis],
        coef,
    }
}

#[test]
fn tilt_product_bias_matches_the_geometry_on_both_sensors() {
    // Static at inner 30°, outer 40°: C_b^n = R_z(40°)·R_x(30°), so the body up direction is
    // (0, sin 30°, cos 30°) and u_y·u_z = sin 30°·cos 30°.
    let mut cfg = ideal(40.0, 30.0);
    cfg.sensor.gyro.custom = vec![declared(
        "tilt",
        CustomKind::Bias,
        "u_y*u_z",
        "1",
        Axis::Y,
        2.5,
    )];
    cfg.sensor.accel.custom = vec![declared(
        "tilt_a",
        CustomKind::Bias,
        "u_y * u_z",
        "1",
        Axis::X,
        40.0,
    )];
    let mut p = Plant::new(&cfg).unwrap();
    let dt = cfg.dt_s();
    let (s, c) = 30f64.to_radians().sin_cos();
    for _ in 0..500 {
        let out = p.step();
        let tr = p.truth();
        let gyro_err = out.dtheta_rad - tr.dtheta_true_rad;
        let accel_err = out.dv_mps - tr.dv_true_mps;
        assert_relative_eq!(gyro_err.y, 2.5 * DPH * s * c * dt, max_relative = 1e-9);
        assert_relative_eq!(accel_err.x, 40.0 * UG * s * c * dt, max_relative = 1e-9);
        assert!(
            gyro_err.x.abs() < 1e-20 && gyro_err.z.abs() < 1e-20,
            "{gyro_err:?}"
        );
        assert_eq!(tr.custom_gyro_rad, gyro_err);
    }
}

#[test]
fn time_bias_integrates_to_half_t_squared() {
    // ∫ c·t dt over [0, T] = c·T²/2 (the midpoint rule is exact for a linear integrand); the
    // dwell cache must not freeze a contribution that grows with time.
    let mut cfg = ideal(0.0, 0.0);
    cfg.sensor.gyro.custom = vec![declared(
        "drift",
        CustomKind::Bias,
        "time",
        "s",
        Axis::X,
        0.01,
    )];
    let mut p = Plant::new(&cfg).unwrap();
    let mut sum = 0.0;
    let n = 20_000;
    for _ in 0..n {
        let out = p.step();
        sum += out.dtheta_rad.x - p.truth().dtheta_true_rad.x;
    }
    let t = n as f64 * cfg.dt_s();
    assert_relative_eq!(sum, 0.01 * DPH * t * t / 2.0, max_relative = 1e-9);
}

#[test]
fn temperature_rate_bias_integrates_to_the_temperature_change() {
    // b·dT/dt integrated over whole thermal steps telescopes to b·(T_end − T_start): the
    // plant holds the rate of the last thermal step until the next one.
    let mut cfg = ideal(0.0, 0.0);
    cfg.thermal.enabled = true;
    cfg.thermal.step_s = 1.0;
    cfg.thermal.chamber.profile = vec![[0.0, 20.0], [100.0, 60.0], [1500.0, 30.0]];
    cfg.sensor.gyro.custom = vec![declared(
        "trate",
        CustomKind::Bias,
        "dtemp_dt:block",
        "K/s",
        Axis::Z,
        300.0,
    )];
    let mut p = Plant::new(&cfg).unwrap();
    let every = (cfg.thermal.step_s * cfg.rate_hz).round() as usize;
    p.step();
    let t0 = p.truth().temps.nodes_c[3];
    let mut sum = p.truth().custom_gyro_rad.z;
    let periods = 2000;
    for _ in 1..every * (periods + 1) {
        let out = p.step();
        sum += out.dtheta_rad.z - p.truth().dtheta_true_rad.z;
    }
    let t_end = p.truth().temps.nodes_c[3];
    assert!(
        (t_end - t0).abs() > 0.5,
        "the block must warm: {t0} → {t_end}"
    );
    assert_relative_eq!(sum, 300.0 * DPH * (t_end - t0), max_relative = 1e-9);
}

#[test]
fn rate_scale_factor_follows_the_true_increment() {
    // A scale factor ∝ |ω_z| during one 180° outer turn at 10 °/s: error = s·|ω_z|·Δθ_z.
    let mut cfg = ideal(0.0, 0.0);
    cfg.scheme = SchemeSpec {
        kind: SchemeKind::Steps,
        accel_dps2: f64::INFINITY,
        lead_dwell_s: 1.0,
        repeat: false,
        steps: vec![RotationStep {
            axis: GimbalAxis::Outer,
            angle_deg: 180.0,
            rate_dps: 10.0,
            dwell_s: 1.0,
        }],
        ..SchemeSpec::default()
    };
    cfg.sensor.gyro.custom = vec![declared(
        "sfw",
        CustomKind::ScaleFactor,
        "abs_w_z",
        "deg/s",
        Axis::Z,
        3.0,
    )];
    let mut p = Plant::new(&cfg).unwrap();
    let (mut sum, mut expect) = (0.0, 0.0);
    for _ in 0..2100 {
        let out = p.step();
        let tr = p.truth();
        sum += out.dtheta_rad.z - tr.dtheta_true_rad.z;
        let w_dps = (tr.dtheta_true_rad.z / cfg.dt_s()).to_degrees();
        expect += 3.0 * PPM * w_dps.abs() * tr.dtheta_true_rad.z;
    }
    // Over the whole turn: 3 ppm/(°/s) · 10 °/s · π.
    assert_relative_eq!(sum, expect, max_relative = 1e-12);
    assert_relative_eq!(
        sum,
        3.0 * PPM * 10.0 * std::f64::consts::PI,
        max_relative = 1e-9
    );
}

#[test]
fn bad_declarations_name_the_key() {
    let mut cfg = ideal(0.0, 0.0);
    let mut bad = declared("a", CustomKind::Bias, "dtemp:block", "K/s", Axis::Z, 1.0);
    cfg.sensor.gyro.custom = vec![bad.clone()];
    let e = cfg.validate().unwrap_err();
    assert_eq!(e[0].path, "sensor.gyro.custom[0].regressor", "{e:?}");
    assert!(e[0].got.contains("unknown signal \"dtemp:block\""), "{e:?}");
    bad.regressor = "dtemp_dt:block".into();
    bad.unit = "K".into();
    cfg.sensor.gyro.custom = vec![bad.clone()];
    let e = cfg.validate().unwrap_err();
    assert_eq!(e[0].path, "sensor.gyro.custom[0].unit", "{e:?}");
    assert!(e[0].expected.starts_with("K/s"), "{e:?}");
    bad.unit = "K/s".into();
    bad.coef = [1.0, 0.0, 0.0];
    cfg.sensor.gyro.custom = vec![bad.clone()];
    cfg.sensor.accel.custom = vec![bad.clone()];
    let e = cfg.validate().unwrap_err();
    assert!(
        e.iter().any(|e| e.path == "sensor.gyro.custom[0].coef[0]"),
        "{e:?}"
    );
    assert!(
        e.iter().any(|e| e.path == "sensor.accel.custom[0].coef[0]"),
        "{e:?}"
    );
    bad.coef = [0.0, 0.0, f64::MAX];
    cfg.sensor.gyro.custom = vec![bad.clone()];
    cfg.sensor.accel.custom = vec![];
    let e = cfg.validate().unwrap_err();
    assert!(
        e.iter().any(|e| e.path == "sensor.gyro.custom[0].coef[2]"),
        "{e:?}"
    );
    assert!(Plant::new(&cfg).is_err());
    // One name per effect across both sensors (`custom:NAME` in the diagnosis).
    bad.coef = [0.0; 3];
    cfg.sensor.gyro.custom = vec![bad.clone()];
    cfg.sensor.accel.custom = vec![bad.clone()];
    let e = cfg.validate().unwrap_err();
    assert_eq!(e[0].path, "sensor.accel.custom[0].name", "{e:?}");
}

#[test]
fn state_round_trip_keeps_the_temperature_rate() {
    let mut cfg = ideal(0.0, 0.0);
    cfg.thermal.enabled = true;
    cfg.thermal.step_s = 1.0;
    cfg.thermal.chamber.profile = vec![[0.0, 20.0], [100.0, 40.0]];
    cfg.sensor.gyro.custom = vec![declared(
        "trate",
        CustomKind::Bias,
        "dtemp_dt:block",
        "K/s",
        Axis::Z,
        300.0,
    )];
    let mut a = Plant::new(&cfg).unwrap();
    for _ in 0..1550 {
        a.step();
    }
    let saved = a.serialize_state();
    let mut b = Plant::from_serialized_state(&cfg, &saved).unwrap();
    for _ in 0..500 {
        assert_eq!(a.step(), b.step());
        assert_eq!(a.truth(), b.truth());
    }
}
