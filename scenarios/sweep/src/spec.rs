//! The sweep file (docs/sweeps.md): a base scenario, the scenario keys to vary with their values
//! (a list or `linspace`; several keys combined as a grid or side by side), the seeds, the
//! navigation time and the outputs to tabulate. Loading it checks everything before anything
//! runs: every error names the file, the line and column, the field, and what is allowed (a
//! key's valid range comes from the plant's parameter table, [`rins_plant::params`]).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use rins_plant::PlantConfig;
use rins_plant::carrier::CarrierKind;
use rins_plant::message::{self, Num};
use rins_plant::params::{self, Param, ParamValue};
use serde::Deserialize;

use super::outputs::{self, Output};
use rins_scenario::file::{Scenario, ScenarioError};
use rins_scenario::spans::SpanIndex;

/// Time the self-alignment takes (300 s coarse + 600 s fine), prepended to the scheme as
/// `rins paper table4 --align self` does.
const SELF_ALIGN_S: f64 = 900.0;
/// Most seeds `seeds = N` may ask for.
const MAX_SEEDS: i64 = 100_000;
/// Most values a `linspace` may make.
const MAX_LINSPACE: i64 = 10_000;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    sweep: RawSweep,
    #[serde(default)]
    parameter: Vec<RawParameter>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    description: String,
    scenario: String,
    #[serde(default)]
    duration_s: Option<f64>,
    #[serde(default)]
    days: Option<f64>,
    seeds: toml::Value,
    outputs: Vec<String>,
    #[serde(default)]
    combine: Option<String>,
    #[serde(default)]
    alignment: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParameter {
    key: String,
    #[serde(default)]
    values: Option<Vec<toml::Value>>,
    #[serde(default)]
    linspace: Option<RawLinspace>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLinspace {
    start: f64,
    stop: f64,
    count: i64,
}

/// How several swept keys make the points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Combine {
    /// Every combination (the cartesian product), the first key varying slowest.
    Grid,
    /// The k-th values of every key together (lists of one length).
    Zip,
}

impl Combine {
    /// The name the sweep file uses.
    pub fn name(self) -> &'static str {
        match self {
            Combine::Grid => "grid",
            Combine::Zip => "zip",
        }
    }
}

/// Initial alignment of the navigators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Align {
    /// From the plant's truth (what the paper's figures match).
    Truth,
    /// 300 s coarse + 600 s fine on the static IMU, prepended to the scheme.
    SelfAlign,
}

impl Align {
    /// The name the sweep file uses.
    pub fn name(self) -> &'static str {
        match self {
            Align::Truth => "truth",
            Align::SelfAlign => "self",
        }
    }

    /// The navigator's alignment.
    pub fn nav(self) -> rins_navigation::Alignment {
        match self {
            Align::Truth => rins_navigation::Alignment::Truth,
            Align::SelfAlign => rins_navigation::Alignment::SelfAlign {
                coarse_s: 300.0,
                fine_s: 600.0,
            },
        }
    }
}

/// One swept scenario key.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// Scenario key path (`sensor.gyro.position_bias.dph[2]`).
    pub key: String,
    /// Its unit (from the parameter table).
    pub unit: &'static str,
    /// The values it takes, in the file's order.
    pub values: Vec<ParamValue>,
    /// Line of its `key` in the sweep file (for messages about the points it makes).
    pub line: Option<usize>,
}

/// One point of the sweep: a value per swept key and the plant it makes.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// One value per [`SweepPlan::parameters`] entry.
    pub values: Vec<ParamValue>,
    /// The base scenario's plant with the values set (and the alignment time prepended).
    pub plant: PlantConfig,
}

