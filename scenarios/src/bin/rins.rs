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
    /// The paper's experiments. Without a subcommand: the headline job, the analytic
    /// verification plus Table 4 with a few seeds (`--full`: 32 seeds).
    Paper {
        #[command(subcommand)]
        which: Option<PaperCommand>,
        #[command(flatten)]
        args: PaperArgs,
    },
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
    /// Headline job: run the full Monte Carlo (32 seeds) instead of 2.
    #[arg(long)]
    full: bool,
    /// Output folder.
    #[arg(long, default_value = "out/paper")]
    out: PathBuf,
}

#[derive(Subcommand)]
enum PaperCommand {
    /// Section 3.1 / Table 4 / Figures 2-3: 1-week static 16-position navigation, uncompensated
    /// vs compensated, over several seeds, side by side with the paper.
    Table4(Table4Args),
}

#[derive(Args)]
struct Table4Args {
    /// Seeds (each runs both cases; both cores are used).
    #[arg(long, default_value_t = 32)]
    runs: usize,
    /// Navigation time in days.
    #[arg(long, default_value_t = 7.0)]
    days: f64,
    /// Scenario (default: the built-in Section 3.1 scenario).
    #[arg(long, default_value = "builtin:paper-16pos-week")]
    scenario: PathBuf,
    /// Initial alignment: `truth` (perfect initial attitude, what the paper's figures match) or
    /// `self` (300 s coarse + 600 s fine on the static IMU, prepended to the scheme).
    #[arg(long, default_value = "truth", value_parser = ["self", "truth"])]
    align: String,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// Output folder for table4.json and the SVG figures.
    #[arg(long, default_value = "out/table4")]
    out: PathBuf,
}

#[derive(Subcommand)]
enum VerifyCommand {
    /// Closed-form static INS responses reproduced by the plant and navigator (Schuler,
    /// Foucault, 24 h, tilt from accelerometer bias, ARW Monte Carlo).
    Ins {
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Monte Carlo runs for the ARW check.
        #[arg(long, default_value_t = 64)]
        runs: usize,
    },
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
    let t4 = Table4Args {
        runs: if a.full { 32 } else { 2 },
        days: 7.0,
        scenario: PathBuf::from("builtin:paper-16pos-week"),
        align: "truth".into(),
        json: false,
        out: a.out.clone(),
    };
    println!("== Section 3.1 / Table 4 ({} seeds; --full for 32) ==", t4.runs);
    cmd_table4(&t4)?;
    if !report.passed() {
        anyhow::bail!("analytic verification failed");
    }
    Ok(())
}

fn cmd_table4(a: &Table4Args) -> Result<()> {
    if a.runs == 0 {
        anyhow::bail!("--runs: expected at least 1 seed, got 0");
    }
    if !(a.days > 0.0 && a.days <= 60.0) {
        anyhow::bail!("--days: expected a number in (0, 60], got {}", a.days);
    }
    let sc = Scenario::load(&a.scenario)?;
    let mut plant = sc.plant.clone();
    if a.align == "self" {
        // The IMU sits at its initial position while aligning; the scheme starts afterwards.
        plant.scheme.lead_dwell_s += 900.0;
    }
    let opt = rins_verify::paper::Table4Options {
        plant,
        runs: a.runs,
        duration_s: a.days * 86_400.0,
        nav: rins_nav::NavRunConfig {
            alignment: if a.align == "self" {
                rins_nav::Alignment::SelfAlign { coarse_s: 300.0, fine_s: 600.0 }
            } else {
                rins_nav::Alignment::Truth
            },
            ..rins_nav::NavRunConfig::default()
        },
    };
    let total = (2 * a.runs as u64 + 2) * (opt.duration_s * sc.plant.rate_hz) as u64;
    let pb = rins_scenarios::progress::bar(total, "table4");
    let r = rins_verify::paper::table4(&opt, &|n| pb.inc(n));
    pb.finish_and_clear();
    std::fs::create_dir_all(&a.out).with_context(|| format!("cannot create {}", a.out.display()))?;
    std::fs::write(a.out.join("table4.json"), serde_json::to_string_pretty(&r)?)?;
    write_table4_figures(&r, &a.out)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", r.to_text());
        println!("  figures and table4.json in {}", a.out.display());
    }
    Ok(())
}

