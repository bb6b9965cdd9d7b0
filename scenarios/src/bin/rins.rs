//! `rins`: run scenarios of the rotating RLG INS plant and verify them.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use rins_scenarios::file::{BUILTIN, Scenario};
use rins_scenarios::sinks::CsvSink;
use rins_scenarios::{Sink, run};

#[derive(Parser)]
#[command(name = "rins", version, about = "Co-simulation plant model of a dual-axis rotating RLG inertial navigation system")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario and write the IMU stream as CSV.
    Run(RunArgs),
    /// Verification reports.
    #[command(subcommand)]
    Verify(VerifyCommand),
    /// The paper's headline experiment (Section 3.1, 16-position 1-week static RINS) with its
    /// verification report. Runs a shortened default; `--full` runs the whole week.
    Paper(PaperArgs),
    /// List the built-in scenarios, or print one.
    Scenarios {
        /// Print this built-in scenario's TOML.
        name: Option<String>,
    },
}

#[derive(Args)]
struct Overrides {
    /// Override `run.seed`.
    #[arg(long)]
    seed: Option<u64>,
    /// Override `scenario.duration_s`.
    #[arg(long)]
    duration_s: Option<f64>,
    /// Override `run.rate_hz`.
    #[arg(long)]
    rate_hz: Option<f64>,
}

#[derive(Args)]
struct RunArgs {
    /// Scenario file, or `builtin:NAME` (see `rins scenarios`).
    scenario: PathBuf,
    /// Output folder (created).
    #[arg(long, default_value = "out")]
    out: PathBuf,
    #[command(flatten)]
    overrides: Overrides,
}

#[derive(Args)]
struct PaperArgs {
    /// Simulate the full week (default: one day).
    #[arg(long)]
    full: bool,
    /// Output folder.
    #[arg(long, default_value = "out/paper")]
    out: PathBuf,
}

#[derive(Subcommand)]
enum VerifyCommand {
    /// Eq. 8 cancellation, Eq. 11 residual and Table 2 against the plant's kinematics.
    Analytic {
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

/// Loads a scenario and applies command-line overrides, re-validating the result.
fn load(path: &std::path::Path, o: &Overrides) -> Result<Scenario> {
    let mut sc = Scenario::load(path)?;
    if let Some(s) = o.seed {
        sc.plant.seed = s;
    }
    if let Some(d) = o.duration_s {
        sc.meta.duration_s = d;
    }
    if let Some(r) = o.rate_hz {
        sc.plant.rate_hz = r;
    }
    sc.validate(None).context("after applying command-line overrides")?;
    Ok(sc)
}

fn cmd_run(a: &RunArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    std::fs::create_dir_all(&a.out).with_context(|| format!("cannot create {}", a.out.display()))?;
    let resolved = toml::to_string_pretty(&sc.plant).context("serialising the resolved configuration")?;
    std::fs::write(a.out.join("resolved-plant.toml"), resolved)?;
    let mut sinks: Vec<Box<dyn Sink>> = Vec::new();
    if sc.outputs.csv {
        sinks.push(Box::new(CsvSink::create(&a.out.join("imu.csv"), sc.outputs, &sc.plant)?));
    }
    let mut refs: Vec<&mut dyn Sink> = sinks.iter_mut().map(|b| b.as_mut() as &mut dyn Sink).collect();
    let n = sc.samples();
    let summary = run(&sc, n, &mut refs)?;
    eprintln!(
        "{}: {} samples ({} s simulated) in {:.2} s, {:.1} ns/sample -> {}",
        sc.meta.name,
        summary.samples,
        sc.meta.duration_s,
        summary.wall_s,
        summary.wall_s * 1e9 / summary.samples.max(1) as f64,
        a.out.display()
    );
    Ok(())
}

fn cmd_paper(a: &PaperArgs) -> Result<()> {
    let report = rins_verify::report::AnalyticReport::run();
    println!("== Analytic verification (Eq. 8, Eq. 11, Table 2) ==\n{}", report.to_text());
    let run_args = RunArgs {
        scenario: PathBuf::from("builtin:paper-16pos-week"),
        out: a.out.clone(),
        overrides: Overrides { seed: None, duration_s: if a.full { None } else { Some(86_400.0) }, rate_hz: None },
    };
    println!("== Headline scenario: {} ==", if a.full { "1 week" } else { "1 day (use --full for the week)" });
    cmd_run(&run_args)?;
    println!("IMU stream written to {}/imu.csv", a.out.display());
    if !report.passed() {
        anyhow::bail!("analytic verification failed");
    }
    Ok(())
}

fn main() -> std::process::ExitCode {
    match dispatch(Cli::parse()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            // The chain, without the backtrace anyhow adds when RUST_BACKTRACE is set.
            eprintln!("error: {e}");
            for cause in e.chain().skip(1) {
                eprintln!("  caused by: {cause}");
            }
            std::process::ExitCode::FAILURE
        }
    }
}

fn dispatch(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Run(a) => cmd_run(&a),
        Command::Paper(a) => cmd_paper(&a),
        Command::Verify(VerifyCommand::Analytic { json }) => {
            let r = rins_verify::report::AnalyticReport::run();
            if json {
                println!("{}", serde_json::to_string_pretty(&r)?);
            } else {
                print!("{}", r.to_text());
            }
            if !r.passed() {
                anyhow::bail!("analytic verification failed");
            }
            Ok(())
        }
        Command::Scenarios { name: None } => {
            for (n, text) in BUILTIN {
                let sc = Scenario::from_toml(text, n)?;
                println!("builtin:{n:<22} {}", sc.meta.description);
            }
            Ok(())
        }
        Command::Scenarios { name: Some(n) } => {
            let n = n.strip_prefix("builtin:").unwrap_or(&n);
            let (_, text) = BUILTIN.iter().find(|(b, _)| *b == n).with_context(|| format!("no built-in scenario {n:?}; see `rins scenarios`"))?;
            print!("{text}");
            Ok(())
        }
    }
}
