//! Weighted least squares on window sums, candidate tests against the current model with the
//! gate (ΔBIC, nested F test, cross-validated error), confidence intervals and collinearity
//! diagnostics (VIF, condition number). The forward selection that uses them is in
//! [`crate::selection`].

// Six channels and coefficient columns indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use nalgebra::{DMatrix, DVector};

use crate::replay::{Group, Window};
use crate::stats::f_sf;

/// One channel's windows: residual sums, their noise variances, durations and fold labels.
#[derive(Clone, Debug)]
pub struct ChannelData {
    /// Channel index 0–5.
    pub channel: usize,
    /// Residual sums.
    pub y: Vec<f64>,
    /// Noise variance of each sum.
    pub v: Vec<f64>,
    /// Window durations, s.
    pub dur: Vec<f64>,
    /// Cross-validation fold of each window.
    pub fold: Vec<usize>,
    /// Number of folds.
    pub folds: usize,
}

/// A weighted least-squares fit.
#[derive(Clone, Debug)]
pub struct Fit {
    /// Coefficients (SI), in group order.
    pub theta: Vec<f64>,
    /// Covariance, scaled by max(1, χ²/dof).
    pub cov: DMatrix<f64>,
    /// Weighted residual sum of squares.
    pub chi2: f64,
    /// Windows.
    pub n: usize,
    /// Condition number of the column-normalised weighted design.
    pub condition: f64,
}

impl Fit {
    /// Reduced χ².
    pub fn chi2_red(&self) -> f64 {
        self.chi2 / (self.n.saturating_sub(self.identified_count())).max(1) as f64
    }

    /// Whether coefficient `i` is identified by the data (a finite variance; see
    /// [`MAX_SE_FILE_UNITS`]); an unidentified one is reported as null and never written.
    pub fn identified(&self, i: usize) -> bool {
        self.cov[(i, i)].is_finite()
    }

    /// Number of identified coefficients among `range` (all with `0..theta.len()`).
    pub fn identified_in(&self, range: std::ops::Range<usize>) -> usize {
        range.filter(|&i| self.identified(i)).count()
    }

    /// Number of identified coefficients.
    pub fn identified_count(&self) -> usize {
        self.identified_in(0..self.theta.len())
    }
}

/// The largest standard error, in the coefficient's scenario-file unit (°/h, ppm, ″, °/h/g,
/// µg, … per K^n), at which a coefficient still counts as identified. The data carry
/// information on a coefficient in proportion to its whitened column's norm (1/σ_θ): an
/// unexcited column (g-sensitivity to x when body x never leaves the horizontal) is exactly zero
/// with gimbal angles but rounding noise (~1e-16 of the input) with a quaternion attitude, and
/// fitting it gives 1e14-sized coefficients. A coefficient the data determine only to ±1e4 file
/// units (1 % scale factor, 2.8° misalignment, 1e4 °/h/g) says nothing about a navigation-grade
/// unit; it is reported as null and never written.
pub const MAX_SE_FILE_UNITS: f64 = 1e4;

/// Design columns of some candidate groups over the windows (SI coefficients), with the SI
/// size of each coefficient's scenario-file unit (what identifiability is judged in).
#[derive(Clone, Debug)]
pub struct Design {
    /// Rows = windows, columns = coefficients.
    pub x: DMatrix<f64>,
    /// Per column, the SI value of one scenario-file unit of its coefficient.
    pub unit: Vec<f64>,
}

impl std::ops::Deref for Design {
    type Target = DMatrix<f64>;
    fn deref(&self) -> &DMatrix<f64> {
        &self.x
    }
}

impl Design {
    /// The columns `cols` only.
    pub fn select(&self, cols: &[usize]) -> Design {
        Design {
            x: DMatrix::from_fn(self.x.nrows(), cols.len(), |r, c| self.x[(r, cols[c])]),
            unit: cols.iter().map(|&c| self.unit[c]).collect(),
        }
    }
}

/// Design columns of `groups` over the windows.
pub fn design(windows: &[Window], groups: &[Group]) -> Design {
    let p: usize = groups.iter().map(|g| g.len).sum();
    let x = DMatrix::from_fn(windows.len(), p, |r, c| {
        let mut c = c;
        for g in groups {
            if c < g.len {
                return windows[r].x[g.offset + c];
            }
            c -= g.len;
        }
        0.0
    });
    let unit = groups
        .iter()
        .flat_map(|g| {
            let mut u: Vec<f64> = g
                .effect
                .coefficient_keys(g.channel)
                .into_iter()
                .map(|(_, u)| u)
                .collect();
            u.resize(g.len, 1.0);
            u.truncate(g.len);
            u
        })
        .collect();
    Design { x, unit }
}

