//! Figures of the verification reports (`rins verify analytic|ins --figures DIR`): φ(t) through
//! one 16-position cycle (Eq. 8, Eq. 11) and each check against its limit.

use std::path::Path;

use anyhow::{Context, Result};
use plotters::style::RGBColor;
use rins_verification::report::Check;

use super::plot::{Kind, Line, PALETTE, Panel, write_svg};

/// φ(t) through one 16-position cycle for a constant bias (Eq. 8) and for δβ (Eq. 11), with the
/// paper's −8·T_s·δβ_z marked: `eq8_eq11_cycle.svg`/`.png` in `dir`.
pub fn write_cycle_figure(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let (bias, dbeta, dwell) = ([0.005; 3], [0.005; 3], 180.0);
    let tr = rins_verification::analytic::cycle_trace(bias, dbeta, dwell, 0.5);
    let arcsec = |r: f64| r.to_degrees() * 3600.0;
    let t_end = tr.last().map_or(0.0, |p| p.t_s) / 60.0;
    let expected = arcsec(-8.0 * dwell * dbeta[2] * rins_plant::units::DPH);
    let panels: Vec<Panel> = ["East", "North", "Up"]
        .iter()
        .enumerate()
        .map(|(i, axis)| {
            let mut lines = vec![
                Line::new(
                    "constant bias 0.005 deg/h on each axis (Eq. 8)",
                    tr.iter()
                        .map(|p| (p.t_s / 60.0, arcsec(p.bias_rad[i])))
                        .collect(),
                    RGBColor(31, 119, 180),
                    Kind::Solid,
                ),
                Line::new(
                    "delta-beta 0.005 deg/h on each axis (Eq. 11)",
                    tr.iter()
                        .map(|p| (p.t_s / 60.0, arcsec(p.delta_beta_rad[i])))
                        .collect(),
                    RGBColor(214, 39, 40),
                    Kind::Dashed,
                ),
            ];
            if i == 2 {
                lines.push(Line::new(
                    "-8 Ts delta-beta_z (stationary phases, Eq. 11)",
                    vec![(0.0, expected), (t_end, expected)],
                    RGBColor(120, 120, 120),
                    Kind::Dashed,
                ));
            }
            Panel::new(
                format!(
                    "{axis}: attitude error accumulated through one cycle (T_s = 180 s, constant-rate moves)"
                ),
                "attitude error (arcsec)",
                lines,
            )
        })
        .collect();
    write_svg(
        &dir.join("eq8_eq11_cycle.svg"),
        "One 16-position cycle: a constant bias cancels, delta-beta leaves -8 Ts delta-beta_z",
        "time in the cycle (min)",
        &panels,
    )
}

/// Each check's value against its limit (log10 of value / limit; ≤ 0 passes), at `path` (SVG,
/// and PNG beside it).
pub fn write_checks_figure(path: &Path, title: &str, checks: &[Check]) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    // An exact zero (e.g. an integral that cancels to the bit) is drawn at 1e-16 of the limit.
    let margin = |c: &Check| {
        (c.value.abs().max(1e-16 * c.limit.abs()) / c.limit.abs().max(f64::MIN_POSITIVE)).log10()
    };
    // Check k sits at category "k+1"; the legend names it.
    let labels: Vec<String> = checks
        .iter()
        .enumerate()
        .map(|(k, c)| format!("{}: {}", k + 1, c.name))
        .collect();
    let numbers: Vec<String> = (1..=checks.len()).map(|k| k.to_string()).collect();
    let mut lines: Vec<Line> = checks
        .iter()
        .zip(&labels)
        .enumerate()
        .map(|(k, (c, label))| {
            Line::new(
                label,
                vec![(k as f64, margin(c)), (k as f64, margin(c))],
                PALETTE[k % PALETTE.len()],
                Kind::ErrorBars,
            )
        })
        .collect();
    lines.push(Line::new(
        "limit",
        vec![(-0.5, 0.0), (checks.len() as f64 - 0.5, 0.0)],
        RGBColor(0, 0, 0),
        Kind::Dashed,
    ));
    let names: Vec<&str> = numbers.iter().map(String::as_str).collect();
    let panel = Panel::new(
        format!(
            "{} checks, {} passed (below the line)",
            checks.len(),
            checks.iter().filter(|c| c.pass).count()
        ),
        "log10(value / limit)",
        lines,
    )
    .categorical(&names);
    write_svg(path, title, "check", &[panel])
}
