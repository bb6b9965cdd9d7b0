//! The result of a sweep: per point the swept values, each seed's end figures for both
//! navigators, and the median and 5–95 % band of each chosen output over the seeds. It
//! serialises to the JSON `rins sweep --json` prints and writes to `sweep.json`.

use std::collections::BTreeMap;

use rins_verification::paper::{Band, EndFigures};
use serde::Serialize;

/// The two navigators every seed feeds, in the order of [`SeedResult`] and of the tables.
pub const NAVIGATORS: [&str; 2] = ["uncompensated", "compensated"];

/// A swept value as the table, the CSV and the figures write it: a number in Rust's shortest
/// round-trip form (`180`, `0.02`), a name or a switch as its text.
pub fn value_text(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Number(n) if n.is_f64() => {
            n.as_f64().map_or_else(String::new, |x| x.to_string())
        }
        other => other.to_string(),
    }
}

/// A finished sweep.
#[derive(Clone, Debug, Serialize)]
pub struct SweepReport {
    /// Short name.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// The sweep file.
    pub sweep_file: String,
    /// The base scenario (file or `builtin:NAME`).
    pub scenario: String,
    /// Navigation time, s.
    pub duration_s: f64,
    /// Navigation time, days.
    pub days: f64,
    /// Initial alignment (`truth` or `self`).
    pub alignment: String,
    /// How the keys combine (`grid` or `zip`).
    pub combine: String,
    /// Seeds run at every point.
    pub seeds: Vec<u64>,
    /// The swept keys.
    pub parameters: Vec<ParameterInfo>,
    /// The outputs tabulated.
    pub outputs: Vec<OutputInfo>,
    /// The points, in order.
    pub points: Vec<PointResult>,
    /// Wall time of the runs, s.
    pub wall_s: f64,
}

/// A swept key.
#[derive(Clone, Debug, Serialize)]
pub struct ParameterInfo {
    /// Scenario key path.
    pub key: String,
    /// Unit.
    pub unit: String,
    /// The values it takes (numbers, switches or enumeration names).
    pub values: Vec<serde_json::Value>,
}

impl ParameterInfo {
    /// The key with its unit, as a column heading or axis label (`scheme.dwell_s (s)`; a
    /// dimensionless key without one).
    pub fn heading(&self) -> String {
        if self.unit == "1" {
            self.key.clone()
        } else {
            format!("{} ({})", self.key, self.unit)
        }
    }
}

/// A tabulated output.
#[derive(Clone, Debug, Serialize)]
pub struct OutputInfo {
    /// Name (`lon_nm`).
    pub name: String,
    /// What it is.
    pub what: String,
    /// Unit.
    pub unit: String,
}

/// One point's results.
#[derive(Clone, Debug, Serialize)]
pub struct PointResult {
    /// `key = value, …`.
    pub label: String,
    /// One value per swept key.
    pub values: Vec<serde_json::Value>,
    /// Per output name: median and 5–95 % over the seeds, uncompensated navigator.
    pub uncompensated: BTreeMap<String, Band>,
    /// The same, δβ-compensated navigator.
    pub compensated: BTreeMap<String, Band>,
    /// Each seed's end figures.
    pub per_seed: Vec<SeedResult>,
}

impl PointResult {
    /// The band of `output` for navigator `nav` (index into [`NAVIGATORS`]).
    pub fn band(&self, nav: usize, output: &str) -> Band {
        let case = if nav == 0 {
            &self.uncompensated
        } else {
            &self.compensated
        };
        case.get(output).copied().unwrap_or(Band {
            median: f64::NAN,
            p05: f64::NAN,
            p95: f64::NAN,
        })
    }
}

/// One seed's end figures at a point.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SeedResult {
    /// Seed.
    pub seed: u64,
    /// Uncompensated navigator.
    pub uncompensated: EndFigures,
    /// δβ-compensated navigator (subtracting the point's own δβ, as Table 4 does).
    pub compensated: EndFigures,
}

impl SeedResult {
    /// The figures of navigator `nav` (index into [`NAVIGATORS`]).
    pub fn figures(&self, nav: usize) -> &EndFigures {
        if nav == 0 {
            &self.uncompensated
        } else {
            &self.compensated
        }
    }
}
