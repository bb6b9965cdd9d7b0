//! Worst cases over a class of effects with box-bounded coefficients, and the part of the
//! general position-dependent bias that no scheme removes.
//!
//! Everything here is linear: the navigation error after N days is Σ_k c_k·p_k with p_k the
//! (north, east) error of effect k at unit coefficient. Over |c_k| ≤ B the largest horizontal
//! error is max over directions d of B·Σ_k |d·p_k|, attained at c_k = B·sign(d·p_k); the
//! largest east (longitude) error is B·Σ_k |p_k,E|.
//!
//! The invariant part: with b_i(u) = k·u_i on every axis (an isotropic g-sensitivity),
//! C_b^n·b = k·C_b^n·u^b = k·(0, 0, 1) whatever the attitude. That member of the class drifts
//! the azimuth by k under every scheme, and a static navigator's longitude by k·sin L·t, so no
//! scheme's worst case can fall below what it does.

use serde::Serialize;

use crate::analyse::{EffectResidual, SchemeAnalysis};
use crate::basis::MONOMIALS;

/// Directions tried in the north–east plane before refining.
const DIRECTIONS: usize = 720;

/// A class's worst case under one scheme.
#[derive(Clone, Debug, Serialize)]
pub struct ClassBound {
    /// Scheme.
    pub scheme: String,
    /// Which class (`general-b(u)` or `plant-delta-beta`).
    pub class: String,
    /// Bound on every coefficient, °/h.
    pub bound_dph: f64,
    /// Largest horizontal position error over the class after the analysis's days, m.
    pub worst_horizontal_m: f64,
    /// Its direction, degrees from north toward east.
    pub worst_direction_deg: f64,
    /// Largest east (longitude) error over the class, m.
    pub worst_east_m: f64,
    /// Coefficients attaining [`ClassBound::worst_horizontal_m`] (effect key, °/h), nonzero ones.
    pub attaining_dph: Vec<(String, f64)>,
    /// What the invariant member (b_i = B·u_i) does, m (`general-b(u)` only; 0 otherwise).
    pub invariant_horizontal_m: f64,
}

/// Worst case of |Σ c_k p_k| over |c_k| ≤ bound: (value, direction rad, signs).
pub fn worst_horizontal(p: &[[f64; 2]], bound: f64) -> (f64, f64, Vec<f64>) {
    let value = |th: f64| {
        let (s, c) = th.sin_cos();
        p.iter().map(|q| (c * q[0] + s * q[1]).abs()).sum::<f64>() * bound
    };
    let mut best = (0.0_f64, 0.0_f64);
    for k in 0..DIRECTIONS {
        let th = std::f64::consts::PI * k as f64 / DIRECTIONS as f64;
        let v = value(th);
        if v > best.0 {
            best = (v, th);
        }
    }
    // Golden-section refinement inside the best grid cell's neighbours.
    let h = std::f64::consts::PI / DIRECTIONS as f64;
    let (mut a, mut b) = (best.1 - h, best.1 + h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if value(x1) > value(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let th = 0.5 * (a + b);
    let (s, c) = th.sin_cos();
    let signs = p
        .iter()
        .map(|q| {
            let d = c * q[0] + s * q[1];
            if d >= 0.0 { bound } else { -bound }
        })
        .collect();
    (value(th).max(best.0), th, signs)
}

/// The classes a bound can be taken over.
pub const CLASSES: [&str; 3] = ["general-b(u)", "general-anisotropic", "plant-delta-beta"];

/// The invariant member's coefficients: b_x = u_x, b_y = u_y, b_z = u_z.
pub const TRACE_KEYS: [&str; 3] = ["general.bx_ux", "general.by_uy", "general.bz_uz"];

fn class_members<'a>(a: &'a SchemeAnalysis, class: &str) -> Vec<&'a EffectResidual> {
    a.effects
        .iter()
        .filter(|e| match class {
            "general-b(u)" | "general-anisotropic" => e.effect.starts_with("general."),
            _ => e.effect.starts_with("gyro.position_bias."),
        })
        .collect()
}

