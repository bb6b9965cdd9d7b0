//! A seed's own isolated table beside the reference table.
//!
//! With azimuth isolation each seed's loop integrates that seed's measured increments, so each
//! seed's outer gimbal stands at its own offset o_k. The seeds of a case sail one sea on one
//! carrier and run one scheme, so their tables differ only in that offset: with δ = o_k − o_ref,
//! C_b^v(k) = R_z(s + o_ref + δ)·R_x(i) = C_b^v(ref)·R(u, δ), a rotation by δ about the outer
//! axis u = R_x(i)ᵀ·z = (0, sin i, cos i) in body axes. The plant therefore moves one reference
//! table, whose loop is fed the reference's own true increments (an ideal loop, the same for
//! every seed), and turns its increments into each seed's:
//!
//! Δθ_k = R(u, δ̄)ᵀ·(Δθ_ref − Δi·x) + Δi·x + (Δo_k − Δo_ref)·u,   Δv_k = R(u, δ̄)ᵀ·Δv_ref,
//!
//! (the carrier's part turned, the inner gimbal's own turn Δi about x kept, the outer gimbal's
//! extra turn added; R(u, δ) leaves u where it is, so the reference's outer turn needs no
//! correction). δ̄ is δ at the interval's middle: the odd parts of δ and u over the interval
//! cancel in the integral, leaving δ̇·h and u̇·h times the carrier rate's change over the
//! interval (an estimate, not a measurement: with δ̇ ~ 1e-6 rad/s and the waves' rate changing by
//! ~7e-5 rad/s over 10 ms, about 1e-15 rad per sample; the hour against each seed's own table
//! in `plant/tests/plant/isolation_reference.rs` bounds the whole difference).
//!
//! What the seeds share beside the motion: the temperature field and the deterministic sensor
//! errors are the reference table's. They depend on the table's azimuth about the outer axis only
//! through the carrier's rate and tilt (scale factor and misalignment times δ times the carrier
//! rate, 1e-5 · δ · |ω|; the up direction moves by δ times the tilt), e.g. 4e-6 °/h on Earth
//! rate for δ = 0.03 rad, and zero-mean along the waves. `Plant::set_isolation_reference(false)`
//! runs each seed's own table instead (the reference the tests compare with).

use nalgebra::{UnitQuaternion, Vector3};

use super::isolation::{IntervalOffset, Isolation};
use crate::stages::interval::Interval;
use crate::state::{Reader, StateError, Writer};
use crate::table::GimbalState;

/// What every seed's table needs from the reference table over one output interval, formed
/// once per interval before the loops are updated.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ReferenceInterval {
    /// The outer axis in body axes at the interval's middle, (0, sin i, cos i).
    pub axis_b: Vector3<f64>,
    /// The inner gimbal's turn over the interval, rad.
    pub inner_step_rad: f64,
    /// The reference loop's offset over the interval.
    pub offset: IntervalOffset,
    /// The navigation frame's turn over the interval ([`super::isolation::nav_frame_turn`]).
    pub nav: UnitQuaternion<f64>,
    /// The scheme's outer angle at the interval's end, rad.
    pub scheme_outer_rad: f64,
    /// Output interval, s.
    pub dt_s: f64,
    /// Internal tick at the interval's end.
    pub tick: u64,
}

/// R(u, δ)ᵀ·v = v·cos δ − (u × v)·sin δ + u·(u·v)·(1 − cos δ): body-axis vector `v` of the
/// reference table in the body axes of the table whose outer gimbal stands δ further, for the
/// outer axis `u` = (0, sin i, cos i) in body axes and `(sin δ, cos δ)`.
#[inline(always)]
fn about_outer_axis(u: &Vector3<f64>, (s, c): (f64, f64), v: &Vector3<f64>) -> Vector3<f64> {
    // u has no x component.
    let ud = u.y * v.y + u.z * v.z;
    let cross = Vector3::new(u.y * v.z - u.z * v.y, u.z * v.x, -u.y * v.x);
    v * c - cross * s + u * (ud * (1.0 - c))
}

/// sin and cos of the offset difference `d`: below 0.1 rad (a seed's loop drifts from the
/// reference's by its gyros' error, milliradians in a week) by their Taylor series to d¹¹ and
/// d¹⁰ (the next terms below 3e-19 relative; to d⁵ and d⁴ below 1e-3 rad), beyond by libm.
#[inline(always)]
fn small_sin_cos(d: f64) -> (f64, f64) {
    let d2 = d * d;
    if d2 < 1e-6 {
        // Below a milliradian (the usual case) the terms from d⁷ and d⁶ on are below 2e-21
        // relative: a short chain (each sample's turn waits on the loop's last update).
        let s = d * (1.0 - d2 * (1.0 / 6.0) * (1.0 - d2 * (1.0 / 20.0)));
        let c = 1.0 - d2 * 0.5 * (1.0 - d2 * (1.0 / 12.0));
        return (s, c);
    }
    if d.abs() >= 0.1 {
        return d.sin_cos();
    }
    let s = d
        * (1.0
            - d2 / 6.0
                * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0 * (1.0 - d2 / 110.0)))));
    let c = 1.0
        - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0 * (1.0 - d2 / 56.0 * (1.0 - d2 / 90.0))));
    (s, c)
}

