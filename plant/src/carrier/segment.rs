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
//! the monic Legendre polynomial on [−1, 1]). [`SegmentRule::choose`] takes, of the (n, M) with
//! that bound ≤ [`SEGMENT_EPS`] at ω = 2·ω_top (products of two motions, e.g. Coriolis and the
//! rotation of gravity, reach twice the highest frequency), the one that costs least per tick.
//!
//! The nodes are symmetric about the segment's middle, so tick M − 1 − k weights each mirrored
//! pair of nodes the other way round from tick k; the tick means are computed for the first half
//! of the ticks from the pairs' half sums and half differences, and both halves follow
//! (`crate::simd::combine_mirrored`): half the products of the plain combination.

use nalgebra::Vector3;

use super::GL_OFFSETS;
use crate::simd::{LANES, MAX_PAIRS, combine_mirrored};

mod ship_segment;

pub use ship_segment::{PointEnv, SegState};

/// Nodes per segment the tests take (the ship chooses its own: [`SegmentRule::choose`]).
pub const SEGMENT_NODES: usize = 16;

/// Fewest nodes per segment [`SegmentRule::choose`] considers.
pub const SEGMENT_MIN_NODES: usize = 6;

/// Most nodes per segment [`SegmentRule::choose`] considers: beyond, the weights of a 256-tick
/// segment outgrow the first-level cache.
pub const SEGMENT_MAX_NODES: usize = 24;

/// What a node costs (the full carrier state, the sea state's jet and the carrier points),
/// in products of one node's values into one tick's means (measured on the 16-position
/// benchmark at sea state 5: about 120 ns against 0.18 ns).
pub const NODE_COST_TICKS: f64 = 650.0;

/// Relative interpolation error the segment length is chosen for (of the motion's amplitude at
/// twice the top frequency).
pub const SEGMENT_EPS: f64 = 1e-10;

/// Longest segment, ticks (a power of two dividing the sea state's resynchronisation period).
/// 512 measured slower at every sea state: a segment's tick means (9 channels × M) then no
/// longer stay in the first-level cache.
pub const SEGMENT_MAX_TICKS: u64 = 256;

/// Shortest segment worth it, ticks: below this the n node evaluations cost more than the
/// exact per-tick path's three (and the mirrored combine wants a block of ticks per half).
pub const SEGMENT_MIN_TICKS: u64 = 2 * LANES as u64;

/// Channels per node: ω_ic (0..3), f at the IMU (3..6) and the up axis (6..9), in the table
/// mount's axes (C_c^v applied; the carrier's for the default mount), then the carrier state: latitude and longitude from the segment start (9, 10),
/// height (11), v^n (12..15), v̇^n (15..18), C_c^n row by row (18..27), ω_nc^c (27..30),
/// α_nc^c (30..33).
pub const CHANNELS: usize = 33;

pub use super::widths::POINT_CHANNELS;

/// Per-row weights (`w[r·n + j]`, n per row) as blocks of [`LANES`] rows, weight after weight
/// (the layout of [`combine_mirrored`]). Half segments are powers of two ≥ [`LANES`] ticks.
fn blocks_of(w: &[f64], n: usize) -> Vec<[f64; LANES]> {
    let blocks = w.len() / n / LANES;
    (0..n)
        .flat_map(|j| (0..blocks).map(move |b| (j, b)))
        .map(|(j, b)| std::array::from_fn(|l| w[(b * LANES + l) * n + j]))
        .collect()
}

/// Half sums or half differences of the point channels of node pairs.
type Pairs = [[f64; POINT_CHANNELS]; MAX_PAIRS];

/// Node j's and its mirror node's weights in a row `w` of n: their sum (the weight of the
/// pair's half sum); the middle node of an odd n alone.
fn pair_sum(w: &[f64], j: usize) -> f64 {
    let k = w.len() - 1 - j;
    if k == j { w[j] } else { w[j] + w[k] }
}

