//! The legend of a panel: its entries, its size boxed inside the plot or as a strip above it,
//! and its drawing (each line's sample mark and label).

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::panel::{Kind, Line};
use super::sizes::{BAR_DOT_PX, TEXT_PT};
use super::text::{font, line_px, text_w};
use crate::figures::rules::{self, LEGEND_PAD_PX, Rect};

/// Width of a legend entry's sample mark, px.
const SAMPLE_PX: i32 = 44;

/// The legend of a panel: the labelled lines (with whether each is a later envelope, its mean
/// drawn narrow) and their text widths.
pub(super) struct Legend<'p, 'a> {
    pub(super) entries: Vec<(&'p Line<'a>, bool, String, i32)>,
}

impl<'p, 'a> Legend<'p, 'a> {
    pub(super) fn of(lines: &'p [Line<'a>], later: &[bool]) -> Option<Self> {
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
    pub(super) fn boxed_size(&self) -> (i32, i32) {
        let longest = self.entries.iter().map(|e| e.3).max().unwrap_or(0);
        (
            2 * LEGEND_PAD_PX + SAMPLE_PX + 10 + longest,
            2 * LEGEND_PAD_PX + line_px(TEXT_PT) * self.entries.len() as i32,
        )
    }

    /// Entry positions (relative to the strip's top-left) of the legend above a plot `w` px
    /// wide, entries side by side, wrapping into rows; and the strip's height.
    pub(super) fn strip(&self, w: i32) -> (Vec<(i32, i32)>, i32) {
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

/// The legend at `r` (backend pixels): each labelled line's mark and label at its place in
/// `at` (relative to `r`'s top-left), in a white box when `boxed`.
pub(super) fn draw_legend<DB: DrawingBackend>(
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
