//! `rins paper`: the paper's headline job (analytic verification plus Table 4 with a few
//! seeds), and the paired studies `table4` and `table5` with what they share.

use std::path::{Path, PathBuf};

use anyhow::Result;
use rins_plant::message::Num;
use rins_verify::paper::{Table4Options, Table4Report};

use super::args::{RerunArgs, whole};
use super::sea::{self, SeaArgs};
use super::table4::{self, Table4Args};
use super::table5::{self, Table5Args};
use crate::figures::paper::write_table4_figures;
use crate::file::Scenario;

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
    #[arg(long, default_value = "4", value_parser = super::table4::parse_subsamples)]
    pub subsamples: rins_nav::Subsamples,
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
    let report = rins_verify::report::AnalyticReport::run();
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
    let mut page =
        crate::html::Report::new("rins paper: analytic verification and Section 3.1 / Table 4");
    crate::html::results::analytic_sections(&mut page, &report, report.checks.len())?;
    page.text(
        &format!("Section 3.1 / Table 4 ({} seeds)", t4.runs),
        "One week of static navigation of the 16-position RINS at 36.6 N 123.6 E with the Table 3 sensors, uncompensated and with delta-beta compensated.",
    );
    crate::html::results::paired_verdict(&mut page, &t4_report, false)?;
    crate::html::results::paired_sections(&mut page, &t4_report, false, &a.out)?;
    let path = page.write(a.report.as_ref().unwrap_or(&a.out))?;
    println!("  HTML report: {}", path.display());
    if !report.passed() {
        anyhow::bail!("analytic verification failed");
    }
    Ok(())
}

/// Checks `--runs` and `--days` of the paired paper runs; returns the number of seeds.
pub fn check_runs_days(runs: i64, days: f64) -> Result<usize> {
    let runs = whole("--runs", runs, 1, usize::MAX, "seed")?;
    if !(days > 0.0 && days <= 60.0) {
        anyhow::bail!("--days: expected a number in (0, 60], got {}", Num(days));
    }
    Ok(runs)
}

/// Runs the paired uncompensated/compensated study with a progress bar and writes
/// `<name>.json` and the figures to `out` (and the Rerun recording when asked for).
pub fn run_paired(
    opt: &Table4Options,
    name: &str,
    out: &Path,
    sc: &Scenario,
    viz: &RerunArgs,
) -> Result<Table4Report> {
    let target = viz.target()?;
    let total = (2 * opt.runs as u64 + 2) * (opt.duration_s * opt.plant.rate_hz) as u64;
    let pb = crate::progress::bar(total, name);
    let r = rins_verify::paper::table4(opt, &|n| pb.inc(n));
    pb.finish_and_clear();
    super::create_dir(out)?;
    std::fs::write(
        out.join(format!("{name}.json")),
        serde_json::to_string_pretty(&r)?,
    )?;
    let figures = if name == "table5" {
        ["Figure 9", "Figure 10"]
    } else {
        ["Figure 2", "Figure 3"]
    };
    write_table4_figures(&r, out, figures)?;
    #[cfg(feature = "rerun")]
    if let Some(t) = &target {
        let text = if name == "table5" {
            r.to_text_table5()
        } else {
            crate::report::RenderText::render_text(&r)
        };
        crate::figures::rerun::record_paired(
            t,
            viz.rerun_bucket_s,
            sc,
            &opt.plant,
            opt.duration_s,
            &r,
            &text,
        )?;
        eprintln!("rerun: recorded -> {}", viz.dest());
    }
    #[cfg(not(feature = "rerun"))]
    let _ = (target, sc);
    Ok(r)
}
