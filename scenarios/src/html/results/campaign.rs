//! The page of `rins campaign --report DIR`: δβ per run, the cubic fit per axis and Figure 8.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;

use super::page_parts::{figures, json};
use crate::html::{Cell, Doc, Report};

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
