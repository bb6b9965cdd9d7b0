//! The scenario file format: TOML, unknown keys rejected, units in key names.
//! Every key, unit and default is listed in docs/scenario-format.md.

use std::path::{Path, PathBuf};

use rins_plant::carrier::{AfterEnd, CarrierKind, CarrierSpec};
use rins_plant::config::{SensorSpec, VehicleSpec};
use rins_plant::earth::{EarthSpec, SiteSpec};
use rins_plant::effects::{AccelSpec, GyroSpec};
use rins_plant::message::Num;
use rins_plant::table::SchemeSpec;
use rins_plant::thermal::ThermalSpec;
use rins_plant::{PlantConfig, presets};
use serde::{Deserialize, Serialize};

use rins_plant::effects::encoder::EncoderSpec;
use rins_plant::effects::temp_sensor::TempSensorSpec;

use crate::spans::SpanIndex;

mod document;
mod preset_fragments;
mod whole_arrays;

use document::{Document, Origin};
use toml::de::DeValue;

/// `[scenario]`: what the run is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScenarioMeta {
    /// Short name (used for output file names).
    pub name: String,
    /// One-line description, with the paper section it reproduces.
    pub description: String,
    /// Simulated duration, s, in (0, 1e7].
    pub duration_s: f64,
}

impl Default for ScenarioMeta {
    fn default() -> Self {
        Self {
            name: "unnamed".into(),
            description: String::new(),
            duration_s: 3600.0,
        }
    }
}

/// `[run]`: timing and seed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunSpec {
    /// IMU output rate, Hz.
    pub rate_hz: f64,
    /// Internal integration steps per output interval.
    pub substeps: u32,
    /// Seed of every random stream.
    pub seed: u64,
}

impl Default for RunSpec {
    fn default() -> Self {
        let p = PlantConfig::default();
        Self {
            rate_hz: p.rate_hz,
            substeps: p.substeps,
            seed: p.seed,
        }
    }
}

/// `[sensor]`: a named preset plus per-term overrides. Read by [`Scenario::from_toml_with`],
/// the terms hold the preset's values with the file's keys laid over them.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorSection {
    /// Starting specification: `paper-table3`, `nav-grade-full` or `ideal` (default `ideal`).
    pub preset: Option<String>,
    /// Gyro terms.
    pub gyro: GyroSpec,
    /// Accelerometer terms.
    pub accel: AccelSpec,
    /// Encoder terms.
    pub encoder: EncoderSpec,
    /// Temperature-sensor terms.
    pub temperature: TempSensorSpec,
}

/// A value given on the command line for a scenario key (`--duration-s` →
/// `scenario.duration_s`). It is laid into the file's document before the one typed read and
/// the one validation, and errors about it name the flag.
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    /// The flag as typed, e.g. `--duration-s`.
    pub flag: &'static str,
    /// Scenario key path, e.g. `scenario.duration_s`.
    pub path: &'static str,
    /// The value.
    pub value: toml::Value,
}

/// `[outputs]`: what `rins run` writes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// Write `imu.csv`.
    pub csv: bool,
    /// Samples per CSV row (increments summed over the row), ≥ 1.
    pub decimation: u64,
    /// Add the error-free increments.
    pub truth: bool,
    /// Add each enabled effect's contribution (mean rate over the row).
    pub effects: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            csv: true,
            decimation: 1,
            truth: false,
            effects: false,
        }
    }
}

/// `[campaign]`: calibration runs over chamber temperatures (used by `rins campaign`).
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CampaignSpec {
    /// Explicit chamber temperatures, °C; if empty, `runs` evenly spaced from `from_c` to `to_c`.
    pub temps_c: Vec<f64>,
    /// Lowest chamber temperature, °C.
    pub from_c: f64,
    /// Highest chamber temperature, °C.
    pub to_c: f64,
    /// Number of runs.
    pub runs: u32,
}

impl CampaignSpec {
    /// The chamber temperatures of the campaign, °C.
    pub fn temperatures_c(&self) -> Vec<f64> {
        if !self.temps_c.is_empty() {
            return self.temps_c.clone();
        }
        let n = self.runs.max(1);
        if n == 1 {
            return vec![self.from_c];
        }
        (0..n)
            .map(|k| self.from_c + (self.to_c - self.from_c) * k as f64 / (n - 1) as f64)
            .collect()
    }
}

