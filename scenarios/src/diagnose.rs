//! The scenario side of model vs measurements ([`rins_mvm`]): simulated measurement logs
//! (datasets with hidden effects, `rins measure`), model file text (built-in scenarios
//! included), and the static report figures of `rins compare` / `rins diagnose`.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use plotters::style::RGBColor;
use rins_mvm::report::unit_of as unit;
use rins_mvm::{Analysis, CHANNELS, CompareReport};
use rins_plant::PlantConfig;

use crate::sinks::CsvSink;
use rins_report::figures::plot::{Kind, Line, Panel, PanelGeometry, write_svg};
use rins_scenario::file::{BUILTIN, OutputSpec};

/// Simulates a measurement log: each `(run label, plant, samples)` is run and appended to one
/// CSV in the measurement format (IMU-rate rows, gimbal angles, node temperatures, `run` label).
pub fn write_measurements(path: &Path, runs: &[(String, PlantConfig, u64)]) -> Result<()> {
    let f =
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut out = std::io::BufWriter::with_capacity(1 << 20, f);
    let opts = OutputSpec {
        csv: true,
        decimation: 1,
        truth: false,
        effects: false,
    };
    for (i, (label, cfg, samples)) in runs.iter().enumerate() {
        let mut sink = CsvSink::for_run(&mut out, opts, cfg, Some(label), i == 0)?;
        let mut plant = rins_scenario::new_plant(cfg, label)?;
        for _ in 0..*samples {
            let s = plant.step();
            crate::runner::Sink::sample(&mut sink, &s, &plant.truth())?;
        }
        crate::runner::Sink::finish(&mut sink)?;
    }
    out.flush()?;
    Ok(())
}

/// Text of a model file (or a built-in scenario).
pub fn model_text(path: &Path) -> Result<String> {
    let s = path.to_string_lossy();
    let name = s.strip_prefix("builtin:").unwrap_or(&s);
    if let Some((_, t)) = BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .filter(|_| s.starts_with("builtin:") || !path.exists())
    {
        return Ok(t.to_string());
    }
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED: RGBColor = RGBColor(214, 39, 40);
const GREEN: RGBColor = RGBColor(44, 160, 44);
const GREY: RGBColor = RGBColor(127, 127, 127);
const DARK_BLUE: RGBColor = RGBColor(10, 50, 110);
const DARK_RED: RGBColor = RGBColor(120, 10, 10);

/// The mean y of `points` per `bin`-wide x bin, at the bin's mean x, in x order: a fitted
/// value drawn as a curve instead of one mark per window.
fn binned(points: Vec<(f64, f64)>, bin: f64) -> Vec<(f64, f64)> {
    let mut bins: std::collections::BTreeMap<i64, (f64, f64, f64)> = Default::default();
    for (x, y) in points
        .into_iter()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
    {
        let b = bins.entry((x / bin).floor() as i64).or_default();
        *b = (b.0 + x, b.1 + y, b.2 + 1.0);
    }
    bins.values().map(|(x, y, n)| (x / n, y / n)).collect()
}

/// Writes the comparison figures of `a` into `dir`: residual vs temperature by position (with
/// the fitted effects when `a` has a diagnosis), bias by position (before and after), Allan
/// deviation of the residual, navigation on measured vs modelled increments.
pub fn write_report(dir: &Path, a: &Analysis) -> Result<Vec<String>> {
    let (pred, before, after) = (a.predictions(), &a.comparison, a.after());
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let ws = &a.replay.windows;
    let mut files = Vec::new();
    let res_labels: Vec<String> = (0..6)
        .map(|c| format!("residual ({})", unit(c).0))
        .collect();
    // Residual vs temperature, coloured by Z-up / Z-down, with the fitted effect.
    let mut panels = Vec::new();
    for c in 0..6 {
        let (u, scale) = (res_labels[c].as_str(), unit(c).1);
        let temp = |i: usize| {
            if c < 3 {
                ws[i].gyro_temp_c[c]
            } else {
                ws[i].accel_temp_c
            }
        };
        let dot = |pick: &dyn Fn(usize) -> bool, val: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
            (0..ws.len())
                .filter(|&i| pick(i))
                .map(|i| (temp(i), val(i)))
                .collect()
        };
        let rate = |i: usize| a.data[c].y[i] / ws[i].duration_s / scale;
        let up = |i: usize| !ws[i].moving && ws[i].up_z > 0.5;
        let down = |i: usize| !ws[i].moving && ws[i].up_z < -0.5;
        let mut lines = vec![
            Line::new("Z-up residual", dot(&up, &rate), BLUE, Kind::Dots),
            Line::new("Z-down residual", dot(&down, &rate), RED, Kind::Dots),
        ];
        if let Some(p) = pred {
            // The fit as a dashed curve per position (its mean per 0.5 K bin), so the dots
            // stay visible under it.
            let fit = |i: usize| p[c][i] / ws[i].duration_s / scale;
            lines.push(Line::new(
                "fitted effects, Z-up",
                binned(dot(&up, &fit), 0.5),
                DARK_BLUE,
                Kind::Dashed,
            ));
            lines.push(Line::new(
                "fitted effects, Z-down",
                binned(dot(&down, &fit), 0.5),
                DARK_RED,
                Kind::Dashed,
            ));
        }
        panels.push(Panel::new(
            format!("{}: residual (measured - model) per window", CHANNELS[c]),
            u,
            lines,
        ));
    }
    let f = dir.join("residual_vs_temperature.svg");
    write_svg(
        &f,
        "Residual vs temperature, coloured by table position",
        "sensor temperature (deg C)",
        &panels,
    )?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Bias by position with the noise floor as error bars, before and after.
    let panels = bias_panels(a, &res_labels);
    let f = dir.join("bias_by_position.svg");
    write_svg(&f, BIAS_TITLE, BIAS_X, &panels)?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Allan deviation of the residual (log10 axes).
    let adev_labels: Vec<String> = (0..6)
        .map(|c| format!("log10 ADEV ({})", unit(c).0))
        .collect();
    let mut panels = Vec::new();
    for c in 0..6 {
        let curve = |r: &CompareReport| {
            r.allan.get(CHANNELS[c]).map_or_else(Vec::new, |v| {
                v.iter()
                    .filter(|(_, a)| *a > 0.0)
                    .map(|(t, a)| (t.log10(), a.log10()))
                    .collect()
            })
        };
        let mut lines = vec![Line::new(
            "model as given",
            curve(before),
            GREY,
            Kind::Solid,
        )];
        if let Some(r) = after {
            lines.push(Line::new(
                "with fitted effects",
                curve(r),
                GREEN,
                Kind::Dashed,
            ));
        }
        panels.push(Panel::new(
            format!("{}: Allan deviation of the residual", CHANNELS[c]),
            adev_labels[c].as_str(),
            lines,
        ));
    }
    let f = dir.join("allan_residual.svg");
    write_svg(
        &f,
        "Allan deviation of the residual",
        "log10 tau (tau in s)",
        &panels,
    )?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Navigation on measured vs modelled increments (the first segments).
    let mut panels = Vec::new();
    for t in a.replay.nav.iter().filter(|t| !t.t_s.is_empty()).take(4) {
        let run = a.run_names.get(t.run as usize).cloned().unwrap_or_default();
        let series = |v: &[f64]| t.t_s.iter().copied().zip(v.iter().copied()).collect();
        panels.push(Panel::new(
            format!("{run}: horizontal position error of static navigation"),
            "horizontal error (m)",
            vec![
                Line::new(
                    "on the measured increments",
                    series(&t.measured_m),
                    GREY,
                    Kind::Envelope,
                ),
                Line::new(
                    "on the model's increments",
                    series(&t.model_m),
                    BLUE,
                    Kind::Dashed,
                ),
            ],
        ));
    }
    if !panels.is_empty() {
        let f = dir.join("navigation_error.svg");
        write_svg(
            &f,
            "Navigation: measured vs model",
            "time since segment start (s)",
            &panels,
        )?;
        files.push(f.display().to_string());
        files.push(f.with_extension("png").display().to_string());
    }
    Ok(files)
}

