//! `rins`: run scenarios of the rotating RLG INS plant and verify them.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use rins_scenarios::file::{BUILTIN, Scenario};
use rins_scenarios::sinks::CsvSink;
use rins_scenarios::{Sink, run};

#[derive(Parser)]
#[command(
    name = "rins",
    version,
    about = "Co-simulation plant model of a dual-axis rotating RLG inertial navigation system"
)]
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
    /// Section 3.2: Z-up and Z-down system-level indirect calibration (Fig. 4-5, Eq. 16-19),
    /// estimating beta at each position and delta-beta = beta_down - beta_up.
    Calibrate(CalibrateArgs),
    /// Section 4.1 / Figure 8: calibrations over the scenario's [campaign] temperatures, a
    /// third-order fit of delta-beta(T) per axis, saved as a compensation file.
    Campaign(CampaignArgs),
    /// The plant as FMI 2.0 / 3.0 co-simulation FMUs: package them, or run one through a scenario.
    #[command(subcommand)]
    Fmu(FmuCommand),
    /// Model vs measurements: replay MODEL on the measured history and show where it fails (a
    /// map of channel x position x temperature x time, each cell in units of its noise floor).
    Compare(CompareArgs),
    /// Rank the plant's candidate effects that explain the residual of MODEL on DATA; with
    /// --apply EFFECT, write MODEL with that effect added and fitted.
    Diagnose(DiagnoseArgs),
    /// Simulate a measurement log from a scenario (one run per [campaign] temperature when the
    /// scenario has one), in the measurement format: test data with known effects.
    Measure(MeasureArgs),
    /// Serve the plant over iceoryx2 shared memory to navigation software (docs/transport.md).
    #[cfg(feature = "transport")]
    Serve(ServeArgs),
    /// The reference navigator as a separate process, consuming a served IMU stream.
    #[cfg(feature = "transport")]
    Nav(NavArgs),
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
    /// Also write figures of the run (SVG and PNG) into the output folder.
    #[arg(long)]
    figures: bool,
    /// With --rerun: run the reference navigator (aligned to the truth) alongside and record its
    /// attitude, velocity and position errors and tRMS.
    #[arg(long)]
    nav: bool,
    #[command(flatten)]
    overrides: Overrides,
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
}

#[derive(Args)]
struct PaperArgs {
    /// Headline job: run the full Monte Carlo (32 seeds) instead of 2.
    #[arg(long)]
    full: bool,
    /// Output folder.
    #[arg(long, default_value = "out/paper")]
    out: PathBuf,
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
}

#[derive(Args)]
struct CalibrateArgs {
    /// Scenario (its plant is calibrated; scheme.lead_dwell_s is the alignment time and
    /// scheme.dwell_s the navigation time in each position).
    scenario: PathBuf,
    /// Drift estimator: `coupled` (Schuler, Earth-rate and Coriolis couplings removed) or
    /// `paper` (Eq. 13-15 as printed).
    #[arg(long, default_value = "coupled", value_parser = ["coupled", "paper"])]
    estimator: String,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Output folder: calibration.json and calibration_beta.svg/.png.
    #[arg(long, default_value = "out/calibrate")]
    out: PathBuf,
}

#[derive(Args)]
struct CampaignArgs {
    /// Scenario with a [campaign] section.
    scenario: PathBuf,
    /// Reference temperature of the fitted polynomial, deg C.
    #[arg(long, default_value_t = 25.0)]
    ref_temp_c: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Output folder: campaign.json, dbeta-compensation.toml, fig8_dbeta_vs_temperature.svg.
    #[arg(long, default_value = "out/campaign")]
    out: PathBuf,
}

#[derive(Args)]
struct DataArgs {
    /// Model: a scenario file (or builtin:NAME) whose plant is the model.
    #[arg(long)]
    model: PathBuf,
    /// Measurement file (docs/measurement-format.md).
    #[arg(long)]
    data: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write SVG figures into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Longest window the rows are summed over, s.
    #[arg(long, default_value_t = 30.0)]
    window_s: f64,
    /// Temperature bin of the cell map, K.
    #[arg(long, default_value_t = 5.0)]
    temp_bin_k: f64,
    /// Time window of the cell map, s.
    #[arg(long, default_value_t = 3600.0)]
    time_window_s: f64,
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
}

#[derive(Args)]
struct CompareArgs {
    #[command(flatten)]
    data: DataArgs,
}

#[derive(Args)]
struct DiagnoseArgs {
    #[command(flatten)]
    data: DataArgs,
    /// Add this effect (e.g. gyro.temperature_gradient_bias), fitted on every axis, to the model.
    #[arg(long)]
    apply: Option<String>,
    /// Where --apply writes the new model (default: MODEL with -fitted before the extension).
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(Args)]
struct MeasureArgs {
    /// Scenario to simulate.
    scenario: PathBuf,
    /// Output CSV.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    overrides: Overrides,
}

#[cfg(feature = "transport")]
#[derive(Args)]
struct ServeArgs {
    /// Scenario to serve.
    scenario: PathBuf,
    /// Session name (letters, digits, '-', '_'): services rins/<session>/imu, cmd, nav.
    #[arg(long, default_value = "default")]
    session: String,
    /// `lockstep` (deterministic) or `free` (as fast as the navigator consumes, or paced).
    #[arg(long, default_value = "lockstep", value_parser = ["lockstep", "free"])]
    mode: String,
    /// Pace at this real-time factor (1 = real time, 10 = ten times faster than real time).
    #[arg(long)]
    pace: Option<f64>,
    /// Records per message, 1-64.
    #[arg(long, default_value_t = 64)]
    batch: usize,
    /// Seconds to wait for a navigator.
    #[arg(long, default_value_t = 30.0)]
    peer_timeout_s: f64,
    /// When the navigator dies, wait for a new one and resend from the first unacknowledged batch.
    #[arg(long)]
    wait_for_restart: bool,
    #[command(flatten)]
    overrides: Overrides,
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
}

#[cfg(feature = "transport")]
#[derive(Args)]
struct NavArgs {
    /// Session to connect to.
    #[arg(long)]
    connect: String,
    /// The scenario being served (site, mount and rate of the plant).
    scenario: PathBuf,
    /// Do not acknowledge batches (for a free-running plant).
    #[arg(long)]
    no_ack: bool,
    /// Command the table after batch SEQ: SEQ:OUTER_DEG:INNER_DEG:RATE_DPS (repeatable).
    #[arg(long)]
    command_after: Vec<String>,
    /// Seconds without a plant before giving up.
    #[arg(long, default_value_t = 30.0)]
    peer_timeout_s: f64,
    #[command(flatten)]
    overrides: Overrides,
}

