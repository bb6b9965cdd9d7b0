//! The segment rule for the ship: the full carrier state is evaluated only at the n
//! Gauss–Legendre nodes of a segment of M ticks, and each tick gets the integral of the
//! interpolating polynomial of ω_ic^c and f^c over it (a fixed linear combination of the node
//! values, weights precomputed once per (n, M)). The per-tick integrals of a segment sum to the
//! n-point Gauss–Legendre rule (exact to degree 2n − 1), so nothing drifts.
//!
//! Segments are aligned to multiples of M ticks from tick 0, and segment s is a function of its
//! index and the mean-track position at its start alone: save/restore and determinism stay
//! exact. A segment that contains a corner of the mean track (the start or end of a course or
//! speed change, where a derivative jumps) runs the exact per-tick path instead.
//!
//! Interpolation error on [0, T] with the Gauss–Legendre nodes, for a component of amplitude A
//! and angular frequency ω: |f − p| ≤ A·(ωT/2)ⁿ·κₙ/n!, κₙ = 2ⁿ(n!)²/(2n)! (the largest value of
//! the monic Legendre polynomial on [−1, 1]). [`SegmentRule::choose`] takes M as the largest
//! power of two with that bound ≤ [`SEGMENT_EPS`] at ω = 2·ω_top (products of two motions, e.g.
//! Coriolis and the rotation of gravity, reach twice the highest frequency).

use nalgebra::Vector3;

use super::GL_OFFSETS;

mod ship;

pub use ship::{PointEnv, SegState};

/// Nodes per segment.
pub const SEGMENT_NODES: usize = 12;

/// Relative interpolation error the segment length is chosen for (of the motion's amplitude at
/// twice the top frequency).
pub const SEGMENT_EPS: f64 = 1e-10;

/// Longest segment, ticks (a power of two dividing the sea state's resynchronisation period).
pub const SEGMENT_MAX_TICKS: u64 = 256;

/// Shortest segment worth it, ticks: below this the n node evaluations cost more than the
/// exact per-tick path's three.
pub const SEGMENT_MIN_TICKS: u64 = 8;

/// Channels per node: ω_ic^c (0..3), f^c at the IMU (3..6), the up axis in carrier axes
/// (6..9), then the carrier state: latitude and longitude from the segment start (9, 10),
/// height (11), v^n (12..15), v̇^n (15..18), C_c^n row by row (18..27), ω_nc^c (27..30),
/// α_nc^c (30..33).
pub const CHANNELS: usize = 33;

/// Channels a tick's increments need (ω_ic^c, f^c, up axis).
pub const POINT_CHANNELS: usize = 9;

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on the Legendre recurrence).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                (p0, p1) = (p1, p2);
            }
            // p1 = P_n(z), p0 = P_{n−1}(z).
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[n - 1 - i] = z;
        w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

/// Nudges the weights `w` by a few ulps so that their sum, accumulated in order as
/// [`SegmentRule`] combines node values, is exactly 1: a constant (an exact 0 or 1 of a level
/// attitude, say) is then reproduced bit for bit. The nudge goes to the smallest weight that
/// can do it (the finest step), so the rule moves by ~1e-19.
fn sum_to_one(w: &mut [f64]) {
    let sum = |w: &[f64]| w.iter().fold(0.0, |s, w| s + w);
    if sum(w) == 1.0 {
        return;
    }
    // The last weight as 1 − (the others' sum): exact when that difference is representable.
    let last = w.len() - 1;
    let keep = w[last];
    w[last] = 1.0 - sum(&w[..last]);
    if sum(w) == 1.0 {
        return;
    }
    w[last] = keep;
    let mut order: Vec<usize> = (0..w.len()).collect();
    order.sort_by(|&a, &b| w[a].abs().total_cmp(&w[b].abs()));
    for i in order {
        let b = w[i];
        for k in 1..=4096u64 {
            let up = sum(w) < 1.0;
            // One ulp of this weight towards the missing part.
            let bits = if up == (w[i] > 0.0) {
                w[i].to_bits() + 1
            } else {
                w[i].to_bits() - 1
            };
            w[i] = f64::from_bits(bits);
            if sum(w) == 1.0 {
                return;
            }
            if k == 4096 {
                w[i] = b;
            }
        }
    }
}

