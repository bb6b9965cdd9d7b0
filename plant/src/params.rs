//! The flat parameter table: every scalar of a [`PlantConfig`] under its scenario-file key path
//! (`site.lat_deg`, `sensor.gyro.bias.dph[2]`, …) with its unit and valid range. One table serves
//! scenario validation, FMU parameter lists (name, unit, min, max) and tools that sweep
//! parameters: a key's range is written once, here. The table is read and set through the typed
//! walk of [`fields`] (no serialisation of the configuration).

use std::borrow::Cow;
use std::collections::HashMap;

use crate::config::PlantConfig;

pub mod fields;

use fields::{ParamFields, Slot};

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
    ("sensor.gyro.nav_field_bias.dph_enu", -100.0, 100.0),
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
    ("carrier.ship.sea.seed", 0.0, u64::MAX as f64),
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
    ("carrier.ship.sea.realisation", &["per-run", "fixed"]),
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
            ("dph_enu", "deg/h"),
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

/// Text that is structure or data rather than a parameter. A declared effect's name, kind,
/// regressor, unit and axes are fixed when the model is built (like `scheme.steps`; its switch
/// and coefficients are parameters), and a trajectory's file name and what to do after its end
/// are data no FMU or sweep sets.
fn structural_text(path: &str) -> bool {
    path.contains(".custom[") || path.starts_with("carrier.trajectory.")
}

/// The table's row for a place of the configuration, if it is a parameter.
fn row(path: &str, slot: &Slot<'_>) -> Option<Param> {
    // Only the run's seed and step count are shown as whole numbers; other whole-number fields
    // (`sea_state`, `components`) are numbers like any other.
    let whole = path == "run.seed" || path == "run.substeps" || path == "carrier.ship.sea.seed";
    let value = match slot {
        Slot::Group => return None,
        Slot::Real(x) => ParamValue::Real(**x),
        Slot::Integer(u) if whole => ParamValue::Integer(**u),
        Slot::Integer(u) => ParamValue::Real(**u as f64),
        Slot::Count(u) if whole => ParamValue::Integer(u64::from(**u)),
        Slot::Count(u) => ParamValue::Real(f64::from(**u)),
        Slot::Bool(b) => {
            return Some(Param {
                path: path.into(),
                value: ParamValue::Bool(**b),
                unit: "1",
                range: None,
            });
        }
        Slot::Enum(_) | Slot::Text(_) if structural_text(path) => return None,
        Slot::Enum(c) => ParamValue::Enum(c.name().into()),
        Slot::Text(s) => ParamValue::Enum(s.to_string()),
    };
    let number = matches!(value, ParamValue::Real(_) | ParamValue::Integer(_));
    Some(Param {
        path: path.into(),
        value,
        unit: if number { unit_for(path) } else { "1" },
        range: if number { range_for(path) } else { None },
    })
}