#[derive(Subcommand)]
enum FmuCommand {
    /// Write RinsImu.fmu (FMI 2.0) and RinsImu3.fmu (FMI 3.0).
    Build {
        /// Output folder.
        #[arg(long, default_value = "out/fmu")]
        out: PathBuf,
        /// Folder holding librins_fmi2.so and librins_fmi3.so (default: next to this executable).
        #[arg(long)]
        lib_dir: Option<PathBuf>,
    },
    /// Run an FMI 2.0 FMU through a scenario, one communication step per IMU sample, writing
    /// the same imu.csv as `rins run`.
    Run {
        /// The .fmu file.
        fmu: PathBuf,
        /// Scenario file, or `builtin:NAME`.
        scenario: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "out/fmu-run")]
        out: PathBuf,
        /// Also write the run's figures (SVG and PNG) into the output folder.
        #[arg(long)]
        figures: bool,
        #[command(flatten)]
        overrides: Overrides,
    },
}

#[derive(Subcommand)]
enum PaperCommand {
    /// Section 3.1 / Table 4 / Figures 2-3: 1-week static 16-position navigation, uncompensated
    /// vs compensated, over several seeds, side by side with the paper.
    Table4(Table4Args),
    /// Section 4.2 / Table 5 / Figures 9-10: 7-day static navigation with the fitted
    /// delta-beta(T) compensated in real time, against the same run uncompensated.
    Table5(Table5Args),
}

#[derive(Args)]
struct Table5Args {
    /// Compensation file from `rins campaign` (default: run the 37-run campaign first).
    #[arg(long)]
    compensation: Option<PathBuf>,
    /// Seeds (both cases each, common random numbers).
    #[arg(long, default_value_t = 4)]
    runs: usize,
    /// Navigation time in days.
    #[arg(long, default_value_t = 7.0)]
    days: f64,
    /// Scenario of the static test.
    #[arg(long, default_value = "builtin:paper-static-week")]
    scenario: PathBuf,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Output folder.
    #[arg(long, default_value = "out/table5")]
    out: PathBuf,
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
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
    #[command(flatten)]
    viz: rins_scenarios::viz::RerunArgs,
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
        /// Write the checks figure (SVG and PNG) into this folder.
        #[arg(long)]
        figures: Option<PathBuf>,
    },
    /// Eq. 8 cancellation, Eq. 11 residual and Table 2 against the plant's kinematics.
    Analytic {
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Write the one-cycle φ(t) figure (Eq. 8, Eq. 11) and the checks figure into this folder.
        #[arg(long)]
        figures: Option<PathBuf>,
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
    sc.validate(None)
        .context("after applying command-line overrides")?;
    Ok(sc)
}

fn cmd_run(a: &RunArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let target = a.viz.target()?;
    if a.nav && target.is_none() {
        anyhow::bail!(
            "--nav records the reference navigator's errors to Rerun: give --rerun DEST too"
        );
    }
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("cannot create {}", a.out.display()))?;
    let resolved =
        toml::to_string_pretty(&sc.plant).context("serialising the resolved configuration")?;
    std::fs::write(a.out.join("resolved-plant.toml"), resolved)?;
    let n = sc.samples();
    let mut sinks: Vec<Box<dyn Sink>> = Vec::new();
    if sc.outputs.csv {
        sinks.push(Box::new(CsvSink::create(
            &a.out.join("imu.csv"),
            sc.outputs,
            &sc.plant,
        )?));
    }
    let mut figures = a
        .figures
        .then(|| rins_scenarios::report::RunFigures::new(&sc.plant, n));
    #[cfg(feature = "rerun")]
    let mut rerun = match &target {
        Some(t) => Some(rins_scenarios::viz::RerunSink::open(
            t,
            &sc,
            n,
            a.viz.rerun_bucket_s,
            a.nav,
        )?),
        None => None,
    };
    let mut refs: Vec<&mut dyn Sink> = sinks
        .iter_mut()
        .map(|b| b.as_mut() as &mut dyn Sink)
        .collect();
    if let Some(f) = figures.as_mut() {
        refs.push(f);
    }
    #[cfg(feature = "rerun")]
    if let Some(r) = rerun.as_mut() {
        refs.push(r);
    }
    rins_scenarios::interrupt::install();
    let summary = run(&sc, n, &mut refs)?;
    drop(refs);
    #[cfg(feature = "rerun")]
    if let Some(mut r) = rerun {
        r.close()?;
        eprintln!(
            "rerun: {} rows per series -> {}",
            r.rows(),
            a.viz.rerun.as_deref().unwrap_or_default()
        );
    }
    drop(sinks);
    if let Some(f) = figures {
        for p in f.write(&a.out, &sc.meta.name)? {
            eprintln!("wrote {}", p.display());
        }
    }
    eprintln!(
        "{}: {} samples ({} s simulated) in {:.2} s, {:.1} ns/sample -> {}",
        sc.meta.name,
        summary.samples,
        summary.samples as f64 / sc.plant.rate_hz,
        summary.wall_s,
        summary.wall_s * 1e9 / summary.samples.max(1) as f64,
        a.out.display()
    );
    if summary.interrupted {
        return Err(Interrupted(summary.samples).into());
    }
    Ok(())
}

/// Ctrl-C stopped a run after this many samples; its outputs were closed cleanly.
#[derive(Debug, thiserror::Error)]
#[error("interrupted after {0} samples; the outputs are complete up to there")]
struct Interrupted(u64);

fn cmd_fmu_run(
    fmu: &std::path::Path,
    scenario: &std::path::Path,
    out: &std::path::Path,
    overrides: &Overrides,
    figures: bool,
) -> Result<()> {
    let sc = load(scenario, overrides)?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut csv = CsvSink::create(&out.join("imu.csv"), sc.outputs, &sc.plant)?;
    let mut figs = rins_scenarios::report::RunFigures::new(&sc.plant, sc.samples());
    let summary = if figures {
        rins_scenarios::fmu::run(fmu, &sc, sc.samples(), &mut [&mut csv, &mut figs])?
    } else {
        rins_scenarios::fmu::run(fmu, &sc, sc.samples(), &mut [&mut csv])?
    };
    if figures {
        for p in figs.write(out, &sc.meta.name)? {
            eprintln!("wrote {}", p.display());
        }
    }
    eprintln!(
        "{} via {}: {} samples in {:.2} s, {:.1} ns/sample -> {}",
        sc.meta.name,
        fmu.display(),
        summary.samples,
        summary.wall_s,
        summary.wall_s * 1e9 / summary.samples.max(1) as f64,
        out.display()
    );
    Ok(())
}