/// Their difference (the weight of the pair's half difference; none for a middle node).
fn pair_difference(w: &[f64], j: usize) -> f64 {
    let k = w.len() - 1 - j;
    if k == j { 0.0 } else { w[j] - w[k] }
}

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
    /// Per tick k < M/2, for the node pairs (j, n − 1 − j) (the nodes are symmetric about the
    /// segment's middle, so tick M − 1 − k weights the pair's nodes the other way round): the
    /// pair's even weights a + b, then its odd weights a − b (a, b: node j's and node
    /// n − 1 − j's mean over the tick). Tick k's mean is S + D and tick M − 1 − k's S − D, with
    /// S the even weights applied to the pairs' half sums and D the odd weights to their half
    /// differences: half the products of the plain rule.
    mirror_w: Vec<f64>,
    /// `mirror_w` transposed into blocks of ticks, weight after weight: what
    /// [`SegmentRule::tick_means_all`] streams through.
    mirror_w_t: Vec<[f64; LANES]>,
    /// Per tick boundary i = 0..=M: the basis at i.
    at_w: Vec<f64>,
    /// Per tick k and in-tick Gauss–Legendre point p: the basis there.
    gl_w: Vec<f64>,
    /// Per node i: the basis integrated from the segment start to node i, over T.
    disp_w: Vec<f64>,
    /// `disp_w` transposed (`[j·n + i]`: node j's weight in node i's displacement).
    disp_w_t: Vec<f64>,
    /// The Gauss–Legendre weights over 2 (they sum to 1): the basis means over the segment.
    seg_w: Vec<f64>,
}

