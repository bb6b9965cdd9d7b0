//! `rins diagnose`: rank the plant's effects that explain the residual of a model on measured
//! data; `--apply` writes the model with effects fitted, `--iterate` iterates to the floor. The work is in `rins_mvm` (figures in
//! `crate::diagnose`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rins_mvm::Effect;

use super::compare::{DataArgs, load_data, record_analysis};
use rins_mvm::Rows;
use rins_report::text::RenderText;

/// Arguments of `rins diagnose`.
#[derive(clap::Args, Debug)]
pub struct DiagnoseArgs {
    /// Model, data and analysis settings.
    #[command(flatten)]
    pub data: DataArgs,
    /// Add these effects (comma-separated or repeated: e.g. gyro.temperature_gradient_bias,
    /// or custom:NAME for a declared `[[sensor.gyro.custom]]` of the model or a term --discover
    /// proposes) to the model, fitted jointly with their parents (the constant of their kind,
    /// lower powers, a product's factors) on every axis each acts on; a coefficient is written
    /// only when the data determine it.
    #[arg(long, value_delimiter = ',', num_args = 1..)]
    pub apply: Vec<String>,
    /// After the catalogue, search a library of regressors built from the declared effects'
    /// signals (degree ≤ 2 products, position indicators) for what the catalogue lacks, and
    /// propose each find as a ready [[sensor.gyro.custom]] block (--apply custom:NAME adds it).
    #[arg(long)]
    pub discover: bool,
    /// Iterate to the floor: compare, rank (catalogue, declared, discovered), fit the accepted
    /// set jointly with its parents, compare again, until every channel is at its noise floor
    /// with no flagged cell or nothing more passes the gate. Writes the final model (--out) and
    /// the history (OUT with -history.json).
    #[arg(long, conflicts_with = "apply")]
    pub iterate: bool,
    /// Steps of --iterate at most.
    #[arg(
        long,
        default_value_t = 6,
        requires = "iterate",
        allow_negative_numbers = true
    )]
    pub max_steps: i64,
    /// Where --apply / --iterate write the new model (default: MODEL with -fitted, or
    /// -iterated, before the extension).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// `--max-steps`, checked: 1..=100 steps.
fn max_steps(a: &DiagnoseArgs) -> Result<usize> {
    super::args::whole("--max-steps", a.max_steps, 1, 100, "steps")
}

