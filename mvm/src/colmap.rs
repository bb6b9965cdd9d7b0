//! Column maps: read a logger's file without editing it. A small TOML file names, for each
//! source column, the documented column it is (docs/measurement-format.md) with a unit
//! conversion (a named unit, or a factor and offset), and the columns to ignore:
//!
//! ```toml
//! ignore = ["status", "crc"]
//! [columns]
//! time_ms = { to = "t_s", unit = "ms" }
//! gx_arcsec = { to = "dtheta_x_rad", unit = "arcsec" }
//! ax = { to = "dv_x_mps", factor = 0.001 }
//! T_block_K = { to = "temp_gyro_c", unit = "K" }
//! ```
//!
//! Documented value = source value × factor + offset. Every mistake (an unknown unit, a unit
//! of another quantity, a target that is not a documented column, a source column the data file
//! lacks) is an error naming the map file and line.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use crate::measurement::MeasurementError;

/// One mapped column.
#[derive(Clone, Debug, PartialEq)]
pub struct MapEntry {
    /// The documented column it becomes.
    pub to: String,
    /// Documented value = source × factor + offset.
    pub factor: f64,
    /// Offset, in the documented column's unit.
    pub offset: f64,
    /// How the conversion was given (`"arcsec"`, `"x 0.001 + 0"`, `""` for a rename).
    pub how: String,
    /// Line of the entry in the map file.
    pub line: usize,
}

/// A column map (see the module documentation).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ColumnMap {
    /// Source column → entry.
    pub columns: BTreeMap<String, MapEntry>,
    /// Source columns to ignore, with their lines.
    pub ignore: BTreeMap<String, usize>,
    /// Map file name, for messages.
    pub source: String,
}

