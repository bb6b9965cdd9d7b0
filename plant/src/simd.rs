//! Runtime CPU dispatch for the plant's two widest loops: the ship's segment rule (every tick's
//! interpolated carrier points from the node values) and the sea state's jet (a sum over wave
//! components). Each loop is written once, as plain Rust; here it is also compiled for AVX-512F
//! and AVX2 and the widest the CPU has is run.
//!
//! The bits do not depend on the choice. Every output lane is its own sum, accumulated in the
//! same order at any vector width, and rustc never fuses a multiply and an add (no fused
//! multiply-add unless written as `mul_add`), so the wide builds compute exactly what the
//! baseline (SSE2) build does; the tests in `carrier::segment` and `carrier::waves` compare
//! them bit for bit.
#![allow(unsafe_code)]

use nalgebra::Complex;

use crate::carrier::widths::{JET_LEN, POINT_CHANNELS};

/// Rows per block of [`combine_mirrored`]: one AVX-512 vector of f64.
pub(crate) const LANES: usize = 8;

/// Compiles `$body` for AVX-512F and AVX2 as well and runs the widest the CPU supports; with
/// `use $wide` the AVX-512F build is the hand-written function `$wide` instead. Exported for
/// the navigator in vector lanes (rins-navigation), whose bits likewise do not depend on the choice.
#[macro_export]
macro_rules! multiversion {
    ($(#[$doc:meta])* $vis:vis fn $name:ident($($a:ident: $t:ty),*) $(-> $r:ty)?
        = $body:ident, $wide:ident, $avx2:ident) => {
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx512f")]
        fn $wide($($a: $t),*) $(-> $r)? {
            $body($($a),*)
        }

        $crate::multiversion! {
            $(#[$doc])* $vis fn $name($($a: $t),*) $(-> $r)? = $body, use $wide, $avx2
        }
    };
    ($(#[$doc:meta])* $vis:vis fn $name:ident($($a:ident: $t:ty),*) $(-> $r:ty)?
        = $body:ident, use $wide:ident, $avx2:ident) => {
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        fn $avx2($($a: $t),*) $(-> $r)? {
            $body($($a),*)
        }

        $(#[$doc])*
        $vis fn $name($($a: $t),*) $(-> $r)? {
            #[cfg(target_arch = "x86_64")]
            {
                if std::arch::is_x86_feature_detected!("avx512f") {
                    // SAFETY: the CPU has AVX-512F, checked just above.
                    return unsafe { $wide($($a),*) };
                }
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU has AVX2, checked just above.
                    return unsafe { $avx2($($a),*) };
                }
            }
            $body($($a),*)
        }
    };
}

/// Most node pairs [`combine_mirrored`] takes.
pub(crate) const MAX_PAIRS: usize = 16;

#[inline(always)]
fn combine_mirrored_body(
    w_t: &[[f64; LANES]],
    even: &[[f64; POINT_CHANNELS]],
    odd: &[[f64; POINT_CHANNELS]],
    out: &mut [f64],
) {
    let rows = out.len() / POINT_CHANNELS;
    let blocks = rows / 2 / LANES;
    let pairs = even.len();
    for b in 0..blocks {
        let mut s = [[0.0; LANES]; POINT_CHANNELS];
        let mut d = [[0.0; LANES]; POINT_CHANNELS];
        for (j, (e, o)) in even.iter().zip(odd).enumerate() {
            let (we, wo) = (&w_t[j * blocks + b], &w_t[(pairs + j) * blocks + b]);
            for c in 0..POINT_CHANNELS {
                for l in 0..LANES {
                    s[c][l] += we[l] * e[c];
                    d[c][l] += wo[l] * o[c];
                }
            }
        }
        // Channel after channel: rows k = 8b..8b + 8 get S + D, their mirrors R − 1 − k
        // (stored in increasing order, so lane-reversed) S − D.
        for c in 0..POINT_CHANNELS {
            let lo = c * rows + b * LANES;
            let hi = c * rows + rows - (b + 1) * LANES;
            let (s, d) = (&s[c], &d[c]);
            let sum: [f64; LANES] = std::array::from_fn(|l| s[l] + d[l]);
            let mirror: [f64; LANES] = std::array::from_fn(|l| s[LANES - 1 - l] - d[LANES - 1 - l]);
            out[lo..lo + LANES].copy_from_slice(&sum);
            out[hi..hi + LANES].copy_from_slice(&mirror);
        }
    }
}

multiversion! {
    /// A symmetric rule's rows from its first half (`crate::carrier::segment::SegmentRule`):
    /// with S_r = Σ_j E_j[r]·e_j and D_r = Σ_j O_j[r]·o_j (sums over the node pairs j in order),
    /// out[c·R + r] = S_r + D_r and out[c·R + R − 1 − r] = S_r − D_r for the point channels c
    /// and the rows r < R/2. `w_t` holds the pairs' even weights E_j, then their odd weights
    /// O_j, each as R/2/[`LANES`] blocks of rows; `even` and `odd` the pairs' half sums and half
    /// differences; `out` the R rows channel after channel.
    pub(crate) fn combine_mirrored(
        w_t: &[[f64; LANES]],
        even: &[[f64; POINT_CHANNELS]],
        odd: &[[f64; POINT_CHANNELS]],
        out: &mut [f64]
    )
        = combine_mirrored_body, combine_mirrored_avx512, combine_mirrored_avx2
}

#[inline(always)]
fn jet_sum_body(
    z: &[Complex<f64>],
    rot: Option<&[Complex<f64>]>,
    re: &[[f64; JET_LEN]],
    im: &[[f64; JET_LEN]],
) -> [f64; JET_LEN] {
    let mut acc = [0.0; JET_LEN];
    for (i, (re, im)) in re.iter().zip(im).enumerate() {
        let z = match rot {
            Some(r) => z[i] * r[i],
            None => z[i],
        };
        for j in 0..JET_LEN {
            acc[j] += re[j] * z.re - im[j] * z.im;
        }
    }
    acc
}

multiversion! {
    /// Σ_i Re(C_{j,i}·z_i·r_i) for the jet values j (C = `re` + i·`im` per component, r_i = 1
    /// without `rot`), the sum over the components in order.
    pub(crate) fn jet_sum(
        z: &[Complex<f64>],
        rot: Option<&[Complex<f64>]>,
        re: &[[f64; JET_LEN]],
        im: &[[f64; JET_LEN]]
    ) -> [f64; JET_LEN]
        = jet_sum_body, jet_sum_avx512, jet_sum_avx2
}

/// Lane-wise a + (b·s − c·t): one vector expression, so the compiler keeps the lanes as the
/// vector (left to itself it vectorised `node_jets` across the jet values, with gathers).
#[inline(always)]
fn acc_diff(a: [f64; LANES], b: &[f64; LANES], s: f64, c: &[f64; LANES], t: f64) -> [f64; LANES] {
    std::array::from_fn(|l| a[l] + (s * b[l] - t * c[l]))
}

/// What [`node_jets`] reads: the phasors z_i; the nodes' rotations r_{i,l} as blocks of
/// [`LANES`] nodes, component after component in a block, real and imaginary parts apart; and
/// each component's jet factors C = `re` + i·`im`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeJetInputs<'a> {
    pub z: &'a [Complex<f64>],
    pub rot_re: &'a [[f64; LANES]],
    pub rot_im: &'a [[f64; LANES]],
    pub re: &'a [[f64; JET_LEN]],
    pub im: &'a [[f64; JET_LEN]],
}

impl NodeJetInputs<'_> {
    /// Blocks of nodes.
    fn blocks(&self) -> usize {
        self.rot_re.len() / self.z.len().max(1)
    }
}

#[inline(always)]
fn node_jets_body(x: &NodeJetInputs<'_>, out: &mut [[f64; LANES]]) {
    let nc = x.z.len();
    for b in 0..x.blocks() {
        let mut acc = [[0.0; LANES]; JET_LEN];
        for i in 0..nc {
            let (rr, ri, z) = (&x.rot_re[b * nc + i], &x.rot_im[b * nc + i], x.z[i]);
            // u = z·r as `Complex`'s product forms it: (z.re·r.re − z.im·r.im, z.re·r.im + z.im·r.re).
            let ur: [f64; LANES] = std::array::from_fn(|l| z.re * rr[l] - z.im * ri[l]);
            let ui: [f64; LANES] = std::array::from_fn(|l| z.re * ri[l] + z.im * rr[l]);
            for (acc, (&cr, &ci)) in acc.iter_mut().zip(x.re[i].iter().zip(&x.im[i])) {
                *acc = acc_diff(*acc, &ur, cr, &ui, ci);
            }
        }
        out[b * JET_LEN..(b + 1) * JET_LEN].copy_from_slice(&acc);
    }
}

/// [`node_jets_body`] for AVX-512F written with the vector operations themselves: left to
/// itself the compiler vectorised the loop over components (with gathers and scatters). The
/// same operations in the same order (no fused multiply-add), so the same bits.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn node_jets_avx512(x: &NodeJetInputs<'_>, out: &mut [[f64; LANES]]) {
    use std::arch::x86_64::{
        _mm512_add_pd, _mm512_loadu_pd, _mm512_mul_pd, _mm512_set1_pd, _mm512_setzero_pd,
        _mm512_storeu_pd, _mm512_sub_pd,
    };
    let nc = x.z.len();
    for b in 0..x.blocks() {
        let mut acc = [_mm512_setzero_pd(); JET_LEN];
        for i in 0..nc {
            let (rr, ri) = (&x.rot_re[b * nc + i], &x.rot_im[b * nc + i]);
            // SAFETY: each is a whole [f64; 8], the 64 bytes an unaligned load reads.
            let (rr, ri) = unsafe { (_mm512_loadu_pd(rr.as_ptr()), _mm512_loadu_pd(ri.as_ptr())) };
            let (zr, zi) = (_mm512_set1_pd(x.z[i].re), _mm512_set1_pd(x.z[i].im));
            let ur = _mm512_sub_pd(_mm512_mul_pd(zr, rr), _mm512_mul_pd(zi, ri));
            let ui = _mm512_add_pd(_mm512_mul_pd(zr, ri), _mm512_mul_pd(zi, rr));
            for (acc, (&cr, &ci)) in acc.iter_mut().zip(x.re[i].iter().zip(&x.im[i])) {
                let t = _mm512_sub_pd(
                    _mm512_mul_pd(_mm512_set1_pd(cr), ur),
                    _mm512_mul_pd(_mm512_set1_pd(ci), ui),
                );
                *acc = _mm512_add_pd(*acc, t);
            }
        }
        for (o, acc) in out[b * JET_LEN..(b + 1) * JET_LEN].iter_mut().zip(acc) {
            // SAFETY: `o` is a whole [f64; 8], the 64 bytes an unaligned store writes.
            unsafe { _mm512_storeu_pd(o.as_mut_ptr(), acc) };
        }
    }
}

