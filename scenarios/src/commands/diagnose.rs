//! `rins diagnose`: rank the plant's effects that explain the residual of a model on measured
//! data; `--apply` writes the model with one fitted. The work is in `crate::diagnose` and
//! `rins_verify::diagnosis`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rins_plant::PlantConfig;
use rins_verify::diagnosis::Analysis;
use rins_verify::diagnosis::replay::Effect;

use super::compare::{DataArgs, load_data, record_analysis};
use crate::report::RenderText;

/// Arguments of `rins diagnose`.
#[derive(clap::Args, Debug)]
pub struct DiagnoseArgs {
    /// Model, data and analysis settings.
    #[command(flatten)]
    pub data: DataArgs,
    /// Add this effect (e.g. gyro.temperature_gradient_bias), fitted on every axis, to the model.
    #[arg(long)]
    pub apply: Option<String>,
    /// Where --apply writes the new model (default: MODEL with -fitted before the extension).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Ranks the candidate effects, writes the fitted model, figures and recording when asked for,
/// and prints the ranking.
pub fn run(a: &DiagnoseArgs) -> Result<()> {
    let (model, h, opts) = load_data(&a.data)?;
    let (report, an, selected) = rins_verify::diagnosis::diagnose(&model, &h, opts);
    if let Some(effect) = &a.apply {
        apply(a, effect, &model, &an, &h.source)?;
    }
    if a.data.report.is_some() || a.data.viz.rerun.is_some() {
        let pred = rins_verify::diagnosis::predictions(&an, &selected);
        record_analysis(
            &a.data.viz,
            &an,
            Some(&pred),
            &h.source,
            &serde_json::to_string_pretty(&report)?,
        )?;
    }
    if let Some(dir) = &a.data.report {
        let pred = rins_verify::diagnosis::predictions(&an, &selected);
        let before = an.compare_report(&h.source, &an.zero_pred());
        let after = an.compare_report(&h.source, &pred);
        for f in crate::diagnose::write_report(dir, &an, Some(&pred), &before, Some(&after))? {
            eprintln!("wrote {f}");
        }
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.render_text());
    }
    Ok(())
}

/// `--apply EFFECT`: fits the effect on every axis and writes the model file with it.
fn apply(
    a: &DiagnoseArgs,
    effect: &str,
    model: &PlantConfig,
    an: &Analysis,
    source: &str,
) -> Result<()> {
    let e = Effect::parse(effect).with_context(|| {
        let names: Vec<String> = Effect::all().iter().map(|e| e.name()).collect();
        format!("--apply {effect:?}: not an effect of the catalogue; one of {names:?}")
    })?;
    let (cfg2, set) = rins_verify::diagnosis::apply(model, an, &[e]).map_err(anyhow::Error::msg)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| default_fitted_path(&a.data.model));
    let text = crate::diagnose::model_with_sensor(
        &crate::diagnose::model_text(&a.data.model)?,
        &cfg2,
        &format!(
            "{} with {effect} fitted on {source}",
            a.data.model.display()
        ),
    )?;
    std::fs::write(&out, text).with_context(|| format!("cannot write {}", out.display()))?;
    eprintln!("wrote {} ({} coefficients)", out.display(), set.len());
    for (k, v) in &set {
        eprintln!("  {k} = {v}");
    }
    Ok(())
}

/// MODEL with `-fitted` before the extension (a built-in model is written as NAME-fitted.toml).
fn default_fitted_path(model: &Path) -> PathBuf {
    let stem = model.file_stem().map_or("model".into(), |s| {
        s.to_string_lossy().replace("builtin:", "")
    });
    model.with_file_name(format!("{stem}-fitted.toml"))
}
