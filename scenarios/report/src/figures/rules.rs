//! The rules every figure follows, in one place, as pure functions the drawing code
//! ([`super::plot`]) applies and the tests check:
//!
//! * a long series is drawn as a per-pixel-column min/max envelope with its mean
//!   ([`envelope`]), so a week of 60 s records neither fills the file nor turns a 16-position
//!   cycle into a solid comb, and the visible extremes stay those of the series;
//! * the legend goes into a corner of the plotting area that no plotted point or segment
//!   touches, chosen from the data ([`place_legend`]); when no corner is free the y range gets
//!   headroom above the data, and when the legend is too tall for that it goes outside, right of
//!   the plot;
//! * tick labels never read "-0" or "-0.0" ([`tick_label`]); an axis of whole numbers (the
//!   iteration steps, `Panel::whole_x`) is ticked at whole numbers only ([`whole_tick_label`]);
//! * a categorical axis (table position, channel, effect) is labelled with its category names
//!   at integer positions, never with numeric ticks (drawn in [`super::plot`]);
//! * print size: a figure is laid out to be printed one column wide, [`PRINT_WIDTH_IN`] = 3.5 in
//!   (88.9 mm, a two-column journal), and no text is smaller than [`MIN_TEXT_PT`] = 8 pt there
//!   ([`min_text_px`]: a 900 px figure is 257 px/in, so 8 pt is 28.6 px);
//! * headroom: every mark (bar end, dot with its radius, trace) lies at least [`HEADROOM_PX`]
//!   inside the frame: the y range, and the x range of scatter and bar panels, is widened by
//!   [`padded_range`] so no bar or point runs into the frame or sits on its edge; a scatter's
//!   outermost dots keep [`SCATTER_X_PAD_FRAC`] of the width from the side frames;
//! * markers stay visible: a sparse scatter is drawn with large opaque dots, a dense one with
//!   translucent dots so overlaps show ([`dot_style`]);
//! * units are typeset: "ug" prints as "µg", "deg C" as "°C", "deg/h" as "°/h" ([`typeset`];
//!   DejaVu Sans, which the PNG uses, has both glyphs).
//!
//! Overlapping traces are told apart by the line kinds of [`super::plot::Kind`] (dashed,
//! translucent envelope fills, dots with transparency), by side-by-side error bars, and by
//! draw order: in a panel of several envelopes the first draws its mean line 3 px wide and each
//! later one 1 px wide on top, so where two cases nearly coincide the second case's line runs
//! inside the first's. Where they coincide at print size (Figure 2's east and north axes,
//! which δβ hardly moves) a difference panel (uncompensated − compensated per axis, on its own
//! scale) shows what draw order cannot ([`super::paper::paired_figures`]).

/// The width a figure is printed at: one column of a two-column journal, 3.5 in (88.9 mm).
pub const PRINT_WIDTH_IN: f64 = 3.5;
/// The smallest text size at [`PRINT_WIDTH_IN`], pt.
pub const MIN_TEXT_PT: f64 = 8.0;
/// Space between the outer edge of every mark and the plot frame, px (about 4 pt at
/// [`PRINT_WIDTH_IN`] for a 900 px figure).
pub const HEADROOM_PX: i32 = 14;

/// The least space between a scatter's outermost dots and the left and right frame, as a
/// share of the plot width (5 %: about 40 px, 4 mm printed, for a 900 px figure), so clusters
/// at a few x values (chamber temperatures) stand clear of the frame, not on its edge.
pub const SCATTER_X_PAD_FRAC: f64 = 0.05;

/// Pixels per printed point of a figure `width_px` wide printed at [`PRINT_WIDTH_IN`]
/// (72 pt to the inch): 900 px → 3.57 px/pt.
pub fn px_per_pt(width_px: u32) -> f64 {
    width_px as f64 / (PRINT_WIDTH_IN * 72.0)
}

/// The smallest font size, px (the em: the SVG's `font-size`), that keeps text at least
/// [`MIN_TEXT_PT`] when a figure `width_px` wide is printed [`PRINT_WIDTH_IN`] wide.
///
/// A point is 1/72 in, so 8 pt is 8/72 in = 0.1111 in (2.82 mm). Printed 3.5 in wide, the
/// figure has `width_px` / 3.5 px per inch; the text needs 8/72 × `width_px` / 3.5 px:
/// for 900 px that is 0.1111 × 257.14 = 28.57 px (for 88 mm, 3.46 in, it would be 28.9 px).
pub fn min_text_px(width_px: u32) -> f64 {
    MIN_TEXT_PT / 72.0 * (width_px as f64 / PRINT_WIDTH_IN)
}

