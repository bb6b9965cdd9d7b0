//! Iterating to the floor (`rins diagnose --iterate`): compare → rank (catalogue, declared,
//! discovered) → joint fit of the accepted set with its parents → compare, step after step,
//! until every channel is at its noise floor with no flagged cell, or nothing more passes the
//! gate (then what stays unexplained, and where).
//!
//! Each accepted term must also survive the joint fit (the nested test of the full set against
//! the set without it passes the gate) and resampling of the runs (its coefficient keeps its
//! sign and stays beyond 2 σ in [`STABILITY`] of the resamples), so a term found only on the
//! remainder a stand-in left does not pass. Coefficients are written only when the data
//! determine them ([`crate::apply::MIN_WRITE_Z`]).

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rins_plant::PlantConfig;
use serde::Serialize;

use crate::apply::{Coefficient, apply_groups};
use crate::fit::{ChannelData, Gate, design, nested_test, wls};
use crate::heredity::{Parent, declare, parents};
use crate::prepare::{Prepared, prepare};
use crate::replay::{CHANNELS, Effect, Group};
use crate::report::{Cell, CompareReport, unit_of};
use crate::rows::Rows;
use crate::{Analysis, Options, analyse, swap};

/// Seed of the run resampling of the joint-fit check.
pub const RESAMPLE_SEED: u64 = 0x17E2_A7E5;
/// The resampling's named stream of that seed.
pub const RESAMPLE_STREAM: u64 = 0x5AB1_E000;
/// Resamples of the runs (or of the 5 blocks with fewer than 3 runs).
pub const RESAMPLES: usize = 100;
/// Share of resamples in which a term's coefficient must keep its sign beyond 2 σ (checked with
/// three runs or more).
pub const STABILITY: f64 = 0.9;

/// How far to iterate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterateOptions {
    /// Steps (joint fits) at most.
    pub max_steps: usize,
    /// A channel is at its floor when its residual RMS is at most this times the floor.
    pub floor_ratio: f64,
}

impl Default for IterateOptions {
    fn default() -> Self {
        Self {
            max_steps: 6,
            floor_ratio: 1.1,
        }
    }
}

/// A channel's residual against its noise floor.
#[derive(Clone, Debug, Serialize)]
pub struct Level {
    /// Channel.
    pub channel: String,
    /// Display unit (°/h or µg).
    pub unit: String,
    /// Residual RMS.
    pub residual_rms: f64,
    /// Noise floor RMS.
    pub noise_floor_rms: f64,
    /// Residual / floor.
    pub ratio: f64,
}

/// A term accepted at a step.
#[derive(Clone, Debug, Serialize)]
pub struct AcceptedTerm {
    /// Channel.
    pub channel: String,
    /// Effect (`gyro.position_bias`, `custom:NAME`).
    pub effect: String,
    /// How it was found: `catalogue`, `declared` (in the model) or `discovered`.
    pub found_by: String,
    /// The term it replaced in the replacement pass ([`crate::swap`]), if it came in that
    /// way; `delta_bic` is then the swap's gain in joint-fit BIC (negative).
    pub replaces: Option<String>,
    /// ΔBIC when it was accepted.
    pub delta_bic: f64,
    /// Parents fitted with it.
    pub parents: Vec<String>,
    /// ΔBIC of removing it from the joint fit (positive: it is needed).
    pub joint_delta_bic: f64,
    /// Share of run resamples in which its coefficient keeps its sign beyond 2 σ.
    pub stability: f64,
    /// Survived the joint fit and the resampling (else dropped).
    pub kept: bool,
    /// A discovered memory term's time constant with its 95 % interval (`--discover`'s
    /// profile likelihood), fixed at the estimate in the model written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau: Option<crate::discover::TauReport>,
    /// Effects the diagnosis found nearly as good an explanation on this data (its confusable
    /// list: |ρ| > 0.9 of the fitted contributions, ΔBIC within 10), each a candidate the data
    /// cannot tell from this term; empty when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub confusable_with: Vec<String>,
}

/// One step of the iteration: the model entering it against the data, and what was fitted.
#[derive(Clone, Debug, Serialize)]
pub struct Step {
    /// Step number (0: the model as given).
    pub step: usize,
    /// Per channel, residual against floor of the model entering the step.
    pub levels: Vec<Level>,
    /// Cells flagged for that model.
    pub flagged_cells: usize,
    /// Terms accepted by the gate at this step, with the joint-fit check.
    pub accepted: Vec<AcceptedTerm>,
    /// Every coefficient of the joint fit: written, kept or null, with the reason.
    pub coefficients: Vec<Coefficient>,
}

