//! The report page of each result command: which tables (from the result's JSON), which paper
//! values beside them, which figures with what caption. The commands call these with their
//! result and output folder.

use std::path::{Path, PathBuf};

use anyhow::Result;
use rins_verify::paper::{published, published_table5};
use serde::Serialize;
use serde_json::Value;

use super::{Cell, Doc, Report};

fn json<T: Serialize>(v: &T) -> Result<Value> {
    Ok(serde_json::to_value(v)?)
}

/// Adds `dir/<stem>.svg` for each (stem, caption) whose file exists.
fn figures(r: &mut Report, dir: &Path, list: &[(&str, &str)]) -> Result<()> {
    for (stem, caption) in list {
        let f = dir.join(format!("{stem}.svg"));
        if f.exists() {
            r.figure(&f, caption)?;
        }
    }
    Ok(())
}

const PAIRED_COLUMNS: [&str; 9] = [
    "quantity",
    "paper uncompensated",
    "paper compensated",
    "ours uncompensated median",
    "5 %",
    "95 %",
    "ours compensated median",
    "5 %",
    "95 %",
];

/// The tables and figures of a paired study (Table 4 or, with `table5`, Table 5) into `r`;
/// `dir` holds its figures.
pub fn paired_sections<T: Serialize>(
    r: &mut Report,
    report: &T,
    table5: bool,
    dir: &Path,
) -> Result<()> {
    let v = json(report)?;
    let (src, name) = if table5 {
        ("table5", "Table 5")
    } else {
        ("table4", "Table 4")
    };
    let d = Doc { src, json: &v };
    let band = |q: &str, paper: Option<[f64; 2]>| {
        let mut row = vec![Cell::Text(q.to_string())];
        for k in 0..2 {
            row.push(paper.map_or(Cell::Text("-".into()), |p| Cell::Paper(p[k], 5)));
        }
        row
    };
    let mut rows = Vec::new();
    let list: Vec<(&str, &str, Option<[f64; 2]>)> = if table5 {
        use published_table5 as p;
        vec![
            ("latitude error (nmi)", "lat_nm", Some(p::LAT_NM)),
            ("longitude error (nmi)", "lon_nm", Some(p::LON_NM)),
            (
                "horizontal error (nmi)",
                "horizontal_nm",
                Some(p::HORIZONTAL_NM),
            ),
            ("tRMS (nmi)", "trms_nm", Some(p::TRMS_NM)),
        ]
    } else {
        vec![
            (
                "|latitude error| (nmi)",
                "abs_lat_nm",
                Some(published::LAT_NM),
            ),
            (
                "|longitude error| (nmi)",
                "abs_lon_nm",
                Some(published::LON_NM),
            ),
            ("latitude error (nmi)", "lat_nm", None),
            ("longitude error (nmi)", "lon_nm", None),
            ("horizontal error (nmi)", "horizontal_nm", None),
            ("tRMS (nmi)", "trms_nm", None),
            (
                "up-axis mean |attitude error| (deg)",
                "up_att_mean_deg",
                Some(published::UP_ATT_MEAN_DEG),
            ),
        ]
    };
    for (q, key, paper) in list {
        let mut row = band(q, paper);
        for case in ["uncompensated", "compensated"] {
            for s in ["median", "p05", "p95"] {
                row.push(d.num(&format!("{case}.{key}.{s}"), 4));
            }
        }
        rows.push(row);
    }
    r.table(
        &format!("{name}: end-of-run errors over the seeds (paper beside ours)"),
        &PAIRED_COLUMNS,
        rows,
    );
    // The paper's improvements (Section 3.1 text for Table 4, Table 5's caption for Table 5).
    let paper_gain: [(&str, &str, Option<f64>); 5] = if table5 {
        [
            ("horizontal", "horizontal", Some(79.86)),
            ("tRMS", "trms", Some(47.48)),
            ("longitude", "lon", Some(82.12)),
            ("latitude", "lat", None),
            ("up-axis mean attitude", "up_att_mean", None),
        ]
    } else {
        [
            ("horizontal", "horizontal", None),
            ("tRMS", "trms", None),
            ("longitude", "lon", Some(59.44)),
            ("latitude", "lat", Some(0.53)),
            ("up-axis mean attitude", "up_att_mean", Some(10.65)),
        ]
    };
    r.table(
        "Improvement by the compensation (medians), %",
        &["quantity", "paper", "ours"],
        paper_gain
            .iter()
            .map(|(q, k, p)| {
                vec![
                    Cell::Text(q.to_string()),
                    p.map_or(Cell::Text("-".into()), |p| Cell::Paper(p, 4)),
                    d.num(&format!("improvement_pct.{k}"), 4),
                ]
            })
            .collect(),
    );
    r.table(
        "Noise-free pair (every stochastic term off): end figures",
        &[
            "case",
            "latitude (nmi)",
            "longitude (nmi)",
            "horizontal (nmi)",
            "tRMS (nmi)",
        ],
        ["uncompensated", "compensated"]
            .iter()
            .map(|c| {
                let mut row = vec![Cell::Text(c.to_string())];
                for k in ["lat_nm", "lon_nm", "horizontal_nm", "trms_nm"] {
                    row.push(d.num(&format!("noise_free.{c}.{k}"), 4));
                }
                row
            })
            .collect(),
    );
    let (f2, f3) = if table5 {
        ("Figure 9", "Figure 10")
    } else {
        ("Figure 2", "Figure 3")
    };
    let att = format!(
        "{f2} counterpart: east, north and up attitude error of the first seed over the run, uncompensated (red) and compensated (blue), and in the bottom panel their difference (uncompensated − compensated) per axis on its own scale: at print size the east and north traces of the two cases overlap, the difference shows what the compensation changed. Each trace is its min-max band per pixel column with the mean line."
    );
    let pos = format!(
        "{f3} counterpart: latitude, longitude and horizontal error with the tRMS of Eq. 20 (dashed), first seed."
    );
    let att_nf = format!("{f2} counterpart for the noise-free pair: the deterministic part alone.");
    let pos_nf = format!("{f3} counterpart for the noise-free pair.");
    figures(
        r,
        dir,
        &[
            ("fig2_attitude_error", &att),
            ("fig3_position_error", &pos),
            ("fig2_attitude_error_noise_free", &att_nf),
            ("fig3_position_error_noise_free", &pos_nf),
        ],
    )
}

