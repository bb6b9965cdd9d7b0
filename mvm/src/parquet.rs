//! Measurement files in Parquet: the same columns, names and rules as the CSV format
//! (docs/measurement-format.md), read column by column on both cores with the `parquet` crate's
//! low-level reader (no Arrow). Numbers may be stored as DOUBLE, FLOAT, INT32 or INT64; labels
//! as UTF-8 strings (or integers). A null is an error like an empty CSV field. The column map
//! applies as for CSV. [`write`] writes a measurement (what `rins measure --format parquet`
//! uses).

use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use parquet::basic::Compression;
use parquet::column::reader::ColumnReader;
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType};
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use rayon::prelude::*;

use crate::colmap::ColumnMap;
use crate::header::{Kind, Layout};
use crate::reader::{Acc, LabelColumn, Measurement, MeasurementError, finish};

/// Whether the file starts with the Parquet magic bytes.
pub fn is_parquet(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 4];
    File::open(path)
        .and_then(|mut f| f.read_exact(&mut magic))
        .is_ok_and(|_| &magic == b"PAR1")
}

fn error(source: &str, row: usize, column: &str, message: String) -> MeasurementError {
    MeasurementError {
        source_name: source.into(),
        row,
        column: column.into(),
        message,
    }
}

/// One column read: numbers or labels.
enum Col {
    Num(Vec<f64>),
    Label(LabelColumn),
    Skip,
}

/// Reads column `i` (all row groups); rows are numbered from 1 across row groups.
fn read_column(
    path: &Path,
    source: &str,
    i: usize,
    name: &str,
    kind: Kind,
) -> Result<Col, MeasurementError> {
    if kind == Kind::Skip {
        return Ok(Col::Skip);
    }
    let pq = |e: parquet::errors::ParquetError| error(source, 0, name, format!("Parquet: {e}"));
    let file = File::open(path).map_err(|e| error(source, 0, "", format!("cannot read: {e}")))?;
    let reader = SerializedFileReader::new(file).map_err(pq)?;
    let md = reader.metadata();
    let total = md.file_metadata().num_rows().max(0) as usize;
    let mut nums: Vec<f64> = Vec::with_capacity(if kind == Kind::Num { total } else { 0 });
    let mut labs = LabelColumn::default();
    let mut row0 = 0usize;
    let mut defs: Vec<i16> = Vec::new();
    for g in 0..md.num_row_groups() {
        let rg = reader.get_row_group(g).map_err(pq)?;
        let n = rg.metadata().num_rows().max(0) as usize;
        defs.clear();
        // A null (definition level below the maximum) is an empty field.
        let null_at = |defs: &[i16], values: usize| {
            let first = defs.iter().position(|d| *d == 0).unwrap_or(values);
            error(
                source,
                row0 + first + 1,
                name,
                "null: not a number or label".into(),
            )
        };
        macro_rules! numbers {
            ($r:expr, $conv:expr) => {{
                let mut v = Vec::with_capacity(n);
                let (recs, vals, _) = $r
                    .read_records(n, Some(&mut defs), None, &mut v)
                    .map_err(pq)?;
                if vals < recs {
                    return Err(null_at(&defs, vals));
                }
                v.into_iter().map($conv).collect::<Vec<f64>>()
            }};
        }
        let col = rg.get_column_reader(i).map_err(pq)?;
        let values: Vec<f64> = match (kind, col) {
            (Kind::Label, ColumnReader::ByteArrayColumnReader(mut r)) => {
                let mut v: Vec<ByteArray> = Vec::with_capacity(n);
                let (recs, vals, _) = r
                    .read_records(n, Some(&mut defs), None, &mut v)
                    .map_err(pq)?;
                if vals < recs {
                    return Err(null_at(&defs, vals));
                }
                for (k, b) in v.iter().enumerate() {
                    let s = b.as_utf8().map_err(|_| {
                        error(source, row0 + k + 1, name, "label is not UTF-8".into())
                    })?;
                    labs.push(s);
                }
                row0 += recs;
                continue;
            }
            (Kind::Label, ColumnReader::Int32ColumnReader(mut r)) => {
                numbers!(r, |x: i32| x as f64)
            }
            (Kind::Label, ColumnReader::Int64ColumnReader(mut r)) => {
                numbers!(r, |x: i64| x as f64)
            }
            (Kind::Num, ColumnReader::DoubleColumnReader(mut r)) => numbers!(r, |x: f64| x),
            (Kind::Num, ColumnReader::FloatColumnReader(mut r)) => {
                numbers!(r, |x: f32| x as f64)
            }
            (Kind::Num, ColumnReader::Int32ColumnReader(mut r)) => {
                numbers!(r, |x: i32| x as f64)
            }
            (Kind::Num, ColumnReader::Int64ColumnReader(mut r)) => {
                numbers!(r, |x: i64| x as f64)
            }
            (k, _) => {
                let want = if k == Kind::Num {
                    "a number (DOUBLE, FLOAT, INT32 or INT64)"
                } else {
                    "a label (UTF-8 string or integer)"
                };
                let have = reader.metadata().file_metadata().schema_descr().column(i);
                return Err(error(
                    source,
                    0,
                    name,
                    format!("stored as {:?}; expected {want}", have.physical_type()),
                ));
            }
        };
        if kind == Kind::Label {
            for x in values {
                labs.push(&format!("{x}"));
            }
        } else {
            if let Some(k) = values.iter().position(|v| !v.is_finite()) {
                return Err(error(
                    source,
                    row0 + k + 1,
                    name,
                    format!("{} is not a finite number", values[k]),
                ));
            }
            nums.extend(values);
        }
        row0 += n;
    }
    Ok(if kind == Kind::Num {
        Col::Num(nums)
    } else {
        Col::Label(labs)
    })
}

