//! What a caller describes (a panel of lines, each drawn by its [`Kind`]) and what the drawing
//! reports back ([`PanelGeometry`], where everything landed).

use plotters::style::RGBColor;

use crate::figures::rules::{Column, Rect};

/// How a line is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A solid line through the points.
    Solid,
    /// A dashed line (for a smooth trace another one overlaps: fits, references, tRMS); drawn
    /// through its per-column means when it has more points than columns.
    Dashed,
    /// Separate error bars: `points` holds (x, y − e), (x, y + e) pairs, one pair per bar,
    /// each drawn with a dot at its centre.
    ErrorBars,
    /// Bars of an asymmetric band with its estimate: `points` holds (x, low), (x, estimate),
    /// (x, high) triples (e.g. 5 %, median, 95 %), each drawn with a dot at the estimate.
    Interval,
    /// Dots, one per point (scatter): large and opaque when sparse, smaller and translucent
    /// when dense ([`rules::dot_style`]).
    Dots,
    /// A long series: per pixel column the min–max band (translucent) and the mean line
    /// ([`rules::envelope`]); drawn as a solid line when it has fewer points than columns.
    Envelope,
}

/// One line of a panel.
pub struct Line<'a> {
    /// Legend label (empty: no legend entry).
    pub label: &'a str,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// How it is drawn.
    pub kind: Kind,
}

impl<'a> Line<'a> {
    /// A line of `kind`.
    pub fn new(label: &'a str, points: Vec<(f64, f64)>, color: RGBColor, kind: Kind) -> Self {
        Self {
            label,
            points,
            color,
            kind,
        }
    }
}

/// One panel of a figure.
pub struct Panel<'a> {
    /// Panel title.
    pub title: String,
    /// y-axis label with unit.
    pub y_label: &'a str,
    /// Lines.
    pub lines: Vec<Line<'a>>,
    /// Category names of a categorical x axis, category k at x = k (empty: numeric x).
    pub categories: Vec<String>,
    /// A numeric x axis of whole numbers (steps, counts): ticked at whole numbers only
    /// ([`crate::figures::rules::whole_tick_label`]), never at 0.5.
    pub whole_x: bool,
}

impl<'a> Panel<'a> {
    /// A panel with a numeric x axis.
    pub fn new(title: impl Into<String>, y_label: &'a str, lines: Vec<Line<'a>>) -> Self {
        Self {
            title: title.into(),
            y_label,
            lines,
            categories: Vec::new(),
            whole_x: false,
        }
    }

    /// The same panel with an x axis of whole numbers (iteration steps): ticks at whole
    /// numbers only, labelled without decimals.
    pub fn whole_x(mut self) -> Self {
        self.whole_x = true;
        self
    }

    /// The same panel with a categorical x axis: `names[k]` labels x = k.
    pub fn categorical(mut self, names: &[&str]) -> Self {
        self.categories = names.iter().map(|s| s.to_string()).collect();
        self
    }
}

/// Where one panel was drawn, in backend pixels, as the plotting code placed it (for tests).
#[derive(Clone, Debug)]
pub struct PanelGeometry {
    /// The plotting area.
    pub plot: Rect,
    /// The legend box, if the panel has one.
    pub legend: Option<Rect>,
    /// Every drawn mark as a pixel segment (a dot is a zero-length segment).
    pub marks: Vec<((i32, i32), (i32, i32))>,
    /// The category labels of a categorical x axis and the pixel x each is drawn at.
    pub categories: Vec<(String, i32)>,
    /// The envelope columns drawn, per enveloped line.
    pub envelopes: Vec<Vec<Column>>,
    /// The bounding box of every mark with its drawn reach (a dot's radius in x and y), the
    /// box the headroom rule keeps [`rules::HEADROOM_PX`] inside the plot (`None`: no marks).
    pub extent: Option<Rect>,
    /// The axis ranges as drawn, data units: x (left, right) and y (bottom, top), after the
    /// padding of [`rules::padded_range`] and any legend headroom.
    pub axes: ((f64, f64), (f64, f64)),
}
