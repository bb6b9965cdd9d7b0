//! The header of a measurement file (CSV or Parquet), checked: each source column's documented
//! name after the column map, whether it is a number, a label or ignored, and its unit
//! conversion.

use crate::colmap::{ColumnMap, Resolved};
use crate::measurement::{GIMBAL, MeasurementError, QUATERNION, REQUIRED, classify};

/// How a source column is read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Kind {
    /// A number.
    Num,
    /// A label.
    Label,
    /// Ignored (a column map says so).
    Skip,
}

/// The header of a file, checked: the documented name of each source column (after the column
/// map), how it is read and its unit conversion (documented = source × factor + offset).
pub(crate) struct Layout {
    /// Source names as in the file (for errors).
    pub raw: Vec<String>,
    /// Documented names.
    pub header: Vec<String>,
    /// How each is read.
    pub kind: Vec<Kind>,
    /// Conversion of each numeric column.
    pub conv: Vec<(f64, f64)>,
    /// File name.
    pub source: String,
}

impl Layout {
    pub(crate) fn err(&self, row: usize, column: &str, message: String) -> MeasurementError {
        MeasurementError {
            source_name: self.source.clone(),
            row,
            column: column.into(),
            message,
        }
    }

    pub(crate) fn new(
        header_line: &str,
        source: &str,
        map: Option<&ColumnMap>,
    ) -> Result<Self, MeasurementError> {
        let raw: Vec<String> = header_line
            .split(',')
            .map(|s| s.trim().to_string())
            .collect();
        Self::from_names(raw, source, map)
    }

    /// Checks source column names (mapped with `map`) as a header.
    pub(crate) fn from_names(
        raw: Vec<String>,
        source: &str,
        map: Option<&ColumnMap>,
    ) -> Result<Self, MeasurementError> {
        let err = |column: &str, message: String| MeasurementError {
            source_name: source.into(),
            row: 0,
            column: column.into(),
            message,
        };
        for (i, h) in raw.iter().enumerate() {
            if raw[..i].contains(h) {
                return Err(err(h, "duplicate column".into()));
            }
        }
        if let Some(m) = map {
            m.check_header(&raw)?;
        }
        let mut header = Vec::with_capacity(raw.len());
        let mut kind = Vec::with_capacity(raw.len());
        let mut conv = Vec::with_capacity(raw.len());
        for r in &raw {
            let resolved = map.map_or(Resolved::Keep, |m| m.resolve(r));
            let (name, c) = match resolved {
                Resolved::Ignore => {
                    header.push(r.clone());
                    kind.push(Kind::Skip);
                    conv.push((1.0, 0.0));
                    continue;
                }
                Resolved::Keep => (r.clone(), (1.0, 0.0)),
                Resolved::Map(e) => (e.to.clone(), (e.factor, e.offset)),
            };
            if header
                .iter()
                .zip(&kind)
                .any(|(h, k)| *h == name && *k != Kind::Skip)
            {
                return Err(err(
                    r,
                    format!(
                        "duplicate column: {name:?} is given twice (directly or through the column map)"
                    ),
                ));
            }
            let numeric = classify(&name).map_err(|m| err(r, m))?;
            header.push(name);
            kind.push(if numeric { Kind::Num } else { Kind::Label });
            conv.push(c);
        }
        let header_used: Vec<String> = header
            .iter()
            .zip(&kind)
            .filter(|(_, k)| **k != Kind::Skip)
            .map(|(h, _)| h.clone())
            .collect();
        for need in REQUIRED {
            if !header_used.iter().any(|h| h == need) {
                return Err(err(need, "missing required column".into()));
            }
        }
        let has = |set: &[&str]| set.iter().all(|c| header_used.iter().any(|h| h == c));
        if !has(&GIMBAL) && !has(&QUATERNION) {
            return Err(err(
                "outer_deg",
                "missing attitude: give outer_deg and inner_deg, or q_bn_w, q_bn_x, q_bn_y, q_bn_z"
                    .into(),
            ));
        }
        if !header_used
            .iter()
            .any(|h| h.starts_with("temp_") && h.ends_with("_c"))
        {
            return Err(err(
                "temp_*_c",
                "missing temperature: at least one temp_<name>_c column".into(),
            ));
        }
        Ok(Self {
            raw,
            header,
            kind,
            conv,
            source: source.into(),
        })
    }
}
