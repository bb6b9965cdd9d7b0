//! `rins paper sea`: the at-sea study. The paper's week (16-position scheme, Table 3 sensors)
//! on a ship at 10-15 kn with course changes and sea state 4-5, without and with azimuth
//! isolation, δβ uncompensated and compensated, over several seeds, beside the static reference
//! (the same sensors and seeds on the static carrier). The navigator starts aligned from truth
//! on the moving base. Runs on [`rins_verification::paper::sea`], Table 4's machinery.

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::style::RGBColor;
use rins_navigation::NavRecord;
use rins_plant::carrier::SeaRealisation;
use rins_verification::paper::{Band, SeaOptions, SeaReport, Table4Report};
use serde::Serialize;

use super::args::RerunArgs;
use super::paired_runs::check_runs_days;
use rins_report::figures::plot::{Kind, Line, Panel, write_svg};
use rins_report::html::results::sea::CASES;
use rins_scenario::file::Scenario;

/// Arguments of `rins paper sea`.
#[derive(clap::Args, Debug)]
pub struct SeaArgs {
    /// Seeds (each runs every case; both cores are used).
    #[arg(long, default_value_t = 8, allow_negative_numbers = true)]
    pub runs: i64,
    /// Navigation time in days.
    #[arg(long, default_value_t = 7.0, allow_negative_numbers = true)]
    pub days: f64,
    /// Scenario with a moving carrier (default: the built-in ship week).
    #[arg(long, default_value = "builtin:ship-16pos-week")]
    pub scenario: PathBuf,
    /// The sea of the seeds: `fixed` (one realisation for every seed, drawn from the
    /// scenario's `carrier.ship.sea.seed` if it fixes one, else from its run seed: the seeds
    /// differ in their sensors only, as over a route) or `per-run` (each seed draws its own sea).
    #[arg(long, value_enum, default_value_t = SeaOfSeeds::Fixed)]
    pub sea: SeaOfSeeds,
    /// IMU intervals per navigator update, 1 to 4 (`rins paper table4 --subsamples`; the
    /// figures in docs/carrier.md are with 1).
    #[arg(long, default_value = "1", value_parser = super::paired_runs::parse_subsamples)]
    pub subsamples: rins_navigation::Subsamples,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Output folder for sea.json, the figures and their data.
    #[arg(long, default_value = "out/sea")]
    pub out: PathBuf,
    /// Write a self-contained HTML report to DIR/report.html.
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// `--rerun DEST` and its bucket length (not recorded for this study).
    #[command(flatten)]
    pub viz: RerunArgs,
}

/// Which sea the seeds of `rins paper sea` sail.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeaOfSeeds {
    /// One realisation for every seed: a batch computes the ship's motion once (with azimuth
    /// isolation, one reference table that each seed's table is turned from), and the seeds'
    /// spread is the sensors'.
    Fixed,
    /// Each seed draws its own realisation from its run seed: the spread includes the sea's.
    PerRun,
}

/// Uncompensated case.
const UNC: RGBColor = RGBColor(200, 40, 40);
/// Compensated case.
const COMP: RGBColor = RGBColor(30, 90, 200);

/// What the end-error figure plots, per case (written to `sea_end_error.json` so a test can
/// compare it with `sea.json`).
#[derive(Clone, Debug, Serialize)]
pub struct EndErrorData {
    /// Case name.
    pub case: &'static str,
    /// Horizontal error at the end, uncompensated: median and 5-95 % band, nmi.
    pub uncompensated_nm: Band,
    /// The same, compensated.
    pub compensated_nm: Band,
    /// The noise-free pair's horizontal error at the end (every stochastic term off; the other
    /// deterministic errors stay, so only the pair's difference is δβ's own effect),
    /// uncompensated and compensated, nmi.
    pub noise_free_nm: [f64; 2],
}

/// Runs the study: sea.json, the figures, the table (or JSON), and with `--report` the page.
pub fn run(a: &SeaArgs) -> Result<()> {
    let runs = check_runs_days(a.runs, a.days)?;
    let sc = Scenario::load(&a.scenario)?;
    if sc.plant.carrier.is_static() {
        anyhow::bail!(
            "{}: rins paper sea needs a moving carrier ([carrier] kind = \"ship\" or \"trajectory\")",
            a.scenario.display()
        );
    }
    if a.viz.target()?.is_some() {
        eprintln!("rins paper sea: --rerun is not recorded for this study");
    }
    let mut ship = sc.plant.clone();
    let sea = &mut ship.carrier.ship.sea;
    match (a.sea, sea.realisation) {
        (SeaOfSeeds::Fixed, SeaRealisation::PerRun) => {
            sea.realisation = SeaRealisation::Fixed;
            sea.seed = sc.plant.seed;
        }
        (SeaOfSeeds::Fixed, SeaRealisation::Fixed) => {}
        (SeaOfSeeds::PerRun, _) => sea.realisation = SeaRealisation::PerRun,
    }
    let mut reference = sc.plant.clone();
    reference.carrier = Default::default();
    let opt = SeaOptions {
        ship,
        paired: rins_verification::paper::Table4Options {
            plant: reference,
            runs,
            duration_s: a.days * 86_400.0,
            compensation: None,
            nav: rins_experiments::NavRunConfig {
                subsamples: a.subsamples,
                ..rins_experiments::NavRunConfig::default()
            },
        },
    };
    let per_run = (opt.paired.duration_s * opt.ship.rate_hz) as u64;
    // Three cases × 2 navigators per seed, plus each case's noise-free pair and the ideal IMU
    // on each ship case (two navigators each).
    let pb = crate::progress::bar((6 * runs as u64 + 10) * per_run, "sea");
    let r = rins_verification::paper::sea(&opt, &|n| pb.inc(n));
    pb.finish_and_clear();
    super::create_dir(&a.out)?;
    std::fs::write(a.out.join("sea.json"), serde_json::to_string_pretty(&r)?)?;
    write_figures(&r, &a.out)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", rins_report::text::RenderText::render_text(&r));
        println!("  figures and sea.json in {}", a.out.display());
    }
    if let Some(dir) = &a.report {
        let page = rins_report::html::results::sea(&r, &a.out, dir)?;
        eprintln!("report: {}", page.display());
    }
    Ok(())
}

