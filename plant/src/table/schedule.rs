//! A resolved scheme laid out on the time axis, evaluated statelessly at any time so that a
//! saved plant state (tick counter only) restores the table exactly.

use super::gimbal::GimbalAngles;
use super::gimbal::GimbalAxis;
use super::profile::TrapezoidProfile;
use super::scheme::ResolvedScheme;

/// Where the table is at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GimbalState {
    /// Gimbal angles, rad.
    pub angles: GimbalAngles,
    /// Outer gimbal rate, rad/s.
    pub outer_rate_rps: f64,
    /// Inner gimbal rate, rad/s.
    pub inner_rate_rps: f64,
    /// Index of the current step in the step list (0 during the lead dwell).
    pub step_index: usize,
    /// True while a gimbal moves.
    pub moving: bool,
}

/// Remembers the segment of the last evaluation so monotonic callers skip the lookup.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cursor {
    start_abs_s: f64,
    end_abs_s: f64,
    seg: usize,
    cycle: f64,
}

impl Default for Cursor {
    fn default() -> Self {
        Self {
            start_abs_s: f64::INFINITY,
            end_abs_s: f64::NEG_INFINITY,
            seg: 0,
            cycle: 0.0,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    start_s: f64,
    from: GimbalAngles,
    axis: GimbalAxis,
    profile: TrapezoidProfile,
    move_end_s: f64,
    end_s: f64,
}

/// A scheme compiled to time segments: a lead dwell, then one cycle of moves and dwells that
/// repeats (or holds the final attitude).
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    initial: GimbalAngles,
    lead_s: f64,
    segments: Vec<Segment>,
    cycle_s: f64,
    cycle_delta: GimbalAngles,
    repeat: bool,
    continuous: Option<(GimbalAxis, f64)>,
}

impl Schedule {
    /// Lays out `scheme` in time.
    pub fn new(scheme: &ResolvedScheme) -> Self {
        let mut t = 0.0;
        let mut at = scheme.initial;
        let mut segments = Vec::with_capacity(scheme.steps.len());
        for s in &scheme.steps {
            let profile = TrapezoidProfile::new(s.angle_rad, s.rate_rps, scheme.accel_rps2);
            let move_end = t + profile.duration_s();
            let end = move_end + s.dwell_s;
            segments.push(Segment {
                start_s: t,
                from: at,
                axis: s.axis,
                profile,
                move_end_s: move_end,
                end_s: end,
            });
            at = at.moved(s.axis, s.angle_rad);
            t = end;
        }
        let cycle_delta = GimbalAngles::new(
            at.outer_rad - scheme.initial.outer_rad,
            at.inner_rad - scheme.initial.inner_rad,
        );
        Self {
            initial: scheme.initial,
            lead_s: scheme.lead_dwell_s,
            segments,
            cycle_s: t,
            cycle_delta,
            repeat: scheme.repeat,
            continuous: scheme.continuous,
        }
    }

    /// Duration of one cycle of moves and dwells (0 for static/continuous), s.
    pub fn cycle_s(&self) -> f64 {
        self.cycle_s
    }

    /// Lead dwell before the first move, s.
    pub fn lead_s(&self) -> f64 {
        self.lead_s
    }

    /// Start, end-of-move and end times of every step of the first cycle (relative to the
    /// cycle start). Quadrature and analysis split integrals at these instants.
    pub fn step_times_s(&self) -> Vec<(f64, [f64; 4], f64)> {
        self.segments
            .iter()
            .map(|s| {
                (
                    s.start_s,
                    s.profile.breakpoints_s().map(|b| b + s.start_s),
                    s.end_s,
                )
            })
            .collect()
    }

    /// [`Schedule::eval`] through a cursor: identical results, but while `t_s` stays inside the
    /// cursor's segment (moves of repeating schemes) no lookup is done.
    pub fn eval_cursor(&self, t_s: f64, cur: &mut Cursor) -> GimbalState {
        if t_s >= cur.start_abs_s && t_s < cur.end_abs_s {
            return self.eval_segment(
                cur.seg,
                cur.cycle,
                t_s - self.lead_s - cur.cycle * self.cycle_s,
            );
        }
        let st = self.eval(t_s);
        let tau = t_s - self.lead_s;
        if tau >= 0.0
            && self.continuous.is_none()
            && !self.segments.is_empty()
            && (self.repeat || tau < self.cycle_s)
        {
            let cycle = if self.repeat {
                (tau / self.cycle_s).floor()
            } else {
                0.0
            };
            let seg = &self.segments[st.step_index];
            let base = self.lead_s + cycle * self.cycle_s;
            *cur = Cursor {
                start_abs_s: base + seg.start_s,
                end_abs_s: base + seg.end_s,
                seg: st.step_index,
                cycle,
            };
        }
        st
    }

    fn eval_segment(&self, idx: usize, cycle: f64, local: f64) -> GimbalState {
        let seg = &self.segments[idx];
        let from = GimbalAngles::new(
            seg.from.outer_rad + cycle * self.cycle_delta.outer_rad,
            seg.from.inner_rad + cycle * self.cycle_delta.inner_rad,
        );
        let dt = local - seg.start_s;
        let angles = from.moved(seg.axis, seg.profile.angle_at(dt));
        let rate = seg.profile.rate_at(dt);
        let (o, i) = match seg.axis {
            GimbalAxis::Outer => (rate, 0.0),
            GimbalAxis::Inner => (0.0, rate),
        };
        GimbalState {
            angles,
            outer_rate_rps: o,
            inner_rate_rps: i,
            step_index: idx,
            moving: local < seg.move_end_s,
        }
    }

