//! Eight lanes as one AVX-512 register, for the AVX-512 build of [`crate::StrapdownLanes`].
//!
//! [`rins_plant::real::Lanes`] computes the same lane by lane in plain Rust, but over the
//! strapdown equations the compiler re-packs its scalar operations in pairs of lanes (with
//! shuffles and two-wide divisions) rather than whole registers; written with the vector
//! operations themselves, every operation is one instruction on all eight lanes. Each is the
//! IEEE operation of `f64` on each lane (no fused multiply-add), so the bits are those of
//! [`rins_plant::real::Lanes`] and of one navigator alone.
//!
//! Values of [`F64x8`] exist only inside functions compiled with AVX-512F
//! (`strapdown_lanes::update_avx512`, entered after the CPU check), which is what makes the
//! intrinsics below sound.
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m512d, _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_NEQ_UQ, _MM_FROUND_NO_EXC,
    _MM_FROUND_TO_ZERO, _mm512_add_pd, _mm512_and_si512, _mm512_castpd_si512, _mm512_castsi512_pd,
    _mm512_cmp_pd_mask, _mm512_div_pd, _mm512_fmadd_pd, _mm512_fnmadd_pd, _mm512_loadu_pd,
    _mm512_mask_blend_pd, _mm512_mul_pd, _mm512_roundscale_pd, _mm512_set1_epi64, _mm512_set1_pd,
    _mm512_sqrt_pd, _mm512_storeu_pd, _mm512_sub_pd, _mm512_xor_si512,
};
use std::ops::{Add, Div, Mul, Neg, Sub};

use rins_plant::real::{Divisor, Lanes, Real, Reciprocal};

/// Eight f64 lanes in one AVX-512 register.
#[derive(Clone, Copy)]
pub(crate) struct F64x8(__m512d);

impl F64x8 {
    #[inline(always)]
    pub fn load(x: &Lanes<8>) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs); 8 f64 are read.
        Self(unsafe { _mm512_loadu_pd(x.0.as_ptr()) })
    }

    #[inline(always)]
    pub fn store(self) -> Lanes<8> {
        let mut out = Lanes([0.0; 8]);
        // SAFETY: as in `load`; 8 f64 are written.
        unsafe { _mm512_storeu_pd(out.0.as_mut_ptr(), self.0) };
        out
    }
}

macro_rules! vector_op {
    ($tr:ident, $f:ident, $intrinsic:ident) => {
        impl $tr for F64x8 {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
                Self(unsafe { $intrinsic(self.0, rhs.0) })
            }
        }
    };
}
vector_op!(Add, add, _mm512_add_pd);
vector_op!(Sub, sub, _mm512_sub_pd);
vector_op!(Mul, mul, _mm512_mul_pd);
vector_op!(Div, div, _mm512_div_pd);

impl Neg for F64x8 {
    type Output = Self;
    /// The sign bit flipped: −x exactly, −0 for +0 (0 − x would give +0).
    #[inline(always)]
    fn neg(self) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe {
            _mm512_castsi512_pd(_mm512_xor_si512(
                _mm512_castpd_si512(self.0),
                _mm512_set1_epi64(i64::MIN),
            ))
        })
    }
}