impl SegmentRule {
    /// The weights for `n` nodes on a segment of `m` ticks.
    pub fn new(n: usize, m: u64) -> Self {
        let (x, w) = gauss_legendre(n);
        let mf = m as f64;
        let node_ticks: Vec<f64> = x.iter().map(|x| 0.5 * (1.0 + x) * mf).collect();
        // The Lagrange basis at t: l_j(t) = Π_{i<j}(t − x_i)·Π_{i>j}(t − x_i)/Π_{i≠j}(x_j − x_i),
        // the two products carried from either end (O(n) per t, defined at the nodes too).
        let inv_den: Vec<f64> = (0..n)
            .map(|j| {
                let d: f64 = (0..n)
                    .filter(|&i| i != j)
                    .map(|i| node_ticks[j] - node_ticks[i])
                    .product();
                1.0 / d
            })
            .collect();
        // Into a caller's buffer: a rule evaluates the basis some 10⁴ times.
        let basis_into = |t: f64, l: &mut [f64]| {
            let mut before = 1.0;
            for (l, x) in l.iter_mut().zip(&node_ticks) {
                *l = before;
                before *= t - x;
            }
            let mut after = 1.0;
            for j in (0..n).rev() {
                l[j] *= after * inv_den[j];
                after *= t - node_ticks[j];
            }
        };
        let basis = |t: f64| -> Vec<f64> {
            let mut l = vec![0.0; n];
            basis_into(t, &mut l);
            l
        };
        // ∫_a^b of the basis by the n-point rule (exact: the basis has degree n − 1), / (b − a).
        let mut l = vec![0.0; n];
        let mut mean = |a: f64, b: f64| -> Vec<f64> {
            let mut acc = vec![0.0; n];
            for (xq, wq) in x.iter().zip(&w) {
                basis_into(a + 0.5 * (1.0 + xq) * (b - a), &mut l);
                acc.iter_mut().zip(&l).for_each(|(s, l)| *s += 0.5 * wq * l);
            }
            acc
        };
        let mut me = Self {
            n,
            m,
            mirror_w: Vec::with_capacity(n.div_ceil(2) * m as usize),
            mirror_w_t: Vec::new(),
            at_w: Vec::with_capacity(n * (m as usize + 1)),
            gl_w: Vec::with_capacity(2 * n * m as usize),
            disp_w: Vec::with_capacity(n * n),
            disp_w_t: Vec::new(),
            seg_w: w.iter().map(|w| 0.5 * w).collect(),
            node_ticks: node_ticks.clone(),
        };
        let pairs = n.div_ceil(2);
        assert!(
            pairs <= MAX_PAIRS && m >= SEGMENT_MIN_TICKS,
            "{n} nodes on {m} ticks"
        );
        for k in 0..m {
            let kf = k as f64;
            if k < m / 2 {
                let w = mean(kf, kf + 1.0);
                let mut even: Vec<f64> = (0..pairs).map(|j| pair_sum(&w, j)).collect();
                // The pairs' half sums then carry the constants: even weights that sum to one
                // keep a constant's bits.
                sum_to_one(&mut even);
                me.mirror_w.extend(even);
                me.mirror_w
                    .extend((0..pairs).map(|j| pair_difference(&w, j)));
            }
            for f in GL_OFFSETS {
                me.gl_w.extend(basis(kf + f));
            }
        }
        for i in 0..=m {
            me.at_w.extend(basis(i as f64));
        }
        for w in [&mut me.at_w, &mut me.gl_w, &mut me.seg_w] {
            w.chunks_mut(n).for_each(sum_to_one);
        }
        me.mirror_w_t = blocks_of(&me.mirror_w, 2 * pairs);
        for &t in &node_ticks {
            me.disp_w
                .extend(mean(0.0, t).into_iter().map(|v| v * t / mf));
        }
        me.disp_w_t = (0..n * n).map(|k| me.disp_w[(k % n) * n + k / n]).collect();
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

    /// What a rule of `n` nodes on `m` ticks costs per tick, in products of one node's values
    /// into one tick's means: n·([`NODE_COST_TICKS`]/M + ½) (the mirrored combine spends half a
    /// product per node and tick).
    pub fn cost_per_tick(n: usize, m: u64) -> f64 {
        n as f64 * (NODE_COST_TICKS / m as f64 + 0.5)
    }

    /// Nodes and segment length, ticks, for motion up to `omega_top_rps` at ticks of `tick_s`:
    /// of the rules with [`SegmentRule::error_bound`] at 2·ω_top ≤ [`SEGMENT_EPS`] (n in
    /// [`SEGMENT_MIN_NODES`]..=[`SEGMENT_MAX_NODES`], M a power of two in
    /// [`SEGMENT_MIN_TICKS`]..=[`SEGMENT_MAX_TICKS`]) the one that costs least per tick,
    /// n·([`NODE_COST_TICKS`]/M + ½) (a tick's means cost half a product per node: the mirrored
    /// combine); `None` when no rule qualifies.
    pub fn choose(omega_top_rps: f64, tick_s: f64) -> Option<(usize, u64)> {
        let cost = Self::cost_per_tick;
        let mut best: Option<(usize, u64)> = None;
        for n in SEGMENT_MIN_NODES..=SEGMENT_MAX_NODES {
            let mut m = SEGMENT_MAX_TICKS;
            while m >= SEGMENT_MIN_TICKS {
                let wt = 2.0 * omega_top_rps * m as f64 * tick_s;
                if Self::error_bound(n, wt) <= SEGMENT_EPS {
                    // Ties go to the fewer nodes (found first).
                    if best.is_none_or(|(bn, bm)| cost(n, m) < cost(bn, bm)) {
                        best = Some((n, m));
                    }
                    break;
                }
                m /= 2;
            }
        }
        best
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

    /// Mean over tick `k` of the interpolated ω_ic^c, f^c and up axis (one tick of
    /// [`SegmentRule::tick_means_all`], bit for bit).
    pub fn tick_mean(&self, k: usize, y: &[[f64; CHANNELS]]) -> [f64; POINT_CHANNELS] {
        let pts: Vec<[f64; POINT_CHANNELS]> =
            y.iter().map(|r| std::array::from_fn(|c| r[c])).collect();
        let (mut even, mut odd) = (
            [[0.0; POINT_CHANNELS]; MAX_PAIRS],
            [[0.0; POINT_CHANNELS]; MAX_PAIRS],
        );
        let p = self.node_pairs(&pts, &mut even, &mut odd);
        let m = self.m as usize;
        let (row, upper) = if k < m / 2 {
            (k, false)
        } else {
            (m - 1 - k, true)
        };
        let w = &self.mirror_w[row * 2 * p..(row + 1) * 2 * p];
        let (mut s, mut d) = ([0.0; POINT_CHANNELS], [0.0; POINT_CHANNELS]);
        for j in 0..p {
            for c in 0..POINT_CHANNELS {
                s[c] += w[j] * even[j][c];
                d[c] += w[p + j] * odd[j][c];
            }
        }
        std::array::from_fn(|c| if upper { s[c] - d[c] } else { s[c] + d[c] })
    }

    /// The node pairs' half sums and half differences, (y_j ± y_{n−1−j})/2 for
    /// j < ⌈n/2⌉ (an odd n's middle node pairs with itself: its half sum is its value), into
    /// the first ⌈n/2⌉ rows of `even` and `odd`; returns ⌈n/2⌉.
    #[inline]
    fn node_pairs(&self, y: &[[f64; POINT_CHANNELS]], even: &mut Pairs, odd: &mut Pairs) -> usize {
        let n = self.n;
        let p = n.div_ceil(2);
        for j in 0..p {
            let (a, b) = (&y[j], &y[n - 1 - j]);
            for c in 0..POINT_CHANNELS {
                even[j][c] = 0.5 * (a[c] + b[c]);
                odd[j][c] = 0.5 * (a[c] - b[c]);
            }
        }
        p
    }

    /// [`SegmentRule::tick_mean`] for every tick of the segment at once: the same sums in the
    /// same order, so the same bits, but a block of ticks shares each pass over the node values
    /// and the products run as wide as the CPU allows (`crate::simd`).
    pub fn tick_means_all(&self, y: &[[f64; POINT_CHANNELS]], out: &mut TickMeans) {
        out.ticks = self.m as usize;
        out.v.resize(POINT_CHANNELS * out.ticks, 0.0);
        let (mut even, mut odd) = (
            [[0.0; POINT_CHANNELS]; MAX_PAIRS],
            [[0.0; POINT_CHANNELS]; MAX_PAIRS],
        );
        let p = self.node_pairs(&y[..self.n], &mut even, &mut odd);
        combine_mirrored(&self.mirror_w_t, &even[..p], &odd[..p], &mut out.v);
    }

    /// The point channels at the two Gauss–Legendre instants of tick `k` from every tick's
    /// means `means` (as [`SegmentRule::tick_means_all`] writes them):
    /// p(τ) = w̄ + w′·τ at τ = ∓h/(2√3) from the tick's middle, w′ from the ticks' means
    /// around it ([`SegmentRule::mean_and_slope`]).
    ///
    /// At those instants τ² = h²/12, so the mean's w″h²/24 is exactly the points' second-order
    /// term: the points err by the cubic term the line leaves out, w‴τ³/6 ≈ 0.008·|w‴|·h³, equal
    /// and opposite at the two instants, plus O(h⁴). In the increments only the rotation between
    /// the instants (the turning gimbal's angle step, (√3/3)·h·rate) weights that odd part:
    /// below 0.003·rate·|w‴|·h⁵, e.g. 6e-14 for a 2°/s gimbal and a 1 m/s² sea at 2 rad/s at
    /// 100 Hz, below the segment rule's own interpolation error ([`SEGMENT_EPS`]·h).
    #[inline]
    pub fn points_from_means(&self, means: &TickMeans, k: usize) -> [[f64; POINT_CHANNELS]; 2] {
        /// 1/(4√3): w′·τ = (2h·w′)·(±1/(4√3)).
        const STEP: f64 = 0.144_337_567_297_406_44;
        let (mean, diff) = self.mean_and_slope(means, k);
        [
            std::array::from_fn(|c| mean[c] - STEP * diff[c]),
            std::array::from_fn(|c| mean[c] + STEP * diff[c]),
        ]
    }

    /// Tick `k`'s means and D = 2h·w′ (w′ at the tick's middle) from the means of the ticks
    /// around it: five of them, so that the difference is exact for polynomials to degree 4 (the
    /// weights solve the moment equations of tick means, not of point values). In the interior
    /// D = (17/12)·(m₊₁ − m₋₁) − (5/24)·(m₊₂ − m₋₂), erring by ≈ 0.09·h⁵·|w⁽⁵⁾|; the two ticks at
    /// either end of the segment take one-sided five-tick stencils (≈ 0.26·h⁵·|w⁽⁵⁾|).
    #[inline]
    pub fn mean_and_slope(
        &self,
        means: &TickMeans,
        k: usize,
    ) -> ([f64; POINT_CHANNELS], [f64; POINT_CHANNELS]) {
        /// From the segment's first tick, ticks 0..5.
        const FIRST: [f64; 5] = [-95.0 / 24.0, 29.0 / 4.0, -5.0, 25.0 / 12.0, -3.0 / 8.0];
        /// From its second tick, ticks −1..4.
        const SECOND: [f64; 5] = [-3.0 / 8.0, -25.0 / 12.0, 7.0 / 2.0, -5.0 / 4.0, 5.0 / 24.0];
        let m = means.ticks;
        assert!(k < m && m >= 5, "tick {k} of a {m}-tick segment");
        let v = &means.v[..POINT_CHANNELS * m];
        let at = |c: usize, k: usize| v[c * m + k];
        let stencil = |c: usize, from: usize, w: &[f64; 5], sign: f64| -> f64 {
            let mut d = 0.0;
            for (i, w) in w.iter().enumerate() {
                // Mirrored stencils read backwards with the sign flipped (w′ is odd).
                let t = if sign > 0.0 { from + i } else { from - i };
                d += w * at(c, t);
            }
            sign * d
        };
        // The case once, not per channel.
        let diff: [f64; POINT_CHANNELS] = if k >= 2 && k + 2 < m {
            // The common case as a plain loop over fixed windows: one bounds check per channel
            // and nothing left to a closure the compiler might not inline.
            let mut d = [0.0; POINT_CHANNELS];
            for (c, d) in d.iter_mut().enumerate() {
                let w: &[f64; 5] = v[c * m + k - 2..c * m + k + 3].try_into().expect("5 ticks");
                *d = 17.0 / 12.0 * (w[3] - w[1]) - 5.0 / 24.0 * (w[4] - w[0]);
            }
            d
        } else if k == 0 {
            std::array::from_fn(|c| stencil(c, 0, &FIRST, 1.0))
        } else if k == 1 {
            std::array::from_fn(|c| stencil(c, 0, &SECOND, 1.0))
        } else if k + 1 == m {
            std::array::from_fn(|c| stencil(c, k, &FIRST, -1.0))
        } else {
            std::array::from_fn(|c| stencil(c, k + 1, &SECOND, -1.0))
        };
        (std::array::from_fn(|c| at(c, k)), diff)
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

    /// The interpolated position and velocity (channels 9..15: Δlat, Δlon, h, v_n) at tick
    /// boundary `i`: the same bits as those channels of [`SegmentRule::state_at`], without the
    /// other eighteen.
    #[inline]
    pub fn position_velocity_at(&self, i: usize, y: &[[f64; CHANNELS]]) -> [f64; 6] {
        Self::combine(&self.at_w[i * self.n..(i + 1) * self.n], y, POINT_CHANNELS)
    }

    /// The interpolated C_c^n (channels 18..27, row by row) at tick boundary `i`: the same bits
    /// as those channels of [`SegmentRule::state_at`], without the other fifteen.
    #[inline]
    pub fn attitude_at(&self, i: usize, y: &[[f64; CHANNELS]]) -> [f64; 9] {
        Self::combine(&self.at_w[i * self.n..(i + 1) * self.n], y, 18)
    }

    /// Displacements from the segment start to each node (into `nodes`) and to the segment end
    /// (returned), from the node velocities `v` (m/s) over a segment of `seg_s` seconds.
    pub fn displacements(&self, v: &[[f64; 2]], seg_s: f64, nodes: &mut Vec<[f64; 2]>) -> [f64; 2] {
        let n = self.n;
        let d = |w: &[f64]| -> [f64; 2] {
            let mut s = [0.0; 2];
            for (wj, vj) in w.iter().zip(v) {
                s[0] += wj * vj[0];
                s[1] += wj * vj[1];
            }
            [s[0] * seg_s, s[1] * seg_s]
        };
        // Node after node in the outer loop: the n sums run side by side (each still over the
        // nodes j in order, so the same bits as one sum at a time), not as n dependent chains.
        nodes.clear();
        nodes.resize(n, [0.0; 2]);
        for (j, vj) in v.iter().enumerate() {
            for (s, w) in nodes.iter_mut().zip(&self.disp_w_t[j * n..(j + 1) * n]) {
                s[0] += w * vj[0];
                s[1] += w * vj[1];
            }
        }
        for s in nodes.iter_mut() {
            *s = [s[0] * seg_s, s[1] * seg_s];
        }
        d(&self.seg_w)
    }
}

/// Every tick's mean points of a segment ([`SegmentRule::tick_means_all`]), channel after
/// channel: a channel's ticks are contiguous, which is how they are computed (one vector per
/// block of ticks) and how [`SegmentRule::points_from_means`] reads neighbours.
#[derive(Clone, Debug, Default)]
pub struct TickMeans {
    ticks: usize,
    v: Vec<f64>,
}

impl TickMeans {
    /// Channel `c` (of [`POINT_CHANNELS`]) over the segment's ticks.
    #[inline]
    pub fn channel(&self, c: usize) -> &[f64] {
        &self.v[c * self.ticks..(c + 1) * self.ticks]
    }

    /// Tick `k`'s point channels.
    #[inline]
    pub fn row(&self, k: usize) -> [f64; POINT_CHANNELS] {
        // One bounds check for the nine reads.
        let v = &self.v[k..k + (POINT_CHANNELS - 1) * self.ticks + 1];
        std::array::from_fn(|c| v[c * self.ticks])
    }
}

/// What a tick of a moving carrier gives the increments: the carrier points (ω_ic, f at the
/// IMU) and the up axis, either as means over the tick in body axes (the segment rule while the
/// table dwells) or at the tick's two Gauss–Legendre points in the table mount's axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TickPoints {
    /// Means over the tick, body axes: (ω_ib^b without the gimbals' part, f^b, up^b).
    BodyMean([Vector3<f64>; 3]),
    /// At the two Gauss–Legendre points, mount axes: (ω_ic^v, f^v, up^v) each.
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
mod tests;
