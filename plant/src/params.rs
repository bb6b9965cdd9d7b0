//! The flat parameter table: every scalar of a [`PlantConfig`] under its scenario-file key path
//! (`site.lat_deg`, `sensor.gyro.bias.dph[2]`, …) with its unit and valid range. One table serves
//! scenario validation, FMU parameter lists (name, unit, min, max) and tools that sweep
//! parameters: a key's range is written once, here.

use ciborium::Value;

use crate::config::PlantConfig;

/// A scalar parameter value.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    /// A real number.
    Real(f64),
    /// A whole number (`run.seed`, `run.substeps`).
    Integer(u64),
    /// A switch.
    Bool(bool),
    /// An enumeration, by name (`scheme.kind`, `sensor.gyro.position_bias.transition`, …).
    Enum(String),
}

/// One row of the table.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// Scenario-file key path, with `[i]` for array elements.
    pub path: String,
    /// Current value.
    pub value: ParamValue,
    /// Unit (SI-like symbols; `1` when dimensionless).
    pub unit: &'static str,
    /// Valid range for numbers.
    pub range: Option<(f64, f64)>,
}

/// Valid ranges by key path (array indices stripped). Keys not listed here are switches,
/// enumerations or structural (checked by [`PlantConfig::validate`] directly).
pub const RANGES: &[(&str, f64, f64)] = &[
    ("run.rate_hz", 1.0, 10_000.0),
    ("run.substeps", 1.0, 1000.0),
    ("run.seed", 0.0, u64::MAX as f64),
    ("site.lat_deg", -89.0, 89.0),
    ("site.lon_deg", -180.0, 360.0),
    ("site.height_m", -1000.0, 20_000.0),
    ("vehicle.azimuth_deg", -360.0, 360.0),
    ("vehicle.pitch_deg", -89.0, 89.0),
    ("vehicle.roll_deg", -180.0, 180.0),
    ("scheme.rate_dps", 1e-6, 100.0),
    ("scheme.accel_dps2", 1e-9, f64::INFINITY),
    ("scheme.dwell_s", 0.0, 1e7),
    ("scheme.lead_dwell_s", 0.0, 1e8),
    ("scheme.initial_outer_deg", -360.0, 360.0),
    ("scheme.initial_inner_deg", -360.0, 360.0),
    ("scheme.steps.angle_deg", -3600.0, 3600.0),
    ("scheme.steps.rate_dps", 1e-6, 100.0),
    ("scheme.steps.dwell_s", 0.0, 1e7),
    ("sensor.gyro.bias.dph", -100.0, 100.0),
    ("sensor.gyro.scale_factor.ppm", -1e5, 1e5),
    ("sensor.gyro.scale_factor_asymmetry.ppm", -1e5, 1e5),
    ("sensor.gyro.misalignment.arcsec", -3600.0, 3600.0),
    ("sensor.gyro.temperature_bias.ref_temp_c", -60.0, 130.0),
    ("sensor.gyro.temperature_bias.per_k", -10.0, 10.0),
    ("sensor.gyro.temperature_bias.per_k2", -1.0, 1.0),
    ("sensor.gyro.temperature_bias.per_k3", -0.1, 0.1),
    (
        "sensor.gyro.temperature_gradient_bias.dph_per_k",
        -10.0,
        10.0,
    ),
    ("sensor.gyro.g_sensitivity.dph_per_g", -100.0, 100.0),
    ("sensor.gyro.position_bias.dph", -100.0, 100.0),
    ("sensor.gyro.position_bias.ref_temp_c", -60.0, 130.0),
    ("sensor.gyro.position_bias.dph_per_k", -10.0, 10.0),
    ("sensor.gyro.position_bias.dph_per_k2", -1.0, 1.0),
    ("sensor.gyro.position_bias.dph_per_k3", -0.1, 0.1),
    ("sensor.gyro.dither_bias.amplitude_change", -1.0, 1.0),
    ("sensor.gyro.dither_bias.dph_per_amplitude", -100.0, 100.0),
    ("sensor.gyro.angle_random_walk.dpsh", 0.0, 10.0),
    ("sensor.gyro.bias_instability.sigma_dph", 0.0, 100.0),
    ("sensor.gyro.bias_instability.tau_s", 1e-3, 1e9),
    ("sensor.gyro.rate_random_walk.dph_per_sqrth", 0.0, 100.0),
    ("sensor.gyro.quantization.pulse", 0.0, 3600.0),
    ("sensor.gyro.custom.coef", -1e9, 1e9),
    ("sensor.accel.bias.ug", -1e5, 1e5),
    ("sensor.accel.scale_factor.ppm", -1e5, 1e5),
    ("sensor.accel.misalignment.arcsec", -3600.0, 3600.0),
    ("sensor.accel.temperature_bias.ref_temp_c", -60.0, 130.0),
    ("sensor.accel.temperature_bias.per_k", -1e4, 1e4),
    ("sensor.accel.temperature_bias.per_k2", -1e3, 1e3),
    ("sensor.accel.temperature_bias.per_k3", -1e2, 1e2),
    ("sensor.accel.velocity_random_walk.ug_per_sqrthz", 0.0, 1e4),
    ("sensor.accel.quantization.pulse", 0.0, 10.0),
    ("sensor.accel.custom.coef", -1e9, 1e9),
    ("sensor.encoder.scale_factor.ppm", -1e5, 1e5),
    ("sensor.encoder.offset.arcsec", -36_000.0, 36_000.0),
    (
        "sensor.encoder.quantization.resolution_arcsec",
        1e-6,
        3600.0,
    ),
    ("sensor.temperature.offset.k", -50.0, 50.0),
    ("sensor.temperature.noise.sigma_k", 0.0, 10.0),
    ("sensor.temperature.resolution.lsb_k", 1e-6, 10.0),
    ("thermal.step_s", 1e-3, 3600.0),
    (
        "thermal.chamber.temp_c",
        crate::thermal::CHAMBER_MIN_C,
        crate::thermal::CHAMBER_MAX_C,
    ),
    ("thermal.chamber.profile", f64::NEG_INFINITY, f64::INFINITY),
    ("thermal.capacitance_j_per_k", 1e-3, 1e9),
    ("thermal.power_w", 0.0, 1e4),
    ("thermal.g_board_housing_w_per_k", 0.0, 1e6),
    ("thermal.g_gyro_housing_w_per_k", 0.0, 1e6),
    ("thermal.g_accel_housing_w_per_k", 0.0, 1e6),
    ("thermal.g_housing_chamber_w_per_k", 1e-6, 1e6),
    ("thermal.g_gyro_gyro_w_per_k", 0.0, 1e6),
    ("thermal.g_board_gyro_w_per_k", 0.0, 1e6),
    ("thermal.g_board_gyro_convection_w_per_k", 0.0, 1e6),
    ("thermal.board_to_block_dir_body", -1.0, 1.0),
    // The carrier (docs/carrier.md).
    ("carrier.lever_arm_m", -500.0, 500.0),
    ("carrier.ship.lat_deg", -80.0, 80.0),
    ("carrier.ship.lon_deg", -180.0, 360.0),
    ("carrier.ship.height_m", -1000.0, 1000.0),
    ("carrier.ship.legs.heading_deg", -360.0, 360.0),
    ("carrier.ship.legs.speed_kn", 0.0, 60.0),
    ("carrier.ship.legs.duration_s", 0.001, 1e8),
    ("carrier.ship.turn_rate_dps", 0.01, 10.0),
    ("carrier.ship.accel_mps2", 0.001, 5.0),
    ("carrier.ship.sea.sea_state", 0.0, 6.0),
    ("carrier.ship.sea.hs_m", 0.0, 20.0),
    ("carrier.ship.sea.tp_s", 2.0, 30.0),
    ("carrier.ship.sea.gamma", 1.0, 7.0),
    ("carrier.ship.sea.heading_to_waves_deg", -360.0, 360.0),
    ("carrier.ship.sea.components", 1.0, 256.0),
    ("carrier.ship.sea.band", 0.1, 10.0),
    ("carrier.ship.sea.rao.roll.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.roll.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.roll.damping", 0.01, 2.0),
    ("carrier.ship.sea.rao.pitch.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.pitch.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.pitch.damping", 0.01, 2.0),
    ("carrier.ship.sea.rao.yaw.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.yaw.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.yaw.damping", 0.01, 2.0),
    ("carrier.ship.sea.rao.heave.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.heave.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.heave.damping", 0.01, 2.0),
    ("carrier.ship.sea.rao.surge.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.surge.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.surge.damping", 0.01, 2.0),
    ("carrier.ship.sea.rao.sway.gain", 0.0, 10.0),
    ("carrier.ship.sea.rao.sway.natural_period_s", 0.0, 100.0),
    ("carrier.ship.sea.rao.sway.damping", 0.01, 2.0),
];

