//! Rotation schemes as data: a list of gimbal moves with dwells, and the schemes the paper uses.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use super::gimbal::{GimbalAngles, GimbalAxis, body_to_nav};
use crate::units::DEG;

/// One step of a rotation scheme: rotate one gimbal by `angle_deg` (signed), then dwell.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationStep {
    /// Gimbal to move.
    pub axis: GimbalAxis,
    /// Signed rotation angle, degrees (non-zero, |angle| ≤ 3600).
    pub angle_deg: f64,
    /// Cruise rate, °/s, in (0, 100].
    pub rate_dps: f64,
    /// Stationary time after the move, s (≥ 0). The paper's T_s.
    pub dwell_s: f64,
}

/// How the table moves over a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SchemeSpec {
    /// Scheme family: `sixteen-position` (Eq. 5–6), `eight-position`, `continuous` (single axis),
    /// `static`, `z-up-calibration` (Fig. 4), `z-down-calibration` (Fig. 5) or `steps`.
    pub kind: SchemeKind,
    /// Cruise rate ω_r for built-in schemes, °/s. Paper: 2.
    pub rate_dps: f64,
    /// Acceleration limit of the table, °/s². `inf` gives constant-rate moves as in Eq. 6.
    pub accel_dps2: f64,
    /// Dwell T_s at each position for built-in schemes, s. Paper: 180 (16-position), 600 (calibration).
    pub dwell_s: f64,
    /// Stationary time before the first move (e.g. alignment), s.
    pub lead_dwell_s: f64,
    /// Gimbal to spin for `continuous`.
    pub axis: GimbalAxis,
    /// Initial outer gimbal angle, degrees (used by `steps`, `continuous`, `static`).
    pub initial_outer_deg: f64,
    /// Initial inner gimbal angle, degrees (used by `steps`, `continuous`, `static`).
    pub initial_inner_deg: f64,
    /// Repeat the step list forever (`steps`; built-in periodic schemes always repeat).
    pub repeat: bool,
    /// Explicit moves for `steps`.
    pub steps: Vec<RotationStep>,
}

/// Scheme families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SchemeKind {
    /// Dual-axis 16-position scheme of Eq. 5–6 and Table 2.
    SixteenPosition,
    /// Dual-axis 8-position scheme: sequences 1–8 of the 16-position scheme.
    EightPosition,
    /// Single-axis continuous rotation at `rate_dps`.
    Continuous,
    /// Table held at the initial angles.
    Static,
    /// Fig. 4: Z up, azimuth 0° for `lead_dwell_s + dwell_s`, rotate 180° about Z, dwell.
    ZUpCalibration,
    /// Fig. 5: Z down (Eq. 18), rotate 180° about Z, dwell.
    ZDownCalibration,
    /// The explicit `steps` list.
    Steps,
}

impl Default for SchemeSpec {
    /// The paper's 16-position scheme: ω_r = 2°/s, T_s = 180 s.
    fn default() -> Self {
        Self {
            kind: SchemeKind::SixteenPosition,
            rate_dps: 2.0,
            accel_dps2: 20.0,
            dwell_s: 180.0,
            lead_dwell_s: 0.0,
            axis: GimbalAxis::Outer,
            initial_outer_deg: 0.0,
            initial_inner_deg: 0.0,
            repeat: true,
            steps: Vec::new(),
        }
    }
}

/// A scheme resolved to explicit gimbal moves.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedScheme {
    /// Gimbal angles at t = 0.
    pub initial: GimbalAngles,
    /// Stationary time before the first move, s.
    pub lead_dwell_s: f64,
    /// Moves (angles in rad, rates in rad/s).
    pub steps: Vec<ResolvedStep>,
    /// Whether the step list repeats.
    pub repeat: bool,
    /// Continuous rotation (axis, rate rad/s) instead of steps.
    pub continuous: Option<(GimbalAxis, f64)>,
    /// Acceleration limit, rad/s².
    pub accel_rps2: f64,
}

/// A move in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResolvedStep {
    /// Gimbal to move.
    pub axis: GimbalAxis,
    /// Signed angle, rad.
    pub angle_rad: f64,
    /// Cruise rate, rad/s.
    pub rate_rps: f64,
    /// Dwell after the move, s.
    pub dwell_s: f64,
}

/// Body-frame rotation axes of the 16 sequences, Eq. 6: +1/-1 about body x or z.
/// Entry t-1 is (axis index 0 = x, 2 = z; sign).
pub const EQ6_BODY_RATES: [(usize, f64); 16] = [
    (2, 1.0),  // 1: +z
    (0, 1.0),  // 2: +x
    (2, -1.0), // 3: -z
    (0, -1.0), // 4: -x
    (0, -1.0), // 5: -x
    (2, -1.0), // 6: -z
    (0, 1.0),  // 7: +x
    (2, 1.0),  // 8: +z
    (2, -1.0), // 9: -z
    (0, -1.0), // 10: -x
    (2, 1.0),  // 11: +z
    (0, 1.0),  // 12: +x
    (0, 1.0),  // 13: +x
    (2, 1.0),  // 14: +z
    (0, -1.0), // 15: -x
    (2, -1.0), // 16: -z
];

