//! Measurement files in Parquet: the same columns, names and rules as the CSV format
//! (docs/measurement-format.md), read column by column on both cores with the `parquet` crate's
//! low-level reader (no Arrow). Numbers may be stored as DOUBLE, FLOAT, INT32 or INT64 (signed,
//! unsigned or DECIMAL); `t_s` also as a time (TIMESTAMP or TIME in ms, µs or ns, or INT96),
//! which becomes seconds since the file's first row. Labels are UTF-8 strings (or integers). A
//! null is an error like an empty CSV field. Pages may be uncompressed or compressed with
//! Snappy, gzip, zstd, LZ4 or LZ4_RAW; page checksums (CRC32) are verified when the writer
//! stored them. The column map applies as for CSV. [`write`] writes a measurement (what `rins
//! measure --format parquet` uses).

use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use parquet::basic::{Compression, ConvertedType, LogicalType, TimeUnit, Type as Physical};
use parquet::column::reader::ColumnReader;
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int96};
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnDescriptor, Type};
use rayon::prelude::*;

use crate::chunks::{Acc, ChunkSink, Chunker};
use crate::colmap::ColumnMap;
use crate::header::{Kind, Layout};
use crate::measurement::{LabelColumn, Measurement, MeasurementError};

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

/// Codecs this reader decompresses (the `parquet` crate's features in the workspace manifest).
const CODECS: &str = "uncompressed, SNAPPY, GZIP, ZSTD, LZ4 or LZ4_RAW";

/// Whether pages compressed with `c` can be read.
fn codec_supported(c: Compression) -> bool {
    !matches!(c, Compression::LZO | Compression::BROTLI(_))
}

/// The codec's name as the Parquet specification writes it.
fn codec_name(c: Compression) -> &'static str {
    match c {
        Compression::UNCOMPRESSED => "UNCOMPRESSED",
        Compression::SNAPPY => "SNAPPY",
        Compression::GZIP(_) => "GZIP",
        Compression::LZO => "LZO",
        Compression::BROTLI(_) => "BROTLI",
        Compression::LZ4 => "LZ4",
        Compression::ZSTD(_) => "ZSTD",
        Compression::LZ4_RAW => "LZ4_RAW",
    }
}

/// How a numeric column's stored values become numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Decode {
    /// As stored (DOUBLE, FLOAT, signed integers).
    Plain,
    /// Unsigned integers (INT32 or INT64 with an unsigned integer type).
    Unsigned,
    /// DECIMAL: the stored integer × 10^-scale.
    Decimal(i32),
    /// A time (TIMESTAMP or TIME, or INT96): integer ticks, `per_s` a second; becomes seconds
    /// since the first row.
    Time {
        /// Ticks per second.
        per_s: i64,
        /// The stored type, for messages.
        what: &'static str,
    },
}

fn per_s(unit: &TimeUnit) -> (i64, &'static str) {
    match unit {
        TimeUnit::MILLIS => (1_000, "ms"),
        TimeUnit::MICROS => (1_000_000, "µs"),
        TimeUnit::NANOS => (1_000_000_000, "ns"),
    }
}

