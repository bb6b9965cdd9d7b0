//! Discovery (`rins diagnose --discover`): what the catalogue lacks, searched in a library of
//! regressors built from the documented signals of declared effects ([`library`]), by sparse
//! orthogonal forward selection with the error-reduction ratio and the catalogue's gate
//! ([`frols`]), with a bootstrap over runs, a confusable list against the catalogue effects and
//! a ready `[[sensor.gyro.custom]]` block per proposal ([`propose`]).
//!
//! The search runs on each channel's remainder after the catalogue's accepted effects. The
//! proposals then enter the catalogue's ranking and forward selection as declared candidates
//! (`custom:NAME`), so a catalogue effect that only stood in for one is ranked below it,
//! reported confusable with it, and no longer accepted ([`Superseded`]).

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

pub mod frols;
pub mod library;
pub mod propose;
pub mod tau;

// The report types live with the other report types (crate::report), beneath everything that
// builds them; named here too, as what discovery returns.
pub use crate::report::discovery::{
    Dependent, DiscoveredTerm, DiscoveryReport, Identical, Proposal, Superseded, TauReport,
};

use rins_plant::PlantConfig;
use rins_plant::effects::CustomSpec;
use rins_plant::effects::custom::{Axis, CustomKind};

use crate::custom::CustomRef;
use crate::fit::{Gate, design};
use crate::prepare::Prepared;
use crate::replay::{CHANNELS, Effect, Group, Kinematics};
use crate::report::Confusable;
use crate::rows::Rows;
use crate::selection::Diagnosis;
use library::{Term, file_unit_si};

/// Terms kept per channel at most.
pub const MAX_TERMS: usize = 3;
/// Position indicators in the library at most (distinct static positions).
pub const MAX_POSITIONS: usize = 32;

/// Relative residual below which a library column is taken as a catalogue column up to scale:
/// far below any noise (whitened columns of 10⁻⁹ relative difference carry no information a
/// noise floor could resolve in ~10⁹ windows).
pub const IDENTICAL_REL: f64 = 1e-9;

/// Whether whitened column `a` is `b` up to scale: ‖a − (a·b/b·b) b‖ ≤ IDENTICAL_REL ‖a‖.
fn same_up_to_scale(a: &[f64], b: &[f64]) -> bool {
    let (ab, bb, aa) = a
        .iter()
        .zip(b)
        .fold((0.0, 0.0, 0.0), |(ab, bb, aa), (x, y)| {
            (ab + x * y, bb + y * y, aa + x * x)
        });
    if !(aa > 0.0 && bb > 0.0) {
        return false;
    }
    let k = ab / bb;
    let r2: f64 = a.iter().zip(b).map(|(x, y)| (x - k * y).powi(2)).sum();
    r2 <= IDENTICAL_REL * IDENTICAL_REL * aa
}

/// The weights (a, b) with ‖t − a·x − b·y‖ ≤ IDENTICAL_REL·‖t‖ (whitened columns), if any:
/// `t` lies in the plane of `x` and `y`, and neither alone is `t` up to scale.
fn in_span_of_two(t: &[f64], x: &[f64], y: &[f64]) -> Option<[f64; 2]> {
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    let (xx, yy, xy, tx, ty, tt) = (
        dot(x, x),
        dot(y, y),
        dot(x, y),
        dot(t, x),
        dot(t, y),
        dot(t, t),
    );
    let det = xx * yy - xy * xy;
    // x and y themselves (nearly) parallel: that is the pairwise case.
    if !(tt > 0.0) || !(det > 1e-12 * xx * yy) {
        return None;
    }
    let a = (tx * yy - ty * xy) / det;
    let b = (ty * xx - tx * xy) / det;
    let r2: f64 = t
        .iter()
        .zip(x.iter().zip(y))
        .map(|(ti, (xi, yi))| (ti - a * xi - b * yi).powi(2))
        .sum();
    (r2 <= IDENTICAL_REL * IDENTICAL_REL * tt && a != 0.0 && b != 0.0).then_some([a, b])
}

