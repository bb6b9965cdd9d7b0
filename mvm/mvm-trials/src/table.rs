//! The table's gimbal angles over a run: piecewise linear in time, one gimbal turning at a time
//! at a constant rate (starting and stopping instantly), from outer = inner = 0.

use nalgebra::Vector3;

use crate::design::{Gimbal, TableLeg};
use crate::units::DEG;

/// One piece of constant table state: a dwell, or a move of one gimbal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableSegment {
    /// Start, s of run time.
    pub t0: f64,
    /// End, s (infinite for the final dwell).
    pub t1: f64,
    /// Outer angle at the start, rad.
    pub outer0_rad: f64,
    /// Inner angle at the start, rad.
    pub inner0_rad: f64,
    /// Turn of the outer gimbal over the segment, rad.
    pub d_outer_rad: f64,
    /// Turn of the inner gimbal over the segment, rad.
    pub d_inner_rad: f64,
    /// When the table last stopped (for a dwell: the end of the last move, or the run's start
    /// when there was none), s.
    pub stopped_s: f64,
}

impl TableSegment {
    /// Whether a gimbal turns.
    pub fn moving(&self) -> bool {
        self.d_outer_rad != 0.0 || self.d_inner_rad != 0.0
    }

    /// (outer, inner) at time `t` within the segment, rad. Angles are the start angle plus the
    /// fraction of the turn, so the end angle is exactly start + turn.
    pub fn angles(&self, t: f64) -> (f64, f64) {
        if !self.moving() {
            return (self.outer0_rad, self.inner0_rad);
        }
        let f = (t - self.t0) / (self.t1 - self.t0);
        (
            self.outer0_rad + self.d_outer_rad * f,
            self.inner0_rad + self.d_inner_rad * f,
        )
    }

    /// The gimbals' rate in body axes, rad/s: inner: rate·x̂; outer (inner angle i fixed):
    /// rate·R_x(−i)·ẑ = rate·(0, sin i, cos i).
    pub fn gimbal_rate_body(&self) -> Vector3<f64> {
        if !self.moving() {
            return Vector3::zeros();
        }
        let dur = self.t1 - self.t0;
        let (s, c) = self.inner0_rad.sin_cos();
        Vector3::new(self.d_inner_rad / dur, 0.0, 0.0)
            + Vector3::new(0.0, s, c) * (self.d_outer_rad / dur)
    }

    /// The gimbals' part of the angular increment over [a, b] within the segment, rad: the
    /// exact angle difference of the turning gimbal along its body axis.
    pub fn gimbal_increment(&self, a: f64, b: f64) -> Vector3<f64> {
        if !self.moving() {
            return Vector3::zeros();
        }
        let ((oa, ia), (ob, ib)) = (self.angles(a), self.angles(b));
        let (s, c) = self.inner0_rad.sin_cos();
        Vector3::new(ib - ia, 0.0, 0.0) + Vector3::new(0.0, s, c) * (ob - oa)
    }

    /// Seconds since the table last stopped at time `t` (0 while it moves).
    pub fn since_stop(&self, t: f64) -> f64 {
        if self.moving() {
            0.0
        } else {
            t - self.stopped_s
        }
    }
}

/// The table segments of one run, in time order, covering [0, ∞).
#[derive(Clone, Debug)]
pub struct Timeline {
    /// Segments; the last is a dwell to infinity.
    pub segments: Vec<TableSegment>,
}

impl Timeline {
    /// The timeline of a table sequence (moves of zero angle are skipped).
    ///
    /// # Panics
    /// If a move's rate is not positive.
    pub fn new(table: &[TableLeg]) -> Self {
        let mut segments: Vec<TableSegment> = Vec::new();
        let (mut t, mut o, mut i, mut stopped) = (0.0, 0.0, 0.0, 0.0);
        for leg in table {
            let (dur, d_o, d_i) = match *leg {
                TableLeg::Dwell { dur_s } => (dur_s.max(0.0), 0.0, 0.0),
                TableLeg::Move {
                    gimbal,
                    delta_deg,
                    rate_dps,
                } => {
                    assert!(rate_dps > 0.0, "a move's rate is positive");
                    let d = delta_deg * DEG;
                    let dur = delta_deg.abs() / rate_dps;
                    match gimbal {
                        Gimbal::Outer => (dur, d, 0.0),
                        Gimbal::Inner => (dur, 0.0, d),
                    }
                }
            };
            if dur == 0.0 {
                continue;
            }
            segments.push(TableSegment {
                t0: t,
                t1: t + dur,
                outer0_rad: o,
                inner0_rad: i,
                d_outer_rad: d_o,
                d_inner_rad: d_i,
                stopped_s: stopped,
            });
            t += dur;
            o += d_o;
            i += d_i;
            if d_o != 0.0 || d_i != 0.0 {
                stopped = t;
            }
        }
        // The table keeps its last position.
        segments.push(TableSegment {
            t0: t,
            t1: f64::INFINITY,
            outer0_rad: o,
            inner0_rad: i,
            d_outer_rad: 0.0,
            d_inner_rad: 0.0,
            stopped_s: stopped,
        });
        Self { segments }
    }

    /// Index of the segment that holds time `t` (the later one at a boundary), searching on
    /// from `hint` (a segment at or before it).
    pub fn segment_at(&self, t: f64, hint: usize) -> usize {
        let mut k = hint.min(self.segments.len() - 1);
        while k > 0 && t < self.segments[k].t0 {
            k -= 1;
        }
        while k + 1 < self.segments.len() && t >= self.segments[k].t1 {
            k += 1;
        }
        k
    }
}
