//! Gyro (RLG) error terms: Eq. 3 (bias, scale factor, misalignment), Eq. 9 (position-dependent
//! bias δβ) and the RLG effects the paper attributes δβ to (temperature, gravity, dither).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::{
    Axes3, MisalignmentSpec, QuantizationSpec, ScaleFactorSpec, TempPolySpec, TermContext, cubic,
    misalignment_regressors, scale_and_misalign,
};
use crate::units::{ARCSEC, DPH, G0, PPM};

pub use super::gyro_term::GyroTerm;

/// Constant gyro bias.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GyroBiasSpec {
    /// Term on.
    pub enabled: bool,
    /// Bias per axis, °/h.
    pub dph: Axes3,
}

/// How δβ moves between Z-up and Z-down during a rotation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Transition {
    /// w = (1 − u)/2 with u = cos(tilt of body z from up): δβ is linear in the body-z
    /// component of gravity, 0 at Z-up, 1 at Z-down, smooth through the rotation.
    #[default]
    Cosine,
    /// w = 1 when the body z axis points below the horizon, 0 above (½ exactly on it).
    Step,
}

impl Transition {
    /// Weight of δβ for a body up direction whose z component is `u`.
    #[inline]
    pub fn weight(self, u: f64) -> f64 {
        match self {
            Transition::Cosine => 0.5 * (1.0 - u),
            Transition::Step => {
                if u < 0.0 {
                    1.0
                } else if u > 0.0 {
                    0.0
                } else {
                    0.5
                }
            }
        }
    }
}

/// Position-dependent bias δβ of Eq. 9: the bias the gyros show at Z-down relative to Z-up,
/// δβ(T) = δβ₀ + c₁ΔT + c₂ΔT² + c₃ΔT³ with ΔT the block temperature minus `ref_temp_c`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PositionBiasSpec {
    /// Term on.
    pub enabled: bool,
    /// δβ at the reference temperature per axis, °/h (Table 3: 0.005).
    pub dph: Axes3,
    /// Transition model between Z-up and Z-down.
    pub transition: Transition,
    /// Reference temperature for the polynomial, °C.
    pub ref_temp_c: f64,
    /// Linear temperature coefficients, °/h/K.
    pub dph_per_k: Axes3,
    /// Quadratic temperature coefficients, °/h/K².
    pub dph_per_k2: Axes3,
    /// Cubic temperature coefficients, °/h/K³.
    pub dph_per_k3: Axes3,
}

impl Default for PositionBiasSpec {
    fn default() -> Self {
        Self {
            enabled: false,
            dph: [0.0; 3],
            transition: Transition::Cosine,
            ref_temp_c: 25.0,
            dph_per_k: [0.0; 3],
            dph_per_k2: [0.0; 3],
            dph_per_k3: [0.0; 3],
        }
    }
}

/// Linear temperature-gradient bias.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GradientBiasSpec {
    /// Term on.
    pub enabled: bool,
    /// Bias per kelvin of block-minus-housing temperature, °/h/K.
    pub dph_per_k: Axes3,
}

/// g-sensitive bias: bias_i = Σ_j G_ij f_j / g₀.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GSensitivitySpec {
    /// Term on.
    pub enabled: bool,
    /// Rows: gyro axis; columns: specific-force axis; °/h/g.
    pub dph_per_g: [Axes3; 3],
}

/// Dither-dependent bias. The dither amplitude changes with the gravity load along the sensing
/// axis, a_i/a₀ = 1 + κ_i((f_i/g₀)² − 1/3), and the bias follows the amplitude change:
/// bias_i = k_i·(a_i/a₀ − 1).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DitherSpec {
    /// Term on.
    pub enabled: bool,
    /// Relative dither-amplitude change κ per g² of sensing-axis load.
    pub amplitude_change: Axes3,
    /// Bias per unit relative amplitude change, °/h.
    pub dph_per_amplitude: Axes3,
}

