//! Static figures with plotters, each written as SVG and PNG. The PNG rasteriser needs a font:
//! DejaVu Sans ships in `assets/fonts/` (licence beside it) and is built into the binary, so a
//! machine without fonts draws the same text.

use std::path::{Path, PathBuf};
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::prelude::*;

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

/// One line of a panel.
pub struct Line<'a> {
    /// Legend label.
    pub label: &'a str,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Draw as separate error bars: `points` holds (x, y − e), (x, y + e) pairs, one pair per
    /// bar, each with a dot at its centre.
    pub error_bars: bool,
}

/// One panel of a figure.
pub struct Panel<'a> {
    /// Panel title.
    pub title: String,
    /// y-axis label with unit.
    pub y_label: &'a str,
    /// Lines.
    pub lines: Vec<Line<'a>>,
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

/// Writes panels stacked vertically, sharing an x axis labelled `x_label`, to `path` (SVG) and
/// to the same name with `.png`. Returns both paths.
pub fn write_figure(
    path: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<Vec<PathBuf>> {
    register_font();
    let height = 40 + 260 * panels.len() as u32;
    let svg = path.with_extension("svg");
    let png = path.with_extension("png");
    draw(
        SVGBackend::new(&svg, (900, height)).into_drawing_area(),
        &svg,
        title,
        x_label,
        panels,
    )?;
    draw(
        BitMapBackend::new(&png, (900, height)).into_drawing_area(),
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

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    path: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| anyhow!("{}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let root = root
        .titled(title, ("sans-serif", 20))
        .map_err(|e| err(&e))?;
    let areas = root.split_evenly((panels.len(), 1));
    for (area, p) in areas.iter().zip(panels) {
        let pts = p.lines.iter().flat_map(|l| l.points.iter());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in pts {
            if x.is_finite() && y.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
        if x0 > x1 {
            continue;
        }
        // Panels of error bars only (estimates at categorical x) keep their outer bars off the frame.
        let x_pad = if p.lines.iter().all(|l| l.error_bars) {
            0.5
        } else {
            0.0
        };
        let pad = ((y1 - y0) * 0.05).max(1e-12);
        let mut chart = ChartBuilder::on(area)
            .caption(&p.title, ("sans-serif", 15))
            .margin(8)
            .x_label_area_size(35)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 - x_pad)..(x1 + x_pad).max(x0 + 1e-9),
                (y0 - pad)..(y1 + pad),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(p.y_label)
            .draw()
            .map_err(|e| err(&e))?;
        for l in &p.lines {
            let color = l.color;
            let series = if l.error_bars {
                let bars = l
                    .points
                    .chunks(2)
                    .filter(|c| c.len() == 2)
                    .map(move |c| PathElement::new(vec![c[0], c[1]], color.stroke_width(1)));
                chart.draw_series(bars).map_err(|e| err(&e))?;
                let dots = l.points.chunks(2).filter(|c| c.len() == 2).map(move |c| {
                    Circle::new((c[0].0, 0.5 * (c[0].1 + c[1].1)), 3, color.filled())
                });
                chart.draw_series(dots).map_err(|e| err(&e))?
            } else {
                chart
                    .draw_series(LineSeries::new(
                        l.points.iter().copied(),
                        color.stroke_width(2),
                    ))
                    .map_err(|e| err(&e))?
            };
            if !l.label.is_empty() {
                series.label(l.label).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                });
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))?;
    Ok(())
}
