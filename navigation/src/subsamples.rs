//! Several IMU intervals per navigator update: the N-sample coning and sculling combination.
//!
//! A navigator that integrates every interval on its own (N = 1) corrects coning and sculling
//! with the previous interval ([`crate::mechanisation`]). One that updates once every N
//! intervals combines them first, with the optimal N-sample coefficients for a polynomial
//! angular rate (Savage, *Strapdown Analytics* §7.1.1; the coefficients of PSINS's `cnscl`):
//!
//! - φ = ΣΔθᵢ + (Σᵢ₍ₙ₎ kᵢ·Δθᵢ) × Δθ_N,
//! - Δv_sf = ΣΔvᵢ + ½·ΣΔθᵢ × ΣΔvᵢ + (Σᵢ₍ₙ₎ kᵢ·Δθᵢ) × Δv_N + (Σᵢ₍ₙ₎ kᵢ·Δvᵢ) × Δθ_N,
//!
//! the sums kᵢ over the first N − 1 intervals, and the navigation frame turned once over N·Δt.
//! The frame's terms (latitude, radii, gravity, Earth and transport rates, Coriolis) then cost
//! once per N intervals, the body terms a combination; the navigator's state and its body up
//! direction move at the update.

use crate::mechanisation::{
    BodyIncrement, Solution, VerticalChannel, add, cross, scale, update_frame,
};
use rins_plant::real::Real;

/// Intervals per navigator update: 1 (every interval, one-plus-previous coning and sculling)
/// to [`Subsamples::MAX`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "u8", into = "u8")]
pub struct Subsamples(u8);

impl Subsamples {
    /// Every interval an update.
    pub const ONE: Self = Self(1);
    /// The most intervals per update the coefficients are given for.
    pub const MAX: u8 = 4;

    /// `n` intervals per update; an error naming the range unless 1 ≤ n ≤ [`Subsamples::MAX`].
    pub fn new(n: u8) -> Result<Self, String> {
        if (1..=Self::MAX).contains(&n) {
            Ok(Self(n))
        } else {
            Err(format!(
                "subsamples {n}: the navigator updates every 1 to {} IMU intervals",
                Self::MAX
            ))
        }
    }

    /// Intervals per update.
    pub fn get(self) -> usize {
        usize::from(self.0)
    }
}

impl Default for Subsamples {
    fn default() -> Self {
        Self::ONE
    }
}

impl TryFrom<u8> for Subsamples {
    type Error = String;
    fn try_from(n: u8) -> Result<Self, String> {
        Self::new(n)
    }
}

impl From<Subsamples> for u8 {
    fn from(n: Subsamples) -> u8 {
        n.0
    }
}

/// The coefficients kᵢ of the first N − 1 intervals, for N = 2, 3, 4 (row N − 2).
const COEFFICIENTS: [&[f64]; 3] = [
    &[2.0 / 3.0],
    &[9.0 / 20.0, 27.0 / 20.0],
    &[54.0 / 105.0, 92.0 / 105.0, 214.0 / 105.0],
];

/// The body rotation and specific-force increment of N = `dtheta.len()` intervals (2 to
/// [`Subsamples::MAX`]; `dv` as long): the combination of the module's docs, summed in interval
/// order.
#[inline(always)]
pub(crate) fn combine<T: Real>(dtheta: &[[T; 3]], dv: &[[T; 3]]) -> BodyIncrement<T> {
    let n = dtheta.len();
    debug_assert!((2..=usize::from(Subsamples::MAX)).contains(&n) && dv.len() == n);
    let k = COEFFICIENTS[n - 2];
    let (mut sum_th, mut sum_dv) = (dtheta[0], dv[0]);
    let (mut k_th, mut k_dv) = (
        scale(&dtheta[0], T::splat(k[0])),
        scale(&dv[0], T::splat(k[0])),
    );
    for i in 1..n - 1 {
        sum_th = add(&sum_th, &dtheta[i]);
        sum_dv = add(&sum_dv, &dv[i]);
        k_th = add(&k_th, &scale(&dtheta[i], T::splat(k[i])));
        k_dv = add(&k_dv, &scale(&dv[i], T::splat(k[i])));
    }
    let (last_th, last_dv) = (dtheta[n - 1], dv[n - 1]);
    sum_th = add(&sum_th, &last_th);
    sum_dv = add(&sum_dv, &last_dv);
    let phi = add(&sum_th, &cross(&k_th, &last_th));
    let rotation = scale(&cross(&sum_th, &sum_dv), T::splat(0.5));
    let sculling = add(&cross(&k_th, &last_dv), &cross(&k_dv, &last_th));
    BodyIncrement {
        phi,
        dv_sf: add(&add(&sum_dv, &rotation), &sculling),
    }
}

