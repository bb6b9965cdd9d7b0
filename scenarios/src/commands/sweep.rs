//! `rins sweep FILE`: a parameter sweep (docs/sweeps.md). Every point × seed runs through the
//! Monte Carlo engine with the uncompensated and the δβ-compensated navigator; the command
//! prints the table of the chosen outputs (median and 5–95 % over the seeds at each point) and
//! writes `sweep.json`, the per-seed table `sweep.csv` and `sweep.parquet`, a figure per
//! output (`sweep_<output>.svg` and `.png`), and with `--report DIR` the HTML page.

use std::path::PathBuf;

use anyhow::{Context, Result};

use rins_report::text::RenderText;
use rins_sweep::{SweepPlan, tables};

/// Arguments of `rins sweep`.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Sweep file (TOML; docs/sweeps.md).
    pub file: PathBuf,
    /// Output folder for sweep.json, sweep.csv, sweep.parquet and the figures.
    #[arg(long, default_value = "out/sweep")]
    pub out: PathBuf,
    /// Print the result as JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Write a self-contained HTML report (tables, figures, the command line) to DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
}

/// Loads and checks the sweep file, runs it with a progress bar, writes the outputs and
/// prints the table (or JSON).
pub fn run(a: &SweepArgs) -> Result<()> {
    let plan = SweepPlan::load(&a.file)?;
    super::create_dir(&a.out)?;
    let total = plan.samples_per_run() * (plan.points.len() * plan.seeds.len() * 2) as u64;
    let pb = crate::progress::bar(total, &plan.name);
    let r = rins_sweep::run(&plan, &|n| pb.inc(n))
        .with_context(|| format!("{}: running the sweep", plan.source))?;
    pb.finish_and_clear();
    let json = serde_json::to_string_pretty(&r)?;
    let path = a.out.join("sweep.json");
    std::fs::write(&path, &json).with_context(|| format!("cannot write {}", path.display()))?;
    tables::write_csv(&r, &a.out.join("sweep.csv"))?;
    tables::write_parquet(&r, &a.out.join("sweep.parquet"))?;
    rins_report::figures::sweep::write_sweep_figures(&r, &a.out)?;
    if a.json {
        println!("{json}");
    } else {
        print!("{}", r.render_text());
        println!(
            "  sweep.json, sweep.csv and sweep.parquet ({} rows: point x seed x navigator) and the figures in {}",
            tables::rows(&r),
            a.out.display()
        );
    }
    if let Some(dir) = &a.report {
        let page = rins_report::html::sweep::report(&r, &a.out, dir)?;
        eprintln!("report: {}", page.display());
    }
    Ok(())
}
