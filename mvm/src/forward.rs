//! Forward selection of one channel's candidates with heredity and a beam.
//!
//! **Heredity both ways.** A candidate enters with its parents (the constant of its kind, the
//! lower powers of a power, the factors of a product: [`crate::heredity`]) that the set lacks.
//! It is judged twice: the block (parents and candidate) must improve the set (ΔBIC below the
//! gate's), and the candidate itself must pass the gate on top of the set with its parents, so a
//! square never stands in for the linear term it is the child of: on data where a temperature-
//! linear scale factor makes `T²` look better than `T` alone on the model as given, `T²` fitted
//! with `T` and the constant explains nothing more, while `T` with the constant explains all.
//! Extensions are ranked by the block's ΔBIC, so the order in which single terms rank on the
//! model as given does not decide the set.
//!
//! **Beam.** The best [`BEAM`] sets are kept at each stage, not only the greedy one; every kept
//! set is extended by every candidate that passes, and the search ends when no set can be
//! extended. The chosen set is the one with the lowest summed block ΔBIC (the BIC of the set
//! against the model as given, stage by stage).

use crate::fit::{Candidate, ChannelData, Design, Fit, Gate, design, paired_cv, wls};
use crate::replay::{Effect, Group, Window};
use crate::stats::f_sf;
use rins_plant::effects::GyroTerm;

/// Sets kept at each stage.
pub const BEAM: usize = 3;
/// Terms per channel at most (parents not counted).
pub const MAX_TERMS: usize = 6;

/// One extension tried: a candidate on top of a set, with the parents it brings.
#[derive(Clone, Debug)]
pub struct Tried {
    /// The candidate's test on top of the set with its parents (its coefficients last).
    pub candidate: Candidate,
    /// Parents it brought (not in the set before).
    pub parents: Vec<Group>,
    /// ΔBIC of the block (parents and candidate) on top of the set.
    pub block_delta_bic: f64,
    /// Whether it passed (the candidate's gate on top of set and parents, the block's ΔBIC).
    pub passes: bool,
}

/// A selected set: the groups in order (a candidate's parents just before it), which of them
/// are parents, and the accepted candidates' tests.
#[derive(Clone, Debug, Default)]
pub struct Selection {
    /// Groups in order of entry.
    pub groups: Vec<Group>,
    /// Per group: the candidate it is a parent of (`None`: accepted in its own right).
    pub parent_of: Vec<Option<Group>>,
    /// The accepted candidates' tests, in order, each with the other extensions tried at its
    /// stage (for the confusable list).
    pub steps: Vec<(Tried, Vec<Candidate>)>,
    /// Summed block ΔBIC.
    pub score: f64,
}

impl Selection {
    fn key(&self) -> Vec<String> {
        let mut k: Vec<String> = self
            .groups
            .iter()
            .map(|g| format!("{}/{}", g.effect.name(), g.len))
            .collect();
        k.sort();
        k
    }

    /// The accepted candidates (not parents), in order.
    pub fn accepted(&self) -> Vec<Group> {
        self.groups
            .iter()
            .zip(&self.parent_of)
            .filter(|(_, p)| p.is_none())
            .map(|(g, _)| *g)
            .collect()
    }
}

/// A test of design `x` (its first `base_cols` columns the base) against the base fit `base`:
/// like [`crate::fit::nested_test`], but the cross-validated gain, which costs two fits per
/// fold, is computed only when ΔBIC and the p-value pass `gate`.
fn lazy_test(
    base: &Fit,
    base_cols: usize,
    x: &Design,
    d: &ChannelData,
    gate: &Gate,
) -> Option<(Fit, f64, f64, f64, f64)> {
    let fit = wls(x, d, None)?;
    let k = fit.identified_in(base_cols..x.ncols()) as f64;
    if k == 0.0 {
        return None;
    }
    let ln_n = (d.y.len() as f64).ln();
    let delta_chi2 = base.chi2 - fit.chi2;
    let dof = (fit.n - fit.identified_count()).max(1) as f64;
    let s2 = (fit.chi2 / dof).max(1.0);
    let p_value = f_sf(delta_chi2 / k / s2, k, dof);
    let delta_bic = -delta_chi2 / s2 + k * ln_n;
    let gain = if gate.passes_test(delta_bic, p_value, f64::INFINITY) {
        paired_cv(x, base_cols, &fit, d).0
    } else {
        f64::NEG_INFINITY
    };
    Some((fit, delta_chi2, delta_bic, p_value, gain))
}

