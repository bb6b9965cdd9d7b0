//! # rins-carrier-fmu
//!
//! The ship carrier of the rins plant ([`rins_plant::carrier`]: legs of course and speed with
//! seeded sea-state motion) as a [`rins_fmi::model::Model`], named `RinsCarrier` (FMI 2) /
//! `RinsCarrier3` (FMI 3): the ship's scenario keys are parameters through the plant's own
//! parameter table ([`table`]), and the outputs are the carrier state a vessel model gives
//! (position, ENU velocity, attitude, angular rate, acceleration) under the names the IMU
//! FMU's carrier inputs carry. The FMI code is generic (`rins-fmi`, `rins-fmi2`, `rins-fmi3`);
//! the shared libraries are the one-line crates `rins-carrier-fmi2` and `rins-carrier-fmi3`.

use std::sync::OnceLock;

use rins_fmi::model::{Model, ModelInfo};
use rins_fmi::standard::FmiVersion;
use rins_fmi::state::{StateReader, StateWriter};
use rins_fmi::vars::{Value, VariableTable};
use rins_plant::PlantConfig;
use rins_plant::carrier::track::MAX_LAT_DEG;
use rins_plant::carrier::{Carrier, CarrierState};

pub mod reference;
pub mod table;

use table::{Role, outputs, table};

/// File name of the shared library cargo builds for `version`.
pub fn library_file(version: FmiVersion) -> &'static str {
    match version {
        FmiVersion::V2 => "librins_carrier_fmi2.so",
        FmiVersion::V3 => "librins_carrier_fmi3.so",
    }
}

/// The ship with its current state.
#[derive(Clone, Debug)]
struct Running {
    carrier: Carrier,
    now: CarrierState,
}

/// The ship carrier as an FMU model.
#[derive(Clone, Debug)]
pub struct RinsCarrier {
    /// Parameter values by slot.
    values: Vec<Value>,
    running: Option<Running>,
    /// Before the end of initialisation: the state at time 0 of the ship the parameters
    /// describe (outputs read in initialization mode), built on the first read.
    preview: OnceLock<Option<CarrierState>>,
}

impl RinsCarrier {
    /// The plant configuration the parameters describe (its `carrier`, `seed` and `rate_hz`
    /// are the ship's), validated by the plant's own rules.
    pub fn config(&self) -> Result<PlantConfig, String> {
        let t = table();
        let cfg = t.params.config(&t.vars.scalars, &self.values)?;
        cfg.validate().map_err(|errs| {
            errs.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        })?;
        Ok(cfg)
    }

    fn build(&self) -> Result<Running, String> {
        let cfg = self.config()?;
        let mut carrier = Carrier::new(&cfg.carrier, cfg.seed, 1.0 / cfg.rate_hz)?
            .ok_or("the carrier FMU models a ship (carrier.kind = ship)")?;
        let now = carrier.state_now();
        Ok(Running { carrier, now })
    }

    /// The carrier state after the last communication step (`None` before initialisation).
    pub fn state(&self) -> Option<&CarrierState> {
        self.running.as_ref().map(|r| &r.now)
    }
}

impl Model for RinsCarrier {
    const INFO: ModelInfo = ModelInfo {
        fmi2_id: "RinsCarrier",
        fmi3_id: "RinsCarrier3",
        description: "Ship carrier of the rins plant: legs of course and speed with seeded sea-state motion (six degrees of freedom through response amplitude operators)",
        stop_time_s: 3600.0,
        step_size_s: 0.01,
    };

