//! Where each key of a TOML text is written, from the TOML parser's own spans: range errors name
//! the line and column of the value, whether it sits under a `[section]`, in a dotted key, in an
//! inline table (`bias = { enabled = true, dph = [500.0, 0.0, 0.0] }`) or an array element.

use std::collections::HashMap;

use toml::de::{DeTable, DeValue};

/// A 1-based line and column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column (characters), from 1.
    pub column: usize,
}

impl std::fmt::Display for Position {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

/// Every key path of a TOML text (`sensor.gyro.bias.dph[1]`, `sensor.gyro.bias.dph`,
/// `sensor.gyro`, …) with the position of its value.
#[derive(Clone, Debug, Default)]
pub struct SpanIndex {
    at: HashMap<String, Position>,
}

impl SpanIndex {
    /// Indexes `text`; a text the parser refuses gives an empty index (the parse error itself
    /// carries its position).
    pub fn new(text: &str) -> Self {
        match DeTable::parse(text) {
            Ok(doc) => Self::of_document(text, doc.get_ref()),
            Err(_) => Self::default(),
        }
    }

    /// Indexes a document already parsed from `text` (its spans are byte offsets into `text`),
    /// so a reader that holds the document does not parse the text again.
    pub fn of_document(text: &str, doc: &DeTable<'_>) -> Self {
        let mut at = HashMap::new();
        walk(&LineStarts::new(text), "", doc, &mut at);
        Self { at }
    }

    /// Position of `path`, else of the nearest written ancestor (an array's element falls back
    /// to the array, a key the file leaves to the preset to nothing).
    pub fn find(&self, path: &str) -> Option<Position> {
        let mut p = path;
        loop {
            if let Some(pos) = self.at.get(p) {
                return Some(*pos);
            }
            // `a.b[2]` → `a.b`; otherwise stop: a parent table's position would mislead.
            p = p.rsplit_once('[')?.0;
        }
    }
}

/// Byte offset → line/column.
struct LineStarts<'a> {
    text: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineStarts<'a> {
    fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Self { text, starts }
    }

    fn position(&self, byte: usize) -> Position {
        let line = self.starts.partition_point(|&s| s <= byte);
        let start = self.starts[line - 1];
        let column = self.text[start..byte.min(self.text.len())].chars().count() + 1;
        Position { line, column }
    }
}

fn walk(
    lines: &LineStarts<'_>,
    prefix: &str,
    table: &DeTable<'_>,
    at: &mut HashMap<String, Position>,
) {
    for (key, value) in table {
        let path = if prefix.is_empty() {
            key.get_ref().to_string()
        } else {
            format!("{prefix}.{}", key.get_ref())
        };
        visit(lines, path, value.span().start, value.get_ref(), at);
    }
}

fn visit(
    lines: &LineStarts<'_>,
    path: String,
    start: usize,
    value: &DeValue<'_>,
    at: &mut HashMap<String, Position>,
) {
    match value {
        DeValue::Table(t) => walk(lines, &path, t, at),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                visit(
                    lines,
                    format!("{path}[{i}]"),
                    item.span().start,
                    item.get_ref(),
                    at,
                );
            }
        }
        _ => {}
    }
    at.entry(path).or_insert_with(|| lines.position(start));
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "\
[scenario]
name = \"x\"
[sensor]
gyro.bias = { enabled = true, dph = [500.0, 0.0, 0.0] }
[sensor.accel.bias]
ug = [1.0,
  2.0, 3.0]
[[scheme.steps]]
angle_deg = 180.0
[[scheme.steps]]
angle_deg = 90.0
";

    #[test]
    fn finds_inline_tables_dotted_keys_arrays_and_array_tables() {
        let s = SpanIndex::new(TEXT);
        let at = |p: &str| s.find(p).map(|x| (x.line, x.column));
        assert_eq!(at("scenario.name"), Some((2, 8)));
        assert_eq!(at("sensor.gyro.bias.dph[0]"), Some((4, 38)));
        assert_eq!(at("sensor.gyro.bias.enabled"), Some((4, 25)));
        assert_eq!(at("sensor.accel.bias.ug[2]"), Some((7, 8)));
        assert_eq!(at("sensor.accel.bias.ug[7]"), Some((6, 6)));
        assert_eq!(at("scheme.steps[1].angle_deg"), Some((11, 13)));
        assert_eq!(at("sensor.gyro.scale_factor.ppm"), None);
    }
}
