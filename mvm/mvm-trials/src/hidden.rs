//! The effects a trial hides from the model: each with its coefficients in the units the tool
//! writes (°/h, ppm, µg, arcsec, per K^k with temperatures as T − 25 °C) and the channels it acts
//! on. Per-axis arrays act on the axes whose coefficient is non-zero. The formulas of the error
//! each adds to the increments are in [`crate::effect_error`].

use serde::{Deserialize, Serialize};

/// Which sensor triad.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Sensor {
    /// Gyros (Δθ).
    Gyro,
    /// Accelerometers (Δv).
    Accel,
}

/// One measured channel: a sensor and an axis (0 = x, 1 = y, 2 = z).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Channel {
    /// Sensor.
    pub sensor: Sensor,
    /// Axis, 0..3.
    pub axis: usize,
}

impl std::fmt::Display for Channel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = match self.sensor {
            Sensor::Gyro => "gyro",
            Sensor::Accel => "accel",
        };
        write!(f, "{s}_{}", ["x", "y", "z"][self.axis])
    }
}

/// An effect the model lacks. Rates are integrated over each row by quadrature with the exact
/// temperatures and attitude; rate-proportional terms multiply the exact true increment. T_b,i
/// is gyro block i, T_h the housing, T_a the accelerometer node, u/n/e the body components of
/// up/north/east, f the specific force, g₀ = 9.80665 m/s².
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum HiddenEffect {
    /// A change of the gyro bias: β_i, °/h.
    GyroBias {
        /// Per axis, °/h.
        dph: [f64; 3],
    },
    /// A change of the gyro scale factor: β_ii·Δθ_i, ppm.
    GyroScaleFactor {
        /// Per axis, ppm.
        ppm: [f64; 3],
    },
    /// Scale-factor asymmetry: a_i·|Δθ_i|, ppm.
    GyroScaleFactorAsymmetry {
        /// Per axis, ppm.
        ppm: [f64; 3],
    },
    /// One gyro misalignment element: β_ij·Δθ_j on axis i, arcsec.
    GyroMisalignment {
        /// Axis i that errs.
        axis: usize,
        /// Axis j whose increment leaks in (≠ i).
        from: usize,
        /// β_ij, arcsec.
        arcsec: f64,
    },
    /// Temperature bias: c1·(T_b,i − 25) + c2·(T_b,i − 25)².
    GyroTemperatureBias {
        /// c1 per axis, °/h/K.
        per_k: [f64; 3],
        /// c2 per axis, °/h/K².
        per_k2: [f64; 3],
    },
    /// Temperature-gradient bias: k_i·(T_b,i − T_h).
    GyroGradientBias {
        /// Per axis, °/h/K.
        dph_per_k: [f64; 3],
    },
    /// One g-sensitivity element: G_ij·f_j/g₀ on axis i.
    GyroGSensitivity {
        /// Axis i that errs.
        axis: usize,
        /// Axis j of the specific force.
        from: usize,
        /// G_ij, °/h/g.
        dph_per_g: f64,
    },
    /// Position bias (Eq. 9, cosine transition): δβ_i·(1 − u_z)/2 with
    /// δβ_i = δβ0_i + c1_i·(T_b,i − 25).
    GyroPositionBias {
        /// δβ0 per axis, °/h.
        dph: [f64; 3],
        /// c1 per axis, °/h/K.
        dph_per_k: [f64; 3],
    },
    /// Dither bias: k_i·((f_i/g₀)² − 1/3).
    GyroDitherBias {
        /// k_i (the product of the catalogue's k and κ) per axis, °/h.
        dph: [f64; 3],
    },
    /// A change of the accelerometer bias: α_i, µg.
    AccelBias {
        /// Per axis, µg.
        ug: [f64; 3],
    },
    /// A change of the accelerometer scale factor: α_ii·Δv_i, ppm.
    AccelScaleFactor {
        /// Per axis, ppm.
        ppm: [f64; 3],
    },
    /// One accelerometer misalignment element: α_ij·Δv_j on axis i, arcsec.
    AccelMisalignment {
        /// Axis i that errs.
        axis: usize,
        /// Axis j whose increment leaks in (≠ i).
        from: usize,
        /// α_ij, arcsec.
        arcsec: f64,
    },
    /// Accelerometer temperature bias: c1·(T_a − 25).
    AccelTemperatureBias {
        /// Per axis, µg/K.
        ug_per_k: [f64; 3],
    },
    /// Scale factor linear in block temperature, ∫ c·(T_b,i − 25)·ω_i dt, together with a
    /// change of the constant scale factor, ppm·Δθ_i (so the model's constant is wrong too).
    ScaleFactorTempLinear {
        /// c per axis, ppm/K.
        ppm_per_k: [f64; 3],
        /// Change of the constant scale factor per axis, ppm.
        ppm: [f64; 3],
    },
    /// Scale factor quadratic in block temperature: ∫ c·(T_b,i − 25)²·ω_i dt.
    ScaleFactorTempQuadratic {
        /// c per axis, ppm/K².
        ppm_per_k2: [f64; 3],
    },
    /// Bias proportional to the block temperature's rate, K·dT_b,i/dt: K·ΔT_b,i over a row.
    TempRateBias {
        /// K per axis, °/h per K/s.
        dph_per_k_per_s: [f64; 3],
    },
    /// Bias proportional to a product of up-direction components, K·u_a·u_b (a = b allowed).
    UpProductBias {
        /// Component a (0..3).
        a: usize,
        /// Component b (0..3).
        b: usize,
        /// K per axis, °/h.
        dph: [f64; 3],
    },
    /// A field fixed in the navigation frame (an RLG's magnetic sensitivity):
    /// b_i = K_i·(m_E·e_i + m_N·n_i + m_U·u_i), m the unit field with m_N = cos I·cos D,
    /// m_E = cos I·sin D, m_U = −sin I (inclination I positive downwards, declination D east
    /// of north).
    NavFieldBias {
        /// K per axis, °/h.
        dph: [f64; 3],
        /// Inclination I, degrees.
        inclination_deg: f64,
        /// Declination D, degrees.
        declination_deg: f64,
    },
    /// Transient after a move: b_i = A_i·exp(−s/τ), s the seconds since the table last stopped
    /// (0 while it moves; at a run's start, before any move, the time since the run started).
    PostMoveTransient {
        /// A per axis, °/h.
        dph: [f64; 3],
        /// τ, s.
        tau_s: f64,
    },
    /// Lagged temperature bias: b_i = K_i·(L_i − 25), L_i the first-order lag of T_b,i with
    /// time constant τ_L (L_i = T_b,i at the run's start).
    LaggedTempBias {
        /// K per axis, °/h/K.
        dph_per_k: [f64; 3],
        /// τ_L, s.
        tau_s: f64,
    },
}