fn load_data(
    a: &DataArgs,
) -> Result<(
    Scenario,
    rins_plant::PlantConfig,
    rins_mvm::History,
    rins_mvm::Options,
)> {
    let sc = Scenario::load(&a.model)?;
    let m = rins_mvm::reader::read(&a.data)?;
    let (model, note) = rins_mvm::with_data_site(&sc.plant, &m);
    if let Some(n) = note {
        eprintln!("{}", n);
    }
    let h = rins_mvm::to_history(m, &a.data.display().to_string())?;
    for (name, v) in [
        ("--window-s", a.window_s),
        ("--temp-bin-k", a.temp_bin_k),
        ("--time-window-s", a.time_window_s),
    ] {
        if !(v > 0.0 && v.is_finite()) {
            anyhow::bail!("{name} must be a positive number, got {v}");
        }
    }
    let opts = rins_mvm::Options {
        window_s: a.window_s,
        temp_bin_k: a.temp_bin_k,
        time_window_s: a.time_window_s,
        ..Default::default()
    };
    Ok((sc, model, h, opts))
}

fn cmd_compare(a: &CompareArgs) -> Result<()> {
    let (_, model, h, opts) = load_data(&a.data)?;
    let an = rins_mvm::analyse(&model, &h, &opts);
    let report = &an.comparison;
    record_analysis(
        &a.data.viz,
        &an,
        None,
        &h.source,
        &serde_json::to_string_pretty(report)?,
    )?;
    if let Some(dir) = &a.data.report {
        for f in rins_scenarios::diagnose::write_report(dir, &an)? {
            eprintln!("wrote {f}");
        }
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    println!(
        "{}: {} rows, {} windows, {} runs",
        report.source, report.rows, report.windows, report.runs
    );
    println!(
        "{:<8} {:>12} {:>12} {:>12}  unit",
        "channel", "resid RMS", "noise RMS", "resid mean"
    );
    for c in &report.channels {
        println!(
            "{:<8} {:>12.5} {:>12.5} {:>12.5}  {}",
            c.channel, c.residual_rms, c.noise_floor_rms, c.residual_mean, c.unit
        );
    }
    for n in &report.noise {
        println!("noise {}: {}", n.channel, n.source);
    }
    println!(
        "{} of {} cells flagged (|z| > {:.2})",
        report.flagged_cells.len(),
        report.cells.len(),
        report.z_critical
    );
    for c in report.flagged_cells.iter().take(20) {
        println!(
            "  {:<8} {:<7} {:>5.1}-{:<5.1} C  {:>7.0}-{:<7.0} s  residual {:>10.5} ± {:.5}  z = {:>6.1}",
            c.channel,
            c.position,
            c.temp_bin_c[0],
            c.temp_bin_c[1],
            c.time_window_s[0],
            c.time_window_s[1],
            c.residual,
            c.noise_floor,
            c.z
        );
    }
    for c in report.correlations.iter().filter(|c| c.significant) {
        println!(
            "  {}: residual correlates with {} (|rho| = {:.2} > {:.2}, lag {})",
            c.channel, c.with, c.max_abs_rho, c.band99, c.lag
        );
    }
    println!("navigation (static, horizontal error at the end of each segment):");
    for n in report.navigation.iter().take(12) {
        println!(
            "  {:<16} {:>7.0} s  measured {:>9.2} m  model {:>9.2} m  (difference RMS {:.2} m)",
            n.run, n.duration_s, n.measured_final_m, n.model_final_m, n.difference_rms_m
        );
    }
    Ok(())
}

/// `--rerun` of compare/diagnose: the residual windows, the fitted prediction, navigation.
fn record_analysis(
    viz: &rins_scenarios::viz::RerunArgs,
    an: &rins_mvm::Analysis,
    pred: Option<&[Vec<f64>]>,
    source: &str,
    text: &str,
) -> Result<()> {
    let target = viz.target()?;
    #[cfg(feature = "rerun")]
    if let Some(t) = &target {
        rins_scenarios::viz::record_diagnosis(t, an, pred, source, text)?;
        eprintln!(
            "rerun: recorded -> {}",
            viz.rerun.as_deref().unwrap_or_default()
        );
    }
    #[cfg(not(feature = "rerun"))]
    let _ = (target, an, pred, source, text);
    Ok(())
}

fn cmd_diagnose(a: &DiagnoseArgs) -> Result<()> {
    let (_, model, h, mut opts) = load_data(&a.data)?;
    opts.diagnose = true;
    if let Some(effect) = &a.apply {
        let e = rins_mvm::Effect::parse(effect).with_context(|| {
            let names: Vec<String> = rins_mvm::Effect::all().iter().map(|e| e.name()).collect();
            format!("--apply {effect:?}: not an effect of the catalogue; one of {names:?}")
        })?;
        opts.apply.push(e);
    }
    let an = rins_mvm::analyse(&model, &h, &opts);
    let report = &an.diagnosis.as_ref().expect("opts.diagnose is set").report;
    if let Some(effect) = &a.apply {
        let applied = (an.applied.clone())
            .expect("opts.apply is set")
            .map_err(anyhow::Error::msg)?;
        let out = a.out.clone().unwrap_or_else(|| {
            let stem = a.data.model.file_stem().map_or("model".into(), |s| {
                s.to_string_lossy().replace("builtin:", "")
            });
            a.data.model.with_file_name(format!("{stem}-fitted.toml"))
        });
        let text = applied
            .model_file(
                &rins_scenarios::diagnose::model_text(&a.data.model)?,
                &format!(
                    "{} with {effect} fitted on {}",
                    a.data.model.display(),
                    h.source
                ),
            )
            .map_err(anyhow::Error::msg)?;
        std::fs::write(&out, text).with_context(|| format!("cannot write {}", out.display()))?;
        eprintln!(
            "wrote {} ({} coefficients)",
            out.display(),
            applied.set.len()
        );
        for (k, v) in &applied.set {
            eprintln!("  {k} = {v}");
        }
    }
    if a.data.report.is_some() || a.data.viz.rerun.is_some() {
        record_analysis(
            &a.data.viz,
            &an,
            an.predictions(),
            &h.source,
            &serde_json::to_string_pretty(report)?,
        )?;
    }
    if let Some(dir) = &a.data.report {
        for f in rins_scenarios::diagnose::write_report(dir, &an)? {
            eprintln!("wrote {f}");
        }
    }
    if a.data.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    println!(
        "{}: candidates ranked by delta-BIC (gate: delta-BIC < -10, Bonferroni p < 0.01, CV gain > 0)",
        report.source
    );
    println!(
        "{:<36} {:<8} {:>10} {:>10} {:>8}  gate  coefficient (95 % CI)",
        "effect", "channel", "dBIC", "p", "CV %"
    );
    for r in report.ranking.iter().take(15) {
        let coef: Vec<String> = r
            .coefficient
            .iter()
            .zip(&r.ci95)
            .zip(&r.keys)
            .map(|((c, ci), k)| {
                format!(
                    "{}={c:.4} [{:.4}, {:.4}]",
                    k.rsplit('.').next().unwrap_or(k),
                    ci[0],
                    ci[1]
                )
            })
            .collect();
        println!(
            "{:<36} {:<8} {:>10.1} {:>10.2e} {:>8.2}  {}  {}",
            r.effect,
            r.channel,
            r.delta_bic,
            r.p_value,
            r.cv_rmse_gain_pct,
            if r.passes_gate { "PASS" } else { "-   " },
            coef.join(" ")
        );
        for c in &r.confusable_with {
            println!(
                "    confusable with {} (gap {:.1}, rho {:.2}, VIF {:.0}): separate by {}",
                c.effect, c.delta_bic_gap, c.correlation, c.vif, c.separate_by
            );
        }
    }
    println!(
        "accepted: {}",
        if report.accepted.is_empty() {
            "none".to_string()
        } else {
            report
                .accepted
                .iter()
                .map(|r| format!("{} on {}", r.effect, r.channel))
                .collect::<Vec<_>>()
                .join(", ")
        }
    );
    for (ch, b) in &report.residual_rms_before {
        println!(
            "  {ch}: residual RMS {b:.5} -> {:.5} (noise floor {:.5})",
            report.residual_rms_after[ch], report.noise_floor_rms[ch]
        );
    }
    println!(
        "flagged cells: {} before, {} after",
        report.flagged_cells.len(),
        report.flagged_cells_after.len()
    );
    for u in &report.unexplained {
        println!("  {u}");
    }
    Ok(())
}

fn cmd_measure(a: &MeasureArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let n = sc.samples();
    let runs: Vec<(String, rins_plant::PlantConfig, u64)> = match &sc.campaign {
        Some(c) => c
            .temperatures_c()
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let mut cfg = sc.plant.clone();
                cfg.thermal.chamber.temp_c = *t;
                cfg.thermal.chamber.profile.clear();
                cfg.seed = sc.plant.seed.wrapping_add(i as u64);
                (format!("run{:02}-{t:.2}C", i + 1), cfg, n)
            })
            .collect(),
        None => vec![(sc.meta.name.clone(), sc.plant.clone(), n)],
    };
    let t0 = std::time::Instant::now();
    rins_scenarios::diagnose::write_measurements(&a.out, &runs)?;
    eprintln!(
        "{}: {} runs x {} samples in {:.1} s -> {}",
        sc.meta.name,
        runs.len(),
        n,
        t0.elapsed().as_secs_f64(),
        a.out.display()
    );
    Ok(())
}