/// Whether a library term and a catalogue effect are the same function of the signals (a
/// gyro bias linear in one up component is the g-sensitivity's G·f/g₀ term; an accelerometer
/// scale factor on a constant, its scale factor; a bias on a constant, the bias).
fn identical_by_definition(term: &Term, effect: Effect) -> bool {
    use rins_plant::effects::custom::Signal;
    use rins_plant::effects::{AccelTerm, GyroTerm};
    let Term::Product { factors, kind } = term else {
        return false;
    };
    matches!(
        (factors.as_slice(), kind, effect),
        (
            [Signal::Up(_)],
            CustomKind::Bias,
            Effect::Gyro(GyroTerm::GSensitivity)
        ) | (
            [Signal::Up(_) | Signal::North(_) | Signal::East(_)],
            CustomKind::Bias,
            Effect::Gyro(GyroTerm::NavFieldBias)
        ) | (
            [Signal::Up(_)],
            CustomKind::Bias,
            Effect::Accel(AccelTerm::ScaleFactor | AccelTerm::Misalignment)
        )
    )
}

/// Whether `term` on gyro channel `c` is a bias ∝ X·w_i with w_i the channel's own body rate:
/// c·X·ω_i·Δt = c·X·Δθ_i, the scale factor ∝ X the library holds too (in other units), so it is
/// left out rather than searched twice under two names.
fn scale_factor_in_disguise(term: &Term, c: usize) -> bool {
    use rins_plant::effects::custom::signals::Signal;
    match term {
        Term::Product {
            factors,
            kind: CustomKind::Bias,
        } if c < 3 => {
            factors.len() == 2 && factors.iter().filter(|f| **f == Signal::Rate(c)).count() == 1
        }
        _ => false,
    }
}

/// A proposal with what augmentation needs.
pub(crate) struct Found {
    proposal: Proposal,
    term: Term,
    accel: bool,
    /// Per channel it was kept on: the column.
    columns: Vec<(usize, Vec<f64>)>,
}

/// The result of the search, before the proposals join the ranking.
pub(crate) struct Search {
    report: DiscoveryReport,
    found: Vec<Found>,
}

/// The report of a term's test: the pick's own (its coefficient the fit's last, `back` = 0) or
/// one of its parents' (`back` columns before the last).
fn tested(
    a: &Prepared,
    c: usize,
    term: &Term,
    col: &[f64],
    pick: &frols::Pick,
    freq: f64,
    back: usize,
) -> DiscoveredTerm {
    let accel = c >= 3;
    let unit = file_unit_si(term.kind(), accel);
    let i = pick.test.fit.theta.len() - 1 - back;
    let (th, se) = (pick.test.fit.theta[i], pick.test.fit.cov[(i, i)].sqrt());
    let identified = pick.test.fit.identified(i);
    let u = match (term.kind(), accel) {
        (CustomKind::Bias, false) => "deg/h",
        (CustomKind::Bias, true) => "ug",
        (CustomKind::ScaleFactor, _) => "ppm",
    };
    DiscoveredTerm {
        channel: CHANNELS[c].into(),
        term: term.describe(),
        regressor: term.regressor(),
        kind: match term.kind() {
            CustomKind::Bias => "bias".into(),
            CustomKind::ScaleFactor => "scale-factor".into(),
        },
        searched_on: String::new(),
        err: pick.err,
        delta_bic: pick.test.delta_bic,
        p_value: pick.test.p_value,
        cv_rmse_gain_pct: pick.test.cv_gain_pct,
        coefficient: if identified { th / unit } else { f64::NAN },
        ci95: if identified {
            [(th - 1.96 * se) / unit, (th + 1.96 * se) / unit]
        } else {
            [f64::NAN; 2]
        },
        unit: format!("{u} per {}", term.unit()),
        passes_gate: pick.passes,
        bootstrap_frequency: freq,
        confusable_with: if pick.passes {
            let groups: Vec<Group> = a
                .replay
                .groups
                .iter()
                .filter(|g| g.channel == c)
                .copied()
                .collect();
            propose::confusable(&a.replay.windows, &a.data[c], &groups, term, col, unit)
        } else {
            Vec::new()
        },
        tau: None,
        parent_of: None,
    }
}

/// A memory term kept on a channel, whose time constant is refined after the search.
struct Refine {
    /// Index into `kept`.
    kept: usize,
    /// Channel.
    channel: usize,
    /// The design of its test (it last).
    design: crate::fit::Design,
    /// The profile over the grid.
    grid: Vec<tau::ProfilePoint>,
}

