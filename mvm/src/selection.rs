//! Which of the catalogue's effects explain the residual: every candidate ranked against the
//! model as given (ΔBIC, nested F test, cross-validated error, 95 % intervals, confusable
//! pairs), forward selection through the gate, the selected effects' joint predictions, and a
//! plain-language summary of what they leave unexplained.

// Six channels indexed in parallel arrays: index loops read best.
#![allow(clippy::needless_range_loop)]

use std::collections::BTreeMap;

use crate::fit::{
    self, Gate, collinearity, contribution, delta_bic_of, design, test_candidates, wls,
};
use crate::prepare::Prepared;
use crate::replay::{CHANNELS, Effect, Group};
use crate::report::{CompareReport, Confusable, DiagnoseReport, RankedEffect, unit_of};

/// What the diagnosis found, with what the figures and the Rerun recording show.
#[derive(Clone, Debug)]
pub struct Diagnosis {
    /// The report `rins diagnose` prints.
    pub report: DiagnoseReport,
    /// Groups accepted by forward selection, per channel, in order of acceptance (a
    /// candidate's parents just before it).
    pub selected: Vec<Vec<Group>>,
    /// Per channel and selected group, the candidate it entered as a parent of (`None`:
    /// accepted in its own right).
    pub parent_of: Vec<Vec<Option<Group>>>,
    /// Per channel and window, the accepted effects' contribution to the window sum (rad for
    /// gyros, m/s for accelerometers), fitted jointly per channel; zeros where none.
    pub predictions: Vec<Vec<f64>>,
    /// The comparison with those predictions removed.
    pub after: CompareReport,
}

/// How to separate two confusable effects.
pub fn separating_experiment(a: &str, b: &str) -> String {
    let has = |k: &str| a.contains(k) || b.contains(k);
    if has("temperature_bias") && has("temperature_gradient_bias") {
        "hold the chamber at two or more steady temperatures (the gradient settles to its steady value while the temperature differs) and add a fast chamber step: the temperature bias follows T, the gradient bias follows the transient".into()
    } else if has("position_bias") && (has("g_sensitivity") || has("dither_bias")) {
        "dwell at tilted positions (inner gimbal at ±45° and ±90°): δβ switches with Z-up/Z-down, g-sensitivity is linear and dither bias quadratic in the gravity component".into()
    } else if has("position_bias") && has(".bias")
        || has("position_bias") && has("temperature_bias")
    {
        "dwell at both Z-up and Z-down at each temperature: δβ appears only at Z-down".into()
    } else if has("scale_factor_asymmetry") && has("scale_factor") {
        "rotate in both directions at the same rate: the scale factor changes sign with the rate, the asymmetry does not".into()
    } else if has("nav_field_bias") {
        "dwell at four or more azimuths at Z-up and at Z-down (and tilted): a field fixed in the navigation frame turns with the azimuth, the other effect does not".into()
    } else if has("misalignment") {
        "rotate about each body axis in turn: misalignment shows on the cross axes only".into()
    } else if has("temperature") {
        "runs at several chamber temperatures spanning the range of interest".into()
    } else {
        "a run that changes the input the two depend on differently (temperature, table position or rotation direction)".into()
    }
}

