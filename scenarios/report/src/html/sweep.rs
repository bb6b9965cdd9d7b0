//! The report page of `rins sweep --report DIR`: the verdict, each output's figure (which shows
//! it), what was swept, per output a table of the median and 5–95 % band at every point for
//! both navigators, and each seed's figures (up to [`MAX_SEED_ROWS`] rows; the CSV has them
//! all). Every number is a cell of the sweep's JSON (`src` "sweep").

use std::path::{Path, PathBuf};

use anyhow::Result;

use super::{Cell, Doc, Report, words};
use rins_sweep::outputs::PER_SEED;
use rins_sweep::{NAVIGATORS, SweepReport};

/// Most per-seed rows the page lists.
pub const MAX_SEED_ROWS: usize = 200;

/// The cell of swept value `i` at point `k`: a number with its JSON path, or text.
fn value_cell(d: &Doc, r: &SweepReport, k: usize, i: usize) -> Cell {
    let v = &r.points[k].values[i];
    if let Some(x) = v.as_f64().filter(|_| v.is_number()) {
        d.num(&format!("points.{k}.values.{i}"), super::digits(x))
    } else {
        d.text(&format!("points.{k}.values.{i}"))
    }
}

/// The verdict: per output, the smallest and the largest median over the points for each
/// navigator, with the points' swept values.
fn verdict(page: &mut Report, d: &Doc, r: &SweepReport) {
    page.verdict(vec![
        words(format!("{} points × ", r.points.len())),
        d.count("seeds"),
        words(format!(
            " seeds, {} swept; the medians over the seeds range as follows.",
            r.parameters
                .iter()
                .map(|p| p.key.as_str())
                .collect::<Vec<_>>()
                .join(" × ")
        )),
    ]);
    let median = |k: usize, nav: &str, o: &str| {
        super::lookup(d.json, &format!("points.{k}.{nav}.{o}.median"))
            .and_then(serde_json::Value::as_f64)
            .unwrap_or(f64::NAN)
    };
    for o in &r.outputs {
        let mut s = vec![words(format!("{} ({}, {}): ", o.name, o.what, o.unit))];
        for (n, nav) in NAVIGATORS.iter().enumerate() {
            let order = |a: &usize, b: &usize| {
                median(*a, nav, &o.name).total_cmp(&median(*b, nav, &o.name))
            };
            let (Some(lo), Some(hi)) = (
                (0..r.points.len()).min_by(order),
                (0..r.points.len()).max_by(order),
            ) else {
                continue;
            };
            if n > 0 {
                s.push(words("; "));
            }
            s.push(words(format!("{nav} from ")));
            s.push(d.num(&format!("points.{lo}.{nav}.{}.median", o.name), 4));
            s.push(words(" ("));
            s.push(d.text(&format!("points.{lo}.label")));
            s.push(words(") to "));
            s.push(d.num(&format!("points.{hi}.{nav}.{}.median", o.name), 4));
            s.push(words(" ("));
            s.push(d.text(&format!("points.{hi}.label")));
            s.push(words(")"));
        }
        s.push(words("."));
        page.verdict(s);
    }
}

