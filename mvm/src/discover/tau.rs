//! The time constant of a memory term found by discovery, by profile likelihood.
//!
//! The selection picks a memory term at one time constant of the library's grid
//! ([`super::library::tau_grid`]). Here the profile χ²(τ) of the same fit (the model before
//! the term, its parents, and the term at τ) is formed over the grid and over nine points
//! around the best one (a quarter of a grid step apart), the minimum is refined by a parabola in
//! ln τ through the three points around it, and the 95 % interval of τ is where the profile
//! stays within 3.84·s² of its minimum (likelihood ratio, one parameter; s² the reduced χ² at
//! the minimum, at least 1), interpolated linearly in ln τ; an end of the searched range that
//! the profile never crosses is reported as an open bound. The coefficient's interval then
//! accounts for τ's uncertainty: its covariance is taken from the fit linearised in both
//! (the column's derivative in τ, times the coefficient, as one more column).

use crate::fit::{ChannelData, Design, wls};

/// χ² units (×s²) of the 95 % profile-likelihood interval of one parameter.
pub const CHI2_95: f64 = 3.841_458_820_694_124;

/// Time constants around `tau_s` at a quarter of the grid's step `ratio`: `tau·ratio^(k/4)`
/// for k = −4…4, the grid points themselves left out.
pub fn fine_around(tau_s: f64, ratio: f64) -> Vec<f64> {
    (-4..=4)
        .filter(|k| k % 4 != 0)
        .map(|k| tau_s * ratio.powf(k as f64 / 4.0))
        .collect()
}

/// Rounds a time constant to three significant digits (the form it is written in).
pub fn round3(tau_s: f64) -> f64 {
    let e = tau_s.abs().log10().floor() as i32 - 2;
    let f = 10f64.powi(e);
    (tau_s / f).round() * f
}

/// One point of a profile: the fit with the time constant fixed at `tau_s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfilePoint {
    /// Time constant, s.
    pub tau_s: f64,
    /// χ² of the fit.
    pub chi2: f64,
    /// The term's coefficient (SI) there.
    pub theta: f64,
    /// Its standard error with τ fixed there.
    pub se: f64,
}

/// The profile over time constants `taus`: the design `x` with its last column replaced by each
/// of `cols` (a point whose fit fails or leaves the term unidentified is left out).
pub fn profile(x: &Design, d: &ChannelData, taus: &[f64], cols: &[Vec<f64>]) -> Vec<ProfilePoint> {
    let last = x.ncols() - 1;
    taus.iter()
        .zip(cols)
        .filter_map(|(&tau_s, col)| {
            let mut x = x.clone();
            for (r, v) in col.iter().enumerate() {
                x.x[(r, last)] = *v;
            }
            let f = wls(&x, d, None)?;
            f.identified(last).then(|| ProfilePoint {
                tau_s,
                chi2: f.chi2,
                theta: f.theta[last],
                se: f.cov[(last, last)].sqrt(),
            })
        })
        .collect()
}

/// The coefficient's 95 % interval over the time constants the data allow: the envelope of
/// its intervals with τ fixed at each profile point within the bound `chi2_bound` (a term
/// whose τ the data leave open is determined only together with it: a decay with τ ≫ the
/// dwells is a bias and a slope, and its amplitude follows τ).
pub fn envelope(points: &[ProfilePoint], chi2_bound: f64) -> Option<[f64; 2]> {
    let inside: Vec<&ProfilePoint> = points.iter().filter(|p| p.chi2 <= chi2_bound).collect();
    (!inside.is_empty()).then(|| {
        [
            inside
                .iter()
                .map(|p| p.theta - 1.96 * p.se)
                .fold(f64::INFINITY, f64::min),
            inside
                .iter()
                .map(|p| p.theta + 1.96 * p.se)
                .fold(f64::NEG_INFINITY, f64::max),
        ]
    })
}

/// The estimate and interval of τ from a profile `(tau, χ²)` (any order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TauEstimate {
    /// The minimum, refined by a parabola in ln τ.
    pub tau_s: f64,
    /// 95 % interval; an end the profile does not cross within the searched range is that
    /// range's end, with `open` set for it.
    pub ci95_s: [f64; 2],
    /// Whether each end is open (the profile stays within the bound up to the range's end).
    pub open: [bool; 2],
    /// The χ² the interval is bounded by (the minimum plus 3.84·s²).
    pub chi2_bound: f64,
}