/// `rins paper table4` / `table5 --report DIR`.
pub fn paired<T: Serialize>(
    report: &T,
    table5: bool,
    fig_dir: &Path,
    out: &Path,
) -> Result<PathBuf> {
    let mut r = Report::new(if table5 {
        "Section 4.2 / Table 5: compensated 7-day navigation"
    } else {
        "Section 3.1 / Table 4: 16-position RINS, uncompensated vs compensated"
    });
    paired_sections(&mut r, report, table5, fig_dir)?;
    r.write(out)
}

/// The analytic verification's checks (Eq. 8, Eq. 11, Table 2) into `r`.
pub fn analytic_sections<T: Serialize>(r: &mut Report, report: &T, n_checks: usize) -> Result<()> {
    let v = json(report)?;
    let d = Doc {
        src: "analytic",
        json: &v,
    };
    r.text(
        "Analytic verification (Eq. 8, Eq. 11, Table 2)",
        "Each check's measured value against its limit; a check passes when the value is at most the limit.",
    );
    r.table(
        "Checks",
        &["check", "value", "limit", "passed"],
        (0..n_checks)
            .map(|k| {
                vec![
                    d.text(&format!("checks.{k}.name")),
                    d.num(&format!("checks.{k}.value"), 4),
                    d.num(&format!("checks.{k}.limit"), 4),
                    d.text(&format!("checks.{k}.pass")),
                ]
            })
            .collect(),
    );
    Ok(())
}