impl Real for F64x8 {
    const LANES: usize = 8;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe { _mm512_set1_pd(x) })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe { _mm512_sqrt_pd(self.0) })
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.store().sin_cos();
        (Self::load(&s), Self::load(&c))
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> f64 {
        self.store().0[i]
    }
    #[inline(always)]
    fn set_lane(&mut self, i: usize, x: f64) {
        let mut l = self.store();
        l.0[i] = x;
        *self = Self::load(&l);
    }
    /// Markstein's route ([`Divisor`]): three fused operations instead of a division, which
    /// takes AVX-512 about 16 cycles. A zero dividend keeps its sign (the route would give +0
    /// for −0).
    #[inline(always)]
    fn div_by(self, d: Divisor) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe {
            let (b, y) = (_mm512_set1_pd(d.value), _mm512_set1_pd(d.reciprocal));
            let q = _mm512_mul_pd(self.0, y);
            let r = _mm512_fnmadd_pd(q, b, self.0);
            let rounded = _mm512_fmadd_pd(r, y, q);
            let zero = _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(self.0, _mm512_set1_pd(0.0));
            _mm512_mask_blend_pd(zero, rounded, self.0)
        })
    }
    /// Markstein's correction twice from the shared reciprocal ([`Reciprocal`]): five fused
    /// operations instead of a division. A zero dividend keeps its sign.
    #[inline(always)]
    fn div_rec(self, d: &Reciprocal<Self>) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe {
            let (a, b, y) = (self.0, d.value.0, d.reciprocal.0);
            let q0 = _mm512_mul_pd(a, y);
            let q1 = _mm512_fmadd_pd(_mm512_fnmadd_pd(q0, b, a), y, q0);
            let q2 = _mm512_fmadd_pd(_mm512_fnmadd_pd(q1, b, a), y, q1);
            let zero = _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(a, _mm512_set1_pd(0.0));
            _mm512_mask_blend_pd(zero, q2, a)
        })
    }
    #[inline(always)]
    fn all_within(self, x: f64) -> bool {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        unsafe {
            let magnitude = _mm512_castsi512_pd(_mm512_and_si512(
                _mm512_castpd_si512(self.0),
                _mm512_set1_epi64(i64::MAX),
            ));
            _mm512_cmp_pd_mask::<_CMP_LE_OQ>(magnitude, _mm512_set1_pd(x)) == 0xff
        }
    }
    #[inline(always)]
    fn differs(self, other: Self) -> bool {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        unsafe { _mm512_cmp_pd_mask::<_CMP_NEQ_UQ>(self.0, other.0) != 0 }
    }
    /// Exact truncation (the same as `x as i64 as f64` below 2⁶³ in magnitude).
    #[inline(always)]
    fn trunc(self) -> Self {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        Self(unsafe { _mm512_roundscale_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.0) })
    }
    #[inline(always)]
    fn any_above(self, x: f64) -> bool {
        // SAFETY: AVX-512F is enabled where F64x8 is used (module docs).
        unsafe { _mm512_cmp_pd_mask::<_CMP_GT_OQ>(self.0, _mm512_set1_pd(x)) != 0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[target_feature(enable = "avx512f")]
    fn divide_all(a: &[Lanes<8>], d: Divisor) -> Vec<Lanes<8>> {
        let mut out = Vec::with_capacity(a.len());
        for x in a {
            out.push(F64x8::load(x).div_by(d).store());
        }
        out
    }

    #[target_feature(enable = "avx512f")]
    fn grid_sin_cos_all(x: &[Lanes<8>]) -> Vec<(Lanes<8>, Lanes<8>)> {
        let mut trig = rins_plant::trig::GridTrig::<F64x8>::default();
        let mut out = Vec::with_capacity(x.len());
        for v in x {
            let (s, c) = trig.sin_cos(F64x8::load(v));
            out.push((s.store(), c.store()));
        }
        out
    }

    /// The grid sines and cosines in AVX-512 registers (truncation, comparisons and the
    /// out-of-reach test as vector operations) give each lane the bits of its angle alone,
    /// across grid points, for a NaN lane and for a lane beyond the grid's reach.
    #[test]
    fn grid_sines_in_registers_are_each_angles_alone() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            eprintln!("no AVX-512F on this CPU: nothing to check");
            return;
        }
        let x: Vec<Lanes<8>> = (0..5_000)
            .map(|k| {
                Lanes(std::array::from_fn(|l| match (l, k % 7) {
                    (6, 3) => f64::NAN,
                    (7, _) => 1e15 + k as f64,
                    _ => (k as f64 * 3.7e-4 - 0.9) * (l as f64 - 3.5),
                }))
            })
            .collect();
        // SAFETY: the CPU has AVX-512F (checked above).
        let got = unsafe { grid_sin_cos_all(&x) };
        let mut alone = [rins_plant::trig::GridTrig::<f64>::default(); 8];
        for (k, (v, (s, c))) in x.iter().zip(&got).enumerate() {
            for (l, one) in alone.iter_mut().enumerate() {
                let (sa, ca) = one.sin_cos(v.0[l]);
                assert_eq!(
                    (s.0[l].to_bits(), c.0[l].to_bits()),
                    (sa.to_bits(), ca.to_bits()),
                    "lane {l}, step {k}"
                );
            }
        }
    }

    #[target_feature(enable = "avx512f")]
    fn divide_through_reciprocals(a: &[Lanes<8>], b: &[Lanes<8>]) -> Vec<Lanes<8>> {
        let mut out = Vec::with_capacity(a.len());
        for (x, d) in a.iter().zip(b) {
            let d = Reciprocal::of(F64x8::load(d));
            out.push(F64x8::load(x).div_rec(&d).store());
        }
        out
    }

    /// Dividing through a shared reciprocal gives the bits of `/`: random quotients over 120
    /// binades of dividend and divisor, divisors whose reciprocal rounds far from 1/b (odd
    /// significands just below a power of two), exact quotients and their neighbours, ±0.
    #[test]
    fn the_route_through_the_reciprocal_gives_the_quotient_of_division() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            eprintln!("no AVX-512F on this CPU: nothing to check");
            return;
        }
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut any = |lo: i32, hi: i32| -> f64 {
            let m: f64 = rng.random_range(1.0..2.0);
            let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
            sign * m * 2f64.powi(rng.random_range(lo..hi))
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for _ in 0..3_000_000 {
            a.push(any(-60, 60));
            b.push(any(-60, 60));
        }
        for k in 1..200_000u64 {
            // Divisors 2^e·(2 − small) and multiples of them, and quotients near integers.
            let d = f64::from_bits(2f64.to_bits() - k) * 2f64.powi((k % 40) as i32 - 20);
            let q = (k % 977) as f64 + 1.0;
            for ulps in -2i64..=2 {
                a.push(f64::from_bits(((q * d).to_bits() as i64 + ulps) as u64));
                b.push(d);
            }
        }
        a.extend([0.0, -0.0, 1.0, -1.0]);
        b.extend([3.0, 3.0, 3.0, 7.0]);
        let pack = |v: &[f64]| -> Vec<Lanes<8>> {
            v.chunks(8)
                .map(|c| Lanes(std::array::from_fn(|i| c.get(i).copied().unwrap_or(1.0))))
                .collect()
        };
        let (pa, pb) = (pack(&a), pack(&b));
        // SAFETY: the CPU has AVX-512F (checked above).
        let got = unsafe { divide_through_reciprocals(&pa, &pb) };
        for ((x, d), q) in pa.iter().zip(&pb).zip(&got) {
            for l in 0..8 {
                assert_eq!(
                    q.0[l].to_bits(),
                    (x.0[l] / d.0[l]).to_bits(),
                    "{} / {}",
                    x.0[l],
                    d.0[l]
                );
            }
        }
    }

    /// Markstein's route gives the bits of `/` for every divisor the equations use: on
    /// dividends spread over 120 binades, on exact multiples of the divisor and their
    /// neighbours a few units in the last place away (where rounding is decided), and on ±0.
    #[test]
    fn the_route_without_division_gives_the_quotient_of_division() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            eprintln!("no AVX-512F on this CPU: nothing to check");
            return;
        }
        let divisors = [12.0, 8.0, 48.0, 384.0, 3840.0, 6_378_137.0f64 * 6_378_137.0];
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut dividends = vec![0.0, -0.0, 1.0, -1.0];
        for _ in 0..2_000_000 {
            let m: f64 = rng.random_range(1.0..2.0);
            let e: i32 = rng.random_range(-60..60);
            let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
            dividends.push(sign * m * 2f64.powi(e));
        }
        for &b in &divisors {
            for k in 1..20_000u64 {
                let exact = k as f64 * b;
                for ulps in -3i64..=3 {
                    dividends.push(f64::from_bits((exact.to_bits() as i64 + ulps) as u64));
                }
            }
        }
        dividends.resize(dividends.len().div_ceil(8) * 8, 1.0);
        let packed: Vec<Lanes<8>> = dividends
            .chunks(8)
            .map(|c| Lanes(std::array::from_fn(|i| c[i])))
            .collect();
        for &b in &divisors {
            let d = Divisor::new(b);
            // SAFETY: the CPU has AVX-512F (checked above).
            let got = unsafe { divide_all(&packed, d) };
            for (x, q) in packed.iter().zip(&got) {
                for l in 0..8 {
                    assert_eq!(q.0[l].to_bits(), (x.0[l] / b).to_bits(), "{} / {b}", x.0[l]);
                }
            }
        }
    }
}
