//! Sines and cosines without libm where an angle moves by small steps: the ship's composition
//! angles from tick to tick and the gimbal angles between a tick's two quadrature points, and
//! a navigator's latitude from update to update.

use crate::real::Real;

/// Largest step [`sin_cos_step`] covers, rad: its series (sin δ to δ⁵, cos δ to δ⁶) then errs
/// by < δ⁷/7! ≈ 2e-18, a fiftieth of an ulp of 1.
pub const SMALL_STEP_RAD: f64 = 0.01;

/// sin and cos of a₀ + δ from s₀ = sin a₀ and c₀ = cos a₀ by the addition theorem with the
/// series of the small step δ (|δ| ≤ [`SMALL_STEP_RAD`]).
#[inline(always)]
pub fn sin_cos_step<T: Real>(s0: T, c0: T, d: T) -> (T, T) {
    // Multiplications by constant reciprocals: a division would lengthen the chain.
    let k = T::splat;
    let d2 = d * d;
    let sd = d * (k(1.0) + d2 * (k(-1.0 / 6.0) + d2 * k(1.0 / 120.0)));
    let cd = k(1.0) + d2 * (k(-0.5) + d2 * (k(1.0 / 24.0) + d2 * k(-1.0 / 720.0)));
    (s0 * cd + c0 * sd, c0 * cd - s0 * sd)
}

/// Largest step [`sin_cos_step_wide`] covers, rad: its series (sin δ to δ⁹, cos δ to δ¹⁰) then
/// errs by < δ¹¹/11! ≈ 2.5e-19.
pub(crate) const WIDE_STEP_RAD: f64 = 0.1;

/// [`sin_cos_step`] for steps up to [`WIDE_STEP_RAD`] (the ship's segment nodes, up to a tenth of
/// a segment apart).
#[inline]
pub(crate) fn sin_cos_step_wide(s0: f64, c0: f64, d: f64) -> (f64, f64) {
    let d2 = d * d;
    let sd = d
        * (1.0
            + d2 * (-1.0 / 6.0
                + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0 + d2 * (1.0 / 362_880.0)))));
    let cd = 1.0
        + d2 * (-0.5
            + d2 * (1.0 / 24.0
                + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40_320.0 + d2 * (-1.0 / 3_628_800.0)))));
    (s0 * cd + c0 * sd, c0 * cd - s0 * sd)
}

/// Spacing of the grid [`GridTrig`] takes sines and cosines at, rad (steps from it stay below
/// it, inside [`SMALL_STEP_RAD`]).
const GRID_RAD: f64 = 0.01;

/// Sines and cosines of angles that move a little every tick (a turning gimbal, a navigator's
/// latitude): libm at the grid point of a 0.01 rad grid towards zero (held while the angle stays
/// near it), the series of [`sin_cos_step`] from there. The result is a function of the angle
/// alone, whatever came before, so a restored plant gets the same bits. Generic over [`Real`]:
/// each lane of [`crate::real::Lanes`] holds its own grid point and gets the bits of one
/// angle alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridTrig<T = f64> {
    k: T,
    /// The grid point k·0.01 rad.
    g: T,
    sin: T,
    cos: T,
}

impl<T: Real> Default for GridTrig<T> {
    /// No grid point yet.
    fn default() -> Self {
        Self {
            k: T::splat(f64::NAN),
            g: T::splat(f64::NAN),
            sin: T::splat(f64::NAN),
            cos: T::splat(f64::NAN),
        }
    }
}

impl<T: Real> GridTrig<T> {
    /// The held grid point: its index k (of k·0.01 rad), the point, its sine and cosine.
    pub fn into_parts(self) -> [T; 4] {
        [self.k, self.g, self.sin, self.cos]
    }

    /// A grid point held by [`Self::into_parts`] (of any lane type).
    pub fn from_parts([k, g, sin, cos]: [T; 4]) -> Self {
        Self { k, g, sin, cos }
    }

    /// sin and cos of `a`.
    #[inline(always)]
    pub fn sin_cos(&mut self, a: T) -> (T, T) {
        // Truncation, not `round` (a libm call on the baseline x86-64): steps stay below one
        // grid spacing, still within the series' reach.
        let k = (a * T::splat(1.0 / GRID_RAD)).trunc();
        if k.differs(self.k) {
            self.new_grid_points(k);
        }
        // The held point is k·0.01 now. Taking the step from it, not from k just computed,
        // keeps the truncation off the chain of dependent operations (the check above is a
        // branch the CPU predicts).
        let d = a - self.g;
        let far = !d.all_within(SMALL_STEP_RAD);
        // a and g are within a factor of two of each other (or both tiny): the step is exact.
        let (mut s, mut c) = sin_cos_step(self.sin, self.cos, d);
        if far {
            // Beyond the series' reach (a huge or non-finite angle): libm for that lane.
            for l in 0..T::LANES {
                let dl = d.lane(l);
                if !(dl.abs() <= SMALL_STEP_RAD) {
                    let (sl, cl) = a.lane(l).sin_cos();
                    s.set_lane(l, sl);
                    c.set_lane(l, cl);
                }
            }
        }
        (s, c)
    }

