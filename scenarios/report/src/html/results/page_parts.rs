//! Pieces several result pages share: the result as JSON, the figures a page shows by file
//! stem (the one that shows the verdict first), the figures of `rins compare` and
//! `rins diagnose`, and a cell's text.

use std::path::Path;

use anyhow::Result;
use serde::Serialize;
use serde_json::Value;

use crate::html::{Cell, Report};

/// The result as the JSON `--json` prints, which every number of a page is looked up in.
pub(super) fn json<T: Serialize>(v: &T) -> Result<Value> {
    Ok(serde_json::to_value(v)?)
}

/// Adds `dir/<stem>.svg` for each (stem, caption) whose file exists: the one of stem `key` as
/// the figure that shows the verdict, directly after it ([`Report::key_figure`]), the others
/// where the page adds them.
pub(super) fn figures_with_key(
    r: &mut Report,
    dir: &Path,
    list: &[(&str, &str)],
    key: &str,
) -> Result<()> {
    for (stem, caption) in list {
        let f = dir.join(format!("{stem}.svg"));
        if !f.exists() {
            continue;
        }
        if *stem == key {
            r.key_figure(&f, caption)?;
        } else {
            r.figure(&f, caption)?;
        }
    }
    Ok(())
}

/// The figures of `rins compare` / `rins diagnose` with their captions.
pub(super) const MVM_FIGURES: [(&str, &str); 4] = [
    (
        "residual_vs_temperature",
        "Residual (measured - model) per window against the sensor temperature, Z-up and Z-down dots; with a diagnosis the fitted effects as dashed curves.",
    ),
    (
        "bias_by_position",
        "Mean residual per table position (categories) with the 95 % noise-floor bars, the model as given (grey) beside the model with the fitted effects (green).",
    ),
    (
        "allan_residual",
        "Allan deviation of the residual: white noise falls with slope -1/2; a flattening or a rise is an unmodelled effect.",
    ),
    (
        "navigation_error",
        "Horizontal error of static navigation on the measured increments (band and mean) and on the model's (dashed), first segments.",
    ),
];

impl Cell {
    /// The text of a text cell (a number's shown value otherwise).
    pub fn as_text(&self) -> String {
        match self {
            Cell::Text(t) => t.clone(),
            Cell::Json { value, sig, .. } | Cell::Paper(value, sig) => {
                crate::html::format_sig(*value, *sig)
            }
            Cell::Count { n, .. } => n.to_string(),
        }
    }
}