/// The end-error figure's data, per case.
pub fn end_error_data(r: &SeaReport) -> Vec<EndErrorData> {
    r.cases()
        .iter()
        .zip(CASES)
        .map(|((_, t), case)| EndErrorData {
            case,
            uncompensated_nm: t.uncompensated.horizontal_nm,
            compensated_nm: t.compensated.horizontal_nm,
            noise_free_nm: [
                t.noise_free.uncompensated.horizontal_nm,
                t.noise_free.compensated.horizontal_nm,
            ],
        })
        .collect()
}

fn hours(recs: &[NavRecord], f: &dyn Fn(&NavRecord) -> f64) -> Vec<(f64, f64)> {
    recs.iter().map(|x| (x.t_s / 3600.0, f(x))).collect()
}

/// Writes `sea_horizontal_error.svg` (first seed, envelopes per case), `sea_end_error.svg`
/// (categorical: median and 5-95 % band per case, side by side, and the noise-free pair)
/// and `sea_end_error.json` (the plotted numbers).
pub fn write_figures(r: &SeaReport, out: &Path) -> Result<()> {
    let nm = rins_navigation::errors::nmi;
    let panels: Vec<Panel> = r
        .cases()
        .iter()
        .map(|(name, t): &(&str, &Table4Report)| {
            let s = &t.first_seed;
            Panel::new(
                format!("{name}: horizontal error (first seed)"),
                "error (nmi)",
                vec![
                    Line::new(
                        "uncompensated",
                        hours(&s.uncompensated, &|x| nm(x.horizontal_m)),
                        UNC,
                        Kind::Envelope,
                    ),
                    Line::new(
                        "compensated",
                        hours(&s.compensated, &|x| nm(x.horizontal_m)),
                        COMP,
                        Kind::Envelope,
                    ),
                ],
            )
        })
        .collect();
    write_svg(
        &out.join("sea_horizontal_error.svg"),
        "At sea: horizontal error, static reference and ship without / with azimuth isolation",
        "time (h)",
        &panels,
    )?;
    let data = end_error_data(r);
    std::fs::write(
        out.join("sea_end_error.json"),
        serde_json::to_string_pretty(&data)?,
    )?;
    write_svg(
        &out.join("sea_end_error.svg"),
        END_ERROR_TITLE,
        END_ERROR_X,
        &end_error_panels(&data, r.runs),
    )
}

/// Title of `sea_end_error`.
pub const END_ERROR_TITLE: &str = "At sea: end-of-run horizontal error per case";
/// x label of `sea_end_error`.
pub const END_ERROR_X: &str = "case";

/// The panels of `sea_end_error` for `data` over `runs` seeds: per case the median (dot) and
/// 5-95 % band, uncompensated left and compensated right of the category; below, the
/// noise-free pair's end errors.
pub fn end_error_panels(data: &[EndErrorData], runs: usize) -> Vec<Panel<'static>> {
    // Side by side at each category: uncompensated left, compensated right; the dot is the
    // median (the 5-95 % band is not symmetric about it).
    let bands = |dx: f64, f: &dyn Fn(&EndErrorData) -> Band| {
        data.iter()
            .enumerate()
            .flat_map(|(k, d)| {
                let (x, b) = (k as f64 + dx, f(d));
                [(x, b.p05), (x, b.median), (x, b.p95)]
            })
            .collect::<Vec<_>>()
    };
    let medians = |dx: f64, f: &dyn Fn(&EndErrorData) -> f64| {
        data.iter()
            .enumerate()
            .map(|(k, d)| (k as f64 + dx, f(d)))
            .collect::<Vec<_>>()
    };
    let end = Panel::new(
        format!("Horizontal error at the end: median (dot) and 5-95 % over {runs} seeds"),
        "error (nmi)",
        vec![
            Line::new(
                "uncompensated",
                bands(-0.12, &|d| d.uncompensated_nm),
                UNC,
                Kind::Interval,
            ),
            Line::new(
                "compensated",
                bands(0.12, &|d| d.compensated_nm),
                COMP,
                Kind::Interval,
            ),
        ],
    )
    .categorical(&CASES);
    let nf = Panel::new(
        "Noise-free pair (every stochastic term off): horizontal error at the end",
        "error (nmi)",
        vec![
            Line::new(
                "uncompensated",
                medians(-0.12, &|d| d.noise_free_nm[0]),
                UNC,
                Kind::Dots,
            ),
            Line::new(
                "compensated",
                medians(0.12, &|d| d.noise_free_nm[1]),
                COMP,
                Kind::Dots,
            ),
        ],
    )
    .categorical(&CASES);
    vec![end, nf]
}
