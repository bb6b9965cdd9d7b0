//! A trajectory file's text, read line by line under the measurement reader's line rule (a line
//! may be at most [`MAX_LINE`] bytes long, as in `rins_mvm::reader`): a file that is not CSV
//! text (`/dev/zero`, random bytes, a file without line breaks) is refused at its first bad line
//! with the file and line named, instead of being read whole into memory first (which grew to
//! gigabytes on `/dev/zero` before the process ran out of memory). A NUL byte and text that is
//! not UTF-8 are refused the same way, so a binary file is named as such rather than reported
//! as a CSV field that is "not a number".

use std::io::{BufRead, BufReader, Read};

use super::trajectory_error::TrajectoryError;

/// Longest line accepted, bytes (the measurement reader's limit: a trajectory row is about two
/// hundred bytes, a header about one hundred).
pub const MAX_LINE: usize = 64 << 10;

/// Characters of a line quoted in an error.
const QUOTE_CHARS: usize = 80;

/// The first [`QUOTE_CHARS`] characters of `bytes` as text (invalid UTF-8 shown as U+FFFD),
/// escaped (NUL and control bytes shown as escapes), quoted, with `…` when cut.
fn quote(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4 * QUOTE_CHARS)]);
    let mut out: String = text
        .chars()
        .take(QUOTE_CHARS)
        .flat_map(char::escape_debug)
        .collect();
    if text.chars().nth(QUOTE_CHARS).is_some() || bytes.len() > 4 * QUOTE_CHARS {
        out.push('…');
    }
    format!("\"{out}\"")
}

/// Whether `line` counts as a data row (header or row) in [`super::Trajectory::parse`]: not
/// blank and not a `#` comment. Used only to give an error the row the parser would give.
fn is_row(line: &str) -> bool {
    let t = line.trim();
    !t.is_empty() && !t.starts_with('#')
}

/// Reads the whole text of `input` (named `source_name` in errors), refusing the first line
/// longer than [`MAX_LINE`] bytes, holding a NUL byte or not UTF-8. Memory stays at the size of
/// the valid text read plus one line, whatever the input.
pub fn read_text(input: impl Read, source_name: &str) -> Result<String, TrajectoryError> {
    // `row` is what the parser would call the line: 0 for the header, then data rows from 1.
    let error = |row: usize, message: String| TrajectoryError {
        source_name: source_name.into(),
        row,
        column: String::new(),
        message,
    };
    let mut input = BufReader::new(input);
    let mut text = String::new();
    let mut line: Vec<u8> = Vec::new();
    // Data rows before the current line, the current line's number (from 1) and its first
    // byte's offset in the file.
    let (mut rows, mut number, mut offset) = (0usize, 0usize, 0u64);
    loop {
        line.clear();
        number += 1;
        // One byte more than the limit: a line of exactly MAX_LINE bytes and its '\n' fit.
        let n = (&mut input)
            .take(MAX_LINE as u64 + 1)
            .read_until(b'\n', &mut line)
            .map_err(|e| error(rows, format!("cannot read: {e}")))?;
        if n == 0 {
            return Ok(text);
        }
        let content = line.strip_suffix(b"\n").unwrap_or(&line);
        if content.len() > MAX_LINE {
            return Err(error(
                rows,
                format!(
                    "line {number}: longer than the limit of {MAX_LINE} bytes (not a trajectory row: a file without line breaks, or binary data); it starts {} (at byte {offset} of the file)",
                    quote(content)
                ),
            ));
        }
        // The first bad byte decides which of the two is reported.
        let nul = content.iter().position(|b| *b == 0);
        let bad_utf8 = std::str::from_utf8(content).err().map(|e| e.valid_up_to());
        if let Some(k) = nul.filter(|k| bad_utf8.is_none_or(|u| *k < u)) {
            return Err(error(
                rows,
                format!(
                    "line {number}: a NUL byte at byte {} of the file (not CSV text: binary data); the line starts {}",
                    offset + k as u64,
                    quote(content)
                ),
            ));
        }
        if let Some(u) = bad_utf8 {
            return Err(error(
                rows,
                format!(
                    "line {number}: not UTF-8 text: byte 0x{:02x} at byte {} of the file",
                    content[u],
                    offset + u as u64
                ),
            ));
        }
        let valid = std::str::from_utf8(&line).expect("checked above: UTF-8 text and its '\\n'");
        if is_row(valid) {
            rows += 1;
        }
        text.push_str(valid);
        offset += n as u64;
    }
}
