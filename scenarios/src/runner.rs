//! Drives the plant through a scenario and hands every sample to the sinks.

use std::time::Instant;

use anyhow::Result;
use rins_plant::{ImuSample, Truth};

use crate::progress;
use rins_scenario::{Scenario, new_plant};

/// Receives every output sample in order.
pub trait Sink {
    /// Called once per output sample with what really happened over it (from the in-process
    /// plant's [`Plant::truth`], or rebuilt from an FMU's outputs).
    fn sample(&mut self, sample: &ImuSample, truth: &Truth) -> Result<()>;
    /// Called once after the last sample.
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
}

/// What a run did.
#[derive(Clone, Copy, Debug)]
pub struct RunSummary {
    /// Output samples produced.
    pub samples: u64,
    /// Wall time, s.
    pub wall_s: f64,
    /// Stopped early by Ctrl-C ([`crate::interrupt`]); the sinks were still finished.
    pub interrupted: bool,
}

/// Runs `scenario` for `samples` output samples, feeding `sinks`.
pub fn run(scenario: &Scenario, samples: u64, sinks: &mut [&mut dyn Sink]) -> Result<RunSummary> {
    let mut plant = new_plant(&scenario.plant, &scenario.source)?;
    let pb = progress::bar(samples, &scenario.meta.name);
    let t0 = Instant::now();
    // About 1-7 ms of wall time between checks of the progress bar and of Ctrl-C.
    const CHUNK: u64 = 1 << 14;
    let mut done = samples;
    for k in 0..samples {
        if k % CHUNK == 0 && crate::interrupt::requested() {
            done = k;
            break;
        }
        let s = plant.step();
        for sink in sinks.iter_mut() {
            sink.sample(&s, &plant.truth())?;
        }
        if k % CHUNK == 0 {
            pb.set_position(k);
        }
    }
    for sink in sinks.iter_mut() {
        sink.finish()?;
    }
    pb.finish_and_clear();
    Ok(RunSummary {
        samples: done,
        wall_s: t0.elapsed().as_secs_f64(),
        interrupted: done < samples,
    })
}