/// `rins calibrate --report DIR`.
pub fn calibration<T: Serialize>(
    result: &T,
    estimator: &str,
    fig_dir: &Path,
    out: &Path,
) -> Result<PathBuf> {
    let v = json(result)?;
    let d = Doc {
        src: "calibration",
        json: &v,
    };
    let mut r = Report::new("Section 3.2: system-level indirect calibration (Z-up / Z-down)");
    r.text("", &format!("Drift estimator: {estimator}. The bias at Z-up (Eq. 17), at Z-down (Eq. 19) and their difference delta-beta, each with its standard error, deg/h."));
    let rows = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, a)| {
            vec![
                Cell::Text(format!("gyro {a}")),
                d.num(&format!("up.beta_dph.{i}"), 4),
                d.num(&format!("up.se_dph.{i}"), 3),
                d.num(&format!("down.beta_dph.{i}"), 4),
                d.num(&format!("down.se_dph.{i}"), 3),
                d.num(&format!("delta_beta_dph.{i}"), 4),
                d.num(&format!("delta_beta_se_dph.{i}"), 3),
            ]
        })
        .collect();
    r.table(
        "Estimated gyro bias, deg/h",
        &[
            "axis",
            "beta Z-up",
            "SE",
            "beta Z-down",
            "SE",
            "delta-beta",
            "SE",
        ],
        rows,
    );
    figures(
        &mut r,
        fig_dir,
        &[(
            "calibration_beta",
            "Estimated bias per axis at Z-up, at Z-down and their difference, each +- 1 standard error (categories on the x axis).",
        )],
    )?;
    r.write(out)
}

/// `rins campaign --report DIR`.
pub fn campaign<T: Serialize>(c: &T, runs: usize, fig_dir: &Path, out: &Path) -> Result<PathBuf> {
    let v = json(c)?;
    let d = Doc {
        src: "campaign",
        json: &v,
    };
    let mut r =
        Report::new("Section 4.1 / Figure 8: temperature campaign and the fitted delta-beta(T)");
    let rows = (0..runs)
        .map(|k| {
            let mut row = vec![d.num(&format!("runs.{k}.chamber_c"), 4)];
            for i in 0..3 {
                row.push(d.num(&format!("runs.{k}.calibration.delta_beta_dph.{i}"), 4));
                row.push(d.num(&format!("runs.{k}.calibration.delta_beta_se_dph.{i}"), 3));
            }
            row
        })
        .collect();
    r.table(
        "delta-beta per run, deg/h",
        &[
            "chamber (deg C)",
            "dbeta x",
            "SE",
            "dbeta y",
            "SE",
            "dbeta z",
            "SE",
        ],
        rows,
    );
    r.table(
        "Third-order fit per axis: delta-beta(T) = c0 + c1 dT + c2 dT^2 + c3 dT^3, dT = T - reference temperature",
        &["axis", "c0", "c1", "c2", "c3", "chi2/dof"],
        ["x", "y", "z"]
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let mut row = vec![Cell::Text(a.to_string())];
                for j in 0..4 {
                    row.push(d.num(&format!("fits.{i}.coef.{j}"), 4));
                }
                row.push(d.num(&format!("fits.{i}.chi2_per_dof"), 3));
                row
            })
            .collect(),
    );
    figures(
        &mut r,
        fig_dir,
        &[(
            "fig8_dbeta_vs_temperature",
            "Figure 8 counterpart: each run's delta-beta +- 1 SE against the gyro block temperature at Z-down, the cubic fit (solid) and its 95 % band (dashed).",
        )],
    )?;
    r.write(out)
}

