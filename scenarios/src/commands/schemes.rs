//! `rins schemes analyse|design|verify`: rotation schemes as a design space (docs/schemes.md).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use rins_plant::effects::CustomSpec;
use rins_schemes::analyse::{AnalyseOptions, SchemeAnalysis, analyse_scheme};
use rins_schemes::bound::{CLASSES, ClassBound, class_bound, coefficient_table};
use rins_schemes::design::{DesignOptions, DesignReport, design};
use rins_schemes::effects::EffectSet;
use rins_schemes::library;
use rins_schemes::response::StaticResponse;
use rins_schemes::{SchemeFile, basis, simulate};
use serde::Serialize;

use rins_report::figures::plot::{Kind, Line, PALETTE, Panel, write_figure};

/// The scheme commands.
#[derive(clap::Subcommand, Debug)]
pub enum SchemesCommand {
    /// Per-cycle residual of every effect under each scheme, and what it does after N days.
    Analyse(AnalyseArgs),
    /// Search schemes for the smallest worst case over an effect class.
    Design(DesignArgs),
    /// Week-long runs of the plant and navigator against the analysis.
    Verify(VerifyArgs),
}

/// Arguments of `rins schemes analyse`.
#[derive(clap::Args, Debug)]
pub struct AnalyseArgs {
    /// Built-in scheme names or scheme files (default: every built-in scheme).
    pub schemes: Vec<String>,
    /// Sensor preset whose catalogue terms are analysed at their magnitudes.
    #[arg(long, default_value = "nav-grade-full")]
    pub preset: String,
    /// A TOML file (a scenario file will do) whose `[[sensor.gyro.custom]]` and
    /// `[[sensor.accel.custom]]` effects are analysed too.
    #[arg(long)]
    pub declared: Option<PathBuf>,
    /// Bound on every coefficient of the classes' worst cases, °/h.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub bound_dph: f64,
    /// Days of the navigation figures.
    #[arg(long, default_value_t = 7.0, allow_negative_numbers = true)]
    pub days: f64,
    /// Latitude of the static navigator, °.
    #[arg(long, default_value_t = 36.6, allow_negative_numbers = true)]
    pub lat_deg: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Write analysis.json and the figure into this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the HTML report (verdict, tables, figure) as DIR/report.html.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// Arguments of `rins schemes design`.
#[derive(clap::Args, Debug)]
pub struct DesignArgs {
    /// Class to minimise: general-b(u), general-anisotropic or plant-delta-beta.
    #[arg(long, default_value = "general-b(u)")]
    pub class: String,
    /// Bound on every coefficient of the class, °/h.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub bound_dph: f64,
    /// Positions per cycle searched (even).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "8,16,32",
        allow_negative_numbers = true
    )]
    pub positions: Vec<usize>,
    /// Dwell after every move, s.
    #[arg(long, default_value_t = 180.0, allow_negative_numbers = true)]
    pub dwell_s: f64,
    /// Table rate, °/s.
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub rate_dps: f64,
    /// Table acceleration, °/s² (inf: constant-rate moves).
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    pub accel_dps2: f64,
    /// Longest cycle, s.
    #[arg(long, default_value_t = 14_400.0, allow_negative_numbers = true)]
    pub max_cycle_s: f64,
    /// Seed of the search.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub seed: u64,
    /// Designs reported (and written).
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    pub top: usize,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Write design.json and each design as a scheme file into this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the HTML report as DIR/report.html.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// Arguments of `rins schemes verify`.
#[derive(clap::Args, Debug)]
pub struct VerifyArgs {
    /// Built-in scheme names or scheme files.
    #[arg(required = true)]
    pub schemes: Vec<String>,
    /// Simulated days.
    #[arg(long, default_value_t = 7.0, allow_negative_numbers = true)]
    pub days: f64,
    /// IMU rate, Hz.
    #[arg(long, default_value_t = 100.0, allow_negative_numbers = true)]
    pub rate_hz: f64,
    /// δβ of the plant's model on every axis, °/h (Table 3: 0.005).
    #[arg(long, default_value_t = 0.005, allow_negative_numbers = true)]
    pub delta_beta_dph: f64,
    /// Bound of the general class whose worst-case coefficients are declared and run, °/h.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub bound_dph: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs a scheme command.
pub fn run(cmd: &SchemesCommand) -> Result<()> {
    match cmd {
        SchemesCommand::Analyse(a) => analyse(a),
        SchemesCommand::Design(a) => run_design(a),
        SchemesCommand::Verify(a) => verify(a),
    }
}

fn check_common(bound_dph: f64, days: f64, lat_deg: f64) -> Result<()> {
    if !(bound_dph.is_finite() && bound_dph > 0.0) {
        bail!("--bound-dph: expected a finite value > 0, got {bound_dph}");
    }
    if !(days.is_finite() && days > 0.0 && days <= 366.0) {
        bail!("--days: expected a value in (0, 366], got {days}");
    }
    if !(lat_deg.is_finite() && lat_deg.abs() < 89.0) {
        bail!("--lat-deg: expected a value in (-89, 89), got {lat_deg}");
    }
    Ok(())
}

fn schemes_of(args: &[String]) -> Result<Vec<SchemeFile>> {
    if args.is_empty() {
        return Ok(library::all_built_in());
    }
    args.iter()
        .map(|a| library::resolve(a).map_err(Into::into))
        .collect()
}

/// The declared effects of a TOML file's `sensor.gyro.custom` and `sensor.accel.custom`.
fn declared(path: &Path) -> Result<(Vec<CustomSpec>, Vec<CustomSpec>)> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let v: toml::Table = toml::from_str(&text).with_context(|| path.display().to_string())?;
    let list = |sensor: &str| -> Result<Vec<CustomSpec>> {
        match v
            .get("sensor")
            .and_then(|s| s.get(sensor))
            .and_then(|s| s.get("custom"))
        {
            None => Ok(Vec::new()),
            Some(c) => c
                .clone()
                .try_into()
                .with_context(|| format!("{}: sensor.{sensor}.custom", path.display())),
        }
    };
    let (g, a) = (list("gyro")?, list("accel")?);
    if g.is_empty() && a.is_empty() {
        bail!(
            "{}: no [[sensor.gyro.custom]] or [[sensor.accel.custom]] tables",
            path.display()
        );
    }
    Ok((g, a))
}