const BIAS_TITLE: &str = "Residual bias per table position";
const BIAS_X: &str = "table position";

/// The table positions of `bias_by_position`, in axis order.
pub const POSITIONS: [&str; 4] = ["z-up", "z-down", "tilted", "moving"];

/// The panels of `bias_by_position`: per channel the mean residual per table position (a
/// categorical axis), the noise floor as 95 % bars, before and after the fitted effects side by
/// side. `labels[c]` is channel c's y label.
fn bias_panels<'a>(a: &Analysis, labels: &'a [String]) -> Vec<Panel<'a>> {
    let positions = POSITIONS;
    let (before, after) = (&a.comparison, a.after());
    let mut panels = Vec::new();
    for c in 0..6 {
        let u = labels[c].as_str();
        let bars = |r: &CompareReport, shift: f64| -> Vec<(f64, f64)> {
            positions
                .iter()
                .enumerate()
                .filter_map(|(k, p)| {
                    let cells: Vec<_> = r
                        .cells
                        .iter()
                        .filter(|x| x.channel == CHANNELS[c] && x.position == *p)
                        .collect();
                    if cells.is_empty() {
                        return None;
                    }
                    // Combine cells by inverse-variance weighting.
                    let w: f64 = cells.iter().map(|x| 1.0 / x.noise_floor.powi(2)).sum();
                    let m = cells
                        .iter()
                        .map(|x| x.residual / x.noise_floor.powi(2))
                        .sum::<f64>()
                        / w;
                    let e = 1.96 / w.sqrt();
                    Some([(k as f64 + shift, m - e), (k as f64 + shift, m + e)])
                })
                .flatten()
                .collect()
        };
        // Side by side: before at k - 0.15, after at k + 0.15.
        let mut lines = vec![Line::new(
            "model as given (95 %)",
            bars(before, -0.15),
            GREY,
            Kind::ErrorBars,
        )];
        if let Some(r) = after {
            lines.push(Line::new(
                "with fitted effects (95 %)",
                bars(r, 0.15),
                GREEN,
                Kind::ErrorBars,
            ));
        }
        panels.push(
            Panel::new(
                format!("{}: mean residual per table position", CHANNELS[c]),
                u,
                lines,
            )
            .categorical(&positions),
        );
    }
    panels
}

/// `bias_by_position` as SVG text with where each panel was drawn (the figure
/// [`write_report`] writes).
pub fn render_bias_by_position(a: &Analysis) -> Result<(String, Vec<PanelGeometry>)> {
    let labels: Vec<String> = (0..6)
        .map(|c| format!("residual ({})", unit(c).0))
        .collect();
    rins_report::figures::plot::render_svg(BIAS_TITLE, BIAS_X, &bias_panels(a, &labels))
}