/// Columns the whitened design `a` (rows already divided by σ) can identify: pivoted
/// Gram–Schmidt in file units, taking the best-determined column first and keeping a column
/// while its part not explained by the columns kept before determines its coefficient to
/// better than [`MAX_SE_FILE_UNITS`] (|a⊥|·unit ≥ 1/MAX_SE). Returns them in column order.
fn identified_columns(a: &DMatrix<f64>, unit: &[f64]) -> Vec<usize> {
    let p = a.ncols();
    let mut q: Vec<DVector<f64>> = (0..p)
        .map(|c| a.column(c) * unit[c].abs())
        .map(|v| {
            if v.iter().all(|x| x.is_finite()) {
                v
            } else {
                v * 0.0
            }
        })
        .collect();
    let mut free: Vec<usize> = (0..p).collect();
    let mut kept = Vec::new();
    while !free.is_empty() {
        let (k, norm) = free
            .iter()
            .enumerate()
            .map(|(k, &c)| (k, q[c].norm()))
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .expect("non-empty");
        if !(norm * MAX_SE_FILE_UNITS >= 1.0) {
            break;
        }
        let c = free.swap_remove(k);
        let e = &q[c] / norm;
        for &o in &free {
            let proj = e.dot(&q[o]);
            q[o] -= &e * proj;
        }
        kept.push(c);
    }
    kept.sort_unstable();
    kept
}

/// WLS of `d.y` on the columns `x` (rows with `mask` false are left out).
pub fn wls(x: &Design, d: &ChannelData, mask: Option<&[bool]>) -> Option<Fit> {
    let rows: Vec<usize> = (0..d.y.len())
        .filter(|&r| mask.is_none_or(|m| m[r]))
        .collect();
    let p = x.ncols();
    let n = rows.len();
    if p == 0 {
        let chi2 = rows.iter().map(|&r| d.y[r] * d.y[r] / d.v[r]).sum();
        return Some(Fit {
            theta: Vec::new(),
            cov: DMatrix::zeros(0, 0),
            chi2,
            n,
            condition: 1.0,
        });
    }
    if n <= p {
        return None;
    }
    let mut a = DMatrix::zeros(n, p);
    let mut b = DVector::zeros(n);
    for (i, &r) in rows.iter().enumerate() {
        let w = 1.0 / d.v[r].sqrt();
        for c in 0..p {
            a[(i, c)] = x[(r, c)] * w;
        }
        b[i] = d.y[r] * w;
    }
    // Coefficients the data cannot determine (MAX_SE_FILE_UNITS: an unexcited column is zero
    // or rounding noise) are not estimated: reported as 0 with an unbounded interval.
    let live = identified_columns(&a, &x.unit);
    if live.is_empty() {
        return None;
    }
    if live.len() < p {
        let f = wls(&x.select(&live), d, mask)?;
        let mut theta = vec![0.0; p];
        let mut cov = DMatrix::from_element(p, p, 0.0);
        for (i, &li) in live.iter().enumerate() {
            theta[li] = f.theta[i];
            for (j, &lj) in live.iter().enumerate() {
                cov[(li, lj)] = f.cov[(i, j)];
            }
        }
        for c in (0..p).filter(|c| !live.contains(c)) {
            cov[(c, c)] = f64::INFINITY;
        }
        return Some(Fit {
            theta,
            cov,
            chi2: f.chi2,
            n: f.n,
            condition: f.condition,
        });
    }
    // Normalise columns: the regressors span many orders of magnitude.
    let scale: Vec<f64> = (0..p).map(|c| a.column(c).norm()).collect();
    for c in 0..p {
        a.column_mut(c).unscale_mut(scale[c]);
    }
    let svd = a.clone().svd(true, true);
    let smax = svd.singular_values.max();
    let smin = svd.singular_values.min();
    if !(smin > smax * 1e-13) {
        return None;
    }
    if !(smin > smax * 1e-10) {
        return None;
    }
    let sol = svd.solve(&b, 0.0).ok()?;
    let resid = &b - &a * &sol;
    let chi2 = resid.norm_squared();
    let mut cov = (a.transpose() * &a).try_inverse()?;
    let red = (chi2 / (n - p) as f64).max(1.0);
    for i in 0..p {
        for j in 0..p {
            cov[(i, j)] *= red / (scale[i] * scale[j]);
        }
    }
    let theta = (0..p).map(|c| sol[c] / scale[c]).collect();
    Some(Fit {
        theta,
        cov,
        chi2,
        n,
        condition: smax / smin,
    })
}

