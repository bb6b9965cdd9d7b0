//! What the paired week studies share (`rins paper`, `paper table4`, `paper table5`, `sea`):
//! their `--runs`/`--days`/`--subsamples` checks and the paired uncompensated/compensated run
//! with its progress, JSON and figures. Each command imports it; none imports another.

use std::path::Path;

use anyhow::Result;
use rins_plant::message::Num;
use rins_verification::paper::{Table4Options, Table4Report};

use super::args::{RerunArgs, whole};
use rins_report::figures::paper::write_table4_figures;
use rins_scenario::file::Scenario;

/// Checks `--runs` and `--days` of the paired paper runs; returns the number of seeds.
pub fn check_runs_days(runs: i64, days: f64) -> Result<usize> {
    let runs = whole("--runs", runs, 1, usize::MAX, "seed")?;
    if !(days > 0.0 && days <= 60.0) {
        anyhow::bail!("--days: expected a number in (0, 60], got {}", Num(days));
    }
    Ok(runs)
}

/// Runs the paired uncompensated/compensated study with a progress bar and writes
/// `<name>.json` and the figures to `out` (and the Rerun recording when asked for).
pub fn run_paired(
    opt: &Table4Options,
    name: &str,
    out: &Path,
    sc: &Scenario,
    viz: &RerunArgs,
) -> Result<Table4Report> {
    let target = viz.target()?;
    let total = (2 * opt.runs as u64 + 2) * (opt.duration_s * opt.plant.rate_hz) as u64;
    let pb = crate::progress::bar(total, name);
    let r = rins_verification::paper::table4(opt, &|n| pb.inc(n));
    pb.finish_and_clear();
    super::create_dir(out)?;
    std::fs::write(
        out.join(format!("{name}.json")),
        serde_json::to_string_pretty(&r)?,
    )?;
    let figures = if name == "table5" {
        ["Figure 9", "Figure 10"]
    } else {
        ["Figure 2", "Figure 3"]
    };
    write_table4_figures(&r, out, figures)?;
    #[cfg(feature = "rerun")]
    if let Some(t) = &target {
        let text = if name == "table5" {
            r.to_text_table5()
        } else {
            rins_report::text::RenderText::render_text(&r)
        };
        crate::recordings::record_paired(
            t,
            viz.rerun_bucket_s,
            sc,
            &opt.plant,
            opt.duration_s,
            &r,
            &text,
        )?;
        eprintln!("rerun: recorded -> {}", viz.dest());
    }
    #[cfg(not(feature = "rerun"))]
    let _ = (target, sc);
    Ok(r)
}

/// `--subsamples`: a count the navigator takes ([`rins_navigation::Subsamples`]), or the range.
pub(crate) fn parse_subsamples(s: &str) -> Result<rins_navigation::Subsamples, String> {
    let n: u8 = s
        .parse()
        .map_err(|_| format!("`{s}` is not a count of intervals (1 to 4)"))?;
    rins_navigation::Subsamples::new(n)
}
