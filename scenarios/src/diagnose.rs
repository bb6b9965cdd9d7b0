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

use crate::file::{BUILTIN, OutputSpec};
use crate::plots::{Line, Panel, write_svg};
use crate::sinks::CsvSink;

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
        let mut plant = crate::runner::new_plant(cfg, label)?;
        for _ in 0..*samples {
            let s = plant.step();
            crate::runner::Sink::sample(&mut sink, &s, plant.truth())?;
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

/// Writes the comparison figures of `a` into `dir`: residual vs temperature by position (with
/// the fitted effects when `a` has a diagnosis), bias by position (before and after), Allan
/// deviation of the residual, navigation on measured vs modelled increments.
pub fn write_report(dir: &Path, a: &Analysis) -> Result<Vec<String>> {
    let (pred, before, after) = (a.predictions(), &a.comparison, a.after());
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let ws = &a.replay.windows;
    let mut files = Vec::new();
    // Residual vs temperature, coloured by Z-up / Z-down, with the fitted effect.
    let mut panels = Vec::new();
    for c in 0..6 {
        let (u, scale) = unit(c);
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
                .flat_map(|i| [(temp(i), val(i)), (temp(i), val(i))])
                .collect()
        };
        let rate = |i: usize| a.data[c].y[i] / ws[i].duration_s / scale;
        let mut lines = vec![
            Line {
                label: "Z-up",
                points: dot(&|i| !ws[i].moving && ws[i].up_z > 0.5, &rate),
                color: BLUE,
                error_bars: true,
            },
            Line {
                label: "Z-down",
                points: dot(&|i| !ws[i].moving && ws[i].up_z < -0.5, &rate),
                color: RED,
                error_bars: true,
            },
        ];
        if let Some(p) = pred {
            lines.push(Line {
                label: "fitted effects",
                points: dot(&|i| !ws[i].moving, &|i| p[c][i] / ws[i].duration_s / scale),
                color: GREEN,
                error_bars: true,
            });
        }
        panels.push(Panel {
            title: format!("{}: residual (measured - model) per window", CHANNELS[c]),
            y_label: u,
            lines,
        });
    }
    let f = dir.join("residual_vs_temperature.svg");
    write_svg(
        &f,
        "Residual vs temperature, coloured by table position",
        "temperature [deg C]",
        &panels,
    )?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Bias by position with the noise floor as error bars, before and after.
    let positions = ["z-up", "z-down", "tilted", "moving"];
    let mut panels = Vec::new();
    for c in 0..6 {
        let (u, _) = unit(c);
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
        let mut lines = vec![Line {
            label: "model as given (95 %)",
            points: bars(before, -0.1),
            color: GREY,
            error_bars: true,
        }];
        if let Some(r) = after {
            lines.push(Line {
                label: "with fitted effects (95 %)",
                points: bars(r, 0.1),
                color: GREEN,
                error_bars: true,
            });
        }
        panels.push(Panel {
            title: format!(
                "{}: mean residual at 0 z-up, 1 z-down, 2 tilted, 3 moving",
                CHANNELS[c]
            ),
            y_label: u,
            lines,
        });
    }
    let f = dir.join("bias_by_position.svg");
    write_svg(&f, "Residual bias per table position", "position", &panels)?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Allan deviation of the residual (log10 axes).
    let mut panels = Vec::new();
    for c in 0..6 {
        let (u, _) = unit(c);
        let curve = |r: &CompareReport| {
            r.allan.get(CHANNELS[c]).map_or_else(Vec::new, |v| {
                v.iter()
                    .filter(|(_, a)| *a > 0.0)
                    .map(|(t, a)| (t.log10(), a.log10()))
                    .collect()
            })
        };
        let mut lines = vec![Line {
            label: "model as given",
            points: curve(before),
            color: GREY,
            error_bars: false,
        }];
        if let Some(r) = after {
            lines.push(Line {
                label: "with fitted effects",
                points: curve(r),
                color: GREEN,
                error_bars: false,
            });
        }
        panels.push(Panel {
            title: format!(
                "{}: log10 Allan deviation of the residual [{u}]",
                CHANNELS[c]
            ),
            y_label: "log10 ADEV",
            lines,
        });
    }
    let f = dir.join("allan_residual.svg");
    write_svg(
        &f,
        "Allan deviation of the residual",
        "log10 tau [s]",
        &panels,
    )?;
    files.push(f.display().to_string());
    files.push(f.with_extension("png").display().to_string());

    // Navigation on measured vs modelled increments (the first segments).
    let mut panels = Vec::new();
    for t in a.replay.nav.iter().filter(|t| !t.t_s.is_empty()).take(4) {
        let run = a.run_names.get(t.run as usize).cloned().unwrap_or_default();
        panels.push(Panel {
            title: format!("{run}: horizontal position error of static navigation"),
            y_label: "m",
            lines: vec![
                Line {
                    label: "on the measured increments",
                    points: t
                        .t_s
                        .iter()
                        .copied()
                        .zip(t.measured_m.iter().copied())
                        .collect(),
                    color: GREY,
                    error_bars: false,
                },
                Line {
                    label: "on the model's increments",
                    points: t
                        .t_s
                        .iter()
                        .copied()
                        .zip(t.model_m.iter().copied())
                        .collect(),
                    color: BLUE,
                    error_bars: false,
                },
            ],
        });
    }
    if !panels.is_empty() {
        let f = dir.join("navigation_error.svg");
        write_svg(
            &f,
            "Navigation: measured vs model",
            "time since segment start [s]",
            &panels,
        )?;
        files.push(f.display().to_string());
        files.push(f.with_extension("png").display().to_string());
    }
    Ok(files)
}
