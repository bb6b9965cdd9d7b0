//! Glue between measurement files, model files and the diagnosis in `rins_verify::diagnosis`:
//! measured columns to a [`History`], simulated measurement logs (datasets with hidden
//! effects), model files written back with fitted effects, and the static report figures.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use plotters::style::RGBColor;
use rins_plant::PlantConfig;
use rins_verify::diagnosis::history::{Attitude, History};
use rins_verify::diagnosis::replay::CHANNELS;
use rins_verify::diagnosis::{Analysis, CompareReport};

use crate::file::{BUILTIN, OutputSpec};
use crate::measurement::Measurement;
use crate::plots::{Line, Panel, write_svg};
use crate::sinks::CsvSink;

/// The measured rows in SI, with the temperatures mapped to the model's inputs: per-gyro
/// columns `temp_gyro_{x,y,z}_c` when present (else the first temperature column on every
/// axis), the gradient as gyro − `temp_housing_c` when a housing temperature is present, and
/// `temp_accel_c` (else the first gyro column) for the accelerometers. The columns are moved
/// out of the measurement, not copied.
pub fn to_history(mut m: Measurement, source: &str) -> Result<History> {
    let n = m.rows;
    fn take(m: &mut Measurement, c: &str, source: &str) -> Result<Vec<f64>> {
        m.columns
            .remove(c)
            .with_context(|| format!("{source}: column {c} missing"))
    }
    let has_gimbal = m.columns.contains_key("outer_deg") && m.columns.contains_key("inner_deg");
    let per_axis = ["temp_gyro_x_c", "temp_gyro_y_c", "temp_gyro_z_c"]
        .iter()
        .all(|c| m.columns.contains_key(*c));
    let first_temp = m
        .temperature_columns()
        .first()
        .map(|s| s.to_string())
        .context("no temperature column")?;
    let common_temp = if per_axis {
        None
    } else {
        m.columns.get(&first_temp).cloned()
    };
    let housing = if per_axis {
        m.columns.remove("temp_housing_c")
    } else {
        None
    };
    let accel = m.columns.remove("temp_accel_c");
    let segs = std::mem::take(&mut m.segments);
    let mut take = |c: &str| take(&mut m, c, source);
    let t_s = take("t_s")?;
    let dtheta_rad = [
        take("dtheta_x_rad")?,
        take("dtheta_y_rad")?,
        take("dtheta_z_rad")?,
    ];
    let dv_mps = [take("dv_x_mps")?, take("dv_y_mps")?, take("dv_z_mps")?];
    let attitude = if has_gimbal {
        let mut o = take("outer_deg")?;
        let mut i = take("inner_deg")?;
        o.iter_mut()
            .chain(i.iter_mut())
            .for_each(|d| *d = d.to_radians());
        Attitude::Gimbal {
            outer_rad: o,
            inner_rad: i,
        }
    } else {
        let q: Vec<Vec<f64>> = ["q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"]
            .iter()
            .map(|c| take(c))
            .collect::<Result<_>>()?;
        Attitude::Quaternion(
            (0..n)
                .map(|k| [q[0][k], q[1][k], q[2][k], q[3][k]])
                .collect(),
        )
    };
    let gyro_temp_c: [Vec<f64>; 3] = match common_temp {
        None => [
            take("temp_gyro_x_c")?,
            take("temp_gyro_y_c")?,
            take("temp_gyro_z_c")?,
        ],
        Some(t) => [t.clone(), t.clone(), t],
    };
    let housing_temp_c = housing;
    let accel_temp_c = accel.unwrap_or_else(|| gyro_temp_c[0].clone());
    let mut run_names: Vec<String> = Vec::new();
    let mut run = vec![0u32; n];
    let mut segments = Vec::new();
    for (r, _, a, b) in &segs {
        let idx = run_names.iter().position(|x| x == r).unwrap_or_else(|| {
            run_names.push(r.clone());
            run_names.len() - 1
        });
        run[*a..*b].iter_mut().for_each(|x| *x = idx as u32);
        segments.push(*a..*b);
    }
    Ok(History {
        t_s,
        dtheta_rad,
        dv_mps,
        attitude,
        gyro_temp_c,
        housing_temp_c,
        accel_temp_c,
        run,
        run_names,
        segments,
        source: source.into(),
    })
}

/// The model with the site the data give (lat/lon/height columns), if any; returns a note.
pub fn with_data_site(model: &PlantConfig, m: &Measurement) -> (PlantConfig, Option<String>) {
    let mut cfg = model.clone();
    let get = |c: &str| m.col(c).and_then(|v| v.first().copied());
    let mut note = None;
    if let (Some(lat), Some(lon)) = (get("lat_deg"), get("lon_deg")) {
        cfg.site.lat_deg = lat;
        cfg.site.lon_deg = lon;
        if let Some(h) = get("height_m") {
            cfg.site.height_m = h;
        }
        if cfg.site != model.site {
            note = Some(format!("site from the data: {lat} deg, {lon} deg"));
        }
    }
    (cfg, note)
}

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

/// The model file `original` with its `[sensor]` replaced by `cfg`'s full sensor specification.
pub fn model_with_sensor(original: &str, cfg: &PlantConfig, note: &str) -> Result<String> {
    let mut table: toml::Table = toml::from_str(original).context("model file is not TOML")?;
    let mut sensor =
        toml::Table::try_from(&cfg.sensor).context("serialising the sensor specification")?;
    sensor.insert("preset".into(), toml::Value::String("ideal".into()));
    table.insert("sensor".into(), toml::Value::Table(sensor));
    Ok(format!(
        "# {note}\n# Written by rins diagnose --apply; [sensor] is the complete specification.\n{}",
        toml::to_string_pretty(&table)?
    ))
}

const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED: RGBColor = RGBColor(214, 39, 40);
const GREEN: RGBColor = RGBColor(44, 160, 44);
const GREY: RGBColor = RGBColor(127, 127, 127);

fn unit(c: usize) -> (&'static str, f64) {
    if c < 3 {
        ("deg/h", rins_plant::units::DPH)
    } else {
        ("ug", rins_plant::units::UG)
    }
}

/// Writes the comparison figures into `dir`: residual vs temperature by position, bias by
/// position (before and after `pred`), Allan deviation of the residual.
pub fn write_report(
    dir: &Path,
    a: &Analysis,
    pred: Option<&[Vec<f64>]>,
    before: &CompareReport,
    after: Option<&CompareReport>,
) -> Result<Vec<String>> {
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
