//! The paper's system-level indirect calibration (Section 3.2, Figures 4–5, Eq. 13–19).
//!
//! At Z-up (and again at Z-down): self-alignment, 10 min of navigation at azimuth 0, a 180° turn
//! about Z, 10 min more. In each segment the drift of the horizontal acceleration error (δV̈_E,
//! δV̈_N, the second derivative of the velocity error) and of the up-axis attitude error (φ̇_U) is
//! fitted, and Eq. 17 (Z-up) / Eq. 19 (Z-down) give the bias. δβ = β_down − β_up.
//!
//! Signs, from Eq. 13 (φ̇ = −C_b^n β) and Eq. 15 (δV̈_E = −g φ̇_N, δV̈_N = g φ̇_E):
//! Z-up, C₁ = I, C₂ = diag(−1,−1,1): β_x = (δV̈_N2 − δV̈_N1)/2g, β_y = −(δV̈_E2 − δV̈_E1)/2g,
//! β_z = −(φ̇_U1 + φ̇_U2)/2. Z-down, C₁ = diag(−1,1,−1), C₂ = diag(1,−1,−1):
//! β_x = −(δV̈_N2 − δV̈_N1)/2g, β_y = −(δV̈_E2 − δV̈_E1)/2g, β_z = (φ̇_U1 + φ̇_U2)/2.
//! These are Eq. 17 and 19 exactly as printed: the derivation confirms their signs.
//!
//! φ_U is taken against the rate table's reference attitude (the plant's truth), as in a lab
//! calibration on a rate table.
//!
//! Eq. 13 and 15 neglect the Schuler, Earth-rate and Coriolis couplings of Eq. 12 and 14. Over
//! 10 min they are not negligible: after the turn the accelerometer bias changes sign in the
//! navigation frame and starts a Schuler oscillation whose curvature is as large as the gyro
//! signal. The default [`Estimator::Coupled`] removes the known couplings from the fitted
//! series, using the navigation velocities and the reference attitude:
//! ã_N = a_N + ∫[ω_s² δv_N + g(Ω_N φ_U − Ω_U φ_N)] dt + 2Ω_U δv_E has drift g·φ̇_E|gyro = δV̈_N,
//! ã_E = a_E + ∫[ω_s² δv_E − g Ω_U φ_E] dt − 2Ω_U δv_N has drift δV̈_E, and
//! φ̃_U = φ_U − ∫[Ω_N φ_E + tan L δv_E/R] dt has drift φ̇_U|gyro. What is left is the gyro term
//! plus exactly a random walk (ARW) and white noise (VRW), which the GLS fit weighs correctly.
//! [`Estimator::Paper`] fits the raw series as Eq. 13–15 do.

use rins_plant::SensorSpec;
use rins_plant::earth::{Site, normal_gravity};
use rins_plant::units::{DPH, DPSH, UG};
use serde::Serialize;

use crate::alignment::Alignment;
use crate::errors::NavRecord;
use crate::fit::{DriftFit, fit_drift};

/// The two calibration attitudes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CalPosition {
    /// Figure 4 / Eq. 16.
    ZUp,
    /// Figure 5 / Eq. 18.
    ZDown,
}

/// How the segment drifts are estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Estimator {
    /// Eq. 13–15 as printed: raw acceleration error and φ_U drifts.
    Paper,
    /// With the Schuler, Earth-rate and Coriolis couplings removed (default).
    Coupled,
}

/// Calibration timing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CalibrationConfig {
    /// Drift estimator.
    pub estimator: Estimator,
    /// Alignment before the first segment.
    pub alignment: Alignment,
    /// Navigation time in each position, s (paper: 600).
    pub segment_s: f64,
    /// Samples of the navigation errors used by the fits, Hz.
    pub fit_rate_hz: f64,
    /// Time skipped after the turn before the second segment's fit, s.
    pub settle_s: f64,
}

impl Default for CalibrationConfig {
    fn default() -> Self {
        Self {
            estimator: Estimator::Coupled,
            alignment: Alignment::SelfAlign {
                coarse_s: 120.0,
                fine_s: 480.0,
            },
            segment_s: 600.0,
            fit_rate_hz: 1.0,
            settle_s: 5.0,
        }
    }
}

