//! `rins run`: run a scenario and write the IMU stream as CSV (and figures, a Rerun recording).

use std::path::PathBuf;

use anyhow::{Context, Result};

use super::Interrupted;
use super::args::{Overrides, RerunArgs, load};
use crate::runner::{Sink, run as run_scenario};
use crate::sinks::CsvSink;
use crate::sinks::RunFigures;

/// Arguments of `rins run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Scenario file, or `builtin:NAME` (see `rins scenarios`).
    pub scenario: PathBuf,
    /// Output folder (created).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Also write figures of the run (SVG and PNG) into the output folder.
    #[arg(long)]
    pub figures: bool,
    /// With --rerun: run the reference navigator (aligned to the truth) alongside and record its
    /// attitude, velocity and position errors and tRMS.
    #[arg(long)]
    pub nav: bool,
    /// `--seed`, `--duration-s`, `--rate-hz`.
    #[command(flatten)]
    pub overrides: Overrides,
    /// `--rerun DEST` and its bucket length.
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// Runs the scenario into `imu.csv` (when the scenario's outputs ask for it), the resolved
/// plant configuration, and the optional figures and recording.
pub fn run(a: &RunArgs) -> Result<()> {
    let sc = load(&a.scenario, &a.overrides)?;
    let target = a.viz.target()?;
    if a.nav && target.is_none() {
        anyhow::bail!(
            "--nav records the reference navigator's errors to Rerun: give --rerun DEST too"
        );
    }
    super::create_dir(&a.out)?;
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
    let mut figures = a.figures.then(|| RunFigures::new(&sc.plant, n));
    #[cfg(feature = "rerun")]
    let mut rerun = match &target {
        Some(t) => Some(crate::recordings::RerunSink::open(
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
    crate::interrupt::install();
    let summary = run_scenario(&sc, n, &mut refs)?;
    drop(refs);
    #[cfg(feature = "rerun")]
    if let Some(mut r) = rerun {
        r.close()?;
        eprintln!("rerun: {} rows per series -> {}", r.rows(), a.viz.dest());
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