fn ranked(
    a: &Prepared,
    c: &fit::Candidate,
    others: &[fit::Candidate],
    gate: &Gate,
) -> RankedEffect {
    let ch = c.group.channel;
    let mut keys = c.group.effect.coefficient_keys(ch);
    keys.truncate(c.group.len);
    let (coefficient, ci95): (Vec<f64>, Vec<[f64; 2]>) = keys
        .iter()
        .enumerate()
        .map(|(k, (_, unit))| {
            let i = c.theta_offset + k;
            let (th, se) = (c.fit.theta[i], c.fit.cov[(i, i)].sqrt());
            if c.fit.identified(i) {
                (
                    th / unit,
                    [(th - 1.96 * se) / unit, (th + 1.96 * se) / unit],
                )
            } else {
                // Not identifiable on this data: null in the report and the JSON.
                (f64::NAN, [f64::NAN, f64::NAN])
            }
        })
        .unzip();
    // Another effect is confusable when it (with a bias correction, which any calibration
    // re-estimates) explains the same residual nearly as well and the two fitted contributions
    // are nearly collinear.
    let ws = &a.replay.windows;
    let d = &a.data[ch];
    let bias = a
        .replay
        .groups
        .iter()
        .find(|g| {
            g.channel == ch
                && matches!(
                    g.effect,
                    Effect::Gyro(rins_plant::effects::GyroTerm::Bias)
                        | Effect::Accel(rins_plant::effects::AccelTerm::Bias)
                )
        })
        .copied();
    let own = contribution(
        ws,
        d,
        std::slice::from_ref(&c.group),
        &c.fit.theta[c.theta_offset..],
    );
    let confusable_with = others
        .iter()
        .filter(|o| o.group.effect != c.group.effect && c.delta_bic < -10.0)
        .take(8)
        .filter_map(|o| {
            let mut alt = vec![o.group];
            if let Some(b) =
                bias.filter(|b| b.effect != o.group.effect && b.effect != c.group.effect)
            {
                alt.push(b);
            }
            let (dbic, fit) = delta_bic_of(ws, d, &[], &alt)?;
            if dbic - c.delta_bic >= 10.0 {
                return None;
            }
            let theirs = contribution(ws, d, &alt, &fit.theta);
            let (rho, vif) = collinearity(&own, &theirs, ws, d, &alt);
            (rho.abs() > 0.9).then(|| Confusable {
                effect: if alt.len() > 1 {
                    format!("{} (with a bias correction)", o.group.effect.name())
                } else {
                    o.group.effect.name()
                },
                delta_bic_gap: dbic - c.delta_bic,
                correlation: rho,
                vif,
                separate_by: separating_experiment(&c.group.effect.name(), &o.group.effect.name()),
            })
        })
        .collect();
    RankedEffect {
        effect: c.group.effect.name(),
        channel: CHANNELS[ch].into(),
        delta_bic: c.delta_bic,
        p_value: c.p_value,
        cv_rmse_gain_pct: c.cv_gain_pct,
        coefficient,
        ci95,
        keys: keys.into_iter().map(|(k, _)| k).collect(),
        condition_number: c.fit.condition,
        confusable_with,
        passes_gate: gate.passes(c),
        parents: Vec::new(),
        field: (c.group.effect == Effect::Gyro(rins_plant::effects::GyroTerm::NavFieldBias)
            && c.group.len == 3)
            .then(|| field_direction(&c.fit, c.theta_offset))
            .flatten(),
    }
}

/// The field's magnitude and direction from the three components (east, north, up; SI) at
/// `offset` of `fit`, when all three are determined.
fn field_direction(fit: &fit::Fit, offset: usize) -> Option<crate::report::FieldDirection> {
    use rins_plant::units::DPH;
    let k: Vec<usize> = (offset..offset + 3).collect();
    if !k.iter().all(|&i| fit.identified(i)) {
        return None;
    }
    let (e, n, u) = (fit.theta[k[0]], fit.theta[k[1]], fit.theta[k[2]]);
    let cov = |a: usize, b: usize| fit.cov[(k[a], k[b])];
    // The delta method: var(f) = ∇fᵀ Σ ∇f for a function f of (e, n, u).
    let spread = |g: [f64; 3]| {
        let mut v = 0.0;
        for a in 0..3 {
            for b in 0..3 {
                v += g[a] * g[b] * cov(a, b);
            }
        }
        1.96 * v.max(0.0).sqrt()
    };
    let h = e.hypot(n);
    let m = (h * h + u * u).sqrt();
    if !(m > 0.0 && h > 0.0) {
        return None;
    }
    let dm = spread([e / m, n / m, u / m]);
    // declination atan2(e, n): ∂/∂e = n/h², ∂/∂n = −e/h².
    let dd = spread([n / (h * h), -e / (h * h), 0.0]).to_degrees();
    // inclination atan2(−u, h): ∂/∂u = −h/m², ∂/∂e = u·e/(h·m²), ∂/∂n = u·n/(h·m²).
    let di = spread([u * e / (h * m * m), u * n / (h * m * m), -h / (m * m)]).to_degrees();
    let (dec, inc) = (e.atan2(n).to_degrees(), (-u).atan2(h).to_degrees());
    Some(crate::report::FieldDirection {
        magnitude_dph: m / DPH,
        magnitude_ci95_dph: [(m - dm) / DPH, (m + dm) / DPH],
        declination_deg: dec,
        declination_ci95_deg: [dec - dd, dec + dd],
        inclination_deg: inc,
        inclination_ci95_deg: [inc - di, inc + di],
    })
}

/// Predictions of `groups` fitted on channel `c`.
fn predict(a: &Prepared, c: usize, groups: &[Group]) -> Vec<f64> {
    let x = design(&a.replay.windows, groups);
    let fit = wls(&x, &a.data[c], None).expect("accepted model fits");
    (0..x.nrows())
        .map(|r| (0..x.ncols()).map(|k| x[(r, k)] * fit.theta[k]).sum())
        .collect()
}

/// Per-channel window predictions of the `selected` groups (zeros where none), fitted jointly.
fn predictions(a: &Prepared, selected: &[Vec<Group>]) -> Vec<Vec<f64>> {
    (0..6)
        .map(|c| {
            if selected[c].is_empty() {
                vec![0.0; a.replay.windows.len()]
            } else {
                predict(a, c, &selected[c])
            }
        })
        .collect()
}