/// Why a calibration could not run.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationError {
    /// Segment too short for a drift fit.
    #[error(
        "calibration segment (scheme.dwell_s) of {segment_s} s at {rate_hz} Hz gives {samples} samples; a second-derivative fit needs at least 30 (set scheme.dwell_s ≥ {min_s} s)"
    )]
    SegmentTooShort {
        /// Segment length, s.
        segment_s: f64,
        /// Fit rate, Hz.
        rate_hz: f64,
        /// Samples it gives.
        samples: usize,
        /// Shortest usable segment, s.
        min_s: f64,
    },
    /// The calibration run itself failed (plant configuration, navigation session).
    #[error("{0}")]
    Run(String),
    /// A fit failed (degenerate data).
    #[error("the {what} fit of the {position:?} calibration failed (degenerate data)")]
    Fit {
        /// Which fit.
        what: &'static str,
        /// Where.
        position: CalPosition,
    },
}

/// Fits of one navigation segment.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SegmentFit {
    /// δV̈_E (drift of the east acceleration error), m/s³.
    pub dvdd_e: DriftFit,
    /// δV̈_N, m/s³.
    pub dvdd_n: DriftFit,
    /// φ̇_U, rad/s.
    pub phi_u_rate: DriftFit,
}

/// The bias estimated at one position.
#[derive(Clone, Debug, Serialize)]
pub struct PositionEstimate {
    /// Which position.
    pub position: CalPosition,
    /// β (x, y, z), °/h.
    pub beta_dph: [f64; 3],
    /// Standard errors, °/h.
    pub se_dph: [f64; 3],
    /// Fits of the two segments.
    pub segments: [SegmentFit; 2],
    /// Mean gyro block temperatures over the run, °C.
    pub gyro_temp_c: [f64; 3],
    /// Chamber temperature, °C.
    pub chamber_c: f64,
}

/// One Z-up + Z-down calibration.
#[derive(Clone, Debug, Serialize)]
pub struct Calibration {
    /// Z-up estimate.
    pub up: PositionEstimate,
    /// Z-down estimate.
    pub down: PositionEstimate,
    /// δβ = β_down − β_up, °/h.
    pub delta_beta_dph: [f64; 3],
    /// Standard errors of δβ, °/h.
    pub delta_beta_se_dph: [f64; 3],
}

/// Series whose drifts are δV̈_E, δV̈_N and φ̇_U (see the module notes), at the record times
/// (accelerations at the midpoints between records).
struct Series {
    t_mid: Vec<f64>,
    acc_e: Vec<f64>,
    acc_n: Vec<f64>,
    t: Vec<f64>,
    phi_u: Vec<f64>,
}

fn series(recs: &[&NavRecord], coupled: bool, lat: f64, g: f64, r_m: f64) -> Series {
    let w = rins_plant::earth::OMEGA_IE_RPS;
    let (wn, wu) = (w * lat.cos(), w * lat.sin());
    let ws2 = g / r_m;
    let mut out = Series {
        t_mid: Vec::new(),
        acc_e: Vec::new(),
        acc_n: Vec::new(),
        t: Vec::new(),
        phi_u: Vec::new(),
    };
    let (mut ie, mut inn, mut iu) = (0.0, 0.0, 0.0);
    let first = recs.first().map(|r| r.t_s).unwrap_or(0.0);
    for (k, r) in recs.iter().enumerate() {
        if k > 0 {
            let p = recs[k - 1];
            let h = r.t_s - p.t_s;
            let mid = |f: &dyn Fn(&NavRecord) -> f64| 0.5 * (f(p) + f(r));
            if coupled {
                ie += h * mid(&|x| ws2 * x.vel_err_mps[0] - g * wu * x.att_err_rad[0]);
                inn += h * mid(&|x| {
                    ws2 * x.vel_err_mps[1] + g * (wn * x.att_err_rad[2] - wu * x.att_err_rad[1])
                });
                iu += h * mid(&|x| wn * x.att_err_rad[0] + x.vel_err_mps[0] * lat.tan() / r_m);
            }
            let (ve, vn) = (
                (r.vel_err_mps[0] - p.vel_err_mps[0]) / h,
                (r.vel_err_mps[1] - p.vel_err_mps[1]) / h,
            );
            let cor = if coupled { 2.0 * wu } else { 0.0 };
            out.t_mid.push(0.5 * (p.t_s + r.t_s) - first);
            out.acc_e.push(ve + ie - cor * mid(&|x| x.vel_err_mps[1]));
            out.acc_n.push(vn + inn + cor * mid(&|x| x.vel_err_mps[0]));
        }
        out.t.push(r.t_s - first);
        out.phi_u.push(r.att_err_rad[2] - iu);
    }
    out
}

