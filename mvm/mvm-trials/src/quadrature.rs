//! Five-point Gauss–Legendre quadrature: exact for polynomials of degree 9, so on the smooth
//! pieces of a row (a fraction of a second, against time constants of 30 s and more and turns
//! of a few degrees) its error is far below the last bit of the increments.

/// Abscissae on [−1, 1].
const X: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683_1,
    0.0,
    0.538_469_310_105_683_1,
    0.906_179_845_938_664,
];

/// Weights on [−1, 1] (sum 2).
const W: [f64; 5] = [
    0.236_926_885_056_189_08,
    0.478_628_670_499_366_47,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_47,
    0.236_926_885_056_189_08,
];

/// The nodes (time, weight) of the rule on [a, b]: Σ w·f(t) ≈ ∫_a^b f dt.
pub fn nodes(a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    X.iter()
        .zip(W)
        .map(move |(x, w)| (mid + half * x, half * w))
}

/// ∫_a^b f dt by the five-point rule.
pub fn integrate(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    nodes(a, b).map(|(t, w)| w * f(t)).sum()
}