/// The library columns of channel `c` as the selection reads them (library indices `idx` of
/// `terms`, their columns `cols`), with the catalogue constants and g-sensitivity a term's
/// heredity asks for appended as parents only (not selectable), leaving out parents the base
/// `base_groups` has already.
#[allow(clippy::too_many_arguments)]
fn candidates(
    a: &Prepared,
    mom: &library::Moments,
    c: usize,
    terms: &[Term],
    idx: &[usize],
    cols: &[Vec<f64>],
    base_groups: &[Group],
) -> frols::Candidates {
    use crate::heredity::{Parent, parents_of_regressor};
    let accel = c >= 3;
    let ws = &a.replay.windows;
    let mut lib = frols::Candidates {
        cols: cols.to_vec(),
        units: idx
            .iter()
            .map(|&t| file_unit_si(terms[t].kind(), accel))
            .collect(),
        complexity: idx.iter().map(|&t| terms[t].complexity()).collect(),
        parents: vec![Vec::new(); idx.len()],
        selectable: vec![true; idx.len()],
        extra_params: idx.iter().map(|&t| terms[t].extra_params()).collect(),
        sf_regressor_range: idx
            .iter()
            .map(|&t| match (&terms[t], accel) {
                (
                    Term::Product {
                        factors,
                        kind: CustomKind::ScaleFactor,
                    },
                    false,
                ) => {
                    let twin = Term::Product {
                        factors: factors.clone(),
                        kind: CustomKind::Bias,
                    };
                    let means: Vec<f64> = mom
                        .column(&twin, c, ws)
                        .iter()
                        .zip(ws)
                        .map(|(v, w)| v / w.duration_s.max(f64::MIN_POSITIVE))
                        .collect();
                    let hi = means.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    let lo = means.iter().copied().fold(f64::INFINITY, f64::min);
                    (hi - lo).max(0.0)
                }
                _ => 0.0,
            })
            .collect(),
    };
    // Catalogue groups appended as parents: effect → their column indices.
    let mut appended: Vec<(Effect, Vec<usize>)> = Vec::new();
    for j in 0..idx.len() {
        let term = &terms[idx[j]];
        let Some(reg) = term.regressor() else {
            continue;
        };
        let mut ps = Vec::new();
        for p in parents_of_regressor(accel, term.kind(), &reg) {
            match p {
                Parent::Effect(e) => {
                    if base_groups.iter().any(|g| g.effect == e) {
                        continue;
                    }
                    if let Some((_, cs)) = appended.iter().find(|(x, _)| *x == e) {
                        ps.extend(cs.iter().copied());
                        continue;
                    }
                    let Some(g) = a
                        .replay
                        .groups
                        .iter()
                        .find(|g| g.channel == c && g.effect == e)
                    else {
                        continue;
                    };
                    let x = design(ws, std::slice::from_ref(g));
                    let mut cs = Vec::new();
                    for k in 0..x.ncols() {
                        lib.cols.push(x.column(k).iter().copied().collect());
                        lib.units.push(x.unit[k]);
                        lib.complexity.push(0);
                        lib.parents.push(Vec::new());
                        lib.selectable.push(false);
                        lib.extra_params.push(0);
                        lib.sf_regressor_range.push(0.0);
                        cs.push(lib.cols.len() - 1);
                    }
                    ps.extend(cs.iter().copied());
                    appended.push((e, cs));
                }
                Parent::Declare {
                    kind, regressor, ..
                } => {
                    if let Some(k) = idx.iter().position(|&t| {
                        terms[t].kind() == kind
                            && terms[t].regressor().as_deref() == Some(&regressor)
                    }) {
                        ps.push(k);
                    }
                }
            }
        }
        lib.parents[j] = ps;
    }
    lib
}