/// Estimates β at `pos` with Eq. 17 or 19 from the error records of one calibration run
/// (alignment done, then `segment_s` of navigation, the turn of `move_s`, `segment_s` more),
/// the site, the sensor noise levels the GLS weights come from, and the gyro temperatures the
/// unit reported and the chamber temperature, which are carried into the estimate.
#[allow(clippy::too_many_arguments)]
pub fn estimate_position(
    records: &[NavRecord],
    pos: CalPosition,
    cfg: &CalibrationConfig,
    site: &Site,
    sensor: &SensorSpec,
    move_s: f64,
    gyro_temp_c: [f64; 3],
    chamber_c: f64,
) -> Result<PositionEstimate, CalibrationError> {
    let total = 2.0 * cfg.segment_s + move_s;
    let g = normal_gravity(site.lat_rad, site.height_m);
    let lat = site.lat_rad;
    let r_m = (site.rm_m * site.rn_m).sqrt() + site.height_m;
    let s = sensor;
    let arw = if s.gyro.angle_random_walk.enabled {
        s.gyro
            .angle_random_walk
            .dpsh
            .iter()
            .fold(0.0_f64, |m, x| m.max(*x))
            * DPSH
    } else {
        0.0
    };
    let vrw = if s.accel.velocity_random_walk.enabled {
        s.accel
            .velocity_random_walk
            .ug_per_sqrthz
            .iter()
            .fold(0.0_f64, |m, x| m.max(*x))
            * UG
    } else {
        0.0
    };
    let dt = 1.0 / cfg.fit_rate_hz;
    let fits = |from: f64, to: f64| -> Result<SegmentFit, CalibrationError> {
        let recs: Vec<&NavRecord> = records
            .iter()
            .filter(|r| r.t_s > from && r.t_s <= to)
            .collect();
        let f = |what, r: Option<DriftFit>| {
            r.ok_or(CalibrationError::Fit {
                what,
                position: pos,
            })
        };
        let sr = series(&recs, cfg.estimator == Estimator::Coupled, lat, g, r_m);
        Ok(SegmentFit {
            dvdd_e: f(
                "east acceleration",
                fit_drift(&sr.t_mid, &sr.acc_e, g * g * arw * arw, vrw * vrw / dt),
            )?,
            dvdd_n: f(
                "north acceleration",
                fit_drift(&sr.t_mid, &sr.acc_n, g * g * arw * arw, vrw * vrw / dt),
            )?,
            phi_u_rate: f("up attitude", fit_drift(&sr.t, &sr.phi_u, arw * arw, 0.0))?,
        })
    };
    let s1 = fits(0.0, cfg.segment_s)?;
    let s2 = fits(cfg.segment_s + move_s + cfg.settle_s, total)?;
    let sign = match pos {
        CalPosition::ZUp => 1.0,
        CalPosition::ZDown => -1.0,
    };
    let beta = [
        sign * (s2.dvdd_n.slope - s1.dvdd_n.slope) / (2.0 * g),
        -(s2.dvdd_e.slope - s1.dvdd_e.slope) / (2.0 * g),
        -sign * (s1.phi_u_rate.slope + s2.phi_u_rate.slope) / 2.0,
    ];
    let hyp = |a: f64, b: f64| a.hypot(b);
    let se = [
        hyp(s1.dvdd_n.se, s2.dvdd_n.se) / (2.0 * g),
        hyp(s1.dvdd_e.se, s2.dvdd_e.se) / (2.0 * g),
        hyp(s1.phi_u_rate.se, s2.phi_u_rate.se) / 2.0,
    ];
    Ok(PositionEstimate {
        position: pos,
        beta_dph: beta.map(|b| b / DPH),
        se_dph: se.map(|e| e / DPH),
        segments: [s1, s2],
        gyro_temp_c,
        chamber_c,
    })
}