/// Bias that follows a field fixed in the navigation frame, as an RLG's bias follows the
/// Earth's magnetic field: on axis i, b_i = Σ_j K_ij·(C_n^b)_ij = K_iE·e_i + K_iN·n_i + K_iU·u_i
/// with e^b, n^b, u^b the body components of east, north and up. A unit with sensitivity k_i
/// along its own axis in a field m^n (ENU) has K_ij = k_i·m_j.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NavFieldSpec {
    /// Term on.
    pub enabled: bool,
    /// Rows: gyro axis; columns: the field's east, north and up components; °/h.
    pub dph_enu: [Axes3; 3],
}

/// Angle random walk.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ArwSpec {
    /// Term on.
    pub enabled: bool,
    /// ARW coefficient per axis, °/√h (Table 3: 0.003).
    pub dpsh: Axes3,
}

/// Bias instability (first-order Gauss–Markov, stationary start).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GaussMarkovSpec {
    /// Term on.
    pub enabled: bool,
    /// Stationary standard deviation, °/h.
    pub sigma_dph: Axes3,
    /// Correlation time, s.
    pub tau_s: Axes3,
}

impl Default for GaussMarkovSpec {
    fn default() -> Self {
        Self {
            enabled: false,
            sigma_dph: [0.0; 3],
            tau_s: [3600.0; 3],
        }
    }
}

/// Rate random walk.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RrwSpec {
    /// Term on.
    pub enabled: bool,
    /// RRW coefficient per axis, °/h/√h.
    pub dph_per_sqrth: Axes3,
}

/// Every gyro error term.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GyroSpec {
    /// Constant bias (Eq. 3).
    pub bias: GyroBiasSpec,
    /// Scale-factor error (Eq. 3).
    pub scale_factor: ScaleFactorSpec,
    /// Scale-factor asymmetry, ppm of |ω|.
    pub scale_factor_asymmetry: ScaleFactorSpec,
    /// Misalignment (Eq. 3).
    pub misalignment: MisalignmentSpec,
    /// Temperature polynomial bias, coefficients in °/h/K^k.
    pub temperature_bias: TempPolySpec,
    /// Temperature-gradient bias.
    pub temperature_gradient_bias: GradientBiasSpec,
    /// g-sensitivity.
    pub g_sensitivity: GSensitivitySpec,
    /// Position-dependent bias δβ (Eq. 9).
    pub position_bias: PositionBiasSpec,
    /// Dither-dependent bias.
    pub dither_bias: DitherSpec,
    /// Bias following a field fixed in the navigation frame (magnetic sensitivity).
    pub nav_field_bias: NavFieldSpec,
    /// Angle random walk.
    pub angle_random_walk: ArwSpec,
    /// Bias instability.
    pub bias_instability: GaussMarkovSpec,
    /// Rate random walk.
    pub rate_random_walk: RrwSpec,
    /// Quantisation, pulse weight in arcsec.
    pub quantization: QuantizationSpec,
    /// Declared effects (`[[sensor.gyro.custom]]`), docs/effects.md.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub custom: Vec<super::custom::CustomSpec>,
}

impl GyroSpec {
    /// The switched-on terms, in [`GyroTerm::ALL`] order (the order of output columns and series).
    pub fn enabled_terms(&self) -> Vec<GyroTerm> {
        GyroTerm::ALL
            .into_iter()
            .filter(|t| self.is_enabled(*t))
            .collect()
    }

