//! The measurement format (docs/measurement-format.md): CSV that another tool can write, with
//! units in the column names. The reader is strict: every problem is an error naming the row and
//! column, and nothing is silently dropped.

use std::collections::BTreeMap;
use std::path::Path;

/// Columns every file needs (plus attitude and at least one temperature).
pub const REQUIRED: [&str; 7] = ["t_s", "dtheta_x_rad", "dtheta_y_rad", "dtheta_z_rad", "dv_x_mps", "dv_y_mps", "dv_z_mps"];
/// Attitude as gimbal angles …
pub const GIMBAL: [&str; 2] = ["outer_deg", "inner_deg"];
/// … or as the IMU quaternion q_b^n.
pub const QUATERNION: [&str; 4] = ["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"];
/// Optional numeric columns with a fixed meaning.
pub const OPTIONAL: [&str; 4] = ["sample", "lat_deg", "lon_deg", "height_m"];
/// Optional label columns.
pub const LABELS: [&str; 3] = ["run", "segment", "position"];
/// Prefixes of optional numeric families: temperatures, truth and per-effect columns.
pub const FAMILIES: [(&str, &str); 5] = [("temp_", "_c"), ("dtheta_true_", "_rad"), ("dv_true_", "_mps"), ("gyro_", "_dph"), ("accel_", "_ug")];

/// Units a quantity may wrongly be given in, to say what was expected.
const WRONG_UNITS: [&str; 12] = ["_deg", "_arcsec", "_mrad", "_urad", "_dph", "_dps", "_g", "_ug", "_ms", "_min", "_h", "_k"];

/// A parsed measurement file.
#[derive(Clone, Debug, Default)]
pub struct Measurement {
    /// Numeric columns by name.
    pub columns: BTreeMap<String, Vec<f64>>,
    /// Label columns by name.
    pub labels: BTreeMap<String, Vec<String>>,
    /// Data rows.
    pub rows: usize,
    /// Row ranges [start, end) of each (run, segment).
    pub segments: Vec<(String, String, usize, usize)>,
}

impl Measurement {
    /// A numeric column.
    pub fn col(&self, name: &str) -> Option<&[f64]> {
        self.columns.get(name).map(Vec::as_slice)
    }
    /// Names of the temperature columns.
    pub fn temperature_columns(&self) -> Vec<&str> {
        self.columns.keys().filter(|k| k.starts_with("temp_") && k.ends_with("_c")).map(String::as_str).collect()
    }
}

/// An error in a measurement file; `row` counts data rows from 1 (the header is row 0).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{source_name}: row {row}, column {column:?}: {message}")]
pub struct MeasurementError {
    /// File.
    pub source_name: String,
    /// Data row (1-based; 0 = header).
    pub row: usize,
    /// Column name.
    pub column: String,
    /// What is wrong.
    pub message: String,
}

fn classify(name: &str) -> Result<bool, String> {
    // Ok(true): numeric, Ok(false): label.
    if REQUIRED.contains(&name) || GIMBAL.contains(&name) || QUATERNION.contains(&name) || OPTIONAL.contains(&name) {
        return Ok(true);
    }
    if LABELS.contains(&name) {
        return Ok(false);
    }
    if FAMILIES.iter().any(|(p, s)| name.starts_with(p) && name.ends_with(s) && name.len() > p.len() + s.len()) {
        return Ok(true);
    }
    // A known quantity in a wrong unit?
    for want in REQUIRED.iter().chain(&GIMBAL).chain(&OPTIONAL[1..]) {
        let base = want.rsplit_once('_').map(|(b, _)| b).unwrap_or(want);
        if let Some(unit) = name.strip_prefix(base).filter(|u| WRONG_UNITS.contains(u) || u.starts_with('_')) {
            return Err(format!("unit {unit:?} not accepted; expected {want}"));
        }
    }
    Err(format!(
        "unknown column; accepted: {:?}, {:?} or {:?}, {:?}, labels {:?}, and families temp_*_c, dtheta_true_*_rad, dv_true_*_mps, gyro_*_dph, accel_*_ug",
        REQUIRED, GIMBAL, QUATERNION, OPTIONAL, LABELS
    ))
}