/// A loaded, checked sweep: everything needed to run it.
#[derive(Clone, Debug)]
pub struct SweepPlan {
    /// The sweep file's path.
    pub source: String,
    /// Short name (`sweep.name`, else the file's stem).
    pub name: String,
    /// One-line description.
    pub description: String,
    /// The base scenario.
    pub scenario: Scenario,
    /// The swept keys.
    pub parameters: Vec<Parameter>,
    /// How the keys' values combine into points.
    pub combine: Combine,
    /// The points, in order.
    pub points: Vec<Point>,
    /// Seeds run at every point.
    pub seeds: Vec<u64>,
    /// Navigation time, s.
    pub duration_s: f64,
    /// Initial alignment.
    pub alignment: Align,
    /// The outputs tabulated and drawn.
    pub outputs: Vec<&'static Output>,
}

/// Why a sweep file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// TOML syntax, an unknown field or a wrong type (toml's message carries line and column).
    #[error("{source_name}: {message}")]
    Parse {
        /// File.
        source_name: String,
        /// toml's message.
        message: String,
    },
    /// Values the sweep cannot run.
    #[error("{source_name}: invalid sweep:\n{}", .problems.join("\n"))]
    Invalid {
        /// File.
        source_name: String,
        /// One line per problem: `line N, column M: field: expected …, got …`.
        problems: Vec<String>,
    },
}

/// The problems found so far, each placed at its field's line.
struct Problems<'a> {
    spans: &'a SpanIndex,
    list: Vec<String>,
}

impl Problems<'_> {
    fn at(&self, field: &str) -> String {
        self.spans
            .find(field)
            .map(|p| format!("{p}: "))
            .unwrap_or_default()
    }

    fn push(&mut self, field: &str, message: impl std::fmt::Display) {
        let at = self.at(field);
        self.list.push(format!("  {at}{field}: {message}"));
    }
}

/// A value as the sweep file writes it.
pub fn show(v: &ParamValue) -> String {
    match v {
        ParamValue::Real(x) => x.to_string(),
        ParamValue::Integer(u) => u.to_string(),
        ParamValue::Bool(b) => b.to_string(),
        ParamValue::Enum(s) => s.clone(),
    }
}

impl SweepPlan {
    /// Loads the sweep file at `path`; a relative scenario path is taken from its folder.
    pub fn load(path: &Path) -> Result<Self, SweepError> {
        let text = std::fs::read_to_string(path).map_err(|e| SweepError::Read {
            path: path.into(),
            source: e,
        })?;
        Self::from_toml(&text, &path.display().to_string(), path.parent())
    }

    /// Parses sweep text; `source_name` appears in every error, `dir` is where a relative
    /// scenario path is looked for (the working folder when `None`).
    pub fn from_toml(
        text: &str,
        source_name: &str,
        dir: Option<&Path>,
    ) -> Result<Self, SweepError> {
        let raw: RawFile = toml::from_str(text).map_err(|e| SweepError::Parse {
            source_name: source_name.into(),
            message: e.to_string(),
        })?;
        let spans = SpanIndex::new(text);
        let mut p = Problems {
            spans: &spans,
            list: Vec::new(),
        };
        let invalid = |problems: Vec<String>| SweepError::Invalid {
            source_name: source_name.into(),
            problems,
        };
        let s = &raw.sweep;
        let scenario = match load_scenario(&s.scenario, dir) {
            Ok(sc) => sc,
            Err(e) => {
                p.push(
                    "sweep.scenario",
                    format!("cannot load the base scenario: {e}"),
                );
                return Err(invalid(p.list));
            }
        };
        let duration_s = duration(s, &scenario, &mut p);
        let seeds = seeds(&s.seeds, scenario.plant.seed, &mut p);
        let outputs = outputs_of(&s.outputs, &mut p);
        let combine = match s.combine.as_deref() {
            None | Some("grid") => Combine::Grid,
            Some("zip") => Combine::Zip,
            Some(other) => {
                p.push(
                    "sweep.combine",
                    format!("expected \"grid\" or \"zip\", got {other:?}"),
                );
                Combine::Grid
            }
        };
        let alignment = match s.alignment.as_deref() {
            None | Some("truth") => Align::Truth,
            Some("self") => {
                if scenario.plant.carrier.kind != CarrierKind::Static {
                    p.push(
                        "sweep.alignment",
                        "self-alignment needs the static carrier; on a moving carrier use \"truth\"",
                    );
                }
                Align::SelfAlign
            }
            Some(other) => {
                p.push(
                    "sweep.alignment",
                    format!("expected \"truth\" or \"self\", got {other:?}"),
                );
                Align::Truth
            }
        };
        let parameters = parameters(&raw.parameter, &scenario.plant, &spans, &mut p);
        if !p.list.is_empty() {
            return Err(invalid(p.list));
        }
        let combos = combinations(&parameters, combine, &mut p);
        if !p.list.is_empty() {
            return Err(invalid(p.list));
        }
        let points = points(
            &parameters,
            combos,
            &scenario,
            duration_s,
            alignment,
            &mut p,
        );
        if !p.list.is_empty() {
            return Err(invalid(p.list));
        }
        let name = s.name.clone().unwrap_or_else(|| {
            Path::new(source_name)
                .file_stem()
                .map_or_else(|| "sweep".into(), |n| n.to_string_lossy().into_owned())
        });
        Ok(Self {
            source: source_name.into(),
            name,
            description: s.description.clone(),
            scenario,
            parameters,
            combine,
            points,
            seeds,
            duration_s,
            alignment,
            outputs,
        })
    }