/// Names accepted by each enumeration parameter, in the order FMUs number them (1-based).
pub const ENUMS: &[(&str, &[&str])] = &[
    (
        "scheme.kind",
        &[
            "sixteen-position",
            "eight-position",
            "continuous",
            "static",
            "z-up-calibration",
            "z-down-calibration",
            "steps",
        ],
    ),
    ("scheme.axis", &["outer", "inner"]),
    ("sensor.gyro.position_bias.transition", &["cosine", "step"]),
    ("carrier.kind", &["static", "ship", "trajectory"]),
    (
        "carrier.ship.sea.spectrum",
        &["none", "pierson-moskowitz", "jonswap"],
    ),
];

/// The names `path` accepts, if it is an enumeration.
pub fn enum_choices(path: &str) -> Option<&'static [&'static str]> {
    let key = key_of(path);
    ENUMS.iter().find(|(k, _)| *k == key).map(|(_, c)| *c)
}

/// Strips array indices: `sensor.gyro.bias.dph[2]` → `sensor.gyro.bias.dph`.
pub fn key_of(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut depth = 0;
    for ch in path.chars() {
        match ch {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ if depth == 0 => out.push(ch),
            _ => {}
        }
    }
    out
}

/// The valid range of `path`, if it is a ranged number.
pub fn range_for(path: &str) -> Option<(f64, f64)> {
    let key = key_of(path);
    RANGES
        .iter()
        .find(|(k, _, _)| *k == key)
        .map(|&(_, lo, hi)| (lo, hi))
}