/// The figures of `rins compare` / `rins diagnose` with their captions.
const MVM_FIGURES: [(&str, &str); 4] = [
    (
        "residual_vs_temperature",
        "Residual (measured - model) per window against the sensor temperature, Z-up and Z-down dots; with a diagnosis the fitted effects as dashed curves.",
    ),
    (
        "bias_by_position",
        "Mean residual per table position (categories) with the 95 % noise-floor bars, the model as given (grey) beside the model with the fitted effects (green).",
    ),
    (
        "allan_residual",
        "Allan deviation of the residual: white noise falls with slope -1/2; a flattening or a rise is an unmodelled effect.",
    ),
    (
        "navigation_error",
        "Horizontal error of static navigation on the measured increments (band and mean) and on the model's (dashed), first segments.",
    ),
];

/// `rins compare --report DIR`.
pub fn compare<T: Serialize>(
    report: &T,
    channels: usize,
    nav: usize,
    dir: &Path,
) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "compare",
        json: &v,
    };
    let mut r = Report::new("Model vs measurements: where the model fails");
    r.text(
        "",
        &format!("Measurements: {}.", d.text("source").as_text()),
    );
    r.table(
        "Residual per channel",
        &[
            "channel",
            "residual RMS",
            "noise-floor RMS",
            "residual mean",
            "unit",
        ],
        (0..channels)
            .map(|k| {
                vec![
                    d.text(&format!("channels.{k}.channel")),
                    d.num(&format!("channels.{k}.residual_rms"), 4),
                    d.num(&format!("channels.{k}.noise_floor_rms"), 4),
                    d.num(&format!("channels.{k}.residual_mean"), 4),
                    d.text(&format!("channels.{k}.unit")),
                ]
            })
            .collect(),
    );
    r.table(
        "Navigation on the measured vs the model's increments (static segments)",
        &[
            "run",
            "duration (s)",
            "measured final (m)",
            "model final (m)",
            "difference RMS (m)",
        ],
        (0..nav.min(12))
            .map(|k| {
                vec![
                    d.text(&format!("navigation.{k}.run")),
                    d.num(&format!("navigation.{k}.duration_s"), 4),
                    d.num(&format!("navigation.{k}.measured_final_m"), 4),
                    d.num(&format!("navigation.{k}.model_final_m"), 4),
                    d.num(&format!("navigation.{k}.difference_rms_m"), 4),
                ]
            })
            .collect(),
    );
    figures(&mut r, dir, &MVM_FIGURES)?;
    r.write(dir)
}

/// A scenario key's unit as a reader writes it (°/h, µg, K², °C).
fn display_unit(unit: &str) -> String {
    unit.replace("deg/h", "°/h")
        .replace("deg/sqrt(h)", "°/√h")
        .replace("degC", "°C")
        .replace("ug", "µg")
        .replace("sqrt(", "√(")
        .replace("K2", "K²")
        .replace("K3", "K³")
}

