//! The measurement format (docs/measurement-format.md): CSV that another tool can write, with
//! units in the column names. The reader is strict: every problem is an error naming the row and
//! column, and nothing is silently dropped. Every value must lie in its column's physical range
//! ([`ranges`]), and a line may be at most [`MAX_LINE`] bytes long.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;

pub use crate::chunks::ChunkSink;
use crate::chunks::Chunker;
use crate::colmap::ColumnMap;
use crate::header::{Kind, Layout};

use crate::ranges;

/// Longest line accepted, bytes (a header of a few hundred columns is a few kB; a longer line is
/// not a measurement row and is reported by its length and start, never echoed).
pub const MAX_LINE: usize = 64 << 10;

/// Characters of a field or line quoted in an error.
const QUOTE_CHARS: usize = rins_plant::message::QUOTE_CHARS;

/// The first [`QUOTE_CHARS`] characters of `s`, escaped (NUL and control bytes shown as
/// escapes), with `…` when cut: [`rins_plant::message::quote`].
pub(crate) fn quote(s: &str) -> String {
    rins_plant::message::quote(s)
}

/// The message for a line of `len` bytes (longer than [`MAX_LINE`]) that starts with `start`.
fn long_line(len: &str, start: &str) -> String {
    format!(
        "line of {len} bytes, longer than the limit of {MAX_LINE} bytes (not a measurement row: a file without line breaks, or binary data); it starts {}",
        quote(start)
    )
}