    /// Whether `term` is switched on.
    pub fn is_enabled(&self, term: GyroTerm) -> bool {
        match term {
            GyroTerm::Bias => self.bias.enabled,
            GyroTerm::ScaleFactor => self.scale_factor.enabled,
            GyroTerm::ScaleFactorAsymmetry => self.scale_factor_asymmetry.enabled,
            GyroTerm::Misalignment => self.misalignment.enabled,
            GyroTerm::TemperatureBias => self.temperature_bias.enabled,
            GyroTerm::TemperatureGradientBias => self.temperature_gradient_bias.enabled,
            GyroTerm::GSensitivity => self.g_sensitivity.enabled,
            GyroTerm::PositionBias => self.position_bias.enabled,
            GyroTerm::DitherBias => self.dither_bias.enabled,
            GyroTerm::NavFieldBias => self.nav_field_bias.enabled,
            GyroTerm::AngleRandomWalk => self.angle_random_walk.enabled,
            GyroTerm::BiasInstability => self.bias_instability.enabled,
            GyroTerm::RateRandomWalk => self.rate_random_walk.enabled,
            GyroTerm::Quantization => self.quantization.enabled,
        }
    }

    /// Switches every term off except those listed.
    pub fn only(&self, keep: &[GyroTerm]) -> Self {
        let mut s = self.clone();
        for t in GyroTerm::ALL {
            if !keep.contains(&t) {
                s.set_enabled(t, false);
            }
        }
        s
    }

    /// Switches `term` on or off.
    pub fn set_enabled(&mut self, term: GyroTerm, on: bool) {
        match term {
            GyroTerm::Bias => self.bias.enabled = on,
            GyroTerm::ScaleFactor => self.scale_factor.enabled = on,
            GyroTerm::ScaleFactorAsymmetry => self.scale_factor_asymmetry.enabled = on,
            GyroTerm::Misalignment => self.misalignment.enabled = on,
            GyroTerm::TemperatureBias => self.temperature_bias.enabled = on,
            GyroTerm::TemperatureGradientBias => self.temperature_gradient_bias.enabled = on,
            GyroTerm::GSensitivity => self.g_sensitivity.enabled = on,
            GyroTerm::PositionBias => self.position_bias.enabled = on,
            GyroTerm::DitherBias => self.dither_bias.enabled = on,
            GyroTerm::NavFieldBias => self.nav_field_bias.enabled = on,
            GyroTerm::AngleRandomWalk => self.angle_random_walk.enabled = on,
            GyroTerm::BiasInstability => self.bias_instability.enabled = on,
            GyroTerm::RateRandomWalk => self.rate_random_walk.enabled = on,
            GyroTerm::Quantization => self.quantization.enabled = on,
        }
    }
}

fn on(flag: bool, v: Axes3, unit: f64) -> Vector3<f64> {
    if flag {
        Vector3::from(v) * unit
    } else {
        Vector3::zeros()
    }
}

/// Deterministic gyro terms compiled to SI (rad/s, fraction, rad). Disabled terms are zero.
#[derive(Clone, Debug, PartialEq)]
pub struct GyroModel {
    bias_rps: Vector3<f64>,
    sf: Vector3<f64>,
    asym: Vector3<f64>,
    mis_rad: [f64; 6],
    temp_ref_c: f64,
    temp_rps: [Vector3<f64>; 3],
    grad_rps_per_k: Vector3<f64>,
    gsens_rps_per_g: nalgebra::Matrix3<f64>,
    pos_on: bool,
    pos_transition: Transition,
    pos_ref_c: f64,
    pos_rps: [Vector3<f64>; 4],
    dither_kappa: Vector3<f64>,
    dither_rps: Vector3<f64>,
    /// Rows: axis; columns: east, north, up; rad/s (zero when off).
    field_rps: nalgebra::Matrix3<f64>,
    field_on: bool,
}

/// Temperature-dependent gyro rates at the current node temperatures, rad/s.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GyroThermalRates {
    /// Temperature polynomial bias.
    pub temp_rps: Vector3<f64>,
    /// Temperature-gradient bias.
    pub grad_rps: Vector3<f64>,
    /// δβ(T) before the position weight.
    pub position_rps: Vector3<f64>,
}

/// Number of gyro terms with a reported contribution.
pub const GYRO_TERMS: usize = GyroTerm::ALL.len();

