//! Accelerometer error terms: Eq. 4 (bias, scale factor, misalignment), temperature
//! polynomial bias, velocity random walk and quantisation.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::dwell_dependence::DwellDependence;
use super::{
    Axes3, MisalignmentSpec, QuantizationSpec, ScaleFactorSpec, TempPolySpec, TermContext, cubic,
    misalignment_regressors, scale_and_misalign,
};
use crate::units::{ARCSEC, PPM, UG};

/// Accelerometer error terms, in reporting order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AccelTerm {
    /// Constant bias α (Eq. 4).
    Bias,
    /// Scale-factor error α_ii (Eq. 4).
    ScaleFactor,
    /// Misalignment α_ij (Eq. 4).
    Misalignment,
    /// Third-order polynomial in cluster temperature.
    TemperatureBias,
    /// Velocity random walk.
    VelocityRandomWalk,
    /// Output quantisation.
    Quantization,
}

impl AccelTerm {
    /// All terms in reporting order.
    pub const ALL: [AccelTerm; 6] = [
        AccelTerm::Bias,
        AccelTerm::ScaleFactor,
        AccelTerm::Misalignment,
        AccelTerm::TemperatureBias,
        AccelTerm::VelocityRandomWalk,
        AccelTerm::Quantization,
    ];
    /// Deterministic terms (the diagnosis catalogue): the first four of [`AccelTerm::ALL`].
    pub const DETERMINISTIC: &'static [AccelTerm] = Self::ALL.split_at(4).0;

    /// Key of the term in scenario files and output columns.
    pub fn key(self) -> &'static str {
        match self {
            AccelTerm::Bias => "bias",
            AccelTerm::ScaleFactor => "scale_factor",
            AccelTerm::Misalignment => "misalignment",
            AccelTerm::TemperatureBias => "temperature_bias",
            AccelTerm::VelocityRandomWalk => "velocity_random_walk",
            AccelTerm::Quantization => "quantization",
        }
    }

    /// What the term's contribution does while the table dwells (the plant's dwell cache
    /// relies on it; see [`DwellDependence`]). No wildcard arm: a new term must answer.
    pub fn dwell_dependence(self) -> DwellDependence {
        use DwellDependence::{HeldInputs, Readout};
        match self {
            // Constants, functions of the true increment (gravity and the Earth rate in body
            // axes in a held dwell), and a bias evaluated at each thermal update, held between.
            AccelTerm::Bias
            | AccelTerm::ScaleFactor
            | AccelTerm::Misalignment
            | AccelTerm::TemperatureBias => HeldInputs,
            AccelTerm::VelocityRandomWalk | AccelTerm::Quantization => Readout,
        }
    }

    /// Whether the term's contribution changes within a held dwell
    /// ([`DwellDependence::varies_in_dwell`]): the plant then works every tick of a dwell.
    pub fn varies_in_dwell(self) -> bool {
        self.dwell_dependence().varies_in_dwell()
    }
}

/// Constant accelerometer bias.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AccelBiasSpec {
    /// Term on.
    pub enabled: bool,
    /// Bias per axis, µg.
    pub ug: Axes3,
}

/// Velocity random walk.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VrwSpec {
    /// Term on.
    pub enabled: bool,
    /// White acceleration noise density per axis, µg/√Hz.
    pub ug_per_sqrthz: Axes3,
}

/// Every accelerometer error term.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AccelSpec {
    /// Constant bias (Eq. 4).
    pub bias: AccelBiasSpec,
    /// Scale-factor error (Eq. 4).
    pub scale_factor: ScaleFactorSpec,
    /// Misalignment (Eq. 4).
    pub misalignment: MisalignmentSpec,
    /// Temperature polynomial bias, coefficients in µg/K^k.
    pub temperature_bias: TempPolySpec,
    /// Velocity random walk.
    pub velocity_random_walk: VrwSpec,
    /// Quantisation, pulse weight in m/s.
    pub quantization: QuantizationSpec,
    /// Declared effects (`[[sensor.accel.custom]]`), docs/effects.md.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub custom: Vec<super::custom::CustomSpec>,
}

impl AccelSpec {
    /// The switched-on terms, in [`AccelTerm::ALL`] order (the order of output columns and series).
    pub fn enabled_terms(&self) -> Vec<AccelTerm> {
        AccelTerm::ALL
            .into_iter()
            .filter(|t| self.is_enabled(*t))
            .collect()
    }

    /// Whether `term` is switched on.
    pub fn is_enabled(&self, term: AccelTerm) -> bool {
        match term {
            AccelTerm::Bias => self.bias.enabled,
            AccelTerm::ScaleFactor => self.scale_factor.enabled,
            AccelTerm::Misalignment => self.misalignment.enabled,
            AccelTerm::TemperatureBias => self.temperature_bias.enabled,
            AccelTerm::VelocityRandomWalk => self.velocity_random_walk.enabled,
            AccelTerm::Quantization => self.quantization.enabled,
        }
    }

    /// Switches `term` on or off.
    pub fn set_enabled(&mut self, term: AccelTerm, on: bool) {
        match term {
            AccelTerm::Bias => self.bias.enabled = on,
            AccelTerm::ScaleFactor => self.scale_factor.enabled = on,
            AccelTerm::Misalignment => self.misalignment.enabled = on,
            AccelTerm::TemperatureBias => self.temperature_bias.enabled = on,
            AccelTerm::VelocityRandomWalk => self.velocity_random_walk.enabled = on,
            AccelTerm::Quantization => self.quantization.enabled = on,
        }
    }

