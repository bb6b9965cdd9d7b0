//! The page of `rins paper sea --report DIR`: the verdict (the end errors at sea against the
//! static reference's), the end-error figure, the summary tables (numbers from sea.json) and the
//! first seed's error over the run.

use std::path::{Path, PathBuf};

use anyhow::Result;
use rins_verification::paper::SeaReport;

use super::page_parts::figures_with_key;
use crate::html::{Cell, Doc, Report, words};

/// Category names of the sea study's cases (the rows of the page and of the end-error
/// figure), in `SeaReport::cases` order.
pub const CASES: [&str; 3] = ["static reference", "ship", "ship + isolation"];

/// The cases' keys in sea.json, in [`CASES`] order.
const KEYS: [&str; 3] = ["static_reference", "ship", "ship_isolated"];

/// `rins paper sea --report DIR`: the page of `r`, with the figures in `fig_dir`.
pub fn sea(r: &SeaReport, fig_dir: &Path, out: &Path) -> Result<PathBuf> {
    let v = serde_json::to_value(r)?;
    let d = Doc {
        src: "sea",
        json: &v,
    };
    let mut page =
        Report::new("At sea: 16-position RINS on a ship, without and with azimuth isolation");
    verdict(&mut page, &d, r);
    page.text(
        "Setup",
        &format!(
            "{} seeds x {:.2} days. The paper's 16-position scheme and Table 3 sensors on a ship at 10-15 kn with course changes in sea state 4-5, beside the same sensors on the static carrier. {} The navigator starts aligned from truth on the moving base; delta-beta is compensated with the plant's own coefficients.",
            r.runs,
            r.days,
            match r.sea_seed {
                Some(seed) => format!("Every seed sails the same sea (sea seed {seed}): the seeds differ in their sensors only."),
                None => "Each seed sails its own sea, drawn from its run seed.".into(),
            }
        ),
    );
    let rows = KEYS
        .iter()
        .zip(CASES)
        .map(|(k, name)| {
            let mut row = vec![Cell::Text(name.to_string())];
            for case in ["uncompensated", "compensated"] {
                for q in ["median", "p05", "p95"] {
                    row.push(d.num(&format!("{k}.{case}.horizontal_nm.{q}"), 4));
                }
            }
            row.push(d.num(&format!("{k}.improvement_pct.horizontal"), 3));
            row.push(d.num(&format!("{k}.noise_free.uncompensated.horizontal_nm"), 4));
            row.push(d.num(&format!("{k}.noise_free.compensated.horizontal_nm"), 4));
            row
        })
        .collect();
    page.table(
        "Horizontal error at the end (nmi)",
        &[
            "case",
            "uncompensated median",
            "5 %",
            "95 %",
            "compensated median",
            "5 %",
            "95 %",
            "improvement %",
            "noise-free unc",
            "noise-free comp",
        ],
        rows,
    );
    page.table(
        "Ideal IMU on the ship (every sensor error off)",
        &[
            "isolation",
            "max horizontal error (m)",
            "max attitude error (rad)",
        ],
        (0..2)
            .map(|k| {
                vec![
                    Cell::Text(["off", "on"][k].into()),
                    d.num(&format!("ideal.{k}.max_horizontal_m"), 3),
                    d.num(&format!("ideal.{k}.max_attitude_rad"), 3),
                ]
            })
            .collect(),
    );
    // The end errors per case, beside the static reference's, show the verdict.
    figures_with_key(
        &mut page,
        fig_dir,
        &[
            (
                "sea_end_error",
                "End-of-run horizontal error per case: median and 5-95 % band over the seeds; below, the noise-free pair.",
            ),
            (
                "sea_horizontal_error",
                "Horizontal error of the first seed, per case (envelopes: min-max per pixel column with the mean).",
            ),
        ],
        "sea_end_error",
    )?;
    page.write(out)
}

/// The verdict: the median horizontal error at the end on the ship without and with azimuth
/// isolation against the static reference's, uncompensated and compensated, what δβ
/// compensation gains in each case, and the ideal IMU's largest error on the ship.
fn verdict(page: &mut Report, d: &Doc, r: &SeaReport) {
    let mut s = vec![
        words("Over "),
        d.num("runs", 1),
        words(if r.runs == 1 { " seed" } else { " seeds" }),
        words(" of "),
        d.num("days", crate::html::digits(r.days).min(4)),
        words(match r.sea_seed {
            Some(_) => {
                " days (one sea for every seed), the median horizontal error at the end, uncompensated → δβ-compensated: "
            }
            None => {
                " days (each seed its own sea), the median horizontal error at the end, uncompensated → δβ-compensated: "
            }
        }),
    ];
    // The ship without and with isolation, then the static reference they are held against.
    for (n, c) in [1, 2, 0].into_iter().enumerate() {
        s.push(words(match n {
            0 => format!("{} ", CASES[c]),
            1 => format!("; {} ", CASES[c]),
            _ => format!(", against the {} ", CASES[c]),
        }));
        s.push(d.num(
            &format!("{}.uncompensated.horizontal_nm.median", KEYS[c]),
            4,
        ));
        s.push(words(" → "));
        s.push(d.num(&format!("{}.compensated.horizontal_nm.median", KEYS[c]), 4));
    }
    s.push(words(
        " nmi (same sensors and seeds on the static carrier).",
    ));
    page.verdict(s);
    let mut s = vec![words("δβ compensation improves the median by ")];
    for (j, (k, name)) in KEYS.iter().zip(CASES).enumerate() {
        if j > 0 {
            s.push(words(", "));
        }
        s.push(d.num(&format!("{k}.improvement_pct.horizontal"), 3));
        s.push(words(format!(" % ({name})")));
    }
    s.push(words(
        "; an ideal IMU (every sensor error off) on the ship stays within ",
    ));
    s.push(d.num("ideal.0.max_horizontal_m", 3));
    s.push(words(" m without and "));
    s.push(d.num("ideal.1.max_horizontal_m", 3));
    s.push(words(" m with isolation: the rest is the sensors'."));
    page.verdict(s);
}
