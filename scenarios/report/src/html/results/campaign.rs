//! The page of `rins campaign --report DIR`: the verdict (the fitted δβ(T) against the plant's
//! own), Figure 8, δβ per run and the cubic fit per axis.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;

use serde_json::Value;

use super::page_parts::{figures_with_key, json};
use crate::html::{Cell, Doc, Report, words};

/// `rins campaign --report DIR`.
pub fn campaign<T: Serialize>(c: &T, runs: usize, fig_dir: &Path, out: &Path) -> Result<PathBuf> {
    let v = json(c)?;
    let d = Doc {
        src: "campaign",
        json: &v,
    };
    let mut r =
        Report::new("Section 4.1 / Figure 8: temperature campaign and the fitted delta-beta(T)");
    verdict(&mut r, &d, &v, runs);
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
    figures_with_key(
        &mut r,
        fig_dir,
        &[(
            "fig8_dbeta_vs_temperature",
            "Figure 8 counterpart: each run's delta-beta +- 1 SE against the gyro block temperature at Z-down, the cubic fit (solid) and its 95 % band (dashed).",
        )],
        "fig8_dbeta_vs_temperature",
    )?;
    r.write(out)
}

/// The verdict: the temperatures the runs span, the fit at the reference temperature beside
/// the plant's δβ there, the fit's largest error over the runs' temperatures (what the
/// compensation file leaves of δβ) and each fit's χ²/dof.
fn verdict(r: &mut Report, d: &Doc, v: &Value, runs: usize) {
    let chamber = |k: &usize| {
        v.pointer(&format!("/runs/{k}/chamber_c"))
            .and_then(Value::as_f64)
            .unwrap_or(f64::NAN)
    };
    let order = |a: &usize, b: &usize| chamber(a).total_cmp(&chamber(b));
    let (Some(lo), Some(hi)) = ((0..runs).min_by(order), (0..runs).max_by(order)) else {
        return;
    };
    let axes = ["x", "y", "z"];
    let mut s = vec![
        d.count("runs"),
        words(" Z-up/Z-down calibrations at chamber temperatures from "),
        d.num(&format!("runs.{lo}.chamber_c"), 4),
        words(" to "),
        d.num(&format!("runs.{hi}.chamber_c"), 4),
        words(" °C, a cubic δβ(T) per axis; at the reference temperature "),
        d.num("ref_temp_c", 4),
        words(" °C the fit gives "),
    ];
    for (i, a) in axes.iter().enumerate() {
        if i > 0 {
            s.push(words(", "));
        }
        s.push(words(format!("{a} ")));
        s.push(d.num(&format!("fits.{i}.coef.0"), 4));
        s.push(words(" (the plant's δβ term "));
        s.push(d.num(&format!("truth.at_ref_dph.{i}"), 4));
        s.push(words(")"));
    }
    s.push(words(" °/h."));
    r.verdict(s);
    let mut s = vec![words(
        "The fit's largest difference from the plant's δβ term over the runs' temperatures (what compensating with it leaves of that term): ",
    )];
    for (i, a) in axes.iter().enumerate() {
        if i > 0 {
            s.push(words(", "));
        }
        s.push(words(format!("{a} ")));
        s.push(d.num(&format!("truth.fit_error_max_dph.{i}"), 3));
    }
    s.push(words(" °/h; χ²/dof of the fits "));
    for (i, a) in axes.iter().enumerate() {
        if i > 0 {
            s.push(words(", "));
        }
        s.push(words(format!("{a} ")));
        s.push(d.num(&format!("fits.{i}.chi2_per_dof"), 3));
    }
    s.push(words("."));
    r.verdict(s);
}
