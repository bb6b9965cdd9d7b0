//! The page of `rins calibrate --report DIR`: the verdict (δβ per axis against the plant's own),
//! the figure of the estimates, the bias at Z-up, at Z-down and their difference.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;

use serde_json::Value;

use super::page_parts::{figures_with_key, json};
use crate::html::{Cell, Doc, Report, words};

/// An estimate further than this many standard errors from the plant's δβ is called off.
const WITHIN_SE: f64 = 2.0;

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
    verdict(&mut r, &d, &v);
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
    figures_with_key(
        &mut r,
        fig_dir,
        &[(
            "calibration_beta",
            "Estimated bias per axis at Z-up, at Z-down and their difference, each +- 1 standard error (categories on the x axis).",
        )],
        "calibration_beta",
    )?;
    r.write(out)
}

/// The verdict: δβ per axis with its standard error beside the plant's own δβ, and whether
/// each estimate is within [`WITHIN_SE`] standard errors of it.
fn verdict(r: &mut Report, d: &Doc, v: &Value) {
    let mut s = vec![words(
        "Estimated δβ = β(Z-down) − β(Z-up) ± 1 SE against the plant's δβ term (Eq. 9) at the Z-down gyro temperatures (",
    )];
    for i in 0..3 {
        if i > 0 {
            s.push(words(", "));
        }
        s.push(d.num(&format!("down.gyro_temp_c.{i}"), 4));
    }
    s.push(words(" °C): "));
    for (i, a) in ["x", "y", "z"].iter().enumerate() {
        if i > 0 {
            s.push(words("; "));
        }
        s.push(words(format!("{a} ")));
        s.push(d.num(&format!("delta_beta_dph.{i}"), 4));
        s.push(words(" ± "));
        s.push(d.num(&format!("delta_beta_se_dph.{i}"), 2));
        s.push(words(" °/h (plant "));
        s.push(d.num(&format!("truth.delta_beta_dph.{i}"), 4));
        s.push(words(", off by "));
        s.push(d.num(&format!("truth.error_se.{i}"), 2));
        s.push(words(" SE)"));
    }
    s.push(words("."));
    r.verdict(s);
    let off: Vec<&str> = ["x", "y", "z"]
        .into_iter()
        .enumerate()
        .filter(|(i, _)| {
            v.pointer(&format!("/truth/error_se/{i}"))
                .and_then(Value::as_f64)
                .is_none_or(|k| k > WITHIN_SE)
        })
        .map(|(_, a)| a)
        .collect();
    r.verdict(vec![words(if off.is_empty() {
        format!("Every axis is within {WITHIN_SE} standard errors of the plant's δβ term.")
    } else {
        format!(
            "Off by more than {WITHIN_SE} standard errors: {} (the others within).",
            off.join(", ")
        )
    } + " Whatever else differs between Z-up and Z-down (g-sensitivity along z, scale factor and misalignment on the Earth rate) enters the estimate too.")]);
}