impl GyroModel {
    /// Compiles the deterministic part of `spec`.
    pub fn new(spec: &GyroSpec) -> Self {
        let tp = &spec.temperature_bias;
        let pb = &spec.position_bias;
        let mut gsens = nalgebra::Matrix3::zeros();
        if spec.g_sensitivity.enabled {
            for i in 0..3 {
                for j in 0..3 {
                    gsens[(i, j)] = spec.g_sensitivity.dph_per_g[i][j] * DPH;
                }
            }
        }
        let mut field = nalgebra::Matrix3::zeros();
        if spec.nav_field_bias.enabled {
            for i in 0..3 {
                for j in 0..3 {
                    field[(i, j)] = spec.nav_field_bias.dph_enu[i][j] * DPH;
                }
            }
        }
        let mut mis = [0.0; 6];
        if spec.misalignment.enabled {
            for (m, a) in mis.iter_mut().zip(spec.misalignment.arcsec) {
                *m = a * ARCSEC;
            }
        }
        Self {
            bias_rps: on(spec.bias.enabled, spec.bias.dph, DPH),
            sf: on(spec.scale_factor.enabled, spec.scale_factor.ppm, PPM),
            asym: on(
                spec.scale_factor_asymmetry.enabled,
                spec.scale_factor_asymmetry.ppm,
                PPM,
            ),
            mis_rad: mis,
            temp_ref_c: tp.ref_temp_c,
            temp_rps: [tp.per_k, tp.per_k2, tp.per_k3].map(|c| on(tp.enabled, c, DPH)),
            grad_rps_per_k: on(
                spec.temperature_gradient_bias.enabled,
                spec.temperature_gradient_bias.dph_per_k,
                DPH,
            ),
            gsens_rps_per_g: gsens,
            pos_on: pb.enabled,
            pos_transition: pb.transition,
            pos_ref_c: pb.ref_temp_c,
            pos_rps: [pb.dph, pb.dph_per_k, pb.dph_per_k2, pb.dph_per_k3]
                .map(|c| on(pb.enabled, c, DPH)),
            dither_kappa: on(
                spec.dither_bias.enabled,
                spec.dither_bias.amplitude_change,
                1.0,
            ),
            dither_rps: on(
                spec.dither_bias.enabled,
                spec.dither_bias.dph_per_amplitude,
                DPH,
            ),
            field_rps: field,
            field_on: spec.nav_field_bias.enabled,
        }
    }

    /// Whether the navigation-field term is on (the plant then computes north and east in body
    /// axes each tick).
    pub fn reads_heading(&self) -> bool {
        self.field_on
    }

    /// The position-dependent bias δβ (Eq. 9) at the block temperatures `temp_c`, rad/s, before
    /// the position weight.
    pub fn position_bias_rps(&self, temp_c: &Vector3<f64>) -> Vector3<f64> {
        let p = &self.pos_rps;
        Vector3::from_fn(|i, _| {
            let dt = temp_c[i] - self.pos_ref_c;
            p[0][i] + cubic(p[1][i], p[2][i], p[3][i], dt)
        })
    }

    /// Weight of δβ at the body up direction `up_b` (0 at Z-up, 1 at Z-down).
    pub fn position_weight(&self, up_b: &Vector3<f64>) -> f64 {
        self.pos_transition.weight(up_b.z)
    }

    /// Relative dither amplitude per axis, a_i/a₀.
    pub fn dither_amplitude_ratio(&self, f_b: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from_fn(|i, _| 1.0 + self.dither_kappa[i] * ((f_b[i] / G0).powi(2) - 1.0 / 3.0))
    }

    /// Evaluates the temperature-dependent rates once per thermal update (temperatures are
    /// constant between updates), so the per-sample path does no polynomial work.
    pub fn thermal_rates(
        &self,
        gyro_temp_c: &Vector3<f64>,
        gradient_k: &Vector3<f64>,
    ) -> GyroThermalRates {
        let dtemp = gyro_temp_c.add_scalar(-self.temp_ref_c);
        GyroThermalRates {
            temp_rps: Vector3::from_fn(|i, _| {
                cubic(
                    self.temp_rps[0][i],
                    self.temp_rps[1][i],
                    self.temp_rps[2][i],
                    dtemp[i],
                )
            }),
            grad_rps: self.grad_rps_per_k.component_mul(gradient_k),
            position_rps: if self.pos_on {
                self.position_bias_rps(gyro_temp_c)
            } else {
                Vector3::zeros()
            },
        }
    }

