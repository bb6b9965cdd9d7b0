//! The temperature stage: the chamber (the scenario's profile or an input overriding it) and the
//! unit's thermal network, advanced on the slow grid of `thermal.step_s`. A changed chamber
//! input ends the current step early, so an input acts at the step it is set for.

use nalgebra::Vector3;

use crate::config::PlantConfig;
use crate::state::{Reader, StateError, Writer};
use crate::thermal::{ChamberSpec, Temperatures, ThermalNetwork, node};

/// What a sample's start did to the temperatures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ThermalEvent {
    /// Only the chamber changed (an input set before any time passed): the network holds the
    /// new chamber temperature; no time advanced, no noise is drawn.
    ChamberHeld,
    /// The network advanced by `h_s`.
    Stepped {
        /// Length of the step, s.
        h_s: f64,
    },
}

/// The chamber and the thermal network on their slow grid.
#[derive(Clone, Debug)]
pub(crate) struct TemperatureField {
    network: ThermalNetwork,
    chamber: ChamberSpec,
    step_s: f64,
    rate_hz: f64,
    /// Output samples per thermal step.
    slow_every: u64,
    /// Output samples left before the next thermal (and slow-noise) update.
    slow_countdown: u64,
    chamber_override_c: Option<f64>,
    /// The chamber override changed since the last sample: the next sample starts with a
    /// thermal update. Transient: set by [`TemperatureField::set_chamber_override`], consumed
    /// by the next [`TemperatureField::begin_sample`].
    chamber_changed: bool,
}

impl TemperatureField {
    /// The network of `cfg` at the chamber's start temperature, the body up direction `up_b`.
    pub(crate) fn new(cfg: &PlantConfig, up_b: &Vector3<f64>) -> Self {
        let chamber0 = cfg.thermal.chamber.temp_at(0.0);
        let slow_every = (cfg.thermal.step_s * cfg.rate_hz).round() as u64;
        Self {
            network: ThermalNetwork::new(&cfg.thermal, chamber0, up_b),
            chamber: cfg.thermal.chamber.clone(),
            step_s: cfg.thermal.step_s,
            rate_hz: cfg.rate_hz,
            slow_every,
            slow_countdown: slow_every,
            chamber_override_c: None,
            chamber_changed: false,
        }
    }

    /// Current temperatures.
    pub(crate) fn temperatures(&self) -> Temperatures {
        self.network.temperatures()
    }

    /// Overrides the chamber temperature (`None`: back to the profile); a change acts from the
    /// next sample.
    pub(crate) fn set_chamber_override(&mut self, temp_c: Option<f64>) {
        self.chamber_changed |= temp_c != self.chamber_override_c;
        self.chamber_override_c = temp_c;
    }

    fn chamber_c(&self, t_s: f64) -> f64 {
        self.chamber_override_c
            .unwrap_or_else(|| self.chamber.temp_at(t_s))
    }

    /// Starts an output sample at time `t_s`: advances the network when a step is due (or the
    /// chamber input changed), with the body up direction from `up_b` (asked for only then).
    #[inline]
    pub(crate) fn begin_sample(
        &mut self,
        t_s: f64,
        up_b: impl FnOnce() -> Vector3<f64>,
    ) -> Option<ThermalEvent> {
        // All but one sample of a thermal step only count down: inlined into the plant's step,
        // where a call per sample cost about 3 % of the plant's time.
        if !self.chamber_changed && self.slow_countdown != 0 {
            self.slow_countdown -= 1;
            return None;
        }
        self.update(t_s, up_b)
    }

    /// [`TemperatureField::begin_sample`] when a step is due or the chamber input changed.
    #[cold]
    #[inline(never)]
    fn update(&mut self, t_s: f64, up_b: impl FnOnce() -> Vector3<f64>) -> Option<ThermalEvent> {
        let elapsed = self.slow_every - self.slow_countdown;
        let split = std::mem::take(&mut self.chamber_changed) && self.slow_countdown != 0;
        let event = if split && elapsed == 0 {
            // No time since the last update (the very first sample): only the chamber changes.
            let ch = self.chamber_c(t_s);
            self.network.hold_chamber(ch);
            Some(ThermalEvent::ChamberHeld)
        } else if self.slow_countdown == 0 || split {
            self.slow_countdown = self.slow_every;
            let h_s = if split {
                elapsed as f64 / self.rate_hz
            } else {
                self.step_s
            };
            let ch = self.chamber_c(t_s);
            self.network.step(h_s, ch, &up_b());
            Some(ThermalEvent::Stepped { h_s })
        } else {
            None
        };
        self.slow_countdown -= 1;
        event
    }

    /// Writes the countdown, the chamber override and the node temperatures.
    pub(crate) fn write(&self, w: &mut Writer) {
        w.u64(self.slow_countdown);
        w.u64(self.chamber_override_c.is_some() as u64);
        w.f64(self.chamber_override_c.unwrap_or(0.0));
        let t = self.network.temperatures();
        t.nodes_c.iter().for_each(|x| w.f64(*x));
        w.f64(t.chamber_c);
    }

    /// Reads what [`TemperatureField::write`] wrote.
    pub(crate) fn read(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        self.slow_countdown = r.u64()?;
        let has_override = r.u64()? != 0;
        let ov = r.f64()?;
        self.chamber_override_c = has_override.then_some(ov);
        let mut nodes = [0.0; node::COUNT];
        for n in nodes.iter_mut() {
            *n = r.f64()?;
        }
        let chamber = r.f64()?;
        self.network.set_state(nodes, chamber);
        Ok(())
    }
}
