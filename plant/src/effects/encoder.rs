//! Gimbal angle encoders: the table angles the unit reports beside its increments. A navigation
//! computer knows the table only through them (carrier attitude, δβ position, azimuth isolation),
//! so their errors are effects like any sensor's:
//!
//! θ_measured = round_res((1 + s)·θ_true + b), per gimbal (outer, inner),
//!
//! with `s` the scale-factor error, `b` the offset and `round_res` rounding to the encoder's
//! resolution (an absolute encoder: no residual is carried from one reading to the next).

use serde::{Deserialize, Serialize};

use crate::table::GimbalAngles;
use crate::units::{ARCSEC, PPM};

/// Encoder error terms, in the order they are applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EncoderTerm {
    /// Scale-factor error s (ppm of the angle).
    ScaleFactor,
    /// Zero offset b (arcsec).
    Offset,
    /// Rounding to the resolution (arcsec per count).
    Quantization,
}

impl EncoderTerm {
    /// All terms in application order.
    pub const ALL: [EncoderTerm; 3] = [
        EncoderTerm::ScaleFactor,
        EncoderTerm::Offset,
        EncoderTerm::Quantization,
    ];

    /// Key of the term under `[sensor.encoder]`.
    pub fn key(self) -> &'static str {
        match self {
            EncoderTerm::ScaleFactor => "scale_factor",
            EncoderTerm::Offset => "offset",
            EncoderTerm::Quantization => "quantization",
        }
    }
}

/// Encoder scale-factor error.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderScaleSpec {
    /// Term on.
    pub enabled: bool,
    /// Scale-factor error [outer, inner], ppm.
    pub ppm: [f64; 2],
}

/// Encoder zero offset.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderOffsetSpec {
    /// Term on.
    pub enabled: bool,
    /// Offset [outer, inner], arcsec.
    pub arcsec: [f64; 2],
}

/// Encoder resolution.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderQuantizationSpec {
    /// Term on.
    pub enabled: bool,
    /// Angle of one count [outer, inner], arcsec (a 22-bit encoder: 0.309″).
    pub resolution_arcsec: [f64; 2],
}

impl Default for EncoderQuantizationSpec {
    fn default() -> Self {
        Self {
            enabled: false,
            resolution_arcsec: [360.0 * 3600.0 / (1u64 << 22) as f64; 2],
        }
    }
}

/// The encoder errors of both gimbals; every term off by default (the paper's presets).
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSpec {
    /// Scale-factor error.
    pub scale_factor: EncoderScaleSpec,
    /// Zero offset.
    pub offset: EncoderOffsetSpec,
    /// Resolution.
    pub quantization: EncoderQuantizationSpec,
}

impl EncoderSpec {
    /// Whether `term` is switched on.
    pub fn is_enabled(&self, term: EncoderTerm) -> bool {
        match term {
            EncoderTerm::ScaleFactor => self.scale_factor.enabled,
            EncoderTerm::Offset => self.offset.enabled,
            EncoderTerm::Quantization => self.quantization.enabled,
        }
    }

    /// The terms switched on, in application order.
    pub fn enabled_terms(&self) -> Vec<EncoderTerm> {
        EncoderTerm::ALL
            .into_iter()
            .filter(|t| self.is_enabled(*t))
            .collect()
    }
}

/// The encoder readout in SI, built once from an [`EncoderSpec`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Encoders {
    /// 1 + s per gimbal.
    gain: [f64; 2],
    /// b per gimbal, rad.
    offset_rad: [f64; 2],
    /// Count angle per gimbal, rad (0: no rounding).
    resolution_rad: [f64; 2],
    /// No term is on: the reading is the true angle.
    ideal: bool,
}

impl Encoders {
    /// The readout of `spec`.
    pub fn new(spec: &EncoderSpec) -> Self {
        let pick = |on: bool, v: [f64; 2], unit: f64| {
            if on { v.map(|x| x * unit) } else { [0.0; 2] }
        };
        let sf = pick(spec.scale_factor.enabled, spec.scale_factor.ppm, PPM);
        Self {
            gain: [1.0 + sf[0], 1.0 + sf[1]],
            offset_rad: pick(spec.offset.enabled, spec.offset.arcsec, ARCSEC),
            resolution_rad: pick(
                spec.quantization.enabled,
                spec.quantization.resolution_arcsec,
                ARCSEC,
            ),
            ideal: EncoderTerm::ALL.iter().all(|t| !spec.is_enabled(*t)),
        }
    }

    /// The angles the encoders report for the true angles `truth`.
    #[inline]
    pub fn read(&self, truth: GimbalAngles) -> GimbalAngles {
        if self.ideal {
            return truth;
        }
        let one = |k: usize, x: f64| {
            let y = self.gain[k] * x + self.offset_rad[k];
            let r = self.resolution_rad[k];
            if r > 0.0 { (y / r).round() * r } else { y }
        };
        GimbalAngles::new(one(0, truth.outer_rad), one(1, truth.inner_rad))
    }
}
