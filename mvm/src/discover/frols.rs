//! Sparse forward selection of library terms by the error-reduction ratio of orthogonal
//! forward regression (FROLS, Billings): the candidates and the residual are orthogonalised
//! (modified Gram–Schmidt, in the whitened metric of the noise floor) against the model so far,
//! the term whose orthogonal part explains most of the residual energy is the next, and it is
//! kept only if it passes the catalogue's [`Gate`] (ΔBIC, nested F test, cross-validated
//! gain) on top of that model. A bootstrap over runs repeats the orthogonal selection on
//! resampled runs and counts how often each kept term is chosen.

use nalgebra::DMatrix;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rayon::prelude::*;

use crate::fit::{ChannelData, Design, Gate, NestedTest, nested_test, wls};

/// Seed of the bootstrap over runs.
pub const BOOTSTRAP_SEED: u64 = 0xD15C_0BE7;
/// The bootstrap's named stream of that seed.
pub const BOOTSTRAP_STREAM: u64 = 0xB007_5742;
/// How much more of the residual's χ² a more complex term must explain than the best simpler
/// one to be preferred (the gate's ΔBIC threshold: "very strong" evidence).
pub const PARSIMONY_CHI2: f64 = 10.0;
/// Bootstrap resamples.
pub const RESAMPLES: usize = 100;
/// A candidate whose part orthogonal to the model keeps less than this share of its norm² is
/// (nearly) in the model already: not selectable.
const MIN_ORTHOGONAL_SHARE: f64 = 1e-8;
/// How many refused blocks (a term with library parents it brings) one step of the selection
/// passes over before it stops: a block ranks by what its parents and the term explain
/// together, so a square whose linear parent carries the signal can rank above the right
/// term, fail the gate, and must not end the search.
pub const MAX_REFUSED_BLOCKS: usize = 3;

/// The orthogonal-regression state of one channel: residual and candidates orthogonal to the
/// model so far, all whitened (and weighted for a bootstrap resample).
struct Ortho {
    r: Vec<f64>,
    q: Vec<Vec<f64>>,
    norm0: Vec<f64>,
    yy: f64,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn remove(v: &mut [f64], e: &[f64]) {
    let p = dot(e, v);
    for (x, u) in v.iter_mut().zip(e) {
        *x -= p * u;
    }
}

impl Ortho {
    /// `y` and `cands` (whitened) orthogonalised against the columns `base` (whitened).
    fn new(y: Vec<f64>, base: &[Vec<f64>], cands: Vec<Vec<f64>>) -> Self {
        let yy = dot(&y, &y);
        let mut s = Ortho {
            r: y,
            norm0: cands.iter().map(|c| dot(c, c)).collect(),
            q: cands,
            yy,
        };
        let mut basis: Vec<Vec<f64>> = Vec::new();
        for b in base {
            let mut e = b.clone();
            let n0 = dot(&e, &e);
            for u in &basis {
                remove(&mut e, u);
            }
            let n = dot(&e, &e);
            if n > 1e-12 * n0 && n > 0.0 {
                let inv = 1.0 / n.sqrt();
                e.iter_mut().for_each(|x| *x *= inv);
                basis.push(e);
            }
        }
        for e in &basis {
            s.take_direction(e);
        }
        s
    }

    fn take_direction(&mut self, e: &[f64]) {
        remove(&mut self.r, e);
        self.q.par_iter_mut().for_each(|q| remove(q, e));
    }

    /// Candidate `j`'s orthogonal part with its parents not yet `taken` removed too, those
    /// parents, what its library parents (the lower terms of its hierarchy: `T` under `T²`,
    /// the factors of a product) explain of the residual beyond its catalogue parents (the
    /// constants, which the catalogue step judges on their own), and how many columns those
    /// library parents add.
    fn beyond_parents(
        &self,
        j: usize,
        lib: &Candidates,
        taken: &[usize],
    ) -> (Vec<f64>, Vec<usize>, f64, usize) {
        let missing: Vec<usize> = lib.parents[j]
            .iter()
            .copied()
            .filter(|p| !taken.contains(p))
            .collect();
        let mut q = self.q[j].clone();
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let (mut parents_gain, mut added) = (0.0, 0);
        // The catalogue parents first, so a library parent's share is what it adds to them
        // (the projection of `j` is the same in any order).
        let ordered = missing
            .iter()
            .filter(|p| !lib.selectable[**p])
            .chain(missing.iter().filter(|p| lib.selectable[**p]));
        for &p in ordered {
            let mut e = self.q[p].clone();
            for u in &basis {
                remove(&mut e, u);
            }
            let n = dot(&e, &e);
            if n > MIN_ORTHOGONAL_SHARE * self.norm0[p] && n > 0.0 {
                let inv = 1.0 / n.sqrt();
                e.iter_mut().for_each(|x| *x *= inv);
                remove(&mut q, &e);
                if lib.selectable[p] {
                    parents_gain += dot(&e, &self.r).powi(2);
                    added += 1;
                }
                basis.push(e);
            }
        }
        (q, missing, parents_gain, added)
    }