    /// Table state at `t_s` and the time until which that state holds unchanged (the end of the
    /// current dwell; `t_s` itself while moving). Lets callers skip evaluation during dwells.
    pub fn eval_hold(&self, t_s: f64) -> (GimbalState, f64) {
        let st = self.eval(t_s);
        if st.moving {
            return (st, t_s);
        }
        let tau = t_s - self.lead_s;
        if tau < 0.0 {
            return (st, self.lead_s);
        }
        if self.continuous.is_some() {
            return (st, t_s);
        }
        if self.segments.is_empty() || (!self.repeat && tau >= self.cycle_s) {
            return (st, f64::INFINITY);
        }
        let n = if self.repeat {
            (tau / self.cycle_s).floor()
        } else {
            0.0
        };
        let end = self.lead_s + n * self.cycle_s + self.segments[st.step_index].end_s;
        (st, end)
    }

    /// Table state at `t_end_s` with its hold time (as [`Schedule::eval_hold`]) and at the
    /// earlier instant `t_mid_s`, sharing the segment lookup when both fall in one segment.
    pub fn eval_end_and_mid(
        &self,
        t_end_s: f64,
        t_mid_s: f64,
        cur: &mut Cursor,
    ) -> ((GimbalState, f64), GimbalState) {
        let mid = self.eval_cursor(t_mid_s, cur);
        let end = self.eval_cursor(t_end_s, cur);
        let hold = if end.moving {
            t_end_s
        } else {
            self.eval_hold(t_end_s).1
        };
        ((end, hold), mid)
    }

    /// Table state at time `t_s` since the run start.
    pub fn eval(&self, t_s: f64) -> GimbalState {
        let still = |angles, step_index| GimbalState {
            angles,
            outer_rate_rps: 0.0,
            inner_rate_rps: 0.0,
            step_index,
            moving: false,
        };
        let tau = t_s - self.lead_s;
        if tau < 0.0 {
            return still(self.initial, 0);
        }
        if let Some((axis, rate)) = self.continuous {
            let angles = self.initial.moved(axis, rate * tau);
            let (o, i) = match axis {
                GimbalAxis::Outer => (rate, 0.0),
                GimbalAxis::Inner => (0.0, rate),
            };
            return GimbalState {
                angles,
                outer_rate_rps: o,
                inner_rate_rps: i,
                step_index: 0,
                moving: true,
            };
        }
        if self.segments.is_empty() {
            return still(self.initial, 0);
        }
        let (cycle, local) = if self.repeat {
            let n = (tau / self.cycle_s).floor();
            (n, tau - n * self.cycle_s)
        } else if tau >= self.cycle_s {
            let end = self
                .initial
                .moved(GimbalAxis::Outer, self.cycle_delta.outer_rad)
                .moved(GimbalAxis::Inner, self.cycle_delta.inner_rad);
            return still(end, self.segments.len() - 1);
        } else {
            (0.0, tau)
        };
        // Few segments (≤ 16 typically): binary search on end times.
        let idx = self
            .segments
            .partition_point(|s| s.end_s <= local)
            .min(self.segments.len() - 1);
        self.eval_segment(idx, cycle, local)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::scheme::SchemeSpec;
    use approx::assert_relative_eq;

    #[test]
    fn cursor_evaluation_equals_lookup() {
        for spec in [
            SchemeSpec::default(),
            SchemeSpec {
                lead_dwell_s: 33.3,
                ..SchemeSpec::default()
            },
        ] {
            let sched = Schedule::new(&spec.resolve());
            let mut cur = Cursor::default();
            for k in 0..1_000_000u64 {
                let t = k as f64 * 0.01 + 0.005;
                assert_eq!(sched.eval_cursor(t, &mut cur), sched.eval(t), "t = {t}");
            }
        }
    }

    #[test]
    fn sixteen_position_cycle_time_and_periodicity() {
        let spec = SchemeSpec {
            accel_dps2: f64::INFINITY,
            ..SchemeSpec::default()
        };
        let sched = Schedule::new(&spec.resolve());
        // 16 (T_r + T_s) with T_r = 180°/2°/s = 90 s and T_s = 180 s.
        assert_relative_eq!(sched.cycle_s(), 16.0 * 270.0, epsilon = 1e-9);
        // The cycle returns to A with net zero rotation (Eq. 7: the scheme returns to A).
        let a = sched.eval(0.5 * sched.cycle_s());
        let b = sched.eval(1.5 * sched.cycle_s());
        assert_relative_eq!(
            a.angles.outer_rad.rem_euclid(std::f64::consts::TAU),
            b.angles.outer_rad.rem_euclid(std::f64::consts::TAU),
            epsilon = 1e-9
        );
        assert_relative_eq!(
            a.angles.inner_rad.rem_euclid(std::f64::consts::TAU),
            b.angles.inner_rad.rem_euclid(std::f64::consts::TAU),
            epsilon = 1e-9
        );
        // 45 s into sequence 1: half way through the first 180° turn at 2°/s.
        let s = sched.eval(45.0);
        assert!(s.moving);
        assert_relative_eq!(s.angles.outer_rad, 90f64.to_radians(), epsilon = 1e-12);
        assert_relative_eq!(s.outer_rate_rps, 2f64.to_radians(), epsilon = 1e-15);
    }
}
