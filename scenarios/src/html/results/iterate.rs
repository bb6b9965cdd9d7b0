//! The page of `rins diagnose --iterate --report DIR`: the residual over the floor step by
//! step, the accepted terms, every coefficient's fate, what stays unexplained, and the
//! iteration figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{figures, json};
use crate::html::{Cell, Doc, Report};

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
                if crate::html::lookup(&v, &path).is_some_and(Value::is_f64) {
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