    /// Adds each deterministic term's increment error (rad) over the interval to `out`
    /// (indexed like [`GyroTerm::ALL`]) and returns their sum.
    #[inline]
    pub fn increment_error(
        &self,
        c: &TermContext,
        out: &mut [Vector3<f64>; GYRO_TERMS],
    ) -> Vector3<f64> {
        let rates = self.thermal_rates(&c.gyro_temp_c, &c.gyro_gradient_k);
        self.increment_error_with(c, &rates, out)
    }

    /// [`GyroModel::increment_error`] with the temperature-dependent rates precomputed.
    #[inline]
    pub fn increment_error_with(
        &self,
        c: &TermContext,
        rates: &GyroThermalRates,
        out: &mut [Vector3<f64>; GYRO_TERMS],
    ) -> Vector3<f64> {
        let dt = c.dt_s;
        let (sf, mis) = scale_and_misalign(&self.sf, &self.mis_rad, &c.dtheta_rad);
        let asym = self.asym.component_mul(&c.dtheta_rad.abs());
        let bias = self.bias_rps * dt;
        let temp = rates.temp_rps * dt;
        let grad = rates.grad_rps * dt;
        let gsens = self.gsens_rps_per_g * (c.f_b_mps2 * (dt / G0));
        let pos = if self.pos_on {
            rates.position_rps * (self.position_weight(&c.up_b) * dt)
        } else {
            Vector3::zeros()
        };
        let load = c.f_b_mps2 / G0;
        let dither = Vector3::from_fn(|i, _| {
            self.dither_rps[i] * self.dither_kappa[i] * (load[i] * load[i] - 1.0 / 3.0) * dt
        });
        out[0] = bias;
        out[1] = sf;
        out[2] = asym;
        out[3] = mis;
        out[4] = temp;
        out[5] = grad;
        out[6] = gsens;
        let field = if self.field_on {
            let f = &self.field_rps;
            let (e, n, u) = (&c.east_b, &c.north_b, &c.up_b);
            Vector3::from_fn(|i, _| (f[(i, 0)] * e[i] + f[(i, 1)] * n[i] + f[(i, 2)] * u[i]) * dt)
        } else {
            Vector3::zeros()
        };
        out[7] = pos;
        out[8] = dither;
        out[9] = field;
        bias + sf + asym + mis + temp + grad + gsens + pos + dither + field
    }

    /// Regressors φ of `term` on `axis` (increment units, so the error is Σ θ·φ).
    pub fn regressors(&self, term: GyroTerm, c: &TermContext, axis: usize, out: &mut Vec<f64>) {
        let dt = c.dt_s;
        match term {
            GyroTerm::Bias => out.push(dt),
            GyroTerm::ScaleFactor => out.push(c.dtheta_rad[axis]),
            GyroTerm::ScaleFactorAsymmetry => out.push(c.dtheta_rad[axis].abs()),
            GyroTerm::Misalignment => misalignment_regressors(&c.dtheta_rad, axis, out),
            GyroTerm::TemperatureBias => {
                let x = c.gyro_temp_c[axis] - self.temp_ref_c;
                out.extend([x * dt, x * x * dt, x * x * x * dt]);
            }
            GyroTerm::TemperatureGradientBias => out.push(c.gyro_gradient_k[axis] * dt),
            GyroTerm::GSensitivity => out.extend((0..3).map(|j| c.f_b_mps2[j] / G0 * dt)),
            GyroTerm::PositionBias => {
                let w = self.position_weight(&c.up_b) * dt;
                let x = c.gyro_temp_c[axis] - self.pos_ref_c;
                out.extend([w, x * w, x * x * w, x * x * x * w]);
            }
            GyroTerm::DitherBias => {
                let l = c.f_b_mps2[axis] / G0;
                out.push((l * l - 1.0 / 3.0) * dt);
            }
            GyroTerm::NavFieldBias => {
                out.extend([c.east_b[axis] * dt, c.north_b[axis] * dt, c.up_b[axis] * dt])
            }
            _ => {}
        }
    }

