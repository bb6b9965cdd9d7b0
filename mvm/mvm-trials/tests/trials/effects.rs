//! Row integrals of the effects against closed forms and independent quadratures.

use rins_mvm_trials::effect_error::row_error;
use rins_mvm_trials::quadrature;
use rins_mvm_trials::row::{Row, RunRows, Setup};
use rins_mvm_trials::units::DPH;
use rins_mvm_trials::{ChamberLeg, Gimbal, HiddenEffect, TableLeg};

use super::{base_model, hold, mv, one_run};

#[test]
fn temperature_rate_bias_integrates_to_k_times_the_change() {
    // A chamber step: the blocks' temperatures change fastest a few minutes after it.
    let chamber = vec![
        hold(10.0, 60.0),
        ChamberLeg::Ramp {
            to_c: 45.0,
            rate_k_per_min: 10.0,
        },
    ];
    let design = one_run(
        vec![TableLeg::Dwell { dur_s: 2000.0 }],
        chamber,
        2000.0,
        0.0,
    );
    let model = base_model();
    let setup = Setup::new(&model, &design);
    let mut rows = RunRows::new(setup, &design, &design.runs[0], &[]);
    let k = [120.0, -80.0, 40.0];
    let effect = HiddenEffect::TempRateBias { dph_per_k_per_s: k };
    let mut row = Row::default();
    for r in [601, 1000, 2700, 12000] {
        rows.row(r, &mut row);
        let (e, _) = row_error(&effect, &row, &rows.thermal, setup.gravity_mps2);
        for i in 0..3 {
            // The independent reference: quadrature of K·dT/dt (the closed form's derivative)
            // over the row, on 20 sub-intervals.
            let n = 20;
            let h = (row.t1 - row.t0) / n as f64;
            let q: f64 = (0..n)
                .map(|j| {
                    let a = row.t0 + j as f64 * h;
                    quadrature::integrate(a, a + h, |t| rows.thermal.block_rate(i, t))
                })
                .sum();
            let want = k[i] * DPH * q;
            // K·ΔT is a difference of closed-form temperatures whose terms reach tens of K: it
            // carries their rounding (~1e-13 K) besides the quadrature's relative accuracy.
            assert!(
                (e[i] - want).abs() <= 1e-9 * want.abs() + k[i].abs() * DPH * 1e-13,
                "row {r} axis {i}: {} vs {want}",
                e[i]
            );
            assert!(want.abs() > 0.0);
        }
    }
}

#[test]
fn post_move_transient_row_integral_is_the_closed_form() {
    // Dwell 100 s, a 90° move at 10 °/s (9 s), then dwell.
    let table = vec![
        TableLeg::Dwell { dur_s: 100.0 },
        mv(Gimbal::Outer, 90.0, 10.0),
    ];
    let design = one_run(table, vec![hold(25.0, 100.0)], 400.0, 0.0);
    let model = base_model();
    let setup = Setup::new(&model, &design);
    let mut rows = RunRows::new(setup, &design, &design.runs[0], &[]);
    let (amp, tau) = ([0.3, -0.2, 0.5], 45.0);
    let effect = HiddenEffect::PostMoveTransient {
        dph: amp,
        tau_s: tau,
    };
    let mut row = Row::default();
    // Before any move s counts from the run's start; while moving b = A; after the stop at
    // 109 s, s counts from it.
    for (r, stop) in [
        (1, Some(0.0)),
        (500, Some(0.0)),
        (1050, None),
        (1091, Some(109.0)),
        (1500, Some(109.0)),
        (3999, Some(109.0)),
    ] {
        rows.row(r, &mut row);
        let (e, _) = row_error(&effect, &row, &rows.thermal, setup.gravity_mps2);
        for i in 0..3 {
            let want = match stop {
                Some(s) => {
                    amp[i] * DPH * tau * ((-(row.t0 - s) / tau).exp() - (-(row.t1 - s) / tau).exp())
                }
                None => amp[i] * DPH * (row.t1 - row.t0),
            };
            assert!(
                (e[i] - want).abs() <= 1e-12 * want.abs(),
                "row {r} axis {i}: {} vs {want}",
                e[i]
            );
        }
    }
}

#[test]
fn generate_adds_the_effect_error_to_the_increments() {
    let table = vec![
        TableLeg::Dwell { dur_s: 50.0 },
        mv(Gimbal::Inner, 180.0, 10.0),
    ];
    let design = one_run(
        table,
        vec![
            hold(20.0, 30.0),
            ChamberLeg::Ramp {
                to_c: 40.0,
                rate_k_per_min: 5.0,
            },
        ],
        200.0,
        30.0,
    );
    let model = super::quiet_model();
    let effect = HiddenEffect::UpProductBias {
        a: 0,
        b: 2,
        dph: [1.0, 0.0, -2.0],
    };
    let without = rins_mvm_trials::generate(&model, &design, &[], 1);
    let with = rins_mvm_trials::generate(&model, &design, std::slice::from_ref(&effect), 1);
    let setup = Setup::new(&model, &design);
    let mut rows = RunRows::new(setup, &design, &design.runs[0], &[]);
    let mut row = Row::default();
    let mut seen = 0.0f64;
    for k in 1..=rows.rows {
        rows.row(k, &mut row);
        let (e, _) = row_error(&effect, &row, &rows.thermal, setup.gravity_mps2);
        for i in 0..3 {
            let d = with.dtheta_rad[i][k - 1] - without.dtheta_rad[i][k - 1];
            assert!(
                (d - e[i]).abs() <= 1e-9 * e[i].abs() + 1e-19,
                "row {k} axis {i}"
            );
            seen = seen.max(e[i].abs());
        }
        assert_eq!(with.dv_mps[0][k - 1], without.dv_mps[0][k - 1]);
    }
    // Roll 30°: u_x = −sin 30°·… is non-zero, so the effect shows.
    assert!(seen > 1e-10);
}