    /// The grid point k·0.01 rad and libm's sine and cosine there, for each lane whose point
    /// changed.
    #[inline(never)]
    fn new_grid_points(&mut self, k: T) {
        for l in 0..T::LANES {
            if k.lane(l) != self.k.lane(l) {
                let g = k.lane(l) * GRID_RAD;
                let (s, c) = g.sin_cos();
                self.sin.set_lane(l, s);
                self.cos.set_lane(l, c);
                self.g.set_lane(l, g);
                self.k.set_lane(l, k.lane(l));
            }
        }
    }
}

/// An angle with its sine and cosine, recomputed only when the angle changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AngleTrig {
    rad: f64,
    sin: f64,
    cos: f64,
}

impl Default for AngleTrig {
    /// No angle yet (a NaN matches nothing).
    fn default() -> Self {
        Self {
            rad: f64::NAN,
            sin: f64::NAN,
            cos: f64::NAN,
        }
    }
}

impl AngleTrig {
    /// sin and cos of `a` (libm when `a` differs from the held angle); `a` is held after.
    #[inline]
    pub(crate) fn at(&mut self, a: f64) -> (f64, f64) {
        if a != self.rad {
            (self.sin, self.cos) = a.sin_cos();
            self.rad = a;
        }
        (self.sin, self.cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest deviation from libm of `step` over steps `ds` from angles across ±13 rad (each
    /// step taken as the sum really makes it: a0 + d rounds).
    fn worst_step_error(step: fn(f64, f64, f64) -> (f64, f64), ds: [f64; 5]) -> f64 {
        let mut worst = 0.0f64;
        for k in 0..2000 {
            let a0 = k as f64 * 0.0137 - 13.0;
            let (s0, c0) = a0.sin_cos();
            for d in ds {
                let a = a0 + d;
                let (s, c) = step(s0, c0, a - a0);
                let (se, ce) = a.sin_cos();
                worst = worst.max((s - se).abs()).max((c - ce).abs());
            }
        }
        worst
    }

    #[test]
    fn small_and_wide_steps_match_libm_to_an_ulp() {
        let small = worst_step_error(sin_cos_step, [1e-9, -3e-5, 2.2e-4, -0.004, 0.0099]);
        let wide = worst_step_error(sin_cos_step_wide, [-0.1, -0.061, 0.003, 0.0437, 0.0999]);
        assert!(small < 4.5e-16 && wide < 4.5e-16, "{small:e} {wide:e}");
        // The short series does not reach that far: the test can tell.
        assert!(worst_step_error(sin_cos_step, [-0.1; 5]) > 1e-12);
    }

    #[test]
    fn grid_sines_match_libm_and_do_not_depend_on_history() {
        let (mut a, mut b) = (GridTrig::default(), GridTrig::default());
        let mut worst = 0.0f64;
        for k in 0..20_000 {
            let x = k as f64 * 3.7e-4 - 2.0;
            let (s, c) = a.sin_cos(x);
            let (se, ce) = x.sin_cos();
            worst = worst.max((s - se).abs()).max((c - ce).abs());
            // A fresh grid (a restored plant) and one that saw other angles give the same bits.
            b.sin_cos(x * 7.0 + 1.0);
            assert_eq!(b.sin_cos(x), (s, c));
            assert_eq!(GridTrig::default().sin_cos(x), (s, c));
        }
        assert!(worst < 4.5e-16, "{worst:e}");
    }

    /// Eight angles side by side, each lane moving on its own (crossing grid points at
    /// different steps, one lane NaN at times, one far beyond the grid), give each lane the
    /// bits of that angle alone.
    #[test]
    fn each_lane_gets_the_bits_of_its_angle_alone() {
        use crate::real::Lanes;
        let mut lanes = GridTrig::<Lanes<8>>::default();
        let mut alone = [GridTrig::<f64>::default(); 8];
        for k in 0..5_000 {
            let x = Lanes(std::array::from_fn(|l| match (l, k % 7) {
                (6, 3) => f64::NAN,
                (7, _) => 1e17 + k as f64,
                _ => (k as f64 * 3.7e-4 - 0.9) * (l as f64 - 3.5),
            }));
            let (s, c) = lanes.sin_cos(x);
            for (l, one) in alone.iter_mut().enumerate() {
                let (sa, ca) = one.sin_cos(x.0[l]);
                assert_eq!(
                    (s.0[l].to_bits(), c.0[l].to_bits()),
                    (sa.to_bits(), ca.to_bits()),
                    "lane {l}, step {k}"
                );
            }
        }
    }

    #[test]
    fn held_angles_are_exact() {
        let mut t = AngleTrig::default();
        assert_eq!(t.at(0.3), 0.3f64.sin_cos());
        assert_eq!(t.at(0.3), 0.3f64.sin_cos());
        assert_eq!(t.at(0.5), 0.5f64.sin_cos());
    }
}