/// Worst case of |Σ c_k p_k| over |c_k| ≤ bound with the coefficients of `trace` (indices
/// into `p`) summing to zero: the general class with its invariant direction removed. For a
/// direction with projections a_k, max Σ a_k c_k = bound·(Σ_{k∉T}|a_k| + max_T a − min_T a)
/// (three trace coefficients: +bound on the largest, −bound on the smallest, 0 on the median;
/// LP duality gives the same as min_λ Σ_T |a_k − λ|).
pub fn worst_horizontal_trace_free(
    p: &[[f64; 2]],
    trace: &[usize; 3],
    bound: f64,
) -> (f64, f64, Vec<f64>) {
    let value = |th: f64| {
        let (s, c) = th.sin_cos();
        let a: Vec<f64> = p.iter().map(|q| c * q[0] + s * q[1]).collect();
        let free: f64 = a
            .iter()
            .enumerate()
            .filter(|(k, _)| !trace.contains(k))
            .map(|(_, v)| v.abs())
            .sum();
        let t = trace.map(|k| a[k]);
        let range = t.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
            - t.iter().cloned().fold(f64::INFINITY, f64::min);
        bound * (free + range)
    };
    // The value is even in the direction's sign only through |·|; scan the whole circle.
    let mut best = (0.0_f64, 0.0_f64);
    for k in 0..2 * DIRECTIONS {
        let th = std::f64::consts::PI * k as f64 / DIRECTIONS as f64;
        let v = value(th);
        if v > best.0 {
            best = (v, th);
        }
    }
    let th = best.1;
    let (s, c) = th.sin_cos();
    let a: Vec<f64> = p.iter().map(|q| c * q[0] + s * q[1]).collect();
    let mut signs: Vec<f64> = a
        .iter()
        .map(|v| if *v >= 0.0 { bound } else { -bound })
        .collect();
    let mut order = *trace;
    order.sort_by(|i, j| a[*i].total_cmp(&a[*j]));
    signs[order[0]] = -bound;
    signs[order[1]] = 0.0;
    signs[order[2]] = bound;
    (best.0, th, signs)
}

/// The worst case over `class` (`general-b(u)`: the 27 basis effects; `plant-delta-beta`: the
/// three per-axis δβ effects) with every coefficient bounded by `bound_dph`. The analysis must
/// hold the class's effects at 1 °/h per unit ([`crate::EffectSet::with_general`],
/// [`crate::EffectSet::with_delta_beta_axes`]).
pub fn class_bound(a: &SchemeAnalysis, class: &str, bound_dph: f64) -> Option<ClassBound> {
    let members = class_members(a, class);
    if members.is_empty() {
        return None;
    }
    let p: Vec<[f64; 2]> = members
        .iter()
        .map(|e| [e.after.north_m, e.after.east_m])
        .collect();
    let worst_of = |p: &[[f64; 2]]| {
        if class == "general-anisotropic" {
            let idx = TRACE_KEYS.map(|k| {
                members
                    .iter()
                    .position(|e| e.effect == k)
                    .expect("the general basis holds the trace keys")
            });
            worst_horizontal_trace_free(p, &idx, bound_dph)
        } else {
            worst_horizontal(p, bound_dph)
        }
    };
    let (worst, th, signs) = worst_of(&p);
    let east_only: Vec<[f64; 2]> = p.iter().map(|q| [0.0, q[1]]).collect();
    let worst_east = worst_of(&east_only).0;
    let invariant = if class == "general-b(u)" {
        let get = |k: &str| a.effect(k).map(|e| [e.after.north_m, e.after.east_m]);
        match (
            get("general.bx_ux"),
            get("general.by_uy"),
            get("general.bz_uz"),
        ) {
            (Some(x), Some(y), Some(z)) => {
                bound_dph * (x[0] + y[0] + z[0]).hypot(x[1] + y[1] + z[1])
            }
            _ => 0.0,
        }
    } else {
        0.0
    };
    Some(ClassBound {
        scheme: a.scheme.clone(),
        class: class.into(),
        bound_dph,
        worst_horizontal_m: worst,
        worst_direction_deg: th.to_degrees(),
        worst_east_m: worst_east,
        attaining_dph: members
            .iter()
            .zip(&signs)
            .filter(|(e, _)| e.after.north_m != 0.0 || e.after.east_m != 0.0)
            .map(|(e, s)| (e.effect.clone(), *s))
            .collect(),
        invariant_horizontal_m: invariant,
    })
}

/// The attaining coefficients of a general-b(u) bound as a 3 × 9 table (axis × monomial).
pub fn coefficient_table(b: &ClassBound) -> [[f64; 9]; 3] {
    let mut t = [[0.0; 9]; 3];
    for (key, c) in &b.attaining_dph {
        for axis in 0..3 {
            for k in 0..MONOMIALS.len() {
                if *key == format!("general.{}", crate::basis::name(axis, k)) {
                    t[axis][k] = *c;
                }
            }
        }
    }
    t
}