    fn table() -> &'static VariableTable {
        &table().vars
    }

    fn documentation() -> String {
        "Default experiment: one hour at 100 Hz, the ship at 12 kn due north in a Pierson-Moskowitz sea state 5. The outputs connect one to one to the carrier inputs of RinsImu (docs/fmu.md).\n\n".into()
    }

    fn new() -> Self {
        Self {
            values: table().vars.scalars.iter().map(|s| s.start).collect(),
            running: None,
            preview: OnceLock::new(),
        }
    }

    fn set(&mut self, slot: usize, v: Value) -> Result<(), String> {
        self.values[slot] = v;
        if self.running.is_none() {
            self.preview = OnceLock::new();
        }
        Ok(())
    }

    fn get(&self, slot: usize) -> Value {
        let Role::Output(k, i) = table().roles[slot] else {
            return self.values[slot];
        };
        let state = match &self.running {
            Some(r) => Some(&r.now),
            None => self
                .preview
                .get_or_init(|| self.build().ok().map(|r| r.now))
                .as_ref(),
        };
        match state {
            Some(s) => Value::Real((outputs()[k].read)(s, i)),
            // Parameters that describe no ship: exiting initialization mode says why.
            None => self.values[slot],
        }
    }

    fn initialize(&mut self) -> Result<(), String> {
        self.running = Some(self.build()?);
        self.preview = OnceLock::new();
        Ok(())
    }

    fn internal_rate_hz(&self) -> f64 {
        self.config().map_or(100.0, |c| c.rate_hz)
    }

    fn advance(&mut self, n: u64) -> Result<(), String> {
        let r = self
            .running
            .as_mut()
            .ok_or("the carrier is not initialised")?;
        let mut nodes = [r.now; 2];
        let limit = MAX_LAT_DEG.to_radians();
        for _ in 0..n {
            r.now = r.carrier.advance(&mut nodes);
            // The last leg continues past its end (validation checked the legs' own
            // durations): a ship that reaches the polar limit stops the run.
            if r.now.lat_rad.abs() > limit {
                return Err(polar_stop(&r.carrier, r.now.lat_rad));
            }
        }
        Ok(())
    }

    fn save(&self, w: &mut StateWriter) {
        w.values(&self.values);
        // The ship's integrated state: its mean-track position and tick (the sea state is a
        // function of the tick).
        match self.running.as_ref().map(|r| &r.carrier) {
            Some(Carrier::Ship(s)) => {
                let (tick, p) = s.position();
                w.u64(1);
                w.u64(tick);
                w.f64(p.lat_rad);
                w.f64(p.lon_rad);
            }
            _ => w.u64(0),
        }
    }

    fn restore(&mut self, r: &mut StateReader<'_>) -> Result<(), String> {
        let values = r.values(&table().vars)?;
        let running = r.u64()? != 0;
        let pos = if running {
            Some((r.u64()?, r.f64()?, r.f64()?))
        } else {
            None
        };
        // Nothing changes until the whole state has been read and checked.
        let mut next = Self {
            values,
            running: None,
            preview: OnceLock::new(),
        };
        if let Some((tick, lat_rad, lon_rad)) = pos {
            if !(lat_rad.is_finite() && lon_rad.is_finite()) {
                return Err("state: the ship's position is not finite".into());
            }
            let mut run = next.build()?;
            let Carrier::Ship(s) = &mut run.carrier else {
                return Err("state: the carrier is not a ship".into());
            };
            s.set_position(
                tick,
                rins_plant::carrier::track::TrackPosition { lat_rad, lon_rad },
            );
            run.now = run.carrier.state_now();
            next.running = Some(run);
        }
        *self = next;
        Ok(())
    }
}

/// Why the ship stopped at the polar limit: the leg, the time and the latitude.
fn polar_stop(carrier: &Carrier, lat_rad: f64) -> String {
    let Carrier::Ship(s) = carrier else {
        return format!("the carrier reached latitude {:.4} °", lat_rad.to_degrees());
    };
    let (tick, _) = s.position();
    let t_s = tick as f64 * s.tick_s();
    let leg = s.track().leg_at(t_s, 0);
    format!(
        "the ship reached latitude {:.4} ° at t = {t_s} s on leg {leg} (continued past its end): \
         ships stay within ±{MAX_LAT_DEG} ° (a rhumb line cannot pass a pole); change the \
         leg's heading or stop the run earlier",
        lat_rad.to_degrees()
    )
}

#[cfg(test)]
mod limits_tests;
#[cfg(test)]
mod tests;
