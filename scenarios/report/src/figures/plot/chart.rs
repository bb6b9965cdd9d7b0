//! One panel's chart: the data ranges with headroom, the layout, the legend's place, the axes
//! and ticks, every line's marks, the category names, and the geometry as drawn.

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::layout::{Layout, builder, probe_plot};
use super::legend::{Legend, draw_legend};
use super::marks::{Drawn, union};
use super::panel::{Kind, Panel, PanelGeometry};
use super::sizes::{BAR_DOT_PX, CAPTION_PT, COLUMN_PX, TEXT_PT};
use super::text::{em_px, font, line_px, text_w, wrap};
use crate::figures::rules::{self, LEGEND_PAD_PX, LegendPlace, Rect};

/// Draws panel `p` into `area` (with the x label `x_label` when it is the `last` panel) and
/// returns where it drew; `None` when the panel has no finite point to draw.
pub(super) fn draw_panel<DB: DrawingBackend>(
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
    let x_fmt = |v: &f64| {
        if p.whole_x {
            rules::whole_tick_label(*v)
        } else {
            rules::tick_label(*v, xs)
        }
    };
    let x_labels = ((pw / (x_ticks_w + 3 * em_px(TEXT_PT) as i32).max(1)).clamp(2, 10)) as usize;
    // At most one tick per whole number in range: plotters' nicest step is then 1, 2, 5, …
    let x_labels = if p.whole_x {
        x_labels.min(((x1.floor() - x0.ceil()) as usize + 1).max(1))
    } else {
        x_labels
    };
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
        .x_labels(x_labels)
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
