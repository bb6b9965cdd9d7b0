//! Static figures with plotters, each written as SVG and PNG, drawn by the rules of
//! [`super::rules`]: envelopes for long series, legends in a free corner (or outside),
//! categorical x axes, no "-0.0" ticks. The PNG rasteriser needs a font: DejaVu Sans ships in
//! `assets/fonts/` (licence beside it) and is built into the binary, so a machine without fonts
//! draws the same text.

use std::path::{Path, PathBuf};
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

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

/// Figure width, px.
pub const WIDTH_PX: u32 = 900;
/// Height of one panel, px.
pub const PANEL_PX: u32 = 260;
/// Pixels per envelope column: a long series gets one min/max/mean column per this many.
pub const COLUMN_PX: i32 = 2;

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
    /// Translucent dots, one per point (scatter).
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

fn size(panels: &[Panel]) -> (u32, u32) {
    (WIDTH_PX, 40 + PANEL_PX * panels.len() as u32)
}

/// Writes panels stacked vertically, sharing an x axis labelled `x_label`, to `path` (SVG) and
/// to the same name with `.png`. Returns both paths.
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
        BitMapBackend::new(&png, size(panels)).into_drawing_area(),
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
        SVGBackend::with_string(&mut text, size(panels)).into_drawing_area(),
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
    Dots(Vec<(f64, f64)>),
    Env(Vec<Column>),
}