#[cfg(feature = "transport")]
fn positive_timeout(s: f64) -> Result<std::time::Duration> {
    if !(s > 0.0 && s.is_finite()) {
        anyhow::bail!("--peer-timeout-s must be a positive number, got {s}");
    }
    Ok(std::time::Duration::from_secs_f64(s))
}

#[cfg(feature = "transport")]
fn cmd_serve(a: &ServeArgs) -> Result<()> {
    use rins_transport::{Mode, ServeOptions};
    let sc = load(&a.scenario, &a.overrides)?;
    if !(1..=rins_transport::layout::BATCH_CAPACITY).contains(&a.batch) {
        anyhow::bail!(
            "--batch must be in 1..={}, got {}",
            rins_transport::layout::BATCH_CAPACITY,
            a.batch
        );
    }
    let mode = if a.mode == "lockstep" {
        Mode::Lockstep
    } else {
        Mode::FreeRunning
    };
    if let Some(k) = a.pace.filter(|k| !(*k > 0.0 && k.is_finite())) {
        anyhow::bail!("--pace must be a positive real-time factor, got {k}");
    }
    let opts = ServeOptions {
        mode,
        batch: a.batch,
        pace: a.pace,
        peer_timeout: positive_timeout(a.peer_timeout_s)?,
        wait_for_restart: a.wait_for_restart,
    };
    let mut plant = rins_scenarios::runner::new_plant(&sc.plant, &sc.source)?;
    let target = a.viz.target()?;
    #[cfg(feature = "rerun")]
    let mut rerun = match &target {
        Some(t) => Some(rins_scenarios::viz::RerunSink::open(
            t,
            &sc,
            sc.samples(),
            a.viz.rerun_bucket_s,
            false,
        )?),
        None => None,
    };
    #[cfg(not(feature = "rerun"))]
    let _ = target;
    #[cfg_attr(not(feature = "rerun"), allow(unused_mut))]
    let mut rerun_err: Option<anyhow::Error> = None;
    let summary = rins_transport::serve_observed(
        &a.session,
        &mut plant,
        sc.samples(),
        &opts,
        &mut |s, tr| {
            #[cfg(feature = "rerun")]
            if let Some(r) = rerun.as_mut()
                && rerun_err.is_none()
                && let Err(e) = r.sample(s, tr)
            {
                rerun_err = Some(e);
            }
            #[cfg(not(feature = "rerun"))]
            let _ = (s, tr);
        },
    )?;
    #[cfg(feature = "rerun")]
    if let Some(mut r) = rerun {
        r.finish()?;
        r.close()?;
        eprintln!(
            "rerun: {} rows per series -> {}",
            r.rows(),
            a.viz.rerun.as_deref().unwrap_or_default()
        );
    }
    if let Some(e) = rerun_err {
        return Err(e.context("recording to Rerun"));
    }
    for e in &summary.events {
        eprintln!("{e}");
    }
    eprintln!(
        "{}: served {} samples in {} batches in {:.2} s ({:.2} M samples/s), {} commands, {} navigator restarts{}",
        sc.meta.name,
        summary.samples,
        summary.batches,
        summary.wall_s,
        summary.samples as f64 / summary.wall_s.max(1e-9) / 1e6,
        summary.commands.len(),
        summary.restarts,
        if summary.interrupted {
            ", interrupted"
        } else {
            ""
        }
    );
    Ok(())
}

