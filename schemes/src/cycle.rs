//! One cycle of a scheme cut into the pieces the integrals are split at: every move's
//! acceleration, cruise and deceleration, and every dwell, from the plant's own [`Schedule`].

use nalgebra::Matrix3;
use rins_plant::effects::custom::MotionClocks;
use rins_plant::table::{
    GimbalAngles, GimbalAxis, Schedule, SchemeKind, SchemeSpec, body_to_nav, gimbal_body_rate,
};

/// Gauss–Legendre sub-intervals of a move's cruise (up to π of rotation at constant rate) and
/// of an acceleration ramp. 16 × 10 nodes integrate a degree-3 trigonometric polynomial over
/// π to the last bit.
pub const CRUISE_PIECES: usize = 16;
/// See [`CRUISE_PIECES`].
pub const RAMP_PIECES: usize = 4;
/// Sub-intervals of a continuous rotation's revolution.
pub const REVOLUTION_PIECES: usize = 64;
/// Nominal cycle of a static table, s (its residual per cycle is its value times this).
pub const STATIC_CYCLE_S: f64 = 3600.0;

/// The table's state at an instant, all the effects read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableState {
    /// Gimbal angles, rad.
    pub angles: GimbalAngles,
    /// Outer gimbal rate, rad/s.
    pub outer_rate_rps: f64,
    /// Inner gimbal rate, rad/s.
    pub inner_rate_rps: f64,
    /// The table's motion clocks (since it last stopped, since it last started), s.
    pub since: MotionClocks,
}

impl TableState {
    /// C_b^n with the vehicle level at azimuth 0.
    pub fn c_bn(&self) -> Matrix3<f64> {
        body_to_nav(&Matrix3::identity(), self.angles)
    }

    /// Body rate relative to the vehicle (no Earth rate), rad/s.
    pub fn body_rate_rps(&self) -> nalgebra::Vector3<f64> {
        gimbal_body_rate(
            self.angles.inner_rad,
            self.outer_rate_rps,
            self.inner_rate_rps,
        )
    }
}

/// A move at constant rate: the attitude is C(θ) = C₀·R(axis, θ), θ = rate·(t − start).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantRate {
    /// Gimbal angles at the piece's start.
    pub from: GimbalAngles,
    /// The gimbal that moves.
    pub axis: GimbalAxis,
    /// Signed rate, rad/s.
    pub rate_rps: f64,
    /// Motion clocks at the piece's start (since the last stop is 0 while moving).
    pub since_start_s: f64,
}

impl ConstantRate {
    /// The state after turning by `theta_rad` (any angle: the trigonometric integration
    /// samples the rotation over a whole turn).
    pub fn at(&self, theta_rad: f64) -> TableState {
        let (o, i) = match self.axis {
            GimbalAxis::Outer => (self.rate_rps, 0.0),
            GimbalAxis::Inner => (0.0, self.rate_rps),
        };
        TableState {
            angles: self.from.moved(self.axis, theta_rad),
            outer_rate_rps: o,
            inner_rate_rps: i,
            since: MotionClocks {
                move_s: 0.0,
                start_s: self.since_start_s + theta_rad / self.rate_rps,
            },
        }
    }
}

/// What happens over a piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceKind {
    /// The table stands at `angles`; `since_stop_s` is the motion clock at the piece's start.
    Dwell {
        /// Where it stands.
        angles: GimbalAngles,
        /// Seconds since the table stopped, at the piece's start.
        since_stop_s: f64,
        /// Seconds since the table last started to move, at the piece's start.
        since_start_s: f64,
    },
    /// The table turns at constant rate.
    Cruise(ConstantRate),
    /// The table accelerates or decelerates (quadrature only).
    Ramp {
        /// When the move started, s (absolute).
        move_start_s: f64,
    },
}

/// One piece of a cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// Start, s (absolute time of the run).
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// What the table does.
    pub kind: PieceKind,
    /// Gauss–Legendre sub-intervals.
    pub gl_pieces: usize,
}

impl Piece {
    /// Whether the table moves.
    pub fn moving(&self) -> bool {
        !matches!(self.kind, PieceKind::Dwell { .. })
    }
}

/// One cycle of a scheme.
#[derive(Clone, Debug)]
pub struct Cycle {
    /// The plant's schedule of the scheme.
    pub schedule: Schedule,
    /// Cycle start (after the lead dwell), s.
    pub start_s: f64,
    /// Cycle length, s.
    pub period_s: f64,
    /// The pieces, in time order, covering [start, start + period).
    pub pieces: Vec<Piece>,
    /// Whether every move runs at constant rate (infinite table acceleration): then every
    /// piece is a dwell or a cruise and the exact integration applies.
    pub constant_rate: bool,
    /// Number of dwell positions per cycle.
    pub positions: usize,
}

/// Why a scheme has no cycle to analyse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CycleError {
    /// The step list does not repeat.
    #[error("the scheme does not repeat (kind {0:?} with repeat = false): it has no cycle")]
    NotPeriodic(SchemeKind),
    /// The cycle does not bring the IMU back to its start attitude.
    #[error(
        "one cycle ends {0:.3e} (max |ΔC|) away from its start attitude: a per-cycle residual needs a scheme that returns to where it began"
    )]
    DoesNotClose(f64),
}