/// `rins schemes analyse`'s output.
#[derive(Serialize)]
struct AnalyseReport {
    analyses: Vec<SchemeAnalysis>,
    bounds: Vec<ClassBound>,
    wall_s: f64,
}

fn analyse(a: &AnalyseArgs) -> Result<()> {
    check_common(a.bound_dph, a.days, a.lat_deg)?;
    let t0 = std::time::Instant::now();
    let schemes = schemes_of(&a.schemes)?;
    let sensor = rins_plant::presets::preset(&a.preset).with_context(|| {
        format!(
            "--preset: expected one of {}, got {}",
            rins_plant::presets::PRESET_NAMES.join(", "),
            a.preset
        )
    })?;
    let lat = a.lat_deg.to_radians();
    let g = rins_plant::earth::normal_gravity(lat, 0.0);
    let mut set = EffectSet::empty(g)
        .with_earth_rate(lat)
        .with_catalogue(&sensor);
    if let Some(p) = &a.declared {
        let (gy, ac) = declared(p)?;
        set = set
            .with_declared(&gy, false)
            .with_context(|| p.display().to_string())?
            .with_declared(&ac, true)
            .with_context(|| p.display().to_string())?;
    }
    let set = set
        .with_general()
        .with_delta_beta_axes(&sensor.gyro.position_bias);
    let opt = AnalyseOptions {
        lat_rad: lat,
        days: a.days,
        time_resolved: true,
    };
    let resp = StaticResponse::new(lat, a.days);
    use rayon::prelude::*;
    let analyses: Vec<SchemeAnalysis> = schemes
        .par_iter()
        .map(|s| analyse_scheme(s, &set, &opt, &resp).with_context(|| s.name.clone()))
        .collect::<Result<_>>()?;
    let bounds: Vec<ClassBound> = analyses
        .iter()
        .flat_map(|an| {
            CLASSES
                .iter()
                .filter_map(|c| class_bound(an, c, a.bound_dph))
        })
        .collect();
    let report = AnalyseReport {
        analyses,
        bounds,
        wall_s: t0.elapsed().as_secs_f64(),
    };
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        std::fs::write(
            dir.join("analysis.json"),
            serde_json::to_string_pretty(&report)?,
        )?;
        write_analysis_figure(&report, dir)?;
    }
    if let Some(dir) = &a.report {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        write_analysis_figure(&report, dir)?;
        let page = rins_report::html::results::schemes_analyse(&report, dir, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", analysis_text(&report));
    }
    Ok(())
}