/// Integrates the increments of `dtheta.len()` intervals of `dt_s` each (2 to 4; `dv` as many)
/// in one update: their combination ([`combine`]), then the navigation frame turned once over
/// N·Δt ([`crate::mechanisation`]).
#[inline(always)]
pub(crate) fn update_subsamples<T: Real>(
    s: &mut Solution<T>,
    dtheta: &[[T; 3]],
    dv: &[[T; 3]],
    dt_s: f64,
    vertical: VerticalChannel,
) {
    let body = combine(dtheta, dv);
    update_frame(s, &body, dt_s * dtheta.len() as f64, vertical);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strapdown::tests::increments;
    use crate::strapdown::{NavState, Strapdown, VerticalChannel};
    use nalgebra::{UnitQuaternion, Vector3};

    #[test]
    fn counts_outside_one_to_four_are_refused_with_the_range() {
        for n in [0u8, 5, 200] {
            let e = Subsamples::new(n).unwrap_err();
            assert!(e.contains("1 to 4"), "{e}");
        }
        assert_eq!(Subsamples::new(4).unwrap().get(), 4);
        let parsed: Result<Subsamples, _> = serde_json::from_str("7");
        assert!(parsed.is_err());
    }

    /// Classical coning at half-angle α and rate Ω: the body rate is
    /// ω = (−2Ω·sin²(α/2), −Ω·sin α·sin Ωt, Ω·sin α·cos Ωt), so each interval's increments
    /// are closed forms. What a coning algorithm approximates is the coning integral
    /// β = ½∫α(t) × ω(t) dt over the update (α(t) = ∫₀ᵗω), here by Simpson's rule on a fine
    /// grid (a second method). The N-sample term's error along the cone axis is Savage's
    /// α²·(ΩT)^(2N+1)·c_N with c = 1/960, 1/204120, 1/82575360 for N = 2, 3, 4 (the rest is
    /// of order α³, from the spin about the axis), and the whole error is far below the coning
    /// the plain sum ignores.
    #[test]
    fn coning_residual_falls_with_the_subsample_count() {
        let (alpha, big_omega) = (0.05_f64, 25.0_f64);
        let spin = -2.0 * big_omega * (alpha / 2.0).sin().powi(2);
        let rate = |t: f64| {
            Vector3::new(
                spin,
                -big_omega * alpha.sin() * (big_omega * t).sin(),
                big_omega * alpha.sin() * (big_omega * t).cos(),
            )
        };
        let increment = |a: f64, b: f64| {
            Vector3::new(
                spin * (b - a),
                alpha.sin() * ((big_omega * b).cos() - (big_omega * a).cos()),
                alpha.sin() * ((big_omega * b).sin() - (big_omega * a).sin()),
            )
        };
        let update_s = 0.04;
        let beta = {
            let m = 20_000;
            let h = update_s / m as f64;
            let f = |j: usize| {
                let t = j as f64 * h;
                increment(0.0, t).cross(&rate(t))
            };
            let mut sum = f(0) + f(m);
            for j in 1..m {
                sum += f(j) * if j % 2 == 1 { 4.0 } else { 2.0 };
            }
            sum * (h / 3.0) * 0.5
        };
        for n in 2..=4usize {
            let h = update_s / n as f64;
            let th: Vec<[f64; 3]> = (0..n)
                .map(|i| increment(i as f64 * h, (i + 1) as f64 * h).into())
                .collect();
            let sum: Vector3<f64> = th.iter().map(|x| Vector3::from(*x)).sum();
            let dv = vec![[0.0; 3]; n];
            let error = Vector3::from(combine(&th, &dv).phi) - sum - beta;
            let c = [1.0 / 960.0, 1.0 / 204_120.0, 1.0 / 82_575_360.0][n - 2];
            let theory = alpha * alpha * (big_omega * update_s).powi(2 * n as i32 + 1) * c;
            assert!(
                (-error.x / theory - 1.0).abs() < 0.05,
                "N = {n}: {:e} along the axis against {theory:e}",
                error.x
            );
            assert!(error.norm() < beta.norm() / 50.0, "N = {n}: {error:?}");
        }
    }

    /// Navigators updating every 4 intervals move about as far as every interval over a few
    /// hundred seconds of smooth turning and accelerating (the same increments, without the
    /// test's one-interval jolts, which no polynomial fit of the rate follows): the two
    /// algorithms are two ways to the same solution.
    #[test]
    fn subsampled_navigators_agree_with_the_interval_by_interval_one() {
        let start = NavState {
            q_bn: UnitQuaternion::from_euler_angles(0.0, -0.02, 1.1),
            v_n: Vector3::new(3.0, -4.0, 0.1),
            lat_rad: 0.64,
            lon_rad: 2.15,
            height_m: 15.0,
        };
        let vertical = VerticalChannel::Hold { ref_height_m: 12.0 };
        let mut one = Strapdown::new(start, 0.01, vertical);
        let mut four = one.clone().with_subsamples(Subsamples::new(4).unwrap());
        for step in 1..=40_000u64 {
            let (mut a, b) = increments(step);
            if step.is_multiple_of(97) {
                a.z -= 0.02;
            }
            one.update(&a, &b);
            four.update(&a, &b);
        }
        let (s1, s4) = (one.state(), four.state());
        let moved = (s1.lat_rad - start.lat_rad).abs() * 6.4e6;
        let apart = (s1.lat_rad - s4.lat_rad).abs() * 6.4e6;
        let apart_e = (s1.lon_rad - s4.lon_rad).abs() * 6.4e6 * s1.lat_rad.cos();
        assert!(moved > 100.0, "moved {moved} m");
        assert!(
            apart < 1e-3 * moved && apart_e < 1e-3 * moved,
            "{apart} {apart_e} of {moved} m"
        );
        assert!(
            s1.q_bn.angle_to(&s4.q_bn) < 1e-6,
            "{}",
            s1.q_bn.angle_to(&s4.q_bn)
        );
    }
}
