//! Declared effects: error terms a scenario adds next to the catalogue without writing Rust.
//!
//! ```toml
//! [[sensor.gyro.custom]]
//! name = "temp_rate"
//! kind = "bias"                  # or "scale-factor"
//! regressor = "dtemp_dt:block"   # a product of documented signals, each with an optional ^N
//! unit = "K/s"                   # the regressor's unit, checked against the signals'
//! axes = ["x", "z"]
//! coef = [120.0, 0.0, 80.0]      # x, y, z: °/h (gyro bias), µg (accel bias) or ppm per unit
//! ```
//!
//! A declared effect is linear in its coefficient: on axis i its increment error is
//! c_i·r·Δt (bias) or c_i·r·Δθ_i / c_i·r·Δv_i (scale factor), with r the regressor over the
//! interval. [`CustomModel`] compiles the list once into a flat plan (each gradient, power and
//! product computed once per interval, then one row of coefficients per term) that the plant
//! evaluates every interval, and serves the same regressors and coefficients to the diagnosis
//! ([`CustomModel::regressor`]), as the catalogue does; both give the same bits.

mod expr;
mod memory;
mod model;
mod plan;
mod plant_side;
pub mod signals;
mod unit;

use serde::{Deserialize, Serialize};

pub use expr::{
    Factor, MAX_POWER, MAX_TAU_S, MIN_TAU_S, Op, is_clock, parse_regressor, regressor_text, unit_of,
};
pub use memory::{MemoryState, decay_value, lag_step, lag_weights};
pub use model::{CompiledEffect, CustomModel, custom_coefficient_key};
pub use plant_side::{Declared, Needs, fill_fast};
pub use signals::{FAMILIES, Family, FastInputs, Frame, MotionClocks, Signal, Unit};

use super::Axes3;

/// What a declared effect's coefficient multiplies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CustomKind {
    /// A bias: coefficient in °/h (gyro) or µg (accelerometer) per unit of the regressor.
    #[default]
    Bias,
    /// A scale-factor error: coefficient in ppm per unit of the regressor, times the true
    /// increment of the axis.
    ScaleFactor,
}

/// A sensor axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl Axis {
    /// 0, 1, 2.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// The axis of index `i` (0–2).
    pub fn of(i: usize) -> Axis {
        [Axis::X, Axis::Y, Axis::Z][i]
    }
}

/// One declared effect, as written in `[[sensor.gyro.custom]]` / `[[sensor.accel.custom]]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CustomSpec {
    /// Name (letters, digits, `_`; at most 32 characters), unique per sensor: `custom:NAME`
    /// in the diagnosis.
    pub name: String,
    /// Term on.
    #[serde(default = "on")]
    pub enabled: bool,
    /// Bias or scale factor.
    #[serde(default)]
    pub kind: CustomKind,
    /// The regressor: signals joined by `*`, each with an optional integer power `^N`
    /// (1 ≤ N ≤ 8), e.g. `"u_x*u_z"`, `"temp:block^2"`, `"dtemp_dt:block"`.
    pub regressor: String,
    /// Unit of the regressor as the author reads it (`"K/s"`, `"1"`, `"K^2"`, `"deg/s"`):
    /// checked against the signals' units, so a coefficient is never read in the wrong unit.
    pub unit: String,
    /// Axes the effect acts on.
    pub axes: Vec<Axis>,
    /// Coefficient per axis (x, y, z) per unit of the regressor: °/h (gyro bias), µg
    /// (accelerometer bias) or ppm (scale factor). Axes not listed in `axes` must be 0.
    #[serde(default)]
    pub coef: Axes3,
}

fn on() -> bool {
    true
}