/// The whole iteration.
#[derive(Clone, Debug, Serialize)]
pub struct IterationReport {
    /// Where the data came from.
    pub source: String,
    /// The steps; the last one's levels are the final model's.
    pub steps: Vec<Step>,
    /// Every channel reached its floor with no flagged cell.
    pub reached_floor: bool,
    /// Why it stopped.
    pub stop: String,
    /// What stays unexplained, and where (empty at the floor).
    pub unexplained: Vec<String>,
    /// The flagged cells of the model as given and of the final model.
    pub cells_before: Vec<Cell>,
    /// The final model's cells (all, for the map).
    pub cells_after: Vec<Cell>,
    /// |z| beyond which a cell is flagged.
    pub z_critical: f64,
    /// When the search stopped: the candidates of the last step that came closest to the gate
    /// without passing it (catalogue, declared and discovered, lowest ΔBIC first), with the
    /// criterion each failed: what was tried when "nothing more passes the gate".
    pub closest_to_gate: Vec<NearMiss>,
}

/// A candidate tried at the last step that did not pass the gate.
#[derive(Clone, Debug, Serialize)]
pub struct NearMiss {
    /// Channel.
    pub channel: String,
    /// Effect (`gyro.temperature_bias`, `custom:NAME`) or a discovery term (`bias ∝ …`).
    pub effect: String,
    /// ΔBIC on the model entering the step.
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated gain, %.
    pub cv_rmse_gain_pct: f64,
    /// What it failed: `ΔBIC ≥ −10`, `p ≥ α/tests`, `CV gain ≤ 0`.
    pub failed: String,
}

/// Near misses shown when the search stops.
pub const NEAR_MISSES: usize = 5;

/// The candidates of `an`'s diagnosis closest to the gate without passing it.
fn near_misses(an: &Analysis) -> Vec<NearMiss> {
    let Some(d) = an.diagnosis.as_ref() else {
        return Vec::new();
    };
    let r = &d.report;
    let failed = |dbic: f64, cv: f64, passes: bool| {
        let mut f = Vec::new();
        if !(dbic < -10.0) {
            f.push("ΔBIC ≥ −10");
        }
        if cv <= 0.0 {
            f.push("CV gain ≤ 0");
        }
        if f.is_empty() && !passes {
            f.push("p ≥ α/tests (Bonferroni)");
        }
        f.join(", ")
    };
    let mut out: Vec<NearMiss> = r
        .ranking
        .iter()
        .filter(|e| !e.passes_gate && e.delta_bic.is_finite())
        .map(|e| NearMiss {
            channel: e.channel.clone(),
            effect: e.effect.clone(),
            delta_bic: e.delta_bic,
            p_value: e.p_value,
            cv_rmse_gain_pct: e.cv_rmse_gain_pct,
            failed: failed(e.delta_bic, e.cv_rmse_gain_pct, e.passes_gate),
        })
        .chain(
            r.discovery
                .iter()
                .flat_map(|d| &d.refused)
                .map(|t| NearMiss {
                    channel: t.channel.clone(),
                    effect: t.term.clone(),
                    delta_bic: t.delta_bic,
                    p_value: t.p_value,
                    cv_rmse_gain_pct: t.cv_rmse_gain_pct,
                    failed: failed(t.delta_bic, t.cv_rmse_gain_pct, t.passes_gate),
                }),
        )
        .collect();
    out.sort_by(|a, b| a.delta_bic.total_cmp(&b.delta_bic));
    out.truncate(NEAR_MISSES);
    out
}

/// The iteration's result.
#[derive(Clone, Debug)]
pub struct Iteration {
    /// The report (steps, stop reason).
    pub report: IterationReport,
    /// The final model.
    pub model: PlantConfig,
    /// The analysis of the final model (a diagnosis with discovery).
    pub last: Analysis,
}

fn levels(r: &CompareReport) -> Vec<Level> {
    r.channels
        .iter()
        .enumerate()
        .map(|(c, s)| Level {
            channel: s.channel.clone(),
            unit: unit_of(c).0.into(),
            residual_rms: s.residual_rms,
            noise_floor_rms: s.noise_floor_rms,
            ratio: if s.noise_floor_rms > 0.0 {
                s.residual_rms / s.noise_floor_rms
            } else {
                f64::INFINITY
            },
        })
        .collect()
}

