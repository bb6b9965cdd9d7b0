//! A parsed measurement file, its errors, and the documented columns of the measurement format
//! (docs/measurement-format.md): what both parsers ([`crate::csv`] and [`crate::parquet`]) build
//! and every layer of the reader beneath them (column maps, the header checks, the physical
//! ranges, the chunks) shares.

use std::collections::{BTreeMap, HashMap};
use std::sync::OnceLock;

/// Columns every file needs (plus attitude and at least one temperature).
pub const REQUIRED: [&str; 7] = [
    "t_s",
    "dtheta_x_rad",
    "dtheta_y_rad",
    "dtheta_z_rad",
    "dv_x_mps",
    "dv_y_mps",
    "dv_z_mps",
];
/// Attitude as gimbal angles …
pub const GIMBAL: [&str; 2] = ["outer_deg", "inner_deg"];
/// … or as the IMU quaternion q_b^n.
pub const QUATERNION: [&str; 4] = ["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"];
/// Optional numeric columns with a fixed meaning.
pub const OPTIONAL: [&str; 4] = ["sample", "lat_deg", "lon_deg", "height_m"];
/// Optional label columns.
pub const LABELS: [&str; 3] = ["run", "segment", "position"];
/// Prefixes of optional numeric families: temperatures, truth and per-effect columns.
pub const FAMILIES: [(&str, &str); 5] = [
    ("temp_", "_c"),
    ("dtheta_true_", "_rad"),
    ("dv_true_", "_mps"),
    ("gyro_", "_dph"),
    ("accel_", "_ug"),
];

/// The CSV names of the plant's output table ([`rins_plant::output_columns`]) for a static
/// carrier, every term, each with whether it is numeric (`false`: the station label). A moving
/// carrier's truth columns are not among them: the model is of a static carrier.
fn plant_columns() -> &'static HashMap<String, bool> {
    use rins_plant::effects::{AccelTerm, GyroTerm};
    use rins_plant::output_columns::{Group, Read, entries};
    static NAMES: OnceLock<HashMap<String, bool>> = OnceLock::new();
    NAMES.get_or_init(|| {
        let groups = [Group::Measured, Group::Setup, Group::Truth, Group::Effects];
        entries(&groups, &GyroTerm::ALL, &AccelTerm::ALL, true)
            .into_iter()
            .flat_map(|e| {
                let numeric = !matches!(e.column.read, Read::Position);
                e.names().into_iter().map(move |n| (n, numeric))
            })
            .collect()
    })
}

/// Units a quantity may wrongly be given in, to say what was expected.
const WRONG_UNITS: [&str; 12] = [
    "_deg", "_arcsec", "_mrad", "_urad", "_dph", "_dps", "_g", "_ug", "_ms", "_min", "_h", "_k",
];

/// A parsed measurement file.
#[derive(Clone, Debug, Default)]
pub struct Measurement {
    /// Numeric columns by name.
    pub columns: BTreeMap<String, Vec<f64>>,
    /// Label columns by name.
    pub labels: BTreeMap<String, LabelColumn>,
    /// Data rows.
    pub rows: usize,
    /// Row ranges [start, end) of each (run, segment).
    pub segments: Vec<(String, String, usize, usize)>,
    /// Source columns a column map said to ignore.
    pub ignored: Vec<String>,
    /// When `t_s` was read from a Parquet time type (TIMESTAMP, TIME or INT96): the first row's
    /// time in ns since the Unix epoch (TIMESTAMP, INT96) or since midnight (TIME); `t_s`
    /// counts seconds from it.
    pub t0_ns: Option<i64>,
}

/// A label column: the distinct labels and, per row, the index of its label (labels repeat
/// over millions of rows; one string each is enough).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LabelColumn {
    /// Distinct labels in order of first appearance.
    pub names: Vec<String>,
    /// Per row, the index into `names`.
    pub index: Vec<u32>,
}

impl LabelColumn {
    /// Label of row `i`.
    pub fn get(&self, i: usize) -> &str {
        &self.names[self.index[i] as usize]
    }

