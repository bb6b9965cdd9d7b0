//! `rins diagnose`: rank the plant's effects that explain the residual of a model on measured
//! data; `--apply` writes the model with one fitted. The work is in `rins_mvm` (figures in
//! `crate::diagnose`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rins_mvm::{Analysis, Effect};

use super::compare::{DataArgs, load_data, record_analysis};
use crate::report::RenderText;

/// Arguments of `rins diagnose`.
#[derive(clap::Args, Debug)]
pub struct DiagnoseArgs {
    /// Model, data and analysis settings.
    #[command(flatten)]
    pub data: DataArgs,
    /// Add this effect (e.g. gyro.temperature_gradient_bias, or custom:NAME for a declared
    /// `[[sensor.gyro.custom]]` of the model or a term --discover proposes), fitted on every
    /// axis it acts on, to the model.
    #[arg(long)]
    pub apply: Option<String>,
    /// After the catalogue, search a library of regressors built from the declared effects'
    /// signals (degree ≤ 2 products, position indicators) for what the catalogue lacks, and
    /// propose each find as a ready [[sensor.gyro.custom]] block (--apply custom:NAME adds it).
    #[arg(long)]
    pub discover: bool,
    /// Where --apply writes the new model (default: MODEL with -fitted before the extension).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Ranks the candidate effects, writes the fitted model, figures and recording when asked for,
/// and prints the ranking.
pub fn run(a: &DiagnoseArgs) -> Result<()> {
    let (model, h, mut opts) = load_data(&a.data)?;
    opts.diagnose = true;
    opts.discover = a.discover;
    // `custom:NAME` that the model does not declare: a discovered term (discovery runs).
    let mut discovered = None;
    if let Some(effect) = &a.apply {
        match Effect::parse_in(&model, effect) {
            Some(e) => opts.apply.push(e),
            None if effect.starts_with("custom:") => {
                opts.discover = true;
                discovered = Some(effect.trim_start_matches("custom:").to_string());
            }
            // A bad name fails before the analysis.
            None => {
                let names: Vec<String> = Effect::all()
                    .into_iter()
                    .chain(
                        rins_mvm::custom::declared(&model)
                            .into_iter()
                            .map(Effect::Custom),
                    )
                    .map(|e| e.name())
                    .collect();
                anyhow::bail!(
                    "--apply {effect:?}: not an effect of the catalogue or a declared effect of the model; one of {names:?} (or custom:NAME of a term --discover proposes)"
                );
            }
        }
    }
    let an = rins_mvm::analyse(&model, &h, &opts);
    let report = &an.diagnosis.as_ref().expect("opts.diagnose is set").report;
    if let Some(name) = &discovered {
        // The model with the proposal declared, then fitted like a declared effect.
        let disc = report.discovery.as_ref().expect("opts.discover is set");
        let with =
            rins_mvm::discover::with_proposal(&model, disc, name).map_err(anyhow::Error::msg)?;
        let effect = Effect::parse_in(&with, &format!("custom:{name}")).expect("declared above");
        let fitted = rins_mvm::analyse(
            &with,
            &h,
            &rins_mvm::Options {
                diagnose: false,
                discover: false,
                apply: vec![effect],
                ..opts.clone()
            },
        );
        write_applied(
            a,
            a.apply.as_deref().unwrap_or_default(),
            &fitted,
            &h.source,
        )?;
    } else if let Some(effect) = &a.apply {
        write_applied(a, effect, &an, &h.source)?;
    }
    if a.data.report.is_some() || a.data.viz.rerun.is_some() {
        record_analysis(
            &a.data.viz,
            &an,
            an.predictions(),
            &h.source,
            &serde_json::to_string_pretty(report)?,
        )?;
    }
    if let Some(dir) = &a.data.report {
        for f in crate::diagnose::write_report(dir, &an)? {
            eprintln!("wrote {f}");
        }
        let channels: Vec<String> = report.residual_rms_before.keys().cloned().collect();
        let page = crate::html::results::diagnose(report, report.ranking.len(), &channels, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(report)?);
    } else {
        print!("{}", report.render_text());
    }
    Ok(())
}

/// `--apply EFFECT`: writes the model file with the effect fitted on every axis.
fn write_applied(a: &DiagnoseArgs, effect: &str, an: &Analysis, source: &str) -> Result<()> {
    let applied = an
        .applied
        .clone()
        .expect("opts.apply is set")
        .map_err(anyhow::Error::msg)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| default_fitted_path(&a.data.model));
    let text = applied
        .model_file(
            &crate::diagnose::model_text(&a.data.model)?,
            &format!(
                "{} with {effect} fitted on {source}",
                a.data.model.display()
            ),
        )
        .map_err(anyhow::Error::msg)?;
    std::fs::write(&out, text).with_context(|| format!("cannot write {}", out.display()))?;
    eprintln!(
        "wrote {} ({} coefficients)",
        out.display(),
        applied.set.len()
    );
    for (k, v) in &applied.set {
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
