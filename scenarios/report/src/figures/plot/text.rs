//! Text: the built-in font and the size, width and line breaking of text at print size.

use std::sync::Once;

use plotters::prelude::*;

use super::sizes::WIDTH_PX;
use crate::figures::rules;

/// DejaVu Sans, registered as the `sans-serif` family for both backends.
static FONT: &[u8] = include_bytes!("../../../fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

pub(super) fn register_font() {
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType font (checked by the figure tests); a failure here
        // would only leave text undrawn in the PNG, never abort.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// The em of text of `pt` points at print width, px: for [`TEXT_PT`], the smallest text,
/// [`rules::min_text_px`] of [`WIDTH_PX`].
pub(super) fn em_px(pt: f64) -> f64 {
    pt * rules::px_per_pt(WIDTH_PX)
}

/// The font for text of `pt` points at print width. plotters writes an SVG `font-size` of its
/// size / 1.24, so the size is the em × 1.24; the PNG rasteriser draws DejaVu Sans a little
/// larger (its ascent + descent is 1.16 em), never smaller.
pub(super) fn font(pt: f64) -> FontDesc<'static> {
    ("sans-serif", em_px(pt) * 1.24).into_font()
}

/// Height of one line of text of `pt` points, px.
pub(super) fn line_px(pt: f64) -> i32 {
    (1.3 * em_px(pt)).ceil() as i32
}

/// Width of `text` in `f`, px (the rasteriser's layout; a rough estimate if it fails).
pub(super) fn text_w(f: &FontDesc, text: &str) -> i32 {
    f.box_size(text).map_or_else(
        |_| (0.6 * f.get_size() / 1.24 * text.chars().count() as f64) as i32,
        |b| b.0 as i32,
    )
}

/// `text` broken at spaces into lines at most `max_w` px wide in `f` (a single word longer
/// than that keeps its own line).
pub(super) fn wrap(text: &str, f: &FontDesc, max_w: i32) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for word in text.split_whitespace() {
        let trial = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if !cur.is_empty() && text_w(f, &trial) > max_w {
            lines.push(std::mem::replace(&mut cur, word.to_string()));
        } else {
            cur = trial;
        }
    }
    if !cur.is_empty() || lines.is_empty() {
        lines.push(cur);
    }
    lines
}