/// Share of run resamples in which coefficient `k` of the joint fit `x` keeps the sign of
/// `sign` and stays beyond 2 σ.
fn stability(x: &crate::fit::Design, d: &ChannelData, k: usize, sign: f64) -> f64 {
    if d.folds == 0 {
        return 0.0;
    }
    let Some(se_all) = wls(x, d, None)
        .filter(|f| f.identified(k))
        .map(|f| f.cov[(k, k)].sqrt())
    else {
        return 0.0;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(RESAMPLE_SEED);
    rng.set_stream(RESAMPLE_STREAM);
    let (mut hits, mut informative) = (0, 0);
    for _ in 0..RESAMPLES {
        let mut count = vec![0.0f64; d.folds];
        for _ in 0..d.folds {
            count[(rng.next_u64() % d.folds as u64) as usize] += 1.0;
        }
        // A unit drawn n times weighs n times: its windows' variances divided by n.
        let mut dr = d.clone();
        let mask: Vec<bool> = d.fold.iter().map(|&f| count[f] > 0.0).collect();
        for (r, &f) in d.fold.iter().enumerate() {
            if count[f] > 0.0 {
                dr.v[r] = d.v[r] / count[f];
            }
        }
        // A resample that leaves out what excites the term (its one tilted run, say) cannot
        // judge it: counted neither way (crate::fit::FOLD_SE_RATIO).
        if let Some(f) = wls(x, &dr, Some(&mask))
            && f.identified(k)
        {
            let (th, se) = (f.theta[k], f.cov[(k, k)].sqrt());
            if se > crate::fit::FOLD_SE_RATIO * se_all {
                continue;
            }
            informative += 1;
            if th * sign > 0.0 && th.abs() >= 2.0 * se {
                hits += 1;
            }
        }
    }
    // Too few informative resamples: the joint fit's test decides alone.
    if informative < RESAMPLES / 4 {
        return f64::NAN;
    }
    hits as f64 / informative as f64
}

/// The accepted groups of one channel (`terms`, with `parent` marking parents) checked in the
/// joint fit: each non-parent term must pass `gate` against the set without it and be stable
/// under resampling. Returns per term (ΔBIC of removing it, stability, kept).
fn joint_check(
    p: &Prepared,
    c: usize,
    terms: &[(Group, bool)],
    gate: &Gate,
) -> Vec<(f64, f64, bool)> {
    let ws = &p.replay.windows;
    let d = &p.data[c];
    let all: Vec<Group> = terms.iter().map(|(g, _)| *g).collect();
    let full = design(ws, &all);
    let full_fit = wls(&full, d, None);
    let mut out = Vec::new();
    let mut offset = 0;
    for (i, (g, parent)) in terms.iter().enumerate() {
        let cols = offset..offset + g.len;
        offset += g.len;
        if *parent {
            out.push((f64::NAN, f64::NAN, true));
            continue;
        }
        // The set without it first, then it: the nested test of its columns.
        let mut order: Vec<Group> = all.clone();
        order.remove(i);
        let base = design(ws, &order);
        let (Some(base_fit), Some(ff)) = (wls(&base, d, None), full_fit.as_ref()) else {
            out.push((f64::NAN, 0.0, false));
            continue;
        };
        order.push(*g);
        let x = design(ws, &order);
        let Some(t) = nested_test(&base_fit, base.ncols(), &x, d) else {
            out.push((f64::NAN, 0.0, false));
            continue;
        };
        // Stability of its best-determined coefficient.
        let k = cols.clone().filter(|&k| ff.identified(k)).max_by(|&a, &b| {
            let z = |k: usize| ff.theta[k].abs() / ff.cov[(k, k)].sqrt();
            z(a).total_cmp(&z(b))
        });
        // Resampling needs runs: with fewer than three, the folds are five contiguous blocks of
        // one run, and a block draw that leaves out a temperature range says nothing about a
        // temperature coefficient; there the joint fit's test decides alone (NaN reported).
        let stab = if p.runs >= 3 {
            k.map_or(0.0, |k| stability(&full, d, k, ff.theta[k].signum()))
        } else {
            f64::NAN
        };
        let passes = gate.passes_test(t.delta_bic, t.p_value, t.cv_gain_pct)
            && (stab.is_nan() || stab >= STABILITY);
        out.push((-t.delta_bic, stab, passes));
    }
    out
}

/// An accepted term: (channel, effect name, coefficients, found by, ΔBIC).
type Accepted = (usize, String, usize, String, f64);

/// The group of an effect name on a channel, at most `len` coefficients long.
type GroupOf<'a> = dyn Fn(usize, &str, Option<usize>) -> Option<Group> + 'a;

/// A channel's terms after the replacement pass.
struct Replaced {
    /// The terms, `true` marking parents.
    terms: Vec<(Group, bool)>,
    /// Index into the accepted list of each non-parent term.
    who: Vec<Option<usize>>,
    /// Per swapped-in term: its accepted index and the name of the term it replaced.
    swapped: Vec<(usize, String)>,
}

/// The replacement pass ([`crate::swap`]) on channel `c`'s `terms` (`who`: index into
/// `accepted` of each non-parent term, `None` for parents). A term swapped in is appended to
/// `accepted` and `parent_names`.
#[allow(clippy::too_many_arguments)]
fn replacement_pass(
    m2: &PlantConfig,
    p2: &Prepared,
    c: usize,
    terms: &[(Group, bool)],
    who: &[Option<usize>],
    accepted: &mut Vec<Accepted>,
    parent_names: &mut Vec<Vec<(usize, String)>>,
    group_of: &GroupOf,
) -> Replaced {
    let mut slots: Vec<usize> = Vec::new();
    let mut current: Vec<swap::Term> = Vec::new();
    for ((g, parent), w) in terms.iter().zip(who) {
        if let (false, Some(i)) = (*parent, w) {
            slots.push(*i);
            current.push(swap::Term {
                group: *g,
                parents: parent_names[*i]
                    .iter()
                    .filter_map(|(_, n)| group_of(c, n, None))
                    .collect(),
            });
        }
    }
    let candidates: Vec<swap::Term> = p2
        .replay
        .groups
        .iter()
        .filter(|g| g.channel == c)
        .flat_map(|g| g.orders())
        .filter_map(|g| {
            swap::parent_groups(m2, p2, c, g.effect).map(|parents| swap::Term { group: g, parents })
        })
        .collect();
    let swaps = swap::replace(p2, c, &mut current, &candidates);
    if swaps.is_empty() {
        return Replaced {
            terms: terms.to_vec(),
            who: who.to_vec(),
            swapped: Vec::new(),
        };
    }
    let mut swapped = Vec::new();
    for s in &swaps {
        let t = &current[s.slot];
        let name = t.group.effect.name();
        let found_by = match t.group.effect {
            Effect::Custom(_) => "declared",
            _ => "catalogue",
        };
        accepted.push((c, name, t.group.len, found_by.into(), -s.gain));
        parent_names.push(t.parents.iter().map(|g| (c, g.effect.name())).collect());
        slots[s.slot] = accepted.len() - 1;
        swapped.push((accepted.len() - 1, s.out.effect.name()));
    }
    // A term swapped in and then out again is not listed as swapped in.
    swapped.retain(|(i, _)| slots.contains(i));
    let mut out: Vec<(Group, bool)> = current.iter().map(|t| (t.group, false)).collect();
    let mut out_who: Vec<Option<usize>> = slots.iter().map(|&i| Some(i)).collect();
    for g in swap::with_parents(&current).into_iter().skip(current.len()) {
        out.push((g, true));
        out_who.push(None);
    }
    Replaced {
        terms: out,
        who: out_who,
        swapped,
    }
}

/// Iterates `model` on `h` to the noise floor (see the module docs).
pub fn iterate(
    model: &PlantConfig,
    h: &(impl Rows + ?Sized),
    opts: &Options,
    it: &IterateOptions,
) -> Result<Iteration, String> {
    let diag_opts = Options {
        diagnose: true,
        discover: true,
        apply: Vec::new(),
        ..opts.clone()
    };
    let mut m = model.clone();
    let mut steps: Vec<Step> = Vec::new();
    let mut cells_before = Vec::new();
    for step in 0.. {
        let an = analyse(&m, h, &diag_opts);
        let cmp = &an.comparison;
        if step == 0 {
            cells_before = cmp.cells.clone();
        }
        let lv = levels(cmp);
        let at_floor = lv.iter().all(|l| l.ratio <= it.floor_ratio) && cmp.flagged_cells.is_empty();
        steps.push(Step {
            step,
            levels: lv,
            flagged_cells: cmp.flagged_cells.len(),
            accepted: Vec::new(),
            coefficients: Vec::new(),
        });
        let finish = |stop: String,
                      reached: bool,
                      unexplained: Vec<String>,
                      steps: Vec<Step>,
                      an: Analysis,
                      m: PlantConfig| {
            Ok(Iteration {
                report: IterationReport {
                    source: h.info().source,
                    steps,
                    reached_floor: reached,
                    stop,
                    unexplained,
                    cells_before: cells_before.clone(),
                    cells_after: an.comparison.cells.clone(),
                    z_critical: an.comparison.z_critical,
                    closest_to_gate: near_misses(&an),
                },
                model: m,
                last: an,
            })
        };
        // The floor alone does not end the search: an effect of z = 8 over thousands of
        // windows moves the residual's RMS by well under 1 %; only the gate decides.
        let diag = an.diagnosis.as_ref().expect("diagnose is set");
        let unexplained = if at_floor {
            Vec::new()
        } else {
            diag.report.unexplained.clone()
        };
        if diag.selected.iter().all(|s| s.is_empty()) {
            let stop = if at_floor {
                format!(
                    "nothing more passes the gate; every channel within {:.0} % of its noise floor and no cell flagged",
                    100.0 * (it.floor_ratio - 1.0)
                )
            } else {
                "nothing more passes the gate".into()
            };
            return finish(stop, at_floor, unexplained, steps, an, m);
        }
        if step >= it.max_steps {
            return finish(
                format!("step limit ({}) reached", it.max_steps),
                at_floor,
                unexplained,
                steps,
                an,
                m,
            );
        }
        // The accepted terms, declared in the model when discovered, with their parents.
        let mut m2 = m.clone();
        let mut accepted: Vec<Accepted> = Vec::new();
        for c in 0..6 {
            // Parents that came with a candidate are added again as its parents below.
            for (g, _) in diag.selected[c]
                .iter()
                .zip(&diag.parent_of[c])
                .filter(|(_, p)| p.is_none())
            {
                let name = g.effect.name();
                let found_by = match g.effect {
                    Effect::Custom(_) if Effect::parse_in(&m, &name).is_none() => {
                        if Effect::parse_in(&m2, &name).is_none() {
                            let disc = diag.report.discovery.as_ref().expect("discover is set");
                            m2 = crate::discover::with_proposal(
                                &m2,
                                disc,
                                name.trim_start_matches("custom:"),
                            )?;
                        }
                        "discovered"
                    }
                    Effect::Custom(_) => "declared",
                    _ => "catalogue",
                };
                let dbic = diag
                    .report
                    .accepted
                    .iter()
                    .find(|r| r.effect == name && r.channel == CHANNELS[c])
                    .map_or(f64::NAN, |r| r.delta_bic);
                accepted.push((c, name, g.len, found_by.into(), dbic));
            }
        }
        // Every accepted declared term is declared on the other axes of its sensor too (zero
        // coefficient), so the swap pass can try it there: a term discovered on x may be what
        // z needs in place of a catalogue stand-in. Axes no fit uses are removed again below.
        let mut widened: Vec<(bool, String, usize)> = Vec::new();
        for (c, name, _, _, _) in &accepted {
            if let Some(Effect::Custom(r)) = Effect::parse_in(&m2, name) {
                let list = if r.accel {
                    &m2.sensor.accel.custom
                } else {
                    &m2.sensor.gyro.custom
                };
                let spec = list[r.index as usize].clone();
                for axis in (0..3).filter(|a| *a != c % 3) {
                    if !spec.axes.iter().any(|x| x.index() == axis) {
                        let (next, _) = declare(
                            &m2,
                            r.accel,
                            spec.kind,
                            &spec.regressor.replace(' ', ""),
                            axis,
                        );
                        m2 = next;
                        widened.push((r.accel, spec.name.clone(), axis));
                    }
                }
            }
        }
        // Parents per channel: (channel, effect name) of each parent of each accepted term.
        let mut parent_names: Vec<Vec<(usize, String)>> = vec![Vec::new(); accepted.len()];
        for (i, (c, name, _, _, _)) in accepted.iter().enumerate() {
            let e = Effect::parse_in(&m2, name).ok_or_else(|| format!("{name} is not declared"))?;
            for p in parents(&m2, e) {
                let pname = match p {
                    Parent::Effect(e) => e.name(),
                    Parent::Declare {
                        accel,
                        kind,
                        regressor,
                    } => {
                        let (next, n) = declare(&m2, accel, kind, &regressor, c % 3);
                        m2 = next;
                        n
                    }
                };
                parent_names[i].push((*c, pname));
            }
        }
        // The joint fit runs on the model with every term declared (zero where new).
        let p2 = prepare(&m2, h, opts);
        let group_of = |c: usize, name: &str, len: Option<usize>| -> Option<Group> {
            p2.replay
                .groups
                .iter()
                .find(|g| g.channel == c && g.effect.name() == name)
                .map(|g| Group {
                    len: len.map_or(g.len, |l| l.min(g.len)),
                    ..*g
                })
        };
        let gate = Gate {
            max_delta_bic: -10.0,
            alpha: opts.alpha,
            tests: p2.replay.groups.len(),
            min_cv_gain_pct: 0.0,
        };
        let mut per_channel: Vec<Vec<Group>> = vec![Vec::new(); 6];
        let mut records = Vec::new();
        for c in 0..6 {
            let mut terms: Vec<(Group, bool)> = Vec::new();
            let mut who: Vec<Option<usize>> = Vec::new();
            for (i, (ac, name, len, _, _)) in accepted.iter().enumerate() {
                if *ac != c {
                    continue;
                }
                if let Some(g) = group_of(c, name, Some(*len))
                    && !terms.iter().any(|(t, _)| t.effect == g.effect)
                {
                    terms.push((g, false));
                    who.push(Some(i));
                }
            }
            for (i, ps) in parent_names.iter().enumerate() {
                if accepted[i].0 != c {
                    continue;
                }
                for (_, pname) in ps {
                    if let Some(g) = group_of(c, pname, None)
                        && !terms.iter().any(|(t, _)| t.effect == g.effect)
                    {
                        terms.push((g, true));
                        who.push(None);
                    }
                }
            }
            if terms.is_empty() {
                continue;
            }
            let Replaced {
                terms,
                who,
                swapped,
            } = replacement_pass(
                &m2,
                &p2,
                c,
                &terms,
                &who,
                &mut accepted,
                &mut parent_names,
                &group_of,
            );
            let checks = joint_check(&p2, c, &terms, &gate);
            for ((g, parent), (jd, stab, keep)) in terms.iter().zip(&checks) {
                if *parent {
                    continue;
                }
                let i = who[terms
                    .iter()
                    .position(|(t, _)| t.effect == g.effect)
                    .expect("listed")]
                .expect("not a parent");
                let (_, name, _, found_by, dbic) = &accepted[i];
                let tau = diag.report.discovery.as_ref().and_then(|d| {
                    d.proposals
                        .iter()
                        .filter(|p| format!("custom:{}", p.name) == *name)
                        .flat_map(|p| &p.terms)
                        .find(|t| t.channel == CHANNELS[c])
                        .and_then(|t| t.tau)
                });
                let confusable_with: Vec<String> = diag
                    .report
                    .accepted
                    .iter()
                    .filter(|r| r.effect == *name && r.channel == CHANNELS[c])
                    .flat_map(|r| &r.confusable_with)
                    .chain(
                        diag.report
                            .discovery
                            .iter()
                            .flat_map(|d| &d.proposals)
                            .filter(|p| format!("custom:{}", p.name) == *name)
                            .flat_map(|p| &p.terms)
                            .filter(|t| t.channel == CHANNELS[c])
                            .flat_map(|t| &t.confusable_with),
                    )
                    .map(|x| {
                        x.effect
                            .trim_end_matches(" (with a bias correction)")
                            .to_string()
                    })
                    // Confusability is mutual: an effect of the ranking that names this one
                    // confusable with it (nearly as good on this data, nearly collinear) is
                    // named here too, though this one's own row, fitted without a bias
                    // correction, may not list it.
                    .chain(
                        diag.report
                            .ranking
                            .iter()
                            .filter(|r| r.channel == CHANNELS[c] && r.effect != *name)
                            .filter(|r| {
                                r.confusable_with.iter().any(|x| {
                                    x.effect.trim_end_matches(" (with a bias correction)")
                                        == name.as_str()
                                })
                            })
                            .map(|r| r.effect.clone()),
                    )
                    .fold(Vec::new(), |mut v: Vec<String>, e| {
                        if !v.contains(&e) {
                            v.push(e);
                        }
                        v
                    });
                records.push(AcceptedTerm {
                    confusable_with,
                    tau,
                    channel: CHANNELS[c].into(),
                    effect: name.clone(),
                    found_by: found_by.clone(),
                    replaces: swapped
                        .iter()
                        .find(|(j, _)| *j == i)
                        .map(|(_, out)| out.clone()),
                    delta_bic: *dbic,
                    parents: parent_names[i].iter().map(|(_, n)| n.clone()).collect(),
                    joint_delta_bic: *jd,
                    stability: *stab,
                    kept: *keep,
                });
            }
            // The survivors with the parents any survivor needs.
            let survivors: Vec<usize> = who
                .iter()
                .zip(&checks)
                .filter_map(|(w, (_, _, keep))| w.filter(|_| *keep))
                .collect();
            let needed: Vec<&String> = survivors
                .iter()
                .flat_map(|&i| parent_names[i].iter().map(|(_, n)| n))
                .collect();
            per_channel[c] = terms
                .iter()
                .zip(&checks)
                .filter(|((g, parent), (_, _, keep))| {
                    if *parent {
                        needed.contains(&&g.effect.name())
                    } else {
                        *keep
                    }
                })
                .map(|((g, _), _)| *g)
                .collect();
        }
        let last = steps.last_mut().expect("pushed");
        last.accepted = records;
        if per_channel.iter().all(|g| g.is_empty()) {
            let mut unexplained = unexplained;
            unexplained.insert(
                0,
                "the terms the gate accepted do not survive the joint fit with their parents and the run resampling".into(),
            );
            return finish(
                "nothing survives the joint fit".into(),
                at_floor,
                unexplained,
                steps,
                an,
                m,
            );
        }
        let applied = apply_groups(&m2, &p2, &[], &per_channel)?;
        // A discovered memory term is fitted with its time constant fixed at the estimate: its
        // coefficient's interval is widened by what τ's uncertainty adds (discovery's fit with
        // τ free).
        let mut coefficients = applied.coefficients;
        let last = steps.last_mut().expect("pushed");
        for c in coefficients.iter_mut() {
            let tau = last
                .accepted
                .iter()
                .find(|a| a.effect == c.effect && a.channel == c.channel)
                .and_then(|a| a.tau);
            if let (Some(t), Some(v), Some(ci)) = (tau, c.fitted, c.ci95.as_mut()) {
                let w = t.coefficient_widening.max(1.0);
                *ci = [
                    (v - (v - ci[0]) * w).min(t.coefficient_ci95[0]),
                    (v + (ci[1] - v) * w).max(t.coefficient_ci95[1]),
                ];
            }
        }
        last.coefficients = coefficients;
        // Declarations this step added for terms that did not survive stay in the list (the
        // history's keys keep their indices) but are switched off.
        let used: Vec<String> = per_channel
            .iter()
            .flatten()
            .map(|g| g.effect.name())
            .collect();
        let mut next = applied.model;
        for accel in [false, true] {
            let before = if accel {
                m.sensor.accel.custom.len()
            } else {
                m.sensor.gyro.custom.len()
            };
            let list = if accel {
                &mut next.sensor.accel.custom
            } else {
                &mut next.sensor.gyro.custom
            };
            for s in list.iter_mut().skip(before) {
                if !used.contains(&format!("custom:{}", s.name)) {
                    s.enabled = false;
                }
            }
        }
        // Axes the widening added and no fit of this step uses are taken off again.
        for (accel, name, axis) in &widened {
            let channel = axis + if *accel { 3 } else { 0 };
            let key = format!("custom:{name}");
            if per_channel[channel].iter().any(|g| g.effect.name() == key) {
                continue;
            }
            let list = if *accel {
                &mut next.sensor.accel.custom
            } else {
                &mut next.sensor.gyro.custom
            };
            if let Some(s) = list.iter_mut().find(|s| &s.name == name) {
                s.axes.retain(|a| a.index() != *axis);
                s.coef[*axis] = 0.0;
            }
        }
        m = next;
    }
    unreachable!("the loop returns")
}
