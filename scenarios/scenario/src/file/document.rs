//! The scenario as one spanned TOML document: the file's text is parsed once; the sensor preset
//! and the command-line overrides are laid into that document; the typed scenario is read from
//! it once. Values the file did not write carry spans past the end of the text, so an error
//! about one of them names the preset or the flag instead of a line of the file.

use std::ops::Range;

use serde::Deserialize;
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeArray, DeTable, DeValue, ValueDeserializer};

use super::whole_arrays::WholeArrays;
use crate::spans::SpanIndex;

/// Where a value of the document came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Origin {
    /// Written in the file (or an error without a place).
    File,
    /// Laid in from the sensor preset.
    Preset,
    /// Set by the override with this index.
    Override(usize),
}

/// The document of one scenario, borrowing the text it was parsed from.
#[derive(Clone)]
pub(super) struct Document<'i> {
    text: &'i str,
    root: Spanned<DeTable<'i>>,
}

impl<'i> Document<'i> {
    /// Parses `text`; a syntax error carries toml's line and column. An integer outside TOML's
    /// range (64-bit signed), which the parser keeps as text, is refused here as the TOML
    /// specification asks, at its line and column, before any key is looked at.
    pub(super) fn parse(text: &'i str) -> Result<Self, toml::de::Error> {
        let root = DeTable::parse(text)?;
        if let Some(value) = first_integer_out_of_range(root.get_ref()) {
            // toml's own refusal of the value (its message and span), shown on the text.
            let value = ValueDeserializer::from(value.clone());
            if let Err(mut e) = toml::Value::deserialize(value) {
                e.set_input(Some(text));
                return Err(e);
            }
        }
        Ok(Self { text, root })
    }

    /// Whether the file has no keys at all.
    pub(super) fn is_empty(&self) -> bool {
        self.root.get_ref().is_empty()
    }

    /// Where each key of the file is written. Call it before laying anything in: only the
    /// file's own keys have a line.
    pub(super) fn spans(&self) -> SpanIndex {
        SpanIndex::of_document(self.text, self.root.get_ref())
    }

    /// `sensor.preset` as the file writes it, if it is a string (a value of another type is
    /// left for the typed read to refuse with its line).
    pub(super) fn preset_name(&self) -> Option<&str> {
        self.root
            .get_ref()
            .get("sensor")?
            .get_ref()
            .as_table()?
            .get("preset")?
            .get_ref()
            .as_str()
    }

    /// Lays the preset's `[sensor]` keys under the file's: a key the file writes wins, tables
    /// the two share are merged key by key, so writing only `dph` under `[sensor.gyro.bias]`
    /// keeps the preset's `enabled`. The preset is named in `[sensor]`, so that table exists.
    pub(super) fn lay_preset(&mut self, fragment: &DeTable<'static>) {
        if fragment.is_empty() {
            return;
        }
        let span = self.preset_span();
        let sensor = self.root.get_mut().get_mut("sensor").map(Spanned::get_mut);
        if let Some(DeValue::Table(sensor)) = sensor {
            fill_from(sensor, fragment, &span);
        }
    }

    /// Sets the dotted `path` to `value` for override number `index`, creating tables on the
    /// way. Where the file writes a non-table on the way, the override is not laid in, so the
    /// typed read refuses the file's value at its line as it would without the override.
    pub(super) fn lay_override(&mut self, index: usize, path: &str, value: DeValue<'i>) {
        let span = self.override_span(index);
        let mut table = self.root.get_mut();
        let mut parts = path.split('.').peekable();
        while let Some(part) = parts.next() {
            let key = Spanned::new(span.clone(), part.to_string().into());
            if parts.peek().is_none() {
                table.insert(key, marked(Spanned::new(span.clone(), value), &span));
                return;
            }
            let next = table
                .entry(key)
                .or_insert_with(|| Spanned::new(span.clone(), DeValue::Table(DeTable::new())));
            match next.get_mut() {
                DeValue::Table(t) => table = t,
                _ => return,
            }
        }
    }

