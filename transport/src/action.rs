//! What a navigator's command asks of the plant, one definition for the wire, the plant link
//! and the in-process reference.

use rins_plant::{GimbalCommand, Plant};

use crate::layout::{NavCommand, kind};

/// A command to the plant beyond acknowledging (docs/transport.md, "Commands back").
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NavAction {
    /// Move the table to (`outer_rad`, `inner_rad`) at `rate_rps` (`kind` 1).
    MoveTo {
        /// Target outer angle, rad.
        outer_rad: f64,
        /// Target inner angle, rad.
        inner_rad: f64,
        /// Cruise rate, rad/s.
        rate_rps: f64,
    },
    /// Switch azimuth isolation on (`kind` 4) or off (`kind` 5): the outer gimbal counter-rotates
    /// the carrier's yaw (docs/carrier.md, "Azimuth isolation").
    AzimuthIsolation(bool),
}

impl NavAction {
    /// The action a received command carries (`None`: acknowledge, stop or hello only).
    pub fn from_command(c: &NavCommand) -> Option<Self> {
        match c.kind {
            kind::MOVE_TO => Some(Self::MoveTo {
                outer_rad: c.outer_rad,
                inner_rad: c.inner_rad,
                rate_rps: c.rate_rps,
            }),
            kind::AZIMUTH_ISOLATION_ON => Some(Self::AzimuthIsolation(true)),
            kind::AZIMUTH_ISOLATION_OFF => Some(Self::AzimuthIsolation(false)),
            _ => None,
        }
    }

    /// Writes the action into an acknowledgement `c` (its kind and fields).
    pub fn write(&self, c: &mut NavCommand) {
        match *self {
            Self::MoveTo {
                outer_rad,
                inner_rad,
                rate_rps,
            } => {
                c.kind = kind::MOVE_TO;
                (c.outer_rad, c.inner_rad, c.rate_rps) = (outer_rad, inner_rad, rate_rps);
            }
            Self::AzimuthIsolation(on) => {
                c.kind = if on {
                    kind::AZIMUTH_ISOLATION_ON
                } else {
                    kind::AZIMUTH_ISOLATION_OFF
                };
            }
        }
    }

    /// Applies the action to `plant` from its next output interval; the plant's reason when it
    /// refuses (a move out of range, isolation on a static carrier).
    pub fn apply(&self, plant: &mut Plant) -> Result<(), String> {
        match *self {
            Self::MoveTo {
                outer_rad,
                inner_rad,
                rate_rps,
            } => plant.command_gimbal(&GimbalCommand::MoveTo {
                outer_rad,
                inner_rad,
                rate_rps,
            }),
            Self::AzimuthIsolation(on) => plant.command_azimuth_isolation(on),
        }
    }
}
