//! The page of `rins diagnose --report DIR`: the ranked effects and their coefficients, the
//! residual before and after, the `--discover` proposals and the model-vs-measurement figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{MVM_FIGURES, figures_with_key, json};
use crate::html::{Cell, Doc, Report, words};

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
    verdict(&mut r, &d, &v);
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
    // The mean residual per position against its noise floor shows the verdict (with a
    // diagnosis, before and after the fitted effects).
    figures_with_key(&mut r, dir, &MVM_FIGURES, "bias_by_position")?;
    r.write(dir)
}

/// Most accepted effects (and keys of each) the verdict names; the tables list them all.
const VERDICT_EFFECTS: usize = 5;

/// The verdict: which effects are missing with their values and intervals, how far each
/// channel's residual falls and to what floor, the flagged cells before and after.
fn verdict(r: &mut Report, d: &Doc, v: &Value) {
    let accepted = v
        .pointer("/accepted")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    if accepted.is_empty() {
        r.verdict(vec![
            words("No effect passes the gate (delta-BIC < -10, Bonferroni p < 0.01, cross-validation gain > 0): "),
            d.count("flagged_cells"),
            words(" cells of the model-vs-measurement map are flagged, and no candidate effect explains them beyond the noise (the closest are ranked below)."),
        ]);
        return;
    }
    let mut s = vec![
        words("Missing from the model: "),
        d.count("accepted"),
        words(" effects pass the gate and are fitted: "),
    ];
    let mut channels: Vec<String> = Vec::new();
    for (j, a) in accepted.iter().enumerate().take(VERDICT_EFFECTS) {
        let channel = a.pointer("/channel").and_then(Value::as_str).unwrap_or("?");
        if !channels.iter().any(|c| c == channel) {
            channels.push(channel.to_string());
        }
        if j > 0 {
            s.push(words("; "));
        }
        s.push(d.text(&format!("accepted.{j}.effect")));
        s.push(words(format!(" on {channel} (")));
        let keys = a
            .pointer("/keys")
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default();
        for (i, key) in keys.iter().enumerate() {
            let key = key.as_str().unwrap_or("?");
            if i > 0 {
                s.push(words(", "));
            }
            s.push(words(format!("{key} = ")));
            s.push(d.num(&format!("accepted.{j}.coefficient.{i}"), 4));
            s.push(words(" ["));
            s.push(d.num(&format!("accepted.{j}.ci95.{i}.0"), 4));
            s.push(words(", "));
            s.push(d.num(&format!("accepted.{j}.ci95.{i}.1"), 4));
            s.push(words(format!(
                "] {}",
                display_unit(rins_plant::params::unit_for(key))
            )));
        }
        s.push(words(")"));
    }
    if accepted.len() > VERDICT_EFFECTS {
        s.push(words("; the others in the tables below"));
    }
    s.push(words(" (95 % intervals in brackets)."));
    r.verdict(s);
    let mut s = vec![words(
        "Residual RMS before → after the fitted effects, with the noise floor: ",
    )];
    for (k, c) in channels.iter().enumerate() {
        if k > 0 {
            s.push(words("; "));
        }
        s.push(words(format!("{c} ")));
        s.push(d.num(&format!("residual_rms_before.{c}"), 4));
        s.push(words(" → "));
        s.push(d.num(&format!("residual_rms_after.{c}"), 4));
        s.push(words(" (floor "));
        s.push(d.num(&format!("noise_floor_rms.{c}"), 4));
        s.push(words(")"));
    }
    s.push(words(". Flagged cells: "));
    s.push(d.count("flagged_cells"));
    s.push(words(" before, "));
    s.push(d.count("flagged_cells_after"));
    s.push(words(" after."));
    r.verdict(s);
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