/// Writes `out/report.html` for `r`, with the figures of `fig_dir`.
pub fn report(r: &SweepReport, fig_dir: &Path, out: &Path) -> Result<PathBuf> {
    let v = serde_json::to_value(r)?;
    let d = Doc {
        src: "sweep",
        json: &v,
    };
    let keys: Vec<&str> = r.parameters.iter().map(|p| p.key.as_str()).collect();
    let mut page = Report::new(&format!("Sweep {}: {}", r.name, keys.join(" × ")));
    verdict(&mut page, &d, r);
    page.text(
        "",
        &format!(
            "{}{} points ({} of the swept keys) × {} seeds, {} days of navigation each from the base scenario {} (alignment: {}). Each seed's samples feed the uncompensated and the δβ-compensated navigator (which subtracts the point's own δβ), as rins paper table4 runs them. Sweep file: {}; wall time {:.1} s.",
            if r.description.is_empty() {
                String::new()
            } else {
                format!("{} ", r.description)
            },
            r.points.len(),
            r.combine,
            r.seeds.len(),
            super::format_sig(r.days, 4),
            r.scenario,
            r.alignment,
            r.sweep_file,
            r.wall_s
        ),
    );
    page.table(
        "Swept scenario keys",
        &["key", "unit", "values"],
        r.parameters
            .iter()
            .map(|p| {
                vec![
                    Cell::Text(p.key.clone()),
                    Cell::Text(p.unit.clone()),
                    Cell::Text(
                        p.values
                            .iter()
                            .map(rins_sweep::value_text)
                            .collect::<Vec<_>>()
                            .join(", "),
                    ),
                ]
            })
            .collect(),
    );
    let heads: Vec<String> = r.parameters.iter().map(|p| p.heading()).collect();
    for o in &r.outputs {
        let mut columns: Vec<&str> = heads.iter().map(String::as_str).collect();
        columns.extend([
            "uncompensated median",
            "5 %",
            "95 %",
            "compensated median",
            "5 %",
            "95 %",
        ]);
        let rows = (0..r.points.len())
            .map(|k| {
                let mut row: Vec<Cell> = (0..r.parameters.len())
                    .map(|i| value_cell(&d, r, k, i))
                    .collect();
                for nav in NAVIGATORS {
                    for s in ["median", "p05", "p95"] {
                        row.push(d.num(&format!("points.{k}.{nav}.{}.{s}", o.name), 4));
                    }
                }
                row
            })
            .collect();
        page.text(&format!("{} ({})", o.what, o.unit), "");
        page.table(
            &format!("{} ({}): median and 5-95 % over the seeds", o.name, o.unit),
            &columns,
            rows,
        );
        // Each output's figure shows its verdict sentence: directly after the verdict.
        let f = fig_dir.join(format!("sweep_{}.svg", o.name));
        if f.exists() {
            page.key_figure(
                &f,
                &format!(
                    "{} against {}: the median over the seeds (line) with the 5-95 % band (bar) at each point, one line per value of the other swept keys; uncompensated (top) and δβ-compensated (bottom) navigator. Lines of one x are set slightly apart so their bars stay visible.",
                    o.what, r.parameters[0].key
                ),
            )?;
        }
    }
    // Each seed's figures of the chosen outputs a run returns as such (the magnitudes are
    // these figures' absolute values).
    let shown: Vec<&str> = PER_SEED
        .iter()
        .copied()
        .filter(|f| {
            r.outputs
                .iter()
                .any(|o| o.name == *f || o.name == format!("abs_{f}"))
        })
        .collect();
    let total = r.points.len() * r.seeds.len();
    if !shown.is_empty() {
        let mut columns = vec!["point", "seed"];
        let names: Vec<String> = NAVIGATORS
            .iter()
            .flat_map(|nav| shown.iter().map(move |f| format!("{f} {nav}")))
            .collect();
        columns.extend(names.iter().map(String::as_str));
        let mut rows = Vec::new();
        'all: for k in 0..r.points.len() {
            for j in 0..r.seeds.len() {
                if rows.len() == MAX_SEED_ROWS {
                    break 'all;
                }
                let mut row = vec![
                    Cell::Text(k.to_string()),
                    d.text(&format!("points.{k}.per_seed.{j}.seed")),
                ];
                for nav in NAVIGATORS {
                    for f in &shown {
                        row.push(d.num(&format!("points.{k}.per_seed.{j}.{nav}.{f}"), 6));
                    }
                }
                rows.push(row);
            }
        }
        let caption = if total > MAX_SEED_ROWS {
            format!(
                "Each seed's end figures (the first {MAX_SEED_ROWS} of {total} point × seed rows; sweep.csv has them all)"
            )
        } else {
            "Each seed's end figures".to_string()
        };
        page.table(&caption, &columns, rows);
    }
    page.write(out)
}
