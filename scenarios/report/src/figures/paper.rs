//! Figures of the paired paper studies (`rins paper table4|table5`): the Figure 2 (attitude
//! error) and Figure 3 (position error, tRMS of Eq. 20) counterparts, uncompensated against
//! compensated, for the first seed and the noise-free pair. Table 5's Figures 9-10 are the same
//! drawings of its runs.

use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;
use rins_navigation::NavRecord;
use rins_verification::paper::{Series, Table4Report};

use super::plot::{Kind, Line, PALETTE, Panel, PanelGeometry, render_svg, write_svg};

/// Uncompensated case.
const UNC: RGBColor = RGBColor(200, 40, 40);
/// Compensated case.
const COMP: RGBColor = RGBColor(30, 90, 200);

/// One figure of a paired study: file stem, title, x label and panels.
pub struct PairedFigure<'a> {
    /// File stem (`fig2_attitude_error`, `fig3_position_error_noise_free`, …).
    pub stem: String,
    /// Title, with the paper's figure number.
    pub title: String,
    /// x-axis label.
    pub x_label: &'static str,
    /// Panels.
    pub panels: Vec<Panel<'a>>,
}

impl PairedFigure<'_> {
    /// The SVG text and where each panel was drawn.
    pub fn render(&self) -> Result<(String, Vec<PanelGeometry>)> {
        render_svg(&self.title, self.x_label, &self.panels)
    }
}

/// Colours of the east, north and up differences (tab10 green, purple, brown: neither case's).
const AXES: [RGBColor; 3] = [PALETTE[2], PALETTE[4], PALETTE[5]];

fn pts(recs: &[NavRecord], f: &dyn Fn(&NavRecord) -> f64) -> Vec<(f64, f64)> {
    recs.iter().map(|x| (x.t_s / 3600.0, f(x))).collect()
}

/// `f`(uncompensated) − `f`(compensated) at the records of the two cases taken at the same
/// time (the pair runs on the same seed and record rate, so they pair one to one; a record
/// without its partner is left out).
pub fn difference(
    unc: &[NavRecord],
    comp: &[NavRecord],
    f: &dyn Fn(&NavRecord) -> f64,
) -> Vec<(f64, f64)> {
    unc.iter()
        .zip(comp)
        .filter(|(u, c)| (u.t_s - c.t_s).abs() <= 1e-6 * u.t_s.abs().max(1.0))
        .map(|(u, c)| (u.t_s / 3600.0, f(u) - f(c)))
        .collect()
}

/// The four figures of a paired study: attitude and position error for the first seed and the
/// noise-free pair. `figures` names the paper's figures they correspond to (Table 4:
/// `["Figure 2", "Figure 3"]`, Table 5: `["Figure 9", "Figure 10"]`); `kind` is how each case's
/// week-long trace is drawn ([`Kind::Envelope`] in the outputs: a per-pixel-column min/max band
/// with its mean, so a 16-position cycle does not become a solid comb and neither case hides
/// the other).
pub fn paired_figures<'a>(
    r: &'a Table4Report,
    figures: [&str; 2],
    kind: Kind,
) -> Vec<PairedFigure<'a>> {
    let mut out = Vec::new();
    for (series, tag, what) in [
        (&r.first_seed, "", "first seed"),
        (&r.noise_free_series, "_noise_free", "noise-free"),
    ] {
        let series: &Series = series;
        let pair = |f: &dyn Fn(&NavRecord) -> f64| {
            vec![
                Line::new("uncompensated", pts(&series.uncompensated, f), UNC, kind),
                Line::new("compensated", pts(&series.compensated, f), COMP, kind),
            ]
        };
        let axes = ["East", "North", "Up"];
        let mut att: Vec<Panel> = axes
            .iter()
            .enumerate()
            .map(|(k, n)| {
                Panel::new(
                    format!("{n}-axis attitude error"),
                    "attitude error (deg)",
                    pair(&|x| x.att_err_rad[k].to_degrees()),
                )
            })
            .collect();
        // Where δβ hardly moves an axis (east and north) the two cases' traces coincide and
        // one hides the other at print size whatever the draw order: the difference panel
        // shows what the compensation changes on each axis, on its own scale.
        att.push(Panel::new(
            "Difference uncompensated - compensated: δβ's own effect",
            "difference (deg)",
            axes.iter()
                .enumerate()
                .map(|(k, n)| {
                    Line::new(
                        *n,
                        difference(&series.uncompensated, &series.compensated, &|x| {
                            x.att_err_rad[k].to_degrees()
                        }),
                        AXES[k],
                        kind,
                    )
                })
                .collect(),
        ));
        out.push(PairedFigure {
            stem: format!("fig2_attitude_error{tag}"),
            title: format!("{} counterpart: attitude error ({what})", figures[0]),
            x_label: "time (h)",
            panels: att,
        });
        let nm = rins_navigation::errors::nmi;
        let mut horizontal = pair(&|x| nm(x.horizontal_m));
        // tRMS is smooth: dashed lines in darker case colours over the envelopes.
        horizontal.push(Line::new(
            "tRMS uncompensated",
            pts(&series.uncompensated, &|x| nm(x.trms_m)),
            RGBColor(150, 20, 20),
            Kind::Dashed,
        ));
        horizontal.push(Line::new(
            "tRMS compensated",
            pts(&series.compensated, &|x| nm(x.trms_m)),
            RGBColor(20, 50, 140),
            Kind::Dashed,
        ));
        out.push(PairedFigure {
            stem: format!("fig3_position_error{tag}"),
            title: format!("{} counterpart: position error ({what})", figures[1]),
            x_label: "time (h)",
            panels: vec![
                Panel::new("Latitude error", "error (nmi)", pair(&|x| nm(x.north_m))),
                Panel::new("Longitude error", "error (nmi)", pair(&|x| nm(x.east_m))),
                Panel::new(
                    "Horizontal error and tRMS (Eq. 20)",
                    "error (nmi)",
                    horizontal,
                ),
            ],
        });
    }
    out
}

/// Writes `fig2_attitude_error{,_noise_free}.svg` and `fig3_position_error{,_noise_free}.svg`
/// (with PNGs) into `out`, the traces as envelopes ([`paired_figures`]).
pub fn write_table4_figures(r: &Table4Report, out: &Path, figures: [&str; 2]) -> Result<()> {
    for f in paired_figures(r, figures, Kind::Envelope) {
        write_svg(
            &out.join(format!("{}.svg", f.stem)),
            &f.title,
            f.x_label,
            &f.panels,
        )?;
    }
    Ok(())
}
