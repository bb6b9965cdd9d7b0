//! The temperature campaign (Section 4.1, Figure 8): Z-up/Z-down calibrations at many chamber
//! temperatures, and a third-order polynomial δβ(T) per axis for real-time compensation.
//!
//! The polynomial's variable is the gyro block temperature the IMU reports during the Z-down run
//! (δβ is the Z-down bias relative to Z-up, and the navigator compensates with the temperature
//! it reads), referenced to `ref_temp_c`.

use nalgebra::{DMatrix, DVector, Matrix4, Vector4};
use rins_plant::effects::gyro::PositionBiasSpec;
use serde::Serialize;

use crate::calibration::{Calibration, CalibrationError};

/// One campaign point.
#[derive(Clone, Debug, Serialize)]
pub struct CampaignRun {
    /// Chamber temperature, °C.
    pub chamber_c: f64,
    /// Gyro block temperatures during the Z-down run, °C.
    pub block_temp_c: [f64; 3],
    /// The calibration.
    pub calibration: Calibration,
}

/// A cubic fit of one axis with its covariance.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct AxisFit {
    /// Coefficients c₀…c₃ of δβ = Σ c_k (T − T_ref)^k, °/h/K^k.
    pub coef: [f64; 4],
    /// Their covariance.
    pub cov: [[f64; 4]; 4],
    /// χ²/(n − 4) of the weighted fit.
    pub chi2_per_dof: f64,
}

impl AxisFit {
    /// Value and 1σ at temperature offset `dt` = T − T_ref.
    pub fn eval(&self, dt: f64) -> (f64, f64) {
        let x = Vector4::new(1.0, dt, dt * dt, dt * dt * dt);
        let v = Vector4::from(self.coef).dot(&x);
        let var = (x.transpose() * Matrix4::from_fn(|i, j| self.cov[i][j]) * x)[(0, 0)];
        (v, var.max(0.0).sqrt())
    }
}

/// The campaign result.
#[derive(Clone, Debug, Serialize)]
pub struct Campaign {
    /// Every run.
    pub runs: Vec<CampaignRun>,
    /// Reference temperature of the fit, °C.
    pub ref_temp_c: f64,
    /// Per-axis cubic fits.
    pub fits: [AxisFit; 3],
    /// Wall time, s.
    pub wall_s: f64,
}

/// Why a campaign could not run.
#[derive(Debug, thiserror::Error)]
pub enum CampaignError {
    /// A temperature outside the thermal model's range.
    #[error(
        "campaign temperature {temp_c} °C (run {index}) is outside the thermal model's range [{min}, {max}] °C"
    )]
    TemperatureOutOfRange {
        /// Offending temperature.
        temp_c: f64,
        /// Run index.
        index: usize,
        /// Range minimum.
        min: f64,
        /// Range maximum.
        max: f64,
    },
    /// Too few runs for a cubic.
    #[error("a third-order fit needs at least 5 campaign runs, got {0}")]
    TooFewRuns(usize),
    /// A calibration failed.
    #[error("run at {temp_c} °C: {source}")]
    Run {
        /// Temperature.
        temp_c: f64,
        /// Cause.
        source: CalibrationError,
    },
}

/// The third-order δβ(T) fit per axis over the campaign's runs (`wall_s`: how long they took).
pub fn fit_campaign(runs: Vec<CampaignRun>, ref_temp_c: f64, wall_s: f64) -> Campaign {
    let fits = [0, 1, 2].map(|i| fit_axis(&runs, i, ref_temp_c));
    Campaign {
        runs,
        ref_temp_c,
        fits,
        wall_s,
    }
}

/// Weighted least-squares cubic (weights 1/SE²); covariance scaled by χ²/dof when above 1.
fn fit_axis(runs: &[CampaignRun], axis: usize, ref_c: f64) -> AxisFit {
    let n = runs.len();
    let x = DMatrix::from_fn(n, 4, |r, j| {
        (runs[r].block_temp_c[axis] - ref_c).powi(j as i32)
    });
    let w = DVector::from_fn(n, |r, _| {
        let se = runs[r].calibration.delta_beta_se_dph[axis];
        if se > 0.0 { 1.0 / (se * se) } else { 1.0 }
    });
    let y = DVector::from_fn(n, |r, _| runs[r].calibration.delta_beta_dph[axis]);
    let xw = DMatrix::from_fn(n, 4, |r, j| x[(r, j)] * w[r]);
    let normal = x.transpose() * &xw;
    let inv = normal
        .clone()
        .try_inverse()
        .unwrap_or_else(|| DMatrix::from_diagonal_element(4, 4, f64::INFINITY));
    let b = &inv * (xw.transpose() * &y);
    let res = &y - &x * &b;
    let chi2 = (0..n).map(|r| res[r] * res[r] * w[r]).sum::<f64>() / (n as f64 - 4.0).max(1.0);
    let scale = chi2.max(1.0);
    AxisFit {
        coef: [b[0], b[1], b[2], b[3]],
        cov: std::array::from_fn(|i| std::array::from_fn(|j| inv[(i, j)] * scale)),
        chi2_per_dof: chi2,
    }
}

impl Campaign {
    /// The fitted compensation as the plant's own position-bias term (loadable by plant and
    /// navigator: it is the `[sensor.gyro.position_bias]` table of a scenario file).
    pub fn compensation(&self) -> PositionBiasSpec {
        PositionBiasSpec {
            enabled: true,
            dph: self.fits.map(|f| f.coef[0]),
            ref_temp_c: self.ref_temp_c,
            dph_per_k: self.fits.map(|f| f.coef[1]),
            dph_per_k2: self.fits.map(|f| f.coef[2]),
            dph_per_k3: self.fits.map(|f| f.coef[3]),
            ..PositionBiasSpec::default()
        }
    }
}