/// The unit of `path`, from the unit in its key name (and, for the bare polynomial and pulse
/// keys, from the sensor they belong to).
pub fn unit_for(path: &str) -> &'static str {
    let key = key_of(path);
    let last = key.rsplit('.').next().unwrap_or("");
    let accel = key.starts_with("sensor.accel");
    match last {
        "per_k" => {
            if accel {
                "ug/K"
            } else {
                "deg/h/K"
            }
        }
        "per_k2" => {
            if accel {
                "ug/K2"
            } else {
                "deg/h/K2"
            }
        }
        "per_k3" => {
            if accel {
                "ug/K3"
            } else {
                "deg/h/K3"
            }
        }
        "pulse" => {
            if accel {
                "m/s"
            } else {
                "arcsec"
            }
        }
        "profile" => "s|degC",
        _ => [
            ("_dph_per_sqrth", "deg/h/sqrt(h)"),
            ("_dph_per_amplitude", "deg/h"),
            ("_dph_per_g", "deg/h/g"),
            ("_dph_per_k3", "deg/h/K3"),
            ("_dph_per_k2", "deg/h/K2"),
            ("_dph_per_k", "deg/h/K"),
            ("_dph", "deg/h"),
            ("dph", "deg/h"),
            ("dpsh", "deg/sqrt(h)"),
            ("ppm", "ppm"),
            ("arcsec", "arcsec"),
            ("ug_per_sqrthz", "ug/sqrt(Hz)"),
            ("ug", "ug"),
            ("_mps2", "m/s2"),
            ("_kn", "kn"),
            ("_dps2", "deg/s2"),
            ("_dps", "deg/s"),
            ("_deg", "deg"),
            ("_hz", "Hz"),
            ("_s", "s"),
            ("_c", "degC"),
            ("_m", "m"),
            ("_w_per_k", "W/K"),
            ("_j_per_k", "J/K"),
            ("_w", "W"),
            ("_k", "K"),
        ]
        .iter()
        .find(|(suffix, _)| last == suffix.trim_start_matches('_') || last.ends_with(suffix))
        .map(|(_, u)| *u)
        .unwrap_or("1"),
    }
}