/// A whole scenario file.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScenarioFile {
    /// `[scenario]`.
    pub scenario: ScenarioMeta,
    /// `[run]`.
    pub run: RunSpec,
    /// `[site]`.
    pub site: SiteSpec,
    /// `[vehicle]`.
    pub vehicle: VehicleSpec,
    /// `[earth]`.
    pub earth: EarthSpec,
    /// `[scheme]`.
    pub scheme: SchemeSpec,
    /// `[sensor]`.
    pub sensor: SensorSection,
    /// `[thermal]`.
    pub thermal: ThermalSpec,
    /// `[carrier]` (static by default; docs/carrier.md).
    pub carrier: CarrierSpec,
    /// `[outputs]`.
    pub outputs: OutputSpec,
    /// `[campaign]`, optional.
    pub campaign: Option<CampaignSpec>,
}

/// A loaded, validated scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Where it came from (file path or `builtin:NAME`).
    pub source: String,
    /// `[scenario]`.
    pub meta: ScenarioMeta,
    /// The plant configuration with the preset applied.
    pub plant: PlantConfig,
    /// `[outputs]`.
    pub outputs: OutputSpec,
    /// `[campaign]`, if present.
    pub campaign: Option<CampaignSpec>,
}

/// Why a scenario could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// TOML syntax, an unknown key or a wrong type (toml's message carries line and column).
    #[error("{source_name}: {message}")]
    Parse {
        /// File.
        source_name: String,
        /// toml's message with line, column and the offending text.
        message: String,
    },
    /// Values outside their valid range.
    #[error("{source_name}: invalid scenario:\n{}", .problems.join("\n"))]
    Invalid {
        /// File.
        source_name: String,
        /// One line per problem: `line N: key: expected …, got …`.
        problems: Vec<String>,
    },
}

/// The scenarios shipped with rins, by name.
pub const BUILTIN: [(&str, &str); 7] = [
    (
        "paper-16pos-week",
        include_str!("../files/paper-16pos-week.toml"),
    ),
    (
        "paper-16pos-short",
        include_str!("../files/paper-16pos-short.toml"),
    ),
    (
        "calibration-z-up",
        include_str!("../files/calibration-z-up.toml"),
    ),
    (
        "calibration-z-down",
        include_str!("../files/calibration-z-down.toml"),
    ),
    ("campaign-37", include_str!("../files/campaign-37.toml")),
    (
        "paper-static-week",
        include_str!("../files/paper-static-week.toml"),
    ),
    (
        "ship-16pos-week",
        include_str!("../files/ship-16pos-week.toml"),
    ),
];

