//! `rins campaign`: Section 4.1 / Figure 8, calibrations over the scenario's temperatures and a
//! third-order fit of δβ(T), saved as a compensation file.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rins_navigation::campaign::Campaign;

use super::calibrate::calibration_config;
use rins_report::figures::calibration::write_campaign_figure;
use rins_report::text::RenderText;
use rins_report::truth::CampaignReport;
use rins_scenario::file::Scenario;

/// Arguments of `rins campaign`.
#[derive(clap::Args, Debug)]
pub struct CampaignArgs {
    /// Scenario with a [campaign] section.
    pub scenario: PathBuf,
    /// Reference temperature of the fitted polynomial, deg C.
    #[arg(long, default_value_t = 25.0, allow_negative_numbers = true)]
    pub ref_temp_c: f64,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Output folder: campaign.json, dbeta-compensation.toml, fig8_dbeta_vs_temperature.svg.
    #[arg(long, default_value = "out/campaign")]
    pub out: PathBuf,
    /// Write a self-contained HTML report (figures, tables with the paper's values, the command
    /// line) to DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
}

/// Runs the campaign, writes its outputs and prints the runs and fits.
pub fn run(a: &CampaignArgs) -> Result<()> {
    let sc = Scenario::load(&a.scenario)?;
    let c = CampaignReport::new(run_campaign_from(&sc, a.ref_temp_c)?, &sc.plant);
    write_outputs(&c, &a.out)?;
    if let Some(dir) = &a.report {
        let page = rins_report::html::results::campaign(&c, c.campaign.runs.len(), &a.out, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&c)?);
        return Ok(());
    }
    print!("{}", c.campaign.render_text());
    println!(
        "  compensation file: {}",
        a.out.join("dbeta-compensation.toml").display()
    );
    Ok(())
}

/// The calibrations at the temperatures of the scenario's `[campaign]` and the δβ(T) fits.
pub fn run_campaign_from(sc: &Scenario, ref_temp_c: f64) -> Result<Campaign> {
    let camp = sc.campaign.as_ref().with_context(|| {
        format!(
            "{}: no [campaign] section (temps_c, or from_c/to_c/runs)",
            sc.source
        )
    })?;
    let cfg = calibration_config(sc, "coupled");
    Ok(rins_experiments::campaign::run_campaign(
        &sc.plant,
        &camp.temperatures_c(),
        &cfg,
        ref_temp_c,
    )?)
}

/// `campaign.json` (with the plant's δβ beside the fits), the compensation file
/// `dbeta-compensation.toml` and the Figure 8 counterpart in `out`.
pub fn write_outputs(report: &CampaignReport, out: &Path) -> Result<()> {
    super::create_dir(out)?;
    std::fs::write(
        out.join("campaign.json"),
        serde_json::to_string_pretty(report)?,
    )?;
    let c = &report.campaign;
    // Written as a scenario fragment: the plant loads it as a scenario (or paste the table into
    // one), the navigator with `rins paper table5 --compensation`.
    let mut gyro = toml::Table::new();
    gyro.insert(
        "position_bias".into(),
        toml::Value::try_from(c.compensation())?,
    );
    let mut sensor = toml::Table::new();
    sensor.insert("gyro".into(), toml::Value::Table(gyro));
    let mut t = toml::Table::new();
    t.insert("sensor".into(), toml::Value::Table(sensor));
    let header = "# Fitted position-dependent gyro bias delta-beta(T) from `rins campaign`: a scenario fragment.\n# The plant reads it as [sensor.gyro.position_bias]; `rins paper table5 --compensation FILE` compensates with it.\n";
    std::fs::write(
        out.join("dbeta-compensation.toml"),
        format!("{header}{}", toml::to_string_pretty(&t)?),
    )?;
    write_campaign_figure(c, out)
}