#[cfg(feature = "transport")]
fn cmd_nav(a: &NavArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let commands = a
        .command_after
        .iter()
        .map(|c| {
            let p: Vec<&str> = c.split(':').collect();
            let bad = || {
                anyhow::anyhow!("--command-after {c:?}: expected SEQ:OUTER_DEG:INNER_DEG:RATE_DPS")
            };
            if p.len() != 4 {
                return Err(bad());
            }
            let f = |s: &str| s.parse::<f64>().map_err(|_| bad());
            Ok(rins_transport::ScheduledCommand {
                after_seq: p[0].parse().map_err(|_| bad())?,
                outer_rad: f(p[1])?.to_radians(),
                inner_rad: f(p[2])?.to_radians(),
                rate_rps: f(p[3])?.to_radians(),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let opts = rins_transport::NavOptions {
        acknowledge: !a.no_ack,
        commands,
        peer_timeout: positive_timeout(a.peer_timeout_s)?,
    };
    let s = rins_transport::navigate(&a.connect, &sc.plant, &opts)?;
    let st = s.nav.state().copied();
    let q = st.map(|s| s.q_bn.into_inner());
    let out = serde_json::json!({
        "samples": s.nav.samples,
        "batches": s.batches,
        "duplicates": s.duplicates,
        "first_tick": s.nav.first_tick,
        "last_tick": s.nav.last_tick,
        "digest": format!("{:016x}", s.nav.digest),
        "interrupted": s.interrupted,
        "lat_rad": st.map(|s| s.lat_rad),
        "lon_rad": st.map(|s| s.lon_rad),
        "v_n": st.map(|s| [s.v_n.x, s.v_n.y, s.v_n.z]),
        "q_bn": q.map(|q| [q.w, q.i, q.j, q.k]),
    });
    println!("{out}");
    Ok(())
}

fn cmd_paper(a: &PaperArgs) -> Result<()> {
    let report = rins_verify::report::AnalyticReport::run();
    println!(
        "== Analytic verification (Eq. 8, Eq. 11, Table 2) ==\n{}",
        report.to_text()
    );
    let t4 = Table4Args {
        runs: if a.full { 32 } else { 2 },
        days: 7.0,
        scenario: PathBuf::from("builtin:paper-16pos-week"),
        align: "truth".into(),
        json: false,
        out: a.out.clone(),
        viz: a.viz.clone(),
    };
    println!(
        "== Section 3.1 / Table 4 ({} seeds; --full for 32) ==",
        t4.runs
    );
    cmd_table4(&t4)?;
    if !report.passed() {
        anyhow::bail!("analytic verification failed");
    }
    Ok(())
}

/// φ(t) through one 16-position cycle for a constant bias (Eq. 8) and for δβ (Eq. 11), with the
/// paper's −8·T_s·δβ_z marked.
fn write_cycle_figure(dir: &std::path::Path) -> Result<()> {
    use plotters::style::RGBColor;
    use rins_scenarios::plots::{Line, Panel, write_svg};
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let (bias, dbeta, dwell) = ([0.005; 3], [0.005; 3], 180.0);
    let tr = rins_verify::analytic::cycle_trace(bias, dbeta, dwell, 0.5);
    let arcsec = |r: f64| r.to_degrees() * 3600.0;
    let t_end = tr.last().map_or(0.0, |p| p.t_s) / 60.0;
    let expected = arcsec(-8.0 * dwell * dbeta[2] * rins_plant::units::DPH);
    let panels: Vec<Panel> = ["East", "North", "Up"]
        .iter()
        .enumerate()
        .map(|(i, axis)| {
            let mut lines = vec![
                Line { label: "constant bias 0.005 deg/h on each axis (Eq. 8)", points: tr.iter().map(|p| (p.t_s / 60.0, arcsec(p.bias_rad[i]))).collect(), color: RGBColor(31, 119, 180), error_bars: false },
                Line { label: "delta-beta 0.005 deg/h on each axis (Eq. 11)", points: tr.iter().map(|p| (p.t_s / 60.0, arcsec(p.delta_beta_rad[i]))).collect(), color: RGBColor(214, 39, 40), error_bars: false },
            ];
            if i == 2 {
                lines.push(Line { label: "-8 Ts delta-beta_z (stationary phases, Eq. 11)", points: vec![(0.0, expected), (t_end, expected)], color: RGBColor(120, 120, 120), error_bars: false });
            }
            Panel { title: format!("{axis}: attitude error accumulated through one cycle (T_s = 180 s, constant-rate moves)"), y_label: "arcsec", lines }
        })
        .collect();
    write_svg(
        &dir.join("eq8_eq11_cycle.svg"),
        "One 16-position cycle: a constant bias cancels, delta-beta leaves -8 Ts delta-beta_z",
        "time in the cycle (min)",
        &panels,
    )
}

/// Each check's value against its limit (log10 of value / limit; ≤ 0 passes).
fn write_checks_figure(
    path: &std::path::Path,
    title: &str,
    checks: &[rins_verify::report::Check],
) -> Result<()> {
    use plotters::style::RGBColor;
    use rins_scenarios::plots::{Line, PALETTE, Panel, write_svg};
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    // An exact zero (e.g. an integral that cancels to the bit) is drawn at 1e-16 of the limit.
    let margin = |c: &rins_verify::report::Check| {
        (c.value.abs().max(1e-16 * c.limit.abs()) / c.limit.abs().max(f64::MIN_POSITIVE)).log10()
    };
    let mut lines: Vec<Line> = checks
        .iter()
        .enumerate()
        .map(|(k, c)| Line {
            label: c.name.as_str(),
            points: vec![(k as f64, margin(c)), (k as f64, margin(c))],
            color: PALETTE[k % PALETTE.len()],
            error_bars: true,
        })
        .collect();
    lines.push(Line {
        label: "limit",
        points: vec![(-0.5, 0.0), (checks.len() as f64 - 0.5, 0.0)],
        color: RGBColor(0, 0, 0),
        error_bars: false,
    });
    let panel = Panel {
        title: format!(
            "{} checks, {} passed (below the line)",
            checks.len(),
            checks.iter().filter(|c| c.pass).count()
        ),
        y_label: "log10(value / limit)",
        lines,
    };
    write_svg(path, title, "check", &[panel])
}

/// Checks `--runs` and `--days` of the paired paper runs.
fn check_runs_days(runs: usize, days: f64) -> Result<()> {
    if runs == 0 {
        anyhow::bail!("--runs: expected at least 1 seed, got 0");
    }
    if !(days > 0.0 && days <= 60.0) {
        anyhow::bail!("--days: expected a number in (0, 60], got {days}");
    }
    Ok(())
}

/// Runs the paired uncompensated/compensated study with a progress bar and writes
/// `<name>.json` and the figures to `out`.
fn run_paired(
    opt: &rins_verify::paper::Table4Options,
    name: &str,
    out: &std::path::Path,
    sc: &Scenario,
    viz: &rins_scenarios::viz::RerunArgs,
) -> Result<rins_verify::paper::Table4Report> {
    let target = viz.target()?;
    let total = (2 * opt.runs as u64 + 2) * (opt.duration_s * opt.plant.rate_hz) as u64;
    let pb = rins_scenarios::progress::bar(total, name);
    let r = rins_verify::paper::table4(opt, &|n| pb.inc(n));
    pb.finish_and_clear();
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    std::fs::write(
        out.join(format!("{name}.json")),
        serde_json::to_string_pretty(&r)?,
    )?;
    write_table4_figures(&r, out)?;
    #[cfg(feature = "rerun")]
    if let Some(t) = &target {
        let text = if name == "table5" {
            r.to_text_table5()
        } else {
            r.to_text()
        };
        rins_scenarios::viz::record_paired(
            t,
            viz.rerun_bucket_s,
            sc,
            &opt.plant,
            opt.duration_s,
            &r,
            &text,
        )?;
        eprintln!(
            "rerun: recorded -> {}",
            viz.rerun.as_deref().unwrap_or_default()
        );
    }
    #[cfg(not(feature = "rerun"))]
    let _ = (target, sc);
    Ok(r)
}

fn cmd_table4(a: &Table4Args) -> Result<()> {
    check_runs_days(a.runs, a.days)?;
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
        compensation: None,
        nav: rins_nav::NavRunConfig {
            alignment: if a.align == "self" {
                rins_nav::Alignment::SelfAlign {
                    coarse_s: 300.0,
                    fine_s: 600.0,
                }
            } else {
                rins_nav::Alignment::Truth
            },
            ..rins_nav::NavRunConfig::default()
        },
    };
    let r = run_paired(&opt, "table4", &a.out, &sc, &a.viz)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", r.to_text());
        println!("  figures and table4.json in {}", a.out.display());
    }
    Ok(())
}

fn write_table4_figures(r: &rins_verify::paper::Table4Report, out: &std::path::Path) -> Result<()> {
    use plotters::style::RGBColor;
    use rins_scenarios::plots::{Line, Panel, write_svg};
    const UNC: RGBColor = RGBColor(200, 40, 40);
    const COMP: RGBColor = RGBColor(30, 90, 200);
    for (series, tag, what) in [
        (&r.first_seed, "", "first seed"),
        (&r.noise_free_series, "_noise_free", "noise-free"),
    ] {
        let pts = |recs: &[rins_nav::NavRecord],
                   f: &dyn Fn(&rins_nav::NavRecord) -> f64|
         -> Vec<(f64, f64)> {
            recs.iter().map(|x| (x.t_s / 3600.0, f(x))).collect()
        };
        let pair = |f: &dyn Fn(&rins_nav::NavRecord) -> f64| {
            vec![
                Line {
                    label: "uncompensated",
                    points: pts(&series.uncompensated, f),
                    color: UNC,
                    error_bars: false,
                },
                Line {
                    label: "compensated",
                    points: pts(&series.compensated, f),
                    color: COMP,
                    error_bars: false,
                },
            ]
        };
        let att = ["East", "North", "Up"]
            .iter()
            .enumerate()
            .map(|(k, n)| Panel {
                title: format!("{n}-axis attitude error"),
                y_label: "deg",
                lines: pair(&|x| x.att_err_rad[k].to_degrees()),
            })
            .collect::<Vec<_>>();
        write_svg(
            &out.join(format!("fig2_attitude_error{tag}.svg")),
            &format!("Figure 2 counterpart: attitude error ({what})"),
            "time (h)",
            &att,
        )?;
        let nm = rins_nav::errors::nmi;
        let pos = vec![
            Panel {
                title: "Latitude error".into(),
                y_label: "nmi",
                lines: pair(&|x| nm(x.north_m)),
            },
            Panel {
                title: "Longitude error".into(),
                y_label: "nmi",
                lines: pair(&|x| nm(x.east_m)),
            },
            Panel {
                title: "Horizontal error and tRMS (Eq. 20)".into(),
                y_label: "nmi",
                lines: {
                    let mut l = pair(&|x| nm(x.horizontal_m));
                    l.push(Line {
                        label: "tRMS uncompensated",
                        points: pts(&series.uncompensated, &|x| nm(x.trms_m)),
                        color: RGBColor(240, 150, 150),
                        error_bars: false,
                    });
                    l.push(Line {
                        label: "tRMS compensated",
                        points: pts(&series.compensated, &|x| nm(x.trms_m)),
                        color: RGBColor(140, 170, 240),
                        error_bars: false,
                    });
                    l
                },
            },
        ];
        write_svg(
            &out.join(format!("fig3_position_error{tag}.svg")),
            &format!("Figure 3 counterpart: position error ({what})"),
            "time (h)",
            &pos,
        )?;
    }
    Ok(())
}

/// Calibration timing from a scenario: lead dwell = alignment, dwell = time in each position.
fn calibration_config(sc: &Scenario, estimator: &str) -> rins_nav::calibration::CalibrationConfig {
    use rins_nav::calibration::{CalibrationConfig, Estimator};
    let lead = sc.plant.scheme.lead_dwell_s;
    let alignment = if lead > 0.0 {
        let coarse = (lead / 4.0).min(120.0);
        rins_nav::Alignment::SelfAlign {
            coarse_s: coarse,
            fine_s: lead - coarse,
        }
    } else {
        rins_nav::Alignment::Truth
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

/// calibration.json and the figure: β at Z-up and Z-down and δβ per axis with ±1 SE.
fn write_calibration(r: &rins_nav::calibration::Calibration, out: &std::path::Path) -> Result<()> {
    use plotters::style::RGBColor;
    use rins_scenarios::plots::{Line, Panel, write_svg};
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    std::fs::write(
        out.join("calibration.json"),
        serde_json::to_string_pretty(r)?,
    )?;
    let bar = |x: f64, v: f64, e: f64| vec![(x, v - e), (x, v + e)];
    let panels: Vec<Panel> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, a)| Panel {
            title: format!(
                "{a}-axis gyro: 0 = beta Z-up (Eq. 17), 1 = beta Z-down (Eq. 19), 2 = delta-beta"
            ),
            y_label: "deg/h",
            lines: vec![
                Line {
                    label: "Z-up +- 1 SE",
                    points: bar(0.0, r.up.beta_dph[i], r.up.se_dph[i]),
                    color: RGBColor(31, 119, 180),
                    error_bars: true,
                },
                Line {
                    label: "Z-down +- 1 SE",
                    points: bar(1.0, r.down.beta_dph[i], r.down.se_dph[i]),
                    color: RGBColor(214, 39, 40),
                    error_bars: true,
                },
                Line {
                    label: "delta-beta +- 1 SE",
                    points: bar(2.0, r.delta_beta_dph[i], r.delta_beta_se_dph[i]),
                    color: RGBColor(44, 160, 44),
                    error_bars: true,
                },
            ],
        })
        .collect();
    write_svg(
        &out.join("calibration_beta.svg"),
        "System-level indirect calibration: estimated gyro bias",
        "estimate",
        &panels,
    )
}

fn cmd_calibrate(a: &CalibrateArgs) -> Result<()> {
    let sc = Scenario::load(&a.scenario)?;
    let cfg = calibration_config(&sc, &a.estimator);
    let r = rins_nav::calibration::calibrate(&sc.plant, &cfg)?;
    write_calibration(&r, &a.out)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!(
        "System-level indirect calibration ({} estimator), {} s per position",
        a.estimator, cfg.segment_s
    );
    for (name, e) in [("Z-up   (Eq. 17)", &r.up), ("Z-down (Eq. 19)", &r.down)] {
        println!(
            "  {name}: beta = [{:+.5}, {:+.5}, {:+.5}] +- [{:.5}, {:.5}, {:.5}] deg/h",
            e.beta_dph[0], e.beta_dph[1], e.beta_dph[2], e.se_dph[0], e.se_dph[1], e.se_dph[2]
        );
        for (k, f) in e.segments.iter().enumerate() {
            println!(
                "      segment {}: dVdd_E {:+.3e} +- {:.1e}, dVdd_N {:+.3e} +- {:.1e} m/s^3, dphi_U {:+.3e} +- {:.1e} rad/s (chi2/dof {:.2} {:.2} {:.2})",
                k + 1,
                f.dvdd_e.slope,
                f.dvdd_e.se,
                f.dvdd_n.slope,
                f.dvdd_n.se,
                f.phi_u_rate.slope,
                f.phi_u_rate.se,
                f.dvdd_e.chi2_per_dof,
                f.dvdd_n.chi2_per_dof,
                f.phi_u_rate.chi2_per_dof
            );
        }
    }
    let (d, e) = (r.delta_beta_dph, r.delta_beta_se_dph);
    println!(
        "  delta-beta = beta_down - beta_up = [{:+.5}, {:+.5}, {:+.5}] +- [{:.5}, {:.5}, {:.5}] deg/h",
        d[0], d[1], d[2], e[0], e[1], e[2]
    );
    Ok(())
}

fn run_campaign_from(sc: &Scenario, ref_temp_c: f64) -> Result<rins_nav::campaign::Campaign> {
    let camp = sc.campaign.as_ref().with_context(|| {
        format!(
            "{}: no [campaign] section (temps_c, or from_c/to_c/runs)",
            sc.source
        )
    })?;
    let cfg = calibration_config(sc, "coupled");
    Ok(rins_nav::campaign::run_campaign(
        &sc.plant,
        &camp.temperatures_c(),
        &cfg,
        ref_temp_c,
    )?)
}

fn write_campaign(c: &rins_nav::campaign::Campaign, out: &std::path::Path) -> Result<()> {
    use plotters::style::RGBColor;
    use rins_scenarios::plots::{Line, Panel, write_svg};
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    std::fs::write(out.join("campaign.json"), serde_json::to_string_pretty(c)?)?;
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
    let panels: Vec<Panel> = ["X", "Y", "Z"]
        .iter()
        .enumerate()
        .map(|(i, axis)| {
            let pts: Vec<(f64, f64)> = c
                .runs
                .iter()
                .map(|r| (r.block_temp_c[i], r.calibration.delta_beta_dph[i]))
                .collect();
            let (lo, hi) = pts
                .iter()
                .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
            let curve = |k: f64| -> Vec<(f64, f64)> {
                (0..=100)
                    .map(|j| {
                        let t = lo + (hi - lo) * j as f64 / 100.0;
                        let (v, sd) = c.fits[i].eval(t - c.ref_temp_c);
                        (t, v + k * 1.96 * sd)
                    })
                    .collect()
            };
            let mut bars = Vec::new();
            for r in &c.runs {
                let (x, y, e) = (
                    r.block_temp_c[i],
                    r.calibration.delta_beta_dph[i],
                    r.calibration.delta_beta_se_dph[i],
                );
                bars.push((x, y - e));
                bars.push((x, y + e));
            }
            Panel {
                title: format!("{axis}-axis gyro: delta-beta = beta(Z-down) - beta(Z-up)"),
                y_label: "deg/h",
                lines: vec![
                    Line {
                        label: "estimate +- 1 SE",
                        points: bars,
                        color: RGBColor(90, 90, 90),
                        error_bars: true,
                    },
                    Line {
                        label: "cubic fit",
                        points: curve(0.0),
                        color: RGBColor(30, 90, 200),
                        error_bars: false,
                    },
                    Line {
                        label: "95 % band",
                        points: curve(1.0),
                        color: RGBColor(140, 170, 240),
                        error_bars: false,
                    },
                    Line {
                        label: "",
                        points: curve(-1.0),
                        color: RGBColor(140, 170, 240),
                        error_bars: false,
                    },
                ],
            }
        })
        .collect();
    write_svg(
        &out.join("fig8_dbeta_vs_temperature.svg"),
        "Figure 8 counterpart: identified position-dependent gyro bias",
        "gyro block temperature at Z-down (deg C)",
        &panels,
    )
}

fn cmd_campaign(a: &CampaignArgs) -> Result<()> {
    let sc = Scenario::load(&a.scenario)?;
    let c = run_campaign_from(&sc, a.ref_temp_c)?;
    write_campaign(&c, &a.out)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&c)?);
        return Ok(());
    }
    println!(
        "Temperature campaign: {} runs ({:.1} s wall)",
        c.runs.len(),
        c.wall_s
    );
    println!(
        "  {:>9} {:>27} {:>27} {:>27}",
        "chamber", "dbeta_x +- SE (deg/h)", "dbeta_y", "dbeta_z"
    );
    for r in &c.runs {
        let (d, e) = (
            r.calibration.delta_beta_dph,
            r.calibration.delta_beta_se_dph,
        );
        println!(
            "  {:>7.2} C {:>+12.5} +- {:>9.5} {:>+12.5} +- {:>9.5} {:>+12.5} +- {:>9.5}",
            r.chamber_c, d[0], e[0], d[1], e[1], d[2], e[2]
        );
    }
    for (i, f) in c.fits.iter().enumerate() {
        println!(
            "  fit {}: c0..c3 = [{:+.3e}, {:+.3e}, {:+.3e}, {:+.3e}] (T - {} C), chi2/dof {:.2}",
            ["x", "y", "z"][i],
            f.coef[0],
            f.coef[1],
            f.coef[2],
            f.coef[3],
            c.ref_temp_c,
            f.chi2_per_dof
        );
    }
    println!(
        "  compensation file: {}",
        a.out.join("dbeta-compensation.toml").display()
    );
    Ok(())
}

