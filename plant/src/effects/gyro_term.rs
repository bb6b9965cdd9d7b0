//! The names and reporting order of the gyro error terms, and what each does within a dwell.

use serde::{Deserialize, Serialize};

use super::dwell_dependence::DwellDependence;

/// Gyro error terms, in the order their contributions are reported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GyroTerm {
    /// Constant bias β (Eq. 3).
    Bias,
    /// Scale-factor error β_ii (Eq. 3).
    ScaleFactor,
    /// Scale-factor asymmetry: error a_i·|ω_i|.
    ScaleFactorAsymmetry,
    /// Misalignment β_ij (Eq. 3).
    Misalignment,
    /// Third-order polynomial in block temperature.
    TemperatureBias,
    /// Linear in the temperature gradient across the block.
    TemperatureGradientBias,
    /// Bias proportional to specific force (g-sensitivity).
    GSensitivity,
    /// Position-dependent bias δβ (Eq. 9), Z-down relative to Z-up, optionally temperature-dependent.
    PositionBias,
    /// Bias from the dither amplitude, which changes with the gravity load on the dither spring.
    DitherBias,
    /// Bias that follows a field fixed in the navigation frame (an RLG's magnetic
    /// sensitivity): each axis's sensitivity to the field's body component along it.
    NavFieldBias,
    /// Angle random walk (white rate noise).
    AngleRandomWalk,
    /// Bias instability as a first-order Gauss–Markov process.
    BiasInstability,
    /// Rate random walk.
    RateRandomWalk,
    /// Output quantisation (pulse weight, residual carried).
    Quantization,
}

impl GyroTerm {
    /// All terms in reporting order.
    pub const ALL: [GyroTerm; 14] = [
        GyroTerm::Bias,
        GyroTerm::ScaleFactor,
        GyroTerm::ScaleFactorAsymmetry,
        GyroTerm::Misalignment,
        GyroTerm::TemperatureBias,
        GyroTerm::TemperatureGradientBias,
        GyroTerm::GSensitivity,
        GyroTerm::PositionBias,
        GyroTerm::DitherBias,
        GyroTerm::NavFieldBias,
        GyroTerm::AngleRandomWalk,
        GyroTerm::BiasInstability,
        GyroTerm::RateRandomWalk,
        GyroTerm::Quantization,
    ];
    /// Deterministic terms, linear in their coefficients (the diagnosis catalogue): the first
    /// ten of [`GyroTerm::ALL`]; the rest are stochastic or quantisation.
    pub const DETERMINISTIC: &'static [GyroTerm] = Self::ALL.split_at(10).0;

    /// Key of the term in scenario files and output columns.
    pub fn key(self) -> &'static str {
        match self {
            GyroTerm::Bias => "bias",
            GyroTerm::ScaleFactor => "scale_factor",
            GyroTerm::ScaleFactorAsymmetry => "scale_factor_asymmetry",
            GyroTerm::Misalignment => "misalignment",
            GyroTerm::TemperatureBias => "temperature_bias",
            GyroTerm::TemperatureGradientBias => "temperature_gradient_bias",
            GyroTerm::GSensitivity => "g_sensitivity",
            GyroTerm::PositionBias => "position_bias",
            GyroTerm::DitherBias => "dither_bias",
            GyroTerm::NavFieldBias => "nav_field_bias",
            GyroTerm::AngleRandomWalk => "angle_random_walk",
            GyroTerm::BiasInstability => "bias_instability",
            GyroTerm::RateRandomWalk => "rate_random_walk",
            GyroTerm::Quantization => "quantization",
        }
    }

    /// What the term's contribution does while the table dwells (the plant's dwell cache
    /// relies on it; see [`DwellDependence`]). No wildcard arm: a new term must answer.
    pub fn dwell_dependence(self) -> DwellDependence {
        use DwellDependence::{HeldInputs, Readout};
        match self {
            // Constants, or functions of the true increment (the Earth rate in body axes in a
            // held dwell).
            GyroTerm::Bias
            | GyroTerm::ScaleFactor
            | GyroTerm::ScaleFactorAsymmetry
            | GyroTerm::Misalignment => HeldInputs,
            // Rates evaluated at each thermal update (`GyroThermalRates`), held between.
            GyroTerm::TemperatureBias | GyroTerm::TemperatureGradientBias => HeldInputs,
            // Functions of the specific force and of the up, north and east directions in
            // body axes, fixed while the table holds still on the static carrier; δβ's
            // temperature polynomial is a thermal rate too.
            GyroTerm::GSensitivity
            | GyroTerm::PositionBias
            | GyroTerm::DitherBias
            | GyroTerm::NavFieldBias => HeldInputs,
            GyroTerm::AngleRandomWalk
            | GyroTerm::BiasInstability
            | GyroTerm::RateRandomWalk
            | GyroTerm::Quantization => Readout,
        }
    }

    /// Whether the term's contribution changes within a held dwell
    /// ([`DwellDependence::varies_in_dwell`]): the plant then works every tick of a dwell.
    pub fn varies_in_dwell(self) -> bool {
        self.dwell_dependence().varies_in_dwell()
    }
}
