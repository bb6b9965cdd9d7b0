//! The reports of a comparison and a diagnosis, as `rins compare --json` and
//! `rins diagnose --json` print them (display units: °/h for gyros, µg for accelerometers); what
//! discovery found is in [`discovery`].

pub mod discovery;

use std::collections::BTreeMap;

use rins_plant::units::{DPH, UG};
use serde::Serialize;

/// Display unit of a channel (0–2 gyro, 3–5 accelerometer) and its size in SI: °/h for gyros,
/// µg for accelerometers.
pub fn unit_of(channel: usize) -> (&'static str, f64) {
    if channel < 3 {
        ("deg/h", DPH)
    } else {
        ("ug", UG)
    }
}

/// The noise floor of one channel.
#[derive(Clone, Debug, Serialize)]
pub struct NoiseFloor {
    /// Channel.
    pub channel: String,
    /// White-noise density from the model's noise terms (ARW / VRW), display unit·√s (0: none).
    pub model_density: f64,
    /// White-noise density from the residual's Allan deviation at 1 s.
    pub data_density: f64,
    /// Density used for the floor.
    pub used_density: f64,
    /// Which one, and why.
    pub source: String,
}

/// One cell of the discrepancy map.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Channel.
    pub channel: String,
    /// `z-up`, `z-down`, `tilted` or `moving`.
    pub position: String,
    /// The static position's orientation, `az DEG` (body x heading, 15° steps; body y when x
    /// is near vertical); empty while moving.
    pub orientation: String,
    /// Temperature bin, °C.
    pub temp_bin_c: [f64; 2],
    /// Time window since the segment start, s.
    pub time_window_s: [f64; 2],
    /// Time since the table last stopped, s: `[0, 30]`, `[30, 120]`, `[120, 600]` or
    /// `[600, ∞]` (`null` in JSON); `[0, 0]` while moving.
    pub since_move_s: [f64; 2],
    /// Mean residual (display unit).
    pub residual: f64,
    /// Its noise floor (1σ, display unit).
    pub noise_floor: f64,
    /// Residual in units of the floor.
    pub z: f64,
    /// Windows in the cell.
    pub windows: usize,
}

/// Residual correlation with an input.
#[derive(Clone, Debug, Serialize)]
pub struct Correlation {
    /// Channel.
    pub channel: String,
    /// `residual` (autocorrelation) or the input name.
    pub with: String,
    /// Largest |ρ| over lags 0–10 (1–10 for the autocorrelation).
    pub max_abs_rho: f64,
    /// Its lag, windows.
    pub lag: usize,
    /// The band |ρ| is judged against: family-wise 99 % (at the options' `alpha`) over every
    /// channel, input and lag tested (Bonferroni), not per lag.
    pub band99: f64,
    /// |ρ| outside the family-wise band.
    pub significant: bool,
}

/// Per-channel residual summary.
#[derive(Clone, Debug, Serialize)]
pub struct ChannelSummary {
    /// Channel.
    pub channel: String,
    /// Unit of the figures.
    pub unit: String,
    /// RMS of the window residual rates.
    pub residual_rms: f64,
    /// RMS the noise alone would give.
    pub noise_floor_rms: f64,
    /// Mean residual rate.
    pub residual_mean: f64,
}

/// Navigation on measured vs modelled increments over one segment.
#[derive(Clone, Debug, Serialize)]
pub struct NavComparison {
    /// Run name.
    pub run: String,
    /// Duration navigated, s.
    pub duration_s: f64,
    /// Final horizontal error navigating on the measurements, m.
    pub measured_final_m: f64,
    /// Final horizontal error navigating on the model's increments, m.
    pub model_final_m: f64,
    /// RMS over the segment of the difference of the two error tracks, m.
    pub difference_rms_m: f64,
}

/// What `rins compare` reports.
#[derive(Clone, Debug, Serialize)]
pub struct CompareReport {
    /// Data file.
    pub source: String,
    /// Rows and windows.
    pub rows: usize,
    /// Windows.
    pub windows: usize,
    /// Runs.
    pub runs: usize,
    /// Per channel.
    pub channels: Vec<ChannelSummary>,
    /// Noise floors.
    pub noise: Vec<NoiseFloor>,
    /// Every cell of the map.
    pub cells: Vec<Cell>,
    /// Cells whose residual exceeds the Bonferroni-corrected 99 % bound.
    pub flagged_cells: Vec<Cell>,
    /// The |z| bound used.
    pub z_critical: f64,
    /// Residual whiteness and cross-correlations.
    pub correlations: Vec<Correlation>,
    /// Allan deviation of the residual per channel: (τ s, ADEV display unit).
    pub allan: BTreeMap<String, Vec<(f64, f64)>>,
    /// Candidates that cannot be tested with this data.
    pub unavailable: Vec<(String, String)>,
    /// Navigation level: static navigation on the measured and on the modelled increments.
    pub navigation: Vec<NavComparison>,
    /// The column map the data were read with: mapped and ignored columns (`None`: none).
    pub column_map: Option<crate::colmap::MapSummary>,
}

