//! The analytic verification's section of the `rins paper` page (Eq. 8, Eq. 11, Table 2).

use anyhow::Result;
use serde::Serialize;

use super::page_parts::json;
use crate::html::{Doc, Report, words};

/// The analytic verification's checks (Eq. 8, Eq. 11, Table 2) into `r`.
pub fn analytic_sections<T: Serialize>(r: &mut Report, report: &T, n_checks: usize) -> Result<()> {
    let v = json(report)?;
    let d = Doc {
        src: "analytic",
        json: &v,
    };
    let passed = v
        .pointer("/checks")
        .and_then(serde_json::Value::as_array)
        .map_or(0, |c| {
            c.iter()
                .filter(|x| x.pointer("/pass").and_then(serde_json::Value::as_bool) == Some(true))
                .count()
        });
    r.verdict(vec![
        words(format!(
            "Analytic verification (Eq. 8, Eq. 11, Table 2): {}, {passed} of ",
            if passed == n_checks {
                "passed"
            } else {
                "FAILED"
            }
        )),
        d.count("checks"),
        words(" checks within their limits."),
    ]);
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