/// The printed size, pt, of text whose em is `em_px` px in a figure `width_px` wide.
pub fn text_pt(em_px: f64, width_px: u32) -> f64 {
    em_px / px_per_pt(width_px)
}

/// The axis range that puts the data range `[lo, hi]` `inset_px` px inside both ends of an
/// axis `len_px` px long (a degenerate range is first widened to ±1e-12 about its value; the
/// inset is capped at 40 % of the axis so a tiny axis still shows its data).
pub fn padded_range(lo: f64, hi: f64, inset_px: f64, len_px: f64) -> (f64, f64) {
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 1e-12, hi + 1e-12)
    };
    let len = len_px.max(1.0);
    let inset = inset_px.clamp(0.0, 0.4 * len);
    let per_px = (hi - lo) / (len - 2.0 * inset);
    (lo - inset * per_px, hi + inset * per_px)
}

/// Radius (px) and opacity of the dots of a scatter of `n` points: a sparse one (up to 10
/// points: a few cases, a noise-free pair) large and opaque, a dense one smaller and
/// translucent so overlapping points show.
pub fn dot_style(n: usize) -> (i32, f64) {
    if n <= 10 { (8, 1.0) } else { (5, 0.5) }
}

/// `text` with its units typeset: the word "ug" → "µg", "deg C" → "°C", the word "deg"
/// (alone or before "/") → "°". Other words are left alone ("plug", "degree", "ug_x").
pub fn typeset(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let word = |c: char| c.is_alphanumeric() || c == '_';
    let mut out = String::with_capacity(text.len() + 4);
    let mut i = 0;
    while i < chars.len() {
        let starts_word = i == 0 || !word(chars[i - 1]);
        let at = |s: &str| {
            let w: Vec<char> = s.chars().collect();
            chars[i..].starts_with(&w) && chars.get(i + w.len()).is_none_or(|&c| !word(c))
        };
        if starts_word && at("ug") {
            out.push_str("µg");
            i += 2;
        } else if starts_word && at("deg C") {
            out.push_str("°C");
            i += 5;
        } else if starts_word && at("deg") {
            out.push('°');
            i += 3;
        } else {
            out.push(chars[i]);
            i += 1;
        }
    }
    out
}

/// A pixel rectangle: left, top, right, bottom (right/bottom exclusive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    /// Left edge, px.
    pub x0: i32,
    /// Top edge, px.
    pub y0: i32,
    /// Right edge, px.
    pub x1: i32,
    /// Bottom edge, px.
    pub y1: i32,
}

impl Rect {
    /// Whether the pixel `(x, y)` lies inside (edges included).
    pub fn contains(&self, (x, y): (i32, i32)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }

    /// Whether the segment `a`–`b` touches the rectangle (sampled every pixel along its length,
    /// exact enough at the resolution the figure is drawn at).
    pub fn touches_segment(&self, a: (i32, i32), b: (i32, i32)) -> bool {
        let n = (a.0 - b.0).abs().max((a.1 - b.1).abs()).max(1);
        (0..=n).any(|k| {
            let t = k as f64 / n as f64;
            let p = (
                (a.0 as f64 + t * (b.0 - a.0) as f64).round() as i32,
                (a.1 as f64 + t * (b.1 - a.1) as f64).round() as i32,
            );
            self.contains(p)
        })
    }
}

/// One pixel column of an envelope: the x at its centre and the min, max and mean of the
/// samples that fall in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Column {
    /// x of the column centre (data units); the column's first sample's x when it has one
    /// sample.
    pub x: f64,
    /// Smallest y in the column.
    pub min: f64,
    /// Largest y in the column.
    pub max: f64,
    /// Mean y in the column.
    pub mean: f64,
}

/// The per-column min/max/mean of `points` over `[x0, x1]` split into `columns` equal columns
/// (non-finite points skipped, empty columns left out). Every finite sample is in exactly one
/// column, so the envelope's overall min and max are the series' min and max.
pub fn envelope(points: &[(f64, f64)], x0: f64, x1: f64, columns: usize) -> Vec<Column> {
    let columns = columns.max(1);
    let width = (x1 - x0).max(f64::MIN_POSITIVE);
    let mut acc: Vec<Option<(f64, f64, f64, u64)>> = vec![None; columns];
    for &(x, y) in points {
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        let k = (((x - x0) / width * columns as f64).floor().max(0.0) as usize).min(columns - 1);
        acc[k] = Some(match acc[k] {
            None => (y, y, y, 1),
            Some((lo, hi, s, n)) => (lo.min(y), hi.max(y), s + y, n + 1),
        });
    }
    acc.iter()
        .enumerate()
        .filter_map(|(k, a)| {
            a.map(|(min, max, sum, n)| Column {
                x: x0 + width * (k as f64 + 0.5) / columns as f64,
                min,
                max,
                mean: sum / n as f64,
            })
        })
        .collect()
}