    /// Switches every term off except those listed.
    pub fn only(&self, keep: &[AccelTerm]) -> Self {
        let mut s = self.clone();
        for t in AccelTerm::ALL {
            if !keep.contains(&t) {
                s.set_enabled(t, false);
            }
        }
        s
    }
}

/// Number of accelerometer terms with a reported contribution.
pub const ACCEL_TERMS: usize = AccelTerm::ALL.len();

/// Deterministic accelerometer terms compiled to SI.
#[derive(Clone, Debug, PartialEq)]
pub struct AccelModel {
    bias_mps2: Vector3<f64>,
    sf: Vector3<f64>,
    mis_rad: [f64; 6],
    temp_ref_c: f64,
    temp_mps2: [Vector3<f64>; 3],
}

impl AccelModel {
    /// Compiles the deterministic part of `spec`.
    pub fn new(spec: &AccelSpec) -> Self {
        let on = |flag: bool, v: Axes3, unit: f64| {
            if flag {
                Vector3::from(v) * unit
            } else {
                Vector3::zeros()
            }
        };
        let tp = &spec.temperature_bias;
        let mut mis = [0.0; 6];
        if spec.misalignment.enabled {
            for (m, a) in mis.iter_mut().zip(spec.misalignment.arcsec) {
                *m = a * ARCSEC;
            }
        }
        Self {
            bias_mps2: on(spec.bias.enabled, spec.bias.ug, UG),
            sf: on(spec.scale_factor.enabled, spec.scale_factor.ppm, PPM),
            mis_rad: mis,
            temp_ref_c: tp.ref_temp_c,
            temp_mps2: [tp.per_k, tp.per_k2, tp.per_k3].map(|c| on(tp.enabled, c, UG)),
        }
    }

    /// Temperature polynomial bias at cluster temperature `temp_c`, m/s² (evaluated per thermal update).
    pub fn thermal_bias_mps2(&self, temp_c: f64) -> Vector3<f64> {
        let x = temp_c - self.temp_ref_c;
        let t = &self.temp_mps2;
        Vector3::from_fn(|i, _| cubic(t[0][i], t[1][i], t[2][i], x))
    }

    /// Adds each deterministic term's increment error (m/s) to `out` and returns the sum.
    #[inline]
    pub fn increment_error(
        &self,
        c: &TermContext,
        out: &mut [Vector3<f64>; ACCEL_TERMS],
    ) -> Vector3<f64> {
        self.increment_error_with(c, &self.thermal_bias_mps2(c.accel_temp_c), out)
    }

    /// [`AccelModel::increment_error`] with the temperature bias precomputed.
    #[inline]
    pub fn increment_error_with(
        &self,
        c: &TermContext,
        thermal_bias_mps2: &Vector3<f64>,
        out: &mut [Vector3<f64>; ACCEL_TERMS],
    ) -> Vector3<f64> {
        let (sf, mis) = scale_and_misalign(&self.sf, &self.mis_rad, &c.dv_mps);
        let bias = self.bias_mps2 * c.dt_s;
        let temp = thermal_bias_mps2 * c.dt_s;
        out[0] = bias;
        out[1] = sf;
        out[2] = mis;
        out[3] = temp;
        bias + sf + mis + temp
    }

    /// Regressors φ of `term` on `axis` (increment units).
    pub fn regressors(&self, term: AccelTerm, c: &TermContext, axis: usize, out: &mut Vec<f64>) {
        match term {
            AccelTerm::Bias => out.push(c.dt_s),
            AccelTerm::ScaleFactor => out.push(c.dv_mps[axis]),
            AccelTerm::Misalignment => misalignment_regressors(&c.dv_mps, axis, out),
            AccelTerm::TemperatureBias => {
                let x = c.accel_temp_c - self.temp_ref_c;
                out.extend([x * c.dt_s, x * x * c.dt_s, x * x * x * c.dt_s]);
            }
            _ => {}
        }
    }

    /// Coefficients θ of `term` on `axis` in SI.
    pub fn coefficients(&self, term: AccelTerm, axis: usize) -> Vec<f64> {
        match term {
            AccelTerm::Bias => vec![self.bias_mps2[axis]],
            AccelTerm::ScaleFactor => vec![self.sf[axis]],
            AccelTerm::Misalignment => super::MISALIGNMENT_PAIRS
                .iter()
                .zip(self.mis_rad)
                .filter(|((i, _), _)| *i == axis)
                .map(|(_, m)| m)
                .collect(),
            AccelTerm::TemperatureBias => self.temp_mps2.iter().map(|c| c[axis]).collect(),
            _ => Vec::new(),
        }
    }
}

/// Scenario-file keys of the coefficients [`AccelModel::coefficients`] returns for `term` on
/// `axis`, in order, with the SI value of one file unit (see the gyro counterpart).
pub fn coefficient_keys(term: AccelTerm, axis: usize) -> Vec<(String, f64)> {
    let k = |name: &str, unit: f64| (format!("sensor.accel.{}.{name}[{axis}]", term.key()), unit);
    match term {
        AccelTerm::Bias => vec![k("ug", UG)],
        AccelTerm::ScaleFactor => vec![k("ppm", PPM)],
        AccelTerm::Misalignment => super::MISALIGNMENT_PAIRS
            .iter()
            .enumerate()
            .filter(|(_, (i, _))| *i == axis)
            .map(|(n, _)| (format!("sensor.accel.misalignment.arcsec[{n}]"), ARCSEC))
            .collect(),
        AccelTerm::TemperatureBias => vec![k("per_k", UG), k("per_k2", UG), k("per_k3", UG)],
        _ => Vec::new(),
    }
}
