//! The page of `rins paper table4` / `table5 --report DIR` (and its sections in the `rins paper`
//! page): the paired study's end-of-run errors with the paper's beside ours, the improvements,
//! the noise-free pair and the Figure 2–3 (9–10) counterparts.

use std::path::{Path, PathBuf};

use anyhow::Result;
use rins_verification::paper::{published, published_table5};
use serde::Serialize;

use super::page_parts::{figures_with_key, json};
use crate::html::{Cell, Doc, Report, words};

const PAIRED_COLUMNS: [&str; 9] = [
    "quantity",
    "paper uncompensated",
    "paper compensated",
    "ours uncompensated median",
    "5 %",
    "95 %",
    "ours compensated median",
    "5 %",
    "95 %",
];

/// The tables and figures of a paired study (Table 4 or, with `table5`, Table 5) into `r`;
/// `dir` holds its figures.
pub fn paired_sections<T: Serialize>(
    r: &mut Report,
    report: &T,
    table5: bool,
    dir: &Path,
) -> Result<()> {
    let v = json(report)?;
    let (src, name) = if table5 {
        ("table5", "Table 5")
    } else {
        ("table4", "Table 4")
    };
    let d = Doc { src, json: &v };
    let band = |q: &str, paper: Option<[f64; 2]>| {
        let mut row = vec![Cell::Text(q.to_string())];
        for k in 0..2 {
            row.push(paper.map_or(Cell::Text("-".into()), |p| Cell::Paper(p[k], 5)));
        }
        row
    };
    let mut rows = Vec::new();
    let list: Vec<(&str, &str, Option<[f64; 2]>)> = if table5 {
        use published_table5 as p;
        vec![
            ("latitude error (nmi)", "lat_nm", Some(p::LAT_NM)),
            ("longitude error (nmi)", "lon_nm", Some(p::LON_NM)),
            (
                "horizontal error (nmi)",
                "horizontal_nm",
                Some(p::HORIZONTAL_NM),
            ),
            ("tRMS (nmi)", "trms_nm", Some(p::TRMS_NM)),
        ]
    } else {
        vec![
            (
                "|latitude error| (nmi)",
                "abs_lat_nm",
                Some(published::LAT_NM),
            ),
            (
                "|longitude error| (nmi)",
                "abs_lon_nm",
                Some(published::LON_NM),
            ),
            ("latitude error (nmi)", "lat_nm", None),
            ("longitude error (nmi)", "lon_nm", None),
            ("horizontal error (nmi)", "horizontal_nm", None),
            ("tRMS (nmi)", "trms_nm", None),
            (
                "up-axis mean |attitude error| (deg)",
                "up_att_mean_deg",
                Some(published::UP_ATT_MEAN_DEG),
            ),
        ]
    };
    for (q, key, paper) in list {
        let mut row = band(q, paper);
        for case in ["uncompensated", "compensated"] {
            for s in ["median", "p05", "p95"] {
                row.push(d.num(&format!("{case}.{key}.{s}"), 4));
            }
        }
        rows.push(row);
    }
    r.table(
        &format!("{name}: end-of-run errors over the seeds (paper beside ours)"),
        &PAIRED_COLUMNS,
        rows,
    );
    // The paper's improvements (Section 3.1 text for Table 4, Table 5's caption for Table 5).
    let paper_gain: [(&str, &str, Option<f64>); 5] = if table5 {
        [
            ("horizontal", "horizontal", Some(79.86)),
            ("tRMS", "trms", Some(47.48)),
            ("longitude", "lon", Some(82.12)),
            ("latitude", "lat", None),
            ("up-axis mean attitude", "up_att_mean", None),
        ]
    } else {
        [
            ("horizontal", "horizontal", None),
            ("tRMS", "trms", None),
            ("longitude", "lon", Some(59.44)),
            ("latitude", "lat", Some(0.53)),
            ("up-axis mean attitude", "up_att_mean", Some(10.65)),
        ]
    };
    r.table(
        "Improvement by the compensation (medians), %",
        &["quantity", "paper", "ours"],
        paper_gain
            .iter()
            .map(|(q, k, p)| {
                vec![
                    Cell::Text(q.to_string()),
                    p.map_or(Cell::Text("-".into()), |p| Cell::Paper(p, 4)),
                    d.num(&format!("improvement_pct.{k}"), 4),
                ]
            })
            .collect(),
    );
    r.table(
        "Noise-free pair (every stochastic term off): end figures",
        &[
            "case",
            "latitude (nmi)",
            "longitude (nmi)",
            "horizontal (nmi)",
            "tRMS (nmi)",
        ],
        ["uncompensated", "compensated"]
            .iter()
            .map(|c| {
                let mut row = vec![Cell::Text(c.to_string())];
                for k in ["lat_nm", "lon_nm", "horizontal_nm", "trms_nm"] {
                    row.push(d.num(&format!("noise_free.{c}.{k}"), 4));
                }
                row
            })
            .collect(),
    );
    let (f2, f3) = if table5 {
        ("Figure 9", "Figure 10")
    } else {
        ("Figure 2", "Figure 3")
    };
    let att = format!(
        "{f2} counterpart: east, north and up attitude error of the first seed over the run, uncompensated (red) and compensated (blue), and in the bottom panel their difference (uncompensated − compensated) per axis on its own scale: at print size the east and north traces of the two cases overlap, the difference shows what the compensation changed. Each trace is its min-max band per pixel column with the mean line."
    );
    let pos = format!(
        "{f3} counterpart: latitude, longitude and horizontal error with the tRMS of Eq. 20 (dashed), first seed."
    );
    let att_nf = format!("{f2} counterpart for the noise-free pair: the deterministic part alone.");
    let pos_nf = format!("{f3} counterpart for the noise-free pair.");
    // The position errors over the run, uncompensated and compensated, show the verdict.
    figures_with_key(
        r,
        dir,
        &[
            ("fig2_attitude_error", &att),
            ("fig3_position_error", &pos),
            ("fig2_attitude_error_noise_free", &att_nf),
            ("fig3_position_error_noise_free", &pos_nf),
        ],
        "fig3_position_error",
    )
}

