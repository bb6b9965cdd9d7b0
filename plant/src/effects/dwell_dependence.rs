//! What a catalogue error term's contribution does while the table dwells: the invariant the
//! plant's dwell cache rests on (`Plant::deterministic_interval` reuses a held dwell's interval
//! instead of working its ticks again), written down per term so that a new term has to say it.

/// How a catalogue term's contribution behaves over a held dwell: the table still on the static
/// carrier, between two thermal updates (the plant clears its dwell cache on every motion,
/// command and thermal update).
///
/// Every term of [`crate::effects::GyroTerm`] and [`crate::effects::AccelTerm`] names its
/// dependence in an exhaustive `match` (no wildcard arm), so a new term does not compile until
/// its author decides; the plant reuses a dwell's interval only while no switched-on term
/// [`DwellDependence::varies_in_dwell`], and `plant/tests/plant/dwell_cache.rs` checks every
/// term, cache on against cache off, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DwellDependence {
    /// A function of the tick's inputs alone, each the same every tick of a held dwell: the
    /// true increments and specific force, the up, north and east directions in body axes,
    /// and the temperatures (and the rates precomputed from them) between thermal updates. Its
    /// contribution is the same bits every tick, so the dwell's interval may be reused.
    HeldInputs,
    /// Changes from one tick of a held dwell to the next: it reads the time or a motion
    /// clock, or has a state of its own that each tick advances. While such a term is on the
    /// plant works out every tick, as without the cache.
    WithinDwell,
    /// Not part of the deterministic interval the cache keeps: a noise process (angle and
    /// velocity random walk, bias instability, rate random walk) drawn per output sample, or
    /// the output quantisation with its carried residual, both applied by the readout stage
    /// (`stages::readout`) to every sample after the interval, cached or not.
    Readout,
}

impl DwellDependence {
    /// Whether the term's contribution changes within a held dwell, so that the plant must not
    /// reuse the dwell's interval while the term is on.
    pub fn varies_in_dwell(self) -> bool {
        self == DwellDependence::WithinDwell
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::{AccelTerm, GyroTerm};

    /// The readout applies exactly the terms outside the deterministic catalogue (noise and
    /// quantisation): those, and only those, are [`DwellDependence::Readout`], and none of
    /// them is asked whether it varies within a dwell.
    #[test]
    fn the_readout_terms_are_those_outside_the_deterministic_catalogue() {
        for t in GyroTerm::ALL {
            let readout = t.dwell_dependence() == DwellDependence::Readout;
            assert_eq!(readout, !GyroTerm::DETERMINISTIC.contains(&t), "{t:?}");
            assert!(!readout || !t.varies_in_dwell(), "{t:?}");
        }
        for t in AccelTerm::ALL {
            let readout = t.dwell_dependence() == DwellDependence::Readout;
            assert_eq!(readout, !AccelTerm::DETERMINISTIC.contains(&t), "{t:?}");
            assert!(!readout || !t.varies_in_dwell(), "{t:?}");
        }
    }
}