/// Cross-validated RMS of the residual rate (rate units) with the columns `x`.
pub fn cv_rmse(x: &Design, d: &ChannelData) -> f64 {
    let mut sse = 0.0;
    let mut count = 0usize;
    for f in 0..d.folds {
        let train: Vec<bool> = d.fold.iter().map(|&k| k != f).collect();
        let Some(fit) = wls(x, d, Some(&train)) else {
            continue;
        };
        for r in (0..d.y.len()).filter(|&r| d.fold[r] == f) {
            let pred: f64 = (0..x.ncols()).map(|c| x[(r, c)] * fit.theta[c]).sum();
            let e = (d.y[r] - pred) / d.dur[r];
            sse += e * e;
            count += 1;
        }
    }
    (sse / count.max(1) as f64).sqrt()
}

/// The largest gyro scale-factor error (fraction) a fitted term may imply anywhere in the data:
/// 0.1 % (1000 ppm), a hundred times what a navigation-grade RLG has. On an axis that sees only
/// the Earth rate (body y of a level table that flips about x and turns about z), a scale
/// factor reads 15 °/h·(its north component), so a bias that follows the azimuth (a field fixed
/// in the navigation frame, a g-sensitivity on a tilted mount) looks like a scale factor of
/// thousands of ppm with one parameter where the true effect has more; the bound refuses such
/// a stand-in.
pub const MAX_GYRO_SCALE_FACTOR: f64 = 1e-3;

/// How much worse than on all the data a coefficient may be determined in a fold's (or a
/// resample's) training data for that fold to judge it: a fold that leaves out the only run
/// exciting a term (the one run with tilted dwells, say) cannot test it, and counts neither
/// for nor against it.
pub const FOLD_SE_RATIO: f64 = 3.0;

/// How much worse than its share of the data (a standard error √folds times the one on all the
/// data) a fold's held-out windows may determine an extra coefficient, beside the base columns,
/// for that fold to judge it. Held-out windows in which the candidate is the base's own column
/// (a dither bias ∝ u_z² on a run of Z-up and Z-down dwells only is the bias there) test
/// nothing of it: the two models differ there only by how each split the level in training,
/// and the gain's sign is chance.
pub const HELD_OUT_SE_RATIO: f64 = 3.0;

/// The cross-validated gain of the design `x` over its first `base_cols` columns, %, and the
/// CV RMSE with `x` (rate units): both models are fitted on each fold's training windows and
/// predict its held-out ones, over the folds that can judge the extra coefficients: the
/// training data determine each within [`FOLD_SE_RATIO`] of its standard error on all the data
/// (`full`, the fit of `x` on all windows), and the held-out data, beside the base columns,
/// within [`HELD_OUT_SE_RATIO`] of their share. No such fold: the gain is NaN, undecided, and
/// the gate ([`Gate::passes_test`]) leaves the decision to ΔBIC and the F test.
pub fn paired_cv(x: &Design, base_cols: usize, full: &Fit, d: &ChannelData) -> (f64, f64) {
    let x0 = x.select(&(0..base_cols).collect::<Vec<_>>());
    let (mut sse0, mut sse1, mut count) = (0.0, 0.0, 0usize);
    for f in 0..d.folds {
        let train: Vec<bool> = d.fold.iter().map(|&k| k != f).collect();
        let Some(f1) = wls(x, d, Some(&train)) else {
            continue;
        };
        let determined = (base_cols..x.ncols()).all(|k| {
            !full.identified(k)
                || f1.identified(k)
                    && f1.cov[(k, k)].sqrt() <= FOLD_SE_RATIO * full.cov[(k, k)].sqrt()
        });
        if !determined {
            continue;
        }
        let held: Vec<bool> = train.iter().map(|t| !t).collect();
        let share = (d.folds as f64).sqrt() * HELD_OUT_SE_RATIO;
        let testable = wls(x, d, Some(&held)).is_some_and(|fh| {
            (base_cols..x.ncols()).all(|k| {
                !full.identified(k)
                    || fh.identified(k) && fh.cov[(k, k)].sqrt() <= share * full.cov[(k, k)].sqrt()
            })
        });
        if !testable {
            continue;
        }
        let f0 = wls(&x0, d, Some(&train));
        for r in (0..d.y.len()).filter(|&r| d.fold[r] == f) {
            let p1: f64 = (0..x.ncols()).map(|c| x[(r, c)] * f1.theta[c]).sum();
            let p0: f64 = f0.as_ref().map_or(0.0, |f0| {
                (0..x0.ncols()).map(|c| x0[(r, c)] * f0.theta[c]).sum()
            });
            let (e0, e1) = ((d.y[r] - p0) / d.dur[r], (d.y[r] - p1) / d.dur[r]);
            sse0 += e0 * e0;
            sse1 += e1 * e1;
            count += 1;
        }
    }
    if count == 0 || !(sse0 > 0.0) {
        return (f64::NAN, f64::NAN);
    }
    (
        100.0 * (1.0 - (sse1 / sse0).sqrt()),
        (sse1 / count as f64).sqrt(),
    )
}

