//! `rins verify analytic|ins`: the analytic and closed-form INS verification reports.

use std::path::PathBuf;

use anyhow::Result;

use super::args::whole;
use super::emit_report;
use rins_report::figures::analytic::{write_checks_figure, write_cycle_figure};

/// The verification reports.
#[derive(clap::Subcommand, Debug)]
pub enum VerifyCommand {
    /// Closed-form static INS responses reproduced by the plant and navigator (Schuler,
    /// Foucault, 24 h, tilt from accelerometer bias, ARW Monte Carlo).
    Ins(InsArgs),
    /// Eq. 8 cancellation, Eq. 11 residual and Table 2 against the plant's kinematics.
    Analytic(AnalyticArgs),
}

/// Arguments of `rins verify ins`.
#[derive(clap::Args, Debug)]
pub struct InsArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Monte Carlo runs for the ARW check.
    #[arg(long, default_value_t = 64, allow_negative_numbers = true)]
    pub runs: i64,
    /// Write the checks figure (SVG and PNG) into this folder.
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Arguments of `rins verify analytic`.
#[derive(clap::Args, Debug)]
pub struct AnalyticArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Write the one-cycle φ(t) figure (Eq. 8, Eq. 11) and the checks figure into this folder.
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Runs one report, prints it, and fails when a check failed.
pub fn run(cmd: &VerifyCommand) -> Result<()> {
    match cmd {
        VerifyCommand::Analytic(a) => analytic(a),
        VerifyCommand::Ins(a) => ins(a),
    }
}

fn analytic(a: &AnalyticArgs) -> Result<()> {
    let r = rins_verification::report::AnalyticReport::run();
    if let Some(dir) = &a.figures {
        write_cycle_figure(dir)?;
        write_checks_figure(
            &dir.join("analytic_checks.svg"),
            "Analytic verification: each check against its limit",
            &r.checks,
        )?;
    }
    emit_report(
        &r,
        a.json,
        &r.to_text(),
        r.passed(),
        "analytic verification",
    )
}

fn ins(a: &InsArgs) -> Result<()> {
    let runs = whole("--runs", a.runs, 8, usize::MAX, "Monte Carlo runs")?;
    let r = rins_verification::ins::InsReport::run(runs);
    if let Some(dir) = &a.figures {
        write_checks_figure(
            &dir.join("ins_checks.svg"),
            "INS closed forms: each check against its limit",
            &r.checks,
        )?;
    }
    emit_report(
        &r,
        a.json,
        &r.to_text(),
        r.passed(),
        "INS closed-form verification",
    )
}
