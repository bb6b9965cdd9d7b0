//! Self-alignment reaches the classical static alignment limits (closed form).

use rins_experiments::{Alignment, NavRunConfig, run};
use rins_plant::earth::{OMEGA_IE_RPS, normal_gravity};
use rins_plant::table::SchemeKind;
use rins_plant::units::{DPH, UG};
use rins_plant::{Plant, PlantConfig};

#[test]
fn fine_alignment_converges_to_bias_limited_attitude() {
    // Level tilt errors phi_N = nabla_E/g, phi_E = -nabla_N/g; heading error
    // phi_U = -eps_E/(Omega cos L) + tan L * phi_N (gyrocompassing with an east gyro bias).
    let mut cfg = PlantConfig::default();
    cfg.thermal.enabled = false;
    cfg.scheme.kind = SchemeKind::Static;
    cfg.sensor.accel.bias.enabled = true;
    cfg.sensor.accel.bias.ug = [30.0, -20.0, 0.0];
    cfg.sensor.gyro.bias.enabled = true;
    cfg.sensor.gyro.bias.dph = [0.01, 0.0, 0.0];
    let mut plant = Plant::new(&cfg).unwrap();
    let nav = NavRunConfig {
        alignment: Alignment::SelfAlign {
            coarse_s: 120.0,
            fine_s: 1500.0,
        },
        record_every_s: 10.0,
        ..NavRunConfig::default()
    };
    let r = run(&mut plant, 10.0, &nav).unwrap();
    let a = r.alignment.expect("self-aligned");
    let lat = 36.6f64.to_radians();
    let g = normal_gravity(lat, 0.0);
    let phi_n = 30.0 * UG / g;
    let phi_e = 20.0 * UG / g;
    let phi_u = -0.01 * DPH / (OMEGA_IE_RPS * lat.cos()) + lat.tan() * phi_n;
    approx::assert_relative_eq!(a.fine_err_rad[0], phi_e, max_relative = 0.05);
    approx::assert_relative_eq!(a.fine_err_rad[1], phi_n, max_relative = 0.05);
    approx::assert_relative_eq!(a.fine_err_rad[2], phi_u, max_relative = 0.05);
    // Coarse alignment alone is already within a few mrad.
    assert!(a.coarse_err_rad.iter().all(|e| e.abs() < 5e-3), "{a:?}");
}

#[test]
fn alignment_refuses_a_moving_table() {
    let cfg = PlantConfig::default(); // 16-position scheme starts moving at t = 0
    let mut plant = Plant::new(&cfg).unwrap();
    let nav = NavRunConfig {
        alignment: Alignment::SelfAlign {
            coarse_s: 60.0,
            fine_s: 60.0,
        },
        ..NavRunConfig::default()
    };
    let e = run(&mut plant, 10.0, &nav).unwrap_err();
    assert!(e.to_string().contains("lead_dwell_s"), "{e}");
}

#[test]
fn ideal_rotating_imu_navigates_without_error() {
    // Kinematic consistency of plant increments and navigator (coning, sculling, frame rates):
    // with ideal sensors the 16-position RINS must stay put for a day.
    let mut cfg = PlantConfig::default();
    cfg.thermal.enabled = false;
    let mut plant = Plant::new(&cfg).unwrap();
    let r = run(
        &mut plant,
        86_400.0,
        &NavRunConfig {
            record_every_s: 3600.0,
            ..NavRunConfig::default()
        },
    )
    .unwrap();
    let e = r.end();
    assert!(e.horizontal_m < 0.5, "{e:?}");
    assert!(e.att_err_rad.iter().all(|a| a.abs() < 1e-8), "{e:?}");
}

#[test]
fn carrier_attitude_error_equals_imu_error_with_exact_encoders() {
    // The gimbal angles are exact, so the vehicle attitude error is the IMU's attitude error
    // expressed in the navigation frame, whatever the table position.
    let mut cfg = PlantConfig::default();
    cfg.vehicle.azimuth_deg = 30.0;
    cfg.vehicle.pitch_deg = 2.0;
    cfg.sensor = rins_plant::presets::paper_table3();
    let mut plant = Plant::new(&cfg).unwrap();
    let r = run(
        &mut plant,
        7200.0,
        &NavRunConfig {
            record_every_s: 97.0,
            ..NavRunConfig::default()
        },
    )
    .unwrap();
    for rec in &r.records {
        for k in 0..3 {
            approx::assert_relative_eq!(
                rec.vehicle_att_err_rad[k],
                rec.att_err_rad[k],
                epsilon = 1e-12
            );
        }
    }
    assert!(
        r.end().att_err_rad.iter().any(|a| a.abs() > 1e-6),
        "errors are not trivially zero"
    );
}
