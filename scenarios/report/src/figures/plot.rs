//! Static figures with plotters, each written as SVG and PNG, drawn by the rules of
//! [`super::rules`]: print size (text at least 8 pt at one column width, titles wrapped),
//! headroom for every mark, envelopes for long series, legends in a free corner (or above the
//! plot), categorical x axes, no "-0.0" ticks, typeset units. The PNG rasteriser needs a font: DejaVu Sans ships in
//! `scenarios/report/fonts/` (licence beside it) and is built into the binary, so a machine without fonts
//! draws the same text.
//!
//! One concept a file: `panel` (what a caller describes), `palette` and `sizes`, the
//! text at print size (`text`), the marks a line becomes (`marks`), the legend (`legend`), the
//! space around a plot (`layout`) and one panel's chart (`chart`); this file draws a figure
//! (title and stacked panels) and writes it.

mod chart;
mod layout;
mod legend;
mod marks;
mod palette;
mod panel;
mod sizes;
mod text;

use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub use palette::PALETTE;
pub use panel::{Kind, Line, Panel, PanelGeometry};
pub use sizes::{BAR_DOT_PX, CAPTION_PT, COLUMN_PX, PANEL_PX, TEXT_PT, TITLE_PT, WIDTH_PX};

use super::rules;
use chart::draw_panel;
use text::{font, line_px, register_font, wrap};

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

/// The figure's size, px: the full width, the title block and one panel height per panel.
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

/// Draws the title and the panels stacked on `root`; errors name `path`.
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
