//! Table commands from the navigation computer (a real RINS navigation computer drives its own
//! table): they replace the configured scheme from the next output interval on.

use crate::plant::Plant;
use crate::table::scheme::{GimbalAxis, ResolvedScheme, ResolvedStep};
use crate::table::{Cursor, GimbalAngles, Schedule};

/// A table command from the navigation computer (a real RINS navigation computer drives its own
/// table). It takes effect at the start of the next output interval: the table leaves its
/// current angles at rest and follows the commanded moves with the scheme's acceleration limit.
#[derive(Clone, Debug, PartialEq)]
pub enum GimbalCommand {
    /// Move to these angles, outer gimbal first, then inner, at `rate_rps`; then hold.
    MoveTo {
        /// Target outer (azimuth) angle, rad.
        outer_rad: f64,
        /// Target inner angle, rad.
        inner_rad: f64,
        /// Cruise rate, rad/s.
        rate_rps: f64,
    },
    /// Run these moves from the current angles, then hold the last attitude (or repeat them).
    Steps {
        /// Moves and dwells.
        steps: Vec<ResolvedStep>,
        /// Repeat the list forever.
        repeat: bool,
    },
}

/// The commanded motion that replaced the configured scheme, kept so a saved state can rebuild it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ActiveCommand {
    pub(crate) start_tick: u64,
    pub(crate) initial: GimbalAngles,
    pub(crate) steps: Vec<ResolvedStep>,
    pub(crate) repeat: bool,
}

impl Plant {
    /// Applies a table command from the next output interval on (see [`GimbalCommand`]).
    /// Rejects non-finite or out-of-range angles and rates with the reason.
    pub fn command_gimbal(&mut self, cmd: &GimbalCommand) -> Result<(), String> {
        let now = self.gimbal_now.angles;
        let rate_ok = |r: f64| r.is_finite() && r > 0.0 && r <= 100f64.to_radians();
        let (steps, repeat) = match cmd {
            GimbalCommand::MoveTo {
                outer_rad,
                inner_rad,
                rate_rps,
            } => {
                if !outer_rad.is_finite() || !inner_rad.is_finite() {
                    return Err(format!(
                        "gimbal target must be finite, got outer {outer_rad} rad, inner {inner_rad} rad"
                    ));
                }
                if !rate_ok(*rate_rps) {
                    return Err(format!(
                        "gimbal rate must be in (0, 100] deg/s, got {} deg/s",
                        rate_rps.to_degrees()
                    ));
                }
                let moves = [
                    (GimbalAxis::Outer, outer_rad - now.outer_rad),
                    (GimbalAxis::Inner, inner_rad - now.inner_rad),
                ];
                let steps = moves
                    .into_iter()
                    .filter(|(_, d)| *d != 0.0)
                    .map(|(axis, angle_rad)| ResolvedStep {
                        axis,
                        angle_rad,
                        rate_rps: *rate_rps,
                        dwell_s: 0.0,
                    })
                    .collect();
                (steps, false)
            }
            GimbalCommand::Steps { steps, repeat } => {
                for (i, s) in steps.iter().enumerate() {
                    if !(s.angle_rad.is_finite()
                        && s.angle_rad.abs() <= 3600f64.to_radians()
                        && rate_ok(s.rate_rps)
                        && s.dwell_s >= 0.0
                        && s.dwell_s.is_finite())
                    {
                        return Err(format!(
                            "gimbal step {i}: angle must be finite within ±3600 deg, rate in (0, 100] deg/s, dwell ≥ 0 s; got {} deg, {} deg/s, {} s",
                            s.angle_rad.to_degrees(),
                            s.rate_rps.to_degrees(),
                            s.dwell_s
                        ));
                    }
                }
                if *repeat && steps.iter().all(|s| s.angle_rad == 0.0 && s.dwell_s == 0.0) {
                    return Err("a repeating gimbal step list needs a non-zero duration".into());
                }
                (steps.clone(), *repeat)
            }
        };
        self.install_command(ActiveCommand {
            start_tick: self.tick,
            initial: now,
            steps,
            repeat,
        });
        Ok(())
    }

    pub(crate) fn install_command(&mut self, c: ActiveCommand) {
        self.schedule = Schedule::new(&ResolvedScheme {
            initial: c.initial,
            lead_dwell_s: c.start_tick as f64 / self.internal_rate_hz,
            steps: c.steps.clone(),
            repeat: c.repeat,
            continuous: None,
            accel_rps2: self.cfg.scheme.accel_dps2.to_radians(),
        });
        self.command = Some(c);
        self.cursor = Cursor::default();
        self.hold_until_tick = 0;
        self.dwell_cache = None;
    }
}

impl Plant {
    /// Switches azimuth isolation on or off from the next output interval (the navigation
    /// computer's command; `[carrier] azimuth_isolation` sets it at start). On: the loop restarts
    /// from the table's attitude now and holds the scheme at its present azimuth in the
    /// navigation frame. Off: the outer offset stays where it is. Refused on the static carrier.
    pub fn command_azimuth_isolation(&mut self, on: bool) -> Result<(), String> {
        if self.cfg.carrier.is_static() {
            // An external carrier (attached after building) keeps no isolation state in the
            // plant's saved state, so it cannot run the loop.
            return Err("azimuth isolation refused: the scenario's carrier is static ([carrier] kind = \"static\"; an external carrier attached to it, such as the carrier FMU, counts as static here), so the plant runs no isolation loop; isolation is allowed only with a moving carrier of the scenario itself: [carrier] kind = \"ship\" or \"trajectory\"".into());
        }
        let c_bn = self.attitude_c_bn();
        let (angles, tick) = (self.gimbal_now.angles, self.tick);
        let run = self.carrier.as_mut().ok_or(
            "azimuth isolation needs a moving carrier ([carrier] kind = \"ship\" or \"trajectory\")",
        )?;
        run.set_isolation(on, &c_bn, angles, tick);
        Ok(())
    }
}
