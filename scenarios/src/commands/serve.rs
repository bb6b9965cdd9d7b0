//! `rins serve`: serve the plant over iceoryx2 shared memory to navigation software
//! (docs/transport.md).

use std::path::PathBuf;
use std::time::Duration;

use anyhow::Result;
use rins_plant::message::Num;
use rins_transport::{Mode, ServeOptions};

use super::args::{Overrides, RerunArgs, load, positive, whole};

/// Arguments of `rins serve`.
#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    /// Scenario to serve.
    pub scenario: PathBuf,
    /// Session name (1-64 letters, digits, '-', '_'): services rins/<session>/imu, cmd, nav.
    #[arg(long, default_value = "default")]
    pub session: String,
    /// `lockstep` (deterministic) or `free` (as fast as the navigator consumes, or paced).
    #[arg(long, default_value = "lockstep", value_parser = ["lockstep", "free"])]
    pub mode: String,
    /// Pace at this real-time factor (1 = real time, 10 = ten times faster than real time).
    #[arg(long, allow_negative_numbers = true)]
    pub pace: Option<f64>,
    /// Records per message, 1-64.
    #[arg(long, default_value_t = 64, allow_negative_numbers = true)]
    pub batch: i64,
    /// Seconds to wait for a navigator.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    pub peer_timeout_s: f64,
    /// When the navigator dies, wait for a new one and resend from the first unacknowledged batch.
    #[arg(long)]
    pub wait_for_restart: bool,
    /// `--seed`, `--duration-s`, `--rate-hz`.
    #[command(flatten)]
    pub overrides: Overrides,
    /// `--rerun DEST` and its bucket length.
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// `--peer-timeout-s` as a duration.
pub fn peer_timeout(s: f64) -> Result<Duration> {
    Ok(Duration::from_secs_f64(positive("--peer-timeout-s", s)?))
}

/// Serves the scenario's samples until the end (or Ctrl-C) and reports what was served.
pub fn run(a: &ServeArgs) -> Result<()> {
    rins_transport::session::check_name(&a.session)?;
    let sc = load(&a.scenario, &a.overrides)?;
    let batch = whole(
        "--batch",
        a.batch,
        1,
        rins_transport::layout::BATCH_CAPACITY,
        "records per message",
    )?;
    let mode = if a.mode == "lockstep" {
        Mode::Lockstep
    } else {
        Mode::FreeRunning
    };
    if let Some(k) = a.pace.filter(|k| !(*k > 0.0 && k.is_finite())) {
        anyhow::bail!(
            "--pace: expected a real-time factor, a finite number > 0, got {}",
            Num(k)
        );
    }
    let opts = ServeOptions {
        mode,
        batch,
        pace: a.pace,
        peer_timeout: peer_timeout(a.peer_timeout_s)?,
        wait_for_restart: a.wait_for_restart,
    };
    let mut plant = rins_scenario::new_plant(&sc.plant, &sc.source)?;
    let target = a.viz.target()?;
    #[cfg(feature = "rerun")]
    let mut rerun = match &target {
        Some(t) => Some(crate::recordings::RerunSink::open(
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
                && let Err(e) = crate::runner::Sink::sample(r, s, tr)
            {
                rerun_err = Some(e);
            }
            #[cfg(not(feature = "rerun"))]
            let _ = (s, tr);
        },
    )?;
    #[cfg(feature = "rerun")]
    if let Some(mut r) = rerun {
        crate::runner::Sink::finish(&mut r)?;
        r.close()?;
        eprintln!("rerun: {} rows per series -> {}", r.rows(), a.viz.dest());
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