    /// Samples of one navigation run at the base rate (for progress bars).
    pub fn samples_per_run(&self) -> u64 {
        self.points
            .iter()
            .map(|p| (self.duration_s * p.plant.rate_hz).round() as u64)
            .max()
            .unwrap_or(0)
    }

    /// `key = value` of each swept key at `point`.
    pub fn label(&self, point: &Point) -> String {
        label(&self.parameters, &point.values)
    }
}

/// `key = value` of each swept key, joined by commas.
fn label(pars: &[Parameter], values: &[ParamValue]) -> String {
    pars.iter()
        .zip(values)
        .map(|(par, v)| format!("{} = {}", par.key, show(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The base scenario: `builtin:NAME`, a bare built-in name, or a file (relative to `dir`).
fn load_scenario(name: &str, dir: Option<&Path>) -> Result<Scenario, ScenarioError> {
    let raw = Path::new(name);
    let is_builtin = name.starts_with("builtin:")
        || (rins_scenario::file::BUILTIN.iter().any(|(n, _)| *n == name) && !raw.exists());
    let path = match dir {
        Some(d) if !is_builtin && raw.is_relative() => d.join(raw),
        _ => raw.to_path_buf(),
    };
    Scenario::load(&path)
}

/// The navigation time: `days` or `duration_s` (not both), else the scenario's.
fn duration(s: &RawSweep, sc: &Scenario, p: &mut Problems) -> f64 {
    let (field, d) = match (s.duration_s, s.days) {
        (Some(_), Some(_)) => {
            p.push(
                "sweep.days",
                "give the navigation time once: sweep.days or sweep.duration_s, not both",
            );
            return sc.meta.duration_s;
        }
        (Some(d), None) => ("sweep.duration_s", d),
        (None, Some(days)) => ("sweep.days", days * 86_400.0),
        (None, None) => return sc.meta.duration_s,
    };
    if !(d > 0.0 && d <= 1e7) {
        let got = if field == "sweep.days" {
            s.days.unwrap_or(d)
        } else {
            d
        };
        let range = if field == "sweep.days" {
            "(0, 115.74] days (1e7 s)"
        } else {
            "(0, 1e7] s"
        };
        p.push(
            field,
            format!("expected a number in {range}, got {}", Num(got)),
        );
    } else if d * sc.plant.rate_hz < 1.0 {
        p.push(
            field,
            format!(
                "expected at least one sample at the scenario's {} Hz, got {} s",
                Num(sc.plant.rate_hz),
                Num(d)
            ),
        );
    }
    d
}

/// `seeds = N` (N seeds from the scenario's `run.seed`, as `rins paper table4 --runs N`) or a
/// list of distinct seeds.
fn seeds(v: &toml::Value, first: u64, p: &mut Problems) -> Vec<u64> {
    match v {
        toml::Value::Integer(n) if (1..=MAX_SEEDS).contains(n) => {
            match first.checked_add(*n as u64 - 1) {
                Some(_) => (0..*n as u64).map(|k| first + k).collect(),
                None => {
                    p.push(
                        "sweep.seeds",
                        format!(
                            "{n} seeds from the scenario's run.seed {first} pass the largest seed; give a list"
                        ),
                    );
                    Vec::new()
                }
            }
        }
        toml::Value::Integer(n) => {
            p.push(
                "sweep.seeds",
                format!("expected a count in [1, {MAX_SEEDS}] or a list of seeds, got {n}"),
            );
            Vec::new()
        }
        toml::Value::Array(list) if list.is_empty() => {
            p.push(
                "sweep.seeds",
                "expected at least one seed, got an empty list",
            );
            Vec::new()
        }
        toml::Value::Array(list) => {
            let mut out = Vec::new();
            for (i, s) in list.iter().enumerate() {
                let field = format!("sweep.seeds[{i}]");
                match s.as_integer() {
                    Some(x) if x >= 0 => {
                        if out.contains(&(x as u64)) {
                            p.push(&field, format!("seed {x} is listed twice"));
                        }
                        out.push(x as u64);
                    }
                    _ => p.push(&field, format!("expected a whole number ≥ 0, got {s}")),
                }
            }
            out
        }
        other => {
            p.push(
                "sweep.seeds",
                format!("expected a count (seeds = 8) or a list (seeds = [1, 5, 9]), got {other}"),
            );
            Vec::new()
        }
    }
}

fn outputs_of(names: &[String], p: &mut Problems) -> Vec<&'static Output> {
    if names.is_empty() {
        p.push(
            "sweep.outputs",
            format!(
                "expected at least one output, got an empty list; outputs are {:?}",
                outputs::names()
            ),
        );
    }
    let mut out: Vec<&'static Output> = Vec::new();
    for (i, n) in names.iter().enumerate() {
        let field = format!("sweep.outputs[{i}]");
        match outputs::output(n) {
            Some(o) if out.iter().any(|x| x.name == o.name) => {
                p.push(&field, format!("{n:?} is listed twice"))
            }
            Some(o) => out.push(o),
            None => p.push(
                &field,
                format!("unknown output {n:?}; outputs are {:?}", outputs::names()),
            ),
        }
    }
    out
}

/// Each `[[parameter]]`: a known key and its checked values.
fn parameters(
    raw: &[RawParameter],
    plant: &PlantConfig,
    spans: &SpanIndex,
    p: &mut Problems,
) -> Vec<Parameter> {
    if raw.is_empty() {
        p.push(
            "parameter",
            "expected at least one [[parameter]] with a key and its values",
        );
    }
    let table = params::flatten(plant);
    let by_path: HashMap<&str, &Param> = table.iter().map(|x| (x.path.as_str(), x)).collect();
    let mut out = Vec::new();
    for (i, rp) in raw.iter().enumerate() {
        let field = |f: &str| format!("parameter[{i}].{f}");
        let key = rp.key.trim();
        if out.iter().any(|x: &Parameter| x.key == key) {
            p.push(&field("key"), format!("{key:?} is swept twice"));
            continue;
        }
        if key == "run.seed" {
            p.push(
                &field("key"),
                "the seeds are given by sweep.seeds, not swept as a parameter",
            );
            continue;
        }
        let Some(param) = by_path.get(key) else {
            p.push(
                &field("key"),
                format!(
                    "unknown scenario key {key:?}; the nearest keys are {} (every key: the paths of docs/scenario-format.md, array elements as name[i])",
                    nearest(key, &table).join(", ")
                ),
            );
            continue;
        };
        let values: Vec<ParamValue> = match (&rp.values, &rp.linspace) {
            (Some(_), Some(_)) | (None, None) => {
                p.push(
                    &field("key"),
                    format!("give the values of {key} once: values = [...] or linspace = {{ start, stop, count }}"),
                );
                continue;
            }
            (Some(list), None) if list.is_empty() => {
                p.push(
                    &field("values"),
                    format!("expected at least one value of {key}, got an empty list"),
                );
                continue;
            }
            (Some(list), None) => list
                .iter()
                .enumerate()
                .filter_map(|(j, v)| {
                    value_of(v, param)
                        .map_err(|m| p.push(&field(&format!("values[{j}]")), format!("{key}: {m}")))
                        .ok()
                })
                .collect(),
            (None, Some(l)) => linspace(l, param, &field, p),
        };
        let line = spans.find(&field("key")).map(|x| x.line);
        out.push(Parameter {
            key: key.to_string(),
            unit: param.unit,
            values,
            line,
        });
    }
    out
}

/// A value of the sweep file as a value of `param`'s kind, range-checked.
fn value_of(v: &toml::Value, param: &Param) -> Result<ParamValue, String> {
    let number = |x: f64| -> Result<f64, String> {
        if !x.is_finite() {
            return Err(format!("expected a finite number, got {}", Num(x)));
        }
        match param.range {
            Some((lo, hi)) if !(lo..=hi).contains(&x) => Err(format!(
                "expected a number in {} {}, got {}",
                message::range(lo, hi),
                param.unit,
                Num(x)
            )),
            _ => Ok(x),
        }
    };
    match (&param.value, v) {
        (ParamValue::Real(_), toml::Value::Float(x)) => number(*x).map(ParamValue::Real),
        (ParamValue::Real(_), toml::Value::Integer(i)) => number(*i as f64).map(ParamValue::Real),
        (ParamValue::Integer(_), toml::Value::Integer(i)) if *i >= 0 => {
            number(*i as f64).map(|_| ParamValue::Integer(*i as u64))
        }
        (ParamValue::Integer(_), toml::Value::Float(x)) if *x >= 0.0 && x.fract() == 0.0 => {
            number(*x).map(|x| ParamValue::Integer(x as u64))
        }
        (ParamValue::Integer(_), other) => Err(format!("expected a whole number ≥ 0, got {other}")),
        (ParamValue::Real(_), other) => Err(format!("expected a number, got {other}")),
        (ParamValue::Bool(_), toml::Value::Boolean(b)) => Ok(ParamValue::Bool(*b)),
        (ParamValue::Bool(_), other) => Err(format!("expected true or false, got {other}")),
        (ParamValue::Enum(_), toml::Value::String(s)) => match params::enum_choices(&param.path) {
            Some(choices) if !choices.contains(&s.as_str()) => {
                Err(format!("expected one of {choices:?}, got {s:?}"))
            }
            _ => Ok(ParamValue::Enum(s.clone())),
        },
        (ParamValue::Enum(_), other) => Err(format!(
            "expected one of {:?}, got {other}",
            params::enum_choices(&param.path).unwrap_or(&[])
        )),
    }
}

/// `count` values from `start` to `stop`, both included (`count = 1`: `start` alone).
fn linspace(
    l: &RawLinspace,
    param: &Param,
    field: &dyn Fn(&str) -> String,
    p: &mut Problems,
) -> Vec<ParamValue> {
    if !matches!(param.value, ParamValue::Real(_) | ParamValue::Integer(_)) {
        p.push(
            &field("linspace"),
            format!("{} is not a number; list its values instead", param.path),
        );
        return Vec::new();
    }
    if !(1..=MAX_LINSPACE).contains(&l.count) {
        p.push(
            &field("linspace.count"),
            format!(
                "expected a whole number in [1, {MAX_LINSPACE}], got {}",
                l.count
            ),
        );
        return Vec::new();
    }
    let mut ok = true;
    for (f, x) in [("start", l.start), ("stop", l.stop)] {
        if let Err(m) = value_of(&toml::Value::Float(x), param) {
            p.push(
                &field(&format!("linspace.{f}")),
                format!("{}: {m}", param.path),
            );
            ok = false;
        }
    }
    if !ok {
        return Vec::new();
    }
    let n = l.count as usize;
    let xs: Vec<f64> = (0..n)
        .map(|k| {
            if k + 1 == n && n > 1 {
                l.stop
            } else {
                l.start + (l.stop - l.start) * k as f64 / (n.max(2) - 1) as f64
            }
        })
        .collect();
    let mut out = Vec::new();
    for x in xs {
        match value_of(&toml::Value::Float(x), param) {
            Ok(v) => out.push(v),
            Err(m) => {
                p.push(&field("linspace"), format!("{}: {m}", param.path));
                return Vec::new();
            }
        }
    }
    out
}

/// Index of each parameter's value at each point.
fn combinations(pars: &[Parameter], combine: Combine, p: &mut Problems) -> Vec<Vec<usize>> {
    match combine {
        Combine::Grid => {
            let mut out: Vec<Vec<usize>> = vec![Vec::new()];
            for par in pars {
                out = out
                    .into_iter()
                    .flat_map(|c| {
                        (0..par.values.len()).map(move |j| {
                            let mut c = c.clone();
                            c.push(j);
                            c
                        })
                    })
                    .collect();
            }
            out
        }
        Combine::Zip => {
            let n = pars.first().map_or(0, |x| x.values.len());
            for (i, par) in pars.iter().enumerate().skip(1) {
                if par.values.len() != n {
                    p.push(
                        &format!("parameter[{i}].key"),
                        format!(
                            "combine = \"zip\" takes the k-th value of every key together, so every list needs the same length: {} has {n} values, {} has {}",
                            pars[0].key,
                            par.key,
                            par.values.len()
                        ),
                    );
                }
            }
            (0..n).map(|k| vec![k; pars.len()]).collect()
        }
    }
}

/// Each point's plant, checked as a whole scenario would be (ranges that depend on other keys,
/// the carrier over the navigation time).
fn points(
    pars: &[Parameter],
    combos: Vec<Vec<usize>>,
    sc: &Scenario,
    duration_s: f64,
    alignment: Align,
    p: &mut Problems,
) -> Vec<Point> {
    let mut out = Vec::new();
    for (k, c) in combos.into_iter().enumerate() {
        let values: Vec<ParamValue> = pars
            .iter()
            .zip(&c)
            .map(|(par, &j)| par.values[j].clone())
            .collect();
        let label = label(pars, &values);
        let lines = pars
            .iter()
            .filter_map(|par| par.line.map(|l| l.to_string()))
            .collect::<Vec<_>>()
            .join(", ");
        let head = format!("  point {k} ({label}; keys at line {lines}): ");
        let plant = match params::apply(
            &sc.plant,
            pars.iter()
                .map(|x| x.key.as_str())
                .zip(values.iter().cloned()),
        ) {
            Ok(mut plant) => {
                if alignment == Align::SelfAlign {
                    // The IMU sits at its initial position while aligning; the scheme starts
                    // afterwards.
                    plant.scheme.lead_dwell_s += SELF_ALIGN_S;
                }
                plant
            }
            Err(e) => {
                p.list.push(format!("{head}{e}"));
                continue;
            }
        };
        let check = Scenario {
            plant: plant.clone(),
            meta: rins_scenario::file::ScenarioMeta {
                duration_s,
                ..sc.meta.clone()
            },
            ..sc.clone()
        };
        if let Err(e) = check.validate(None) {
            let msg = match e {
                ScenarioError::Invalid { problems, .. } => problems
                    .iter()
                    .map(|x| x.trim().replace("(default or preset value) ", ""))
                    .collect::<Vec<_>>()
                    .join("; "),
                other => other.to_string(),
            };
            p.list.push(format!("{head}{msg}"));
            continue;
        }
        out.push(Point { values, plant });
    }
    out
}

/// The five keys of the table nearest to `key` (edit distance), for an unknown key.
fn nearest(key: &str, table: &[Param]) -> Vec<String> {
    let mut scored: Vec<(usize, &str)> = table
        .iter()
        .map(|x| (distance(key, &x.path), x.path.as_str()))
        .collect();
    scored.sort();
    scored
        .into_iter()
        .take(5)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// Levenshtein distance, by characters.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance() {
        assert_eq!(distance("kitten", "sitting"), 3);
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("dph", "dph"), 0);
    }
}
