//! A tick on which one gimbal turns smoothly, and the mean over that tick of a carrier vector
//! seen in the turning body frame, from the vector's tick mean and slope: what the moving base
//! needs while the table turns, without evaluating the table and the carrier at the tick's
//! quadrature points.
//!
//! Over a tick of length h with middle t_m, let the turning gimbal's angle be
//! a(t_m + τ) = a_m + r·τ + ½α·τ² (exact within one phase of the move profile) and a carrier
//! vector w(t_m + τ) = w̄ + w′·τ + ½w″·(τ² − h²/12) + … (w̄ its mean over the tick). The frame
//! turns by R(τ) = exp(a(τ)·K) relative to the middle, K the generator of the transposed
//! rotation the body frame applies (K·v = v × axis; on the plane of the turn K² = −1, so K³ = −K
//! and K⁴ = −K²). Integrating the series of R(τ)·w(τ) over the tick, to O(h⁴) in everything but
//! w″ and w‴:
//!
//! (1/h)∫R(τ)·w dτ = w̄ + K·[(Q/6 − QΔ²/80)·w̄ + (Δ/24 − Δ³/960)·D]
//!                      + K²·[(Δ²/24 + Q²/40 − Δ⁴/1920)·w̄ + (QΔ/80)·D],
//!
//! with Δ = a(end) − a(start) = r·h, Q = a(start) − 2a(middle) + a(end) = α·h²/4 and
//! D = 2h·w′ ([`crate::carrier::segment::SegmentRule::mean_and_slope`]: from five tick means,
//! exact to O(h⁵)). The second-order part is Δ·K·D/24 + Q·K·w̄/6 + Δ²·K²·w̄/24; the rest are
//! the fourth-order terms in w̄ and D (Q²/40: the table's acceleration phases). Left out:
//! K·(α·w″/720 + r·w‴/480)·h⁴ and K²·r²·w″·h⁴/720, e.g. 6e-12 m/s² (6e-14 m/s per step) for a
//! 2°/s table under a 1 m/s² sea at 2 rad/s at 100 Hz, below the two-point Gauss–Legendre
//! rule's own error there.

use nalgebra::Vector3;

use super::{GimbalFrame, GimbalState};

/// Largest departure from a linear rate over the tick that still counts as one profile phase,
/// rad/s: rounding leaves ~1e-17; a phase change inside the tick leaves α times its distance
/// from the tick's end (a distance under 3e-12 s at 20°/s² then errs by ~1e-24 rad).
const RATE_KINK_RPS: f64 = 1e-12;

/// One gimbal turning over a tick with its angle quadratic in time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothTurn {
    /// True when the outer gimbal turns (else the inner).
    pub outer: bool,
    /// Δ = a(end) − a(start), rad.
    pub delta_rad: f64,
    /// Q = a(start) − 2·a(middle) + a(end) = α·h²/4, rad.
    pub q_rad: f64,
    /// The expansion's coefficients of K·w̄, K·D, K²·w̄ and K²·D (module docs).
    coef: [f64; 4],
}

impl SmoothTurn {
    /// The turn over a tick from the table states at its start, middle and end; `None` when
    /// both gimbals turn or a phase of the move profile changes inside the tick (the rate is not
    /// linear across it: the angle is not one quadratic).
    pub fn of(g0: &GimbalState, gm: &GimbalState, g1: &GimbalState) -> Option<Self> {
        let (a0, a1) = (g0.angles, g1.angles);
        let outer = a0.outer_rad != a1.outer_rad;
        if outer && a0.inner_rad != a1.inner_rad {
            return None;
        }
        let pick = |g: &GimbalState| {
            if outer {
                (g.angles.outer_rad, g.outer_rate_rps)
            } else {
                (g.angles.inner_rad, g.inner_rate_rps)
            }
        };
        let ((x0, r0), (xm, rm), (x1, r1)) = (pick(g0), pick(gm), pick(g1));
        if !((r0 + r1 - 2.0 * rm).abs() <= RATE_KINK_RPS) {
            return None;
        }
        let (dl, q) = (x1 - x0, x0 - 2.0 * xm + x1);
        Some(Self {
            outer,
            delta_rad: dl,
            q_rad: q,
            coef: [
                q / 6.0 - q * dl * dl / 80.0,
                dl / 24.0 - dl * dl * dl / 960.0,
                dl * dl / 24.0 + q * q / 40.0 - dl * dl * dl * dl / 1920.0,
                q * dl / 80.0,
            ],
        })
    }