impl HiddenEffect {
    /// The sensor it acts on.
    pub fn sensor(&self) -> Sensor {
        use HiddenEffect::*;
        match self {
            AccelBias { .. }
            | AccelScaleFactor { .. }
            | AccelMisalignment { .. }
            | AccelTemperatureBias { .. } => Sensor::Accel,
            _ => Sensor::Gyro,
        }
    }

    /// The channels it acts on: the axes with a non-zero coefficient.
    pub fn channels(&self) -> Vec<Channel> {
        use HiddenEffect::*;
        let sensor = self.sensor();
        let per_axis: [bool; 3] = match self {
            GyroMisalignment {
                axis, arcsec: c, ..
            }
            | AccelMisalignment {
                axis, arcsec: c, ..
            }
            | GyroGSensitivity {
                axis, dph_per_g: c, ..
            } => [0, 1, 2].map(|i| i == *axis && *c != 0.0),
            GyroTemperatureBias { per_k, per_k2 } => {
                [0, 1, 2].map(|i| per_k[i] != 0.0 || per_k2[i] != 0.0)
            }
            GyroPositionBias { dph, dph_per_k } => {
                [0, 1, 2].map(|i| dph[i] != 0.0 || dph_per_k[i] != 0.0)
            }
            ScaleFactorTempLinear { ppm_per_k, ppm } => {
                [0, 1, 2].map(|i| ppm_per_k[i] != 0.0 || ppm[i] != 0.0)
            }
            GyroBias { dph: c }
            | GyroScaleFactor { ppm: c }
            | GyroScaleFactorAsymmetry { ppm: c }
            | GyroGradientBias { dph_per_k: c }
            | GyroDitherBias { dph: c }
            | AccelBias { ug: c }
            | AccelScaleFactor { ppm: c }
            | AccelTemperatureBias { ug_per_k: c }
            | ScaleFactorTempQuadratic { ppm_per_k2: c }
            | TempRateBias { dph_per_k_per_s: c }
            | UpProductBias { dph: c, .. }
            | NavFieldBias { dph: c, .. }
            | PostMoveTransient { dph: c, .. }
            | LaggedTempBias { dph_per_k: c, .. } => c.map(|x| x != 0.0),
        };
        (0..3)
            .filter(|i| per_axis[*i])
            .map(|axis| Channel { sensor, axis })
            .collect()
    }