/// Parses measurement CSV text; `source_name` appears in every error.
pub fn parse(text: &str, source_name: &str) -> Result<Measurement, MeasurementError> {
    let err = |row: usize, column: &str, message: String| MeasurementError { source_name: source_name.into(), row, column: column.into(), message };
    let mut lines = text.lines().filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty());
    let header: Vec<String> = lines.next().ok_or_else(|| err(0, "", "empty file: expected a header row".into()))?.split(',').map(|s| s.trim().to_string()).collect();
    let mut numeric = Vec::with_capacity(header.len());
    for (i, h) in header.iter().enumerate() {
        if header[..i].contains(h) {
            return Err(err(0, h, "duplicate column".into()));
        }
        numeric.push(classify(h).map_err(|m| err(0, h, m))?);
    }
    for need in REQUIRED {
        if !header.iter().any(|h| h == need) {
            return Err(err(0, need, "missing required column".into()));
        }
    }
    let has = |set: &[&str]| set.iter().all(|c| header.iter().any(|h| h == c));
    if !has(&GIMBAL) && !has(&QUATERNION) {
        return Err(err(0, "outer_deg", "missing attitude: give outer_deg and inner_deg, or q_bn_w, q_bn_x, q_bn_y, q_bn_z".into()));
    }
    if !header.iter().any(|h| h.starts_with("temp_") && h.ends_with("_c")) {
        return Err(err(0, "temp_*_c", "missing temperature: at least one temp_<name>_c column".into()));
    }
    // Parse into vectors by column index; the maps are filled once at the end (a map lookup
    // per field would dominate on million-row files).
    let mut nums: Vec<Vec<f64>> = vec![Vec::new(); header.len()];
    let mut labs: Vec<Vec<String>> = vec![Vec::new(); header.len()];
    let mut rows = 0;
    for (r, line) in lines.enumerate() {
        let row = r + 1;
        let mut count = 0;
        for (i, f) in line.split(',').enumerate() {
            count += 1;
            if i >= header.len() {
                continue;
            }
            let f = f.trim();
            if numeric[i] {
                let v: f64 = f.parse().map_err(|_| err(row, &header[i], format!("not a number: {f:?}")))?;
                if !v.is_finite() {
                    return Err(err(row, &header[i], format!("{v} is not a finite number")));
                }
                nums[i].push(v);
            } else {
                match labs[i].last() {
                    Some(last) if last == f => {
                        let l = last.clone();
                        labs[i].push(l)
                    }
                    _ => labs[i].push(f.to_string()),
                }
            }
        }
        if count != header.len() {
            return Err(err(row, "", format!("{count} fields, header has {}", header.len())));
        }
        rows = row;
    }
    let mut m = Measurement { rows, ..Measurement::default() };
    for ((h, &num), (n, l)) in header.iter().zip(&numeric).zip(nums.into_iter().zip(labs)) {
        if num {
            m.columns.insert(h.clone(), n);
        } else {
            m.labels.insert(h.clone(), l);
        }
    }
    if m.rows < 2 {
        return Err(err(m.rows, "t_s", "need at least two data rows".into()));
    }
    // Segments: consecutive rows with the same (run, segment) labels.
    let label = |name: &str, i: usize| m.labels.get(name).map(|v| v[i].clone()).unwrap_or_default();
    let mut start = 0;
    for i in 1..=m.rows {
        if i == m.rows || label("run", i) != label("run", start) || label("segment", i) != label("segment", start) {
            m.segments.push((label("run", start), label("segment", start), start, i));
            start = i;
        }
    }
    // Time strictly increasing within a segment, and evenly spaced (a gap means lost samples).
    let t = m.columns["t_s"].clone();
    for &(_, _, a, b) in &m.segments {
        if b - a < 2 {
            continue;
        }
        let mut d: Vec<f64> = t[a..b].windows(2).map(|w| w[1] - w[0]).collect();
        for (k, dt) in d.iter().enumerate() {
            if *dt <= 0.0 {
                return Err(err(a + k + 2, "t_s", format!("time not increasing: {} after {}", t[a + k + 1], t[a + k])));
            }
        }
        d.sort_by(f64::total_cmp);
        let median = d[d.len() / 2];
        for k in a + 1..b {
            let dt = t[k] - t[k - 1];
            // The last row of a decimated file may be shorter; a longer step is a gap.
            if dt > median * 1.01 + 1e-9 {
                return Err(err(k + 1, "t_s", format!("gap: {dt} s since the previous row, the segment's interval is {median} s (start a new segment or run after a gap)")));
            }
        }
    }
    Ok(m)
}

/// Reads and parses a measurement file.
pub fn read(path: &Path) -> Result<Measurement, MeasurementError> {
    let text = std::fs::read_to_string(path).map_err(|e| MeasurementError {
        source_name: path.display().to_string(),
        row: 0,
        column: String::new(),
        message: format!("cannot read: {e}"),
    })?;
    parse(&text, &path.display().to_string())
}
