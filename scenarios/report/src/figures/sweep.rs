//! Figures of `rins sweep`: one per output, the median over the seeds against the first swept
//! key with its 5–95 % band as a bar at each point, one line per value of the other swept keys
//! (if any); the uncompensated and the δβ-compensated navigator in two panels sharing the x
//! axis. A first key whose values are names or switches gets a categorical x axis.

use std::path::{Path, PathBuf};

use anyhow::Result;

use super::plot::{Kind, Line, PALETTE, Panel, PanelGeometry, render_svg, write_figure};
use rins_sweep::{NAVIGATORS, SweepReport, value_text};

/// Where the lines of a point's group sit apart in x, as a fraction of the x span (a dodge,
/// so that bars at the same x stay apart).
const DODGE: f64 = 0.012;

/// One sweep figure: file stem, title, x label and its two panels' content.
pub struct SweepFigure {
    /// File stem (`sweep_lon_nm`).
    pub stem: String,
    /// Title.
    pub title: String,
    /// x-axis label (the first swept key and its unit).
    pub x_label: String,
    /// y-axis label (the output and its unit).
    pub y_label: String,
    /// Category names when the first key is not numeric (empty: numeric x).
    pub categories: Vec<String>,
    /// Per navigator ([`NAVIGATORS`]), per line: its legend label and its (x, p05, median,
    /// p95) points in x order.
    pub lines: Vec<Vec<(String, Vec<[f64; 4]>)>>,
}

impl SweepFigure {
    /// The panels to draw.
    pub fn panels(&self) -> Vec<Panel<'_>> {
        NAVIGATORS
            .iter()
            .zip(&self.lines)
            .map(|(nav, lines)| {
                let mut drawn = Vec::new();
                for (j, (label, pts)) in lines.iter().enumerate() {
                    let color = PALETTE[j % PALETTE.len()];
                    drawn.push(Line::new(
                        label,
                        pts.iter().map(|p| (p[0], p[2])).collect(),
                        color,
                        Kind::Solid,
                    ));
                    drawn.push(Line::new(
                        "",
                        pts.iter()
                            .flat_map(|p| [(p[0], p[1]), (p[0], p[2]), (p[0], p[3])])
                            .collect(),
                        color,
                        Kind::Interval,
                    ));
                }
                let panel = Panel::new(format!("{nav} navigator"), self.y_label.as_str(), drawn);
                if self.categories.is_empty() {
                    panel
                } else {
                    let names: Vec<&str> = self.categories.iter().map(String::as_str).collect();
                    panel.categorical(&names)
                }
            })
            .collect()
    }

    /// The SVG text and where each panel was drawn.
    pub fn render(&self) -> Result<(String, Vec<PanelGeometry>)> {
        render_svg(&self.title, &self.x_label, &self.panels())
    }
}

/// The figures of `r`, one per output.
pub fn sweep_figures(r: &SweepReport) -> Vec<SweepFigure> {
    let Some(first) = r.parameters.first() else {
        return Vec::new();
    };
    let numeric = first.values.iter().all(serde_json::Value::is_number);
    // Categorical x: each distinct name at its first position in the key's list.
    let mut categories: Vec<String> = Vec::new();
    if !numeric {
        for v in &first.values {
            let t = value_text(v);
            if !categories.contains(&t) {
                categories.push(t);
            }
        }
    }
    let x_of = |v: &serde_json::Value| {
        if numeric {
            v.as_f64().unwrap_or(f64::NAN)
        } else {
            categories
                .iter()
                .position(|c| *c == value_text(v))
                .unwrap_or(0) as f64
        }
    };
    // The lines: points grouped by the values of the other keys, in order of appearance.
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (k, p) in r.points.iter().enumerate() {
        let label = r.parameters[1..]
            .iter()
            .zip(&p.values[1..])
            .map(|(par, v)| {
                let unit = if par.unit == "1" {
                    ""
                } else {
                    par.unit.as_str()
                };
                format!("{} = {} {unit}", par.key, value_text(v))
                    .trim_end()
                    .to_string()
            })
            .collect::<Vec<_>>()
            .join(", ");
        match groups.iter_mut().find(|(l, _)| *l == label) {
            Some(g) => g.1.push(k),
            None => groups.push((label, vec![k])),
        }
    }
    let xs: Vec<f64> = r.points.iter().map(|p| x_of(&p.values[0])).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let n = groups.len() as f64;
    let seeds = r.seeds.len();
    r.outputs
        .iter()
        .map(|o| {
            let lines = (0..NAVIGATORS.len())
                .map(|nav| {
                    groups
                        .iter()
                        .enumerate()
                        .map(|(j, (label, ks))| {
                            let dx = DODGE * span * (j as f64 - 0.5 * (n - 1.0));
                            let mut pts: Vec<[f64; 4]> = ks
                                .iter()
                                .map(|&k| {
                                    let b = r.points[k].band(nav, &o.name);
                                    [xs[k] + dx, b.p05, b.median, b.p95]
                                })
                                .collect();
                            // A grid's line runs along x; a zipped sweep keeps the file's order.
                            if r.combine == "grid" {
                                pts.sort_by(|a, b| a[0].total_cmp(&b[0]));
                            }
                            let label = if label.is_empty() {
                                "median, bars 5-95 %".to_string()
                            } else {
                                label.clone()
                            };
                            (label, pts)
                        })
                        .collect()
                })
                .collect();
            SweepFigure {
                stem: format!("sweep_{}", o.name),
                title: format!(
                    "{}: {} against {}; median and 5-95 % of {seeds} seeds, {} days",
                    r.name,
                    o.name,
                    first.key,
                    crate::html::format_sig(r.days, 3)
                ),
                x_label: first.heading(),
                y_label: format!("{} ({})", o.name, o.unit),
                categories: categories.clone(),
                lines,
            }
        })
        .collect()
}

/// Writes `sweep_<output>.svg` and `.png` for every output into `out`; returns the SVG paths.
pub fn write_sweep_figures(r: &SweepReport, out: &Path) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for f in sweep_figures(r) {
        let path = out.join(format!("{}.svg", f.stem));
        write_figure(&path, &f.title, &f.x_label, &f.panels())?;
        written.push(path);
    }
    Ok(written)
}