/// Every extension of `set` by a candidate of `pool` (at each polynomial order), with its
/// parents from `parents`.
fn extensions(
    windows: &[Window],
    d: &ChannelData,
    set: &Selection,
    pool: &[Group],
    parents: &dyn Fn(&Group) -> Vec<Group>,
    gate: &Gate,
) -> Vec<Tried> {
    let x0 = design(windows, &set.groups);
    let Some(f0) = wls(&x0, d, None) else {
        return Vec::new();
    };
    let ln_n = (d.y.len() as f64).ln();
    // Bases with parents, shared by the candidates that bring the same parents.
    let mut bases: Vec<(Vec<Group>, Option<(Design, Fit)>)> = Vec::new();
    let mut out: Vec<Tried> = Vec::new();
    for g in pool.iter().flat_map(|g| g.orders()) {
        if set.groups.iter().any(|s| s.effect == g.effect) {
            continue;
        }
        let missing: Vec<Group> = parents(&g)
            .into_iter()
            .filter(|p| p.effect != g.effect && !set.groups.iter().any(|s| s.effect == p.effect))
            .collect();
        let with: Vec<Group> = set.groups.iter().chain(&missing).copied().collect();
        let base = match bases.iter().position(|(m, _)| *m == missing) {
            Some(i) => i,
            None => {
                let b = if missing.is_empty() {
                    Some((x0.clone(), f0.clone()))
                } else {
                    let x = design(windows, &with);
                    wls(&x, d, None).map(|f| (x, f))
                };
                bases.push((missing.clone(), b));
                bases.len() - 1
            }
        };
        let Some((xb, fb)) = &bases[base].1 else {
            continue;
        };
        let mut all = with.clone();
        all.push(g);
        let x = design(windows, &all);
        let Some((fit, delta_chi2, delta_bic, p_value, cv_gain_pct)) =
            lazy_test(fb, xb.ncols(), &x, d, gate)
        else {
            continue;
        };
        // A gyro scale factor beyond what any navigation-grade unit has is a bias in disguise.
        if matches!(
            g.effect,
            Effect::Gyro(GyroTerm::ScaleFactor | GyroTerm::ScaleFactorAsymmetry)
        ) && (xb.ncols()..x.ncols())
            .any(|k| fit.identified(k) && fit.theta[k].abs() > crate::fit::MAX_GYRO_SCALE_FACTOR)
        {
            continue;
        }
        // The block: parents and candidate on top of the set.
        let k_block = fit.identified_in(x0.ncols()..x.ncols()) as f64;
        let s2 = fit.chi2_red().max(1.0);
        let block_delta_bic = -(f0.chi2 - fit.chi2) / s2 + k_block * ln_n;
        let passes = gate.passes_test(delta_bic, p_value, cv_gain_pct)
            && block_delta_bic < gate.max_delta_bic;
        let cand = Candidate {
            group: g,
            theta_offset: xb.ncols(),
            cv_rmse: f64::NAN,
            fit,
            delta_chi2,
            delta_bic,
            p_value,
            cv_gain_pct,
        };
        let tried = Tried {
            candidate: cand,
            parents: missing,
            block_delta_bic,
            passes,
        };
        // Of a polynomial's orders (tried from the lowest), a higher one replaces a lower one
        // only if its extra terms are significant (p < 0.001), as in the ranking.
        match out
            .iter_mut()
            .find(|t| t.candidate.group.effect == g.effect)
        {
            Some(t)
                if crate::fit::higher_order_significant(&t.candidate.fit, &tried.candidate.fit) =>
            {
                *t = tried
            }
            Some(_) => {}
            None => out.push(tried),
        }
    }
    out.sort_by(|a, b| a.block_delta_bic.total_cmp(&b.block_delta_bic));
    out
}

/// Selects one channel's set from `pool` (see the module docs); `parents` gives a candidate's
/// parents as groups of the pool's channel.
pub fn select(
    windows: &[Window],
    d: &ChannelData,
    pool: &[Group],
    parents: &dyn Fn(&Group) -> Vec<Group>,
    gate: &Gate,
) -> Selection {
    let mut beams = vec![Selection::default()];
    let mut done: Vec<Selection> = Vec::new();
    for _ in 0..MAX_TERMS {
        let mut next: Vec<Selection> = Vec::new();
        for set in &beams {
            let tried = extensions(windows, d, set, pool, parents, gate);
            let others: Vec<Candidate> = tried.iter().map(|t| t.candidate.clone()).collect();
            let mut extended = false;
            for t in tried.iter().filter(|t| t.passes) {
                extended = true;
                let mut s = set.clone();
                for p in &t.parents {
                    s.groups.push(*p);
                    s.parent_of.push(Some(t.candidate.group));
                }
                s.groups.push(t.candidate.group);
                s.parent_of.push(None);
                s.score += t.block_delta_bic;
                s.steps.push((t.clone(), others.clone()));
                if !next.iter().any(|n| n.key() == s.key()) {
                    next.push(s);
                }
            }
            if !extended {
                done.push(set.clone());
            }
        }
        if next.is_empty() {
            break;
        }
        next.sort_by(|a, b| a.score.total_cmp(&b.score));
        next.truncate(BEAM);
        beams = next;
    }
    done.extend(beams);
    done.into_iter()
        .min_by(|a, b| a.score.total_cmp(&b.score))
        .unwrap_or_default()
}