/// A metre figure for the text tables: values below 0.05 m print as 0.0 (no "-0.0").
fn metres(v: f64) -> String {
    if v.abs() < 0.05 {
        "0.0".into()
    } else {
        format!("{v:.1}")
    }
}

fn analysis_text(r: &AnalyseReport) -> String {
    let mut s = String::new();
    let a0 = &r.analyses[0];
    s.push_str(&format!(
        "Per-cycle residuals and the static navigator after {} days at {:.1} deg (east error, m; Schuler-averaged)\n",
        a0.days, a0.lat_deg
    ));
    s.push_str(&format!("{:34}", "effect"));
    for a in &r.analyses {
        s.push_str(&format!(" {:>17}", a.scheme));
    }
    s.push('\n');
    s.push_str(&format!("{:34}", "cycle (s) / positions"));
    for a in &r.analyses {
        s.push_str(&format!(" {:>11.1} / {:>3}", a.cycle_s, a.positions));
    }
    s.push('\n');
    for (k, e) in a0.effects.iter().enumerate() {
        if e.group == rins_schemes::effects::Group::General
            || e.effect.starts_with("gyro.position_bias.")
        {
            continue;
        }
        s.push_str(&format!("{:34}", e.effect));
        for a in &r.analyses {
            s.push_str(&format!(" {:>17}", metres(a.effects[k].after.east_m)));
        }
        s.push('\n');
    }
    s.push_str(&format!(
        "\nWorst case over each class, |coefficients| <= {} deg/h (horizontal, m)\n",
        r.bounds[0].bound_dph
    ));
    for class in CLASSES {
        s.push_str(&format!("{:34}", class));
        for a in &r.analyses {
            let b = r
                .bounds
                .iter()
                .find(|b| b.scheme == a.scheme && b.class == class);
            s.push_str(&format!(
                " {:>17.1}",
                b.map_or(f64::NAN, |b| b.worst_horizontal_m)
            ));
        }
        s.push('\n');
    }
    if let Some(b) = r.bounds.iter().find(|b| b.class == CLASSES[0]) {
        s.push_str(&format!(
            "{:34} {:>17.1}  (b_i = B u_i: the same under every scheme)\n",
            "invariant member", b.invariant_horizontal_m
        ));
    }
    // Both methods exist for constant-rate moves; compare where the residual is not zero to
    // rounding (a cancelled residual has no relative precision).
    let pairs: Vec<f64> = r
        .analyses
        .iter()
        .flat_map(|a| {
            a.effects.iter().filter_map(|e| {
                let d = e.methods_rel_diff?;
                (nalgebra::Vector3::from(e.per_cycle).norm() > 1e-9 * e.modulated).then_some(d)
            })
        })
        .collect();
    if !pairs.is_empty() {
        s.push_str(&format!(
            "\nQuadrature against exact integration ({} effect-scheme pairs with constant-rate moves and a residual): largest relative difference {:.1e}\n",
            pairs.len(),
            pairs.iter().cloned().fold(0.0, f64::max)
        ));
    }
    for (k, why) in &a0.skipped {
        s.push_str(&format!("not analysed: {k}: {why}\n"));
    }
    s.push_str(&format!("wall time {:.2} s\n", r.wall_s));
    s
}

/// A short category name for an effect key (the figure's x axis).
fn short(key: &str) -> String {
    key.replace("gyro.", "g.")
        .replace("accel.", "a.")
        .replace("custom.", "")
        .replace("scale_factor_asymmetry", "asym")
        .replace("scale_factor", "SF")
        .replace("misalignment", "mis")
        .replace("g_sensitivity", "gsens")
        .replace("position_bias", "dbeta")
        .replace("dither_bias", "dither")
        .replace("nav_field_bias", "field")
}