/// The weights of the segment rule for (n, M).
#[derive(Clone, Debug)]
pub struct SegmentRule {
    /// Nodes per segment.
    pub n: usize,
    /// Ticks per segment.
    pub m: u64,
    /// Node times, ticks from the segment start.
    pub node_ticks: Vec<f64>,
    /// Per tick k: the mean of each Lagrange basis polynomial over [k, k + 1].
    mean_w: Vec<f64>,
    /// Per tick boundary i = 0..=M: the basis at i.
    at_w: Vec<f64>,
    /// Per tick k and in-tick Gauss–Legendre point p: the basis there.
    gl_w: Vec<f64>,
    /// Per node i: the basis integrated from the segment start to node i, over T.
    disp_w: Vec<f64>,
    /// The Gauss–Legendre weights over 2 (they sum to 1): the basis means over the segment.
    seg_w: Vec<f64>,
}

impl SegmentRule {
    /// The weights for `n` nodes on a segment of `m` ticks.
    pub fn new(n: usize, m: u64) -> Self {
        let (x, w) = gauss_legendre(n);
        let mf = m as f64;
        let node_ticks: Vec<f64> = x.iter().map(|x| 0.5 * (1.0 + x) * mf).collect();
        let basis = |t: f64| -> Vec<f64> {
            (0..n)
                .map(|j| {
                    (0..n)
                        .filter(|&i| i != j)
                        .map(|i| (t - node_ticks[i]) / (node_ticks[j] - node_ticks[i]))
                        .product()
                })
                .collect()
        };
        // ∫_a^b of the basis by the n-point rule (exact: the basis has degree n − 1), / (b − a).
        let mean = |a: f64, b: f64| -> Vec<f64> {
            let mut acc = vec![0.0; n];
            for (xq, wq) in x.iter().zip(&w) {
                let l = basis(a + 0.5 * (1.0 + xq) * (b - a));
                acc.iter_mut().zip(l).for_each(|(s, l)| *s += 0.5 * wq * l);
            }
            acc
        };
        let mut me = Self {
            n,
            m,
            mean_w: Vec::with_capacity(n * m as usize),
            at_w: Vec::with_capacity(n * (m as usize + 1)),
            gl_w: Vec::with_capacity(2 * n * m as usize),
            disp_w: Vec::with_capacity(n * n),
            seg_w: w.iter().map(|w| 0.5 * w).collect(),
            node_ticks: node_ticks.clone(),
        };
        for k in 0..m {
            let k = k as f64;
            me.mean_w.extend(mean(k, k + 1.0));
            for f in GL_OFFSETS {
                me.gl_w.extend(basis(k + f));
            }
        }
        for i in 0..=m {
            me.at_w.extend(basis(i as f64));
        }
        for w in [&mut me.mean_w, &mut me.at_w, &mut me.gl_w, &mut me.seg_w] {
            w.chunks_mut(n).for_each(sum_to_one);
        }
        for &t in &node_ticks {
            me.disp_w
                .extend(mean(0.0, t).into_iter().map(|v| v * t / mf));
        }
        me
    }

    /// Bound of the interpolation error relative to the amplitude, for ω·T = `omega_t`:
    /// (ωT/2)ⁿ·κₙ/n!, κₙ = 2ⁿ(n!)²/(2n)!.
    pub fn error_bound(n: usize, omega_t: f64) -> f64 {
        let mut b = 1.0;
        for k in 1..=n {
            // (x/2)ⁿ·2ⁿ(n!)²/((2n)!·n!) = xⁿ·n!/(2n)! = Π_k x/(n + k).
            b *= omega_t / (n + k) as f64;
        }
        b
    }

