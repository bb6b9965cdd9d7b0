//! Text of `rins sweep`: per output, one row per point with the swept values and the median
//! and 5–95 % band over the seeds for the uncompensated and the compensated navigator.

use std::fmt::Write;

use super::RenderText;
use rins_sweep::{NAVIGATORS, SweepReport, value_text};

impl RenderText for SweepReport {
    fn render_text(&self) -> String {
        let mut s = format!(
            "Sweep {}: {} points x {} seeds x {:.4} days on {} (alignment {}, {}; wall {:.1} s)\n",
            self.name,
            self.points.len(),
            self.seeds.len(),
            self.days,
            self.scenario,
            self.alignment,
            self.combine,
            self.wall_s
        );
        if !self.description.is_empty() {
            let _ = writeln!(s, "  {}", self.description);
        }
        let heads: Vec<String> = self.parameters.iter().map(|p| p.heading()).collect();
        let widths: Vec<usize> = heads
            .iter()
            .enumerate()
            .map(|(i, h)| {
                self.points
                    .iter()
                    .map(|p| value_text(&p.values[i]).chars().count())
                    .chain([h.chars().count()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        for o in &self.outputs {
            let _ = writeln!(
                s,
                "\n{} ({}), median [5 %, 95 %] over the seeds:",
                o.what, o.unit
            );
            s.push(' ');
            for (h, w) in heads.iter().zip(&widths) {
                let _ = write!(s, " {h:<w$}");
            }
            for nav in NAVIGATORS {
                let _ = write!(s, "   {nav:<30}");
            }
            s.push('\n');
            for p in &self.points {
                s.push(' ');
                for (v, w) in p.values.iter().zip(&widths) {
                    let _ = write!(s, " {:<w$}", value_text(v));
                }
                for n in 0..NAVIGATORS.len() {
                    let b = p.band(n, &o.name);
                    let _ = write!(s, "   {:>9.4} [{:>8.4}, {:>8.4}]", b.median, b.p05, b.p95);
                }
                s.push('\n');
            }
        }
        s
    }
}
