//! The page of `rins compare --report DIR`: residual per channel, navigation on the measured vs
//! the model's increments, and the model-vs-measurement figures.

use std::path::{Path, PathBuf};

use anyhow::Result;
use serde::Serialize;

use super::page_parts::{MVM_FIGURES, figures, json};
use crate::html::{Doc, Report};

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
    figures(&mut r, dir, &MVM_FIGURES)?;
    r.write(dir)
}