impl Scenario {
    /// Loads `path`, or a built-in scenario when `path` is `builtin:NAME` or a bare built-in name.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        Self::load_with(path, &[])
    }

    /// [`Scenario::load`] with command-line overrides laid over the file before validation.
    pub fn load_with(path: &Path, overrides: &[Override]) -> Result<Self, ScenarioError> {
        let s = path.to_string_lossy();
        let name = s.strip_prefix("builtin:").unwrap_or(&s);
        let explicit = s.starts_with("builtin:");
        if let Some((n, text)) = BUILTIN
            .iter()
            .find(|(n, _)| *n == name)
            .filter(|_| explicit || !path.exists())
        {
            return Self::from_toml_with(text, &format!("builtin:{n}"), overrides);
        }
        if explicit {
            let names: Vec<&str> = BUILTIN.iter().map(|(n, _)| *n).collect();
            return Err(ScenarioError::Parse {
                source_name: s.to_string(),
                message: format!("no such built-in scenario; built-ins are {names:?}"),
            });
        }
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError::Read {
            path: path.into(),
            source: e,
        })?;
        Self::from_toml_with(&text, &path.display().to_string(), overrides)
    }

    /// Parses scenario text; `source_name` appears in every error.
    pub fn from_toml(text: &str, source_name: &str) -> Result<Self, ScenarioError> {
        Self::from_toml_with(text, source_name, &[])
    }

    /// [`Scenario::from_toml`] with command-line overrides.
    ///
    /// The one path from text to configuration: the text is parsed once into a spanned
    /// document; the overrides, then the sensor preset (as its TOML fragment, under the file's
    /// own `[sensor]` keys) are laid into it; the typed scenario is read from it once (unknown
    /// keys and wrong types refused with toml's line and column); then everything is
    /// range-checked once, errors naming the line from the same document or the flag.
    pub fn from_toml_with(
        text: &str,
        source_name: &str,
        overrides: &[Override],
    ) -> Result<Self, ScenarioError> {
        let parse_err = |message: String| ScenarioError::Parse {
            source_name: source_name.into(),
            message,
        };
        // The overrides' values as TOML text, so they join the document as its own values; they
        // live as long as the document that borrows them.
        let override_texts: Vec<String> = overrides.iter().map(|o| o.value.to_string()).collect();
        let mut doc = Document::parse(text).map_err(|e| parse_err(e.to_string()))?;
        if doc.is_empty() {
            // An empty file would silently run every default: refuse it.
            return Err(ScenarioError::Invalid {
                source_name: source_name.into(),
                problems: vec![
                    "  the file has no keys (empty or only comments); write at least a [scenario] section, or use builtin:NAME (see `rins scenarios`)".into(),
                ],
            });
        }
        let spans = doc.spans();
        let read_err = |(origin, e): (Origin, toml::de::Error)| {
            parse_err(match origin {
                Origin::Override(i) => format!("{}: {e}", overrides[i].flag),
                Origin::File | Origin::Preset => e.to_string(),
            })
        };
        // A flag that replaces a value the file writes must not hide a wrong type there: the
        // file is then read on its own first (a second typed read, in this case only).
        if overrides.iter().any(|o| spans.find(o.path).is_some()) {
            doc.clone().read::<ScenarioFile>().map_err(read_err)?;
        }
        for (i, (o, value)) in overrides.iter().zip(&override_texts).enumerate() {
            let value = DeValue::parse(value).map_err(|e| parse_err(format!("{}: {e}", o.flag)))?;
            doc.lay_override(i, o.path, value.into_inner());
        }
        let preset_name = doc.preset_name().unwrap_or("ideal").to_string();
        let fragment = preset_fragments::fragment(&preset_name);
        if let Some(fragment) = fragment {
            doc.lay_preset(fragment);
        }
        let raw: ScenarioFile = doc.read().map_err(read_err)?;
        if fragment.is_none() {
            let line = spans
                .find("sensor.preset")
                .map(|p| format!("{p}: "))
                .unwrap_or_default();
            return Err(ScenarioError::Invalid {
                source_name: source_name.into(),
                problems: vec![format!(
                    "{line}sensor.preset: expected one of {:?}, got {preset_name:?}",
                    presets::PRESET_NAMES
                )],
            });
        }
        let sensor = SensorSpec {
            gyro: raw.sensor.gyro,
            accel: raw.sensor.accel,
            encoder: raw.sensor.encoder,
            temperature: raw.sensor.temperature,
        };
        let plant = PlantConfig {
            rate_hz: raw.run.rate_hz,
            substeps: raw.run.substeps,
            seed: raw.run.seed,
            site: raw.site,
            vehicle: raw.vehicle,
            earth: raw.earth,
            scheme: raw.scheme,
            sensor,
            thermal: raw.thermal,
            carrier: carrier_resolved(raw.carrier, source_name),
        };
        let scenario = Scenario {
            source: source_name.into(),
            meta: raw.scenario,
            plant,
            outputs: raw.outputs,
            campaign: raw.campaign,
        };
        scenario.validate_at(&spans, overrides)?;
        Ok(scenario)
    }

    /// Range-checks everything; `text` (when given) lets errors name the line.
    pub fn validate(&self, text: Option<&str>) -> Result<(), ScenarioError> {
        self.validate_at(&text.map(SpanIndex::new).unwrap_or_default(), &[])
    }

    /// Range-checks everything, the one place scenario values are checked; errors name the line
    /// and column the file writes the key at (`spans`), or the flag of an override that set it.
    fn validate_at(&self, spans: &SpanIndex, overrides: &[Override]) -> Result<(), ScenarioError> {
        let mut problems: Vec<(String, String)> = Vec::new();
        if !(self.meta.duration_s > 0.0 && self.meta.duration_s <= 1e7) {
            problems.push((
                "scenario.duration_s".into(),
                format!(
                    "expected a number in (0, 1e7], got {}",
                    Num(self.meta.duration_s)
                ),
            ));
        }
        if self.outputs.decimation == 0 {
            problems.push((
                "outputs.decimation".into(),
                "expected a whole number ≥ 1, got 0".into(),
            ));
        }
        if let Some(c) = &self.campaign {
            for (i, t) in c.temperatures_c().iter().enumerate() {
                if !(rins_plant::thermal::CHAMBER_MIN_C..=rins_plant::thermal::CHAMBER_MAX_C)
                    .contains(t)
                {
                    problems.push((
                        "campaign.temps_c".into(),
                        format!(
                            "expected chamber temperatures in [{}, {}] °C (the thermal model's range), got {} at run {i}",
                            rins_plant::thermal::CHAMBER_MIN_C,
                            rins_plant::thermal::CHAMBER_MAX_C,
                            Num(*t)
                        ),
                    ));
                }
            }
        }
        let plant_errors = self.plant.validate().err().unwrap_or_default();
        let plant_valid = plant_errors.is_empty();
        carrier_problems(
            &self.plant,
            plant_valid,
            self.meta.duration_s,
            &mut problems,
        );
        problems.extend(
            plant_errors
                .into_iter()
                .map(|e| (e.path, format!("expected {}, got {}", e.expected, e.got))),
        );
        if problems.is_empty() {
            return Ok(());
        }
        let lines = problems
            .into_iter()
            .map(|(path, msg)| {
                let flag = overrides.iter().find(|o| o.path == path).map(|o| o.flag);
                let at = match (flag, spans.find(&path)) {
                    (Some(f), _) => format!("{f}: "),
                    (None, Some(p)) => format!("{p}: "),
                    (None, None) => "(default or preset value) ".into(),
                };
                format!("  {at}{path}: {msg}")
            })
            .collect();
        Err(ScenarioError::Invalid {
            source_name: self.source.clone(),
            problems: lines,
        })
    }

    /// Number of output samples in the scenario.
    pub fn samples(&self) -> u64 {
        (self.meta.duration_s * self.plant.rate_hz).round() as u64
    }
}

