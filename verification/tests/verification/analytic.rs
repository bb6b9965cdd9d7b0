//! The analytic harness figures required of the plant (Eq. 8, Eq. 11, Table 2).

use rins_verification::analytic::{cycle_trace, eq8, eq11};
use rins_verification::report::AnalyticReport;
use rins_verification::table2::compare;

#[test]
fn eq8_errors_cancel_over_a_cycle() {
    let r = eq8();
    for c in &r.cases {
        assert!(
            c.cancellation_ratio <= 1e-9,
            "{} (accel {}): ratio {:e}",
            c.errors,
            c.accel_dps2,
            c.cancellation_ratio
        );
    }
    // 16 (T_r + T_s) with T_r = 90 s + ramp time 0.1 s at the default 20 deg/s^2.
    approx::assert_relative_eq!(r.cycle_s, 16.0 * (90.1 + 180.0), epsilon = 1e-9);
}

#[test]
fn eq11_stationary_residual_and_paper_example() {
    let r = eq11([0.005; 3], 180.0);
    assert!(
        r.stationary_z_rel_err <= 1e-9,
        "{:e}",
        r.stationary_z_rel_err
    );
    assert!(
        r.stationary_xy_over_z <= 1e-12,
        "{:e}",
        r.stationary_xy_over_z
    );
    // The paper: T_s = 180 s and dbeta_z = 0.005 deg/h give about 0.002 deg.
    approx::assert_relative_eq!(r.expected_z_deg, -0.002, epsilon = 1e-12);
    assert!(r.rotation_rel_err <= 1e-6, "{:e}", r.rotation_rel_err);
}

#[test]
fn eq11_scales_with_dwell_and_only_dbeta_z_survives_the_dwells() {
    // A second dwell time and a delta-beta with z = 0: stationary residual vanishes.
    let r = eq11([0.01, -0.02, 0.0], 60.0);
    let s = nalgebra::Vector3::from(r.stationary_rad);
    assert!(s.norm() < 1e-15, "{s:?}");
    let r2 = eq11([0.0, 0.0, 0.004], 300.0);
    approx::assert_relative_eq!(
        r2.stationary_rad[2],
        -8.0 * 300.0 * 0.004 * rins_plant::units::DPH,
        max_relative = 1e-9
    );
}

#[test]
fn table2_has_exactly_the_two_misprinted_entries() {
    // Independently derived by hand from Eq. 5-6: sequences 3 and 6 run at Z down (from C and
    // from D), so their (3,3) entry is -1; Table 2 prints 1.
    let t = compare();
    let found: Vec<(usize, usize, usize)> = t
        .mismatches
        .iter()
        .map(|m| (m.sequence, m.row, m.col))
        .collect();
    assert_eq!(found, vec![(3, 3, 3), (6, 3, 3)]);
    for m in &t.mismatches {
        assert_eq!(m.printed, 1.0);
        approx::assert_relative_eq!(m.derived, -1.0, epsilon = 1e-12);
    }
    assert!(t.max_abs_diff_agreeing < 1e-12);
}

#[test]
fn report_passes_and_serialises_required_keys() {
    let r = AnalyticReport::run();
    assert!(r.passed(), "{}", r.to_text());
    let v = serde_json::to_value(&r).unwrap();
    for key in [
        "/eq8/cancellation_ratio",
        "/eq11/stationary_rad",
        "/eq11/expected_z_rad",
        "/eq11/rotation_rad",
        "/eq11/rotation_closed_form_rad",
        "/table2/mismatches",
    ] {
        assert!(v.pointer(key).is_some(), "missing {key}");
    }
}

#[test]
fn accel_scale_factor_on_gravity_is_rectified_not_cancelled() {
    let r = eq8();
    let v = &r.accel_scale_factor_vertical;
    // A real, positive vertical residual (SF z = 40 ppm dominates), matching its closed form.
    assert!(v.numeric_mps > 1.0, "{}", v.numeric_mps);
    assert!(v.rel_err < 1e-9, "{:e}", v.rel_err);
    // Horizontal components still cancel.
    let sf = r
        .cases
        .iter()
        .find(|c| c.errors == "accel scale_factor")
        .unwrap();
    assert!(sf.cancellation_ratio < 1e-9);
}

#[test]
fn cycle_trace_ends_where_the_quadrature_says() {
    // Midpoint rule at 0.05 s against the Gauss–Legendre integrals of eq11: a second method.
    let (bias, dbeta, dwell) = ([0.01, -0.02, 0.015], [0.003, -0.004, 0.005], 180.0);
    let tr = cycle_trace(bias, dbeta, dwell, 0.05);
    let end = tr.last().unwrap();
    let r = eq11(dbeta, dwell);
    let full = r.full_cycle_rad;
    for (i, (got, want)) in end.delta_beta_rad.iter().zip(full).enumerate() {
        assert!(
            (got - want).abs() <= 1e-3 * r.expected_z_rad.abs(),
            "axis {i}: {got} vs {want}"
        );
    }
    // Eq. 8: a constant bias integrates back to zero; halfway through it does not.
    let scale = 0.02 * rins_plant::units::DPH * dwell;
    for i in 0..3 {
        assert!(
            end.bias_rad[i].abs() <= 1e-3 * scale,
            "axis {i}: {}",
            end.bias_rad[i]
        );
    }
    let mid = &tr[tr.len() / 4];
    assert!(
        mid.bias_rad.iter().any(|v| v.abs() > 0.1 * scale),
        "{:?}",
        mid.bias_rad
    );
}