/// What a source column becomes under a map.
#[derive(Clone, Debug, PartialEq)]
pub enum Resolved<'a> {
    /// Not mapped: read under its own name.
    Keep,
    /// Read as `to`, converted.
    Map(&'a MapEntry),
    /// Ignored.
    Ignore,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEntry {
    to: String,
    unit: Option<String>,
    factor: Option<f64>,
    offset: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMap {
    #[serde(default)]
    ignore: Vec<String>,
    #[serde(default)]
    columns: BTreeMap<String, RawEntry>,
}

/// Quantity families by the documented column's unit suffix: (suffix, family, size of the
/// column's unit in the family's base unit).
const TARGET_UNITS: [(&str, &str, f64); 8] = [
    ("_rad", "angle", 1.0),
    ("_deg", "angle", std::f64::consts::PI / 180.0),
    ("_mps", "velocity", 1.0),
    ("_s", "time", 1.0),
    ("_c", "temperature", 1.0),
    ("_m", "length", 1.0),
    ("_dph", "rate", std::f64::consts::PI / 180.0 / 3600.0),
    ("_ug", "acceleration", 9.806_65e-6),
];

/// Named source units: (name, family, size in the family's base unit, offset in the base unit).
/// Temperatures convert to °C (K − 273.15, (°F − 32)·5/9).
const UNITS: [(&str, &str, f64, f64); 33] = [
    ("rad", "angle", 1.0, 0.0),
    ("mrad", "angle", 1e-3, 0.0),
    ("urad", "angle", 1e-6, 0.0),
    ("deg", "angle", std::f64::consts::PI / 180.0, 0.0),
    ("arcmin", "angle", std::f64::consts::PI / 10_800.0, 0.0),
    ("arcsec", "angle", std::f64::consts::PI / 648_000.0, 0.0),
    ("m/s", "velocity", 1.0, 0.0),
    ("mps", "velocity", 1.0, 0.0),
    ("mm/s", "velocity", 1e-3, 0.0),
    ("cm/s", "velocity", 1e-2, 0.0),
    ("ft/s", "velocity", 0.3048, 0.0),
    ("g*s", "velocity", 9.806_65, 0.0),
    ("s", "time", 1.0, 0.0),
    ("ms", "time", 1e-3, 0.0),
    ("us", "time", 1e-6, 0.0),
    ("ns", "time", 1e-9, 0.0),
    ("min", "time", 60.0, 0.0),
    ("h", "time", 3600.0, 0.0),
    ("C", "temperature", 1.0, 0.0),
    ("degC", "temperature", 1.0, 0.0),
    ("K", "temperature", 1.0, -273.15),
    ("F", "temperature", 5.0 / 9.0, -160.0 / 9.0),
    ("degF", "temperature", 5.0 / 9.0, -160.0 / 9.0),
    ("m", "length", 1.0, 0.0),
    ("km", "length", 1e3, 0.0),
    ("ft", "length", 0.3048, 0.0),
    ("deg/h", "rate", std::f64::consts::PI / 180.0 / 3600.0, 0.0),
    ("deg/s", "rate", std::f64::consts::PI / 180.0, 0.0),
    ("rad/s", "rate", 1.0, 0.0),
    ("ug", "acceleration", 9.806_65e-6, 0.0),
    ("mg", "acceleration", 9.806_65e-3, 0.0),
    ("g", "acceleration", 9.806_65, 0.0),
    ("m/s2", "acceleration", 1.0, 0.0),
];

/// Factor and offset converting a value in `unit` into the documented column `to`.
pub fn conversion(unit: &str, to: &str) -> Result<(f64, f64), String> {
    let (suffix, family, target) = TARGET_UNITS
        .iter()
        .find(|(s, _, _)| to.ends_with(s))
        .copied()
        .ok_or_else(|| {
            format!(
                "{to:?} has no unit to convert into (labels and quaternion components take no unit)"
            )
        })?;
    let names: Vec<&str> = UNITS
        .iter()
        .filter(|u| u.1 == family)
        .map(|u| u.0)
        .collect();
    let (_, fam, size, offset) = UNITS.iter().find(|u| u.0 == unit).copied().ok_or_else(|| {
        format!("unknown unit {unit:?}; for {to:?} ({family}, {suffix}) one of {names:?}")
    })?;
    if fam != family {
        return Err(format!(
            "unit {unit:?} ({fam}) does not fit {to:?} ({family}): one of {names:?}"
        ));
    }
    Ok((size / target, offset / target))
}

/// 1-based line of byte `pos` in `text`.
fn line_of(text: &str, pos: usize) -> usize {
    text[..pos.min(text.len())]
        .bytes()
        .filter(|b| *b == b'\n')
        .count()
        + 1
}

/// Line of the entry for `key` (`key = …` or `"key" = …` at a line start), else of the first
/// mention of `"key"` (an `ignore` item), else 0.
fn line_of_key(text: &str, key: &str) -> usize {
    let quoted = format!("\"{key}\"");
    for (i, l) in text.lines().enumerate() {
        let t = l.trim_start();
        for k in [key, quoted.as_str()] {
            if let Some(rest) = t.strip_prefix(k)
                && rest.trim_start().starts_with('=')
            {
                return i + 1;
            }
        }
    }
    text.find(&quoted).map_or(0, |p| line_of(text, p))
}

impl ColumnMap {
    /// Parses a map; `source` names the map file in errors. Targets are checked to be
    /// documented columns (`classify` says whether a name is one).
    pub fn parse(
        text: &str,
        source: &str,
        classify: impl Fn(&str) -> Result<bool, String>,
    ) -> Result<Self, MeasurementError> {
        let err = |line: usize, column: &str, message: String| MeasurementError {
            source_name: source.into(),
            row: line,
            column: column.into(),
            message: format!("column map, line {line}: {message}"),
        };
        let raw: RawMap = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(0, |s| line_of(text, s.start));
            err(line, "", e.message().to_string())
        })?;
        let mut map = ColumnMap {
            source: source.into(),
            ..Default::default()
        };
        for name in raw.ignore {
            let line = line_of_key(text, &name);
            map.ignore.insert(name, line);
        }
        let mut targets: BTreeMap<String, String> = BTreeMap::new();
        for (name, e) in raw.columns {
            let line = line_of_key(text, &name);
            if map.ignore.contains_key(&name) {
                return Err(err(line, &name, "both mapped and ignored".into()));
            }
            let numeric = classify(&e.to).map_err(|m| {
                err(
                    line,
                    &name,
                    format!("target {:?} is not a documented column: {m}", e.to),
                )
            })?;
            if let Some(other) = targets.insert(e.to.clone(), name.clone()) {
                return Err(err(
                    line,
                    &name,
                    format!("{:?} is also the target of {other:?}", e.to),
                ));
            }
            let (factor, offset, how) = match (&e.unit, e.factor, e.offset) {
                (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                    return Err(err(
                        line,
                        &name,
                        "give a unit or a factor/offset, not both".into(),
                    ));
                }
                (Some(u), None, None) => {
                    let (f, o) = conversion(u, &e.to).map_err(|m| err(line, &name, m))?;
                    (f, o, u.clone())
                }
                (None, None, None) => (1.0, 0.0, String::new()),
                (None, f, o) => {
                    let (f, o) = (f.unwrap_or(1.0), o.unwrap_or(0.0));
                    if !f.is_finite() || !o.is_finite() || f == 0.0 {
                        return Err(err(
                            line,
                            &name,
                            format!(
                                "factor must be finite and non-zero, offset finite (got {}, {})",
                                rins_plant::message::num(f),
                                rins_plant::message::num(o)
                            ),
                        ));
                    }
                    (f, o, format!("x {f} + {o}"))
                }
            };
            if !numeric && (factor != 1.0 || offset != 0.0) {
                return Err(err(
                    line,
                    &name,
                    format!("{:?} is a label column: it takes no unit conversion", e.to),
                ));
            }
            map.columns.insert(
                name,
                MapEntry {
                    to: e.to,
                    factor,
                    offset,
                    how,
                    line,
                },
            );
        }
        Ok(map)
    }

    /// Reads and parses a map file.
    pub fn load(
        path: &Path,
        classify: impl Fn(&str) -> Result<bool, String>,
    ) -> Result<Self, MeasurementError> {
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| MeasurementError {
            source_name: source.clone(),
            row: 0,
            column: String::new(),
            message: format!("cannot read the column map: {e}"),
        })?;
        Self::parse(&text, &source, classify)
    }

    /// What the source column `name` becomes.
    pub fn resolve(&self, name: &str) -> Resolved<'_> {
        if self.ignore.contains_key(name) {
            Resolved::Ignore
        } else if let Some(e) = self.columns.get(name) {
            Resolved::Map(e)
        } else {
            Resolved::Keep
        }
    }

    /// Checks that every source column the map names is in `header`: an entry for a column
    /// the file lacks is an error naming the map line (a typo would otherwise pass unseen).
    pub fn check_header(&self, header: &[String]) -> Result<(), MeasurementError> {
        let lines = self
            .columns
            .iter()
            .map(|(k, e)| (k, e.line))
            .chain(self.ignore.iter().map(|(k, l)| (k, *l)));
        for (name, line) in lines {
            if !header.iter().any(|h| h == name) {
                return Err(MeasurementError {
                    source_name: self.source.clone(),
                    row: line,
                    column: name.clone(),
                    message: format!(
                        "column map, line {line}: the data file has no column {name:?}; its columns are {header:?}"
                    ),
                });
            }
        }
        Ok(())
    }
}

/// What a map did to a file's columns, as the reports list it.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct MapSummary {
    /// The map file.
    pub map: String,
    /// `source -> documented (conversion)` per mapped column.
    pub mapped: Vec<String>,
    /// Source columns ignored.
    pub ignored: Vec<String>,
}

impl ColumnMap {
    /// The summary the reports list.
    pub fn summary(&self) -> MapSummary {
        MapSummary {
            map: self.source.clone(),
            mapped: self
                .columns
                .iter()
                .map(|(k, e)| {
                    if e.how.is_empty() {
                        format!("{k} -> {}", e.to)
                    } else {
                        format!("{k} -> {} ({})", e.to, e.how)
                    }
                })
                .collect(),
            ignored: self.ignore.keys().cloned().collect(),
        }
    }
}