/// Two figures: each catalogue (and declared) effect's east error under every scheme, and the
/// worst case over each class; log scale, values below 1 m drawn at 1 m.
fn write_analysis_figure(r: &AnalyseReport, dir: &Path) -> Result<()> {
    let a0 = &r.analyses[0];
    let keys: Vec<&str> = a0
        .effects
        .iter()
        .filter(|e| {
            e.group != rins_schemes::effects::Group::General
                && !e.effect.starts_with("gyro.position_bias.")
        })
        .map(|e| e.effect.as_str())
        .collect();
    let value = |m: f64| m.abs().max(1.0).log10();
    let mut lines = Vec::new();
    let mut class_lines = Vec::new();
    for (j, a) in r.analyses.iter().enumerate() {
        let shift = (j as f64 - 0.5 * (r.analyses.len() - 1) as f64) * 0.12;
        let pts = keys
            .iter()
            .enumerate()
            .map(|(k, key)| {
                (
                    k as f64 + shift,
                    value(a.effect(key).map_or(0.0, |e| e.after.east_m)),
                )
            })
            .collect();
        lines.push(Line::new(
            &a.scheme,
            pts,
            PALETTE[j % PALETTE.len()],
            Kind::Dots,
        ));
        let cpts = CLASSES
            .iter()
            .enumerate()
            .filter_map(|(k, c)| {
                r.bounds
                    .iter()
                    .find(|b| b.scheme == a.scheme && b.class == *c)
                    .map(|b| (k as f64 + shift, value(b.worst_horizontal_m)))
            })
            .collect();
        class_lines.push(Line::new(
            &a.scheme,
            cpts,
            PALETTE[j % PALETTE.len()],
            Kind::Dots,
        ));
    }
    let names: Vec<String> = keys.iter().map(|k| short(k)).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    write_figure(
        &dir.join("schemes_effects"),
        &format!(
            "East error of each effect after {} days, schemes side by side",
            a0.days
        ),
        "effect (g. gyro, a. accelerometer)",
        &[
            Panel::new("below 1 m drawn at 1 m", "log10 |east error| (m)", lines)
                .categorical(&names),
        ],
    )?;
    write_figure(
        &dir.join("schemes_classes"),
        &format!(
            "Worst case over each class after {} days, coefficients within {} deg/h",
            a0.days, r.bounds[0].bound_dph
        ),
        "class",
        &[Panel::new(
            "below 1 m drawn at 1 m",
            "log10 worst horizontal (m)",
            class_lines,
        )
        .categorical(&["general b(u)", "anisotropic", "plant dbeta"])],
    )?;
    Ok(())
}

fn design_text(r: &DesignReport) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "Searched class {} (every coefficient within {} deg/h), {} candidates judged, {} refused (a constant error survived or the cycle was too long), {:.1} s\n",
        r.options.class, r.options.bound_dph, r.evaluated, r.refused, r.wall_s
    ));
    s.push_str(&format!(
        "{:40} {:>9} {:>16} {:>20} {:>17} {:>11}\n",
        "scheme",
        "cycle s",
        "general-b(u) m",
        "general-anisotropic m",
        "plant-delta-beta m",
        "constants"
    ));
    for c in std::iter::once(&r.reference).chain(r.best.iter()) {
        s.push_str(&format!(
            "{:40} {:>9.0} {:>16.1} {:>20.1} {:>17.1} {:>11.1e}\n",
            c.file.name,
            c.cycle_s,
            c.bounds[0].worst_horizontal_m,
            c.bounds[1].worst_horizontal_m,
            c.bounds[2].worst_horizontal_m,
            c.constants_max_fraction
        ));
    }
    let k = CLASSES
        .iter()
        .position(|c| *c == r.options.class)
        .unwrap_or(0);
    if let Some(best) = r.best.first() {
        let ratio = best.bounds[k].worst_horizontal_m / r.reference.bounds[k].worst_horizontal_m;
        s.push_str(&format!(
            "best against the 16-position scheme on {}: {:.3} ({})\n",
            r.options.class,
            ratio,
            if ratio <= 0.5 { "halved" } else { "not halved" }
        ));
    }
    s.push_str(&format!(
        "general-b(u): no scheme goes below the invariant member b_i = B u_i: {:.1} m (the 16-position scheme: {:.1} m)\n",
        r.invariant_m, r.reference.bounds[0].worst_horizontal_m
    ));
    s.push_str(&format!(
        "general-anisotropic: no scheme on this table goes below {:.1} m (body x never vertical)\n",
        r.anisotropic_floor_m
    ));
    if r.options.class == "plant-delta-beta" {
        s.push_str("caveat: the plant's delta-beta depends on u_z alone; a scheme that keeps z near horizontal turns it into a constant that rotation cancels, an artefact of the model\n");
    }
    s
}