/// How the numbers of column `c` are decoded, or why they cannot be.
fn decode_of(c: &ColumnDescriptor) -> Result<Decode, String> {
    let physical = c.physical_type();
    let int = matches!(physical, Physical::INT32 | Physical::INT64);
    let refuse = |what: String| {
        Err(format!(
            "stored as {what}; expected a number (DOUBLE, FLOAT, INT32 or INT64, signed, unsigned or DECIMAL; t_s also a TIMESTAMP, TIME or INT96)"
        ))
    };
    if physical == Physical::INT96 {
        return Ok(Decode::Time {
            per_s: 1_000_000_000,
            what: "INT96 timestamp (ns)",
        });
    }
    match (c.logical_type_ref(), c.converted_type()) {
        (Some(LogicalType::Timestamp { unit, .. }), _) if int => {
            let (p, u) = per_s(unit);
            Ok(Decode::Time {
                per_s: p,
                what: match u {
                    "ms" => "TIMESTAMP (ms)",
                    "µs" => "TIMESTAMP (µs)",
                    _ => "TIMESTAMP (ns)",
                },
            })
        }
        (Some(LogicalType::Time { unit, .. }), _) if int => {
            let (p, u) = per_s(unit);
            Ok(Decode::Time {
                per_s: p,
                what: match u {
                    "ms" => "TIME (ms)",
                    "µs" => "TIME (µs)",
                    _ => "TIME (ns)",
                },
            })
        }
        (None, ConvertedType::TIMESTAMP_MILLIS) if int => Ok(Decode::Time {
            per_s: 1_000,
            what: "TIMESTAMP_MILLIS",
        }),
        (None, ConvertedType::TIMESTAMP_MICROS) if int => Ok(Decode::Time {
            per_s: 1_000_000,
            what: "TIMESTAMP_MICROS",
        }),
        (None, ConvertedType::TIME_MILLIS) if int => Ok(Decode::Time {
            per_s: 1_000,
            what: "TIME_MILLIS",
        }),
        (None, ConvertedType::TIME_MICROS) if int => Ok(Decode::Time {
            per_s: 1_000_000,
            what: "TIME_MICROS",
        }),
        (Some(LogicalType::Decimal { scale, .. }), _) if int => Ok(Decode::Decimal(*scale)),
        (None, ConvertedType::DECIMAL) if int => Ok(Decode::Decimal(c.type_scale())),
        (Some(LogicalType::Integer { is_signed, .. }), _) if int => Ok(if *is_signed {
            Decode::Plain
        } else {
            Decode::Unsigned
        }),
        (
            None,
            ConvertedType::UINT_8
            | ConvertedType::UINT_16
            | ConvertedType::UINT_32
            | ConvertedType::UINT_64,
        ) if int => Ok(Decode::Unsigned),
        (None, ConvertedType::NONE | ConvertedType::INT_8 | ConvertedType::INT_16)
        | (None, ConvertedType::INT_32 | ConvertedType::INT_64)
            if int || matches!(physical, Physical::FLOAT | Physical::DOUBLE) =>
        {
            Ok(Decode::Plain)
        }
        (Some(l), _) => refuse(format!("{physical} with logical type {l:?}")),
        (None, ConvertedType::NONE) => refuse(format!("{physical}")),
        (None, t) => refuse(format!("{physical} with converted type {t}")),
    }
}

/// Rows allocated before reading: the footer's row counts are only claims (a damaged footer
/// may say 2^45), so vectors start at most this long and grow with the rows actually decoded.
const PREALLOC_ROWS: usize = 1 << 22;

/// One column read: numbers (with the first row's time in ns for a time type) or labels.
enum Col {
    Num(Vec<f64>),
    /// A time type's integer ticks and ticks per second.
    Ticks(Vec<i64>, i64),
    Label(LabelColumn),
    Skip,
}

/// A reader error on column `name` in row group `g` (rows `a`..=`b`, 1-based): a checksum that
/// does not match, or a page that does not decode.
fn page_error(
    source: &str,
    name: &str,
    g: usize,
    a: usize,
    b: usize,
    e: parquet::errors::ParquetError,
) -> MeasurementError {
    let text = e.to_string();
    let what = if text.contains("CRC checksum mismatch") {
        "a page checksum (CRC32) does not match its data: the file is corrupt".to_string()
    } else {
        format!("Parquet: {text}")
    };
    error(
        source,
        a,
        name,
        format!("{what} (row group {g}, rows {a} to {b})"),
    )
}

