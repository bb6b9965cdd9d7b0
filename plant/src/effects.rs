//! Sensor error effects. Each effect is a named, switchable, parameterised term.
//!
//! Every deterministic effect is linear in its parameters: its increment error on axis `i` over
//! one interval is Σ_k θ_ik · φ_ik(context). The plant evaluates the sum on its hot path; the
//! diagnosis uses the regressors φ (from [`GyroModel::regressors`] / [`AccelModel::regressors`])
//! and the coefficients θ, so one definition serves simulation, FMU parameters and diagnosis.

pub mod accel;
pub mod custom;
pub mod dwell_dependence;
pub mod encoder;
pub mod gyro;
pub mod gyro_term;
pub mod noise;
pub mod quantize;
pub mod temp_sensor;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

pub use accel::{AccelModel, AccelSpec, AccelTerm};
pub use custom::{CustomKind, CustomModel, CustomSpec};
pub use dwell_dependence::DwellDependence;
pub use gyro::{GyroModel, GyroSpec, GyroTerm};

/// What the effects see over one integration interval (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TermContext {
    /// Interval length, s.
    pub dt_s: f64,
    /// True angular increment ∫ω_ib^b dt, rad.
    pub dtheta_rad: Vector3<f64>,
    /// True velocity increment ∫f^b dt, m/s.
    pub dv_mps: Vector3<f64>,
    /// Specific force at the interval midpoint, body axes, m/s².
    pub f_b_mps2: Vector3<f64>,
    /// Unit up direction in body axes at the midpoint (z component = cos of Z-axis tilt).
    pub up_b: Vector3<f64>,
    /// Unit north direction in body axes (read by the navigation-field term only; zero when
    /// nothing reads it).
    pub north_b: Vector3<f64>,
    /// Unit east direction in body axes (likewise).
    pub east_b: Vector3<f64>,
    /// Gyro block temperatures, °C.
    pub gyro_temp_c: Vector3<f64>,
    /// Temperature gradient across each gyro block, K.
    pub gyro_gradient_k: Vector3<f64>,
    /// Accelerometer cluster temperature, °C.
    pub accel_temp_c: f64,
}

/// Per-axis values, x/y/z.
pub type Axes3 = [f64; 3];

/// Scale-factor error (diagonal of Eq. 3 / Eq. 4).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScaleFactorSpec {
    /// Term on.
    pub enabled: bool,
    /// Scale-factor error per axis, ppm.
    pub ppm: Axes3,
}

/// Axis misalignment (off-diagonal of Eq. 3 / Eq. 4): error_i = Σ_{j≠i} m_ij · input_j.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MisalignmentSpec {
    /// Term on.
    pub enabled: bool,
    /// Coefficients [xy, xz, yx, yz, zx, zy], arcsec (β_xy … of Eq. 3, α_xy … of Eq. 4).
    pub arcsec: [f64; 6],
}

/// Third-order temperature polynomial: Σ_k c_k (T − T_ref)^k.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TempPolySpec {
    /// Term on.
    pub enabled: bool,
    /// Reference temperature T_ref, °C.
    pub ref_temp_c: f64,
    /// Linear coefficients per axis (unit per K).
    pub per_k: Axes3,
    /// Quadratic coefficients per axis (unit per K²).
    pub per_k2: Axes3,
    /// Cubic coefficients per axis (unit per K³).
    pub per_k3: Axes3,
}

impl Default for TempPolySpec {
    fn default() -> Self {
        Self {
            enabled: false,
            ref_temp_c: 25.0,
            per_k: [0.0; 3],
            per_k2: [0.0; 3],
            per_k3: [0.0; 3],
        }
    }
}

/// Quantisation of the output increments (pulse weight; the residual is carried).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct QuantizationSpec {
    /// Term on.
    pub enabled: bool,
    /// Pulse weight per axis (arcsec for gyros, m/s for accelerometers).
    pub pulse: Axes3,
}

/// The index pairs (i, j) of the misalignment vector [xy, xz, yx, yz, zx, zy].
pub const MISALIGNMENT_PAIRS: [(usize, usize); 6] =
    [(0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)];

/// Applies a scale factor and misalignment (both in SI: fraction and rad) to an input increment.
#[inline]
fn scale_and_misalign(
    sf: &Vector3<f64>,
    mis: &[f64; 6],
    input: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let sfe = sf.component_mul(input);
    let mut m = Vector3::zeros();
    for (k, &(i, j)) in MISALIGNMENT_PAIRS.iter().enumerate() {
        m[i] += mis[k] * input[j];
    }
    (sfe, m)
}

/// Evaluates Σ_k c_k x^k for k = 1..3.
#[inline]
fn cubic(c1: f64, c2: f64, c3: f64, x: f64) -> f64 {
    x * (c1 + x * (c2 + x * c3))
}

/// Pushes regressors of a misalignment row for axis `axis` given an input increment.
fn misalignment_regressors(input: &Vector3<f64>, axis: usize, out: &mut Vec<f64>) {
    for &(i, j) in &MISALIGNMENT_PAIRS {
        if i == axis {
            out.push(input[j]);
        }
    }
}