/// Every scalar parameter of `cfg`, in a stable order: the order of the fields in the
/// configuration types (that of the scenario file), array elements in index order.
pub fn flatten(cfg: &PlantConfig) -> Vec<Param> {
    // The walk lends places mutably (one walk serves reading and setting); a copy is cheap
    // next to the table it gives.
    let mut cfg = cfg.clone();
    let mut out = Vec::new();
    cfg.visit_fields(&mut String::new(), &mut |path, slot| {
        out.extend(row(path, &slot));
    });
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

/// `cfg` with every `(path, value)` set, in one pass over the configuration (an FMU sets all
/// its parameters at once). A path may be given more than once: the last value stays. Errors
/// are those of the first bad `(path, value)` in order; a value that is accepted but does not
/// fit its field (a step count beyond u32, an unknown name for an enumeration outside
/// [`ENUMS`]) is reported, with its path, only if no other value is bad and no later value of
/// the same path replaces it.
pub fn apply<'a>(
    cfg: &PlantConfig,
    values: impl IntoIterator<Item = (&'a str, ParamValue)>,
) -> Result<PlantConfig, ParamError> {
    let values: Vec<(&str, ParamValue)> = values.into_iter().collect();
    let mut scratch = String::new();
    let keys: Vec<Option<Cow<'_, str>>> = values
        .iter()
        .map(|(path, _)| canonical(path, &mut scratch))
        .collect();
    apply_in_order(cfg, &values, &keys).unwrap_or_else(|| apply_any_order(cfg, &values, &keys))
}

/// [`apply`] for values in the table's order (as an FMU and a sweep give them): each is matched
/// as the walk passes its place. `None` if a value is not met in that order (an unknown path, or
/// values in another order), with nothing decided.
fn apply_in_order(
    cfg: &PlantConfig,
    values: &[(&str, ParamValue)],
    keys: &[Option<Cow<'_, str>>],
) -> Option<Result<PlantConfig, ParamError>> {
    let mut out = cfg.clone();
    let mut next = 0;
    let mut bad = None;
    let mut misfit = None;
    out.visit_fields(&mut String::new(), &mut |key, mut slot| {
        if bad.is_some() {
            return;
        }
        let mut last_misfit = None;
        while let Some(Some(k)) = keys.get(next)
            && k == key
        {
            let (path, value) = &values[next];
            next += 1;
            match put(path, &mut slot, value) {
                Ok(()) => last_misfit = None,
                // Every value before this one was met and taken: it is the first bad one.
                Err(Put::Bad(e)) => {
                    bad = Some(e);
                    return;
                }
                Err(Put::Misfit(e)) => last_misfit = Some(e),
            }
        }
        if misfit.is_none() {
            misfit = last_misfit;
        }
    });
    match (bad, misfit) {
        (Some(e), _) => Some(Err(e)),
        _ if next < values.len() => None,
        (None, Some(e)) => Some(Err(e)),
        (None, None) => Some(Ok(out)),
    }
}

/// [`apply`] for values in any order: they are looked up by key path as the walk passes.
fn apply_any_order(
    cfg: &PlantConfig,
    values: &[(&str, ParamValue)],
    keys: &[Option<Cow<'_, str>>],
) -> Result<PlantConfig, ParamError> {
    // The first error in the order of `values`.
    fn note(i: usize, e: ParamError, first: &mut Option<(usize, ParamError)>) {
        if first.as_ref().is_none_or(|(j, _)| i < *j) {
            *first = Some((i, e));
        }
    }
    let mut first: Option<(usize, ParamError)> = None;
    // Indices of the values for each place, by its key path as the walk spells it.
    let mut wanted: HashMap<&str, Vec<usize>> = HashMap::with_capacity(values.len());
    for (i, key) in keys.iter().enumerate() {
        match key {
            Some(key) => wanted.entry(key).or_default().push(i),
            None => note(i, ParamError::Unknown(values[i].0.into()), &mut first),
        }
    }
    let mut out = cfg.clone();
    let mut found = vec![false; values.len()];
    let mut misfit: Option<ParamError> = None;
    out.visit_fields(&mut String::new(), &mut |key, mut slot| {
        let Some(ix) = wanted.get(key) else {
            return;
        };
        let mut last_misfit = None;
        for &i in ix {
            found[i] = true;
            let (path, value) = &values[i];
            match put(path, &mut slot, value) {
                Ok(()) => last_misfit = None,
                Err(Put::Bad(e)) => note(i, e, &mut first),
                Err(Put::Misfit(e)) => last_misfit = Some(e),
            }
        }
        if misfit.is_none() {
            misfit = last_misfit;
        }
    });
    for (i, (path, _)) in values.iter().enumerate() {
        if !found[i] {
            note(i, ParamError::Unknown((*path).into()), &mut first);
        }
    }
    match (first, misfit) {
        (Some((_, e)), _) | (None, Some(e)) => Err(e),
        (None, None) => Ok(out),
    }
}

/// `path` spelt as the walk spells it (`seed` → `run.seed`, `dph[02]` → `dph[2]`), or `None`
/// if an index is no number. The grammar is that of the scenario keys: names joined by `.`,
/// each with any number of `[i]`; the `run.` of the three run keys is optional. `scratch` is
/// working space; a path already spelt so is returned as it is.
fn canonical<'p>(path: &'p str, scratch: &mut String) -> Option<Cow<'p, str>> {
    let inner = path
        .strip_prefix("run.")
        .filter(|p| ["rate_hz", "substeps", "seed"].contains(p))
        .unwrap_or(path);
    scratch.clear();
    for (n, part) in inner.split('.').enumerate() {
        let (name, idx) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if n > 0 {
            scratch.push('.');
        } else if matches!(name, "rate_hz" | "substeps" | "seed") {
            // The run's keys without their table (the walk names them `run.*`).
            scratch.push_str("run.");
        }
        scratch.push_str(name);
        for ix in idx.split(']').filter(|s| !s.is_empty()) {
            fields::push_element(scratch, ix.trim_start_matches('[').parse().ok()?);
        }
    }
    Some(if scratch == path {
        Cow::Borrowed(path)
    } else {
        Cow::Owned(scratch.clone())
    })
}

/// Why a value was not put in its place.
enum Put {
    /// The value is of the wrong kind or refused outright.
    Bad(ParamError),
    /// The value is accepted but does not fit the field.
    Misfit(ParamError),
}

/// Puts `value` in `slot` (the place `path` names).
fn put(path: &str, slot: &mut Slot<'_>, value: &ParamValue) -> Result<(), Put> {
    let invalid = |message: String| ParamError::Invalid {
        path: path.into(),
        message,
    };
    // A whole-number field given as a real: only whole values.
    let whole = |x: f64| {
        if x >= 0.0 && x.fract() == 0.0 && x <= u64::MAX as f64 {
            // Saturating: 2^64, the one real above u64::MAX that passes, is u64::MAX.
            Ok(x as u64)
        } else {
            Err(Put::Bad(invalid(format!(
                "expected a whole number ≥ 0, got {}",
                crate::message::Num(x)
            ))))
        }
    };
    // A whole number for a u32 field: the value is accepted, but must fit when it stays.
    let fit = |u: u64| {
        u32::try_from(u).map_err(|_| {
            Put::Misfit(invalid(format!(
                "expected a whole number in [0, {}], got {u}",
                u32::MAX
            )))
        })
    };
    match (slot, value) {
        (Slot::Real(x), ParamValue::Real(v)) => **x = *v,
        (Slot::Real(x), ParamValue::Integer(u)) => **x = *u as f64,
        (Slot::Integer(n), ParamValue::Real(v)) => **n = whole(*v)?,
        (Slot::Integer(n), ParamValue::Integer(u)) => **n = *u,
        (Slot::Count(n), ParamValue::Real(v)) => **n = fit(whole(*v)?)?,
        (Slot::Count(n), ParamValue::Integer(u)) => **n = fit(*u)?,
        (Slot::Bool(b), ParamValue::Bool(v)) => **b = *v,
        (Slot::Enum(c), ParamValue::Enum(name)) => {
            if !c.set_name(name) {
                let e = |choices: &[&str]| {
                    invalid(format!(
                        "unknown variant {name:?}, expected one of {choices:?}"
                    ))
                };
                // A scenario key's names are checked with the value; a structural
                // enumeration's (a declared effect's axes) only when the value stays.
                return Err(match enum_choices(path) {
                    Some(choices) => Put::Bad(e(choices)),
                    None => Put::Misfit(e(c.names())),
                });
            }
        }
        (Slot::Text(t), ParamValue::Enum(s)) => s.clone_into(*t),
        (slot, value) => {
            let like = match slot {
                Slot::Bool(_) => "a switch (true/false)",
                Slot::Enum(_) | Slot::Text(_) => "an enumeration name",
                Slot::Real(_) | Slot::Integer(_) | Slot::Count(_) => "a number",
                Slot::Group => "a scalar",
            };
            return Err(Put::Bad(invalid(format!("expected {like}, got {value:?}"))));
        }
    }
    Ok(())
}

#[cfg(test)]
mod params_tests;
