//! Time as integer counters: internal ticks (substeps of an output interval) and output samples.
//! Every time in seconds is derived from them, never accumulated.

use crate::config::PlantConfig;

/// The plant's clock.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Clock {
    /// Internal ticks since start (substeps × output samples).
    tick: u64,
    /// Output samples since start.
    samples: u64,
    substeps: u64,
    internal_rate_hz: f64,
    dt_s: f64,
}

impl Clock {
    /// The clock of `cfg` at time zero.
    pub(crate) fn new(cfg: &PlantConfig) -> Self {
        let dt_s = 1.0 / cfg.rate_hz;
        Self {
            tick: 0,
            samples: 0,
            substeps: cfg.substeps as u64,
            internal_rate_hz: cfg.rate_hz * cfg.substeps as f64,
            dt_s,
        }
    }

    /// Internal ticks since start.
    pub(crate) fn tick(&self) -> u64 {
        self.tick
    }

    /// Output samples since start.
    pub(crate) fn samples(&self) -> u64 {
        self.samples
    }

    /// Internal ticks per output interval.
    pub(crate) fn substeps(&self) -> u64 {
        self.substeps
    }

    /// Output interval Δt, s.
    pub(crate) fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Internal tick length as the carriers count it, 1/(rate·substeps), s.
    pub(crate) fn tick_s(&self) -> f64 {
        1.0 / self.internal_rate_hz
    }

    /// Internal tick length as the integration takes it, Δt/substeps, s: within an ulp of
    /// [`Clock::tick_s`], kept apart so that outputs keep their bits.
    pub(crate) fn h_s(&self) -> f64 {
        self.dt_s / self.substeps as f64
    }

    /// Time now, s.
    pub(crate) fn time_s(&self) -> f64 {
        self.tick as f64 / self.internal_rate_hz
    }

    /// Time at the middle of the current tick, s.
    pub(crate) fn tick_mid_s(&self) -> f64 {
        (self.tick as f64 + 0.5) / self.internal_rate_hz
    }

    /// Starts the next output sample; returns its index.
    pub(crate) fn begin_sample(&mut self) -> u64 {
        self.samples += 1;
        self.samples - 1
    }

    /// One internal tick done.
    pub(crate) fn advance_tick(&mut self) {
        self.tick += 1;
    }

    /// A whole output interval done at once (a dwell reusing its interval).
    pub(crate) fn advance_interval(&mut self) {
        self.tick += self.substeps;
    }

    /// Restores the counters (state restore).
    pub(crate) fn restore(&mut self, tick: u64, samples: u64) {
        self.tick = tick;
        self.samples = samples;
    }
}