/// Scenario-file path of a top-level `PlantConfig` field (`rate_hz` lives in `[run]`).
fn section_of(field: &str) -> String {
    match field {
        "rate_hz" | "substeps" | "seed" => format!("run.{field}"),
        _ => field.to_string(),
    }
}

/// The configuration as a value tree. CBOR's data model keeps what JSON cannot: NaN and ±inf
/// (`scheme.accel_dps2 = inf`) and the whole u64 range (`run.seed`), so the tree round-trips
/// every configuration exactly.
fn tree(cfg: &PlantConfig) -> Value {
    Value::serialized(cfg).expect("PlantConfig serialises")
}

fn walk(prefix: &str, v: &Value, out: &mut Vec<Param>) {
    let number = |value: ParamValue| Param {
        path: prefix.into(),
        value,
        unit: unit_for(prefix),
        range: range_for(prefix),
    };
    match v {
        Value::Map(m) => {
            for (k, v) in m {
                let k = k.as_text().unwrap_or_default();
                let p = if prefix.is_empty() {
                    section_of(k)
                } else {
                    format!("{prefix}.{k}")
                };
                walk(&p, v, out);
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                walk(&format!("{prefix}[{i}]"), v, out);
            }
        }
        Value::Bool(b) => out.push(Param {
            path: prefix.into(),
            value: ParamValue::Bool(*b),
            unit: "1",
            range: None,
        }),
        // A declared effect's name, kind, regressor, unit and axes are its structure, fixed
        // when the model is built (like `scheme.steps`); its switch and coefficients are
        // parameters.
        Value::Text(_) if prefix.contains(".custom[") => {}
        // A file name (and what to do after its end) is no parameter an FMU or a sweep can set
        // (the trajectory is data).
        Value::Text(_) if prefix.starts_with("carrier.trajectory.") => {}
        Value::Text(s) => out.push(Param {
            path: prefix.into(),
            value: ParamValue::Enum(s.clone()),
            unit: "1",
            range: None,
        }),
        Value::Integer(i) => out.push(number(match u64::try_from(*i) {
            Ok(u) if prefix == "run.seed" || prefix == "run.substeps" => ParamValue::Integer(u),
            _ => ParamValue::Real(i128::from(*i) as f64),
        })),
        Value::Float(x) => out.push(number(ParamValue::Real(*x))),
        // Nothing in a PlantConfig serialises to anything else.
        _ => {}
    }
}

/// Every scalar parameter of `cfg`, in a stable order.
pub fn flatten(cfg: &PlantConfig) -> Vec<Param> {
    let mut out = Vec::new();
    walk("", &tree(cfg), &mut out);
    out
}

/// Why a parameter could not be set.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// No such key path.
    #[error("unknown parameter {0:?}")]
    Unknown(String),
    /// The value has the wrong kind or is not accepted (e.g. an unknown enumeration name).
    #[error("parameter {path}: {message}")]
    Invalid {
        /// Key path.
        path: String,
        /// What is wrong.
        message: String,
    },
}