/// A candidate in the ranking.
#[derive(Clone, Debug, Serialize)]
pub struct RankedEffect {
    /// `gyro.<term>` / `accel.<term>`.
    pub effect: String,
    /// Channel.
    pub channel: String,
    /// BIC change when added to the model (negative favours it).
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated RMSE gain, % (leave one run out, or 5 blocks with fewer than 3 runs).
    pub cv_rmse_gain_pct: f64,
    /// Fitted coefficients in scenario-file units, keyed like the scenario file.
    pub coefficient: Vec<f64>,
    /// Their 95 % intervals.
    pub ci95: Vec<[f64; 2]>,
    /// Scenario keys of the coefficients.
    pub keys: Vec<String>,
    /// Condition number of the fit.
    pub condition_number: f64,
    /// Other effects that explain the same residual on this data.
    pub confusable_with: Vec<Confusable>,
    /// Passes the gate (ΔBIC < −10, Bonferroni p < 0.01, CV gain > 0).
    pub passes_gate: bool,
    /// Parents fitted with it that the model lacked (heredity: the constant of its kind, the
    /// lower powers and factors); when accepted, its figures are on top of them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub parents: Vec<String>,
    /// For `gyro.nav_field_bias` with its three components determined: the field's magnitude
    /// and direction along this axis's sensitivity.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldDirection>,
}

/// A field fixed in the navigation frame as one gyro axis sees it: K·m with K the axis's
/// sensitivity and m the field's unit direction; intervals by the delta method from the
/// components' covariance.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FieldDirection {
    /// |K·m|, °/h.
    pub magnitude_dph: f64,
    /// Its 95 % interval.
    pub magnitude_ci95_dph: [f64; 2],
    /// Declination of m, degrees east of north.
    pub declination_deg: f64,
    /// Its 95 % interval.
    pub declination_ci95_deg: [f64; 2],
    /// Inclination of m, degrees below the horizon.
    pub inclination_deg: f64,
    /// Its 95 % interval.
    pub inclination_ci95_deg: [f64; 2],
}

/// An effect that cannot be told apart from another on this data.
#[derive(Clone, Debug, Serialize)]
pub struct Confusable {
    /// The other effect.
    pub effect: String,
    /// Its ΔBIC minus this one's (below 10: nearly as good).
    pub delta_bic_gap: f64,
    /// Correlation of the two fitted contributions.
    pub correlation: f64,
    /// Variance inflation of this effect's coefficients with the other in the model.
    pub vif: f64,
    /// What experiment would separate them.
    pub separate_by: String,
}

/// What `rins diagnose` reports.
#[derive(Clone, Debug, Serialize)]
pub struct DiagnoseReport {
    /// Data file.
    pub source: String,
    /// Every candidate against the model as given, best first.
    pub ranking: Vec<RankedEffect>,
    /// Effects accepted by forward selection, in order, per channel.
    pub accepted: Vec<RankedEffect>,
    /// Residual RMS per channel before (display units).
    pub residual_rms_before: BTreeMap<String, f64>,
    /// … and after the accepted effects.
    pub residual_rms_after: BTreeMap<String, f64>,
    /// Noise floor RMS per channel.
    pub noise_floor_rms: BTreeMap<String, f64>,
    /// Flagged cells before.
    pub flagged_cells: Vec<Cell>,
    /// Flagged cells the accepted effects leave: where the best model still fails.
    pub flagged_cells_after: Vec<Cell>,
    /// Plain-language summary of the unexplained remainder.
    pub unexplained: Vec<String>,
    /// Candidates that cannot be tested with this data.
    pub unavailable: Vec<(String, String)>,
    /// The column map the data were read with (`None`: none).
    pub column_map: Option<crate::colmap::MapSummary>,
    /// What `--discover` found (absent without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub discovery: Option<discovery::DiscoveryReport>,
}
