//! The number type of code that runs for one navigator or for several side by side: one `f64`,
//! or [`Lanes`], one navigator per vector lane. The WGS-84 radii and normal gravity
//! ([`crate::earth`]) and the navigator's strapdown equations (rins-navigation) are written over it
//! once.
//!
//! Every operation of [`Lanes`] is the `f64` operation on each lane: IEEE add, subtract,
//! multiply, divide and square root are correctly rounded whatever the vector width, and rustc
//! never fuses a multiply and an add, so a lane computes exactly the bits one navigator computes
//! alone. Sine and cosine are not vector operations: they call the same `f64::sin_cos` per lane.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A real number, or several side by side.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// How many numbers side by side.
    const LANES: usize;
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// Square root of each lane.
    fn sqrt(self) -> Self;
    /// Sine and cosine of each lane (`f64::sin_cos`).
    fn sin_cos(self) -> (Self, Self);
    /// Lane `i`.
    fn lane(&self, i: usize) -> f64;
    /// Sets lane `i`.
    fn set_lane(&mut self, i: usize, x: f64);
    /// Whether any lane exceeds `x`.
    fn any_above(self, x: f64) -> bool;
    /// Whether every lane lies within ±`x` (false for a NaN lane).
    fn all_within(self, x: f64) -> bool;
    /// Whether any lane differs from `other`'s (as `!=`: a NaN differs from everything).
    fn differs(self, other: Self) -> bool;
    /// Each lane rounded towards zero, for |lanes| < 2⁶³ (as `x as i64 as f64`, which on the
    /// baseline x86-64 needs no libm call).
    fn trunc(self) -> Self;
    /// Each lane divided by the constant `d`, correctly rounded: the bits of `/`. A vector
    /// build with fused multiply-add may take the route through the reciprocal that needs no
    /// division ([`Divisor`]).
    #[inline(always)]
    fn div_by(self, d: Divisor) -> Self {
        self / Self::splat(d.value)
    }
    /// Each lane divided by `d`'s lane, correctly rounded: the bits of `/`. A vector build with
    /// fused multiply-add may divide through the reciprocal ([`Reciprocal`]).
    #[inline(always)]
    fn div_rec(self, d: &Reciprocal<Self>) -> Self {
        self / d.value
    }
}

/// A divisor b that several quotients share, with y = RN(1/b): one division, then each quotient
/// a/b by Markstein's correction applied twice (q₀ = RN(a·y) may be off by more than an ulp
/// when y's own rounding is near half an ulp; one correction brings it within an ulp, a
/// faithful rounding, and the second gives RN(a/b) by the theorem of [`Divisor`]). Where `/`
/// is the cheaper route ([`Real::div_rec`]'s default) the reciprocal is never used and the
/// compiler drops it.
#[derive(Clone, Copy, Debug)]
pub struct Reciprocal<T> {
    /// b.
    pub value: T,
    /// RN(1/b).
    pub reciprocal: T,
}

impl<T: Real> Reciprocal<T> {
    /// `b` and its reciprocal.
    #[inline(always)]
    pub fn of(b: T) -> Self {
        Self {
            value: b,
            reciprocal: T::splat(1.0) / b,
        }
    }
}

/// A constant divisor b with its reciprocal y = RN(1/b), for dividing without a division:
/// q = RN(a·y), r = a − q·b (exact with a fused multiply-add), q' = RN(q + r·y).
///
/// Markstein's theorem (Markstein 1990; Muller et al., *Handbook of Floating-Point
/// Arithmetic*, 2nd ed., §4.9) makes q' the correctly rounded a/b when q is a faithful
/// rounding of a/b and y approximates 1/b with a relative error below 2⁻⁵³ (no overflow or
/// underflow). Both hold when |y·b − 1| ≤ 2⁻⁵⁴: then |a·y − a/b| < ½ ulp(a/b), so RN(a·y) is
/// one of the two neighbours of a/b. [`Divisor::new`] checks that bound; the divisors used
/// (12, 48, 384, 3840, a²) meet it, and a test compares the route with `/` on millions of
/// quotients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Divisor {
    /// b.
    pub value: f64,
    /// RN(1/b).
    pub reciprocal: f64,
}

impl Divisor {
    /// `value` and its reciprocal; panics (at compile time in a `const`) unless
    /// |RN(1/b)·b − 1| ≤ 2⁻⁵⁴.
    pub const fn new(value: f64) -> Self {
        let reciprocal = 1.0 / value;
        // y·b − 1 exactly: it needs far fewer than 53 bits, so the fused operation's one
        // rounding is exact.
        let residual = reciprocal.mul_add(value, -1.0);
        assert!(
            residual.abs() <= 1.0 / 18_014_398_509_481_984.0,
            "the reciprocal is not close enough for the division without a division"
        );
        Self { value, reciprocal }
    }
}

impl Real for f64 {
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
    #[inline(always)]
    fn lane(&self, _: usize) -> f64 {
        *self
    }
    #[inline(always)]
    fn set_lane(&mut self, _: usize, x: f64) {
        *self = x;
    }
    #[inline(always)]
    fn any_above(self, x: f64) -> bool {
        self > x
    }
    #[inline(always)]
    fn all_within(self, x: f64) -> bool {
        self.abs() <= x
    }
    #[inline(always)]
    fn differs(self, other: Self) -> bool {
        self != other
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        (self as i64) as f64
    }
}

/// `N` numbers side by side, one per navigator; each operation acts lane by lane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Lanes<const N: usize>(pub [f64; N]);

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const N: usize> $tr for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                Lanes(std::array::from_fn(|i| self.0[i] $op rhs.0[i]))
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const N: usize> Neg for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Lanes(self.0.map(|x| -x))
    }
}

impl<const N: usize> Real for Lanes<N> {
    const LANES: usize = N;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Lanes([x; N])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Lanes(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let mut s = Lanes([0.0; N]);
        let mut c = Lanes([0.0; N]);
        sin_cos_each(&self, &mut s, &mut c);
        (s, c)
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn set_lane(&mut self, i: usize, x: f64) {
        self.0[i] = x;
    }
    #[inline(always)]
    fn any_above(self, x: f64) -> bool {
        self.0.iter().any(|&v| v > x)
    }
    #[inline(always)]
    fn all_within(self, x: f64) -> bool {
        self.0.iter().all(|&v| v.abs() <= x)
    }
    #[inline(always)]
    fn differs(self, other: Self) -> bool {
        self.0.iter().zip(&other.0).any(|(a, b)| a != b)
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        Lanes(self.0.map(|v| (v as i64) as f64))
    }
}

/// Sine and cosine of each lane, into `s` and `c`. Kept out of line: inlined, the compiler
/// carries the scalar results on in pairs of lanes instead of whole vectors.
#[inline(never)]
fn sin_cos_each<const N: usize>(x: &Lanes<N>, s: &mut Lanes<N>, c: &mut Lanes<N>) {
    for i in 0..N {
        (s.0[i], c.0[i]) = x.0[i].sin_cos();
    }
}