/// The first bytes of `bytes` as text, for [`long_line`] (invalid UTF-8 shown as U+FFFD).
fn start_of(bytes: &[u8]) -> String {
    String::from_utf8_lossy(&bytes[..bytes.len().min(4 * QUOTE_CHARS)]).into_owned()
}

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

    fn append(&mut self, other: LabelColumn) {
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

/// Whether a line is data (not blank, not a `#` comment).
fn is_data(line: &str) -> bool {
    let t = line.trim_start();
    !t.is_empty() && !t.starts_with('#')
}

/// Data rows in `part`.
fn count_rows(part: &str) -> usize {
    part.lines().filter(|l| is_data(l)).count()
}

type Columns = (Vec<Vec<f64>>, Vec<LabelColumn>, usize);

/// Parses the data rows of `part`; row numbers start after `row0`.
fn parse_rows(
    part: &str,
    row0: usize,
    header: &[String],
    kind: &[Kind],
    source_name: &str,
) -> Result<Columns, MeasurementError> {
    let err = |row: usize, column: &str, message: String| MeasurementError {
        source_name: source_name.into(),
        row,
        column: column.into(),
        message,
    };
    // Columns are filled by index (a map lookup per field would dominate on million-row files).
    let estimate = part.len() / 200;
    let mut nums: Vec<Vec<f64>> = kind
        .iter()
        .map(|&n| {
            if n == Kind::Num {
                Vec::with_capacity(estimate)
            } else {
                Vec::new()
            }
        })
        .collect();
    let mut labs: Vec<LabelColumn> = vec![LabelColumn::default(); header.len()];
    let mut row = row0;
    for line in part.lines() {
        if !is_data(line) {
            continue;
        }
        row += 1;
        if line.len() > MAX_LINE {
            return Err(err(row, "", long_line(&line.len().to_string(), line)));
        }
        let mut count = 0;
        // Fields by byte scan (',' is ASCII, so every slice is on a char boundary).
        let bytes = line.as_bytes();
        let mut a = 0;
        while a <= bytes.len() {
            let b = bytes[a..]
                .iter()
                .position(|c| *c == b',')
                .map_or(bytes.len(), |k| a + k);
            let i = count;
            count += 1;
            if i < header.len() {
                let mut f = &line[a..b];
                if f.starts_with(' ') || f.ends_with(' ') || f.ends_with('\r') {
                    f = f.trim();
                }
                if kind[i] == Kind::Num {
                    let v: f64 = f
                        .parse()
                        .map_err(|_| err(row, &header[i], format!("not a number: {}", quote(f))))?;
                    if !v.is_finite() {
                        return Err(err(row, &header[i], format!("{v} is not a finite number")));
                    }
                    nums[i].push(v);
                } else if kind[i] == Kind::Label {
                    labs[i].push(f);
                }
            }
            a = b + 1;
        }
        if count < header.len() {
            // A short row: the first column it lacks.
            return Err(err(
                row,
                &header[count],
                format!(
                    "missing: the row ends before this column ({count} fields, header has {})",
                    header.len()
                ),
            ));
        }
        if count > header.len() {
            return Err(err(
                row,
                "",
                format!(
                    "{count} fields, header has {} (the last is {})",
                    header.len(),
                    quote(header.last().map_or("", String::as_str))
                ),
            ));
        }
    }
    Ok((nums, labs, row - row0))
}

/// Columns filled so far.
pub(crate) struct Acc {
    /// Numeric columns (empty for labels and ignored ones).
    pub nums: Vec<Vec<f64>>,
    /// Label columns.
    pub labs: Vec<LabelColumn>,
    /// Rows.
    pub rows: usize,
}

impl Acc {
    pub(crate) fn new(l: &Layout) -> Self {
        Self {
            nums: vec![Vec::new(); l.header.len()],
            labs: vec![LabelColumn::default(); l.header.len()],
            rows: 0,
        }
    }

    /// The first `k` rows, which leave `self`.
    pub(crate) fn split_front(&mut self, k: usize) -> Acc {
        let front = |v: &mut Vec<f64>| {
            if v.is_empty() {
                return Vec::new();
            }
            let back = v.split_off(k);
            std::mem::replace(v, back)
        };
        let nums = self.nums.iter_mut().map(front).collect();
        let labs = self
            .labs
            .iter_mut()
            .map(|l| {
                if l.index.is_empty() {
                    return LabelColumn::default();
                }
                let back = l.index.split_off(k);
                LabelColumn {
                    names: l.names.clone(),
                    index: std::mem::replace(&mut l.index, back),
                }
            })
            .collect();
        self.rows -= k;
        Acc {
            nums,
            labs,
            rows: k,
        }
    }

    /// Appends the rows of `other`.
    pub(crate) fn append(&mut self, other: Acc) {
        for (x, y) in self.nums.iter_mut().zip(other.nums) {
            x.extend(y);
        }
        for (x, y) in self.labs.iter_mut().zip(other.labs) {
            x.append(y);
        }
        self.rows += other.rows;
    }

    /// Parses the complete lines of `chunk`, in two halves on both cores; `before` rows of the
    /// file precede these rows (for error rows).
    fn add_from(&mut self, l: &Layout, chunk: &str, before: usize) -> Result<(), MeasurementError> {
        let mid = chunk.len() / 2;
        let cut = chunk[mid..].find('\n').map_or(chunk.len(), |k| mid + k + 1);
        let (first, second) = chunk.split_at(cut);
        let row0 = before + self.rows;
        let (a, b) = rayon::join(
            || parse_rows(first, row0, &l.raw, &l.kind, &l.source),
            // Row numbers of the second half continue the first half's.
            || parse_rows(second, row0 + count_rows(first), &l.raw, &l.kind, &l.source),
        );
        for (nums, labs, rows) in [a?, b?] {
            self.append(Acc { nums, labs, rows });
        }
        Ok(())
    }
}

/// Appends chunk `m` (the rows after those of `into`) to `into`.
fn append_chunk(into: &mut Measurement, m: Measurement) {
    if into.rows == 0 {
        *into = m;
        return;
    }
    let r0 = into.rows;
    for (name, v) in m.columns {
        into.columns.entry(name).or_default().extend(v);
    }
    for (name, l) in m.labels {
        into.labels.entry(name).or_default().append(l);
    }
    into.segments.extend(
        m.segments
            .into_iter()
            .map(|(r, s, a, b)| (r, s, a + r0, b + r0)),
    );
    into.rows += m.rows;
}

/// Parses measurement CSV text; `source_name` appears in every error.
pub fn parse(text: &str, source_name: &str) -> Result<Measurement, MeasurementError> {
    parse_with(text, source_name, None)
}

/// Parses measurement CSV text whose columns are named and converted by `map`.
pub fn parse_with(
    text: &str,
    source_name: &str,
    map: Option<&ColumnMap>,
) -> Result<Measurement, MeasurementError> {
    // The header is the first data line; everything after it is rows.
    let mut offset = 0;
    let mut header_line = None;
    for line in text.split_inclusive('\n') {
        if line.len() > MAX_LINE {
            return Err(MeasurementError {
                source_name: source_name.into(),
                row: 0,
                column: String::new(),
                message: long_line(&line.len().to_string(), line),
            });
        }
        offset += line.len();
        if is_data(line) {
            header_line = Some(line);
            break;
        }
    }
    let header_line = header_line.ok_or_else(|| MeasurementError {
        source_name: source_name.into(),
        row: 0,
        column: String::new(),
        message: "empty file: expected a header row".into(),
    })?;
    let layout = Layout::new(header_line, source_name, map)?;
    let mut acc = Acc::new(&layout);
    acc.add_from(&layout, &text[offset..], 0)?;
    let mut all = Measurement::default();
    let mut sink = |m| {
        append_chunk(&mut all, m);
        Ok(())
    };
    let mut chunker = Chunker::new(layout, usize::MAX, &mut sink);
    chunker.push(acc)?;
    chunker.end()?;
    Ok(all)
}

/// Builds the measurement from the parsed columns of whole segments and checks segments, time
/// and the physical ranges ([`ranges`]); `t0_ns` is the origin of a `t_s` read from a Parquet
/// time type; the rows follow `row0` rows of the file (for error rows).
pub(crate) fn finish(
    layout: &Layout,
    acc: Acc,
    t0_ns: Option<i64>,
    row0: usize,
) -> Result<Measurement, MeasurementError> {
    let err = |row: usize, column: &str, message: String| layout.err(row0 + row, column, message);
    let mut m = Measurement {
        rows: acc.rows,
        t0_ns,
        ..Measurement::default()
    };
    for (i, (n, l)) in acc.nums.into_iter().zip(acc.labs).enumerate() {
        let h = layout.header[i].clone();
        match layout.kind[i] {
            Kind::Skip => m.ignored.push(layout.raw[i].clone()),
            Kind::Label => {
                m.labels.insert(h, l);
            }
            Kind::Num => {
                let mut n = n;
                let (f, o) = layout.conv[i];
                if (f, o) != (1.0, 0.0) {
                    for (k, v) in n.iter_mut().enumerate() {
                        *v = *v * f + o;
                        if !v.is_finite() {
                            return Err(err(
                                k + 1,
                                &layout.raw[i],
                                format!(
                                    "not finite after the column map's conversion (x {f} + {o})"
                                ),
                            ));
                        }
                    }
                }
                m.columns.insert(h, n);
            }
        }
    }
    // Values out of their physical range, before time is looked at (a t_s of 1e30 is a unit
    // mistake, not a gap).
    ranges::check_values(&m, layout, row0)?;
    // Segments: consecutive rows with the same (run, segment) labels.
    let label = |name: &str, i: usize| m.labels.get(name).map_or(u32::MAX, |c| c.index[i]);
    let name = |col: &str, i: usize| {
        m.labels
            .get(col)
            .map_or(String::new(), |c| c.get(i).to_string())
    };
    let mut start = 0;
    let mut segments = Vec::new();
    for i in 1..=m.rows {
        if i == m.rows
            || label("run", i) != label("run", start)
            || label("segment", i) != label("segment", start)
        {
            segments.push((name("run", start), name("segment", start), start, i));
            start = i;
        }
    }
    m.segments = segments;
    // Time strictly increasing within a segment, and evenly spaced (a gap means lost samples).
    let t_col = ranges::source_of(layout, "t_s").0;
    let t = &m.columns["t_s"];
    // Each row's interval; a segment's first row takes the segment's median interval (a
    // one-row segment the longest interval accepted).
    let mut dt_s = vec![ranges::ROW_INTERVAL_S[1]; m.rows];
    for &(_, _, a, b) in &m.segments {
        if b - a < 2 {
            continue;
        }
        let mut d: Vec<f64> = t[a..b].windows(2).map(|w| w[1] - w[0]).collect();
        for (k, dt) in d.iter().enumerate() {
            if *dt <= 0.0 {
                return Err(err(
                    a + k + 2,
                    &t_col,
                    format!(
                        "time not increasing: {} after {}",
                        ranges::show(t[a + k + 1]),
                        ranges::show(t[a + k])
                    ),
                ));
            }
        }
        dt_s[a + 1..b].copy_from_slice(&d);
        d.sort_by(f64::total_cmp);
        let median = d[d.len() / 2];
        dt_s[a] = median;
        for k in a + 1..b {
            let dt = t[k] - t[k - 1];
            // The last row of a decimated file may be shorter; a longer step is a gap.
            if dt > median * 1.01 + 1e-9 {
                return Err(err(
                    k + 1,
                    &t_col,
                    format!(
                        "gap: {} s since the previous row, the segment's interval is {} s (start a new segment or run after a gap)",
                        ranges::show(dt),
                        ranges::show(median)
                    ),
                ));
            }
        }
    }
    ranges::check_rows(&m, layout, &dt_s, row0)?;
    Ok(m)
}

/// Reads and parses a measurement file, streaming it in [`PIECE`]-byte pieces (a multi-GB
/// file is never held in memory as text).
pub fn read(path: &Path) -> Result<Measurement, MeasurementError> {
    read_with(path, None)
}

/// Reads a measurement file whose columns are named and converted by `map`: CSV, or Parquet
/// when the file starts with the Parquet magic bytes (`PAR1`). The whole file is returned;
/// [`stream_with`] hands it on in chunks instead.
pub fn read_with(path: &Path, map: Option<&ColumnMap>) -> Result<Measurement, MeasurementError> {
    let mut all = Measurement::default();
    stream_with(path, map, usize::MAX, &mut |m| {
        append_chunk(&mut all, m);
        Ok(())
    })?;
    Ok(all)
}

/// Reads a measurement file (CSV or Parquet, columns named and converted by `map`) and hands
/// its rows to `sink` in chunks of whole segments, each of at least `chunk_rows` rows (the
/// last may be shorter), checked as [`read_with`] checks them (error rows count from the
/// file's first). Memory holds one piece of text, the rows of the segment being read and one
/// chunk; a Parquet file is read one row group at a time.
pub fn stream_with(
    path: &Path,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
    if crate::parquet::is_parquet(path) {
        return crate::parquet::stream(path, map, chunk_rows, sink);
    }
    let source = path.display().to_string();
    let f = std::fs::File::open(path).map_err(|e| MeasurementError {
        source_name: source.clone(),
        row: 0,
        column: String::new(),
        message: format!("cannot read: {e}"),
    })?;
    stream_from(f, &source, map, chunk_rows, sink)
}

/// Bytes read and parsed at a time by [`stream_from`].
pub const PIECE: usize = 16 << 20;

/// Reads measurement CSV from a stream (a file, a pipe, `/dev/zero`), [`PIECE`] bytes at a time:
/// memory stays below two pieces whatever the input, and a line longer than [`MAX_LINE`] stops
/// the read at once. `source_name` appears in every error. The whole stream is returned.
pub fn read_from(
    input: impl Read,
    source_name: &str,
    map: Option<&ColumnMap>,
) -> Result<Measurement, MeasurementError> {
    let mut all = Measurement::default();
    stream_from(input, source_name, map, usize::MAX, &mut |m| {
        append_chunk(&mut all, m);
        Ok(())
    })?;
    Ok(all)
}

/// [`read_from`] handing the rows on to `sink` in chunks of whole segments of at least
/// `chunk_rows` rows ([`stream_with`]).
pub fn stream_from(
    mut input: impl Read,
    source_name: &str,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
    let source = source_name.to_string();
    let error = |row: usize, message: String| MeasurementError {
        source_name: source.clone(),
        row,
        column: String::new(),
        message,
    };
    let mut buf: Vec<u8> = Vec::with_capacity(PIECE + MAX_LINE + 1);
    let mut chunker: Option<Chunker> = None;
    // Rows parsed so far (for the row of a UTF-8 error or an over-long line).
    let mut rows = 0usize;
    // Bytes of the file before `buf`, for error positions.
    let mut consumed: u64 = 0;
    loop {
        // Fill the buffer to a whole piece (a pipe gives a few kB per read).
        let n = (&mut input)
            .take(PIECE as u64)
            .read_to_end(&mut buf)
            .map_err(|e| error(0, format!("cannot read: {e}")))?;
        let eof = n < PIECE;
        // Parse every complete line; keep the partial last line for the next piece.
        let end = if eof {
            buf.len()
        } else {
            buf.iter().rposition(|b| *b == b'\n').map_or(0, |k| k + 1)
        };
        if end > 0 {
            let text = std::str::from_utf8(&buf[..end]).map_err(|e| {
                not_utf8(
                    &buf[..end],
                    e,
                    consumed,
                    chunker.as_ref().map(|_| rows),
                    &source,
                )
            })?;
            let mut body = text;
            if chunker.is_none() {
                let mut offset = 0;
                for line in text.split_inclusive('\n') {
                    if line.len() > MAX_LINE {
                        return Err(error(0, long_line(&line.len().to_string(), line)));
                    }
                    offset += line.len();
                    if is_data(line) {
                        let l = Layout::new(line, &source, map)?;
                        chunker = Some(Chunker::new(l, chunk_rows, &mut *sink));
                        break;
                    }
                }
                body = &text[offset..];
            }
            if let Some(c) = &mut chunker {
                let mut acc = Acc::new(c.layout());
                acc.add_from(c.layout(), body, rows)?;
                rows += acc.rows;
                c.push(acc)?;
            }
            buf.drain(..end);
            consumed += end as u64;
        }
        // What is left is a partial line, which may only grow to MAX_LINE.
        if buf.len() > MAX_LINE {
            return Err(error(
                chunker.as_ref().map_or(0, |_| rows + 1),
                format!(
                    "{} (at byte {consumed} of the file)",
                    long_line(&format!("more than {}", buf.len()), &start_of(&buf))
                ),
            ));
        }
        if eof {
            break;
        }
    }
    let chunker = chunker.ok_or_else(|| error(0, "empty file: expected a header row".into()))?;
    chunker.end().map(|_| ())
}

/// The error for a piece that is not UTF-8: the file byte offset of the bad byte (`piece`
/// starts at byte `start` of the file) and its data row (`rows` were parsed before the piece;
/// None while the header has not been found).
fn not_utf8(
    piece: &[u8],
    e: std::str::Utf8Error,
    start: u64,
    rows: Option<usize>,
    source: &str,
) -> MeasurementError {
    let bad = e.valid_up_to();
    // The complete lines before the bad one are valid text.
    let before = piece[..bad]
        .iter()
        .rposition(|b| *b == b'\n')
        .map_or("", |k| {
            std::str::from_utf8(&piece[..=k]).expect("a prefix of the valid part")
        });
    let row = match rows {
        Some(r) => r + count_rows(before) + 1,
        // The header is the first data line; rows count from the line after it.
        None => match before.split_inclusive('\n').position(is_data) {
            Some(h) => {
                let after: usize = before.split_inclusive('\n').take(h + 1).map(str::len).sum();
                count_rows(&before[after..]) + 1
            }
            None => 0,
        },
    };
    MeasurementError {
        source_name: source.into(),
        row,
        column: String::new(),
        message: format!(
            "not UTF-8 text: byte 0x{:02x} at byte {} of the file",
            piece[bad],
            start + bad as u64
        ),
    }
}

#[cfg(test)]
mod tests {
    use rins_plant::effects::{AccelTerm, GyroTerm};
    use rins_plant::output_columns::{COLUMNS, Group, entries};

    /// Every column `rins run`/`rins measure` writes of a static carrier (the plant's output
    /// table, every term) is one this reader accepts, numeric or label as written: a quantity
    /// added to the table is read back, or this fails until the format names it. (The reader
    /// models a static carrier: a moving carrier's truth columns are refused as unknown,
    /// docs/scenario-format.md, "Carrier truth".)
    #[test]
    fn every_column_of_the_plants_output_table_is_read() {
        let groups = [Group::Measured, Group::Setup, Group::Truth, Group::Effects];
        let all = entries(&groups, &GyroTerm::ALL, &AccelTerm::ALL, true);
        let in_csv = COLUMNS
            .iter()
            .filter(|c| c.in_csv && groups.contains(&c.group));
        assert!(all.len() >= in_csv.count());
        for e in all {
            for name in e.names() {
                let numeric = super::classify(&name)
                    .unwrap_or_else(|m| panic!("column {name} of the output table: {m}"));
                let label = matches!(e.column.read, rins_plant::output_columns::Read::Position);
                assert_eq!(numeric, !label, "{name}");
            }
        }
    }
}