/// Searches the library on each channel's remainder after `selected` (the catalogue's accepted
/// groups per channel).
pub(crate) fn search(
    model: &PlantConfig,
    rows: &(impl Rows + ?Sized),
    a: &Prepared,
    selected: &[Vec<Group>],
) -> Search {
    let ws = &a.replay.windows;
    let info = rows.info();
    let kin = Kinematics::new(model);
    let taus = library::tau_grid();
    let memory = library::memory_terms(&info, &taus);
    let mom = library::moments(&kin, rows, ws, &memory);
    let sig = library::library_signals(&info);
    let mut terms = library::product_terms(&sig);
    terms.extend(
        mom.positions(ws, MAX_POSITIONS)
            .into_iter()
            .map(|up| Term::Position { up }),
    );
    terms.extend(memory.iter().cloned());
    // A term a declared effect of the model already is: tested by the catalogue step.
    let declared: Vec<(bool, CustomKind, String)> = [false, true]
        .into_iter()
        .flat_map(|accel| {
            let list = if accel {
                &model.sensor.accel.custom
            } else {
                &model.sensor.gyro.custom
            };
            list.iter()
                .map(move |s| (accel, s.kind, s.regressor.replace(' ', "")))
        })
        .collect();
    let lib_for = |c: usize| -> Vec<usize> {
        (0..terms.len())
            .filter(|&t| {
                let r = terms[t].regressor();
                !declared.iter().any(|(acc, k, reg)| {
                    *acc == (c >= 3) && *k == terms[t].kind() && Some(reg) == r.as_ref()
                }) && !scale_factor_in_disguise(&terms[t], c)
            })
            .collect()
    };
    let per_channel: Vec<Vec<usize>> = (0..6).map(lib_for).collect();
    // Every term on every channel, searched on the remainder and on the model as given.
    let tests: usize = (0..6)
        .map(|c| per_channel[c].len() * if selected[c].is_empty() { 1 } else { 2 })
        .sum();
    let gate = Gate {
        max_delta_bic: -10.0,
        alpha: a.opts.alpha,
        tests,
        min_cv_gain_pct: 0.0,
    };
    let mut refused = Vec::new();
    let mut identical = Vec::new();
    let mut dependent = Vec::new();
    // (channel, term, column, test)
    let mut kept: Vec<(usize, Term, Vec<f64>, DiscoveredTerm)> = Vec::new();
    let mut refine: Vec<Refine> = Vec::new();
    for c in 0..6 {
        let idx = &per_channel[c];
        let all_cols: Vec<Vec<f64>> = idx.iter().map(|&t| mom.column(&terms[t], c, ws)).collect();
        // A term that is a catalogue column up to scale on this data is that catalogue effect,
        // not new physics: reported, and left to the catalogue step.
        let whiten = |v: &[f64]| -> Vec<f64> {
            v.iter()
                .zip(&a.data[c].v)
                .map(|(x, var)| x / var.sqrt())
                .collect()
        };
        let catalogue: Vec<(Effect, Vec<f64>)> = a
            .replay
            .groups
            .iter()
            .filter(|g| g.channel == c && !matches!(g.effect, Effect::Custom(_)))
            .flat_map(|g| {
                let x = design(ws, std::slice::from_ref(g));
                (0..x.ncols())
                    .map(|k| (g.effect, whiten(x.column(k).as_slice())))
                    .collect::<Vec<_>>()
            })
            .collect();
        // The coefficient key of each catalogue column, for the dependence report.
        let catalogue_keys: Vec<String> = a
            .replay
            .groups
            .iter()
            .filter(|g| g.channel == c && !matches!(g.effect, Effect::Custom(_)))
            .flat_map(|g| {
                let n = design(ws, std::slice::from_ref(g)).ncols();
                let keys = g.effect.coefficient_keys(c);
                (0..n)
                    .map(|k| {
                        keys.get(k).map_or_else(
                            || format!("{}[{k}]", g.effect.name()),
                            |(key, _)| key.clone(),
                        )
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut keep = Vec::new();
        for (j, col) in all_cols.iter().enumerate() {
            let wc = whiten(col);
            match catalogue.iter().find(|(_, cc)| same_up_to_scale(&wc, cc)) {
                Some((e, _)) => identical.push(Identical {
                    channel: CHANNELS[c].into(),
                    term: terms[idx[j]].describe(),
                    effect: e.name(),
                    by_definition: identical_by_definition(&terms[idx[j]], *e),
                }),
                None => keep.push(j),
            }
        }
        let idx: Vec<usize> = keep.iter().map(|&j| idx[j]).collect();
        let idx = &idx;
        let cols: Vec<Vec<f64>> = keep.iter().map(|&j| all_cols[j].clone()).collect();
        // On the catalogue's remainder, and on the residual of the model as given: a
        // catalogue effect accepted as a stand-in can leave too little of the remainder for
        // the term it stands in for; the ranking then decides between them.
        let bases: Vec<(&str, &[Group])> = if selected[c].is_empty() {
            vec![("model as given", &[])]
        } else {
            vec![
                ("remainder after the catalogue", &selected[c]),
                ("model as given", &[]),
            ]
        };
        for (on, groups) in bases {
            let base = design(ws, groups);
            let lib = candidates(a, &mom, c, &terms, idx, &cols, groups);
            let (picks, miss) = frols::select(&a.data[c], &base, &lib, &gate, MAX_TERMS);
            let chosen: Vec<usize> = picks.iter().map(|p| p.term).collect();
            let freq = frols::bootstrap(&a.data[c], &base, &lib, &chosen);
            for (k, p) in picks.iter().enumerate() {
                let t = idx[p.term];
                if kept
                    .iter()
                    .any(|(kc, kt, _, _)| *kc == c && *kt == terms[t])
                {
                    continue;
                }
                let mut dt = tested(a, c, &terms[t], &cols[p.term], p, freq[k], 0);
                dt.searched_on = on.into();
                if terms[t].tau_s().is_some() {
                    // The profile over the grid: the same family at every grid τ.
                    let family: Vec<(f64, Vec<f64>)> = idx
                        .iter()
                        .zip(&cols)
                        .filter(|(u, _)| terms[**u].same_family(&terms[t]))
                        .map(|(u, col)| (terms[*u].tau_s().unwrap_or(f64::NAN), col.clone()))
                        .collect();
                    let grid = tau::profile(
                        &p.design,
                        &a.data[c],
                        &family.iter().map(|(t, _)| *t).collect::<Vec<_>>(),
                        &family
                            .iter()
                            .map(|(_, col)| col.clone())
                            .collect::<Vec<_>>(),
                    );
                    refine.push(Refine {
                        kept: kept.len(),
                        channel: c,
                        design: p.design.clone(),
                        grid,
                    });
                }
                let child = terms[t].describe();
                kept.push((c, terms[t].clone(), cols[p.term].clone(), dt));
                // Its parents from the library enter with it (the catalogue's are the ranking's).
                for (pos, &par) in p.parents.iter().enumerate() {
                    if par >= idx.len() {
                        continue;
                    }
                    let pt = &terms[idx[par]];
                    if kept.iter().any(|(kc, kt, _, _)| *kc == c && kt == pt) {
                        continue;
                    }
                    let back = p.parents.len() - pos;
                    let mut pd = tested(a, c, pt, &cols[par], p, f64::NAN, back);
                    pd.searched_on = on.into();
                    pd.parent_of = Some(child.clone());
                    kept.push((c, pt.clone(), cols[par].clone(), pd));
                }
            }
            if let Some(p) = miss
                && !refused
                    .iter()
                    .any(|r: &DiscoveredTerm| r.channel == CHANNELS[c])
                && picks.is_empty()
            {
                let mut dt = tested(a, c, &terms[idx[p.term]], &cols[p.term], &p, f64::NAN, 0);
                dt.searched_on = on.into();
                refused.push(dt);
            }
        }
        // A kept term in the plane of two other columns (kept terms or catalogue columns).
        let mine: Vec<(String, Vec<f64>)> = kept
            .iter()
            .filter(|(kc, _, _, _)| *kc == c)
            .map(|(_, t, col, _)| (t.describe(), whiten(col)))
            .collect();
        let others: Vec<(String, &[f64])> = mine
            .iter()
            .map(|(n, v)| (n.clone(), v.as_slice()))
            .chain(
                catalogue_keys
                    .iter()
                    .zip(&catalogue)
                    .map(|(k, (_, v))| (k.clone(), v.as_slice())),
            )
            .collect();
        for (name, col) in &mine {
            'found: for i in 0..others.len() {
                for j in i + 1..others.len() {
                    if &others[i].0 == name || &others[j].0 == name {
                        continue;
                    }
                    if let Some(w) = in_span_of_two(col, others[i].1, others[j].1) {
                        dependent.push(Dependent {
                            channel: CHANNELS[c].into(),
                            term: name.clone(),
                            on: [others[i].0.clone(), others[j].0.clone()],
                            weights: w,
                        });
                        break 'found;
                    }
                }
            }
        }
    }
    refine_taus(&kin, rows, a, &taus, &mut kept, &refine);
    // Group the kept terms into proposals: one per term and sensor, on every axis it was kept on.
    let mut found: Vec<Found> = Vec::new();
    for (c, t, col, dt) in kept {
        let accel = c >= 3;
        let f = match found
            .iter_mut()
            .position(|f| f.accel == accel && f.term == t)
        {
            Some(i) => &mut found[i],
            None => {
                found.push(Found {
                    proposal: Proposal {
                        name: t.name(),
                        sensor: if accel { "accel" } else { "gyro" }.into(),
                        terms: Vec::new(),
                        coef: [0.0; 3],
                        toml: None,
                    },
                    term: t.clone(),
                    accel,
                    columns: Vec::new(),
                });
                found.last_mut().expect("pushed")
            }
        };
        f.proposal.coef[c % 3] = if dt.coefficient.is_finite() {
            dt.coefficient
        } else {
            0.0
        };
        f.proposal.terms.push(dt);
        f.columns.push((c, col));
    }
    for f in &mut found {
        let ci: Vec<(usize, [f64; 2])> = f
            .columns
            .iter()
            .zip(&f.proposal.terms)
            .map(|((c, _), t)| (c % 3, t.ci95))
            .collect();
        f.proposal.toml =
            propose::toml_block(&f.proposal.name, f.accel, &f.term, f.proposal.coef, &ci);
    }
    found.sort_by(|x, y| {
        let best = |f: &Found| {
            f.proposal
                .terms
                .iter()
                .map(|t| t.delta_bic)
                .fold(f64::INFINITY, f64::min)
        };
        best(x).total_cmp(&best(y))
    });
    Search {
        report: DiscoveryReport {
            library_terms: (0..6)
                .map(|c| (CHANNELS[c].to_string(), per_channel[c].len()))
                .collect(),
            tests,
            bootstrap_resamples: frols::RESAMPLES,
            proposals: found.iter().map(|f| f.proposal.clone()).collect(),
            refused,
            superseded: Vec::new(),
            identical,
            dependent,
        },
        found,
    }
}

/// Refines the time constant of each kept memory term (`refine`) by profile likelihood
/// ([`tau`]): two more passes over the rows, shared by every term (the points around each grid
/// pick, then each estimate with its derivative), after which each such term in `kept` is
/// the term at its estimate, with its column, coefficient and intervals.
fn refine_taus(
    kin: &Kinematics,
    rows: &(impl Rows + ?Sized),
    a: &Prepared,
    taus: &[f64],
    kept: &mut [(usize, Term, Vec<f64>, DiscoveredTerm)],
    refine: &[Refine],
) {
    if refine.is_empty() {
        return;
    }
    let ws = &a.replay.windows;
    let ratio = taus[1] / taus[0];
    // Pass 1: the points around each pick.
    let mut fine_terms: Vec<Term> = Vec::new();
    let mut fine_of: Vec<Vec<(f64, usize)>> = Vec::new();
    for r in refine {
        let t = &kept[r.kept].1;
        let mut v = Vec::new();
        let (lo, hi) = (taus[0], taus[taus.len() - 1]);
        for tau_s in tau::fine_around(t.tau_s().unwrap_or(60.0), ratio)
            .into_iter()
            .filter(|t| (lo..=hi).contains(t))
        {
            let ft = t.with_tau(tau_s);
            let k = fine_terms.iter().position(|x| *x == ft).unwrap_or_else(|| {
                fine_terms.push(ft);
                fine_terms.len() - 1
            });
            v.push((tau_s, k));
        }
        fine_of.push(v);
    }
    let mom = library::moments(kin, rows, ws, &fine_terms);
    // (estimate, grid pick, the coefficient's envelope over the τ interval).
    let mut estimates: Vec<Option<(tau::TauEstimate, f64, Option<[f64; 2]>)>> = Vec::new();
    for (r, fine) in refine.iter().zip(&fine_of) {
        let cols: Vec<Vec<f64>> = fine
            .iter()
            .map(|(_, k)| mom.column(&fine_terms[*k], r.channel, ws))
            .collect();
        let taus_fine: Vec<f64> = fine.iter().map(|(t, _)| *t).collect();
        let mut pts = r.grid.clone();
        pts.extend(tau::profile(
            &r.design,
            &a.data[r.channel],
            &taus_fine,
            &cols,
        ));
        let d = &a.data[r.channel];
        let min = pts.iter().map(|p| p.chi2).fold(f64::INFINITY, f64::min);
        let dof = d.y.len().saturating_sub(r.design.ncols() + 1).max(1) as f64;
        let s2 = (min / dof).max(1.0);
        let pairs: Vec<(f64, f64)> = pts.iter().map(|p| (p.tau_s, p.chi2)).collect();
        estimates.push(tau::estimate(&pairs, s2).map(|e| {
            (
                e,
                kept[r.kept].1.tau_s().unwrap_or(f64::NAN),
                tau::envelope(&pts, e.chi2_bound),
            )
        }));
    }
    // Pass 2: each estimate (rounded to three digits) and ±0.1 % for the derivative.
    let mut final_terms: Vec<Term> = Vec::new();
    for (r, e) in refine.iter().zip(&estimates) {
        if let Some((e, _, _)) = e {
            let tau_s = tau::round3(e.tau_s);
            let t = &kept[r.kept].1;
            for f in [1.0, 1.001, 0.999] {
                let ft = t.with_tau(tau_s * f);
                if !final_terms.contains(&ft) {
                    final_terms.push(ft);
                }
            }
        }
    }
    let mom = library::moments(kin, rows, ws, &final_terms);
    for (r, e) in refine.iter().zip(estimates) {
        let Some((e, grid_tau_s, env)) = e else {
            continue;
        };
        let c = r.channel;
        let tau_s = tau::round3(e.tau_s);
        let (c0, cp, cm) = {
            let t = &kept[r.kept].1;
            (
                mom.column(&t.with_tau(tau_s), c, ws),
                mom.column(&t.with_tau(tau_s * 1.001), c, ws),
                mom.column(&t.with_tau(tau_s * 0.999), c, ws),
            )
        };
        let dcol: Vec<f64> = cp
            .iter()
            .zip(&cm)
            .map(|(p, m)| (p - m) / (0.002 * tau_s))
            .collect();
        let mut x = r.design.clone();
        let last = x.ncols() - 1;
        for (i, v) in c0.iter().enumerate() {
            x.x[(i, last)] = *v;
        }
        let (term, _, dt) = {
            let k = &mut kept[r.kept];
            k.1 = k.1.with_tau(tau_s);
            k.2 = c0.clone();
            (&k.1, (), &mut k.3)
        };
        let unit = file_unit_si(term.kind(), c >= 3);
        let mut widening = 1.0;
        if let Some((coef, se, wide)) = tau::coefficient_with_tau(&x, &a.data[c], &dcol) {
            dt.coefficient = coef / unit;
            // The linearised interval, and the envelope of the intervals over the time
            // constants the data allow when that is wider (τ left open: the amplitude follows
            // it far from the estimate, where the linearisation does not reach).
            let (mut lo, mut hi) = (coef - 1.96 * se, coef + 1.96 * se);
            if let Some([a, b]) = env {
                lo = lo.min(a);
                hi = hi.max(b);
            }
            dt.ci95 = [lo / unit, hi / unit];
            let fixed = se / wide;
            widening = ((hi - coef).max(coef - lo) / (1.96 * fixed)).max(1.0);
        }
        dt.term = term.describe();
        dt.regressor = term.regressor();
        dt.tau = Some(TauReport {
            tau_s,
            ci95_s: e.ci95_s,
            open: e.open,
            grid_tau_s,
            coefficient_widening: widening,
            coefficient_ci95: dt.ci95,
        });
    }
}

/// The declared-effect reference a proposal would have in `model` (declared after the model's
/// own effects of its sensor, in proposal order), or `None` for an indicator.
fn reference(model: &PlantConfig, found: &[Found], i: usize) -> Option<CustomRef> {
    let f = &found[i];
    f.proposal.toml.as_ref()?;
    let own = if f.accel {
        model.sensor.accel.custom.len()
    } else {
        model.sensor.gyro.custom.len()
    };
    let before = found[..i]
        .iter()
        .filter(|g| g.accel == f.accel && g.proposal.toml.is_some())
        .count();
    let axes = f.columns.iter().fold(0u8, |m, (c, _)| m | 1 << (c % 3));
    Some(CustomRef::new(
        f.accel,
        (own + before) as u16,
        f.term.kind(),
        axes,
        &f.proposal.name,
    ))
}

impl Search {
    /// The report as searched (nothing joined the ranking).
    pub(crate) fn into_report(self) -> DiscoveryReport {
        self.report
    }

    /// Adds the declarable proposals to `a` as candidates of the catalogue's ranking (groups
    /// and window regressor sums), returning whether any was added.
    pub(crate) fn augment(&self, model: &PlantConfig, a: &mut Prepared) -> bool {
        let mut any = false;
        for i in 0..self.found.len() {
            let Some(r) = reference(model, &self.found, i) else {
                continue;
            };
            if let Some(reg) = self.found[i].term.regressor() {
                a.declared.push(crate::prepare::DeclaredCandidate {
                    accel: r.accel,
                    index: r.index,
                    kind: r.kind,
                    regressor: reg.replace(' ', ""),
                });
            }
            for (c, col) in &self.found[i].columns {
                let offset = a.replay.windows.first().map_or(0, |w| w.x.len());
                for (w, v) in a.replay.windows.iter_mut().zip(col) {
                    w.x.push(*v);
                }
                a.replay.groups.push(Group {
                    channel: *c,
                    effect: Effect::Custom(r),
                    offset,
                    len: 1,
                });
                any = true;
            }
        }
        any
    }

    /// The report, with the catalogue effects `before` (accepted on the catalogue alone) that
    /// the diagnosis with the proposals `after` no longer accepts: each is named superseded, and
    /// reported confusable with the discovered term in `after`'s ranking.
    pub(crate) fn finish(mut self, before: &Diagnosis, after: &mut Diagnosis) -> DiscoveryReport {
        let disc: Vec<String> = self
            .report
            .proposals
            .iter()
            .map(|p| format!("custom:{}", p.name))
            .collect();
        for c in 0..6 {
            let by = after.selected[c]
                .iter()
                .map(|g| g.effect.name())
                .find(|n| disc.contains(n));
            let Some(by) = by else { continue };
            for g in &before.selected[c] {
                if after.selected[c].iter().any(|s| s.effect == g.effect) {
                    continue;
                }
                let name = g.effect.name();
                let dbic = |n: &str| {
                    after
                        .report
                        .ranking
                        .iter()
                        .find(|r| r.effect == n && r.channel == CHANNELS[c])
                        .map_or(f64::NAN, |r| r.delta_bic)
                };
                let (de, db) = (dbic(&name), dbic(&by));
                if let Some(r) = after
                    .report
                    .ranking
                    .iter_mut()
                    .find(|r| r.effect == name && r.channel == CHANNELS[c])
                    && !r.confusable_with.iter().any(|x| x.effect.starts_with(&by))
                {
                    let term =
                        &self.found[disc.iter().position(|d| *d == by).expect("listed")].term;
                    r.confusable_with.push(Confusable {
                        effect: by.clone(),
                        delta_bic_gap: db - de,
                        correlation: f64::NAN,
                        vif: f64::NAN,
                        separate_by: propose::separating(term, &name),
                    });
                }
                self.report.superseded.push(Superseded {
                    channel: CHANNELS[c].into(),
                    effect: name,
                    by: by.clone(),
                    delta_bic_effect: de,
                    delta_bic_by: db,
                });
            }
        }
        self.report
    }
}

/// `model` with the proposal `name` declared after its own declared effects, with a zero
/// coefficient on the axes it was found on: the model `--apply custom:NAME` fits.
pub fn with_proposal(
    model: &PlantConfig,
    report: &DiscoveryReport,
    name: &str,
) -> Result<PlantConfig, String> {
    let p = report
        .proposals
        .iter()
        .find(|p| p.name == name)
        .ok_or_else(|| {
            let names: Vec<&str> = report.proposals.iter().map(|p| p.name.as_str()).collect();
            format!("custom:{name} is neither declared in the model nor discovered; discovered: {names:?}")
        })?;
    let Some(t) = p.terms.first() else {
        return Err(format!("custom:{name} was found on no channel"));
    };
    let Some(regressor) = &t.regressor else {
        return Err(format!(
            "custom:{name} is a position indicator, which a declared effect cannot express"
        ));
    };
    let mut m = model.clone();
    let spec = CustomSpec {
        name: p.name.clone(),
        enabled: true,
        kind: if t.kind == "bias" {
            CustomKind::Bias
        } else {
            CustomKind::ScaleFactor
        },
        regressor: regressor.clone(),
        unit: t.unit.split(" per ").nth(1).unwrap_or("1").to_string(),
        axes: p
            .terms
            .iter()
            .map(|t| Axis::of(CHANNELS.iter().position(|c| *c == t.channel).unwrap_or(0) % 3))
            .collect(),
        coef: [0.0; 3],
    };
    if p.sensor == "accel" {
        m.sensor.accel.custom.push(spec);
    } else {
        m.sensor.gyro.custom.push(spec);
    }
    Ok(m)
}