/// A candidate tested against the current model of its channel.
#[derive(Clone, Debug)]
pub struct Candidate {
    /// The group tested.
    pub group: Group,
    /// The fit with it added.
    pub fit: Fit,
    /// χ² drop.
    pub delta_chi2: f64,
    /// BIC change (negative favours adding it).
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated RMSE gain, %.
    pub cv_gain_pct: f64,
    /// CV RMSE with it, rate units.
    pub cv_rmse: f64,
    /// Index of its coefficients within `fit.theta`.
    pub theta_offset: usize,
}

/// A nested test of extra design columns against a base fit: what [`test_candidates`] computes
/// for each candidate, and discovery ([`crate::discover`]) for each library term, so both go
/// through the same [`Gate`].
#[derive(Clone, Debug)]
pub struct NestedTest {
    /// The fit with the extra columns.
    pub fit: Fit,
    /// χ² drop.
    pub delta_chi2: f64,
    /// BIC change (negative favours the extra columns).
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated RMSE gain, %.
    pub cv_gain_pct: f64,
    /// CV RMSE with them, rate units.
    pub cv_rmse: f64,
}

/// Tests the design `x` (the base model's `base_cols` columns first, then the extra ones)
/// against `base` (fitted on those first columns): ΔBIC, nested F test and cross-validated
/// gain ([`paired_cv`]). `None` if `x` cannot be fitted or identifies none of the extra columns.
pub fn nested_test(
    base: &Fit,
    base_cols: usize,
    x: &Design,
    d: &ChannelData,
) -> Option<NestedTest> {
    let fit = wls(x, d, None)?;
    // Only the coefficients the data identify count as parameters (an unexcited one is
    // not estimated); a candidate with none cannot explain anything.
    let k = fit.identified_in(base_cols..x.ncols()) as f64;
    if k == 0.0 {
        return None;
    }
    let ln_n = (d.y.len() as f64).ln();
    let delta_chi2 = base.chi2 - fit.chi2;
    let dof = (fit.n - fit.identified_count()).max(1) as f64;
    // Nested F test, with the noise floor as the variance unless the data say it is larger.
    let s2 = (fit.chi2 / dof).max(1.0);
    let p_value = f_sf(delta_chi2 / k / s2, k, dof);
    let delta_bic = -delta_chi2 / s2 + k * ln_n;
    let (cv_gain_pct, cv) = paired_cv(x, base_cols, &fit, d);
    Some(NestedTest {
        fit,
        delta_chi2,
        delta_bic,
        p_value,
        cv_gain_pct,
        cv_rmse: cv,
    })
}

/// Tests every group of `pool` added to `selected`.
pub fn test_candidates(
    windows: &[Window],
    d: &ChannelData,
    selected: &[Group],
    pool: &[Group],
) -> (Fit, Vec<Candidate>) {
    let x0 = design(windows, selected);
    let base = wls(&x0, d, None).expect("the selected model is identifiable");
    let mut out: Vec<Candidate> = Vec::new();
    for g in pool.iter().flat_map(|g| g.orders()) {
        let mut groups = selected.to_vec();
        groups.push(g);
        let x = design(windows, &groups);
        let Some(t) = nested_test(&base, x0.ncols(), &x, d) else {
            continue;
        };
        let cand = Candidate {
            group: g,
            theta_offset: x0.ncols(),
            fit: t.fit,
            delta_chi2: t.delta_chi2,
            delta_bic: t.delta_bic,
            p_value: t.p_value,
            cv_gain_pct: t.cv_gain_pct,
            cv_rmse: t.cv_rmse,
        };
        // Of a polynomial's orders (tried from the lowest), a higher one replaces a lower one
        // only if its extra terms are significant (nested F test, p < 0.001, as the orders are
        // tried in turn): a chance quadratic
        // term would bias the linear one.
        match out.iter_mut().find(|c| c.group.effect == g.effect) {
            Some(c) if higher_order_significant(&c.fit, &cand.fit) => *c = cand,
            Some(_) => {}
            None => out.push(cand),
        }
    }
    out.sort_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic));
    (base, out)
}

