//! `rins compare`: replay a model on measured logs and map where it fails. The work is in
//! `rins_mvm` (and the figures in `crate::diagnose`); this module reads the arguments, and the
//! data and model arguments it shares with `rins diagnose`.

use std::path::PathBuf;

use anyhow::Result;
use rins_mvm::{Analysis, Options, RowCache, Rows};
use rins_plant::PlantConfig;

use super::args::{RerunArgs, positive};
use rins_report::text::RenderText;

/// The model, the measurements and the analysis settings of `compare` and `diagnose`.
#[derive(clap::Args, Debug)]
pub struct DataArgs {
    /// Model: a scenario file (or builtin:NAME) whose plant is the model.
    #[arg(long)]
    pub model: PathBuf,
    /// Measurement file (docs/measurement-format.md): CSV, or Parquet (read by its content).
    #[arg(long)]
    pub data: PathBuf,
    /// Column map (TOML): the logger's column names and units -> the documented columns, and
    /// columns to ignore (docs/measurement-format.md, "Column map").
    #[arg(long)]
    pub map: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Write the SVG/PNG figures and a self-contained HTML report (DIR/report.html) into DIR.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Longest window the rows are summed over, s.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    pub window_s: f64,
    /// Temperature bin of the cell map, K.
    #[arg(long, default_value_t = 5.0, allow_negative_numbers = true)]
    pub temp_bin_k: f64,
    /// Time window of the cell map, s.
    #[arg(long, default_value_t = 3600.0, allow_negative_numbers = true)]
    pub time_window_s: f64,
    /// `--rerun DEST` and its bucket length.
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// Arguments of `rins compare`.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// Model, data and analysis settings.
    #[command(flatten)]
    pub data: DataArgs,
}

/// The model (at the data's site), the measured rows and the analysis options. The data are
/// streamed into a row cache (`rins_mvm::RowCache`): memory holds a few segments at a time,
/// whatever the file's length.
pub fn load_data(a: &DataArgs) -> Result<(PlantConfig, RowCache, Options)> {
    let sc = rins_scenario::file::Scenario::load(&a.model)?;
    // The replay represents a static carrier on a table only: a moving one is refused.
    rins_mvm::history::check_model(&sc.plant)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.model.display()))?;
    let map = a
        .map
        .as_deref()
        .map(|p| rins_mvm::colmap::ColumnMap::load(p, rins_mvm::measurement::classify))
        .transpose()?;
    // The flags are checked before the data file is read (which may take minutes).
    let (window_s, temp_bin_k, time_window_s) = (
        positive("--window-s", a.window_s)?,
        positive("--temp-bin-k", a.temp_bin_k)?,
        positive("--time-window-s", a.time_window_s)?,
    );
    let h = RowCache::read(&a.data, map.as_ref(), rins_mvm::row_cache::CHUNK_ROWS)?;
    let (model, note) = rins_mvm::with_site(&sc.plant, h.first_site());
    if let Some(n) = note {
        eprintln!("{}", n);
    }
    let opts = Options {
        window_s,
        temp_bin_k,
        time_window_s,
        column_map: map.map(|m| m.summary()),
        ..Default::default()
    };
    Ok((model, h, opts))
}

/// Replays the model on the data and prints (or writes) where it fails.
pub fn run(a: &CompareArgs) -> Result<()> {
    let (model, h, opts) = load_data(&a.data)?;
    let an = rins_mvm::analyse(&model, &h, &opts);
    let report = &an.comparison;
    record_analysis(
        &a.data.viz,
        &an,
        None,
        None,
        &h.info().source,
        &serde_json::to_string_pretty(report)?,
    )?;
    if let Some(dir) = &a.data.report {
        for f in crate::diagnose::write_report(dir, &an)? {
            eprintln!("wrote {f}");
        }
        let page = rins_report::html::results::compare(
            report,
            report.channels.len(),
            report.navigation.len(),
            dir,
        )?;
        eprintln!("report: {}", page.display());
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(report)?);
    } else {
        print!("{}", report.render_text());
    }
    Ok(())
}

/// `--rerun` of compare/diagnose: the residual windows, the fitted prediction, navigation.
pub fn record_analysis(
    viz: &RerunArgs,
    an: &Analysis,
    pred: Option<&[Vec<f64>]>,
    history: Option<&rins_mvm::IterationReport>,
    source: &str,
    text: &str,
) -> Result<()> {
    let target = viz.target()?;
    #[cfg(feature = "rerun")]
    if let Some(t) = &target {
        crate::recordings::record_diagnosis(t, an, pred, history, source, text)?;
        eprintln!("rerun: recorded -> {}", viz.dest());
    }
    #[cfg(not(feature = "rerun"))]
    let _ = (target, an, pred, history, source, text);
    Ok(())
}
