//! Static figures with plotters, each written as SVG and PNG, drawn by the rules of
//! [`super::rules`]: print size (text at least 8 pt at one column width, titles wrapped),
//! headroom for every mark, envelopes for long series, legends in a free corner (or above the
//! plot), categorical x axes, no "-0.0" ticks, typeset units. The PNG rasteriser needs a font: DejaVu Sans ships in
//! `assets/fonts/` (licence beside it) and is built into the binary, so a machine without fonts
//! draws the same text.

use std::path::{Path, PathBuf};
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::rules::{self, Column, LEGEND_PAD_PX, LegendPlace, Rect};

/// Line colours in order (matplotlib's tab10), for figures with many lines.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Figure width, px: printed at [`rules::PRINT_WIDTH_IN`] (3.5 in, one journal column) that is
/// 257 px/in.
pub const WIDTH_PX: u32 = 900;
/// Height of one panel, px.
pub const PANEL_PX: u32 = 440;
/// Pixels per envelope column: a long series gets one min/max/mean column per this many.
pub const COLUMN_PX: i32 = 2;
/// Size of tick labels, axis labels, legend and category names at print width, pt.
pub const TEXT_PT: f64 = rules::MIN_TEXT_PT;
/// Size of a panel's title at print width, pt.
pub const CAPTION_PT: f64 = 9.0;
/// Size of the figure's title at print width, pt.
pub const TITLE_PT: f64 = 10.0;
/// Radius of the dot at a bar's estimate, px.
pub const BAR_DOT_PX: i32 = 6;

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
}

