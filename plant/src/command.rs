//! Table commands from the navigation computer (a real RINS navigation computer drives its own
//! table): they replace the configured scheme from the next output interval on.

use crate::message::Num;
use crate::table::GimbalAngles;
use crate::table::gimbal::GimbalAxis;
use crate::table::scheme::ResolvedStep;

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

impl ActiveCommand {
    /// The motion `cmd` asks for from internal tick `start_tick`, the table at `now`. Rejects
    /// non-finite or out-of-range angles and rates with the reason.
    pub(crate) fn new(
        cmd: &GimbalCommand,
        now: GimbalAngles,
        start_tick: u64,
    ) -> Result<Self, String> {
        let rate_ok = |r: f64| r.is_finite() && r > 0.0 && r <= 100f64.to_radians();
        let (steps, repeat) = match cmd {
            GimbalCommand::MoveTo {
                outer_rad,
                inner_rad,
                rate_rps,
            } => {
                if !outer_rad.is_finite() || !inner_rad.is_finite() {
                    return Err(format!(
                        "gimbal target must be finite, got outer {} rad, inner {} rad",
                        Num(*outer_rad),
                        Num(*inner_rad)
                    ));
                }
                if !rate_ok(*rate_rps) {
                    return Err(format!(
                        "gimbal rate must be in (0, 100] deg/s, got {} deg/s",
                        Num(rate_rps.to_degrees())
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
                            Num(s.angle_rad.to_degrees()),
                            Num(s.rate_rps.to_degrees()),
                            Num(s.dwell_s)
                        ));
                    }
                }
                if *repeat && steps.iter().all(|s| s.angle_rad == 0.0 && s.dwell_s == 0.0) {
                    return Err("a repeating gimbal step list needs a non-zero duration".into());
                }
                (steps.clone(), *repeat)
            }
        };
        Ok(Self {
            start_tick,
            initial: now,
            steps,
            repeat,
        })
    }
}