/// The estimate of τ from the profile points `pts` (τ, χ²) and the noise scale `s2`.
pub fn estimate(pts: &[(f64, f64)], s2: f64) -> Option<TauEstimate> {
    let mut p: Vec<(f64, f64)> = pts
        .iter()
        .copied()
        .filter(|(t, c)| t.is_finite() && c.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    p.dedup_by(|a, b| a.0 == b.0);
    if p.is_empty() {
        return None;
    }
    let (k, &(t_min, c_min)) = p
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.1.total_cmp(&b.1.1))?;
    // A parabola in ln τ through the minimum and its neighbours.
    let (mut tau, mut cmin) = (t_min, c_min);
    if k > 0 && k + 1 < p.len() {
        let (x0, y0) = (p[k - 1].0.ln(), p[k - 1].1);
        let (x1, y1) = (p[k].0.ln(), p[k].1);
        let (x2, y2) = (p[k + 1].0.ln(), p[k + 1].1);
        let d1 = (y1 - y0) / (x1 - x0);
        let d2 = (y2 - y1) / (x2 - x1);
        let a = (d2 - d1) / (x2 - x0);
        if a > 0.0 {
            let b = d1 - a * (x0 + x1);
            let xm = (-b / (2.0 * a)).clamp(x0, x2);
            tau = xm.exp();
            // Newton's form: y = y0 + d1·(x − x0) + a·(x − x0)·(x − x1).
            cmin = (y0 + d1 * (xm - x0) + a * (xm - x0) * (xm - x1)).min(c_min);
        }
    }
    let bound = cmin + CHI2_95 * s2.max(1.0);
    let chi2_bound = bound;
    let cross = |i: usize, j: usize| {
        // ln τ where the straight line between points i and j meets the bound.
        let (xi, yi) = (p[i].0.ln(), p[i].1);
        let (xj, yj) = (p[j].0.ln(), p[j].1);
        let f = (bound - yi) / (yj - yi);
        (xi + f * (xj - xi)).exp()
    };
    let mut lo = (p[0].0, true);
    for i in (0..k).rev() {
        if p[i].1 > bound {
            lo = (cross(i + 1, i), false);
            break;
        }
    }
    let mut hi = (p[p.len() - 1].0, true);
    for i in k + 1..p.len() {
        if p[i].1 > bound {
            hi = (cross(i - 1, i), false);
            break;
        }
    }
    Some(TauEstimate {
        tau_s: tau,
        ci95_s: [lo.0.min(tau), hi.0.max(tau)],
        open: [lo.1, hi.1],
        chi2_bound,
    })
}

/// The last coefficient of the fit of `x`, its standard error with the time constant free, and
/// that error's ratio to the one with the time constant fixed: the design gains the column
/// `coef·∂col/∂τ` (`dcol_dtau` the derivative of the last column) and the covariance of the two
/// is read from that fit (scaled by the reduced χ², at least 1).
pub fn coefficient_with_tau(
    x: &Design,
    d: &ChannelData,
    dcol_dtau: &[f64],
) -> Option<(f64, f64, f64)> {
    let f = wls(x, d, None)?;
    let k = x.ncols() - 1;
    let coef = f.theta[k];
    if !f.identified(k) {
        return None;
    }
    let jac: Vec<f64> = dcol_dtau.iter().map(|v| v * coef).collect();
    let x2 = super::frols::append(x, &jac, 1.0);
    let fixed = f.cov[(k, k)].sqrt();
    let se = match wls(&x2, d, None) {
        Some(g) if g.identified(k) && g.identified(k + 1) => g.cov[(k, k)].sqrt().max(fixed),
        _ => fixed,
    };
    Some((coef, se, se / fixed))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A parabolic profile in ln τ: the minimum and the interval are the parabola's.
    #[test]
    fn a_parabolic_profile_gives_its_vertex_and_crossings() {
        let (t0, w) = (300.0f64, 0.4f64);
        // χ² = 100 + (ln τ − ln τ0)²/w² · CHI2_95: crosses the bound at ln τ0 ± w.
        let pts: Vec<(f64, f64)> = (0..40)
            .map(|k| {
                let t = 10.0 * 1.2f64.powi(k);
                (t, 100.0 + ((t.ln() - t0.ln()) / w).powi(2) * CHI2_95)
            })
            .collect();
        let e = estimate(&pts, 1.0).unwrap();
        assert!((e.tau_s / t0 - 1.0).abs() < 1e-9, "{e:?}");
        // Linear interpolation of a parabola between points 1.2× apart (0.18 in ln τ): the
        // crossing is found within a tenth of the spacing, 2 % here.
        assert!(
            (e.ci95_s[0] / (t0 * (-w).exp()) - 1.0).abs() < 0.02,
            "{e:?}"
        );
        assert!((e.ci95_s[1] / (t0 * w.exp()) - 1.0).abs() < 0.02, "{e:?}");
        assert_eq!(e.open, [false, false]);
        // A profile that stays flat to the range's end: an open bound there.
        let flat: Vec<(f64, f64)> = pts.iter().map(|(t, c)| (*t, c.min(101.0))).collect();
        let e = estimate(&flat, 1.0).unwrap();
        assert!(e.open[0] && e.open[1]);
    }

    #[test]
    fn rounding_and_fine_points() {
        assert_eq!(round3(123.456), 123.0);
        assert_eq!(round3(0.012345), 0.0123);
        assert_eq!(round3(98765.0), 98800.0);
        let f = fine_around(100.0, 2.0);
        assert_eq!(f.len(), 6);
        assert!((f[0] - 100.0 / 2f64.powf(0.75)).abs() < 1e-12);
    }
}
