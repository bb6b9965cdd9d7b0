//! The pages of `rins schemes analyse --report DIR` and `rins schemes design --report DIR`:
//! the verdict first (what the invariant member leaves under any scheme, which scheme leaves
//! least), then the class worst cases, each effect's week and the figure.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{figures_with_key, json};
use crate::html::{Cell, Doc, Report, format_sig};

const CLASSES: [&str; 3] = ["general-b(u)", "general-anisotropic", "plant-delta-beta"];

fn as_f64(v: &Value, path: &str) -> f64 {
    v.pointer(path).and_then(Value::as_f64).unwrap_or(f64::NAN)
}

/// `rins schemes analyse --report DIR`.
pub fn schemes_analyse<T: Serialize>(report: &T, fig_dir: &Path, dir: &Path) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "schemes",
        json: &v,
    };
    let analyses = v["analyses"].as_array().cloned().unwrap_or_default();
    let bounds = v["bounds"].as_array().cloned().unwrap_or_default();
    let bound_index = |scheme: &str, class: &str| {
        bounds
            .iter()
            .position(|b| b["scheme"] == scheme && b["class"] == class)
    };
    let mut r = Report::new("Rotation schemes: what each leaves of each effect");
    // The verdict: the general class's floor and the scheme that leaves least of each class.
    if let Some(k) = bounds.iter().position(|b| b["class"] == CLASSES[0]) {
        r.verdict(vec![
            Cell::Text(
                "Under the general position-dependent bias b(u) with every coefficient within "
                    .into(),
            ),
            d.num(&format!("bounds.{k}.bound_dph"), 3),
            Cell::Text(
                " deg/h, no scheme can leave less than the invariant member b_i = B u_i: ".into(),
            ),
            d.num(&format!("bounds.{k}.invariant_horizontal_m"), 4),
            Cell::Text(" m after ".into()),
            d.num("analyses.0.days", 3),
            Cell::Text(" days, the same under every scheme.".into()),
        ]);
    }
    for class in CLASSES {
        let best = analyses
            .iter()
            .filter_map(|a| {
                let s = a["scheme"].as_str()?;
                let k = bound_index(s, class)?;
                Some((k, as_f64(&v, &format!("/bounds/{k}/worst_horizontal_m"))))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((k, _)) = best {
            r.verdict(vec![
                Cell::Text(format!("Least worst case over {class}: ")),
                d.text(&format!("bounds.{k}.scheme")),
                Cell::Text(" (".into()),
                d.num(&format!("bounds.{k}.worst_horizontal_m"), 4),
                Cell::Text(" m).".into()),
            ]);
        }
    }
    let mut columns = vec!["class"];
    let names: Vec<String> = analyses
        .iter()
        .map(|a| a["scheme"].as_str().unwrap_or("?").to_string())
        .collect();
    columns.extend(names.iter().map(String::as_str));
    r.table(
        "Worst horizontal position error over each class after the run (m)",
        &columns,
        CLASSES
            .iter()
            .map(|class| {
                let mut row = vec![Cell::Text((*class).into())];
                for s in &names {
                    row.push(match bound_index(s, class) {
                        Some(k) => d.num(&format!("bounds.{k}.worst_horizontal_m"), 4),
                        None => Cell::Text("n/a".into()),
                    });
                }
                row
            })
            .collect(),
    );
    let effects = analyses
        .first()
        .and_then(|a| a["effects"].as_array().cloned())
        .unwrap_or_default();
    let rows = effects
        .iter()
        .enumerate()
        .filter(|(_, e)| {
            let k = e["effect"].as_str().unwrap_or("");
            !k.starts_with("general.") && !k.starts_with("gyro.position_bias.")
        })
        .map(|(k, e)| {
            let mut row = vec![Cell::Text(e["effect"].as_str().unwrap_or("?").into())];
            for j in 0..names.len() {
                row.push(d.num(&format!("analyses.{j}.effects.{k}.after.east_m"), 4));
            }
            row
        })
        .collect();
    r.table(
        "East (longitude) error of each effect at its preset magnitude (m, Schuler-averaged)",
        &columns
            .iter()
            .map(|c| if *c == "class" { "effect" } else { c })
            .collect::<Vec<_>>(),
        rows,
    );
    r.text(
        "Models",
        "Every effect is evaluated by the plant's own models at a uniform reference temperature, without Earth rate in the body rate. The plant's delta-beta depends on u_z alone (Eq. 9): a scheme that keeps z horizontal turns it into a constant, an artefact of that model; the general b(u) has each gyro's bias depend on the whole up direction to second order. Navigation figures: the static free-inertial error model after the run, averaged over the last Schuler period.",
    );
    figures_with_key(
        &mut r,
        fig_dir,
        &[
            (
                "schemes_effects",
                "Each effect's east (longitude) error after the run at its preset magnitude, schemes side by side (log scale; below 1 m drawn at 1 m).",
            ),
            (
                "schemes_classes",
                "The worst case over each class with every coefficient within the bound, schemes side by side; under the general b(u) no scheme goes below the invariant member.",
            ),
        ],
        "schemes_classes",
    )?;
    r.write(dir)
}

/// `rins schemes design --report DIR`.
pub fn schemes_design<T: Serialize>(report: &T, dir: &Path) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "design",
        json: &v,
    };
    let class = v["options"]["class"].as_str().unwrap_or("?").to_string();
    let k = CLASSES.iter().position(|c| *c == class).unwrap_or(0);
    let reference = as_f64(&v, &format!("/reference/bounds/{k}/worst_horizontal_m"));
    let best = as_f64(&v, &format!("/best/0/bounds/{k}/worst_horizontal_m"));
    let mut r = Report::new("Rotation scheme search");
    let ratio = best / reference;
    r.verdict(vec![
        Cell::Text(format!("Searched class {class}: the best design leaves ")),
        d.num(&format!("best.0.bounds.{k}.worst_horizontal_m"), 4),
        Cell::Text(" m against the 16-position scheme's ".into()),
        d.num(&format!("reference.bounds.{k}.worst_horizontal_m"), 4),
        Cell::Text(format!(
            " m ({}, ratio {}).",
            if ratio <= 0.5 { "halved" } else { "not halved" },
            format_sig(ratio, 3)
        )),
    ]);
    r.verdict(vec![
        Cell::Text("The general class cannot go below its invariant member, ".into()),
        d.num("invariant_m", 4),
        Cell::Text(" m; on this table (body x never vertical) its anisotropic part cannot go below ".into()),
        d.num("anisotropic_floor_m", 4),
        Cell::Text(format!(
            " m.{}",
            if class == "plant-delta-beta" {
                " Caveat: under the plant's u_z-only delta-beta a scheme that keeps z near horizontal makes it a constant that rotation cancels, an artefact of the model."
            } else {
                ""
            }
        )),
    ]);
    let n = v["best"].as_array().map_or(0, Vec::len);
    let mut rows = vec![{
        let mut row = vec![Cell::Text("sixteen-position".into())];
        row.push(d.num("reference.cycle_s", 5));
        for j in 0..3 {
            row.push(d.num(&format!("reference.bounds.{j}.worst_horizontal_m"), 4));
        }
        row.push(d.num("reference.constants_max_fraction", 2));
        row
    }];
    for i in 0..n {
        let mut row = vec![d.text(&format!("best.{i}.file.name"))];
        row.push(d.num(&format!("best.{i}.cycle_s"), 5));
        for j in 0..3 {
            row.push(d.num(&format!("best.{i}.bounds.{j}.worst_horizontal_m"), 4));
        }
        row.push(d.num(&format!("best.{i}.constants_max_fraction"), 2));
        rows.push(row);
    }
    r.table(
        "Worst horizontal position error over each class (m) and the largest fraction a constant error leaves",
        &[
            "scheme",
            "cycle (s)",
            CLASSES[0],
            CLASSES[1],
            CLASSES[2],
            "constants",
        ],
        rows,
    );
    r.write(dir)
}
