//! The exact increments against closed forms: a full outer turn, static dwells, gravity, and
//! the mount convention against the plant's documented C_v^n.

use nalgebra::{Matrix3, Vector3};
use rins_mvm_trials::Gimbal;
use rins_mvm_trials::rotation::{body_to_nav, mount, rot_x, rot_z};
use rins_mvm_trials::row::{Row, RunRows, Setup};
use rins_plant::config::VehicleSpec;
use rins_plant::earth::Site;

use super::{base_model, hold, mv, one_run};

#[test]
fn mount_is_the_documented_vehicle_rotation() {
    for (az, pitch, roll) in [
        (0.0, 0.0, 30.0),
        (37.0, -12.0, 30.0),
        (-150.0, 45.0, -170.0),
    ] {
        let plant = VehicleSpec {
            azimuth_deg: az,
            pitch_deg: pitch,
            roll_deg: roll,
        }
        .c_vn();
        let ours = mount(az, pitch, roll);
        assert!((plant - ours).amax() < 1e-15, "{az} {pitch} {roll}");
    }
    // Roll about the vehicle y axis tips body x towards down (x sees gravity).
    let c = mount(0.0, 0.0, 30.0);
    assert!((c[(2, 0)] + 0.5).abs() < 1e-15);
}

/// Sums of Δθ over rows [from, to] (1-based) of the one run of `design`.
fn sum_rows(rows: &mut RunRows, from: usize, to: usize) -> Vector3<f64> {
    let mut row = Row::default();
    let mut s = Vector3::zeros();
    for k in from..=to {
        rows.row(k, &mut row);
        s += row.dtheta;
    }
    s
}

#[test]
fn full_outer_turn_gives_two_pi_about_body_z() {
    let mut model = base_model();
    model.earth.rotation = false;
    for (inner, expect) in [
        (0.0, Vector3::new(0.0, 0.0, 1.0)),
        (180.0, Vector3::new(0.0, 0.0, -1.0)),
    ] {
        // Tilt to the inner angle at t < 10 s, then one turn of 360° at 10 °/s (36 s).
        let table = vec![
            mv(Gimbal::Inner, inner, 20.0),
            rins_mvm_trials::TableLeg::Dwell {
                dur_s: 10.0 - inner / 20.0,
            },
            mv(Gimbal::Outer, 360.0, 10.0),
        ];
        let design = one_run(table, vec![hold(25.0, 100.0)], 60.0, 0.0);
        let setup = Setup::new(&model, &design);
        let mut rows = RunRows::new(setup, &design, &design.runs[0], &[]);
        let turn = sum_rows(&mut rows, 101, 460);
        let want = expect * (2.0 * std::f64::consts::PI);
        // x exactly nothing, y only sin(π)·2π at Z-down, z to the rounding of 360 sums.
        assert!(
            turn[0] == 0.0 && (turn[1] - want[1]).abs() < 1e-15,
            "inner {inner}: {turn:?}"
        );
        assert!((turn[2] - want[2]).abs() < 1e-13, "inner {inner}: {turn:?}");
    }
    // With the Earth: over a full turn at Z-up the horizontal Earth rate averages out and the
    // vertical adds Ω·sin L·T.
    let model = base_model();
    let design = one_run(
        vec![mv(Gimbal::Outer, 360.0, 10.0)],
        vec![hold(25.0, 100.0)],
        40.0,
        0.0,
    );
    let site = Site::new(&model.site, &model.earth);
    let mut rows = RunRows::new(Setup::new(&model, &design), &design, &design.runs[0], &[]);
    let turn = sum_rows(&mut rows, 1, 360);
    let want = Vector3::new(
        0.0,
        0.0,
        2.0 * std::f64::consts::PI + site.omega_ie_n[2] * 36.0,
    );
    let d = turn - want;
    assert!(
        d[0].abs() < 1e-17 && d[1].abs() < 1e-17 && d[2].abs() < 1e-13,
        "{d:?}"
    );
}

