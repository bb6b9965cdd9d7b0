//! The page of `rins diagnose --iterate --report DIR`: the residual over the floor step by
//! step, the accepted terms, every coefficient's fate, what stays unexplained, and the
//! iteration figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{figures_with_key, json};
use crate::html::{Cell, Doc, Report, words};

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
    verdict(&mut r, &d, &v);
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
    figures_with_key(&mut r, dir, &ITERATION_FIGURES, "iteration_history")?;
    r.write(dir)
}

/// The verdict: the terms kept, each channel's residual over its floor at step 0 and at the
/// last step, the flagged cells before and after, and why the iteration stopped.
fn verdict(r: &mut Report, d: &Doc, v: &Value) {
    let steps = v
        .pointer("/steps")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let last = steps.len().saturating_sub(1);
    let mut kept = Vec::new();
    for (k, st) in steps.iter().enumerate() {
        let accepted = st
            .pointer("/accepted")
            .and_then(Value::as_array)
            .cloned()
            .unwrap_or_default();
        for (j, a) in accepted.iter().enumerate() {
            if a.pointer("/kept").and_then(Value::as_bool) == Some(true) {
                kept.push(format!("steps.{k}.accepted.{j}"));
            }
        }
    }
    let mut s = if kept.is_empty() {
        vec![words(
            "No term was kept: the model as given is as close to the data as the gate can tell",
        )]
    } else {
        let mut s = vec![words(format!(
            "{} term{} kept in {last} step{}: ",
            kept.len(),
            if kept.len() == 1 { "" } else { "s" },
            if last == 1 { "" } else { "s" }
        ))];
        for (i, t) in kept.iter().enumerate() {
            if i > 0 {
                s.push(words(", "));
            }
            s.push(d.text(&format!("{t}.effect")));
            s.push(words(" on "));
            s.push(d.text(&format!("{t}.channel")));
            s.push(words(" ("));
            s.push(d.text(&format!("{t}.found_by")));
            s.push(words(")"));
        }
        s
    };
    s.push(words(". Stopped: "));
    s.push(d.text("stop"));
    s.push(words("."));
    r.verdict(s);
    let levels = steps
        .first()
        .and_then(|st| st.pointer("/levels"))
        .and_then(Value::as_array)
        .map_or(0, Vec::len);
    let mut s = vec![words(format!(
        "Residual RMS over the noise floor, step 0 (the model as given) → step {last}: "
    ))];
    for c in 0..levels {
        if c > 0 {
            s.push(words(", "));
        }
        s.push(d.text(&format!("steps.0.levels.{c}.channel")));
        s.push(words(" "));
        s.push(d.num(&format!("steps.0.levels.{c}.ratio"), 3));
        s.push(words(" → "));
        s.push(d.num(&format!("steps.{last}.levels.{c}.ratio"), 3));
    }
    s.push(words(" (1 is the floor); flagged cells "));
    s.push(d.num("steps.0.flagged_cells", 1));
    s.push(words(" → "));
    s.push(d.num(&format!("steps.{last}.flagged_cells"), 1));
    s.push(words(
        match v.pointer("/reached_floor").and_then(Value::as_bool) {
            Some(true) => ": every channel at its noise floor.",
            _ => ".",
        },
    ));
    r.verdict(s);
}