    /// The candidate (selectable, not in `skip` nor `taken`) that explains most of the
    /// residual beyond its parents not yet taken, with its error-reduction ratio and those
    /// parents; preferring the simpler: a candidate of higher `complexity` (a product of two
    /// signals, an indicator, a memory term) is taken only if it explains more than the best
    /// simpler one by [`PARSIMONY_CHI2`] (in units of the residual's variance), and a term
    /// with a time constant pays for it as one more parameter (ln n in χ²); on data that cannot
    /// tell T·Δθ from T·|ω|·Δθ (constant-rate moves), the degree-one term is proposed.
    fn best(
        &self,
        skip: &[usize],
        taken: &[usize],
        lib: &Candidates,
    ) -> Option<(usize, f64, Vec<usize>)> {
        let n = self.r.len().max(1) as f64;
        // The columns are whitened by the noise floor: one unit of χ² is the noise. (The
        // residual's own variance would be the unexplained signal's while a large effect
        // remains, and would demand of a complex term hundreds of units more than the simple
        // one explains: a lag of the temperature never beat the temperature itself.)
        let s2 = 1.0;
        let scores: Vec<(usize, f64, f64, Vec<usize>)> = (0..self.q.len())
            .into_par_iter()
            .filter(|j| lib.selectable[*j] && !skip.contains(j) && !taken.contains(j))
            .filter_map(|j| {
                let owned;
                let (q, parents, parents_gain, added): (&[f64], Vec<usize>, f64, usize) =
                    if lib.parents[j].iter().all(|p| taken.contains(p)) {
                        (&self.q[j], Vec::new(), 0.0, 0)
                    } else {
                        let (q, p, pg, added) = self.beyond_parents(j, lib, taken);
                        owned = q;
                        (&owned, p, pg, added)
                    };
                let qq = dot(q, q);
                (qq > MIN_ORTHOGONAL_SHARE * self.norm0[j] && qq > 0.0).then(|| {
                    let g = dot(q, &self.r);
                    let gain = g * g / qq;
                    // Ranked by what its block (the library parents it brings and the term)
                    // explains beyond the catalogue constants, each column it adds paying
                    // ln n: a square whose linear parent carries most of the signal ranks with
                    // that signal, not with its small remainder beyond the parent (which left
                    // a temperature-quadratic scale factor to a three-column stand-in). The
                    // constants are left out: counted, a bias change rode in on any product
                    // that had the bias as a parent and died with it in the joint fit. The
                    // parsimony rule below still prefers the parent alone unless the block
                    // explains clearly more.
                    let penalised =
                        gain + parents_gain - (lib.extra_params[j] + added) as f64 * n.ln() * s2;
                    (j, penalised, gain, parents)
                })
            })
            .collect();
        let top = |max: u8| {
            scores
                .iter()
                .filter(|(j, ..)| lib.complexity[*j] <= max)
                .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
        };
        let mut pick = top(u8::MAX)?;
        for level in (0..lib.complexity[pick.0]).rev() {
            if let Some(simple) = top(level)
                && simple.1 >= pick.1 - PARSIMONY_CHI2 * s2
            {
                pick = simple;
            }
        }
        Some((
            pick.0,
            pick.2 / self.yy.max(f64::MIN_POSITIVE),
            pick.3.clone(),
        ))
    }

