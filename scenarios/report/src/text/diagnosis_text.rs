//! Text of the model-vs-measurement reports: `rins compare` (where the model fails) and
//! `rins diagnose` (which effects explain it). These go with the diagnosis when it moves.

use std::fmt::Write;

use rins_mvm::{CompareReport, DiagnoseReport};

use super::RenderText;

impl RenderText for CompareReport {
    fn render_text(&self) -> String {
        let mut s = String::new();
        // Writing to a String cannot fail.
        let _ = writeln!(
            s,
            "{}: {} rows, {} windows, {} runs",
            self.source, self.rows, self.windows, self.runs
        );
        column_map(&mut s, self.column_map.as_ref());
        let _ = writeln!(
            s,
            "{:<8} {:>12} {:>12} {:>12}  unit",
            "channel", "resid RMS", "noise RMS", "resid mean"
        );
        for c in &self.channels {
            let _ = writeln!(
                s,
                "{:<8} {:>12.5} {:>12.5} {:>12.5}  {}",
                c.channel, c.residual_rms, c.noise_floor_rms, c.residual_mean, c.unit
            );
        }
        for n in &self.noise {
            let _ = writeln!(s, "noise {}: {}", n.channel, n.source);
        }
        let _ = writeln!(
            s,
            "{} of {} cells flagged (|z| > {:.2})",
            self.flagged_cells.len(),
            self.cells.len(),
            self.z_critical
        );
        for c in self.flagged_cells.iter().take(20) {
            // The time since the table last stopped, for a static cell.
            let since = match c.since_move_s {
                [_, hi] if hi == 0.0 => String::new(),
                [lo, hi] if hi.is_finite() => format!("{lo:.0}-{hi:.0} s after a move"),
                [lo, _] => format!("> {lo:.0} s after a move"),
            };
            let _ = writeln!(
                s,
                "  {:<8} {:<7} {:<6} {:>5.1}-{:<5.1} °C  {:>7.0}-{:<7.0} s  {:<22} residual {:>10.5} ± {:.5}  z = {:>6.1}",
                c.channel,
                c.position,
                c.orientation,
                c.temp_bin_c[0],
                c.temp_bin_c[1],
                c.time_window_s[0],
                c.time_window_s[1],
                since,
                c.residual,
                c.noise_floor,
                c.z
            );
        }
        for c in self.correlations.iter().filter(|c| c.significant) {
            if c.with == "residual" {
                // The whiteness check: the residual against itself at lags 1-10.
                let _ = writeln!(
                    s,
                    "  {}: residual is not white (autocorrelation |rho| = {:.2} > {:.2} at lag {})",
                    c.channel, c.max_abs_rho, c.band99, c.lag
                );
            } else {
                let _ = writeln!(
                    s,
                    "  {}: residual correlates with {} (|rho| = {:.2} > {:.2}, lag {})",
                    c.channel, c.with, c.max_abs_rho, c.band99, c.lag
                );
            }
        }
        let _ = writeln!(
            s,
            "navigation (static, horizontal error at the end of each segment):"
        );
        for n in self.navigation.iter().take(12) {
            let _ = writeln!(
                s,
                "  {:<16} {:>7.0} s  measured {:>9.2} m  model {:>9.2} m  (difference RMS {:.2} m)",
                n.run, n.duration_s, n.measured_final_m, n.model_final_m, n.difference_rms_m
            );
        }
        s
    }
}

/// The column map's mapped and ignored columns, when the data were read with one.
fn column_map(s: &mut String, m: Option<&rins_mvm::colmap::MapSummary>) {
    if let Some(m) = m {
        let _ = writeln!(s, "column map {}: {}", m.map, m.mapped.join(", "));
        if !m.ignored.is_empty() {
            let _ = writeln!(s, "  ignored columns: {}", m.ignored.join(", "));
        }
    }
}