/// The four dwell attitudes of Eq. 5 (body to ENU with the vehicle level, azimuth 0).
pub fn eq5_position(name: char) -> Matrix3<f64> {
    match name {
        'A' => Matrix3::identity(),
        'B' => Matrix3::from_diagonal(&Vector3::new(-1.0, -1.0, 1.0)),
        'C' => Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, -1.0)),
        'D' => Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0)),
        _ => panic!("Eq. 5 defines positions A-D only"),
    }
}

/// Converts body-frame 180° rotations (Eq. 6) into gimbal moves. A body-x rotation is the inner
/// gimbal; a body-z rotation is the outer gimbal, whose axis in body coordinates is
/// R_x(inner)ᵀ·ẑ = [0, sin(inner), cos(inner)], so its direction flips when the IMU is Z-down.
fn gimbal_moves_from_body_rates(
    seq: &[(usize, f64)],
    rate_rps: f64,
    dwell_s: f64,
) -> Vec<ResolvedStep> {
    let mut inner = 0.0_f64;
    seq.iter()
        .map(|&(axis, sign)| {
            let (gimbal, dir) = if axis == 0 {
                (GimbalAxis::Inner, sign)
            } else {
                (GimbalAxis::Outer, sign * inner.cos().signum())
            };
            let angle = dir * 180.0 * DEG;
            if gimbal == GimbalAxis::Inner {
                inner += angle;
            }
            ResolvedStep {
                axis: gimbal,
                angle_rad: angle,
                rate_rps,
                dwell_s,
            }
        })
        .collect()
}

impl SchemeSpec {
    /// Resolves the spec to explicit gimbal moves.
    pub fn resolve(&self) -> ResolvedScheme {
        let rate = self.rate_dps * DEG;
        let accel = self.accel_dps2 * DEG;
        let start = GimbalAngles::new(self.initial_outer_deg * DEG, self.initial_inner_deg * DEG);
        let base = ResolvedScheme {
            initial: start,
            lead_dwell_s: self.lead_dwell_s,
            steps: Vec::new(),
            repeat: false,
            continuous: None,
            accel_rps2: accel,
        };
        let half_turn = |axis| ResolvedStep {
            axis,
            angle_rad: 180.0 * DEG,
            rate_rps: rate,
            dwell_s: self.dwell_s,
        };
        match self.kind {
            SchemeKind::SixteenPosition | SchemeKind::EightPosition => {
                let n = if self.kind == SchemeKind::SixteenPosition {
                    16
                } else {
                    8
                };
                ResolvedScheme {
                    initial: GimbalAngles::new(0.0, 0.0),
                    steps: gimbal_moves_from_body_rates(&EQ6_BODY_RATES[..n], rate, self.dwell_s),
                    repeat: true,
                    ..base
                }
            }
            SchemeKind::Continuous => ResolvedScheme {
                continuous: Some((self.axis, rate)),
                ..base
            },
            SchemeKind::Static => base,
            SchemeKind::ZUpCalibration => ResolvedScheme {
                initial: GimbalAngles::new(0.0, 0.0),
                lead_dwell_s: self.lead_dwell_s + self.dwell_s,
                steps: vec![half_turn(GimbalAxis::Outer)],
                ..base
            },
            SchemeKind::ZDownCalibration => ResolvedScheme {
                initial: GimbalAngles::new(180.0 * DEG, 180.0 * DEG),
                lead_dwell_s: self.lead_dwell_s + self.dwell_s,
                steps: vec![half_turn(GimbalAxis::Outer)],
                ..base
            },
            SchemeKind::Steps => ResolvedScheme {
                steps: self
                    .steps
                    .iter()
                    .map(|s| ResolvedStep {
                        axis: s.axis,
                        angle_rad: s.angle_deg * DEG,
                        rate_rps: s.rate_dps * DEG,
                        dwell_s: s.dwell_s,
                    })
                    .collect(),
                repeat: self.repeat,
                ..base
            },
        }
    }
}

/// Builds the body attitude C_b^n at each dwell of a resolved scheme (vehicle level, azimuth 0).
pub fn dwell_attitudes(scheme: &ResolvedScheme) -> Vec<Matrix3<f64>> {
    let mut angles = scheme.initial;
    scheme
        .steps
        .iter()
        .map(|s| {
            angles = angles.moved(s.axis, s.angle_rad);
            body_to_nav(&Matrix3::identity(), angles)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sixteen_position_visits_eq7_dwell_order() {
        let scheme = SchemeSpec::default().resolve();
        let order = "BCDADCBABCDADCBA"; // the dwell order of Eq. 7
        for (c, name) in dwell_attitudes(&scheme).iter().zip(order.chars()) {
            assert_relative_eq!(*c, eq5_position(name), epsilon = 1e-12);
        }
    }

    #[test]
    fn calibration_schemes_match_eq16_and_eq18() {
        for (kind, first, second) in [
            (SchemeKind::ZUpCalibration, 'A', 'B'),
            (SchemeKind::ZDownCalibration, 'C', 'D'),
        ] {
            let spec = SchemeSpec {
                kind,
                dwell_s: 600.0,
                ..SchemeSpec::default()
            };
            let s = spec.resolve();
            assert_relative_eq!(
                body_to_nav(&Matrix3::identity(), s.initial),
                eq5_position(first),
                epsilon = 1e-12
            );
            assert_relative_eq!(
                dwell_attitudes(&s)[0],
                eq5_position(second),
                epsilon = 1e-12
            );
        }
    }
}