impl Drawn {
    fn of(l: &Line, x0: f64, x1: f64, columns: usize) -> Self {
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
            Kind::Dots => Drawn::Dots(l.points.iter().filter(finite).copied().collect()),
            Kind::Envelope if l.points.len() > 2 * columns => {
                Drawn::Env(rules::envelope(&l.points, x0, x1, columns))
            }
            Kind::Envelope => Drawn::Path(l.points.clone(), false),
        }
    }

    /// Pixel segments of the marks, through `map` (data → pixel).
    fn marks(&self, map: &dyn Fn((f64, f64)) -> (i32, i32)) -> Vec<((i32, i32), (i32, i32))> {
        // A dot is drawn with a 3 px radius: its mark spans that.
        let dot = |c: (i32, i32)| ((c.0 - 3, c.1), (c.0 + 3, c.1));
        let ok = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        match self {
            Drawn::Path(p, _) => {
                let px: Vec<_> = p.iter().filter(|p| ok(p)).map(|&p| map(p)).collect();
                px.windows(2).map(|w| (w[0], w[1])).collect()
            }
            Drawn::Bars(b) => b
                .iter()
                .filter(|b| b.iter().all(ok))
                .flat_map(|b| [(map(b[0]), map(b[2])), dot(map(b[1]))])
                .collect(),
            Drawn::Dots(d) => d.iter().map(|&p| dot(map(p))).collect(),
            Drawn::Env(cols) => {
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
}

/// Legend box size for the labelled lines, px: plotters draws 12 pt text at about 9.7 px,
/// about 6 px a character.
fn legend_size(lines: &[Line]) -> Option<(i32, i32)> {
    let labels: Vec<&str> = lines
        .iter()
        .map(|l| l.label)
        .filter(|l| !l.is_empty())
        .collect();
    let longest = labels.iter().map(|l| l.chars().count()).max()?;
    Some((40 + 6 * longest as i32, 8 + 17 * labels.len() as i32))
}

/// The pixel rectangle of the plotting area a chart with these settings gets in an area of
/// `dim` px (drawn on a throwaway backend: the label areas are fixed, so the data range does
/// not move it).
fn probe_plot(dim: (u32, u32), title: &str, right_px: i32) -> Result<Rect> {
    let mut s = String::new();
    let area = SVGBackend::with_string(&mut s, dim).into_drawing_area();
    let chart = builder(&area, title, right_px)
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
    title: &'b str,
    right_px: i32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    b.caption(title, ("sans-serif", 15))
        .margin(8)
        .margin_right(8 + right_px)
        .x_label_area_size(35)
        .y_label_area_size(70);
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
    let root = root
        .titled(title, ("sans-serif", 20))
        .map_err(|e| err(&e))?;
    let mut out = Vec::new();
    for (area, p) in root.split_evenly((panels.len(), 1)).iter().zip(panels) {
        if let Some(g) = draw_panel(area, p, x_label).map_err(|e| err(&e))? {
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
    x1 = x1.max(x0 + 1e-9);
    let pad = ((y1 - y0) * 0.05).max(1e-12);
    (y0, y1) = (y0 - pad, y1 + pad);

    // Lay out: the plot rectangle, the envelopes at its pixel columns, the legend from the marks.
    let dim = area.dim_in_pixel();
    let mut plot = probe_plot(dim, &p.title, 0)?;
    let (pw, ph) = (plot.x1 - plot.x0, plot.y1 - plot.y0);
    let columns = (pw / COLUMN_PX).max(1) as usize;
    let drawn: Vec<Drawn> = p
        .lines
        .iter()
        .map(|l| Drawn::of(l, x0, x1, columns))
        .collect();
    let map = |(x, y): (f64, f64)| {
        (
            ((x - x0) / (x1 - x0) * pw as f64).round() as i32,
            ((y1 - y) / (y1 - y0) * ph as f64).round() as i32,
        )
    };
    let marks: Vec<_> = drawn.iter().flat_map(|d| d.marks(&map)).collect();
    let size = legend_size(&p.lines);
    let place = size.map(|(w, h)| rules::place_legend(pw, ph, w, h, &marks));
    let right_px = match (place, size) {
        (Some(LegendPlace::Outside), Some((w, _))) => w + 2 * LEGEND_PAD_PX,
        _ => 0,
    };
    if let Some(LegendPlace::Headroom(_, raise)) = place {
        y1 += raise * (y1 - y0);
    }
    if right_px > 0 {
        plot = probe_plot(dim, &p.title, right_px)?;
    }
    let columns_now = ((plot.x1 - plot.x0) / COLUMN_PX).max(1) as usize;
    let drawn: Vec<Drawn> = if columns_now == columns {
        drawn
    } else {
        p.lines
            .iter()
            .map(|l| Drawn::of(l, x0, x1, columns_now))
            .collect()
    };

    let mut chart = builder(area, &p.title, right_px)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    let (xs, ys) = (x1 - x0, y1 - y0);
    let y_fmt = |v: &f64| rules::tick_label(*v, ys);
    let x_fmt = |v: &f64| rules::tick_label(*v, xs);
    let mut mesh = chart.configure_mesh();
    // Major grid lines only: the light ones read as noise and weigh most of a figure's file.
    mesh.x_desc(x_label)
        .y_desc(p.y_label)
        .max_light_lines(0)
        .y_label_formatter(&y_fmt)
        .x_label_formatter(&x_fmt);
    if categorical {
        // No numeric ticks on a category axis: the names are drawn below.
        mesh.x_labels(0).disable_x_mesh();
    }
    mesh.draw().map_err(|x| e(&x))?;

    let mut envelopes = Vec::new();
    for (l, d) in p.lines.iter().zip(&drawn) {
        let c = l.color;
        match d {
            Drawn::Path(pts, dashed) => {
                let pts = pts
                    .iter()
                    .copied()
                    .filter(|p| p.0.is_finite() && p.1.is_finite());
                if *dashed {
                    chart.draw_series(DashedLineSeries::new(pts, 7, 4, c.stroke_width(2)))
                } else {
                    chart.draw_series(LineSeries::new(pts, c.stroke_width(2)))
                }
                .map_err(|x| e(&x))?;
            }
            Drawn::Bars(bars) => {
                chart
                    .draw_series(
                        bars.iter()
                            .map(|b| PathElement::new(vec![b[0], b[2]], c.stroke_width(2))),
                    )
                    .map_err(|x| e(&x))?;
                chart
                    .draw_series(bars.iter().map(|b| Circle::new(b[1], 3, c.filled())))
                    .map_err(|x| e(&x))?;
            }
            Drawn::Dots(pts) => {
                chart
                    .draw_series(pts.iter().map(|&q| Circle::new(q, 2, c.mix(0.45).filled())))
                    .map_err(|x| e(&x))?;
            }
            Drawn::Env(cols) => {
                let mut ring: Vec<(f64, f64)> = cols.iter().map(|k| (k.x, k.max)).collect();
                ring.extend(cols.iter().rev().map(|k| (k.x, k.min)));
                chart
                    .draw_series(std::iter::once(Polygon::new(ring, c.mix(0.25).filled())))
                    .map_err(|x| e(&x))?;
                chart
                    .draw_series(LineSeries::new(
                        cols.iter().map(|k| (k.x, k.mean)),
                        c.stroke_width(1),
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
    let base = area.get_base_pixel();
    let mut categories = Vec::new();
    for (k, name) in p.categories.iter().enumerate() {
        let (x, _) = to_px((k as f64, y0));
        let style = TextStyle::from(("sans-serif", 13).into_font()).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Top,
            ),
        );
        area.draw(&Text::new(
            name.clone(),
            (x - base.0, plot.y1 + 6 - base.1),
            style,
        ))
        .map_err(|x| e(&x))?;
        categories.push((name.clone(), x));
    }
    let legend = match (place, size) {
        (Some(place), Some((w, h))) => {
            let r = match place {
                LegendPlace::Inside(r) | LegendPlace::Headroom(r, _) => Rect {
                    x0: plot.x0 + r.x0,
                    y0: plot.y0 + r.y0,
                    x1: plot.x0 + r.x1,
                    y1: plot.y0 + r.y1,
                },
                LegendPlace::Outside => Rect {
                    x0: plot.x1 + LEGEND_PAD_PX,
                    y0: plot.y0,
                    x1: plot.x1 + LEGEND_PAD_PX + w,
                    y1: plot.y0 + h,
                },
            };
            draw_legend(area, r, &p.lines)?;
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
    }))
}

/// The legend box at `r` (backend pixels): one row per labelled line with its mark.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: Rect,
    lines: &[Line],
) -> Result<()> {
    let e = |e: &dyn std::fmt::Display| anyhow!("{e}");
    let b = area.get_base_pixel();
    let (x0, y0, x1, y1) = (r.x0 - b.0, r.y0 - b.1, r.x1 - b.0, r.y1 - b.1);
    area.draw(&Rectangle::new(
        [(x0, y0), (x1, y1)],
        WHITE.mix(0.9).filled(),
    ))
    .map_err(|x| e(&x))?;
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1)))
        .map_err(|x| e(&x))?;
    for (k, l) in lines.iter().filter(|l| !l.label.is_empty()).enumerate() {
        let y = y0 + 12 + 17 * k as i32;
        let (a, c) = (x0 + 6, l.color);
        match l.kind {
            Kind::Solid => area.draw(&PathElement::new(
                vec![(a, y), (a + 22, y)],
                c.stroke_width(2),
            )),
            Kind::Dashed => area.draw(&DashedPathElement::new(
                vec![(a, y), (a + 22, y)],
                5,
                3,
                c.stroke_width(2),
            )),
            Kind::ErrorBars | Kind::Interval => area
                .draw(&PathElement::new(
                    vec![(a + 11, y - 6), (a + 11, y + 6)],
                    c.stroke_width(2),
                ))
                .and_then(|_| area.draw(&Circle::new((a + 11, y), 3, c.filled()))),
            Kind::Dots => area.draw(&Circle::new((a + 11, y), 3, c.mix(0.6).filled())),
            Kind::Envelope => area
                .draw(&Rectangle::new(
                    [(a, y - 5), (a + 22, y + 5)],
                    c.mix(0.25).filled(),
                ))
                .and_then(|_| {
                    area.draw(&PathElement::new(
                        vec![(a, y), (a + 22, y)],
                        c.stroke_width(1),
                    ))
                }),
        }
        .map_err(|x| e(&x))?;
        area.draw(&Text::new(
            l.label.to_string(),
            (a + 28, y - 7),
            ("sans-serif", 12),
        ))
        .map_err(|x| e(&x))?;
    }
    Ok(())
}