/// A seed's own loop, turning the reference table's interval into its own.
#[derive(Clone, Debug)]
pub(crate) struct OwnTable {
    /// The seed's isolation loop (fed its measured increments).
    pub lp: Isolation,
}

impl OwnTable {
    /// The reference's interval `x` on this seed's table (module docs): the true increments
    /// turned by the offset difference, the deterministic errors the reference's.
    #[inline(always)]
    pub fn turn(&self, x: &Interval, r: &ReferenceInterval) -> Interval {
        let own = self.lp.interval_offset(r.dt_s);
        let sc = small_sin_cos(own.mid_rad - r.offset.mid_rad);
        let u = r.axis_b;
        let turn = |v: &Vector3<f64>| about_outer_axis(&u, sc, v);
        let inner = Vector3::new(r.inner_step_rad, 0.0, 0.0);
        Interval {
            dtheta_true_rad: turn(&(x.dtheta_true_rad - inner))
                + inner
                + u * (own.step_rad - r.offset.step_rad),
            dv_true_mps: turn(&x.dv_true_mps),
            ..*x
        }
    }

    /// The reference table's true state `g` at the interval's end on this seed's table.
    #[inline(always)]
    pub fn gimbal(&self, mut g: GimbalState, r: &ReferenceInterval) -> GimbalState {
        let own = self.lp.interval_offset(r.dt_s);
        g.angles.outer_rad += own.end_rad - r.offset.end_rad;
        g.outer_rate_rps += own.end_rps - r.offset.end_rps;
        g
    }

    /// Closes the interval: the loop takes the seed's measured increment.
    #[inline(always)]
    pub fn update(&mut self, measured_rad: &Vector3<f64>, r: &ReferenceInterval) {
        self.lp
            .update_with(measured_rad, &r.nav, r.scheme_outer_rad, r.dt_s, r.tick);
    }

    /// Writes the loop's state.
    pub fn write(&self, w: &mut Writer) {
        self.lp.write(w);
    }

    /// Reads what [`OwnTable::write`] wrote.
    pub fn read(r: &mut Reader<'_>) -> Result<Self, StateError> {
        Ok(Self {
            lp: Isolation::read(r)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{GimbalAngles, GimbalFrame};

    /// A carrier vector in the body axes of the table at outer angle o + δ (the gimbal frame
    /// itself) equals the reference table's (at o) turned about the outer axis by δ, for
    /// angles all round, small and large δ.
    #[test]
    fn the_turn_is_the_outer_gimbal_standing_further_by_the_difference() {
        for k in 0..2_000u32 {
            let a = f64::from(k);
            let (outer, inner) = ((a * 0.37).sin() * 3.1, (a * 0.61).cos() * 3.1);
            let d = [1e-7, -4e-4, 0.03, -0.09, 0.7][k as usize % 5] * (a * 0.13).cos();
            let w = Vector3::new((a * 0.7).sin(), (a * 0.3).cos() * 2.0, 9.8 + a.sin());
            let reference = GimbalFrame::at(GimbalAngles::new(outer, inner));
            let seed = GimbalFrame::at(GimbalAngles::new(outer + d, inner));
            let u = Vector3::new(0.0, inner.sin(), inner.cos());
            let got = about_outer_axis(&u, small_sin_cos(d), &reference.to_body(&w));
            let want = seed.to_body(&w);
            assert!(
                (got - want).amax() < 4e-15 * w.norm(),
                "{k}: {got} against {want}"
            );
        }
    }

    /// The series agree with libm to a few ulp on both sides of each switch.
    #[test]
    fn the_small_sine_and_cosine_are_libms_to_rounding() {
        for k in 0..20_000u32 {
            let d = (f64::from(k) * 0.731).sin() * [1.2e-3, 0.12, 1.0][k as usize % 3];
            let (s, c) = small_sin_cos(d);
            let (ls, lc) = d.sin_cos();
            assert!(
                (s - ls).abs() <= 2.0 * f64::EPSILON * ls.abs(),
                "{d}: {s} {ls}"
            );
            assert!((c - lc).abs() <= 2.0 * f64::EPSILON, "{d}: {c} {lc}");
        }
    }
}
