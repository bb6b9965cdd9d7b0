//! `rins paper`: the paper's headline job (analytic verification plus Table 4 with a few
//! seeds), and the paired studies `table4` and `table5` with what they share.

use std::path::PathBuf;

use anyhow::Result;

use super::args::RerunArgs;
use super::sea::{self, SeaArgs};
use super::table4::{self, Table4Args};
use super::table5::{self, Table5Args};

/// Arguments of `rins paper`: a study, or without one the headline job.
#[derive(clap::Args, Debug)]
pub struct PaperArgs {
    /// The study to run (without one: the headline job).
    #[command(subcommand)]
    pub which: Option<PaperCommand>,
    /// Headline job: seeds of Table 4 (the paper's 32 by default; fewer for a quick look).
    #[arg(long, default_value_t = 32, allow_negative_numbers = true)]
    pub runs: i64,
    /// Headline job: IMU intervals per navigator update (1 to 4; see `rins paper table4`).
    #[arg(long, default_value = "4", value_parser = super::paired_runs::parse_subsamples)]
    pub subsamples: rins_navigation::Subsamples,
    /// Output folder.
    #[arg(long, default_value = "out/paper")]
    pub out: PathBuf,
    /// Folder of the headline job's HTML report (default: the output folder): DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// `--rerun DEST` and its bucket length.
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// The paired studies.
#[derive(clap::Subcommand, Debug)]
pub enum PaperCommand {
    /// Section 3.1 / Table 4 / Figures 2-3: 1-week static 16-position navigation, uncompensated
    /// vs compensated, over several seeds, side by side with the paper.
    Table4(Table4Args),
    /// Section 4.2 / Table 5 / Figures 9-10: 7-day static navigation with the fitted
    /// delta-beta(T) compensated in real time, against the same run uncompensated.
    Table5(Table5Args),
    /// At sea: the 16-position week on a ship (10-15 kn, course changes, sea state 4-5)
    /// without and with azimuth isolation, delta-beta uncompensated/compensated, beside the
    /// static reference, over several seeds.
    Sea(SeaArgs),
}

/// Runs the study asked for, or the headline job.
pub fn run(a: &PaperArgs) -> Result<()> {
    match &a.which {
        Some(PaperCommand::Table4(t)) => table4::run(t),
        Some(PaperCommand::Table5(t)) => table5::run(t),
        Some(PaperCommand::Sea(t)) => sea::run(t),
        None => headline(a),
    }
}

/// The analytic verification, then Table 4 with the paper's 32 seeds (`--runs`); fails when
/// the verification failed.
fn headline(a: &PaperArgs) -> Result<()> {
    let report = rins_verification::report::AnalyticReport::run();
    println!(
        "== Analytic verification (Eq. 8, Eq. 11, Table 2) ==\n{}",
        report.to_text()
    );
    let t4 = Table4Args {
        runs: a.runs,
        days: 7.0,
        scenario: PathBuf::from("builtin:paper-16pos-week"),
        align: "truth".into(),
        subsamples: a.subsamples,
        json: false,
        out: a.out.clone(),
        report: None,
        viz: a.viz.clone(),
    };
    println!("== Section 3.1 / Table 4 ({} seeds) ==", t4.runs);
    let t4_report = table4::study(&t4)?;
    // The headline always writes its HTML report: the README's first command leaves it there.
    let mut page = rins_report::html::Report::new(
        "rins paper: analytic verification and Section 3.1 / Table 4",
    );
    rins_report::html::results::analytic_sections(&mut page, &report, report.checks.len())?;
    page.text(
        &format!("Section 3.1 / Table 4 ({} seeds)", t4.runs),
        "One week of static navigation of the 16-position RINS at 36.6 N 123.6 E with the Table 3 sensors, uncompensated and with delta-beta compensated.",
    );
    rins_report::html::results::paired_verdict(&mut page, &t4_report, false)?;
    rins_report::html::results::paired_sections(&mut page, &t4_report, false, &a.out)?;
    let path = page.write(a.report.as_ref().unwrap_or(&a.out))?;
    println!("  HTML report: {}", path.display());
    if !report.passed() {
        anyhow::bail!("analytic verification failed");
    }
    Ok(())
}
