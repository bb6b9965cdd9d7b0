//! Text of a system-level calibration (`rins calibrate`, Section 3.2) and of a temperature
//! campaign (`rins campaign`, Section 4.1).

use std::fmt::Write;

use rins_navigation::calibration::Calibration;
use rins_navigation::campaign::Campaign;

use super::RenderText;
use crate::truth::CalibrationTruth;

/// A calibration with the settings it ran with (the result itself does not carry them).
pub struct CalibrationRun<'a> {
    /// The estimates.
    pub result: &'a Calibration,
    /// The plant's δβ beside the estimate, when known.
    pub truth: Option<&'a CalibrationTruth>,
    /// Drift estimator name (`coupled` or `paper`).
    pub estimator: &'a str,
    /// Navigation time in each position, s.
    pub segment_s: f64,
}

impl RenderText for CalibrationRun<'_> {
    fn render_text(&self) -> String {
        let (r, mut s) = (self.result, String::new());
        // Writing to a String cannot fail.
        let _ = writeln!(
            s,
            "System-level indirect calibration ({} estimator), {} s per position",
            self.estimator, self.segment_s
        );
        for (name, e) in [("Z-up   (Eq. 17)", &r.up), ("Z-down (Eq. 19)", &r.down)] {
            let _ = writeln!(
                s,
                "  {name}: beta = [{:+.5}, {:+.5}, {:+.5}] +- [{:.5}, {:.5}, {:.5}] deg/h",
                e.beta_dph[0], e.beta_dph[1], e.beta_dph[2], e.se_dph[0], e.se_dph[1], e.se_dph[2]
            );
            for (k, f) in e.segments.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "      segment {}: dVdd_E {:+.3e} +- {:.1e}, dVdd_N {:+.3e} +- {:.1e} m/s^3, dphi_U {:+.3e} +- {:.1e} rad/s (chi2/dof {:.2} {:.2} {:.2})",
                    k + 1,
                    f.dvdd_e.slope,
                    f.dvdd_e.se,
                    f.dvdd_n.slope,
                    f.dvdd_n.se,
                    f.phi_u_rate.slope,
                    f.phi_u_rate.se,
                    f.dvdd_e.chi2_per_dof,
                    f.dvdd_n.chi2_per_dof,
                    f.phi_u_rate.chi2_per_dof
                );
            }
        }
        let (d, e) = (r.delta_beta_dph, r.delta_beta_se_dph);
        let _ = writeln!(
            s,
            "  delta-beta = beta_down - beta_up = [{:+.5}, {:+.5}, {:+.5}] +- [{:.5}, {:.5}, {:.5}] deg/h",
            d[0], d[1], d[2], e[0], e[1], e[2]
        );
        if let Some(t) = self.truth {
            let (p, k) = (t.delta_beta_dph, t.error_se);
            let _ = writeln!(
                s,
                "  the plant's delta-beta = [{:+.5}, {:+.5}, {:+.5}] deg/h: the estimate is off by [{:.1}, {:.1}, {:.1}] SE",
                p[0], p[1], p[2], k[0], k[1], k[2]
            );
        }
        s
    }
}

impl RenderText for Campaign {
    fn render_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "Temperature campaign: {} runs ({:.1} s wall)",
            self.runs.len(),
            self.wall_s
        );
        let _ = writeln!(
            s,
            "  {:>9} {:>27} {:>27} {:>27}",
            "chamber", "dbeta_x +- SE (deg/h)", "dbeta_y", "dbeta_z"
        );
        for r in &self.runs {
            let (d, e) = (
                r.calibration.delta_beta_dph,
                r.calibration.delta_beta_se_dph,
            );
            let _ = writeln!(
                s,
                "  {:>7.2} C {:>+12.5} +- {:>9.5} {:>+12.5} +- {:>9.5} {:>+12.5} +- {:>9.5}",
                r.chamber_c, d[0], e[0], d[1], e[1], d[2], e[2]
            );
        }
        for (i, f) in self.fits.iter().enumerate() {
            let _ = writeln!(
                s,
                "  fit {}: c0..c3 = [{:+.3e}, {:+.3e}, {:+.3e}, {:+.3e}] (T - {} C), chi2/dof {:.2}",
                ["x", "y", "z"][i],
                f.coef[0],
                f.coef[1],
                f.coef[2],
                f.coef[3],
                self.ref_temp_c,
                f.chi2_per_dof
            );
        }
        s
    }
}