impl<'a> Panel<'a> {
    /// A panel with a numeric x axis.
    pub fn new(title: impl Into<String>, y_label: &'a str, lines: Vec<Line<'a>>) -> Self {
        Self {
            title: title.into(),
            y_label,
            lines,
            categories: Vec::new(),
        }
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

/// DejaVu Sans, registered as the `sans-serif` family for both backends.
static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

fn register_font() {
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType font (checked by the figure tests); a failure here
        // would only leave text undrawn in the PNG, never abort.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// The em of text of `pt` points at print width, px: for [`TEXT_PT`], the smallest text,
/// [`rules::min_text_px`] of [`WIDTH_PX`].
fn em_px(pt: f64) -> f64 {
    pt * rules::px_per_pt(WIDTH_PX)
}

/// The font for text of `pt` points at print width. plotters writes an SVG `font-size` of its
/// size / 1.24, so the size is the em × 1.24; the PNG rasteriser draws DejaVu Sans a little
/// larger (its ascent + descent is 1.16 em), never smaller.
fn font(pt: f64) -> FontDesc<'static> {
    ("sans-serif", em_px(pt) * 1.24).into_font()
}

/// Height of one line of text of `pt` points, px.
fn line_px(pt: f64) -> i32 {
    (1.3 * em_px(pt)).ceil() as i32
}

/// Width of `text` in `f`, px (the rasteriser's layout; a rough estimate if it fails).
fn text_w(f: &FontDesc, text: &str) -> i32 {
    f.box_size(text).map_or_else(
        |_| (0.6 * f.get_size() / 1.24 * text.chars().count() as f64) as i32,
        |b| b.0 as i32,
    )
}

/// `text` broken at spaces into lines at most `max_w` px wide in `f` (a single word longer
/// than that keeps its own line).
fn wrap(text: &str, f: &FontDesc, max_w: i32) -> Vec<String> {
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

/// The figure title's lines and the height they take, px.
fn title_block(title: &str) -> (Vec<String>, i32) {
    let lines = wrap(
        &rules::typeset(title),
        &font(TITLE_PT),
        WIDTH_PX as i32 - 24,
    );
    let h = 10 + line_px(TITLE_PT) * lines.len() as i32;
    (lines, h)
}

fn size(title: &str, panels: &[Panel]) -> (u32, u32) {
    let (_, h) = title_block(title);
    (WIDTH_PX, h as u32 + PANEL_PX * panels.len() as u32)
}

/// Writes panels stacked vertically, sharing an x axis labelled `x_label` (under the last
/// panel), to `path` (SVG) and to the same name with `.png`. Returns both paths.
pub fn write_figure(
    path: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<Vec<PathBuf>> {
    let svg = path.with_extension("svg");
    let png = path.with_extension("png");
    let (text, _) = render_svg(title, x_label, panels)?;
    std::fs::write(&svg, text).map_err(|e| anyhow!("{}: {e}", svg.display()))?;
    draw(
        BitMapBackend::new(&png, size(title, panels)).into_drawing_area(),
        &png,
        title,
        x_label,
        panels,
    )?;
    Ok(vec![svg, png])
}

/// [`write_figure`], for callers that only name the SVG.
pub fn write_svg(path: &Path, title: &str, x_label: &str, panels: &[Panel]) -> Result<()> {
    write_figure(path, title, x_label, panels).map(|_| ())
}

/// The SVG text of a figure and where each panel's plot, legend and marks were drawn.
pub fn render_svg(
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<(String, Vec<PanelGeometry>)> {
    let mut text = String::new();
    let geometry = draw(
        SVGBackend::with_string(&mut text, size(title, panels)).into_drawing_area(),
        Path::new(title),
        title,
        x_label,
        panels,
    )?;
    Ok((text, geometry))
}

/// A line as drawn: the shapes it becomes after the rules are applied.
enum Drawn {
    Path(Vec<(f64, f64)>, bool),
    /// Low end, dot, high end.
    Bars(Vec<[(f64, f64); 3]>),
    /// Dots with their radius (px) and opacity.
    Dots(Vec<(f64, f64)>, i32, f64),
    /// Envelope columns; `true`: the mean line narrow (an envelope after the panel's first).
    Env(Vec<Column>, bool),
}

impl Drawn {
    fn of(l: &Line, x0: f64, x1: f64, columns: usize, later_envelope: bool) -> Self {
        let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
        match l.kind {
            Kind::Solid => Drawn::Path(l.points.clone(), false),
            // A long dashed trace (a smooth one by its use) runs through its column means: a
            // dash per sample would outweigh the figure.
            Kind::Dashed if l.points.len() > 2 * columns => Drawn::Path(
                rules::envelope(&l.points, x0, x1, columns)
                    .iter()
                    .map(|c| (c.x, c.mean))
                    .collect(),
                true,
            ),
            Kind::Dashed => Drawn::Path(l.points.clone(), true),
            Kind::ErrorBars => Drawn::Bars(
                l.points
                    .chunks(2)
                    .filter(|c| c.len() == 2)
                    .map(|c| [c[0], (c[0].0, 0.5 * (c[0].1 + c[1].1)), c[1]])
                    .collect(),
            ),
            Kind::Interval => Drawn::Bars(
                l.points
                    .chunks(3)
                    .filter(|c| c.len() == 3)
                    .map(|c| [c[0], c[1], c[2]])
                    .collect(),
            ),
            Kind::Dots => {
                let pts: Vec<_> = l.points.iter().filter(finite).copied().collect();
                let (r, alpha) = rules::dot_style(pts.len());
                Drawn::Dots(pts, r, alpha)
            }
            Kind::Envelope if l.points.len() > 2 * columns => {
                Drawn::Env(rules::envelope(&l.points, x0, x1, columns), later_envelope)
            }
            Kind::Envelope => Drawn::Path(l.points.clone(), false),
        }
    }

    /// How far a mark reaches beyond its centre line, px (a dot's radius, half a stroke).
    fn reach_px(&self) -> i32 {
        match self {
            Drawn::Bars(_) => BAR_DOT_PX,
            Drawn::Dots(_, r, _) => *r,
            _ => 2,
        }
    }

    /// Pixel segments of the marks, through `map` (data → pixel). A dot is a horizontal
    /// segment across its diameter.
    fn marks(&self, map: &dyn Fn((f64, f64)) -> (i32, i32)) -> Vec<((i32, i32), (i32, i32))> {
        let dot = |c: (i32, i32), r: i32| ((c.0 - r, c.1), (c.0 + r, c.1));
        let ok = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        match self {
            Drawn::Path(p, _) => {
                let px: Vec<_> = p.iter().filter(|p| ok(p)).map(|&p| map(p)).collect();
                px.windows(2).map(|w| (w[0], w[1])).collect()
            }
            Drawn::Bars(b) => b
                .iter()
                .filter(|b| b.iter().all(ok))
                .flat_map(|b| [(map(b[0]), map(b[2])), dot(map(b[1]), BAR_DOT_PX)])
                .collect(),
            Drawn::Dots(d, r, _) => d.iter().map(|&p| dot(map(p), *r)).collect(),
            Drawn::Env(cols, _) => {
                let mut m: Vec<_> = cols
                    .iter()
                    .map(|c| (map((c.x, c.min)), map((c.x, c.max))))
                    .collect();
                let mean: Vec<_> = cols.iter().map(|c| map((c.x, c.mean))).collect();
                m.extend(mean.windows(2).map(|w| (w[0], w[1])));
                m
            }
        }
    }

    /// The bounding box of the marks with their reach, through `map`.
    fn extent(&self, map: &dyn Fn((f64, f64)) -> (i32, i32)) -> Option<Rect> {
        let r = self.reach_px();
        let m = self.marks(map);
        let pts = m.iter().flat_map(|&(a, b)| [a, b]);
        let mut e: Option<Rect> = None;
        for (x, y) in pts {
            let (dx, dy) = match self {
                // A dot segment already spans its radius in x.
                Drawn::Bars(_) | Drawn::Dots(..) => (0, r),
                _ => (r, r),
            };
            let q = Rect {
                x0: x - dx,
                y0: y - dy,
                x1: x + dx,
                y1: y + dy,
            };
            e = Some(e.map_or(q, |e| union(e, q)));
        }
        e
    }
}

fn union(a: Rect, b: Rect) -> Rect {
    Rect {
        x0: a.x0.min(b.x0),
        y0: a.y0.min(b.y0),
        x1: a.x1.max(b.x1),
        y1: a.y1.max(b.y1),
    }
}

/// Width of a legend entry's sample mark, px.
const SAMPLE_PX: i32 = 44;

/// The legend of a panel: the labelled lines (with whether each is a later envelope, its mean
/// drawn narrow) and their text widths.
struct Legend<'p, 'a> {
    entries: Vec<(&'p Line<'a>, bool, String, i32)>,
}

impl<'p, 'a> Legend<'p, 'a> {
    fn of(lines: &'p [Line<'a>], later: &[bool]) -> Option<Self> {
        let f = font(TEXT_PT);
        let entries: Vec<_> = lines
            .iter()
            .zip(later)
            .filter(|(l, _)| !l.label.is_empty())
            .map(|(l, &d)| {
                let t = rules::typeset(l.label);
                let w = text_w(&f, &t);
                (l, d, t, w)
            })
            .collect();
        (!entries.is_empty()).then_some(Self { entries })
    }

    /// Size of the boxed legend inside the plot: one entry a row, px.
    fn boxed_size(&self) -> (i32, i32) {
        let longest = self.entries.iter().map(|e| e.3).max().unwrap_or(0);
        (
            2 * LEGEND_PAD_PX + SAMPLE_PX + 10 + longest,
            2 * LEGEND_PAD_PX + line_px(TEXT_PT) * self.entries.len() as i32,
        )
    }

    /// Entry positions (relative to the strip's top-left) of the legend above a plot `w` px
    /// wide, entries side by side, wrapping into rows; and the strip's height.
    fn strip(&self, w: i32) -> (Vec<(i32, i32)>, i32) {
        let row = line_px(TEXT_PT);
        let (mut x, mut y) = (0, 0);
        let mut at = Vec::new();
        for e in &self.entries {
            let ew = SAMPLE_PX + 10 + e.3;
            if x > 0 && x + ew > w {
                (x, y) = (0, y + row);
            }
            at.push((x, y));
            x += ew + 28;
        }
        (at, y + row + 4)
    }
}

/// The space around a panel's plotting area, px.
#[derive(Clone, Copy, Debug)]
struct Layout {
    /// Above the plot: the panel title and a legend strip.
    top: i32,
    /// Right of the plot (room for the last x tick label).
    right: i32,
    /// Below the plot: x tick labels or category names, and the x label on the last panel.
    x_area: i32,
    /// Left of the plot: y tick labels and the y label.
    y_area: i32,
}

/// The pixel rectangle of the plotting area a chart with this layout gets in an area of `dim`
/// px (drawn on a throwaway backend: the label areas are fixed, so the data range does not
/// move it).
fn probe_plot(dim: (u32, u32), layout: &Layout) -> Result<Rect> {
    let mut s = String::new();
    let area = SVGBackend::with_string(&mut s, dim).into_drawing_area();
    let chart = builder(&area, layout)
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(|e| anyhow!("{e}"))?;
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    Ok(Rect {
        x0: xr.start,
        y0: yr.start,
        x1: xr.end,
        y1: yr.end,
    })
}

fn builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    layout: &Layout,
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    b.margin(6)
        .margin_top(layout.top)
        .margin_right(layout.right)
        .x_label_area_size(layout.x_area)
        .y_label_area_size(layout.y_area);
    b
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    path: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<Vec<PanelGeometry>> {
    register_font();
    let err = |e: &dyn std::fmt::Display| anyhow!("{}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (lines, title_h) = title_block(title);
    let style = TextStyle::from(font(TITLE_PT)).pos(Pos::new(HPos::Center, VPos::Top));
    for (k, l) in lines.iter().enumerate() {
        root.draw(&Text::new(
            l.clone(),
            (WIDTH_PX as i32 / 2, 8 + line_px(TITLE_PT) * k as i32),
            style.clone(),
        ))
        .map_err(|e| err(&e))?;
    }
    let (_, body) = root.split_vertically(title_h);
    let mut out = Vec::new();
    let n = panels.len();
    for (k, (area, p)) in body.split_evenly((n, 1)).iter().zip(panels).enumerate() {
        if let Some(g) = draw_panel(area, p, x_label, k + 1 == n).map_err(|e| err(&e))? {
            out.push(g);
        }
    }
    root.present().map_err(|e| err(&e))?;
    Ok(out)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
    x_label: &str,
    last: bool,
) -> Result<Option<PanelGeometry>> {
    let e = |e: &dyn std::fmt::Display| anyhow!("{e}");
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in p.lines.iter().flat_map(|l| l.points.iter()) {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return Ok(None);
    }
    let categorical = !p.categories.is_empty();
    if categorical {
        // Category k sits at x = k, half a slot from each side.
        x0 = x0.min(0.0) - 0.5;
        x1 = x1.max(p.categories.len() as f64 - 1.0) + 0.5;
    } else if p
        .lines
        .iter()
        .all(|l| matches!(l.kind, Kind::ErrorBars | Kind::Interval))
    {
        // Bars at discrete x keep their outer bars off the frame.
        x0 -= 0.5;
        x1 += 0.5;
    }
    // A numeric x axis of dots (with or without curves) is widened in pixels below.
    let pad_x = !categorical && p.lines.iter().any(|l| l.kind == Kind::Dots);
    x1 = x1.max(x0 + 1e-9);
    // Envelopes after a panel's first draw their mean line narrow over the first's wide one
    // (draw order: where they coincide both show).
    let mut seen = false;
    let later: Vec<bool> = p
        .lines
        .iter()
        .map(|l| {
            let is_env = l.kind == Kind::Envelope;
            let d = is_env && seen;
            seen |= is_env;
            d
        })
        .collect();

    // Lay out: text sizes fix the label areas; the plot rectangle; the ranges padded to keep
    // every mark HEADROOM_PX inside the frame; the envelopes at its pixel columns; the legend
    // from the marks.
    let dim = area.dim_in_pixel();
    let tf = font(TEXT_PT);
    let caption_h = |lines: usize| 8 + line_px(CAPTION_PT) * lines as i32;
    let ys_guess = y1 - y0;
    let y_ticks_w = [y0 - 0.25 * ys_guess, y1 + 0.25 * ys_guess, 0.5 * (y0 + y1)]
        .iter()
        .map(|&v| text_w(&tf, &rules::tick_label(v, 1.2 * ys_guess.max(1e-12))))
        .max()
        .unwrap_or(0);
    let x_ticks_w = if categorical {
        0
    } else {
        [x0, x1]
            .iter()
            .map(|&v| text_w(&tf, &rules::tick_label(v, x1 - x0)))
            .max()
            .unwrap_or(0)
    };
    let y_area = y_ticks_w + 16 + line_px(TEXT_PT) + 6;
    // The title is centred over the plot: it wraps within twice the distance from the plot's
    // centre to the nearer side of the panel.
    let centre = (y_area + 6 + dim.0 as i32 - 10.max(x_ticks_w / 2 + 4)) / 2;
    let caption = wrap(
        &rules::typeset(&p.title),
        &font(CAPTION_PT),
        2 * centre.min(dim.0 as i32 - centre) - 16,
    );
    let mut layout = Layout {
        top: caption_h(caption.len()) + 6,
        right: 10.max(x_ticks_w / 2 + 4),
        x_area: 14 + line_px(TEXT_PT) + if last { line_px(TEXT_PT) + 4 } else { 0 },
        y_area,
    };
    let mut plot = probe_plot(dim, &layout)?;
    let (pw, mut ph) = (plot.x1 - plot.x0, plot.y1 - plot.y0);
    let columns = (pw / COLUMN_PX).max(1) as usize;
    let drawn: Vec<Drawn> = p
        .lines
        .iter()
        .zip(&later)
        .map(|(l, &d)| Drawn::of(l, x0, x1, columns, d))
        .collect();
    let inset = (rules::HEADROOM_PX + drawn.iter().map(Drawn::reach_px).max().unwrap_or(0)) as f64;
    let (data_y0, data_y1) = (y0, y1);
    (y0, y1) = rules::padded_range(data_y0, data_y1, inset, ph as f64);
    if pad_x {
        // Clusters at a few x values (chamber temperatures) sit well off the side frames.
        let inset_x = inset.max(rules::SCATTER_X_PAD_FRAC * pw as f64);
        (x0, x1) = rules::padded_range(x0, x1, inset_x, pw as f64);
    }
    let drawn: Vec<Drawn> = if pad_x {
        p.lines
            .iter()
            .zip(&later)
            .map(|(l, &d)| Drawn::of(l, x0, x1, columns, d))
            .collect()
    } else {
        drawn
    };
    let legend = Legend::of(&p.lines, &later);
    let place = {
        let map = |(x, y): (f64, f64)| {
            (
                ((x - x0) / (x1 - x0) * pw as f64).round() as i32,
                ((y1 - y) / (y1 - y0) * ph as f64).round() as i32,
            )
        };
        let marks: Vec<_> = drawn.iter().flat_map(|d| d.marks(&map)).collect();
        legend.as_ref().map(|l| {
            let (w, h) = l.boxed_size();
            rules::place_legend(pw, ph, w, h, &marks)
        })
    };
    let strip = match (&place, &legend) {
        (Some(LegendPlace::Outside), Some(l)) => Some(l.strip(pw)),
        _ => None,
    };
    if let Some((_, h)) = &strip {
        // The legend goes above the plot: the plot is lowered, its y range padded anew.
        layout.top += h;
        plot = probe_plot(dim, &layout)?;
        ph = plot.y1 - plot.y0;
        (y0, y1) = rules::padded_range(data_y0, data_y1, inset, ph as f64);
    }
    if let Some(LegendPlace::Headroom(_, raise)) = place {
        y1 += raise * (y1 - y0);
    }

    // The panel title, centred over the plot (the probe's pixels are relative to the panel).
    let base = area.get_base_pixel();
    let cap_style = TextStyle::from(font(CAPTION_PT)).pos(Pos::new(HPos::Center, VPos::Top));
    for (k, l) in caption.iter().enumerate() {
        area.draw(&Text::new(
            l.clone(),
            ((plot.x0 + plot.x1) / 2, 6 + line_px(CAPTION_PT) * k as i32),
            cap_style.clone(),
        ))
        .map_err(|x| e(&x))?;
    }

    let mut chart = builder(area, &layout)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    let (xs, ys) = (x1 - x0, y1 - y0);
    let y_fmt = |v: &f64| rules::tick_label(*v, ys);
    let x_fmt = |v: &f64| rules::tick_label(*v, xs);
    let y_desc = rules::typeset(p.y_label);
    let x_desc = if last {
        rules::typeset(x_label)
    } else {
        String::new()
    };
    let mut mesh = chart.configure_mesh();
    // Major grid lines only: the light ones read as noise and weigh most of a figure's file.
    // Tick counts leave a label's size free between labels.
    mesh.y_desc(y_desc)
        .label_style(tf.clone())
        .axis_desc_style(tf.clone())
        .max_light_lines(0)
        .y_labels(((ph / line_px(TEXT_PT)).max(4)) as usize)
        .x_labels(((pw / (x_ticks_w + 3 * em_px(TEXT_PT) as i32).max(1)).clamp(2, 10)) as usize)
        .y_label_formatter(&y_fmt)
        .x_label_formatter(&x_fmt);
    if !x_desc.is_empty() {
        mesh.x_desc(x_desc);
    }
    if categorical {
        // No numeric ticks on a category axis: the names are drawn below.
        mesh.x_labels(0).disable_x_mesh();
    }
    mesh.draw().map_err(|x| e(&x))?;

    let mut envelopes = Vec::new();
    for (l, d) in p.lines.iter().zip(&drawn) {
        let c = l.color;
        // A solid or dashed line through `pts` (a macro: the chart is borrowed per draw).
        macro_rules! path {
            ($pts:expr, $dashed:expr) => {{
                let pts = $pts
                    .iter()
                    .copied()
                    .filter(|p: &(f64, f64)| p.0.is_finite() && p.1.is_finite());
                if $dashed {
                    chart
                        .draw_series(DashedLineSeries::new(pts, 12, 7, c.stroke_width(2)))
                        .map(|_| ())
                } else {
                    chart
                        .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                        .map(|_| ())
                }
            }};
        }
        match d {
            Drawn::Path(pts, dashed) => path!(pts, *dashed).map_err(|x| e(&x))?,
            Drawn::Bars(bars) => {
                chart
                    .draw_series(
                        bars.iter()
                            .map(|b| PathElement::new(vec![b[0], b[2]], c.stroke_width(3))),
                    )
                    .map_err(|x| e(&x))?;
                chart
                    .draw_series(
                        bars.iter()
                            .map(|b| Circle::new(b[1], BAR_DOT_PX, c.filled())),
                    )
                    .map_err(|x| e(&x))?;
            }
            Drawn::Dots(pts, r, alpha) => {
                chart
                    .draw_series(
                        pts.iter()
                            .map(|&q| Circle::new(q, *r, c.mix(*alpha).filled())),
                    )
                    .map_err(|x| e(&x))?;
            }
            Drawn::Env(cols, narrow) => {
                let mut ring: Vec<(f64, f64)> = cols.iter().map(|k| (k.x, k.max)).collect();
                ring.extend(cols.iter().rev().map(|k| (k.x, k.min)));
                chart
                    .draw_series(std::iter::once(Polygon::new(ring, c.mix(0.25).filled())))
                    .map_err(|x| e(&x))?;
                // The first envelope's mean 3 px wide, later ones 1 px on top: where they
                // coincide the later line runs inside the first.
                chart
                    .draw_series(LineSeries::new(
                        cols.iter().map(|k| (k.x, k.mean)),
                        c.stroke_width(if *narrow { 1 } else { 3 }),
                    ))
                    .map_err(|x| e(&x))?;
                envelopes.push(cols.clone());
            }
        }
    }

    // Geometry as the chart maps it.
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let plot = Rect {
        x0: xr.start,
        y0: yr.start,
        x1: xr.end,
        y1: yr.end,
    };
    let to_px = |q: (f64, f64)| chart.backend_coord(&q);
    let marks: Vec<_> = drawn.iter().flat_map(|d| d.marks(&to_px)).collect();
    let extent = drawn.iter().filter_map(|d| d.extent(&to_px)).reduce(union);
    let mut categories = Vec::new();
    for (k, name) in p.categories.iter().enumerate() {
        let (x, _) = to_px((k as f64, y0));
        let style = TextStyle::from(tf.clone()).pos(Pos::new(HPos::Center, VPos::Top));
        area.draw(&Text::new(
            rules::typeset(name),
            (x - base.0, plot.y1 + 8 - base.1),
            style,
        ))
        .map_err(|x| e(&x))?;
        categories.push((name.clone(), x));
    }
    let legend = match (place, legend) {
        (Some(place), Some(lg)) => {
            let (w, h) = lg.boxed_size();
            let (r, at) = match place {
                LegendPlace::Inside(r) | LegendPlace::Headroom(r, _) => {
                    let r = Rect {
                        x0: plot.x0 + r.x0,
                        y0: plot.y0 + r.y0,
                        x1: plot.x0 + r.x1,
                        y1: plot.y0 + r.y1,
                    };
                    let at: Vec<(i32, i32)> = (0..lg.entries.len() as i32)
                        .map(|k| (LEGEND_PAD_PX, LEGEND_PAD_PX + line_px(TEXT_PT) * k))
                        .collect();
                    debug_assert_eq!((r.x1 - r.x0, r.y1 - r.y0), (w, h));
                    (r, at)
                }
                LegendPlace::Outside => {
                    let (at, sh) = lg.strip(plot.x1 - plot.x0);
                    let r = Rect {
                        x0: plot.x0,
                        y0: plot.y0 - sh - 2,
                        x1: plot.x1,
                        y1: plot.y0 - 2,
                    };
                    (r, at)
                }
            };
            draw_legend(area, r, &lg, &at, !matches!(place, LegendPlace::Outside))?;
            Some(r)
        }
        _ => None,
    };
    Ok(Some(PanelGeometry {
        plot,
        legend,
        marks,
        categories,
        envelopes,
        extent,
        axes: ((x0, x1), (y0, y1)),
    }))
}

/// The legend at `r` (backend pixels): each labelled line's mark and label at its place in
/// `at` (relative to `r`'s top-left), in a white box when `boxed`.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: Rect,
    lg: &Legend,
    at: &[(i32, i32)],
    boxed: bool,
) -> Result<()> {
    let e = |e: &dyn std::fmt::Display| anyhow!("{e}");
    let b = area.get_base_pixel();
    let (x0, y0, x1, y1) = (r.x0 - b.0, r.y0 - b.1, r.x1 - b.0, r.y1 - b.1);
    if boxed {
        area.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            WHITE.mix(0.9).filled(),
        ))
        .map_err(|x| e(&x))?;
        area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1)))
            .map_err(|x| e(&x))?;
    }
    let row = line_px(TEXT_PT);
    let style = TextStyle::from(font(TEXT_PT)).pos(Pos::new(HPos::Left, VPos::Center));
    for ((l, later, label, _), &(dx, dy)) in lg.entries.iter().zip(at) {
        let (a, y, c) = (x0 + dx, y0 + dy + row / 2, l.color);
        let s = SAMPLE_PX;
        match l.kind {
            Kind::Solid => area.draw(&PathElement::new(
                vec![(a, y), (a + s, y)],
                c.stroke_width(2),
            )),
            Kind::Dashed => area.draw(&DashedPathElement::new(
                vec![(a, y), (a + s, y)],
                12,
                7,
                c.stroke_width(2),
            )),
            Kind::ErrorBars | Kind::Interval => area
                .draw(&PathElement::new(
                    vec![(a + s / 2, y - 12), (a + s / 2, y + 12)],
                    c.stroke_width(3),
                ))
                .and_then(|_| area.draw(&Circle::new((a + s / 2, y), BAR_DOT_PX, c.filled()))),
            Kind::Dots => {
                let (r, alpha) = rules::dot_style(l.points.len());
                area.draw(&Circle::new(
                    (a + s / 2, y),
                    r,
                    c.mix(alpha.max(0.6)).filled(),
                ))
            }
            Kind::Envelope => area
                .draw(&Rectangle::new(
                    [(a, y - 9), (a + s, y + 9)],
                    c.mix(0.25).filled(),
                ))
                .and_then(|_| {
                    area.draw(&PathElement::new(
                        vec![(a, y), (a + s, y)],
                        c.stroke_width(if *later { 1 } else { 3 }),
                    ))
                }),
        }
        .map_err(|x| e(&x))?;
        area.draw(&Text::new(label.clone(), (a + s + 10, y), style.clone()))
            .map_err(|x| e(&x))?;
    }
    Ok(())
}