/// Reads a Parquet measurement file; `map` names and converts its columns as for CSV.
pub fn read(path: &Path, map: Option<&ColumnMap>) -> Result<Measurement, MeasurementError> {
    let source = path.display().to_string();
    let file = File::open(path).map_err(|e| error(&source, 0, "", format!("cannot read: {e}")))?;
    let reader = SerializedFileReader::new(file)
        .map_err(|e| error(&source, 0, "", format!("not a readable Parquet file: {e}")))?;
    let schema = reader.metadata().file_metadata().schema_descr_ptr();
    let mut names = Vec::new();
    for c in schema.columns() {
        if c.max_rep_level() > 0 || c.path().parts().len() > 1 {
            return Err(error(
                &source,
                0,
                &c.path().string(),
                "nested or repeated column: the measurement format is flat".into(),
            ));
        }
        names.push(c.name().to_string());
    }
    let layout = Layout::from_names(names, &source, map)?;
    let rows = reader.metadata().file_metadata().num_rows().max(0) as usize;
    let cols: Vec<Col> = (0..layout.raw.len())
        .into_par_iter()
        .map(|i| read_column(path, &source, i, &layout.raw[i], layout.kind[i]))
        .collect::<Result<_, _>>()?;
    let mut acc = Acc::new(&layout);
    acc.rows = rows;
    for (i, c) in cols.into_iter().enumerate() {
        match c {
            Col::Num(v) => acc.nums[i] = v,
            Col::Label(l) => acc.labs[i] = l,
            Col::Skip => {}
        }
    }
    finish(layout, acc)
}

/// Rows per row group written.
const ROW_GROUP: usize = 1 << 20;

/// Writes `m` as Parquet: labels as UTF-8 strings (dictionary encoded), numbers as DOUBLE,
/// row groups of 2^20 rows, Snappy compression.
pub fn write(path: &Path, m: &Measurement) -> Result<(), String> {
    let fail = |e: parquet::errors::ParquetError| format!("{}: Parquet: {e}", path.display());
    let mut fields = Vec::new();
    for name in m.labels.keys() {
        fields.push(format!("REQUIRED BYTE_ARRAY {name} (UTF8);"));
    }
    for name in m.columns.keys() {
        fields.push(format!("REQUIRED DOUBLE {name};"));
    }
    let schema: Type = parquet::schema::parser::parse_message_type(&format!(
        "message measurement {{ {} }}",
        fields.join(" ")
    ))
    .map_err(fail)?;
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .build();
    let file = File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut w = SerializedFileWriter::new(file, Arc::new(schema), Arc::new(props)).map_err(fail)?;
    let mut start = 0;
    while start < m.rows {
        let end = (start + ROW_GROUP).min(m.rows);
        let mut rg = w.next_row_group().map_err(fail)?;
        for l in m.labels.values() {
            let mut c = rg
                .next_column()
                .map_err(fail)?
                .ok_or("schema has fewer columns")?;
            let v: Vec<ByteArray> = (start..end).map(|k| ByteArray::from(l.get(k))).collect();
            c.typed::<ByteArrayType>()
                .write_batch(&v, None, None)
                .map_err(fail)?;
            c.close().map_err(fail)?;
        }
        for v in m.columns.values() {
            let mut c = rg
                .next_column()
                .map_err(fail)?
                .ok_or("schema has fewer columns")?;
            c.typed::<DoubleType>()
                .write_batch(&v[start..end], None, None)
                .map_err(fail)?;
            c.close().map_err(fail)?;
        }
        rg.close().map_err(fail)?;
        start = end;
    }
    w.close().map_err(fail)?;
    Ok(())
}