    /// The effect with every coefficient multiplied by `f` (time constants, field direction and
    /// axes unchanged): its error, and its oracle z, scale by `f`.
    pub fn scaled(&self, f: f64) -> Self {
        use HiddenEffect::*;
        let s = |c: &[f64; 3]| c.map(|x| x * f);
        match self.clone() {
            GyroBias { dph } => GyroBias { dph: s(&dph) },
            GyroScaleFactor { ppm } => GyroScaleFactor { ppm: s(&ppm) },
            GyroScaleFactorAsymmetry { ppm } => GyroScaleFactorAsymmetry { ppm: s(&ppm) },
            GyroMisalignment { axis, from, arcsec } => GyroMisalignment {
                axis,
                from,
                arcsec: arcsec * f,
            },
            GyroTemperatureBias { per_k, per_k2 } => GyroTemperatureBias {
                per_k: s(&per_k),
                per_k2: s(&per_k2),
            },
            GyroGradientBias { dph_per_k } => GyroGradientBias {
                dph_per_k: s(&dph_per_k),
            },
            GyroGSensitivity {
                axis,
                from,
                dph_per_g,
            } => GyroGSensitivity {
                axis,
                from,
                dph_per_g: dph_per_g * f,
            },
            GyroPositionBias { dph, dph_per_k } => GyroPositionBias {
                dph: s(&dph),
                dph_per_k: s(&dph_per_k),
            },
            GyroDitherBias { dph } => GyroDitherBias { dph: s(&dph) },
            AccelBias { ug } => AccelBias { ug: s(&ug) },
            AccelScaleFactor { ppm } => AccelScaleFactor { ppm: s(&ppm) },
            AccelMisalignment { axis, from, arcsec } => AccelMisalignment {
                axis,
                from,
                arcsec: arcsec * f,
            },
            AccelTemperatureBias { ug_per_k } => AccelTemperatureBias {
                ug_per_k: s(&ug_per_k),
            },
            ScaleFactorTempLinear { ppm_per_k, ppm } => ScaleFactorTempLinear {
                ppm_per_k: s(&ppm_per_k),
                ppm: s(&ppm),
            },
            ScaleFactorTempQuadratic { ppm_per_k2 } => ScaleFactorTempQuadratic {
                ppm_per_k2: s(&ppm_per_k2),
            },
            TempRateBias { dph_per_k_per_s } => TempRateBias {
                dph_per_k_per_s: s(&dph_per_k_per_s),
            },
            UpProductBias { a, b, dph } => UpProductBias { a, b, dph: s(&dph) },
            NavFieldBias {
                dph,
                inclination_deg,
                declination_deg,
            } => NavFieldBias {
                dph: s(&dph),
                inclination_deg,
                declination_deg,
            },
            PostMoveTransient { dph, tau_s } => PostMoveTransient {
                dph: s(&dph),
                tau_s,
            },
            LaggedTempBias { dph_per_k, tau_s } => LaggedTempBias {
                dph_per_k: s(&dph_per_k),
                tau_s,
            },
        }
    }

    /// The time constant of the extra temperature lag it reads, if any.
    pub fn lag_tau_s(&self) -> Option<f64> {
        match self {
            HiddenEffect::LaggedTempBias { tau_s, .. } => Some(*tau_s),
            _ => None,
        }
    }
}