/// Reads column `i` of row group `g`, whose first row follows `before` rows of the file (rows
/// are numbered from 1 across row groups).
fn read_column(
    path: &Path,
    source: &str,
    (i, g, before): (usize, usize, usize),
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
    let descr = md.file_metadata().schema_descr().column(i);
    let decode = if kind == Kind::Num {
        decode_of(&descr).map_err(|m| error(source, 0, name, m))?
    } else {
        Decode::Plain
    };
    let total = md.row_group(g).num_rows().max(0) as usize;
    let mut nums: Vec<f64> = Vec::with_capacity(if kind == Kind::Num {
        total.min(PREALLOC_ROWS)
    } else {
        0
    });
    let mut ticks: Vec<i64> = Vec::new();
    let mut labs = LabelColumn::default();
    let mut row0 = before;
    let mut defs: Vec<i16> = Vec::new();
    // One row group per call: the reader streams the file group by group.
    #[allow(clippy::never_loop)]
    for g in [g] {
        let n = md.row_group(g).num_rows().max(0) as usize;
        let pe = |e| page_error(source, name, g, row0 + 1, row0 + n, e);
        let rg = reader.get_row_group(g).map_err(pe)?;
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
        macro_rules! read_all {
            ($r:expr, $t:ty) => {{
                let mut v: Vec<$t> = Vec::with_capacity(n.min(PREALLOC_ROWS));
                let (recs, vals, _) = $r
                    .read_records(n, Some(&mut defs), None, &mut v)
                    .map_err(pe)?;
                if vals < recs {
                    return Err(null_at(&defs, vals));
                }
                v
            }};
        }
        macro_rules! numbers {
            ($r:expr, $t:ty, $conv:expr) => {{
                read_all!($r, $t)
                    .into_iter()
                    .map($conv)
                    .collect::<Vec<f64>>()
            }};
        }
        let col = rg.get_column_reader(i).map_err(pe)?;
        let scale = match decode {
            Decode::Decimal(s) => 10f64.powi(s),
            _ => 1.0,
        };
        let values: Vec<f64> = match (kind, decode, col) {
            (Kind::Label, _, ColumnReader::ByteArrayColumnReader(mut r)) => {
                let v = read_all!(r, ByteArray);
                for (k, b) in v.iter().enumerate() {
                    let s = b.as_utf8().map_err(|_| {
                        error(source, row0 + k + 1, name, "label is not UTF-8".into())
                    })?;
                    labs.push(s);
                }
                row0 += v.len();
                continue;
            }
            (Kind::Label, _, ColumnReader::Int32ColumnReader(mut r)) => {
                numbers!(r, i32, |x: i32| x as f64)
            }
            (Kind::Label, _, ColumnReader::Int64ColumnReader(mut r)) => {
                numbers!(r, i64, |x: i64| x as f64)
            }
            (Kind::Num, Decode::Time { .. }, ColumnReader::Int32ColumnReader(mut r)) => {
                ticks.extend(read_all!(r, i32).into_iter().map(i64::from));
                row0 += n;
                continue;
            }
            (Kind::Num, Decode::Time { .. }, ColumnReader::Int64ColumnReader(mut r)) => {
                ticks.extend(read_all!(r, i64));
                row0 += n;
                continue;
            }
            (Kind::Num, Decode::Time { .. }, ColumnReader::Int96ColumnReader(mut r)) => {
                ticks.extend(read_all!(r, Int96).iter().map(Int96::to_nanos));
                row0 += n;
                continue;
            }
            (Kind::Num, _, ColumnReader::DoubleColumnReader(mut r)) => {
                numbers!(r, f64, |x: f64| x)
            }
            (Kind::Num, _, ColumnReader::FloatColumnReader(mut r)) => {
                numbers!(r, f32, |x: f32| x as f64)
            }
            (Kind::Num, Decode::Unsigned, ColumnReader::Int32ColumnReader(mut r)) => {
                numbers!(r, i32, |x: i32| x as u32 as f64)
            }
            (Kind::Num, Decode::Unsigned, ColumnReader::Int64ColumnReader(mut r)) => {
                numbers!(r, i64, |x: i64| x as u64 as f64)
            }
            (Kind::Num, _, ColumnReader::Int32ColumnReader(mut r)) => {
                numbers!(r, i32, |x: i32| x as f64 / scale)
            }
            (Kind::Num, _, ColumnReader::Int64ColumnReader(mut r)) => {
                numbers!(r, i64, |x: i64| x as f64 / scale)
            }
            (k, _, _) => {
                let want = if k == Kind::Num {
                    "a number (DOUBLE, FLOAT, INT32 or INT64)"
                } else {
                    "a label (UTF-8 string or integer)"
                };
                return Err(error(
                    source,
                    0,
                    name,
                    format!("stored as {}; expected {want}", descr.physical_type()),
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
    if let Decode::Time { per_s, .. } = decode {
        return Ok(Col::Ticks(ticks, per_s));
    }
    Ok(match kind {
        Kind::Num => Col::Num(nums),
        _ => Col::Label(labs),
    })
}

/// Checks what can be checked before reading any page: each read column's codec, and that a
/// time type is `t_s` read without a unit conversion.
fn check_columns(
    reader: &SerializedFileReader<File>,
    layout: &Layout,
) -> Result<(), MeasurementError> {
    let md = reader.metadata();
    let schema = md.file_metadata().schema_descr();
    for i in 0..layout.raw.len() {
        if layout.kind[i] == Kind::Skip {
            continue;
        }
        let name = &layout.raw[i];
        for g in 0..md.num_row_groups() {
            let c = md.row_group(g).column(i).compression();
            if !codec_supported(c) {
                return Err(layout.err(
                    0,
                    name,
                    format!(
                        "compressed with {}, which this reader does not decompress (it reads {CODECS}): write the file with one of them (pandas: to_parquet(..., compression=\"zstd\"))",
                        codec_name(c)
                    ),
                ));
            }
        }
        if layout.kind[i] != Kind::Num {
            continue;
        }
        let d = decode_of(&schema.column(i)).map_err(|m| layout.err(0, name, m))?;
        if let Decode::Time { what, .. } = d {
            if layout.header[i] != "t_s" {
                return Err(layout.err(
                    0,
                    name,
                    format!(
                        "stored as a {what}: only t_s may be a time (the reader converts it to seconds since the first row)"
                    ),
                ));
            }
            let (f, o) = layout.conv[i];
            if (f, o) != (1.0, 0.0) {
                return Err(layout.err(
                    0,
                    name,
                    format!(
                        "stored as a {what}, which the reader converts to seconds itself, but the column map converts it (x {f} + {o}): map it by name only ({{ to = \"t_s\" }})"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// What a panic carried, as text.
fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}

/// The `parquet` crate panics on some corrupt files (an assertion in its bit reader) instead of
/// returning an error: a panic inside `f` becomes an error naming the file and `column`.
fn no_panic<T>(
    source: &str,
    column: &str,
    f: impl FnOnce() -> Result<T, MeasurementError>,
) -> Result<T, MeasurementError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).unwrap_or_else(|p| {
        Err(error(
            source,
            0,
            column,
            format!(
                "the Parquet decoder failed on corrupt data ({}): the file is damaged",
                panic_text(p.as_ref())
            ),
        ))
    })
}

/// Reads a Parquet measurement file; `map` names and converts its columns as for CSV
/// ([`crate::reader::read_with`] reads either format).
pub fn read(path: &Path, map: Option<&ColumnMap>) -> Result<Measurement, MeasurementError> {
    let mut all = Measurement::default();
    stream(path, map, usize::MAX, &mut |m| {
        all.append_chunk(m);
        Ok(())
    })?;
    Ok(all)
}

/// Reads a Parquet measurement file one row group at a time (its columns on both cores) and
/// hands the rows to `sink` in chunks of whole segments ([`crate::reader::stream_with`]).
pub(crate) fn stream(
    path: &Path,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
    let source = path.display().to_string();
    no_panic(&source, "", || {
        stream_checked(path, &source, map, chunk_rows, sink)
    })
}

fn stream_checked(
    path: &Path,
    source: &str,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
    let source = source.to_string();
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
    check_columns(&reader, &layout)?;
    let md = reader.metadata();
    let groups = md.num_row_groups();
    let mut chunker = Chunker::new(layout, chunk_rows, sink);
    // The first row's time, in ticks, for a `t_s` stored as a time type.
    let mut t0_tick: Option<i64> = None;
    let mut before = 0usize;
    for g in 0..groups {
        let rows = md.row_group(g).num_rows().max(0) as usize;
        let layout = chunker.layout();
        let results: Vec<Result<Col, MeasurementError>> = (0..layout.raw.len())
            .into_par_iter()
            .map(|i| {
                no_panic(&source, &layout.raw[i], || {
                    read_column(
                        path,
                        &source,
                        (i, g, before),
                        &layout.raw[i],
                        layout.kind[i],
                    )
                })
            })
            .collect();
        // The earliest row wins, then the column first in the file (not whichever thread
        // finished first).
        if let Some(e) = results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.as_ref().err().map(|e| (e.row, i, e)))
            .min_by_key(|(row, i, _)| (*row, *i))
        {
            return Err(e.2.clone());
        }
        let mut acc = Acc::new(layout);
        acc.rows = rows;
        let count = |n: usize, what: &str, i: usize| {
            if n == rows {
                Ok(())
            } else {
                Err(error(
                    &source,
                    0,
                    &layout.raw[i],
                    format!("{n} {what}, row group {g} says {rows} rows: the file is corrupt"),
                ))
            }
        };
        let mut t0_ns = None;
        for (i, c) in results.into_iter().enumerate() {
            match c? {
                Col::Num(v) => {
                    count(v.len(), "values", i)?;
                    acc.nums[i] = v;
                }
                Col::Ticks(ticks, per_s) => {
                    count(ticks.len(), "values", i)?;
                    // Seconds since the file's first row, from exact integer differences.
                    let t0 = *t0_tick.get_or_insert(ticks.first().copied().unwrap_or(0));
                    acc.nums[i] = ticks
                        .iter()
                        .map(|&t| (i128::from(t) - i128::from(t0)) as f64 / per_s as f64)
                        .collect();
                    t0_ns = Some(t0.saturating_mul(1_000_000_000 / per_s));
                }
                Col::Label(l) => {
                    count(l.index.len(), "labels", i)?;
                    acc.labs[i] = l
                }
                Col::Skip => {}
            }
        }
        chunker.set_t0_ns(t0_ns);
        chunker.push(acc)?;
        before += rows;
    }
    chunker.end().map(|_| ())
}

/// Rows per row group written.
const ROW_GROUP: usize = 1 << 20;

/// Writes `m` as Parquet: labels as UTF-8 strings (dictionary encoded), numbers as DOUBLE,
/// row groups of 2^20 rows, Snappy compression.
pub fn write(path: &Path, m: &Measurement) -> Result<(), String> {
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .build();
    write_with(path, m, props)
}

/// Writes `m` as [`write`] does, with the writer properties `props` (another codec, page size,
/// encoding).
pub fn write_with(path: &Path, m: &Measurement, props: WriterProperties) -> Result<(), String> {
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