fn run_design(a: &DesignArgs) -> Result<()> {
    let opt = DesignOptions {
        class: a.class.clone(),
        bound_dph: a.bound_dph,
        positions: a.positions.clone(),
        dwell_s: a.dwell_s,
        rate_dps: a.rate_dps,
        accel_dps2: a.accel_dps2,
        max_cycle_s: a.max_cycle_s,
        seed: a.seed,
        top: a.top,
        ..DesignOptions::default()
    };
    let r = design(&opt, &|_| {})?;
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        std::fs::write(dir.join("design.json"), serde_json::to_string_pretty(&r)?)?;
        for c in &r.best {
            std::fs::write(dir.join(format!("{}.toml", c.file.name)), c.file.to_toml())?;
        }
    }
    if let Some(dir) = &a.report {
        let page = rins_report::html::results::schemes_design(&r, dir)?;
        eprintln!("report: {}", page.display());
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        print!("{}", design_text(&r));
    }
    Ok(())
}

/// One scheme's simulation against its analysis.
#[derive(Serialize)]
struct VerifyRow {
    scheme: String,
    case: String,
    analysed_east_m: f64,
    simulated_east_m: f64,
    simulated_end_east_nmi: f64,
    rel_diff: f64,
    wall_s: f64,
}

fn verify(a: &VerifyArgs) -> Result<()> {
    check_common(a.bound_dph, a.days, 36.6)?;
    if !(a.rate_hz >= 10.0 && a.rate_hz <= 2000.0) {
        bail!(
            "--rate-hz: expected a value in [10, 2000], got {}",
            a.rate_hz
        );
    }
    let schemes = schemes_of(&a.schemes)?;
    let opt = AnalyseOptions {
        days: a.days,
        ..AnalyseOptions::default()
    };
    let resp = StaticResponse::new(opt.lat_rad, a.days);
    let g = rins_plant::earth::normal_gravity(opt.lat_rad, 0.0);
    // Every (scheme, case) is one independent week: all of them on every core.
    let mut tasks = Vec::new();
    for s in &schemes {
        let mut dbeta = rins_plant::SensorSpec::default();
        dbeta.gyro.position_bias.enabled = true;
        dbeta.gyro.position_bias.dph = [a.delta_beta_dph; 3];
        // The general class's worst case under this scheme, declared as custom effects.
        let general = analyse_scheme(s, &EffectSet::empty(g).with_general(), &opt, &resp)?;
        let worst = class_bound(&general, CLASSES[0], a.bound_dph).expect("general class");
        let mut worst_sensor = rins_plant::SensorSpec::default();
        worst_sensor.gyro.custom = basis::as_declared(&coefficient_table(&worst));
        tasks.push((s, "plant delta-beta", dbeta));
        tasks.push((s, "general b(u) worst case", worst_sensor));
        tasks.push((
            s,
            "Table 3 sensors, noise off",
            rins_plant::presets::paper_table3(),
        ));
    }
    use rayon::prelude::*;
    let rows: Vec<VerifyRow> = tasks
        .par_iter()
        .map(|(s, case, sensor)| {
            let base = EffectSet::empty(g).with_earth_rate(opt.lat_rad);
            let set = if sensor.gyro.custom.is_empty() {
                base.with_catalogue(sensor)
            } else {
                base.with_declared(&sensor.gyro.custom, false)?
            };
            let an = analyse_scheme(s, &set, &opt, &resp)?;
            let analysed: f64 = an.effects.iter().map(|e| e.after.east_m).sum();
            let sim =
                simulate::simulate(s, sensor, a.days, a.rate_hz).map_err(anyhow::Error::msg)?;
            Ok(VerifyRow {
                scheme: s.name.clone(),
                case: (*case).into(),
                analysed_east_m: analysed,
                simulated_east_m: sim.east_m,
                simulated_end_east_nmi: sim.end_east_nmi,
                rel_diff: (sim.east_m - analysed).abs() / analysed.abs().max(1e-9),
                wall_s: sim.wall_s,
            })
        })
        .collect::<Result<_>>()?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
    } else {
        println!(
            "{:28} {:26} {:>14} {:>14} {:>12} {:>9} {:>7}",
            "scheme", "case", "analysed E m", "simulated E m", "end E nmi", "rel diff", "wall s"
        );
        for r in &rows {
            println!(
                "{:28} {:26} {:>14.1} {:>14.1} {:>12.3} {:>9.4} {:>7.1}",
                r.scheme,
                r.case,
                r.analysed_east_m,
                r.simulated_east_m,
                r.simulated_end_east_nmi,
                r.rel_diff,
                r.wall_s
            );
        }
    }
    Ok(())
}
