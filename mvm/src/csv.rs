//! The measurement format's CSV parser (docs/measurement-format.md): CSV that another tool can
//! write, with units in the column names. The reader is strict: every problem is an error naming
//! the row and column, and nothing is silently dropped. Every value must lie in its column's
//! physical range ([`crate::ranges`]), and a line may be at most [`MAX_LINE`] bytes long.

use std::io::Read;
use std::path::Path;

use crate::chunks::{Acc, ChunkSink, Chunker};
use crate::colmap::ColumnMap;
use crate::header::{Kind, Layout};
use crate::measurement::{LabelColumn, Measurement, MeasurementError};

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

/// Parses the complete lines of `chunk` into `acc`, in two halves on both cores; `before` rows
/// of the file precede these rows (for error rows).
fn parse_into(
    acc: &mut Acc,
    l: &Layout,
    chunk: &str,
    before: usize,
) -> Result<(), MeasurementError> {
    let mid = chunk.len() / 2;
    let cut = chunk[mid..].find('\n').map_or(chunk.len(), |k| mid + k + 1);
    let (first, second) = chunk.split_at(cut);
    let row0 = before + acc.rows;
    let (a, b) = rayon::join(
        || parse_rows(first, row0, &l.raw, &l.kind, &l.source),
        // Row numbers of the second half continue the first half's.
        || parse_rows(second, row0 + count_rows(first), &l.raw, &l.kind, &l.source),
    );
    for (nums, labs, rows) in [a?, b?] {
        acc.append(Acc { nums, labs, rows });
    }
    Ok(())
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
    parse_into(&mut acc, &layout, &text[offset..], 0)?;
    let mut all = Measurement::default();
    let mut sink = |m| {
        all.append_chunk(m);
        Ok(())
    };
    let mut chunker = Chunker::new(layout, usize::MAX, &mut sink);
    chunker.push(acc)?;
    chunker.end()?;
    Ok(all)
}

/// Reads a measurement CSV file and hands its rows to `sink` ([`crate::reader::stream_with`]).
pub(crate) fn stream(
    path: &Path,
    map: Option<&ColumnMap>,
    chunk_rows: usize,
    sink: &mut ChunkSink<'_>,
) -> Result<(), MeasurementError> {
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
        all.append_chunk(m);
        Ok(())
    })?;
    Ok(all)
}

/// [`read_from`] handing the rows on to `sink` in chunks of whole segments of at least
/// `chunk_rows` rows ([`crate::reader::stream_with`]).
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
                parse_into(&mut acc, c.layout(), body, rows)?;
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
