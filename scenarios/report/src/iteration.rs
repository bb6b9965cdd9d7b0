//! How `rins diagnose --iterate` is shown: the terminal text of each step (accepted terms,
//! coefficients with 95 % intervals, residual against floor, flagged cells), the history figure
//! ("watch the error fall": residual/floor per channel against step), the cell map before and
//! after, and the HTML page.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::style::RGBColor;
use rins_mvm::iterate::IterationReport;
use rins_mvm::{CHANNELS, Fate};

use crate::figures::plot::{Kind, Line, Panel, write_figure};

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];
const GREY: RGBColor = RGBColor(110, 110, 110);

/// A coefficient as printed: scientific notation below 1e-3, "n/a" when there is none.
pub fn number(v: Option<f64>) -> String {
    match v {
        Some(v) if v.is_finite() && v != 0.0 && v.abs() < 1e-3 => format!("{v:.3e}"),
        Some(v) if v.is_finite() => format!("{v:.4}"),
        _ => "n/a".into(),
    }
}

/// The terminal text of an iteration.
pub fn render_text(r: &IterationReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "Iterating on {} ({} steps)", r.source, r.steps.len());
    for st in &r.steps {
        let lv: Vec<String> = st
            .levels
            .iter()
            .map(|l| format!("{} {:.2}", l.channel, l.ratio))
            .collect();
        let _ = writeln!(
            s,
            "\nstep {}: residual / floor: {}; {} cells flagged",
            st.step,
            lv.join(", "),
            st.flagged_cells
        );
        for t in &st.accepted {
            let _ = writeln!(
                s,
                "  {} {} ({}, {}){}: joint fit dBIC {:.1}, {}{}",
                if t.kept { "accepted" } else { "dropped " },
                t.effect,
                t.channel,
                match &t.replaces {
                    Some(out) =>
                        format!("in place of {out}: joint-fit BIC {:.1} lower", -t.delta_bic),
                    None => format!("dBIC {:.1}", t.delta_bic),
                },
                if t.parents.is_empty() {
                    String::new()
                } else {
                    format!(" with {}", t.parents.join(", "))
                },
                -t.joint_delta_bic,
                if t.stability.is_finite() {
                    format!("stable in {:.0} % of run resamples", 100.0 * t.stability)
                } else {
                    "no run resampling (fewer than 3 runs)".into()
                },
                if t.kept {
                    ""
                } else {
                    " -> not fitted (it does not survive the joint fit)"
                },
            );
            if let Some(tau) = &t.tau {
                let _ = writeln!(
                    s,
                    "    time constant {:.4} s, 95 % [{}{:.4}, {:.4}{}] s (profile likelihood)",
                    tau.tau_s,
                    if tau.open[0] { "≤ " } else { "" },
                    tau.ci95_s[0],
                    tau.ci95_s[1],
                    if tau.open[1] { " or more" } else { "" },
                );
            }
            if !t.confusable_with.is_empty() {
                let _ = writeln!(
                    s,
                    "    confusable on this data with {}",
                    t.confusable_with.join(", ")
                );
            }
        }
        for c in &st.coefficients {
            let what = match c.fate {
                Fate::Written => format!(
                    "{} [{}, {}] written (was {})",
                    number(c.fitted),
                    number(c.ci95.map(|x| x[0])),
                    number(c.ci95.map(|x| x[1])),
                    number(Some(c.model))
                ),
                Fate::Kept => format!("{} kept: {}", number(Some(c.model)), c.reason),
                Fate::Null => format!("{} kept (null): {}", number(Some(c.model)), c.reason),
            };
            let _ = writeln!(s, "    {} = {what}", c.key);
        }
    }
    let _ = writeln!(s, "\nstopped: {}", r.stop);
    for u in &r.unexplained {
        let _ = writeln!(s, "  {u}");
    }
    if !r.closest_to_gate.is_empty() {
        let _ = writeln!(s, "closest to the gate (not passed):");
        for m in &r.closest_to_gate {
            let _ = writeln!(
                s,
                "  {} on {}: dBIC {:.1}, p {:.2e}, CV {}: {}",
                m.effect,
                m.channel,
                m.delta_bic,
                m.p_value,
                crate::text::diagnosis_text::cv_phrase(m.cv_rmse_gain_pct),
                m.failed
            );
        }
    }
    s
}

/// Writes `iteration_history` (residual/floor per channel against step) and
/// `cells_before_after` (each cell's z before and after) as SVG and PNG into `dir`.
pub fn write_figures(dir: &Path, r: &IterationReport) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let steps = r.steps.len();
    let floor = |lo: f64| vec![(lo, 1.0), ((steps.max(2) - 1) as f64, 1.0)];
    let mut panels = Vec::new();
    for (title, range) in [("gyros", 0..3), ("accelerometers", 3..6)] {
        let mut lines: Vec<Line> = range
            .map(|c| {
                Line::new(
                    CHANNELS[c],
                    r.steps
                        .iter()
                        .map(|st| (st.step as f64, st.levels[c].ratio))
                        .collect(),
                    COLORS[c],
                    Kind::Solid,
                )
            })
            .collect();
        lines.push(Line::new("noise floor", floor(0.0), GREY, Kind::Dashed));
        panels.push(
            Panel::new(
                format!("{title}: residual RMS / noise floor after each step"),
                "residual / floor",
                lines,
            )
            .whole_x(),
        );
    }
    files.extend(write_figure(
        &dir.join("iteration_history.svg"),
        "Iterating to the floor: the error falling step by step",
        "step (0: the model as given)",
        &panels,
    )?);
    // The cell map: each cell's z (mean residual in units of its floor), before and after.
    let mut panels = Vec::new();
    let zc = r.z_critical;
    for ch in CHANNELS {
        let pick = |cells: &[rins_mvm::Cell]| -> Vec<(f64, f64)> {
            cells
                .iter()
                .filter(|c| c.channel == ch)
                .enumerate()
                .map(|(i, c)| (i as f64, c.z))
                .collect()
        };
        let before = pick(&r.cells_before);
        let n = before.len().max(1) as f64;
        panels.push(Panel::new(
            format!("{ch}: cells (position x temperature x time) before and after"),
            "z = mean residual / floor",
            vec![
                Line::new("model as given", before, GREY, Kind::Dots),
                Line::new("final model", pick(&r.cells_after), COLORS[0], Kind::Dots),
                Line::new(
                    "flag bound",
                    vec![(0.0, zc), (n, zc)],
                    COLORS[1],
                    Kind::Dashed,
                ),
                Line::new("", vec![(0.0, -zc), (n, -zc)], COLORS[1], Kind::Dashed),
            ],
        ));
    }
    files.extend(write_figure(
        &dir.join("cells_before_after.svg"),
        "The cell map before and after the iteration",
        "cell (in the order of the compare report)",
        &panels,
    )?);
    Ok(files)
}