/// Whether the fit with more polynomial terms (`high`) is significantly better than `low`
/// (nested F test on their χ², p < 0.001 since the orders are tried in turn).
pub fn higher_order_significant(low: &Fit, high: &Fit) -> bool {
    let extra = high
        .identified_count()
        .saturating_sub(low.identified_count())
        .max(1) as f64;
    let dof = (high.n.saturating_sub(high.identified_count())).max(1) as f64;
    let f = (low.chi2 - high.chi2) / extra / high.chi2_red().max(1.0);
    f_sf(f, extra, dof) < 0.001
}

/// The gate a candidate must pass to be claimed.
#[derive(Clone, Copy, Debug)]
pub struct Gate {
    /// ΔBIC must be below this (−10: "very strong" evidence).
    pub max_delta_bic: f64,
    /// Family-wise significance, split over the candidates (Bonferroni).
    pub alpha: f64,
    /// Number of candidates tested.
    pub tests: usize,
    /// The cross-validated error must fall by at least this, %.
    pub min_cv_gain_pct: f64,
}

impl Gate {
    /// Whether `c` passes.
    pub fn passes(&self, c: &Candidate) -> bool {
        self.passes_test(c.delta_bic, c.p_value, c.cv_gain_pct)
    }

    /// Whether a test with these figures passes.
    pub fn passes_test(&self, delta_bic: f64, p_value: f64, cv_gain_pct: f64) -> bool {
        delta_bic < self.max_delta_bic
            && p_value < self.alpha / self.tests.max(1) as f64
            // NaN: no fold can judge the candidate (see [`paired_cv`]); ΔBIC and F decide.
            && (cv_gain_pct.is_nan() || cv_gain_pct > self.min_cv_gain_pct)
    }
}

/// ΔBIC (against `selected` alone) of adding `groups` together, or `None` if not identifiable.
pub fn delta_bic_of(
    windows: &[Window],
    d: &ChannelData,
    selected: &[Group],
    groups: &[Group],
) -> Option<(f64, Fit)> {
    let base = wls(&design(windows, selected), d, None)?;
    let mut all = selected.to_vec();
    all.extend_from_slice(groups);
    let fit = wls(&design(windows, &all), d, None)?;
    let k = fit
        .identified_count()
        .saturating_sub(base.identified_count());
    let s2 = fit.chi2_red().max(1.0);
    Some((
        -(base.chi2 - fit.chi2) / s2 + k as f64 * (d.y.len() as f64).ln(),
        fit,
    ))
}

/// Whitened contribution Σ x·θ / σ of `groups` with coefficients `theta` (in group order).
pub fn contribution(
    windows: &[Window],
    d: &ChannelData,
    groups: &[Group],
    theta: &[f64],
) -> Vec<f64> {
    let x = design(windows, groups);
    (0..x.nrows())
        .map(|r| (0..x.ncols()).map(|k| x[(r, k)] * theta[k]).sum::<f64>() / d.v[r].sqrt())
        .collect()
}

/// Pearson correlation of two whitened contributions, and the variance inflation of the first
/// when regressed on `other_cols` (with an intercept).
pub fn collinearity(
    a: &[f64],
    b: &[f64],
    windows: &[Window],
    d: &ChannelData,
    other: &[Group],
) -> (f64, f64) {
    let n = a.len().max(1) as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    let rho = if saa > 0.0 && sbb > 0.0 {
        sab / (saa * sbb).sqrt()
    } else {
        0.0
    };
    let xb = design(windows, other);
    let mut m = DMatrix::zeros(a.len(), xb.ncols() + 1);
    for r in 0..a.len() {
        let w = 1.0 / d.v[r].sqrt();
        for k in 0..xb.ncols() {
            m[(r, k)] = xb[(r, k)] * w;
        }
        m[(r, xb.ncols())] = 1.0;
    }
    let y = DVector::from_iterator(a.len(), a.iter().map(|x| x - ma));
    let r2 = m.clone().svd(true, true).solve(&y, 1e-12).map_or(0.0, |s| {
        let fitted = &m * s;
        let tot = y.norm_squared();
        if tot > 0.0 {
            (1.0 - (&y - fitted).norm_squared() / tot).clamp(0.0, 1.0)
        } else {
            0.0
        }
    });
    (rho, 1.0 / (1.0 - r2).max(1e-12))
}
