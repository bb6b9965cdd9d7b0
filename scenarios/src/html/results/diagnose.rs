//! The page of `rins diagnose --report DIR`: the ranked effects and their coefficients, the
//! residual before and after, the `--discover` proposals and the model-vs-measurement figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{MVM_FIGURES, figures, json};
use crate::html::{Cell, Doc, Report};

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