/// `rins diagnose`: rank the catalogue's effects against the residual, select by the gate and
/// compare again with the selected effects removed; `before` is the comparison of the model as
/// given.
pub(crate) fn diagnose(a: &Prepared, source: &str, before: &CompareReport) -> Diagnosis {
    let opts = &a.opts;
    let tests = a.replay.groups.len();
    let gate = Gate {
        max_delta_bic: -10.0,
        alpha: opts.alpha,
        tests,
        min_cv_gain_pct: 0.0,
    };
    let mut ranking = Vec::new();
    let mut accepted = Vec::new();
    let mut selected: Vec<Vec<Group>> = vec![Vec::new(); 6];
    let mut parent_of: Vec<Vec<Option<Group>>> = vec![Vec::new(); 6];
    for c in 0..6 {
        let pool: Vec<Group> = a
            .replay
            .groups
            .iter()
            .filter(|g| g.channel == c)
            .copied()
            .collect();
        let (_, first) = test_candidates(&a.replay.windows, &a.data[c], &[], &pool);
        ranking.extend(first.iter().map(|cand| ranked(a, cand, &first, &gate)));
        // Forward selection with heredity and a beam (crate::forward).
        let parents = |g: &Group| a.parent_groups(g);
        let sel = crate::forward::select(&a.replay.windows, &a.data[c], &pool, &parents, &gate);
        for (t, others) in &sel.steps {
            let mut r = ranked(a, &t.candidate, others, &gate);
            r.parents = t.parents.iter().map(|p| p.effect.name()).collect();
            accepted.push(r);
        }
        selected[c] = sel.groups.clone();
        parent_of[c] = sel.parent_of.clone();
    }
    ranking.sort_by(|x, y| x.delta_bic.total_cmp(&y.delta_bic));
    let pred = predictions(a, &selected);
    let after = a.compare_report(source, &pred);
    let mut unexplained = Vec::new();
    if after.flagged_cells.is_empty() {
        if !before.flagged_cells.is_empty() {
            unexplained.push("the accepted effects clear every flagged cell".into());
        }
    } else {
        let mut by: BTreeMap<(String, String), usize> = BTreeMap::new();
        for c in &after.flagged_cells {
            *by.entry((c.channel.clone(), c.position.clone()))
                .or_default() += 1;
        }
        let claim = if accepted.is_empty() {
            "no candidate in the catalogue passes the gate"
        } else {
            "the accepted effects do not explain all of it"
        };
        unexplained.push(format!(
            "{claim}; {} cells stay outside ±{:.2}σ",
            after.flagged_cells.len(),
            after.z_critical
        ));
        for ((ch, pos), n) in by {
            let worst = after
                .flagged_cells
                .iter()
                .filter(|c| c.channel == ch && c.position == pos)
                .max_by(|a, b| a.z.abs().total_cmp(&b.z.abs()))
                .expect("non-empty");
            unexplained.push(format!(
                "{ch} at {pos}: {n} cells, worst {:.4} {} (z = {:.1}) at {} {:.0}–{:.0} °C, {:.0}–{:.0} s",
                worst.residual,
                unit_of(CHANNELS.iter().position(|x| *x == ch).unwrap_or(0)).0,
                worst.z,
                worst.orientation,
                worst.temp_bin_c[0],
                worst.temp_bin_c[1],
                worst.time_window_s[0],
                worst.time_window_s[1]
            ));
        }
        for corr in after
            .correlations
            .iter()
            .filter(|c| c.significant && c.with != "residual")
        {
            unexplained.push(format!(
                "{}: residual correlates with {} (|ρ| = {:.2} > {:.2} at lag {})",
                corr.channel, corr.with, corr.max_abs_rho, corr.band99, corr.lag
            ));
        }
    }
    let map = |r: &CompareReport| {
        r.channels
            .iter()
            .map(|c| (c.channel.clone(), c.residual_rms))
            .collect()
    };
    let report = DiagnoseReport {
        source: source.into(),
        ranking,
        accepted,
        residual_rms_before: map(before),
        residual_rms_after: map(&after),
        noise_floor_rms: before
            .channels
            .iter()
            .map(|c| (c.channel.clone(), c.noise_floor_rms))
            .collect(),
        flagged_cells: before.flagged_cells.clone(),
        flagged_cells_after: after.flagged_cells.clone(),
        unexplained,
        unavailable: a.replay.unavailable.clone(),
        column_map: before.column_map.clone(),
        discovery: None,
    };
    Diagnosis {
        report,
        selected,
        parent_of,
        predictions: pred,
        after,
    }
}