/// `cfg` with the parameter at `path` set to `value` (range-checked by [`PlantConfig::validate`]).
pub fn set(cfg: &PlantConfig, path: &str, value: ParamValue) -> Result<PlantConfig, ParamError> {
    apply(cfg, std::iter::once((path, value)))
}

/// `cfg` with every `(path, value)` set, in one pass (an FMU sets all its parameters at once).
pub fn apply<'a>(
    cfg: &PlantConfig,
    values: impl IntoIterator<Item = (&'a str, ParamValue)>,
) -> Result<PlantConfig, ParamError> {
    let mut v = tree(cfg);
    let mut last = String::new();
    for (path, value) in values {
        set_node(&mut v, path, value)?;
        last = path.to_string();
    }
    v.deserialized().map_err(|e| ParamError::Invalid {
        path: last,
        message: e.to_string(),
    })
}

fn set_node(v: &mut Value, path: &str, value: ParamValue) -> Result<(), ParamError> {
    let inner = path
        .strip_prefix("run.")
        .filter(|p| ["rate_hz", "substeps", "seed"].contains(p))
        .unwrap_or(path);
    let mut node = v;
    for part in inner.split('.') {
        let (name, idx) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        node = match node {
            Value::Map(m) => m
                .iter_mut()
                .find(|(k, _)| k.as_text() == Some(name))
                .map(|(_, v)| v),
            _ => None,
        }
        .ok_or_else(|| ParamError::Unknown(path.into()))?;
        for ix in idx.split(']').filter(|s| !s.is_empty()) {
            let i: usize = ix
                .trim_start_matches('[')
                .parse()
                .map_err(|_| ParamError::Unknown(path.into()))?;
            node = match node {
                Value::Array(a) => a.get_mut(i),
                _ => None,
            }
            .ok_or_else(|| ParamError::Unknown(path.into()))?;
        }
    }
    let kind_ok = matches!(
        (&*node, &value),
        (
            Value::Integer(_) | Value::Float(_),
            ParamValue::Real(_) | ParamValue::Integer(_)
        ) | (Value::Bool(_), ParamValue::Bool(_))
            | (Value::Text(_), ParamValue::Enum(_))
    );
    if !kind_ok {
        let like = match &*node {
            Value::Bool(_) => "a switch (true/false)",
            Value::Text(_) => "an enumeration name",
            Value::Integer(_) | Value::Float(_) => "a number",
            _ => "a scalar",
        };
        return Err(ParamError::Invalid {
            path: path.into(),
            message: format!("expected {like}, got {value:?}"),
        });
    }
    if let (ParamValue::Enum(name), Some(choices)) = (&value, enum_choices(path))
        && !choices.contains(&name.as_str())
    {
        return Err(ParamError::Invalid {
            path: path.into(),
            message: format!("unknown variant {name:?}, expected one of {choices:?}"),
        });
    }
    *node = match (value, &*node) {
        // A whole-number field (`run.seed`, `run.substeps`) given as a real: only whole values.
        (ParamValue::Real(x), Value::Integer(_)) => {
            if !(x >= 0.0 && x.fract() == 0.0 && x <= u64::MAX as f64) {
                return Err(ParamError::Invalid {
                    path: path.into(),
                    message: format!("expected a whole number ≥ 0, got {x}"),
                });
            }
            Value::Integer((x as u64).into())
        }
        (ParamValue::Real(x), _) => Value::Float(x),
        (ParamValue::Integer(u), Value::Integer(_)) => Value::Integer(u.into()),
        (ParamValue::Integer(u), _) => Value::Float(u as f64),
        (ParamValue::Bool(b), _) => Value::Bool(b),
        (ParamValue::Enum(s), _) => Value::Text(s),
    };
    Ok(())
}

#[cfg(test)]
mod params_tests;
