//! One tick of the IMU's true increments on a moving carrier: the carrier's points (from the
//! ship's segment rule or the carrier's own tick), the gimbal frames at the tick's quadrature
//! points, and [`crate::kinematics::moving_base_increments`].

use nalgebra::Vector3;

use super::Motion;
use crate::carrier::segment::TickPoints;
use crate::carrier::{Carrier, GL_OFFSETS};
use crate::kinematics::{
    CarrierPoint, TableIncrements, carrier_points, dwell_increments, moving_base_increments,
};
use crate::table::{GimbalAngles, GimbalState, SmoothTurn};

impl Motion {
    /// One tick on the moving carrier from table state `g0` to `g1` (`gm` at its middle): the
    /// increments and the up axis in body axes (the mean over the tick). The carrier part is the
    /// ship's segment-rule tick means while the table dwells, their turning-frame expansion
    /// ([`SmoothTurn`]) while a gimbal turns within one profile phase, and two-point
    /// Gauss–Legendre otherwise; the gimbal part is the exact angle difference.
    pub(crate) fn carrier_tick(
        &mut self,
        tick: u64,
        g0: &GimbalState,
        g1: &GimbalState,
        gm: &GimbalState,
        h: f64,
    ) -> (TableIncrements, Vector3<f64>) {
        // Most ticks: the table dwells (no gimbal part), no isolation loop runs, and a ship on
        // its segment rule has the tick's means in body axes ready.
        if g0.angles == g1.angles {
            let run = self.carrier.as_mut().expect("moving carrier");
            if let (None, Carrier::Ship(s)) = (&run.isolation, &mut run.carrier) {
                let frame = run.trig.frame(g1.angles);
                if let Some([w, f, up]) = s.dwell_means(&frame, &mut run.now) {
                    return (dwell_increments(Vector3::zeros(), w, f, h), up);
                }
            }
        }
        // Turning ticks of a ship on its segment rule: the tick's means and slopes through the
        // turning frame (no quadrature points), unless a profile phase changes inside the tick.
        if g0.angles != g1.angles {
            let run = self.carrier.as_mut().expect("moving carrier");
            if let (None, Carrier::Ship(s)) = (&run.isolation, &mut run.carrier)
                && s.segment_ticks().is_some()
                && let Some(turn) = SmoothTurn::of(g0, gm, g1)
            {
                let frame = run.trig.frame_turning(gm.angles, turn.outer);
                if let Some([w, f, up]) = s.turn_means(&frame, &turn, &mut run.now) {
                    // The inner gimbal rests while the outer turns: its angle is the frame's.
                    let d_outer = g1.angles.outer_rad - g0.angles.outer_rad;
                    let gimbal = Vector3::new(
                        g1.angles.inner_rad - g0.angles.inner_rad,
                        frame.sin_inner * d_outer,
                        frame.cos_inner * d_outer,
                    );
                    return (dwell_increments(gimbal, w, f, h), up);
                }
            }
        }
        let angles: [GimbalAngles; 2] = if g0.angles != g1.angles {
            GL_OFFSETS.map(|f| {
                let t = (tick as f64 + f) / self.internal_rate_hz;
                self.schedule.eval_cursor(t, &mut self.cursor).angles
            })
        } else {
            [g1.angles; 2]
        };
        let ticks = self.substeps as f64;
        let dt = self.dt_s;
        let run = self.carrier.as_mut().expect("moving carrier");
        // Azimuth isolation: the outer offset at the tick's ends and quadrature points.
        let iso = run.isolation.as_ref().map(|i| {
            let at = |f: f64| i.offset_at(tick as f64 + f, ticks, dt);
            let rate = |f: f64| i.rate_at(tick as f64 + f, ticks, dt);
            (at(0.0), at(1.0), GL_OFFSETS.map(at), GL_OFFSETS.map(rate))
        });
        let angles = match iso {
            Some((_, _, nodes, _)) => {
                let mut a = angles;
                a.iter_mut().zip(nodes).for_each(|(a, o)| a.outer_rad += o);
                a
            }
            None => angles,
        };
        let turning = angles[0] != angles[1];
        let frames = run.trig.frames(&angles);
        let pts = match &mut run.carrier {
            Carrier::Ship(s) if s.segment_ticks().is_some() => {
                s.advance_points(&frames[0], turning, &mut run.now)
            }
            _ => {
                let mut nodes = [run.now; 2];
                let end = run.carrier.advance(&mut nodes);
                let pts = carrier_points(
                    &run.carrier,
                    &nodes,
                    run.rotation,
                    run.gravity,
                    &run.lever_c_m,
                );
                let up = |i: usize| nodes[i].c_cn.row(2).transpose();
                run.now = end;
                let p = [
                    [pts[0].omega_ic_c, pts[0].f_c, up(0)],
                    [pts[1].omega_ic_c, pts[1].f_c, up(1)],
                ];
                // Carrier axes to the table mount's (C_c^v); the default mount is the identity.
                TickPoints::Nodes(match run.mount_t {
                    None => p,
                    Some(m) => p.map(|q| q.map(|v| m * v)),
                })
            }
        };
        let d_outer = g1.angles.outer_rad - g0.angles.outer_rad;
        // No sine while the outer gimbal rests (most ticks): its terms are zero then. While it
        // turns the inner gimbal rests, at the angle the frames hold.
        let (si, ci) = if d_outer == 0.0 {
            (0.0, 0.0)
        } else {
            run.trig.inner.at(gm.angles.inner_rad)
        };
        let gimbal = Vector3::new(
            g1.angles.inner_rad - g0.angles.inner_rad,
            si * d_outer,
            ci * d_outer,
        );
        let gimbal = match iso {
            // The offset turns the outer axis, [0, sin i, cos i] in body axes: the exact
            // angle difference while the inner gimbal dwells, else two-point Gauss–Legendre of
            // the offset rate times the axis.
            Some((o0, o1, _, rates)) => {
                if angles[0].inner_rad == angles[1].inner_rad {
                    let (si, ci) = (frames[0].sin_inner, frames[0].cos_inner);
                    gimbal + (o1 - o0) * Vector3::new(0.0, si, ci)
                } else {
                    let v = frames
                        .iter()
                        .zip(rates)
                        .fold(Vector3::zeros(), |v, (f, r)| {
                            v + r * Vector3::new(0.0, f.sin_inner, f.cos_inner)
                        });
                    gimbal + 0.5 * h * v
                }
            }
            None => gimbal,
        };
        match pts {
            // The segment rule while the table dwells: the tick's means, already in body axes.
            TickPoints::BodyMean([w, f, up]) => (dwell_increments(gimbal, w, f, h), up),
            TickPoints::Nodes(p) => {
                let pts = p.map(|[w, f, _]| CarrierPoint {
                    omega_ic_c: w,
                    f_c: f,
                });
                let inc = moving_base_increments(&frames, &pts, gimbal, h);
                let up_b = 0.5 * (frames[0].to_body(&p[0][2]) + frames[1].to_body(&p[1][2]));
                (inc, up_b)
            }
        }
    }
}