fn cmd_table5(a: &Table5Args) -> Result<()> {
    check_runs_days(a.runs, a.days)?;
    let comp = match &a.compensation {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            // The file is a scenario fragment: its [sensor.gyro.position_bias] is the compensation.
            let sc = Scenario::from_toml(&text, &path.display().to_string())?;
            let pb = sc.plant.sensor.gyro.position_bias;
            if !pb.enabled {
                anyhow::bail!(
                    "{}: expected an enabled [sensor.gyro.position_bias] table (from `rins campaign`)",
                    path.display()
                );
            }
            pb
        }
        None => {
            eprintln!("no --compensation given: running the 37-run campaign first");
            let c = run_campaign_from(
                &Scenario::load(std::path::Path::new("builtin:campaign-37"))?,
                25.0,
            )?;
            write_campaign(&c, &a.out.join("campaign"))?;
            c.compensation()
        }
    };
    let sc = Scenario::load(&a.scenario)?;
    let opt = rins_verify::paper::Table4Options {
        plant: sc.plant.clone(),
        runs: a.runs,
        duration_s: a.days * 86_400.0,
        nav: rins_nav::NavRunConfig::default(),
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
    Ok(())
}

/// Prints a verification report as JSON or text and fails when a check failed.
fn emit_report<T: serde::Serialize>(
    report: &T,
    json: bool,
    text: &str,
    passed: bool,
    what: &str,
) -> Result<()> {
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

/// Restores the default SIGPIPE action so `rins … | head` ends quietly, as Unix tools do,
/// instead of panicking on the closed pipe (Rust ignores SIGPIPE by default).
#[allow(unsafe_code)]
fn default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any other thread exists; SIG_DFL is a valid action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> std::process::ExitCode {
    default_sigpipe();
    match dispatch(Cli::parse()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) if e.downcast_ref::<Interrupted>().is_some() => {
            eprintln!("{e}");
            std::process::ExitCode::from(130)
        }
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
        Command::Paper {
            which: Some(PaperCommand::Table4(a)),
            ..
        } => cmd_table4(&a),
        Command::Paper {
            which: Some(PaperCommand::Table5(a)),
            ..
        } => cmd_table5(&a),
        Command::Calibrate(a) => cmd_calibrate(&a),
        Command::Campaign(a) => cmd_campaign(&a),
        Command::Verify(VerifyCommand::Analytic { json, figures }) => {
            let r = rins_verify::report::AnalyticReport::run();
            if let Some(dir) = &figures {
                write_cycle_figure(dir)?;
                write_checks_figure(
                    &dir.join("analytic_checks.svg"),
                    "Analytic verification: each check against its limit",
                    &r.checks,
                )?;
            }
            emit_report(&r, json, &r.to_text(), r.passed(), "analytic verification")
        }
        Command::Verify(VerifyCommand::Ins {
            json,
            runs,
            figures,
        }) => {
            if runs < 8 {
                anyhow::bail!("--runs: expected at least 8 Monte Carlo runs, got {runs}");
            }
            let r = rins_verify::ins::InsReport::run(runs);
            if let Some(dir) = &figures {
                write_checks_figure(
                    &dir.join("ins_checks.svg"),
                    "INS closed forms: each check against its limit",
                    &r.checks,
                )?;
            }
            emit_report(
                &r,
                json,
                &r.to_text(),
                r.passed(),
                "INS closed-form verification",
            )
        }
        Command::Fmu(FmuCommand::Build { out, lib_dir }) => {
            let lib_dir = lib_dir.unwrap_or_else(rins_scenarios::fmu::default_lib_dir);
            for p in rins_scenarios::fmu::build(&out, &lib_dir)? {
                println!("{}", p.display());
            }
            Ok(())
        }
        Command::Fmu(FmuCommand::Run {
            fmu,
            scenario,
            out,
            figures,
            overrides,
        }) => cmd_fmu_run(&fmu, &scenario, &out, &overrides, figures),
        #[cfg(feature = "transport")]
        Command::Serve(a) => cmd_serve(&a),
        #[cfg(feature = "transport")]
        Command::Nav(a) => cmd_nav(&a),
        Command::Compare(a) => cmd_compare(&a),
        Command::Diagnose(a) => cmd_diagnose(&a),
        Command::Measure(a) => cmd_measure(&a),
        Command::Scenarios { name: None } => {
            for (n, text) in BUILTIN {
                let sc = Scenario::from_toml(text, n)?;
                println!("builtin:{n:<22} {}", sc.meta.description);
            }
            Ok(())
        }
        Command::Scenarios { name: Some(n) } => {
            let n = n.strip_prefix("builtin:").unwrap_or(&n);
            let (_, text) = BUILTIN
                .iter()
                .find(|(b, _)| *b == n)
                .with_context(|| format!("no built-in scenario {n:?}; see `rins scenarios`"))?;
            print!("{text}");
            Ok(())
        }
    }
}