impl RenderText for DiagnoseReport {
    fn render_text(&self) -> String {
        let mut s = String::new();
        column_map(&mut s, self.column_map.as_ref());
        let _ = writeln!(
            s,
            "{}: candidates ranked by delta-BIC (gate: delta-BIC < -10, Bonferroni p < 0.01, CV gain > 0 where a fold can judge it)",
            self.source
        );
        let _ = writeln!(
            s,
            "{:<36} {:<8} {:>10} {:>10} {:>8}  gate  coefficient (95 % CI)",
            "effect", "channel", "dBIC", "p", "CV %"
        );
        for r in self.ranking.iter().take(15) {
            let coef: Vec<String> = r
                .coefficient
                .iter()
                .zip(&r.ci95)
                .zip(&r.keys)
                .map(|((c, ci), k)| {
                    let k = k.rsplit('.').next().unwrap_or(k);
                    if c.is_nan() {
                        // Not identifiable on this data (null in the JSON).
                        format!("{k}=not identifiable")
                    } else {
                        format!("{k}={} [{}, {}]", num(*c), num(ci[0]), num(ci[1]))
                    }
                })
                .collect();
            let _ = writeln!(
                s,
                "{:<36} {:<8} {:>10.1} {:>10.2e} {:>8}  {}  {}",
                r.effect,
                r.channel,
                r.delta_bic,
                r.p_value,
                cv_cell(r.cv_rmse_gain_pct),
                if r.passes_gate { "PASS" } else { "-   " },
                coef.join(" ")
            );
            for c in &r.confusable_with {
                let _ = writeln!(
                    s,
                    "    confusable with {} (gap {:.1}, {}): separate by {}",
                    c.effect,
                    c.delta_bic_gap,
                    collinearity(c.correlation, c.vif),
                    c.separate_by
                );
            }
        }
        if self.ranking.len() > 15 {
            let _ = writeln!(
                s,
                "  ... {} more candidates in --json",
                self.ranking.len() - 15
            );
        }
        // The ranking tests each candidate against the model as given; forward selection tests
        // each against the ones accepted before it, so an effect can pass only there.
        if self.accepted.is_empty() {
            let _ = writeln!(s, "accepted: none");
        } else {
            let _ = writeln!(
                s,
                "accepted by forward selection (each tested on top of those before it on its channel):"
            );
            for r in &self.accepted {
                let _ = writeln!(
                    s,
                    "  {} on {} (dBIC {:.1}, p {:.2e}, CV {})",
                    r.effect,
                    r.channel,
                    r.delta_bic,
                    r.p_value,
                    cv_phrase(r.cv_rmse_gain_pct)
                );
            }
        }
        for (ch, b) in &self.residual_rms_before {
            let _ = writeln!(
                s,
                "  {ch}: residual RMS {b:.5} -> {:.5} (noise floor {:.5})",
                self.residual_rms_after[ch], self.noise_floor_rms[ch]
            );
        }
        let _ = writeln!(
            s,
            "flagged cells: {} before, {} after",
            self.flagged_cells.len(),
            self.flagged_cells_after.len()
        );
        for u in &self.unexplained {
            let _ = writeln!(s, "  {u}");
        }
        if let Some(d) = &self.discovery {
            discovery(&mut s, d);
        }
        s
    }
}