    /// Reads the typed value from the document (unknown keys, wrong types and arrays longer
    /// than the type's refused), and says where a refused value came from. An error about a
    /// value of the file shows the file's line and column, word for word as `toml::from_str`
    /// on the text.
    pub(super) fn read<T: DeserializeOwned>(self) -> Result<T, (Origin, toml::de::Error)> {
        let text = self.text;
        let whole = WholeArrays(toml::de::Deserializer::from(self.root));
        T::deserialize(whole).map_err(|mut e| {
            let origin = origin_of(text, e.span());
            if origin == Origin::File {
                e.set_input(Some(text));
            }
            (origin, e)
        })
    }

    /// The span that marks preset values: just past the end of the text.
    fn preset_span(&self) -> Range<usize> {
        let at = self.text.len() + 1;
        at..at
    }

    /// The span that marks values of override number `index`.
    fn override_span(&self, index: usize) -> Range<usize> {
        let at = self.text.len() + 2 + index;
        at..at
    }
}

/// Which layer a span points into (see [`Document::preset_span`], [`Document::override_span`]).
fn origin_of(text: &str, span: Option<Range<usize>>) -> Origin {
    match span.map(|s| s.start.checked_sub(text.len() + 1)) {
        Some(Some(0)) => Origin::Preset,
        Some(Some(k)) => Origin::Override(k - 1),
        _ => Origin::File,
    }
}

/// The first integer, in document order, that does not fit an `i64`.
fn first_integer_out_of_range<'a, 'i>(table: &'a DeTable<'i>) -> Option<&'a Spanned<DeValue<'i>>> {
    fn visit<'a, 'i>(value: &'a Spanned<DeValue<'i>>) -> Option<&'a Spanned<DeValue<'i>>> {
        match value.get_ref() {
            DeValue::Integer(n) => i64::from_str_radix(n.as_str(), n.radix())
                .is_err()
                .then_some(value),
            DeValue::Array(items) => items.iter().find_map(visit),
            DeValue::Table(t) => first_integer_out_of_range(t),
            _ => None,
        }
    }
    table.values().find_map(visit)
}

/// Copies into `table` every key of `base` it lacks, marked with `span`; where both hold a
/// table, recurses. `table`'s own values (and their spans) stay.
fn fill_from<'i>(table: &mut DeTable<'i>, base: &DeTable<'static>, span: &Range<usize>) {
    for (key, value) in base {
        match table.get_mut(key.get_ref().as_ref()).map(Spanned::get_mut) {
            Some(DeValue::Table(own)) => {
                if let DeValue::Table(b) = value.get_ref() {
                    fill_from(own, b, span);
                }
            }
            Some(_) => {}
            None => {
                table.insert(
                    Spanned::new(span.clone(), key.get_ref().clone()),
                    marked(value.clone(), span),
                );
            }
        }
    }
}

/// `value` with every span inside it (keys, elements) replaced by `span`.
fn marked<'i>(value: Spanned<DeValue<'i>>, span: &Range<usize>) -> Spanned<DeValue<'i>> {
    let value = match value.into_inner() {
        DeValue::Array(items) => DeValue::Array(
            items
                .into_iter()
                .map(|item| marked(item, span))
                .collect::<DeArray<'i>>(),
        ),
        DeValue::Table(t) => DeValue::Table(
            t.into_iter()
                .map(|(k, v)| (Spanned::new(span.clone(), k.into_inner()), marked(v, span)))
                .collect(),
        ),
        other => other,
    };
    Spanned::new(span.clone(), value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origins_of_spans() {
        let text = "a = 1\n";
        assert_eq!(origin_of(text, None), Origin::File);
        assert_eq!(origin_of(text, Some(4..5)), Origin::File);
        assert_eq!(origin_of(text, Some(6..6)), Origin::File);
        assert_eq!(origin_of(text, Some(7..7)), Origin::Preset);
        assert_eq!(origin_of(text, Some(8..8)), Origin::Override(0));
        assert_eq!(origin_of(text, Some(10..10)), Origin::Override(2));
    }
}
