//! The page of `rins compare --report DIR`: residual per channel, navigation on the measured vs
//! the model's increments, and the model-vs-measurement figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use super::page_parts::{MVM_FIGURES, figures_with_key, json};
use crate::html::{Doc, Report, words};

/// `rins compare --report DIR`.
pub fn compare<T: Serialize>(
    report: &T,
    channels: usize,
    nav: usize,
    dir: &Path,
) -> Result<PathBuf> {
    let v = json(report)?;
    let d = Doc {
        src: "compare",
        json: &v,
    };
    let mut r = Report::new("Model vs measurements: where the model fails");
    verdict(&mut r, &d, &v);
    r.text(
        "",
        &format!("Measurements: {}.", d.text("source").as_text()),
    );
    r.table(
        "Residual per channel",
        &[
            "channel",
            "residual RMS",
            "noise-floor RMS",
            "residual mean",
            "unit",
        ],
        (0..channels)
            .map(|k| {
                vec![
                    d.text(&format!("channels.{k}.channel")),
                    d.num(&format!("channels.{k}.residual_rms"), 4),
                    d.num(&format!("channels.{k}.noise_floor_rms"), 4),
                    d.num(&format!("channels.{k}.residual_mean"), 4),
                    d.text(&format!("channels.{k}.unit")),
                ]
            })
            .collect(),
    );
    r.table(
        "Navigation on the measured vs the model's increments (static segments)",
        &[
            "run",
            "duration (s)",
            "measured final (m)",
            "model final (m)",
            "difference RMS (m)",
        ],
        (0..nav.min(12))
            .map(|k| {
                vec![
                    d.text(&format!("navigation.{k}.run")),
                    d.num(&format!("navigation.{k}.duration_s"), 4),
                    d.num(&format!("navigation.{k}.measured_final_m"), 4),
                    d.num(&format!("navigation.{k}.model_final_m"), 4),
                    d.num(&format!("navigation.{k}.difference_rms_m"), 4),
                ]
            })
            .collect(),
    );
    // The mean residual per position against its noise floor shows the verdict (with a
    // diagnosis, before and after the fitted effects).
    figures_with_key(&mut r, dir, &MVM_FIGURES, "bias_by_position")?;
    r.write(dir)
}

/// The verdict: how many cells are flagged and the largest, and the channel whose residual
/// stands highest over its noise floor.
fn verdict(r: &mut Report, d: &Doc, v: &Value) {
    let f = |x: &Value, k: &str| x.pointer(k).and_then(Value::as_f64).unwrap_or(f64::NAN);
    let flagged = v
        .pointer("/flagged_cells")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let mut s = vec![
        d.count("flagged_cells"),
        words(" of "),
        d.count("cells"),
        words(" cells of channel × position × temperature × time are flagged (|z| > "),
        d.num("z_critical", 3),
        words(")"),
    ];
    let largest = (0..flagged.len()).max_by(|&a, &b| {
        f(&flagged[a], "/z")
            .abs()
            .total_cmp(&f(&flagged[b], "/z").abs())
    });
    match largest {
        Some(k) => {
            let c = &flagged[k];
            let t = |p: &str| c.pointer(p).and_then(Value::as_str).unwrap_or("");
            let place = [t("/position"), t("/orientation")]
                .into_iter()
                .filter(|x| !x.is_empty())
                .collect::<Vec<_>>()
                .join(" ");
            s.push(words(format!(
                "; the largest is {} at {place}, {:.0}-{:.0} °C: z = ",
                t("/channel"),
                f(c, "/temp_bin_c/0"),
                f(c, "/temp_bin_c/1")
            )));
            s.push(d.num(&format!("flagged_cells.{k}.z"), 3));
            s.push(words(", residual "));
            s.push(d.num(&format!("flagged_cells.{k}.residual"), 3));
            s.push(words(" against a noise floor of "));
            s.push(d.num(&format!("flagged_cells.{k}.noise_floor"), 3));
            s.push(words("."));
        }
        None => s.push(words(
            ": the model agrees with the data within the noise everywhere.",
        )),
    }
    r.verdict(s);
    let channels = v
        .pointer("/channels")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let ratio = |c: &Value| f(c, "/residual_rms") / f(c, "/noise_floor_rms");
    if let Some(k) =
        (0..channels.len()).max_by(|&a, &b| ratio(&channels[a]).total_cmp(&ratio(&channels[b])))
    {
        let c = &channels[k];
        let name = c.pointer("/channel").and_then(Value::as_str).unwrap_or("?");
        let unit = c.pointer("/unit").and_then(Value::as_str).unwrap_or("");
        r.verdict(vec![
            words(format!(
                "Highest residual over its noise floor: {name}, residual RMS "
            )),
            d.num(&format!("channels.{k}.residual_rms"), 4),
            words(" against "),
            d.num(&format!("channels.{k}.noise_floor_rms"), 4),
            words(format!(" {unit} (rins diagnose names the effect).")),
        ]);
    }
}
