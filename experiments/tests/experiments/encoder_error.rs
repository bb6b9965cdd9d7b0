//! The navigator knows the carrier only through the gimbal encoders: with encoder errors on, its
//! carrier-attitude error follows the closed form while its IMU attitude is unaffected.
//!
//! With a level mount, C_v^n(nav) = C_b^n·(R_z(o + δo)·R_x(i + δi))ᵀ = R_z(o)·R_x(−δi)·R_z(−o − δo),
//! so to first order φ_v = δi·(cos o, sin o, 0) + δo·(0, 0, 1), with δ = reading − true angle.

use nalgebra::{Matrix3, Rotation3, Vector3};
use rins_experiments::Tracker;
use rins_navigation::errors::attitude_error;
use rins_plant::table::SchemeKind;
use rins_plant::units::{ARCSEC, PPM};
use rins_plant::{Plant, PlantConfig};

fn turning(encoders: bool) -> PlantConfig {
    let mut c = PlantConfig::default();
    c.scheme.kind = SchemeKind::SixteenPosition;
    c.scheme.dwell_s = 20.0;
    if encoders {
        let e = &mut c.sensor.encoder;
        e.scale_factor.enabled = true;
        e.scale_factor.ppm = [200.0, 0.0];
        e.offset.enabled = true;
        e.offset.arcsec = [-15.0, 20.0];
    }
    c
}

/// Largest |φ_v − closed form| and largest |φ_v| over one hour, records every second.
fn run(encoders: bool) -> (f64, f64, f64) {
    let mut p = Plant::new(&turning(encoders)).unwrap();
    let mut nav = Tracker::at_truth(&p, 1.0);
    let (mut worst, mut peak, mut imu_att) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..360_000 {
        let s = p.step();
        let Some(r) = nav.push(&s, || p.truth()) else {
            continue;
        };
        let g = p.truth().gimbal.angles;
        let (d_outer, d_inner) = if encoders {
            (200.0 * PPM * g.outer_rad - 15.0 * ARCSEC, 20.0 * ARCSEC)
        } else {
            (0.0, 0.0)
        };
        // The exact rotation, read with the φ convention (I − [φ×]) of the error records.
        let rz = |a: f64| Rotation3::from_axis_angle(&Vector3::z_axis(), a).into_inner();
        let rx = |a: f64| Rotation3::from_axis_angle(&Vector3::x_axis(), a).into_inner();
        let c = rz(g.outer_rad) * rx(-d_inner) * rz(-g.outer_rad - d_outer);
        let expect = attitude_error(&c, &Matrix3::identity());
        let first_order = [
            d_inner * g.outer_rad.cos(),
            d_inner * g.outer_rad.sin(),
            d_outer,
        ];
        for k in 0..3 {
            // The first-order form of the module notes holds to second order in δ.
            assert!((expect[k] - first_order[k]).abs() < 2e-7);
        }
        for k in 0..3 {
            worst = worst.max((r.vehicle_att_err_rad[k] - expect[k]).abs());
            peak = peak.max(r.vehicle_att_err_rad[k].abs());
            imu_att = imu_att.max(r.att_err_rad[k].abs());
        }
    }
    (worst, peak, imu_att)
}

#[test]
fn carrier_attitude_error_follows_the_encoder_errors() {
    let (worst, peak, imu_att) = run(true);
    // Signal: ≥ 15″ ≈ 7e-5 rad; the navigator's own error with an ideal IMU ≪ 1e-8 rad.
    assert!(peak > 7e-5, "peak {peak}");
    assert!(worst < 1e-8, "closed form missed by {worst} rad");
    let (worst0, peak0, imu_att0) = run(false);
    assert!(peak0 < 1e-8 && worst0 < 1e-8, "{peak0} {worst0}");
    // Encoders do not enter the IMU attitude: the same error either way.
    assert!(
        (imu_att - imu_att0).abs() < 1e-12,
        "{imu_att} vs {imu_att0}"
    );
}