    /// Coefficients θ of `term` on `axis` in SI, matching [`GyroModel::regressors`].
    pub fn coefficients(&self, term: GyroTerm, axis: usize) -> Vec<f64> {
        match term {
            GyroTerm::Bias => vec![self.bias_rps[axis]],
            GyroTerm::ScaleFactor => vec![self.sf[axis]],
            GyroTerm::ScaleFactorAsymmetry => vec![self.asym[axis]],
            GyroTerm::Misalignment => super::MISALIGNMENT_PAIRS
                .iter()
                .zip(self.mis_rad)
                .filter(|((i, _), _)| *i == axis)
                .map(|(_, m)| m)
                .collect(),
            GyroTerm::TemperatureBias => self.temp_rps.iter().map(|c| c[axis]).collect(),
            GyroTerm::TemperatureGradientBias => vec![self.grad_rps_per_k[axis]],
            GyroTerm::GSensitivity => (0..3).map(|j| self.gsens_rps_per_g[(axis, j)]).collect(),
            GyroTerm::PositionBias => self.pos_rps.iter().map(|c| c[axis]).collect(),
            GyroTerm::DitherBias => vec![self.dither_rps[axis] * self.dither_kappa[axis]],
            GyroTerm::NavFieldBias => (0..3).map(|j| self.field_rps[(axis, j)]).collect(),
            _ => Vec::new(),
        }
    }
}

/// Scenario-file keys of the coefficients [`GyroModel::coefficients`] returns for `term` on
/// `axis`, in the same order, each with the SI value of one file unit (a fitted SI coefficient
/// θ is written as θ / unit). The diagnosis writes fitted effects back to model files with it.
pub fn coefficient_keys(term: GyroTerm, axis: usize) -> Vec<(String, f64)> {
    let k = |name: &str, unit: f64| (format!("sensor.gyro.{}.{name}[{axis}]", term.key()), unit);
    match term {
        GyroTerm::Bias => vec![k("dph", DPH)],
        GyroTerm::ScaleFactor | GyroTerm::ScaleFactorAsymmetry => vec![k("ppm", PPM)],
        GyroTerm::Misalignment => super::MISALIGNMENT_PAIRS
            .iter()
            .enumerate()
            .filter(|(_, (i, _))| *i == axis)
            .map(|(n, _)| (format!("sensor.gyro.misalignment.arcsec[{n}]"), ARCSEC))
            .collect(),
        GyroTerm::TemperatureBias => vec![k("per_k", DPH), k("per_k2", DPH), k("per_k3", DPH)],
        GyroTerm::TemperatureGradientBias => vec![k("dph_per_k", DPH)],
        GyroTerm::GSensitivity => (0..3)
            .map(|j| {
                (
                    format!("sensor.gyro.g_sensitivity.dph_per_g[{axis}][{j}]"),
                    DPH,
                )
            })
            .collect(),
        GyroTerm::PositionBias => vec![
            k("dph", DPH),
            k("dph_per_k", DPH),
            k("dph_per_k2", DPH),
            k("dph_per_k3", DPH),
        ],
        // Written with amplitude_change = 1, so dph_per_amplitude carries the whole coefficient.
        GyroTerm::DitherBias => vec![k("dph_per_amplitude", DPH)],
        GyroTerm::NavFieldBias => (0..3)
            .map(|j| {
                (
                    format!("sensor.gyro.nav_field_bias.dph_enu[{axis}][{j}]"),
                    DPH,
                )
            })
            .collect(),
        _ => Vec::new(),
    }
}