/// The `--discover` part of the diagnosis text.
fn discovery(s: &mut String, d: &rins_mvm::discover::DiscoveryReport) {
    let terms: usize = d.library_terms.iter().map(|(_, n)| n).sum();
    let _ = writeln!(
        s,
        "discovery: {terms} library terms over the channels (gate Bonferroni over {}), bootstrap over runs x{}",
        d.tests, d.bootstrap_resamples
    );
    if d.proposals.is_empty() {
        let _ = writeln!(s, "  nothing passes the gate");
    }
    for p in &d.proposals {
        let _ = writeln!(s, "  proposal custom:{} ({})", p.name, p.sensor);
        for t in &p.terms {
            let _ = writeln!(
                s,
                "    {} {}: {} [{}, {}] {}, dBIC {:.1}, p {:.2e}, CV {}, ERR {:.4}, bootstrap {:.2}",
                t.channel,
                t.term,
                num(t.coefficient),
                num(t.ci95[0]),
                num(t.ci95[1]),
                t.unit,
                t.delta_bic,
                t.p_value,
                cv_phrase(t.cv_rmse_gain_pct),
                t.err,
                t.bootstrap_frequency
            );
            for c in &t.confusable_with {
                let _ = writeln!(
                    s,
                    "      confusable with {} ({}): separate by {}",
                    c.effect,
                    collinearity(c.correlation, c.vif),
                    c.separate_by
                );
            }
        }
        if let Some(t) = &p.toml {
            for l in t.lines() {
                let _ = writeln!(s, "    {l}");
            }
        }
    }
    for x in &d.superseded {
        let _ = writeln!(
            s,
            "  {}: {} explains the residual better than {} (dBIC {:.1} vs {:.1}): {} is reported confusable, not accepted",
            x.channel, x.by, x.effect, x.delta_bic_by, x.delta_bic_effect, x.effect
        );
    }
    for x in &d.identical {
        let _ = writeln!(
            s,
            "  {}: {} is {} on this data{}: tested as the catalogue effect, not proposed",
            x.channel,
            x.term,
            x.effect,
            if x.by_definition {
                " (the same regressor by definition: no experiment separates them)"
            } else {
                " (identical on this data; a run that excites them differently would split them)"
            }
        );
    }
    for x in &d.dependent {
        let _ = writeln!(
            s,
            "  {}: {}, {} and {} are linearly dependent on this data ({} = {:.4e}·{} {} {:.4e}·{}): their coefficients are determined only together, each one's value depends on which others are fitted",
            x.channel,
            x.term,
            x.on[0],
            x.on[1],
            x.term,
            x.weights[0],
            x.on[0],
            if x.weights[1] < 0.0 { "−" } else { "+" },
            x.weights[1].abs(),
            x.on[1]
        );
    }
    for t in &d.refused {
        let _ = writeln!(
            s,
            "  nearest miss on {}: {} (dBIC {:.1}, p {:.2e}, CV {})",
            t.channel,
            t.term,
            t.delta_bic,
            t.p_value,
            cv_phrase(t.cv_rmse_gain_pct)
        );
    }
}

/// A coefficient as printed: scientific notation for magnitudes below 10⁻³ (so a small
/// coefficient never reads "-0.0000"), "n/a" when there is none.
fn num(v: f64) -> String {
    if !v.is_finite() {
        "n/a".into()
    } else if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.3e}")
    } else {
        format!("{v:.4}")
    }
}

/// Correlation and variance inflation of a confusable pair as printed: "identical on this
/// data" when the VIF is beyond any numerical meaning, "n/a" where they were not computed.
fn collinearity(rho: f64, vif: f64) -> String {
    let rho = if rho.is_finite() {
        format!("rho {rho:.3}")
    } else {
        "rho n/a".into()
    };
    if !vif.is_finite() {
        format!("{rho}, VIF n/a")
    } else if vif > 1e9 {
        format!("{rho}, identical on this data")
    } else {
        format!("{rho}, VIF {vif:.0}")
    }
}

/// A cross-validated gain in a table's column: `0.12`, or `n/a` when no fold could judge the
/// candidate (NaN: `rins_mvm::fit::paired_cv`).
pub(crate) fn cv_cell(gain_pct: f64) -> String {
    if gain_pct.is_nan() {
        "n/a".into()
    } else {
        format!("{gain_pct:.2}")
    }
}

/// A cross-validated gain in a sentence: `0.12 %`, or `n/a (no fold can judge it)`.
pub(crate) fn cv_phrase(gain_pct: f64) -> String {
    if gain_pct.is_nan() {
        "n/a (no fold can judge it)".into()
    } else {
        format!("{gain_pct:.2} %")
    }
}