/// Where a panel's legend goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LegendPlace {
    /// Inside the plotting area, at this rectangle (relative to the plot's top-left corner),
    /// which no point or segment touches.
    Inside(Rect),
    /// Inside at the top right, after raising the y range's top by this fraction of the range
    /// so the band under the legend holds no data.
    Headroom(Rect, f64),
    /// Outside, in a strip above the plotting area (the plot is lowered by the strip's
    /// height), its entries side by side.
    Outside,
}

/// Padding between a legend and the plot frame, px.
pub const LEGEND_PAD_PX: i32 = 6;
/// The largest share of the plot height a legend band may take as headroom; a taller legend
/// goes above the plot.
pub const HEADROOM_MAX_FRAC: f64 = 0.25;

/// Picks a legend place for a `w`×`h` px legend in a `plot_w`×`plot_h` px plot whose marks are
/// `segments` (pixel coordinates relative to the plot's top-left; a point is a segment of zero
/// length): the first free corner of upper right, upper left, lower right, lower left; else
/// headroom when the legend band takes at most [`HEADROOM_MAX_FRAC`] of the height; else
/// outside (above the plot).
pub fn place_legend(
    plot_w: i32,
    plot_h: i32,
    w: i32,
    h: i32,
    segments: &[((i32, i32), (i32, i32))],
) -> LegendPlace {
    let p = LEGEND_PAD_PX;
    if w + 2 * p > plot_w || h + 2 * p > plot_h {
        return LegendPlace::Outside;
    }
    let corners = [
        (plot_w - p - w, p),
        (p, p),
        (plot_w - p - w, plot_h - p - h),
        (p, plot_h - p - h),
    ];
    for (x, y) in corners {
        let r = Rect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        };
        if !segments.iter().any(|&(a, b)| r.touches_segment(a, b)) {
            return LegendPlace::Inside(r);
        }
    }
    let band = h + 2 * p;
    if (band as f64) <= HEADROOM_MAX_FRAC * plot_h as f64 {
        // Data squeezed into the lower plot_h - band px: the top band is free.
        let raise = band as f64 / (plot_h - band) as f64;
        let (x, y) = corners[0];
        return LegendPlace::Headroom(
            Rect {
                x0: x,
                y0: y,
                x1: x + w,
                y1: y + h,
            },
            raise,
        );
    }
    LegendPlace::Outside
}

/// A tick label of an axis of whole numbers (iteration steps): `v` without decimals when it is
/// a whole number, nothing otherwise, so such an axis never reads 0.5 or 1.5 (the iteration
/// history ticked its step axis at 0.0, 0.5, 1.0).
pub fn whole_tick_label(v: f64) -> String {
    if (v - v.round()).abs() <= 1e-9 * v.abs().max(1.0) {
        // `+ 0.0`: -0 prints as 0.
        format!("{}", v.round() + 0.0)
    } else {
        String::new()
    }
}

