//! Marks: each line as it is drawn after the rules are applied (paths, bars, dots, envelope
//! columns), with the pixels it covers for the headroom and legend rules.

use super::panel::{Kind, Line};
use super::sizes::BAR_DOT_PX;
use crate::figures::rules::{self, Column, Rect};

/// A line as drawn: the shapes it becomes after the rules are applied.
pub(super) enum Drawn {
    Path(Vec<(f64, f64)>, bool),
    /// Low end, dot, high end.
    Bars(Vec<[(f64, f64); 3]>),
    /// Dots with their radius (px) and opacity.
    Dots(Vec<(f64, f64)>, i32, f64),
    /// Envelope columns; `true`: the mean line narrow (an envelope after the panel's first).
    Env(Vec<Column>, bool),
}

impl Drawn {
    pub(super) fn of(l: &Line, x0: f64, x1: f64, columns: usize, later_envelope: bool) -> Self {
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
    pub(super) fn reach_px(&self) -> i32 {
        match self {
            Drawn::Bars(_) => BAR_DOT_PX,
            Drawn::Dots(_, r, _) => *r,
            _ => 2,
        }
    }

    /// Pixel segments of the marks, through `map` (data → pixel). A dot is a horizontal
    /// segment across its diameter.
    pub(super) fn marks(
        &self,
        map: &dyn Fn((f64, f64)) -> (i32, i32),
    ) -> Vec<((i32, i32), (i32, i32))> {
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
    pub(super) fn extent(&self, map: &dyn Fn((f64, f64)) -> (i32, i32)) -> Option<Rect> {
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

pub(super) fn union(a: Rect, b: Rect) -> Rect {
    Rect {
        x0: a.x0.min(b.x0),
        y0: a.y0.min(b.y0),
        x1: a.x1.max(b.x1),
        y1: a.y1.max(b.y1),
    }
}
