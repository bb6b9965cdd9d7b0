//! `rins calibrate`: Section 3.2, the Z-up and Z-down system-level indirect calibration.

use std::path::PathBuf;

use anyhow::Result;
use rins_navigation::calibration::{CalibrationConfig, Estimator};

use rins_report::figures::calibration::write_calibration_figure;
use rins_report::text::{CalibrationRun, RenderText};
use rins_report::truth::CalibrationReport;
use rins_scenario::file::Scenario;

/// Arguments of `rins calibrate`.
#[derive(clap::Args, Debug)]
pub struct CalibrateArgs {
    /// Scenario (its plant is calibrated; scheme.lead_dwell_s is the alignment time and
    /// scheme.dwell_s the navigation time in each position).
    pub scenario: PathBuf,
    /// Drift estimator: `coupled` (Schuler, Earth-rate and Coriolis couplings removed) or
    /// `paper` (Eq. 13-15 as printed).
    #[arg(long, default_value = "coupled", value_parser = ["coupled", "paper"])]
    pub estimator: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Output folder: calibration.json and calibration_beta.svg/.png.
    #[arg(long, default_value = "out/calibrate")]
    pub out: PathBuf,
    /// Write a self-contained HTML report (figures, tables with the paper's values, the command
    /// line) to DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
}

/// Calibrates the scenario's plant (Fig. 4-5, Eq. 16-19), writes `calibration.json` (with the
/// plant's δβ beside the estimate) and the figure, and prints β at each position and
/// δβ = β_down − β_up.
pub fn run(a: &CalibrateArgs) -> Result<()> {
    let sc = Scenario::load(&a.scenario)?;
    let cfg = calibration_config(&sc, &a.estimator);
    let r = CalibrationReport::new(
        rins_experiments::calibration::calibrate(&sc.plant, &cfg)?,
        &sc.plant,
    );
    super::create_dir(&a.out)?;
    std::fs::write(
        a.out.join("calibration.json"),
        serde_json::to_string_pretty(&r)?,
    )?;
    write_calibration_figure(&r.calibration, &a.out)?;
    if let Some(dir) = &a.report {
        let page = rins_report::html::results::calibration(&r, &a.estimator, &a.out, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    let text = CalibrationRun {
        result: &r.calibration,
        truth: Some(&r.truth),
        estimator: &a.estimator,
        segment_s: cfg.segment_s,
    };
    print!("{}", text.render_text());
    Ok(())
}

/// Calibration timing from a scenario: lead dwell = alignment, dwell = time in each position.
pub fn calibration_config(sc: &Scenario, estimator: &str) -> CalibrationConfig {
    let lead = sc.plant.scheme.lead_dwell_s;
    let alignment = if lead > 0.0 {
        let coarse = (lead / 4.0).min(120.0);
        rins_navigation::Alignment::SelfAlign {
            coarse_s: coarse,
            fine_s: lead - coarse,
        }
    } else {
        rins_navigation::Alignment::Truth
    };
    CalibrationConfig {
        estimator: if estimator == "paper" {
            Estimator::Paper
        } else {
            Estimator::Coupled
        },
        alignment,
        segment_s: sc.plant.scheme.dwell_s,
        ..CalibrationConfig::default()
    }
}