fn write_table4_figures(r: &rins_verify::paper::Table4Report, out: &std::path::Path) -> Result<()> {
    use rins_scenarios::plots::{Line, Panel, write_svg};
    use plotters::style::RGBColor;
    const UNC: RGBColor = RGBColor(200, 40, 40);
    const COMP: RGBColor = RGBColor(30, 90, 200);
    for (series, tag, what) in [(&r.first_seed, "", "first seed"), (&r.noise_free_series, "_noise_free", "noise-free")] {
        let pts = |recs: &[rins_nav::NavRecord], f: &dyn Fn(&rins_nav::NavRecord) -> f64| -> Vec<(f64, f64)> {
            recs.iter().map(|x| (x.t_s / 3600.0, f(x))).collect()
        };
        let pair = |f: &dyn Fn(&rins_nav::NavRecord) -> f64| {
            vec![
                Line { label: "uncompensated", points: pts(&series.uncompensated, f), color: UNC },
                Line { label: "compensated", points: pts(&series.compensated, f), color: COMP },
            ]
        };
        let att = ["East", "North", "Up"]
            .iter()
            .enumerate()
            .map(|(k, n)| Panel { title: format!("{n}-axis attitude error"), y_label: "deg", lines: pair(&|x| x.att_err_rad[k].to_degrees()) })
            .collect::<Vec<_>>();
        write_svg(&out.join(format!("fig2_attitude_error{tag}.svg")), &format!("Figure 2 counterpart: attitude error ({what})"), "time (h)", &att)?;
        let nm = rins_nav::errors::nmi;
        let pos = vec![
            Panel { title: "Latitude error".into(), y_label: "nmi", lines: pair(&|x| nm(x.north_m)) },
            Panel { title: "Longitude error".into(), y_label: "nmi", lines: pair(&|x| nm(x.east_m)) },
            Panel { title: "Horizontal error and tRMS (Eq. 20)".into(), y_label: "nmi", lines: {
                let mut l = pair(&|x| nm(x.horizontal_m));
                l.push(Line { label: "tRMS uncompensated", points: pts(&series.uncompensated, &|x| nm(x.trms_m)), color: RGBColor(240, 150, 150) });
                l.push(Line { label: "tRMS compensated", points: pts(&series.compensated, &|x| nm(x.trms_m)), color: RGBColor(140, 170, 240) });
                l
            } },
        ];
        write_svg(&out.join(format!("fig3_position_error{tag}.svg")), &format!("Figure 3 counterpart: position error ({what})"), "time (h)", &pos)?;
    }
    Ok(())
}

/// Prints a verification report as JSON or text and fails when a check failed.
fn emit_report<T: serde::Serialize>(report: &T, json: bool, text: &str, passed: bool, what: &str) -> Result<()> {
    if json {
        println!("{}", serde_json::to_string_pretty(report)?);
    } else {
        print!("{text}");
    }
    if !passed {
        anyhow::bail!("{what} failed");
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
        Command::Paper { which: None, args } => cmd_paper(&args),
        Command::Paper { which: Some(PaperCommand::Table4(a)), .. } => cmd_table4(&a),
        Command::Verify(VerifyCommand::Analytic { json }) => {
            let r = rins_verify::report::AnalyticReport::run();
            emit_report(&r, json, &r.to_text(), r.passed(), "analytic verification")
        }
        Command::Verify(VerifyCommand::Ins { json, runs }) => {
            if runs < 8 {
                anyhow::bail!("--runs: expected at least 8 Monte Carlo runs, got {runs}");
            }
            let r = rins_verify::ins::InsReport::run(runs);
            emit_report(&r, json, &r.to_text(), r.passed(), "INS closed-form verification")
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