/// A tick label for `v` on an axis spanning `span`: enough decimals for the tick step, no
/// "-0"/"-0.0", scientific notation for very small steps or large magnitudes. The notation is
/// chosen from the axis (its step and span), not from each value, so one axis never mixes
/// "5.00e-4" with "-0.0010"; a zero in scientific notation reads "0".
pub fn tick_label(v: f64, span: f64) -> String {
    let step = (span.abs() / 5.0).max(f64::MIN_POSITIVE);
    let mag = v.abs().max(span.abs());
    let s = if step < 1e-4 || mag >= 1e6 {
        if v.abs() < 1e-9 * step {
            return "0".to_string();
        }
        format!("{v:.2e}")
    } else {
        let decimals = (-(step.log10().floor()) as i32).clamp(0, 6) as usize;
        format!("{v:.decimals$}")
    };
    // A value that rounds to zero prints without its sign.
    if s.starts_with('-') && s[1..].chars().all(|c| matches!(c, '0' | '.')) {
        s[1..].to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn envelope_keeps_the_extremes_and_every_sample() {
        let pts: Vec<(f64, f64)> = (0..10_000)
            .map(|i| (i as f64, ((i * 7919) % 1000) as f64 - 500.0))
            .collect();
        let env = envelope(&pts, 0.0, 9999.0, 300);
        assert_eq!(env.len(), 300);
        let lo = env.iter().map(|c| c.min).fold(f64::MAX, f64::min);
        let hi = env.iter().map(|c| c.max).fold(f64::MIN, f64::max);
        assert_eq!(lo, pts.iter().map(|p| p.1).fold(f64::MAX, f64::min));
        assert_eq!(hi, pts.iter().map(|p| p.1).fold(f64::MIN, f64::max));
        let mean: f64 = pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64;
        // Equal columns hold 33 or 34 samples: the mean of the column means is near the mean.
        let cm: f64 = env.iter().map(|c| c.mean).sum::<f64>() / env.len() as f64;
        assert!((cm - mean).abs() < 5.0, "{cm} vs {mean}");
    }

    #[test]
    fn no_minus_zero_ticks() {
        assert_eq!(tick_label(-0.0, 1.0), "0.0");
        assert_eq!(tick_label(-1e-17, 0.5), "0.0");
        assert_eq!(tick_label(-0.004, 0.05), "0.00");
        assert_eq!(tick_label(-0.25, 1.0), "-0.2");
        assert_eq!(tick_label(3.0, 40.0), "3");
        assert_eq!(tick_label(2.5e-6, 1e-5), "2.50e-6");
        assert_eq!(tick_label(0.0, 1e-5), "0");
        // One notation per axis: a ±0.001 axis reads 0.0005, 0, -0.0010 alike.
        assert_eq!(tick_label(5e-4, 0.002), "0.0005");
        assert_eq!(tick_label(0.0, 0.002), "0.0000");
        assert_eq!(tick_label(-1e-3, 0.002), "-0.0010");
        assert_eq!(tick_label(2.0e6, 4.0e6), "2.00e6");
    }

    #[test]
    fn print_size_of_a_900_px_figure() {
        // 3.5 in at 72 pt/in is 252 pt across 900 px.
        assert!((px_per_pt(900) - 900.0 / 252.0).abs() < 1e-12);
        assert!((MIN_TEXT_PT * px_per_pt(900) - 28.571_428_571).abs() < 1e-6);
        // The same minimum by the arithmetic of min_text_px's doc: 8/72 in at 900/3.5 px/in.
        assert!((min_text_px(900) - 8.0 / 72.0 * 900.0 / 3.5).abs() < 1e-12);
        assert!((text_pt(min_text_px(900), 900) - MIN_TEXT_PT).abs() < 1e-12);
        // Half the pixels, half the minimum.
        assert!((min_text_px(450) - 0.5 * min_text_px(900)).abs() < 1e-12);
        // plotters' old 12-unit text: an SVG em of 12 / 1.24 = 9.68 px is 2.7 pt.
        assert!((text_pt(12.0 / 1.24, 900) - 2.71).abs() < 0.01);
    }

    #[test]
    fn padded_range_keeps_the_data_inset() {
        let (lo, hi) = padded_range(2.0, 10.0, 20.0, 300.0);
        // Pixel of a value on a 300 px axis over [lo, hi].
        let px = |v: f64| (v - lo) / (hi - lo) * 300.0;
        assert!((px(2.0) - 20.0).abs() < 1e-9 && (px(10.0) - 280.0).abs() < 1e-9);
        let (lo, hi) = padded_range(5.0, 5.0, 10.0, 100.0);
        assert!(lo < 5.0 && hi > 5.0);
    }

    #[test]
    fn units_are_typeset() {
        assert_eq!(typeset("residual (ug)"), "residual (µg)");
        assert_eq!(
            typeset("sensor temperature (deg C)"),
            "sensor temperature (°C)"
        );
        assert_eq!(typeset("rate (deg/h), ug/K"), "rate (°/h), µg/K");
        assert_eq!(typeset("attitude error (deg)"), "attitude error (°)");
        assert_eq!(typeset("plug degree ug_x bug"), "plug degree ug_x bug");
    }

    #[test]
    fn legend_takes_a_free_corner_or_headroom() {
        // Points along the top band: the lower corners are free; lower right comes first.
        let top: Vec<_> = (0..100).map(|x| ((x * 8, 20), (x * 8, 20))).collect();
        match place_legend(800, 200, 100, 40, &top) {
            LegendPlace::Inside(r) => assert!(r.y0 > 100 && r.x0 > 400, "{r:?}"),
            p => panic!("{p:?}"),
        }
        // A diagonal and the opposite diagonal cross every corner: headroom.
        let mut cross: Vec<_> = vec![((0, 0), (800, 200)), ((0, 200), (800, 0))];
        cross.push(((0, 100), (800, 100)));
        assert!(matches!(
            place_legend(800, 200, 100, 30, &cross),
            LegendPlace::Headroom(_, _)
        ));
        // A band over a quarter of the height goes above the plot.
        assert_eq!(
            place_legend(800, 200, 100, 40, &cross),
            LegendPlace::Outside
        );
        assert_eq!(
            place_legend(800, 200, 100, 150, &cross),
            LegendPlace::Outside
        );
    }
}
