//! The plant's saved state: the header (the format's magic and the configuration's
//! fingerprint) and the stages' parts in order, each stage writing and reading its own
//! (`crate::state` holds the format's pieces and the layout notes).

use super::Plant;
use crate::carrier::own_table::OwnTable;
use crate::config::PlantConfig;
use crate::stages::readout::ReadoutTerms;
use crate::state::{MAGIC, Reader, StateError, Writer, fingerprint};

impl Plant {
    /// The plant's evolving state as bytes (see the module notes for the layout).
    pub fn serialize_state(&self) -> Vec<u8> {
        let mut w = Writer(MAGIC.to_vec());
        w.u64(fingerprint(self.config()));
        self.write_state(&mut w);
        w.0
    }

    /// A plant built from `cfg` and resumed from `bytes` (from [`Plant::serialize_state`] of a
    /// plant with the same configuration): it continues bit-identically.
    pub fn from_serialized_state(cfg: &PlantConfig, bytes: &[u8]) -> Result<Plant, StateError> {
        if bytes.len() < 16 || &bytes[..8] != MAGIC {
            return Err(StateError::BadHeader);
        }
        let mut r = Reader::new(bytes, MAGIC.len());
        let saved = r.u64()?;
        let current = fingerprint(cfg);
        if saved != current {
            return Err(StateError::ConfigMismatch { saved, current });
        }
        let mut plant = Plant::new(cfg).map_err(|e| {
            StateError::Config(
                e.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join("; "),
            )
        })?;
        plant.read_state(&mut r)?;
        if r.pos() != bytes.len() {
            return Err(StateError::Length {
                got: bytes.len(),
                expected: r.pos(),
            });
        }
        Ok(plant)
    }

    /// Writes every evolving quantity, stage by stage (caches excluded), for [`crate::state`].
    pub(crate) fn write_state(&self, w: &mut Writer) {
        w.u64(self.clock.tick());
        w.u64(self.clock.samples());
        self.temperature.write(w);
        self.lane.readout.write(w);
        self.write_truth(w);
        self.errors.write(w, &self.truth);
        self.motion.write(w);
        w.u64(self.lane.own.is_some() as u64);
        if let Some(o) = &self.lane.own {
            o.write(w);
        }
    }

    /// Reads what [`Plant::write_state`] wrote into a freshly built plant of the same
    /// configuration, then rebuilds the derived quantities.
    pub(crate) fn read_state(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        let (tick, samples) = (r.u64()?, r.u64()?);
        self.clock.restore(tick, samples);
        self.temperature.read(r)?;
        self.lane.readout.read(r)?;
        self.read_truth(r)?;
        let temps = self.temperature.temperatures();
        self.errors.read(r, &temps, &mut self.truth)?;
        self.motion.read(r, tick)?;
        self.lane.own = match r.u64()? {
            0 => None,
            1 if self.motion.carrier().is_some_and(|c| c.isolation.is_some()) => {
                Some(OwnTable::read(r)?)
            }
            f => {
                return Err(StateError::Inconsistent(format!(
                    "own isolation loop flag {f} (0 or 1, and 1 only beside the table's loop)"
                )));
            }
        };
        self.truth.gimbal = self.motion.gimbal_now();
        self.dwell = None;
        Ok(())
    }

    /// The truth's evolving part (the rest is rebuilt or filled in by the next step).
    fn write_truth(&self, w: &mut Writer) {
        let mut tr = self.truth;
        self.lane.readout.terms().write_into(&mut tr);
        w.v3(&tr.dtheta_true_rad);
        w.v3(&tr.dv_true_mps);
        tr.temps.nodes_c.iter().for_each(|x| w.f64(*x));
        w.f64(tr.temps.chamber_c);
        tr.gyro_terms_rad.iter().for_each(|v| w.v3(v));
        tr.accel_terms_mps.iter().for_each(|v| w.v3(v));
        w.f64(tr.position_weight);
    }

    fn read_truth(&mut self, r: &mut Reader<'_>) -> Result<(), StateError> {
        let tr = &mut self.truth;
        tr.dtheta_true_rad = r.v3()?;
        tr.dv_true_mps = r.v3()?;
        for n in tr.temps.nodes_c.iter_mut() {
            *n = r.f64()?;
        }
        tr.temps.chamber_c = r.f64()?;
        for v in tr.gyro_terms_rad.iter_mut() {
            *v = r.v3()?;
        }
        for v in tr.accel_terms_mps.iter_mut() {
            *v = r.v3()?;
        }
        tr.position_weight = r.f64()?;
        self.lane
            .readout
            .set_terms(ReadoutTerms::read_from(&self.truth));
        Ok(())
    }
}
