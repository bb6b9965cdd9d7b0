//! `rins paper table5`: Section 4.2 / Table 5 / Figures 9-10.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use super::args::RerunArgs;
use super::campaign::{run_campaign_from, write_outputs};
use super::paired_runs::{check_runs_days, run_paired};
use rins_report::truth::CampaignReport;
use rins_scenario::file::Scenario;

/// Arguments of `rins paper table5`.
#[derive(clap::Args, Debug)]
pub struct Table5Args {
    /// Compensation file from `rins campaign` (default: run the 37-run campaign first).
    #[arg(long)]
    pub compensation: Option<PathBuf>,
    /// Seeds (both cases each, common random numbers).
    #[arg(long, default_value_t = 4, allow_negative_numbers = true)]
    pub runs: i64,
    /// Navigation time in days.
    #[arg(long, default_value_t = 7.0, allow_negative_numbers = true)]
    pub days: f64,
    /// Scenario of the static test.
    #[arg(long, default_value = "builtin:paper-static-week")]
    pub scenario: PathBuf,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Write a self-contained HTML report (figures, tables with the paper's values, the command
    /// line) to DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// Output folder.
    #[arg(long, default_value = "out/table5")]
    pub out: PathBuf,
    /// `--rerun DEST` and its bucket length.
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// 7-day static navigation with the fitted δβ(T) compensated in real time, against the same
/// run uncompensated.
pub fn run(a: &Table5Args) -> Result<()> {
    let runs = check_runs_days(a.runs, a.days)?;
    let comp = match &a.compensation {
        Some(path) => read_compensation(path)?,
        None => {
            eprintln!("no --compensation given: running the 37-run campaign first");
            let camp = Scenario::load(Path::new("builtin:campaign-37"))?;
            let c = CampaignReport::new(run_campaign_from(&camp, 25.0)?, &camp.plant);
            write_outputs(&c, &a.out.join("campaign"))?;
            c.campaign.compensation()
        }
    };
    let sc = Scenario::load(&a.scenario)?;
    let opt = rins_verification::paper::Table4Options {
        plant: sc.plant.clone(),
        runs,
        duration_s: a.days * 86_400.0,
        nav: rins_experiments::NavRunConfig::default(),
        compensation: Some(comp),
    };
    let r = run_paired(&opt, "table5", &a.out, &sc, &a.viz)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", r.to_text_table5());
        println!(
            "  figures (Figures 9-10 counterparts: fig3_position_error*.svg) and table5.json in {}",
            a.out.display()
        );
    }
    if let Some(dir) = &a.report {
        let page = rins_report::html::results::paired(&r, true, &a.out, dir)?;
        eprintln!("report: {}", page.display());
    }
    Ok(())
}

/// The compensation of a file from `rins campaign`: a scenario fragment whose
/// `[sensor.gyro.position_bias]` is the fitted δβ(T).
fn read_compensation(path: &Path) -> Result<rins_plant::effects::gyro::PositionBiasSpec> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let sc = Scenario::from_toml(&text, &path.display().to_string())?;
    let pb = sc.plant.sensor.gyro.position_bias;
    if !pb.enabled {
        anyhow::bail!(
            "{}: expected an enabled [sensor.gyro.position_bias] table (from `rins campaign`)",
            path.display()
        );
    }
    Ok(pb)
}