    pub(crate) fn push(&mut self, label: &str) {
        let k = match self.index.last() {
            Some(&k) if self.names[k as usize] == label => k,
            _ => match self.names.iter().position(|n| n == label) {
                Some(k) => k as u32,
                None => {
                    self.names.push(label.to_string());
                    (self.names.len() - 1) as u32
                }
            },
        };
        self.index.push(k);
    }

    /// Appends the rows of `other`.
    pub(crate) fn append(&mut self, other: LabelColumn) {
        for i in other.index {
            self.push(&other.names[i as usize]);
        }
    }
}

impl Measurement {
    /// A numeric column.
    pub fn col(&self, name: &str) -> Option<&[f64]> {
        self.columns.get(name).map(Vec::as_slice)
    }
    /// Names of the temperature columns.
    pub fn temperature_columns(&self) -> Vec<&str> {
        self.columns
            .keys()
            .filter(|k| k.starts_with("temp_") && k.ends_with("_c"))
            .map(String::as_str)
            .collect()
    }
    pub(crate) fn append_chunk(&mut self, m: Measurement) {
        if self.rows == 0 {
            *self = m;
            return;
        }
        let r0 = self.rows;
        for (name, v) in m.columns {
            self.columns.entry(name).or_default().extend(v);
        }
        for (name, l) in m.labels {
            self.labels.entry(name).or_default().append(l);
        }
        self.segments.extend(
            m.segments
                .into_iter()
                .map(|(r, s, a, b)| (r, s, a + r0, b + r0)),
        );
        self.rows += m.rows;
    }
}

/// An error in a measurement file; `row` counts data rows from 1 (the header is row 0). The
/// message says where ([`rins_plant::message::file_location`]): the whole file (row 0 without a
/// column), the header's column, the row, or the row's column, quoted to its first 80
/// characters.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{source_name}: {}: {message}", rins_plant::message::file_location(*.row, .column))]
pub struct MeasurementError {
    /// File.
    pub source_name: String,
    /// Data row (1-based; 0 = the header, or the whole file when `column` is empty).
    pub row: usize,
    /// Column name (empty: the whole row, or the whole file).
    pub column: String,
    /// What is wrong.
    pub message: String,
}

/// Whether `name` is a documented column: `Ok(true)` numeric, `Ok(false)` a label, `Err` why
/// not (a known quantity in another unit, or an unknown column).
pub fn classify(name: &str) -> Result<bool, String> {
    // Ok(true): numeric, Ok(false): label.
    if REQUIRED.contains(&name)
        || GIMBAL.contains(&name)
        || QUATERNION.contains(&name)
        || OPTIONAL.contains(&name)
    {
        return Ok(true);
    }
    if LABELS.contains(&name) {
        return Ok(false);
    }
    if FAMILIES
        .iter()
        .any(|(p, s)| name.starts_with(p) && name.ends_with(s) && name.len() > p.len() + s.len())
    {
        return Ok(true);
    }
    // Any other column the plant writes (its output table): the plant's own CSV is always a
    // measurement file, whatever quantity the table gains.
    if let Some(&numeric) = plant_columns().get(name) {
        return Ok(numeric);
    }
    // A known quantity in a wrong unit?
    for want in REQUIRED.iter().chain(&GIMBAL).chain(&OPTIONAL[1..]) {
        let base = want.rsplit_once('_').map(|(b, _)| b).unwrap_or(want);
        if let Some(unit) = name
            .strip_prefix(base)
            .filter(|u| WRONG_UNITS.contains(u) || u.starts_with('_'))
        {
            return Err(format!(
                "unit {unit:?} not accepted; expected {want} (convert it with a column map, --map FILE: docs/measurement-format.md)"
            ));
        }
    }
    Err(format!(
        "unknown column; accepted: {:?}, {:?} or {:?}, {:?}, labels {:?}, and families temp_*_c, dtheta_true_*_rad, dv_true_*_mps, gyro_*_dph, accel_*_ug; a logger's own names and units are read with a column map (--map FILE: source column -> documented column with its unit, or ignore it; docs/measurement-format.md)",
        REQUIRED, GIMBAL, QUATERNION, OPTIONAL, LABELS
    ))
}
