//! The replacement pass of `--iterate` (Miller's replacement algorithm, *Subset Selection in
//! Regression*, ch. 3): forward selection accepts the best single term at each stage, so a
//! stand-in that explains most of a missing effect early (a catalogue term found before
//! discovery offers the real one) stays in the set. After the gate, each accepted term of a
//! channel is tried against every other candidate of that channel, each with its parents; the
//! swap that lowers the joint fit's BIC most is made while one lowers it by more than 6.
//!
//! Why 6 and not the gate's 10: both sets have passed the gate, and a swap chooses between two
//! explanations of the same size, not whether to add one; a BIC difference above 6 is "strong"
//! evidence on Kass & Raftery's scale (J. Am. Stat. Assoc. 90 (1995) 773, §3.2), a likelihood
//! ratio above 20. The greedy order that put the stand-in first carries no evidence of its own.

use rins_plant::PlantConfig;
use rins_plant::effects::custom::CustomKind;

use crate::fit::{design, wls};
use crate::heredity::{Parent, parents};
use crate::prepare::Prepared;
use crate::replay::{Effect, Group};

/// A swap lowers the joint fit's BIC by more than this ("strong" evidence, see the module
/// docs).
pub const MIN_SWAP_GAIN: f64 = 6.0;
/// Swaps per channel and step at most (each strictly lowers the BIC, so this only bounds the
/// work).
pub const MAX_SWAPS: usize = 4;

/// An accepted term of a channel with its parents' groups.
#[derive(Clone, Debug)]
pub struct Term {
    /// The term.
    pub group: Group,
    /// Its parents on the same channel.
    pub parents: Vec<Group>,
}

/// A swap made: `out` replaced by `term`, lowering the joint BIC by `gain`.
#[derive(Clone, Debug)]
pub struct Swap {
    /// Index of the replaced term in the list given.
    pub slot: usize,
    /// The term that was there.
    pub out: Group,
    /// BIC gain of the swap (positive).
    pub gain: f64,
}

/// The groups of `terms` with their parents, each once, terms first.
pub fn with_parents(terms: &[Term]) -> Vec<Group> {
    let mut all: Vec<Group> = terms.iter().map(|t| t.group).collect();
    for p in terms.iter().flat_map(|t| &t.parents) {
        if !all.iter().any(|g| g.effect == p.effect) {
            all.push(*p);
        }
    }
    all
}

/// The parents of `effect` on channel `c` as groups of `p`, or `None` when one has no group
/// there (a lower monomial not declared on this axis): such a candidate is not tried.
pub fn parent_groups(
    model: &PlantConfig,
    p: &Prepared,
    c: usize,
    effect: Effect,
) -> Option<Vec<Group>> {
    let group = |name: &str| {
        p.replay
            .groups
            .iter()
            .find(|g| g.channel == c && g.effect.name() == name)
            .copied()
    };
    parents(model, effect)
        .into_iter()
        .map(|parent| match parent {
            Parent::Effect(e) => group(&e.name()),
            Parent::Declare {
                accel,
                kind,
                regressor,
            } => declared_name(model, accel, kind, &regressor, c % 3).and_then(|n| group(&n)),
        })
        .collect()
}

/// `custom:NAME` of the enabled declaration of `kind` and `regressor` acting on `axis`.
fn declared_name(
    model: &PlantConfig,
    accel: bool,
    kind: CustomKind,
    regressor: &str,
    axis: usize,
) -> Option<String> {
    let list = if accel {
        &model.sensor.accel.custom
    } else {
        &model.sensor.gyro.custom
    };
    list.iter()
        .find(|s| {
            s.enabled
                && s.kind == kind
                && s.regressor.replace(' ', "") == regressor
                && s.axes.iter().any(|a| a.index() == axis)
        })
        .map(|s| format!("custom:{}", s.name))
}

/// BIC of the joint fit of `groups` on channel `c`, with the noise scale `s2`; `None` when the
/// fit fails.
fn bic(p: &Prepared, c: usize, groups: &[Group], s2: f64) -> Option<f64> {
    let d = &p.data[c];
    let f = wls(&design(&p.replay.windows, groups), d, None)?;
    Some(f.chi2 / s2 + f.identified_count() as f64 * (d.y.len() as f64).ln())
}

/// Runs the replacement pass on the accepted `terms` of channel `c`; `candidates` are the
/// channel's other candidates with their parents. Swaps are made in place; returns them in
/// order. The noise scale is the current set's reduced χ² (at least 1), held for the pass so
/// every set is judged on the same scale.
pub fn replace(p: &Prepared, c: usize, terms: &mut [Term], candidates: &[Term]) -> Vec<Swap> {
    let d = &p.data[c];
    let Some(start) = wls(&design(&p.replay.windows, &with_parents(terms)), d, None) else {
        return Vec::new();
    };
    let s2 = start.chi2_red().max(1.0);
    let mut swaps = Vec::new();
    for _ in 0..MAX_SWAPS {
        let Some(now) = bic(p, c, &with_parents(terms), s2) else {
            break;
        };
        let mut best: Option<(usize, usize, f64)> = None;
        for slot in 0..terms.len() {
            for (k, cand) in candidates.iter().enumerate() {
                let effect = cand.group.effect;
                if terms.iter().any(|t| {
                    t.group.effect == effect || t.parents.iter().any(|q| q.effect == effect)
                }) {
                    continue;
                }
                let mut trial = terms.to_vec();
                trial[slot] = cand.clone();
                if let Some(b) = bic(p, c, &with_parents(&trial), s2)
                    && now - b > MIN_SWAP_GAIN
                    && best.is_none_or(|(_, _, g)| now - b > g)
                {
                    best = Some((slot, k, now - b));
                }
            }
        }
        let Some((slot, k, gain)) = best else {
            break;
        };
        let out = terms[slot].group;
        terms[slot] = candidates[k].clone();
        swaps.push(Swap { slot, out, gain });
    }
    swaps
}