#[test]
fn static_dwell_senses_the_earth_rate_and_gravity() {
    let model = base_model();
    let site = Site::new(&model.site, &model.earth);
    // Dwells at outer 0, 90°, tilted 45° and Z-down, mount roll 30°.
    let table = vec![
        rins_mvm_trials::TableLeg::Dwell { dur_s: 20.0 },
        mv(Gimbal::Outer, 90.0, 10.0),
        rins_mvm_trials::TableLeg::Dwell { dur_s: 20.0 },
        mv(Gimbal::Inner, 45.0, 10.0),
        rins_mvm_trials::TableLeg::Dwell { dur_s: 20.0 },
        mv(Gimbal::Inner, 135.0, 10.0),
    ];
    let design = one_run(table, vec![hold(25.0, 100.0)], 120.0, 30.0);
    let mut rows = RunRows::new(Setup::new(&model, &design), &design, &design.runs[0], &[]);
    let c_vn = mount(0.0, 0.0, 30.0);
    let mut row = Row::default();
    // (row, outer, inner) of rows inside dwells.
    for (k, o, i) in [
        (5, 0.0, 0.0),
        (400, 90.0, 0.0),
        (600, 90.0, 45.0),
        (1000, 90.0, 180.0),
    ] {
        rows.row(k, &mut row);
        // The row's own interval (k·0.1 s − (k − 1)·0.1 s is 0.1 s to a few ulp of k·0.1).
        let dt = row.t1 - row.t0;
        let c_nb: Matrix3<f64> =
            body_to_nav(&c_vn, f64::to_radians(o), f64::to_radians(i)).transpose();
        // An independent form of the same matrix: R_x(−i)·R_z(−o)·C_v^nᵀ.
        let c_nb2 = rot_x(-f64::to_radians(i)) * rot_z(-f64::to_radians(o)) * c_vn.transpose();
        assert!((c_nb - c_nb2).amax() < 1e-15);
        let want = c_nb * site.omega_ie_n * dt;
        assert!(
            (row.dtheta - want).amax() < 1e-15,
            "row {k}: {:?}",
            row.dtheta - want
        );
        let g_dt = site.gravity_mps2 * dt;
        assert!(
            (row.dv.norm() - g_dt).abs() < 1e-15 * g_dt * 10.0,
            "row {k}"
        );
        assert!((row.dv - c_nb * Vector3::new(0.0, 0.0, g_dt)).amax() < 1e-15);
    }
}

#[test]
fn velocity_increment_of_a_turning_row_is_the_exact_integral() {
    // An inner turn of 180° at 20 °/s from Z-up, level mount: u^b = (0, sin i, cos i), so
    // ∫ g·u^b dt over a row = g/ω·(0, cos i0 − cos i1, sin i1 − sin i0).
    let model = base_model();
    let site = Site::new(&model.site, &model.earth);
    let design = one_run(
        vec![
            rins_mvm_trials::TableLeg::Dwell { dur_s: 1.0 },
            mv(Gimbal::Inner, 180.0, 20.0),
        ],
        vec![hold(25.0, 100.0)],
        20.0,
        0.0,
    );
    let mut rows = RunRows::new(Setup::new(&model, &design), &design, &design.runs[0], &[]);
    let mut row = Row::default();
    let w = 20f64.to_radians();
    let g = site.gravity_mps2;
    for k in [11, 12, 40, 100] {
        rows.row(k, &mut row);
        let i0 = w * (row.t0 - 1.0).max(0.0);
        let i1 = w * (row.t1 - 1.0);
        // (cos i0 − cos i1, sin i1 − sin i0) as products, free of cancellation.
        let (m, h) = (0.5 * (i0 + i1), 0.5 * (i1 - i0));
        let want = Vector3::new(0.0, 2.0 * m.sin() * h.sin(), 2.0 * m.cos() * h.sin()) * (g / w)
            // the row's part before the move started (row 11 only): Z-up
            + Vector3::new(0.0, 0.0, g * (1.0 - row.t0).max(0.0));
        // To the rounding of the angles and the quadrature sum (a few ulp of g·Δt).
        assert!(
            (row.dv - want).amax() < 1e-14 * g * 0.1,
            "row {k}: {:?}",
            row.dv - want
        );
        // A midpoint rule, g·u^b(t_mid)·Δt, would be off by (ωΔt)²/24 of g·Δt: 5e-6 here, a
        // bias of 50 µg over the row, far above a row's VRW.
        if k > 11 {
            let im = 0.5 * (i0 + i1);
            let mid = Vector3::new(0.0, im.sin(), im.cos()) * (g * (row.t1 - row.t0));
            let rel = (mid - row.dv).norm() / row.dv.norm();
            let expect = (w * 0.1f64).powi(2) / 24.0;
            assert!((rel / expect - 1.0).abs() < 1e-3, "{rel} vs {expect}");
        }
    }
}
