//! What discovery reports ([`crate::discover::search`]): each library term tested on each channel, the
//! proposals with their bootstrap and ready blocks, the catalogue effects a proposal
//! supersedes, and the terms that are catalogue effects already (identical up to scale, or in
//! the span of two).

use serde::Serialize;

use super::Confusable;

/// One library term tested on one channel.
#[derive(Clone, Debug, Serialize)]
pub struct DiscoveredTerm {
    /// Channel.
    pub channel: String,
    /// What the term is (`bias ∝ dtemp_dt:block`).
    pub term: String,
    /// The regressor as a declared effect writes it (`null` for a position indicator).
    pub regressor: Option<String>,
    /// `bias` or `scale-factor`.
    pub kind: String,
    /// What it was searched on: the `remainder after the catalogue` (its accepted effects in
    /// the base model) or the residual of the `model as given`.
    pub searched_on: String,
    /// Error-reduction ratio: the share of the remaining residual energy (whitened) its part
    /// orthogonal to the model before it explains.
    pub err: f64,
    /// ΔBIC on top of the catalogue's accepted effects and the terms kept before it.
    pub delta_bic: f64,
    /// Nested F-test p-value.
    pub p_value: f64,
    /// Cross-validated RMSE gain, %.
    pub cv_rmse_gain_pct: f64,
    /// Coefficient in file units (°/h, µg or ppm per unit of the regressor).
    pub coefficient: f64,
    /// Its 95 % interval.
    pub ci95: [f64; 2],
    /// Unit of the coefficient.
    pub unit: String,
    /// Passes the gate (the catalogue's, Bonferroni over the library).
    pub passes_gate: bool,
    /// Share of bootstrap resamples over runs in which the orthogonal selection picks it.
    pub bootstrap_frequency: f64,
    /// Catalogue effects whose fitted contribution is collinear with its own.
    pub confusable_with: Vec<Confusable>,
    /// A memory term's time constant, by profile likelihood (`--discover` searches it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tau: Option<TauReport>,
    /// The kept term this one entered with as a parent (heredity), if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parent_of: Option<String>,
}

/// The time constant of a discovered memory term.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TauReport {
    /// The estimate (profile-likelihood minimum, rounded to three digits), s.
    pub tau_s: f64,
    /// Its 95 % interval, s (an open end is the searched range's end: 10 s or 3 h).
    pub ci95_s: [f64; 2],
    /// Whether each end is open (the profile never leaves the bound on that side).
    pub open: [bool; 2],
    /// The grid point the selection picked, s.
    pub grid_tau_s: f64,
    /// How much wider the coefficient's interval is with τ free than with τ fixed at its
    /// estimate (the joint fit that writes the model fixes τ and widens its intervals by this).
    pub coefficient_widening: f64,
    /// The coefficient's 95 % interval with τ free (file units): linearised, and the envelope
    /// over the time constants the data allow (the joint fit's interval covers it too).
    pub coefficient_ci95: [f64; 2],
}

/// A proposal: one term on the axes it was found on, as a declared effect.
#[derive(Clone, Debug, Serialize)]
pub struct Proposal {
    /// Name (`custom:NAME` for `--apply`).
    pub name: String,
    /// `gyro` or `accel`.
    pub sensor: String,
    /// The term's tests, per channel it was kept on.
    pub terms: Vec<DiscoveredTerm>,
    /// Coefficients per axis (x, y, z) in file units; 0 on axes it was not found on.
    pub coef: [f64; 3],
    /// The `[[sensor.gyro.custom]]` / `[[sensor.accel.custom]]` block (`null` when the term
    /// cannot be declared: a position indicator).
    pub toml: Option<String>,
}

/// A catalogue effect accepted on the catalogue alone that a discovered term replaced.
#[derive(Clone, Debug, Serialize)]
pub struct Superseded {
    /// Channel.
    pub channel: String,
    /// The catalogue effect (now reported confusable, not accepted).
    pub effect: String,
    /// The discovered effect that explains the residual better.
    pub by: String,
    /// ΔBIC of the catalogue effect against the model as given.
    pub delta_bic_effect: f64,
    /// ΔBIC of the discovered one.
    pub delta_bic_by: f64,
}

/// What `--discover` reports.
#[derive(Clone, Debug, Serialize)]
pub struct DiscoveryReport {
    /// Library terms per channel (signals and their products as bias and scale factor, and
    /// position indicators).
    pub library_terms: Vec<(String, usize)>,
    /// Tests the gate's Bonferroni split counts (every term on every channel).
    pub tests: usize,
    /// Bootstrap resamples over runs.
    pub bootstrap_resamples: usize,
    /// Proposals (terms that passed the gate), best first.
    pub proposals: Vec<Proposal>,
    /// Per channel, the best term the gate refused (the nearest miss).
    pub refused: Vec<DiscoveredTerm>,
    /// Catalogue effects replaced by a discovered one.
    pub superseded: Vec<Superseded>,
    /// Library terms whose column is, on this data, a catalogue effect's column up to scale:
    /// not new physics, so not proposed; the catalogue effect is tested in its place.
    pub identical: Vec<Identical>,
    /// Kept terms whose column is, on this data, a combination of two other columns of the
    /// channel (kept terms or catalogue columns): a dependence among three that the pairwise
    /// `identical` check cannot see.
    pub dependent: Vec<Dependent>,
}

/// Three columns of a channel that are linearly dependent on this data: `term` = a·`on[0]` +
/// b·`on[1]` at every window. Their coefficients are then determined only as a combination:
/// each one's value depends on which of the others is in the fit.
#[derive(Clone, Debug, Serialize)]
pub struct Dependent {
    /// Channel.
    pub channel: String,
    /// The kept library term.
    pub term: String,
    /// The two columns it is a combination of (a kept term, or a catalogue coefficient key).
    pub on: [String; 2],
    /// a and b (in the columns' SI units).
    pub weights: [f64; 2],
}

/// A library term identical on the data to a catalogue effect's regressor.
#[derive(Clone, Debug, Serialize)]
pub struct Identical {
    /// Channel.
    pub channel: String,
    /// The library term (`bias ∝ u_z`).
    pub term: String,
    /// The catalogue effect it is (`gyro.g_sensitivity`).
    pub effect: String,
    /// Whether the two are the same function of the signals, so that no experiment can
    /// separate them (e.g. a bias ∝ u_z is G_zz·f_z/g₀ with f = g·u); otherwise they only
    /// coincide on this data and a different experiment would split them.
    pub by_definition: bool,
}