    /// Segment length, ticks, for motion up to `omega_top_rps` at ticks of `tick_s`: the
    /// largest power of two ≤ [`SEGMENT_MAX_TICKS`] with [`SegmentRule::error_bound`] at
    /// 2·ω_top ≤ [`SEGMENT_EPS`]; `None` when that is below [`SEGMENT_MIN_TICKS`].
    pub fn choose(omega_top_rps: f64, tick_s: f64) -> Option<u64> {
        let mut m = SEGMENT_MAX_TICKS;
        while m >= SEGMENT_MIN_TICKS {
            let wt = 2.0 * omega_top_rps * m as f64 * tick_s;
            if Self::error_bound(SEGMENT_NODES, wt) <= SEGMENT_EPS {
                return Some(m);
            }
            m /= 2;
        }
        None
    }

    /// Σ_j w_j·y_j over the channels `range` of the node values `y`, into `out`.
    #[inline]
    fn combine<const C: usize>(w: &[f64], y: &[[f64; CHANNELS]], first: usize) -> [f64; C] {
        let mut out = [0.0; C];
        for (wj, yj) in w.iter().zip(y) {
            let y = &yj[first..first + C];
            for c in 0..C {
                out[c] += wj * y[c];
            }
        }
        out
    }

    /// Mean over tick `k` of the interpolated ω_ic^c, f^c and up axis.
    #[inline]
    pub fn tick_mean(&self, k: usize, y: &[[f64; CHANNELS]]) -> [f64; POINT_CHANNELS] {
        Self::combine(&self.mean_w[k * self.n..(k + 1) * self.n], y, 0)
    }

    /// The interpolated ω_ic^c, f^c and up axis at in-tick Gauss–Legendre point `p` of tick `k`.
    #[inline]
    pub fn tick_point(&self, k: usize, p: usize, y: &[[f64; CHANNELS]]) -> [f64; POINT_CHANNELS] {
        let o = (2 * k + p) * self.n;
        Self::combine(&self.gl_w[o..o + self.n], y, 0)
    }

    /// The interpolated carrier-state channels (9..33) at tick boundary `i` (0..=M).
    #[inline]
    pub fn state_at(&self, i: usize, y: &[[f64; CHANNELS]]) -> [f64; CHANNELS - POINT_CHANNELS] {
        Self::combine(&self.at_w[i * self.n..(i + 1) * self.n], y, POINT_CHANNELS)
    }

    /// Displacements from the segment start to each node and to the segment end, from the
    /// node velocities `v` (m/s) over a segment of `seg_s` seconds.
    pub fn displacements(&self, v: &[[f64; 2]], seg_s: f64) -> (Vec<[f64; 2]>, [f64; 2]) {
        let n = self.n;
        let d = |w: &[f64]| -> [f64; 2] {
            let mut s = [0.0; 2];
            for (wj, vj) in w.iter().zip(v) {
                s[0] += wj * vj[0];
                s[1] += wj * vj[1];
            }
            [s[0] * seg_s, s[1] * seg_s]
        };
        let nodes = (0..n)
            .map(|i| d(&self.disp_w[i * n..(i + 1) * n]))
            .collect();
        (nodes, d(&self.seg_w))
    }
}

/// What a tick of a moving carrier gives the increments: the carrier points (ω_ic^c, f^c at the
/// IMU) and the up axis in carrier axes, either as means over the tick (the segment rule while
/// the table dwells) or at the tick's two Gauss–Legendre points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TickPoints {
    /// Means over the tick: (ω_ic^c, f^c, up^c).
    Mean([Vector3<f64>; 3]),
    /// At the two Gauss–Legendre points: (ω_ic^c, f^c, up^c) each.
    Nodes([[Vector3<f64>; 3]; 2]),
}