/// `rins diagnose --report DIR`.
pub fn diagnose<T: Serialize>(
    report: &T,
    ranked: usize,
    channels: &[String],
    dir: &Path,
) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "diagnose",
        json: &v,
    };
    let mut r = Report::new("Model vs measurements: which effects explain the residual");
    r.text("", &format!("Measurements: {}. Gate: delta-BIC < -10, Bonferroni p < 0.01, cross-validation gain > 0.", d.text("source").as_text()));
    r.table(
        "Candidate effects ranked by delta-BIC",
        &[
            "effect",
            "channel",
            "delta-BIC",
            "p",
            "CV gain %",
            "passes gate",
        ],
        (0..ranked.min(15))
            .map(|k| {
                vec![
                    d.text(&format!("ranking.{k}.effect")),
                    d.text(&format!("ranking.{k}.channel")),
                    d.num(&format!("ranking.{k}.delta_bic"), 4),
                    d.num(&format!("ranking.{k}.p_value"), 3),
                    d.num(&format!("ranking.{k}.cv_rmse_gain_pct"), 3),
                    d.text(&format!("ranking.{k}.passes_gate")),
                ]
            })
            .collect(),
    );
    let mut rows = Vec::new();
    for k in 0..ranked.min(15) {
        let keys = v
            .pointer(&format!("/ranking/{k}/keys"))
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default();
        for (j, key) in keys.iter().enumerate() {
            let key = key.as_str().unwrap_or("?");
            rows.push(vec![
                d.text(&format!("ranking.{k}.channel")),
                Cell::Text(key.to_string()),
                d.num(&format!("ranking.{k}.coefficient.{j}"), 4),
                d.num(&format!("ranking.{k}.ci95.{j}.0"), 4),
                d.num(&format!("ranking.{k}.ci95.{j}.1"), 4),
                Cell::Text(display_unit(rins_plant::params::unit_for(key))),
            ]);
        }
    }
    r.table(
        "Coefficients of the ranked effects (each fitted against the model as given; the key names the effect; n/a: not identifiable on this data)",
        &["channel", "key", "coefficient", "95 % low", "95 % high", "unit"],
        rows,
    );
    r.table(
        "Residual RMS before and after the accepted effects",
        &["channel", "before", "after", "noise floor"],
        channels
            .iter()
            .map(|c| {
                vec![
                    Cell::Text(c.clone()),
                    d.num(&format!("residual_rms_before.{c}"), 4),
                    d.num(&format!("residual_rms_after.{c}"), 4),
                    d.num(&format!("noise_floor_rms.{c}"), 4),
                ]
            })
            .collect(),
    );
    discovery(&mut r, &d);
    figures(&mut r, dir, &MVM_FIGURES)?;
    r.write(dir)
}

/// The `--discover` proposals (when the report has them), every figure from the JSON.
fn discovery(r: &mut Report, d: &Doc) {
    let Some(props) = d
        .json
        .pointer("/discovery/proposals")
        .and_then(|v| v.as_array())
    else {
        return;
    };
    let mut rows = Vec::new();
    for (k, p) in props.iter().enumerate() {
        let n = p
            .pointer("/terms")
            .and_then(|t| t.as_array())
            .map_or(0, Vec::len);
        for j in 0..n {
            let t = format!("discovery.proposals.{k}.terms.{j}");
            rows.push(vec![
                d.text(&format!("discovery.proposals.{k}.name")),
                d.text(&format!("{t}.channel")),
                d.text(&format!("{t}.term")),
                d.num(&format!("{t}.coefficient"), 4),
                d.num(&format!("{t}.ci95.0"), 4),
                d.num(&format!("{t}.ci95.1"), 4),
                d.text(&format!("{t}.unit")),
                d.num(&format!("{t}.delta_bic"), 4),
                d.num(&format!("{t}.bootstrap_frequency"), 2),
            ]);
        }
    }
    r.table(
        "Discovered terms (--discover): proposals for [[sensor.*.custom]]",
        &[
            "proposal",
            "channel",
            "term",
            "coefficient",
            "95 % low",
            "95 % high",
            "unit",
            "delta-BIC",
            "bootstrap frequency",
        ],
        rows,
    );
}

impl Cell {
    /// The text of a text cell (a number's shown value otherwise).
    pub fn as_text(&self) -> String {
        match self {
            Cell::Text(t) => t.clone(),
            Cell::Json { value, sig, .. } | Cell::Paper(value, sig) => {
                super::format_sig(*value, *sig)
            }
        }
    }
}

const ITERATION_FIGURES: [(&str, &str); 2] = [
    (
        "iteration_history",
        "Watch the error fall: each channel's residual RMS over its noise floor after each step (step 0 is the model as given); the dashed line is the floor.",
    ),
    (
        "cells_before_after",
        "The cell map before (grey) and after (blue) the iteration: each cell's mean residual in units of its noise floor, with the family-wise flag bound (dashed).",
    ),
];