/// Ranks the candidate effects, writes the fitted model, figures and recording when asked for,
/// and prints the ranking.
pub fn run(a: &DiagnoseArgs) -> Result<()> {
    // A bad --max-steps fails before the data are read.
    max_steps(a)?;
    let (model, h, mut opts) = load_data(&a.data)?;
    if a.iterate {
        return iterate(a, &model, &h, &opts);
    }
    opts.diagnose = true;
    opts.discover = a.discover;
    // A bad name fails before the analysis; `custom:NAME` that the model does not declare is a
    // discovered term (discovery runs).
    for effect in &a.apply {
        if Effect::parse_in(&model, effect).is_some() {
            continue;
        }
        if effect.starts_with("custom:") {
            opts.discover = true;
            continue;
        }
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
    let an = rins_mvm::analyse(&model, &h, &opts);
    let report = &an.diagnosis.as_ref().expect("opts.diagnose is set").report;
    if !a.apply.is_empty() {
        let plain = rins_mvm::Options {
            diagnose: false,
            discover: false,
            apply: Vec::new(),
            ..opts.clone()
        };
        let applied = rins_mvm::apply::apply_with_parents(
            &model,
            &h,
            &plain,
            &a.apply,
            report.discovery.as_ref(),
        )
        .map_err(anyhow::Error::msg)?;
        write_applied(a, &applied, &h.info().source)?;
    }
    if a.data.report.is_some() || a.data.viz.rerun.is_some() {
        record_analysis(
            &a.data.viz,
            &an,
            an.predictions(),
            None,
            &h.info().source,
            &serde_json::to_string_pretty(report)?,
        )?;
    }
    if let Some(dir) = &a.data.report {
        for f in crate::diagnose::write_report(dir, &an)? {
            eprintln!("wrote {f}");
        }
        let channels: Vec<String> = report.residual_rms_before.keys().cloned().collect();
        let page =
            rins_report::html::results::diagnose(report, report.ranking.len(), &channels, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(report)?);
    } else {
        print!("{}", report.render_text());
    }
    Ok(())
}

/// `--iterate`: iterates to the floor, writes the final model, the history, the figures and
/// the page, and prints each step.
fn iterate(
    a: &DiagnoseArgs,
    model: &rins_plant::PlantConfig,
    h: &rins_mvm::RowCache,
    opts: &rins_mvm::Options,
) -> Result<()> {
    let it = rins_mvm::iterate(
        model,
        h,
        opts,
        &rins_mvm::IterateOptions {
            max_steps: max_steps(a)?,
            ..Default::default()
        },
    )
    .map_err(anyhow::Error::msg)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| suffixed_path(&a.data.model, "iterated"));
    let text = rins_mvm::apply::model_file(
        &it.model,
        &crate::diagnose::model_text(&a.data.model)?,
        &format!(
            "{} iterated to the floor on {} ({}): {}",
            a.data.model.display(),
            h.info().source,
            it.report.steps.len() - 1,
            it.report.stop
        ),
    )
    .map_err(anyhow::Error::msg)?;
    std::fs::write(&out, text).with_context(|| format!("cannot write {}", out.display()))?;
    eprintln!("wrote {}", out.display());
    let history = out.with_file_name(format!(
        "{}-history.json",
        out.file_stem()
            .map_or("model".into(), |s| s.to_string_lossy())
    ));
    let json = serde_json::to_string_pretty(&it.report)?;
    std::fs::write(&history, &json)
        .with_context(|| format!("cannot write {}", history.display()))?;
    eprintln!("wrote {}", history.display());
    if a.data.report.is_some() || a.data.viz.rerun.is_some() {
        record_analysis(
            &a.data.viz,
            &it.last,
            it.last.predictions(),
            Some(&it.report),
            &h.info().source,
            &json,
        )?;
    }
    if let Some(dir) = &a.data.report {
        for f in rins_report::iteration::write_figures(dir, &it.report)? {
            eprintln!("wrote {}", f.display());
        }
        let page = rins_report::html::results::iterate(&it.report, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.data.json {
        println!("{json}");
    } else {
        print!("{}", rins_report::iteration::render_text(&it.report));
    }
    Ok(())
}

/// `--apply`: writes the model file with the effects fitted and says what happened to every
/// coefficient.
fn write_applied(a: &DiagnoseArgs, applied: &rins_mvm::Applied, source: &str) -> Result<()> {
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| suffixed_path(&a.data.model, "fitted"));
    let names = a.apply.join(", ");
    let text = applied
        .model_file(
            &crate::diagnose::model_text(&a.data.model)?,
            &format!("{} with {names} fitted on {source}", a.data.model.display()),
        )
        .map_err(anyhow::Error::msg)?;
    std::fs::write(&out, text).with_context(|| format!("cannot write {}", out.display()))?;
    eprintln!(
        "wrote {} ({} coefficients written)",
        out.display(),
        applied.set.len()
    );
    for c in &applied.coefficients {
        match c.fate {
            rins_mvm::Fate::Written => eprintln!(
                "  {} = {} [{}, {}] (written; was {})",
                c.key,
                rins_report::iteration::number(c.fitted),
                rins_report::iteration::number(c.ci95.map(|x| x[0])),
                rins_report::iteration::number(c.ci95.map(|x| x[1])),
                rins_report::iteration::number(Some(c.model))
            ),
            _ => eprintln!(
                "  {} = {} (kept: {})",
                c.key,
                rins_report::iteration::number(Some(c.model)),
                c.reason
            ),
        }
    }
    if a.apply.iter().any(|n| n.starts_with("custom:")) {
        eprintln!(
            "  (the written values come from the joint fit with the parents on the plant's row-exact regressor; a discovery proposal's coefficient is the window estimate on its own, so they can differ)"
        );
    }
    Ok(())
}

/// MODEL with `-SUFFIX` before the extension (a built-in model is written as
/// NAME-SUFFIX.toml).
fn suffixed_path(model: &Path, suffix: &str) -> PathBuf {
    let stem = model.file_stem().map_or("model".into(), |s| {
        s.to_string_lossy().replace("builtin:", "")
    });
    model.with_file_name(format!("{stem}-{suffix}.toml"))
}