    /// The mean over the tick of C_v^b(t)·w(t) (module docs), from the mean `mean` of w and
    /// `diff` = D = 2h·w′ in the table mount's axes; `frame` is the gimbal frame at the tick's
    /// middle.
    #[inline]
    pub fn mean_in_body(
        &self,
        frame: &GimbalFrame,
        mean: &Vector3<f64>,
        diff: &Vector3<f64>,
    ) -> Vector3<f64> {
        let [c_w, c_d, c_kw, c_kd] = self.coef;
        if self.outer {
            // R_z(a_m + δ)ᵀ = R_z(δ)ᵀ·R_z(a_m)ᵀ: the turn acts between the two plane rotations.
            // K = K_z leaves the z component alone and sees only D's x and y.
            let w = frame.outer_to(mean);
            let (so, co) = (frame.sin_outer, frame.cos_outer);
            let (dx, dy) = (co * diff.x + so * diff.y, co * diff.y - so * diff.x);
            // w + c_w·K·w + c_d·K·D + c_kw·K²·w + c_kd·K²·D with K(x, y, z) = (y, −x, 0),
            // K² = −1 on x, y.
            let x = w.x + c_w * w.y + c_d * dy - c_kw * w.x - c_kd * dx;
            let y = w.y - c_w * w.x - c_d * dx - c_kw * w.y - c_kd * dy;
            frame.inner_to(&Vector3::new(x, y, w.z))
        } else {
            // R_x(a_m + δ)ᵀ = R_x(δ)ᵀ·R_x(a_m)ᵀ: the turn acts last, in body axes, where
            // K = K_x(x, y, z) = (0, z, −y) leaves x alone.
            let (w, d) = (frame.to_body(mean), frame.to_body(diff));
            let y = w.y + c_w * w.z + c_d * d.z - c_kw * w.y - c_kd * d.y;
            let z = w.z - c_w * w.y - c_d * d.y - c_kw * w.z - c_kd * d.z;
            Vector3::new(w.x, y, z)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::GimbalAngles;

    fn state(outer: f64, inner: f64, outer_rate: f64, inner_rate: f64) -> GimbalState {
        GimbalState {
            angles: GimbalAngles::new(outer, inner),
            outer_rate_rps: outer_rate,
            inner_rate_rps: inner_rate,
            step_index: 0,
            moving: true,
        }
    }

    /// The tick mean of C_v^b(t)·w(t) by 64-point composite Simpson, against the expansion,
    /// for either gimbal accelerating through a tick while w varies as a sinusoid.
    #[test]
    fn the_expansion_is_the_tick_mean_of_the_turning_frame() {
        let h = 0.01;
        for (r, alpha) in [(0.5, 3.0), (0.035, 0.35), (0.035, 0.0)] {
            let w = |t: f64| {
                Vector3::new(
                    0.3 * (2.0 * t).sin() + 0.1,
                    -0.2 * (1.3 * t + 0.4).cos(),
                    9.8 + 0.5 * (0.7 * t).sin(),
                )
            };
            let t_m = 0.37;
            let mean_of = |f: &dyn Fn(f64) -> Vector3<f64>| {
                let n = 64;
                (0..=n).fold(Vector3::zeros(), |acc, i| {
                    let wt = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    acc + wt * f(t_m - 0.5 * h + i as f64 * h / n as f64)
                }) / (3.0 * n as f64)
            };
            for outer in [true, false] {
                let (o0, i0) = (0.8, -0.6);
                let angle = |t: f64| {
                    let tau = t - t_m;
                    1.1 + r * tau + 0.5 * alpha * tau * tau
                };
                let rate = |t: f64| r + alpha * (t - t_m);
                let g = |t: f64| {
                    if outer {
                        state(angle(t), i0, rate(t), 0.0)
                    } else {
                        state(o0, angle(t), 0.0, rate(t))
                    }
                };
                let fr = |t: f64| {
                    let s = g(t).angles;
                    GimbalFrame::at(s)
                };
                let turn = SmoothTurn::of(&g(t_m - 0.5 * h), &g(t_m), &g(t_m + 0.5 * h)).unwrap();
                assert_eq!(turn.outer, outer);
                // The carrier vector's mean and slope over the tick, as the segment rule gives
                // them (D from five tick means).
                let mean = mean_of(&w);
                let neighbour = |dt: f64| mean_of(&|t| w(t + dt));
                let diff = 17.0 / 12.0 * (neighbour(h) - neighbour(-h))
                    - 5.0 / 24.0 * (neighbour(2.0 * h) - neighbour(-2.0 * h));
                let got = turn.mean_in_body(&fr(t_m), &mean, &diff);
                let exact = mean_of(&|t| fr(t).to_body(&w(t)));
                let err = (got - exact).norm();
                // Leaving the terms out altogether errs by the whole correction: the expansion must
                // be far below that.
                let plain = (fr(t_m).to_body(&mean) - exact).norm();
                // What is left are the terms in w″ and w‴ (module docs), here |w″| ≤ 1.2 and
                // |w‴| ≤ 2.4 per component; three times that for the vector and higher orders.
                let left =
                    (alpha.abs() * 1.2 / 720.0 + r.abs() * 2.4 / 480.0 + r * r * 1.2 / 720.0)
                        * h.powi(4);
                let bound = 3.0 * left;
                assert!(
                    err <= bound && err < 1e-4 * plain,
                    "r {r}, α {alpha}, outer {outer}: {err:e} (bound {bound:e}, uncorrected {plain:e})"
                );
            }
        }
    }

    #[test]
    fn a_phase_change_inside_the_tick_is_no_smooth_turn() {
        // Accelerating, then at constant rate from the middle on.
        let (g0, gm, g1) = (
            state(0.0, 0.0, 0.0, 0.0),
            state(0.001, 0.0, 0.02, 0.0),
            state(0.002, 0.0, 0.02, 0.0),
        );
        assert!(SmoothTurn::of(&g0, &gm, &g1).is_none());
        // Both gimbals turning.
        let g1 = state(0.002, 0.001, 0.02, 0.01);
        assert!(SmoothTurn::of(&g0, &gm, &g1).is_none());
    }
}