impl Cycle {
    /// Lays out one cycle of `spec` (its first, after the lead dwell).
    pub fn new(spec: &SchemeSpec) -> Result<Self, CycleError> {
        let resolved = spec.resolve();
        let schedule = Schedule::new(&resolved);
        let lead = schedule.lead_s();
        if let Some((axis, rate)) = resolved.continuous {
            let period = std::f64::consts::TAU / rate.abs();
            let from = schedule.eval(lead).angles;
            let cr = ConstantRate {
                from,
                axis,
                rate_rps: rate,
                since_start_s: lead,
            };
            return Ok(Self {
                schedule,
                start_s: lead,
                period_s: period,
                pieces: vec![Piece {
                    start_s: lead,
                    end_s: lead + period,
                    kind: PieceKind::Cruise(cr),
                    gl_pieces: REVOLUTION_PIECES,
                }],
                constant_rate: true,
                positions: 0,
            });
        }
        if resolved.steps.is_empty() {
            let angles = schedule.eval(lead).angles;
            return Ok(Self {
                schedule,
                start_s: lead,
                period_s: STATIC_CYCLE_S,
                pieces: vec![Piece {
                    start_s: lead,
                    end_s: lead + STATIC_CYCLE_S,
                    kind: PieceKind::Dwell {
                        angles,
                        since_stop_s: lead,
                        since_start_s: lead,
                    },
                    gl_pieces: 1,
                }],
                constant_rate: true,
                positions: 1,
            });
        }
        if !resolved.repeat {
            return Err(CycleError::NotPeriodic(spec.kind));
        }
        let mut pieces = Vec::new();
        let mut constant_rate = true;
        for (start, bp, end) in schedule.step_times_s() {
            let (start, end) = (lead + start, lead + end);
            let bp = bp.map(|b| lead + b);
            let st = schedule.eval(0.5 * (bp[1] + bp[2]));
            let axis = if st.outer_rate_rps != 0.0 {
                GimbalAxis::Outer
            } else {
                GimbalAxis::Inner
            };
            let rate = st.outer_rate_rps + st.inner_rate_rps;
            for (a, b) in [(bp[0], bp[1]), (bp[2], bp[3])] {
                if b > a {
                    constant_rate = false;
                    pieces.push(Piece {
                        start_s: a,
                        end_s: b,
                        kind: PieceKind::Ramp {
                            move_start_s: start,
                        },
                        gl_pieces: RAMP_PIECES,
                    });
                }
            }
            if bp[2] > bp[1] {
                let from = schedule.eval(bp[1]).angles;
                pieces.push(Piece {
                    start_s: bp[1],
                    end_s: bp[2],
                    kind: PieceKind::Cruise(ConstantRate {
                        from,
                        axis,
                        rate_rps: rate,
                        since_start_s: bp[1] - start,
                    }),
                    gl_pieces: CRUISE_PIECES,
                });
            }
            if end > bp[3] {
                pieces.push(Piece {
                    start_s: bp[3],
                    end_s: end,
                    kind: PieceKind::Dwell {
                        angles: schedule.eval(0.5 * (bp[3] + end)).angles,
                        since_stop_s: 0.0,
                        since_start_s: bp[3] - start,
                    },
                    gl_pieces: 1,
                });
            }
        }
        pieces.sort_by(|a, b| a.start_s.total_cmp(&b.start_s));
        let period = schedule.cycle_s();
        let c0 = body_to_nav(&Matrix3::identity(), schedule.eval(lead).angles);
        let c1 = body_to_nav(&Matrix3::identity(), schedule.eval(lead + period).angles);
        let gap = (c1 - c0).abs().max();
        if gap > 1e-9 {
            return Err(CycleError::DoesNotClose(gap));
        }
        Ok(Self {
            schedule,
            start_s: lead,
            period_s: period,
            positions: resolved.steps.len(),
            pieces,
            constant_rate,
        })
    }

    /// The table's state at `t_s` inside `piece` (the plant's schedule for the angles and
    /// rates; the piece for the motion clocks).
    pub fn state(&self, piece: &Piece, t_s: f64) -> TableState {
        let g = self.schedule.eval(t_s);
        let since = match piece.kind {
            PieceKind::Dwell {
                since_stop_s,
                since_start_s,
                ..
            } => MotionClocks {
                move_s: since_stop_s + (t_s - piece.start_s),
                start_s: since_start_s + (t_s - piece.start_s),
            },
            PieceKind::Cruise(cr) => MotionClocks {
                move_s: 0.0,
                start_s: cr.since_start_s + (t_s - piece.start_s),
            },
            PieceKind::Ramp { move_start_s } => MotionClocks {
                move_s: 0.0,
                start_s: t_s - move_start_s,
            },
        };
        TableState {
            angles: g.angles,
            outer_rate_rps: g.outer_rate_rps,
            inner_rate_rps: g.inner_rate_rps,
            since,
        }
    }
}
