//! The analytic verification report: figures, pass/fail checks, text and JSON renderings.

use serde::Serialize;

use crate::analytic::{Eq8Report, Eq11Report, eq8, eq11};
use crate::table2::{Table2Report, compare};

/// One named check with its figure and limit.
#[derive(Clone, Debug, Serialize)]
pub struct Check {
    /// What is checked.
    pub name: String,
    /// Measured figure.
    pub value: f64,
    /// Pass limit (value ≤ limit).
    pub limit: f64,
    /// Whether it passed.
    pub pass: bool,
}

impl Check {
    /// A check that passes when `value <= limit`.
    pub fn at_most(name: &str, value: f64, limit: f64) -> Self {
        Self {
            name: name.into(),
            value,
            limit,
            pass: value.is_finite() && value <= limit,
        }
    }
}

/// `rins verify analytic`.
#[derive(Clone, Debug, Serialize)]
pub struct AnalyticReport {
    /// Eq. 8 cancellation.
    pub eq8: Eq8Report,
    /// Eq. 11 residual.
    pub eq11: Eq11Report,
    /// Table 2 against the kinematics.
    pub table2: Table2Report,
    /// Pass/fail checks.
    pub checks: Vec<Check>,
}

impl AnalyticReport {
    /// Runs every analytic check with the paper's values (T_s = 180 s, δβ = 0.005 °/h).
    pub fn run() -> Self {
        let eq8 = eq8();
        let eq11 = eq11([0.005; 3], 180.0);
        let table2 = compare();
        let checks = vec![
            Check::at_most("eq8 cancellation ratio", eq8.cancellation_ratio, 1e-9),
            Check::at_most(
                "eq8 accel SF vertical: numeric vs closed form",
                eq8.accel_scale_factor_vertical.rel_err,
                1e-9,
            ),
            Check::at_most(
                "eq11 stationary z vs -8 Ts dbz (relative)",
                eq11.stationary_z_rel_err,
                1e-9,
            ),
            Check::at_most(
                "eq11 stationary |x|,|y| / |z|",
                eq11.stationary_xy_over_z,
                1e-12,
            ),
            Check::at_most(
                "eq11 paper example |z| - 0.002 deg",
                (eq11.expected_z_deg.abs() - 0.002).abs(),
                1e-12,
            ),
            Check::at_most(
                "eq11 rotation numeric vs closed form (relative)",
                eq11.rotation_rel_err,
                1e-6,
            ),
        ];
        Self {
            eq8,
            eq11,
            table2,
            checks,
        }
    }

    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.checks.iter().all(|c| c.pass)
    }

    /// Human-readable report.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let e8 = &self.eq8;
        s += &format!(
            "Eq. 8  cancellation over one 16-position cycle ({:.0} s)\n",
            e8.cycle_s
        );
        for c in &e8.cases {
            s += &format!(
                "  {:<22} accel {:>5} deg/s^2   ratio {:9.2e}   integral [{:+.2e}, {:+.2e}, {:+.2e}]\n",
                c.errors,
                c.accel_dps2,
                c.cancellation_ratio,
                c.integral[0],
                c.integral[1],
                c.integral[2]
            );
        }
        let v = &e8.accel_scale_factor_vertical;
        s += &format!(
            "  accel scale factor, vertical: {:+.6e} m/s per cycle (closed form {:+.6e}), i.e. {:.2} ug of vertical bias:\n  rectified under gravity, not cancelled by rotation (the paper says accelerometer errors cancel 'in the same way')\n",
            v.numeric_mps, v.closed_form_mps, v.equivalent_bias_ug
        );
        let e = &self.eq11;
        s += &format!(
            "\nEq. 11 position-dependent bias, dbeta = {:?} deg/h, Ts = {} s\n",
            e.delta_beta_dph, e.dwell_s
        );
        s += &format!(
            "  stationary      [{:+.6e}, {:+.6e}, {:+.6e}] rad\n  expected z      {:+.6e} rad = {:+.6} deg (paper: ~0.002 deg)\n",
            e.stationary_rad[0],
            e.stationary_rad[1],
            e.stationary_rad[2],
            e.expected_z_rad,
            e.expected_z_deg
        );
        s += &format!(
            "  rotation        [{:+.6e}, {:+.6e}, {:+.6e}] rad (numeric, constant-rate moves)\n  closed form     [{:+.6e}, {:+.6e}, {:+.6e}] rad\n",
            e.rotation_rad[0],
            e.rotation_rad[1],
            e.rotation_rad[2],
            e.rotation_closed_form_rad[0],
            e.rotation_closed_form_rad[1],
            e.rotation_closed_form_rad[2]
        );
        s += &format!(
            "  full cycle      [{:+.6e}, {:+.6e}, {:+.6e}] rad; rotation phases cancel: {}\n  accel-limited rotation [{:+.6e}, {:+.6e}, {:+.6e}] rad\n",
            e.full_cycle_rad[0],
            e.full_cycle_rad[1],
            e.full_cycle_rad[2],
            e.rotation_phases_cancel,
            e.rotation_accel_limited_rad[0],
            e.rotation_accel_limited_rad[1],
            e.rotation_accel_limited_rad[2]
        );
        let t = &self.table2;
        s += &format!(
            "\nTable 2 vs kinematics of Eq. 5-6: {} entries compared, {} mismatches\n",
            t.entries_compared,
            t.mismatches.len()
        );
        for m in &t.mismatches {
            s += &format!(
                "  (C_b^n)_{:<2} row {} col {}: printed {:>3} = {:+.4}, kinematics give {:+.4} (at {} deg); the kinematics are right\n",
                m.sequence, m.row, m.col, m.printed_expr, m.printed, m.derived, m.probe_deg
            );
        }
        s += "\nChecks\n";
        for c in &self.checks {
            s += &format!(
                "  [{}] {:<48} {:10.3e} <= {:.0e}\n",
                if c.pass { "pass" } else { "FAIL" },
                c.name,
                c.value,
                c.limit
            );
        }
        s
    }
}
