//! The page of `rins calibrate --report DIR`: the bias at Z-up, at Z-down and their difference.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;

use super::page_parts::{figures, json};
use crate::html::{Cell, Doc, Report};

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
