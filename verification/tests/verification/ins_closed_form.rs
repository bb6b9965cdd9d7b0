//! The navigator reproduces textbook static free-inertial responses (each check can fail).

use rins_verification::ins::{InsReport, accel_bias_case, arw_position_sigma, gyro_bias_case};

#[test]
fn the_whole_ins_report_passes() {
    let r = InsReport::run(64);
    assert!(r.passed(), "{}", r.to_text());
}

#[test]
fn north_and_up_gyro_bias_match_published_week_figures() {
    // Independent figures (notes, computed by hand from the closed form): 0.01 deg/h for 168 h at
    // 36.6 N gives 120.7 km east for a north gyro and 89.3 km for an up gyro.
    let n = gyro_bias_case(1, 0.01, 168.0, 20.0);
    approx::assert_relative_eq!(n.end_m[1], 120_700.0, max_relative = 0.005);
    let u = gyro_bias_case(2, 0.01, 168.0, 20.0);
    approx::assert_relative_eq!(u.end_m[1], 89_300.0, max_relative = 0.005);
}

#[test]
fn schuler_period_is_84_4_minutes_and_foucault_40_hours() {
    let a = accel_bias_case(50.0, 30.0, 20.0);
    approx::assert_relative_eq!(a.schuler_period_min, 84.4, max_relative = 0.005);
    approx::assert_relative_eq!(a.foucault_period_h, 40.1, max_relative = 0.01);
}

#[test]
fn arw_floor_after_a_week_is_about_5_3_km() {
    // Notes: ARW 0.003 deg/rt-h leaves ~5.3 km (2.9 nmi) 1-sigma per horizontal axis after a week.
    let (n, e) = arw_position_sigma(0.003 * rins_plant::units::DPSH, 36.6f64.to_radians(), 168.0);
    approx::assert_relative_eq!(n, 5300.0, max_relative = 0.03);
    approx::assert_relative_eq!(e, 5300.0, max_relative = 0.03);
}