/// `rins diagnose --iterate --report DIR`.
pub fn iterate<T: Serialize>(report: &T, dir: &Path) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "iterate",
        json: &v,
    };
    let mut r = Report::new("Model vs measurements: iterating to the noise floor");
    r.text(
        "",
        &format!(
            "Measurements: {}. Each step compares the model with the data, ranks the catalogue, declared and discovered effects through the gate (delta-BIC < -10, Bonferroni p < 0.01, cross-validation gain > 0), keeps a term only if it survives the joint fit with its parents and run resampling, and fits the kept set jointly. Stopped: {}.",
            d.text("source").as_text(),
            d.text("stop").as_text()
        ),
    );
    let steps = v
        .pointer("/steps")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    let channels = 6;
    let mut cols = vec!["step".to_string(), "cells flagged".to_string()];
    for c in 0..channels {
        cols.push(
            v.pointer(&format!("/steps/0/levels/{c}/channel"))
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string()
                + " residual/floor",
        );
    }
    let col_refs: Vec<&str> = cols.iter().map(String::as_str).collect();
    r.table(
        "Residual RMS over the noise floor per channel, step by step",
        &col_refs,
        (0..steps)
            .map(|k| {
                let mut row = vec![
                    d.text(&format!("steps.{k}.step")),
                    d.text(&format!("steps.{k}.flagged_cells")),
                ];
                row.extend((0..channels).map(|c| d.num(&format!("steps.{k}.levels.{c}.ratio"), 3)));
                row
            })
            .collect(),
    );
    let mut rows = Vec::new();
    for k in 0..steps {
        let n = v
            .pointer(&format!("/steps/{k}/accepted"))
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        for j in 0..n {
            let t = format!("steps.{k}.accepted.{j}");
            rows.push(vec![
                d.text(&format!("steps.{k}.step")),
                d.text(&format!("{t}.channel")),
                d.text(&format!("{t}.effect")),
                d.text(&format!("{t}.found_by")),
                match crate::html::lookup(&v, &format!("{t}.replaces")).and_then(Value::as_str) {
                    Some(out) => Cell::Text(out.into()),
                    None => Cell::Text("-".into()),
                },
                d.num(&format!("{t}.delta_bic"), 4),
                d.num(&format!("{t}.stability"), 2),
                d.text(&format!("{t}.kept")),
            ]);
        }
    }
    r.table(
        "Terms accepted by the gate, with the joint-fit check",
        &[
            "step",
            "channel",
            "effect",
            "found by",
            "in place of (replacement pass)",
            "delta-BIC",
            "stable in (share of run resamples)",
            "kept",
        ],
        rows,
    );
    let mut rows = Vec::new();
    for k in 0..steps {
        let n = v
            .pointer(&format!("/steps/{k}/coefficients"))
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        for j in 0..n {
            let t = format!("steps.{k}.coefficients.{j}");
            // A kept or null coefficient has no fitted value: said in words, not "n/a".
            let fitted = |path: String| {
                if super::lookup(&v, &path).is_some_and(Value::is_f64) {
                    d.num(&path, 4)
                } else {
                    Cell::Text("not fitted".into())
                }
            };
            rows.push(vec![
                d.text(&format!("steps.{k}.step")),
                d.text(&format!("{t}.key")),
                d.num(&format!("{t}.model"), 4),
                fitted(format!("{t}.fitted")),
                fitted(format!("{t}.ci95.0")),
                fitted(format!("{t}.ci95.1")),
                d.text(&format!("{t}.fate")),
                d.text(&format!("{t}.reason")),
            ]);
        }
    }
    r.table(
        "Every coefficient of the joint fits: written, kept or null (file units)",
        &[
            "step",
            "key",
            "model",
            "fitted",
            "95 % low",
            "95 % high",
            "fate",
            "why",
        ],
        rows,
    );
    let n = v
        .pointer("/unexplained")
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    if n > 0 {
        let text: Vec<String> = (0..n)
            .map(|k| d.text(&format!("unexplained.{k}")).as_text())
            .collect();
        r.text("What stays unexplained", &text.join("; "));
    }
    figures(&mut r, dir, &ITERATION_FIGURES)?;
    r.write(dir)
}
