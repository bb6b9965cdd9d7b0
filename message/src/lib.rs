//! Numbers as error messages echo them. Rust's `{}` writes an `f64` in plain decimals whatever
//! its size: 1e-300 as "0.000…01" (302 characters), 1e300 as 301 digits, and 2^63 (an integer
//! a file gives a real-valued key) as "9223372036854776000", digits that look exact and are
//! not. [`Num`] writes the shortest text that reads back as the same `f64`: in plain decimals
//! for magnitudes in [1e-4, 1e7) ("0.001", "250", "-3.5"), in exponent form below 1e-4 and
//! from 1e15 up ("1e-300", "1e300", "9.223372036854776e18"), and in between in whichever form
//! is shorter ("1e10", "1712345678.25"); NaN, inf and -inf are spelled so. A precision
//! (`{:.3}`) is kept, in the same form. [`range`] writes a closed range with its bounds so.
//! The range checks of the scenario, sweep, command-line, trajectory and measurement messages,
//! and the FMU layer's variable ranges, format their numbers through these. [`quote`] and
//! [`file_location`] name a text and a place in a file so.
//!
//! Its own crate, below both `rins-plant` (which re-exports it as `rins_plant::message`) and
//! the generic `rins-fmi`, which depends on nothing of the plant.

use std::fmt;

/// Magnitudes always written in plain decimals: [`PLAIN_MIN`, `PLAIN_MAX`).
const PLAIN_MIN: f64 = 1e-4;
/// See [`PLAIN_MIN`].
const PLAIN_MAX: f64 = 1e7;
/// Magnitudes from [`PLAIN_MAX`] up to this one are written in the shorter of the two forms;
/// beyond it plain decimals would pad the 17 significant digits with zeros.
const EXP_MIN: f64 = 1e15;

/// An `f64` as a message echoes it (see the module docs): `format!("got {}", Num(v))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v.is_nan() {
            return f.write_str("NaN");
        }
        if v.is_infinite() {
            return f.write_str(if v > 0.0 { "inf" } else { "-inf" });
        }
        let a = v.abs();
        let (plain, exp) = match f.precision() {
            None => (format!("{v}"), format!("{v:e}")),
            Some(p) => (format!("{v:.p$}"), format!("{v:.p$e}")),
        };
        let use_plain = a == 0.0
            || (PLAIN_MIN..PLAIN_MAX).contains(&a)
            || ((PLAIN_MAX..EXP_MIN).contains(&a) && plain.len() <= exp.len());
        f.write_str(if use_plain { &plain } else { &exp })
    }
}

/// `v` as a message echoes it: `Num(v).to_string()`.
pub fn num(v: f64) -> String {
    Num(v).to_string()
}

/// The closed range `[lo, hi]` with its bounds as [`Num`] writes them (an infinite bound as
/// `inf`).
pub fn range(lo: f64, hi: f64) -> String {
    format!("[{}, {}]", Num(lo), Num(hi))
}

/// What a range check expects of a value `v` that is outside `[lo, hi]`: "a number in [lo, hi]",
/// and "a finite number in [lo, hi]" when `v` is infinite or NaN and the range has finite
/// bounds (so "got inf" is not read as too large a number).
pub fn expected_in(v: f64, lo: f64, hi: f64) -> String {
    if !v.is_finite() && lo.is_finite() && hi.is_finite() {
        format!("a finite number in {}", range(lo, hi))
    } else {
        format!("a number in {}", range(lo, hi))
    }
}

/// Characters of a name or a text that [`quote`] keeps.
pub const QUOTE_CHARS: usize = 80;

/// `s` in double quotes, escaped (control characters as escapes), cut to its first
/// [`QUOTE_CHARS`] characters with `…` (a 5000-character column name is not echoed whole).
pub fn quote(s: &str) -> String {
    let mut out: String = s
        .chars()
        .take(QUOTE_CHARS)
        .flat_map(char::escape_debug)
        .collect();
    if s.chars().nth(QUOTE_CHARS).is_some() {
        out.push('…');
    }
    format!("\"{out}\"")
}

/// Where in a file of a header and data rows (a trajectory, a measurement file) an error lies,
/// for its message: `row` counts data rows from 1, 0 is the header (with a `column`) or the
/// file as a whole (without one); an empty `column` is the whole row. So "the whole file",
/// "header, column \"lat_deg\"", "row 3" or "row 3, column \"t_s\"", never `row 0,
/// column ""`.
pub fn file_location(row: usize, column: &str) -> String {
    match (row, column.is_empty()) {
        (0, true) => "the whole file".into(),
        (0, false) => format!("header, column {}", quote(column)),
        (r, true) => format!("row {r}"),
        (r, false) => format!("row {r}, column {}", quote(column)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 44: what the messages echoed before (hundreds of digits, 2^63 as
    /// "9223372036854776000") and what they echo now.
    #[test]
    fn numbers_are_echoed_short_and_exact() {
        let cases: [(f64, &str); 17] = [
            (1e-300, "1e-300"),
            (1e300, "1e300"),
            (-1e300, "-1e300"),
            (9_223_372_036_854_775_808.0, "9.223372036854776e18"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (0.0, "0"),
            (-0.0, "-0"),
            (500.0, "500"),
            (0.001, "0.001"),
            (0.00001, "1e-5"),
            (1e7, "1e7"),
            (1712345678.25, "1712345678.25"),
            (9999999.5, "9999999.5"),
            (123456789012345.0, "123456789012345"),
            (f64::MIN_POSITIVE, "2.2250738585072014e-308"),
        ];
        for (v, want) in cases {
            assert_eq!(num(v), want, "{v:e}");
            // Every echo reads back as the same number.
            if v.is_finite() {
                assert_eq!(num(v).parse::<f64>().unwrap(), v, "{want}");
            }
        }
        assert_eq!(format!("{:.3}", Num(9.4712)), "9.471");
        assert_eq!(format!("{:.3}", Num(2.1177e75)), "2.118e75");
        assert_eq!(range(0.0, 20.0), "[0, 20]");
        assert_eq!(range(1e-9, f64::INFINITY), "[1e-9, inf]");
        assert_eq!(
            expected_in(f64::INFINITY, 0.0, 20.0),
            "a finite number in [0, 20]"
        );
        assert_eq!(expected_in(1e300, 0.0, 20.0), "a number in [0, 20]");
    }

    /// Issue 44: file-level errors said `row 0, column ""`.
    #[test]
    fn file_locations_name_the_file_the_header_or_the_row() {
        assert_eq!(file_location(0, ""), "the whole file");
        assert_eq!(file_location(0, "t_s"), "header, column \"t_s\"");
        assert_eq!(file_location(4, ""), "row 4");
        assert_eq!(file_location(4, "lat_deg"), "row 4, column \"lat_deg\"");
        let long = "x".repeat(100);
        assert_eq!(
            file_location(1, &long),
            format!("row 1, column \"{}…\"", "x".repeat(80))
        );
    }
}