/// `[carrier]` with a relative trajectory file name taken from the scenario file's folder.
fn carrier_resolved(mut c: CarrierSpec, source_name: &str) -> CarrierSpec {
    let f = Path::new(&c.trajectory.file);
    let src = Path::new(source_name);
    if let Some(dir) = src
        .parent()
        .filter(|_| c.kind == CarrierKind::Trajectory && f.is_relative() && src.is_file())
    {
        c.trajectory.file = dir.join(f).display().to_string();
    }
    c
}

/// A trajectory carrier's file must read and pass the trajectory rules (its errors name the
/// row and column in the trajectory file) and last the run unless `after_end = "hold"`; a
/// ship's last leg, continued to the end of the run, must stay within the polar limit (the
/// plant's own validation checks the legs over their own durations; `plant_valid` is its
/// verdict, so the polar check runs only on legs that passed it).
fn carrier_problems(
    plant: &PlantConfig,
    plant_valid: bool,
    duration_s: f64,
    problems: &mut Vec<(String, String)>,
) {
    let c = &plant.carrier;
    if c.kind == CarrierKind::Ship && plant_valid {
        let legs_s: f64 = c.ship.legs.iter().map(|l| l.duration_s).sum();
        if duration_s > legs_s
            && let Some((path, e, g)) =
                rins_plant::carrier::track::polar_problem(&c.ship, duration_s)
        {
            problems.push((path, format!("expected {e}, got {g}")));
        }
    }
    if c.kind != CarrierKind::Trajectory || c.trajectory.file.is_empty() {
        return;
    }
    match rins_plant::carrier::Trajectory::read(&c.trajectory.file) {
        Err(e) => problems.push(("carrier.trajectory.file".into(), e.to_string())),
        Ok(t) if c.trajectory.after_end == AfterEnd::Error && t.end_s() < duration_s * (1.0 - 1e-9) => {
            problems.push((
                "carrier.trajectory.file".into(),
                format!(
                    "{}: the last row is at t = {} s (plant time), before the end of the run at \
                     scenario.duration_s = {duration_s} s; give a file that covers the run, a \
                     shorter run, or carrier.trajectory.after_end = \"hold\" (stop at the last row)",
                    c.trajectory.file,
                    t.end_s()
                ),
            ))
        }
        Ok(_) => {}
    }
}