impl TickPoints {
    /// From the channels 0..9 of [`CHANNELS`].
    #[inline]
    pub fn split(c: &[f64; POINT_CHANNELS]) -> [Vector3<f64>; 3] {
        [
            Vector3::new(c[0], c[1], c[2]),
            Vector3::new(c[3], c[4], c[5]),
            Vector3::new(c[6], c[7], c[8]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_means_sum_to_the_gauss_legendre_rule_and_reproduce_polynomials() {
        let rule = SegmentRule::new(SEGMENT_NODES, 64);
        // y(t) = t^(2n−1) on [0, 64] ticks: its per-tick integrals are exact (the interpolant of
        // a degree-(n−1) polynomial is itself) only below degree n; their sum is the n-point
        // rule, exact to degree 2n − 1.
        let n = SEGMENT_NODES;
        for deg in [n - 1, 2 * n - 1] {
            let f = |t: f64| (t / 64.0).powi(deg as i32);
            let y: Vec<[f64; CHANNELS]> = rule
                .node_ticks
                .iter()
                .map(|&t| {
                    let mut c = [0.0; CHANNELS];
                    c[0] = f(t);
                    c
                })
                .collect();
            let total: f64 = (0..64).map(|k| rule.tick_mean(k, &y)[0]).sum();
            let exact = 64.0 / (deg as f64 + 1.0);
            assert!(
                (total - exact).abs() < 1e-12,
                "degree {deg}: {total} vs {exact}"
            );
            if deg == n - 1 {
                for k in [0usize, 17, 63] {
                    let e = 64.0 * ((k as f64 + 1.0) / 64.0).powi(n as i32)
                        - 64.0 * (k as f64 / 64.0).powi(n as i32);
                    let m = rule.tick_mean(k, &y)[0] * n as f64;
                    assert!((m - e).abs() < 1e-12, "tick {k}: {m} vs {e}");
                }
            }
        }
    }

    #[test]
    fn constants_are_reproduced_bit_for_bit() {
        for m in [16, 64, 256] {
            let rule = SegmentRule::new(SEGMENT_NODES, m);
            let y = vec![[1.0; CHANNELS]; SEGMENT_NODES];
            for k in 0..m as usize {
                assert_eq!(rule.tick_mean(k, &y), [1.0; POINT_CHANNELS]);
                assert_eq!(rule.tick_point(k, 1, &y), [1.0; POINT_CHANNELS]);
                assert_eq!(rule.state_at(k + 1, &y), [1.0; CHANNELS - POINT_CHANNELS]);
            }
        }
    }

    #[test]
    fn error_bound_is_the_closed_form_and_holds_for_a_sinusoid() {
        // κ₂ = 2²·(2!)²/4! = 2/3: bound (x/2)²·(2/3)/2.
        let x = 0.7f64;
        assert!((SegmentRule::error_bound(2, x) - (x / 2.0).powi(2) / 3.0).abs() < 1e-15);
        // sin(ωt) on a 64-tick segment at 100 Hz, ω = 3 rad/s: the interpolant's largest
        // error over the tick boundaries stays below the bound.
        let (h, m) = (0.01, 64u64);
        let rule = SegmentRule::new(SEGMENT_NODES, m);
        let w = 3.0;
        let y: Vec<[f64; CHANNELS]> = rule
            .node_ticks
            .iter()
            .map(|&t| {
                let mut c = [0.0; CHANNELS];
                c[POINT_CHANNELS] = (w * t * h + 0.3).sin();
                c
            })
            .collect();
        let worst = (0..=m as usize)
            .map(|i| (rule.state_at(i, &y)[0] - (w * i as f64 * h + 0.3).sin()).abs())
            .fold(0.0, f64::max);
        let bound = SegmentRule::error_bound(SEGMENT_NODES, w * m as f64 * h);
        assert!(
            worst <= bound && worst > 1e-3 * bound,
            "{worst:e} vs {bound:e}"
        );
    }
}
