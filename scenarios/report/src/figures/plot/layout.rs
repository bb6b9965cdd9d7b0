//! The space around a panel's plotting area and the chart builder that reserves it.

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::figures::rules::Rect;

/// The space around a panel's plotting area, px.
#[derive(Clone, Copy, Debug)]
pub(super) struct Layout {
    /// Above the plot: the panel title and a legend strip.
    pub(super) top: i32,
    /// Right of the plot (room for the last x tick label).
    pub(super) right: i32,
    /// Below the plot: x tick labels or category names, and the x label on the last panel.
    pub(super) x_area: i32,
    /// Left of the plot: y tick labels and the y label.
    pub(super) y_area: i32,
}

/// The pixel rectangle of the plotting area a chart with this layout gets in an area of `dim`
/// px (drawn on a throwaway backend: the label areas are fixed, so the data range does not
/// move it).
pub(super) fn probe_plot(dim: (u32, u32), layout: &Layout) -> Result<Rect> {
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

/// A chart builder on `area` that reserves the margins and label areas of `layout`.
pub(super) fn builder<'a, 'b, DB: DrawingBackend>(
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