multiversion! {
    /// [`jet_sum`] with rotations for [`LANES`] nodes side by side: for each block b of nodes,
    /// out[b·JET_LEN + j][l] = Σ_i Re(C_{j,i}·z_i·r_{i,l}), the same operations in the same
    /// order as [`jet_sum`] for one node.
    pub(crate) fn node_jets(x: &NodeJetInputs<'_>, out: &mut [[f64; LANES]])
        = node_jets_body, use node_jets_avx512, node_jets_avx2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dispatched build (the widest this CPU has) against the baseline body.
    #[test]
    fn wide_builds_give_the_baseline_bits() {
        let val =
            |k: usize| ((k * 7919 % 1013) as f64 * 0.731).sin() * 10f64.powi(k as i32 % 7 - 3);
        let z: Vec<Complex<f64>> = (0..16).map(|i| Complex::new(val(i), val(i + 99))).collect();
        let r: Vec<Complex<f64>> = (0..16)
            .map(|i| Complex::from_polar(1.0, val(i + 7)))
            .collect();
        let re: Vec<[f64; JET_LEN]> = (0..16)
            .map(|i| std::array::from_fn(|j| val(i * 31 + j)))
            .collect();
        let im: Vec<[f64; JET_LEN]> = (0..16)
            .map(|i| std::array::from_fn(|j| val(i * 37 + j + 5)))
            .collect();
        for rot in [None, Some(&r[..])] {
            let a = jet_sum(&z, rot, &re, &im);
            let b = jet_sum_body(&z, rot, &re, &im);
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        }
        let rot: Vec<[f64; LANES]> = (0..32)
            .map(|k| std::array::from_fn(|l| val(k * 8 + l + 11)))
            .collect();
        let (mut a, mut b) = (
            vec![[0.0; LANES]; 2 * JET_LEN],
            vec![[0.0; LANES]; 2 * JET_LEN],
        );
        let rot_im: Vec<[f64; LANES]> = rot.iter().map(|r| r.map(|v| v * 0.7 - 0.1)).collect();
        let x = NodeJetInputs {
            z: &z,
            rot_re: &rot,
            rot_im: &rot_im,
            re: &re,
            im: &im,
        };
        node_jets(&x, &mut a);
        node_jets_body(&x, &mut b);
        let bits = |v: &[[f64; LANES]]| v.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
        let (e, o): (Vec<[f64; POINT_CHANNELS]>, Vec<_>) = (0..6)
            .map(|j| {
                let f = |k: usize| std::array::from_fn(|c| val(j * 41 + c + k));
                (f(0), f(500))
            })
            .unzip();
        let w_t: Vec<[f64; LANES]> = (0..12 * 4)
            .map(|k| std::array::from_fn(|l| val(k * 8 + l + 3)))
            .collect();
        let (mut a, mut b) = (vec![0.0; 9 * 64], vec![0.0; 9 * 64]);
        combine_mirrored(&w_t, &e, &o, &mut a);
        combine_mirrored_body(&w_t, &e, &o, &mut b);
        let bits = |v: &[f64]| v.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
    }
}
