//! Figures of the calibration results: β at Z-up and Z-down and δβ per axis of one calibration
//! (`rins calibrate`, Section 3.2) and δβ against temperature with its cubic fit over the
//! campaign (`rins campaign`, Figure 8).

use std::path::Path;

use anyhow::Result;
use plotters::style::RGBColor;
use rins_navigation::calibration::Calibration;
use rins_navigation::campaign::Campaign;

use super::plot::{Kind, Line, Panel, write_svg};

/// `calibration_beta.svg`/`.png` in `out`: β at Z-up (Eq. 17), Z-down (Eq. 19) and δβ per
/// axis, each ±1 SE.
pub fn write_calibration_figure(r: &Calibration, out: &Path) -> Result<()> {
    let bar = |x: f64, v: f64, e: f64| vec![(x, v - e), (x, v + e)];
    let panels: Vec<Panel> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, a)| {
            Panel::new(
                format!("{a}-axis gyro: estimated bias +- 1 SE"),
                "bias (deg/h)",
                vec![
                    Line::new(
                        "Z-up +- 1 SE",
                        bar(0.0, r.up.beta_dph[i], r.up.se_dph[i]),
                        RGBColor(31, 119, 180),
                        Kind::ErrorBars,
                    ),
                    Line::new(
                        "Z-down +- 1 SE",
                        bar(1.0, r.down.beta_dph[i], r.down.se_dph[i]),
                        RGBColor(214, 39, 40),
                        Kind::ErrorBars,
                    ),
                    Line::new(
                        "delta-beta +- 1 SE",
                        bar(2.0, r.delta_beta_dph[i], r.delta_beta_se_dph[i]),
                        RGBColor(44, 160, 44),
                        Kind::ErrorBars,
                    ),
                ],
            )
            .categorical(&[
                "beta Z-up (Eq. 17)",
                "beta Z-down (Eq. 19)",
                "delta-beta = down - up",
            ])
        })
        .collect();
    write_svg(
        &out.join("calibration_beta.svg"),
        "System-level indirect calibration: estimated gyro bias",
        "estimate",
        &panels,
    )
}

/// `fig8_dbeta_vs_temperature.svg`/`.png` in `out`: each run's δβ ±1 SE against the gyro block
/// temperature at Z-down, with the cubic fit and its 95 % band (Figure 8 counterpart).
pub fn write_campaign_figure(c: &Campaign, out: &Path) -> Result<()> {
    let panels: Vec<Panel> = ["X", "Y", "Z"]
        .iter()
        .enumerate()
        .map(|(i, axis)| {
            let pts: Vec<(f64, f64)> = c
                .runs
                .iter()
                .map(|r| (r.block_temp_c[i], r.calibration.delta_beta_dph[i]))
                .collect();
            let (lo, hi) = pts
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
            let curve = |k: f64| -> Vec<(f64, f64)> {
                (0..=100)
                    .map(|j| {
                        let t = lo + (hi - lo) * j as f64 / 100.0;
                        let (v, sd) = c.fits[i].eval(t - c.ref_temp_c);
                        (t, v + k * 1.96 * sd)
                    })
                    .collect()
            };
            let mut bars = Vec::new();
            for r in &c.runs {
                let (x, y, e) = (
                    r.block_temp_c[i],
                    r.calibration.delta_beta_dph[i],
                    r.calibration.delta_beta_se_dph[i],
                );
                bars.push((x, y - e));
                bars.push((x, y + e));
            }
            Panel::new(
                format!("{axis}-axis gyro: delta-beta = beta(Z-down) - beta(Z-up)"),
                "delta-beta (deg/h)",
                vec![
                    Line::new(
                        "estimate +- 1 SE",
                        bars,
                        RGBColor(90, 90, 90),
                        Kind::ErrorBars,
                    ),
                    Line::new("cubic fit", curve(0.0), RGBColor(30, 90, 200), Kind::Solid),
                    Line::new(
                        "95 % band",
                        curve(1.0),
                        RGBColor(140, 170, 240),
                        Kind::Dashed,
                    ),
                    Line::new("", curve(-1.0), RGBColor(140, 170, 240), Kind::Dashed),
                ],
            )
        })
        .collect();
    write_svg(
        &out.join("fig8_dbeta_vs_temperature.svg"),
        "Figure 8 counterpart: identified position-dependent gyro bias",
        "gyro block temperature at Z-down (deg C)",
        &panels,
    )
}