/// The verdict of a paired study (Table 4, or Table 5 with `table5`) into `r`: what the δβ
/// compensation does to the end-of-run longitude and horizontal errors, ours beside the
/// paper's improvement.
pub fn paired_verdict<T: Serialize>(r: &mut Report, report: &T, table5: bool) -> Result<()> {
    let v = json(report)?;
    let (src, lon, paper_lon) = if table5 {
        ("table5", "lon_nm", 82.12)
    } else {
        ("table4", "abs_lon_nm", 59.44)
    };
    let d = Doc { src, json: &v };
    let f = |k: &str| {
        v.pointer(k)
            .and_then(serde_json::Value::as_f64)
            .unwrap_or(0.0)
    };
    // The days as given (7, 0.05), at most 4 digits.
    let days_sig = crate::html::digits(f("/days")).min(4);
    r.verdict(vec![
        words(format!(
            "{}: over ",
            if table5 { "Table 5" } else { "Table 4" }
        )),
        d.num("runs", 1),
        words(if f("/runs") == 1.0 { " seed" } else { " seeds" }),
        words(" of "),
        d.num("days", days_sig),
        words(" days, δβ compensation takes the median "),
        words(if table5 {
            "longitude error"
        } else {
            "|longitude error|"
        }),
        words(" from "),
        d.num(&format!("uncompensated.{lon}.median"), 4),
        words(" to "),
        d.num(&format!("compensated.{lon}.median"), 4),
        words(" nmi (improvement "),
        d.num("improvement_pct.lon", 4),
        words(" %; the paper's: "),
        Cell::Paper(paper_lon, 4),
        words(" %), and the median horizontal error from "),
        d.num("uncompensated.horizontal_nm.median", 4),
        words(" to "),
        d.num("compensated.horizontal_nm.median", 4),
        words(" nmi."),
    ]);
    Ok(())
}

/// `rins paper table4` / `table5 --report DIR`.
pub fn paired<T: Serialize>(
    report: &T,
    table5: bool,
    fig_dir: &Path,
    out: &Path,
) -> Result<PathBuf> {
    let mut r = Report::new(if table5 {
        "Section 4.2 / Table 5: compensated 7-day navigation"
    } else {
        "Section 3.1 / Table 4: 16-position RINS, uncompensated vs compensated"
    });
    paired_verdict(&mut r, report, table5)?;
    paired_sections(&mut r, report, table5, fig_dir)?;
    r.write(out)
}