    /// Moves candidate `j` into the model.
    fn take(&mut self, j: usize) {
        let mut e = self.q[j].clone();
        let n = dot(&e, &e).sqrt();
        if !(n > 0.0) {
            return;
        }
        e.iter_mut().for_each(|x| *x /= n);
        self.take_direction(&e);
    }
}

/// The library of one channel as the selection reads it: columns (SI coefficients) with their
/// file units, complexity, parents, whether each may be selected alone, and the parameters
/// each has beyond its coefficient.
#[derive(Clone, Debug, Default)]
pub struct Candidates {
    /// Window sums of each candidate at a unit SI coefficient.
    pub cols: Vec<Vec<f64>>,
    /// SI size of each coefficient's file unit.
    pub units: Vec<f64>,
    /// 0 for one signal, 1 for a product, an indicator or a memory term.
    pub complexity: Vec<u8>,
    /// Each candidate's parents (heredity), as indices of this list: they enter with it.
    pub parents: Vec<Vec<usize>>,
    /// Whether a candidate may be selected in its own right (the catalogue constants are
    /// here only as parents).
    pub selectable: Vec<bool>,
    /// Parameters beyond the coefficient (a memory term's time constant).
    pub extra_params: Vec<usize>,
    /// For a gyro scale-factor term, the range (largest minus smallest) of its regressor over
    /// the windows: the scale factor it implies varies by its coefficient times this, which
    /// must stay within [`crate::fit::MAX_GYRO_SCALE_FACTOR`] (the constant of its kind is its
    /// parent and takes the rest); 0 for other terms.
    pub sf_regressor_range: Vec<f64>,
}

fn whiten(col: &[f64], d: &ChannelData, w: Option<&[f64]>) -> Vec<f64> {
    (0..col.len())
        .map(|r| col[r] / d.v[r].sqrt() * w.map_or(1.0, |w| w[r].sqrt()))
        .collect()
}

/// A term the selection kept (or the best one it tried and the gate refused).
#[derive(Clone, Debug)]
pub struct Pick {
    /// Index of the term in the library.
    pub term: usize,
    /// Its error-reduction ratio: the share of the residual energy (after the catalogue's
    /// accepted effects, the terms before it and its parents) its orthogonal part explains.
    pub err: f64,
    /// The parents it brought (library indices), fitted with it.
    pub parents: Vec<usize>,
    /// The nested test on top of the model before it and its parents; its coefficient is
    /// the last; ΔBIC counts a time constant as a parameter.
    pub test: NestedTest,
    /// Whether it passed the gate.
    pub passes: bool,
    /// The design of the test: the model before it, its parents, and it last.
    pub design: Design,
}

/// Forward selection on one channel: at most `max_terms` library terms of `lib` on top of the
/// design `base` (the catalogue's accepted effects), each with its parents (which enter the
/// model with it). A refused candidate that brought library parents (a block) does not end the
/// search: it is dropped and the next best is tried, at most [`MAX_REFUSED_BLOCKS`] times a
/// step; a refused term without library parents (or one block too many) ends it. Returns the
/// kept terms in order and, if the search ended on a refusal, the first term the gate refused
/// in that last step.
pub fn select(
    d: &ChannelData,
    base: &Design,
    lib: &Candidates,
    gate: &Gate,
    max_terms: usize,
) -> (Vec<Pick>, Option<Pick>) {
    let basew: Vec<Vec<f64>> = (0..base.ncols())
        .map(|c| whiten(base.column(c).as_slice(), d, None))
        .collect();
    let candw: Vec<Vec<f64>> = lib.cols.iter().map(|c| whiten(c, d, None)).collect();
    let mut o = Ortho::new(whiten(&d.y, d, None), &basew, candw);
    let Some(mut fit0) = wls(base, d, None) else {
        return (Vec::new(), None);
    };
    let mut x = base.clone();
    let mut kept: Vec<Pick> = Vec::new();
    let mut tried: Vec<usize> = Vec::new();
    let mut taken: Vec<usize> = Vec::new();
    let ln_n = (d.y.len() as f64).ln();
    // The refusals of this step: the first refused, and how many blocks were passed over.
    let mut miss: Option<Pick> = None;
    let mut refused_blocks = 0;
    while kept.len() < max_terms {
        let Some((j, err, parents)) = o.best(&tried, &taken, lib) else {
            break;
        };
        tried.push(j);
        // The parents first: the child is tested on top of them.
        let mut xp = x.clone();
        for &p in &parents {
            xp = append(&xp, &lib.cols[p], lib.units[p]);
        }
        let fit_p = if parents.is_empty() {
            fit0.clone()
        } else {
            match wls(&xp, d, None) {
                Some(f) => f,
                None => continue,
            }
        };
        let x1 = append(&xp, &lib.cols[j], lib.units[j]);
        let Some(mut test) = nested_test(&fit_p, xp.ncols(), &x1, d) else {
            // Not identifiable on top of the model: the next best.
            continue;
        };
        test.delta_bic += lib.extra_params[j] as f64 * ln_n;
        // The term last, its parents before it.
        let theta = &test.fit.theta;
        let implausible = parents
            .iter()
            .chain(std::iter::once(&j))
            .zip(theta.len() - parents.len() - 1..)
            .any(|(&k, i)| {
                theta[i].abs() * lib.sf_regressor_range[k] > crate::fit::MAX_GYRO_SCALE_FACTOR
            });
        if implausible {
            // An implausible scale factor (the term's, or a parent's it brings): a bias in
            // disguise; the next best.
            continue;
        }
        // The block (parents and term) must improve the model too: parents that explain
        // nothing must not ride in on a term that only passes on top of them.
        let block_ok = parents.is_empty()
            || wls(&x1, d, None).is_some_and(|f| {
                let k = f.identified_in(x.ncols()..x1.ncols()) as f64 + lib.extra_params[j] as f64;
                let s2 = f.chi2_red().max(1.0);
                -(fit0.chi2 - f.chi2) / s2 + k * ln_n < gate.max_delta_bic
            });
        let passes = block_ok && gate.passes_test(test.delta_bic, test.p_value, test.cv_gain_pct);
        let pick = Pick {
            term: j,
            err,
            parents,
            test,
            passes,
            design: x1.clone(),
        };
        if !passes {
            let block = pick.parents.iter().any(|&p| lib.selectable[p]);
            miss.get_or_insert(pick);
            if block && refused_blocks < MAX_REFUSED_BLOCKS {
                // A block refused (its parents may carry the signal on their own, or the
                // term below it is the right one): the next best.
                refused_blocks += 1;
                continue;
            }
            return (kept, miss);
        }
        miss = None;
        refused_blocks = 0;
        for &p in &pick.parents {
            o.take(p);
            taken.push(p);
        }
        o.take(j);
        taken.push(j);
        fit0 = pick.test.fit.clone();
        x = x1;
        kept.push(pick);
    }
    (kept, miss)
}

/// `x` with the column `col` (file unit `unit`) appended.
pub fn append(x: &Design, col: &[f64], unit: f64) -> Design {
    let (n, p) = (x.nrows(), x.ncols());
    let m = DMatrix::from_fn(n, p + 1, |r, c| if c < p { x[(r, c)] } else { col[r] });
    let mut u = x.unit.clone();
    u.push(unit);
    Design { x: m, unit: u }
}

/// Selection frequency of each of `picked` (library indices) over [`RESAMPLES`] bootstrap
/// resamples of the cross-validation units (runs, or blocks with fewer than three runs): in
/// each resample the orthogonal selection takes `picked.len()` terms (each with its parents)
/// on top of `base`, and a term counts when it is among them.
pub fn bootstrap(d: &ChannelData, base: &Design, lib: &Candidates, picked: &[usize]) -> Vec<f64> {
    if picked.is_empty() || d.folds == 0 {
        return Vec::new();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(BOOTSTRAP_SEED);
    rng.set_stream(BOOTSTRAP_STREAM);
    // Draw every resample first (sequentially, so the result does not depend on threads).
    let draws: Vec<Vec<f64>> = (0..RESAMPLES)
        .map(|_| {
            let mut count = vec![0.0; d.folds];
            for _ in 0..d.folds {
                count[(rng.next_u64() % d.folds as u64) as usize] += 1.0;
            }
            count
        })
        .collect();
    let hits: Vec<Vec<bool>> = draws
        .iter()
        .map(|count| {
            let w: Vec<f64> = d.fold.iter().map(|&f| count[f]).collect();
            let basew: Vec<Vec<f64>> = (0..base.ncols())
                .map(|c| whiten(base.column(c).as_slice(), d, Some(&w)))
                .collect();
            let candw: Vec<Vec<f64>> = lib.cols.iter().map(|c| whiten(c, d, Some(&w))).collect();
            let mut o = Ortho::new(whiten(&d.y, d, Some(&w)), &basew, candw);
            let mut chosen = Vec::new();
            let mut taken = Vec::new();
            while chosen.len() < picked.len() {
                let Some((j, _, parents)) = o.best(&chosen, &taken, lib) else {
                    break;
                };
                for p in parents {
                    o.take(p);
                    taken.push(p);
                }
                o.take(j);
                taken.push(j);
                chosen.push(j);
            }
            picked.iter().map(|p| chosen.contains(p)).collect()
        })
        .collect();
    (0..picked.len())
        .map(|i| hits.iter().filter(|h| h[i]).count() as f64 / RESAMPLES as f64)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_distr::{Distribution, StandardNormal};

    /// Windows of the synthetic channel.
    const N: usize = 200;
    /// Cross-validation folds (windows interleaved).
    const FOLDS: usize = 5;

    /// Column `k` of an orthogonal set over the windows: cos(2π·k·r/N), norm² N/2 (k < N/2).
    fn wave(k: usize) -> Vec<f64> {
        (0..N)
            .map(|r| (2.0 * std::f64::consts::PI * (k * r) as f64 / N as f64).cos())
            .collect()
    }

    /// A channel of unit noise variance whose sums are `signal` plus unit Gaussian noise
    /// (fixed seed).
    fn channel(signal: &[(f64, &[f64])]) -> ChannelData {
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let y = (0..N)
            .map(|r| {
                let noise: f64 = StandardNormal.sample(&mut rng);
                signal.iter().map(|(a, c)| a * c[r]).sum::<f64>() + noise
            })
            .collect();
        ChannelData {
            channel: 0,
            y,
            v: vec![1.0; N],
            dur: vec![1.0; N],
            fold: (0..N).map(|r| r % FOLDS).collect(),
            folds: FOLDS,
        }
    }

    /// The discovery gate (ΔBIC < −10, p below 0.05 over the candidates, a positive
    /// cross-validated gain).
    fn gate(tests: usize) -> Gate {
        Gate {
            max_delta_bic: -10.0,
            alpha: 0.05,
            tests,
            min_cv_gain_pct: 0.0,
        }
    }

    /// A library of `cols`, each of complexity `complexity[i]`, with `parents[i]`, all
    /// selectable, no time constants and no scale-factor bound.
    fn library(cols: Vec<Vec<f64>>, complexity: Vec<u8>, parents: Vec<Vec<usize>>) -> Candidates {
        let k = cols.len();
        Candidates {
            cols,
            units: vec![1.0; k],
            complexity,
            parents,
            selectable: vec![true; k],
            extra_params: vec![0; k],
            sf_regressor_range: vec![0.0; k],
        }
    }

    fn empty_base() -> Design {
        Design {
            x: DMatrix::zeros(N, 0),
            unit: Vec::new(),
        }
    }

    /// A block that ranks first on its parent's signal and is refused (the term adds ~50 χ² to
    /// its parent, which ranks it above the parent alone, but on top of the parent, with the
    /// third term still unexplained, its ΔBIC is positive) is passed over: the parent alone,
    /// then the third term, are kept.
    #[test]
    fn a_refused_block_with_selectable_parents_passes_to_the_next_best() {
        let (p, t, c) = (wave(3), wave(7), wave(11));
        // χ² of each (norm² N/2 = 100): parent 10 000, term 50, third 2000.
        let d = channel(&[(10.0, &p), (0.5f64 * 2f64.sqrt(), &t), (20f64.sqrt(), &c)]);
        let lib = library(vec![p, t, c], vec![0, 1, 0], vec![vec![], vec![0], vec![]]);
        let (kept, miss) = select(&d, &empty_base(), &lib, &gate(3), 3);
        let terms: Vec<usize> = kept.iter().map(|k| k.term).collect();
        assert_eq!(
            terms,
            [0, 2],
            "kept {terms:?}, miss {:?}",
            miss.map(|m| m.term)
        );
        assert!(kept.iter().all(|k| k.parents.is_empty() && k.passes));
        assert!(miss.is_none(), "the search ended on no refusal");
        // The block was the first choice (and refused, as nothing it brought was kept).
        let o = Ortho::new(
            whiten(&d.y, &d, None),
            &[],
            lib.cols.iter().map(|c| whiten(c, &d, None)).collect(),
        );
        let (first, _, parents) = o.best(&[], &[], &lib).unwrap();
        assert_eq!((first, parents), (1, vec![0]));
    }

    /// A refused term without library parents ends the search, even though a term below it
    /// would pass: its signal lies in one cross-validation fold only (its column in all of
    /// them), so it ranks first but predicts wrongly on the other folds.
    #[test]
    fn a_refused_single_term_ends_the_search() {
        let w = wave(13);
        let in_one_fold: Vec<f64> = w
            .iter()
            .enumerate()
            .map(|(r, v)| if r % FOLDS == 0 { *v } else { 0.0 })
            .collect();
        let c = wave(11);
        let d = channel(&[(15.0, &in_one_fold), (2.0, &c)]);
        let one_fold = w;
        let lib = library(
            vec![one_fold.clone(), c.clone()],
            vec![0, 0],
            vec![vec![], vec![]],
        );
        let (kept, miss) = select(&d, &empty_base(), &lib, &gate(2), 2);
        assert!(
            kept.is_empty(),
            "kept {:?}",
            kept.iter().map(|k| k.term).collect::<Vec<_>>()
        );
        let miss = miss.expect("the refusal is reported");
        assert_eq!(miss.term, 0);
        assert!(!miss.passes && miss.parents.is_empty());
        assert!(
            miss.test.delta_bic < -10.0 && miss.test.cv_gain_pct <= 0.0,
            "{:?}",
            miss.test
        );
        // The second term passes on its own: the search ended on the refusal, not for want of
        // a candidate.
        let lib2 = library(vec![c.clone()], vec![0], vec![vec![]]);
        let (kept2, _) = select(&d, &empty_base(), &lib2, &gate(2), 2);
        assert_eq!(kept2.iter().map(|k| k.term).collect::<Vec<_>>(), [0]);
        // The same term as a block (with a selectable parent that explains nothing) is passed
        // over, and the search goes on to the second term.
        let zero_signal = wave(5);
        let lib3 = library(
            vec![one_fold, c, zero_signal],
            vec![1, 0, 0],
            vec![vec![2], vec![], vec![]],
        );
        let (kept3, _) = select(&d, &empty_base(), &lib3, &gate(3), 3);
        assert_eq!(kept3.first().map(|k| k.term), Some(1));
    }

    /// A term whose column lives in one fold only is judged by no fold (the fold that holds it
    /// out cannot determine it in training, the others hold out none of it): its CV gain is
    /// NaN, undecided, and ΔBIC and the F test keep it.
    #[test]
    fn a_term_no_fold_can_judge_is_decided_by_delta_bic() {
        let one_fold: Vec<f64> = (0..N)
            .map(|r| if r % FOLDS == 0 { 1.0 } else { 0.0 })
            .collect();
        let d = channel(&[(5.0, &one_fold)]);
        let lib = library(vec![one_fold], vec![0], vec![vec![]]);
        let (kept, _) = select(&d, &empty_base(), &lib, &gate(1), 1);
        assert_eq!(kept.iter().map(|k| k.term).collect::<Vec<_>>(), [0]);
        assert!(kept[0].test.cv_gain_pct.is_nan(), "{:?}", kept[0].test);
        assert!(kept[0].test.delta_bic < -10.0);
    }

    /// A block whose term implies a plausible scale factor but whose library parent does not
    /// (its coefficient times its regressor's range beyond 0.1 %) is passed over, and so is
    /// the parent alone: the third term is kept, the block never.
    #[test]
    fn a_block_whose_parent_implies_an_implausible_scale_factor_is_refused() {
        let (p, t, c) = (wave(3), wave(7), wave(11));
        // χ²: parent 10 000, term 2500, third 2500 (passes with the rest unexplained).
        let d = channel(&[(10.0, &p), (5.0, &t), (5.0, &c)]);
        let mut lib = library(vec![p, t, c], vec![0, 1, 0], vec![vec![], vec![0], vec![]]);
        // Parent: 10 × 2e-4 = 2e-3 > 1e-3; term: 5 × 1e-5 = 5e-5, well inside.
        lib.sf_regressor_range = vec![2e-4, 1e-5, 0.0];
        let (kept, _) = select(&d, &empty_base(), &lib, &gate(3), 3);
        let terms: Vec<usize> = kept.iter().map(|k| k.term).collect();
        assert_eq!(terms, [2], "kept {terms:?}");
        // Without the parent's bound the block is kept with its parent, first: the bound, not
        // the gate, refused it.
        lib.sf_regressor_range = vec![0.0, 1e-5, 0.0];
        let (kept, _) = select(&d, &empty_base(), &lib, &gate(3), 3);
        assert_eq!((kept[0].term, kept[0].parents.clone()), (1, vec![0]));
        let theta = &kept[0].test.fit.theta;
        assert!((theta[1] - 5.0).abs() < 0.5);
        assert!(theta[1].abs() * 1e-5 < crate::fit::MAX_GYRO_SCALE_FACTOR);
        assert!(theta[0].abs() * 2e-4 > crate::fit::MAX_GYRO_SCALE_FACTOR);
    }
}
