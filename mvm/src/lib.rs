//! # rins-mvm: model vs measurements
//!
//! Replays a model on measured data, shows where it fails, ranks the candidate effects of the
//! plant's catalogue that explain the residual, and fits the chosen ones into the model
//! (docs/model-vs-measurements.md).
//!
//! The steps, each in its own module: [`reader`] (the strict measurement reader,
//! docs/measurement-format.md: [`csv`] or [`parquet`] by the file's first bytes, into a
//! [`measurement::Measurement`]), [`colmap`] (column maps for a logger's own names and units),
//! [`history`] (the measured rows in SI), [`rows`] (the
//! rows walked chunk by chunk of whole segments), [`row_cache`] (a file streamed once into a
//! temporary file and walked back by every pass, so memory does not grow with the file),
//! [`replay`] (model
//! expectation, residual and regressors per row, summed into windows, in one pass over the
//! rows), [`fit`] (weighted least squares, candidate tests, gate, collinearity), [`stats`]
//! (Allan variance, correlations, test distributions), `prepare` (noise floors and folds),
//! `compare` (cell map, correlations, Allan, navigation level), [`selection`] (ranking and
//! forward selection), [`apply`] (fitting chosen effects into the model), [`discover`] (what
//! the catalogue lacks), [`iterate`] (compare → rank → joint fit, step after step, to the noise
//! floor), `swap` (its replacement pass: a stand-in accepted early is swapped for the term the
//! data prefer) and [`report`] (the report types).
//!
//! [`analyse`] is the one entry: it returns everything the `rins compare` / `rins diagnose`
//! commands, their figures and the Rerun recording use, so none of them recomputes anything.

pub mod apply;
mod chunks;
pub mod colmap;
mod compare;
pub mod csv;
pub mod custom;
pub mod discover;
pub mod fit;
pub mod forward;
mod header;
pub mod heredity;
pub mod history;
pub mod iterate;
pub mod measurement;
pub mod parquet;
mod prepare;
pub mod ranges;
pub mod reader;
pub mod replay;
pub mod report;
pub mod row_cache;
pub mod rows;
pub mod selection;
pub mod stats;
mod swap;

use rins_plant::PlantConfig;

pub use apply::{Applied, Coefficient, Fate};
pub use fit::ChannelData;
pub use history::{Attitude, History, to_history, with_data_site, with_site};
pub use iterate::{IterateOptions, Iteration, IterationReport, NearMiss, iterate};
pub use replay::{CHANNELS, Effect, Group, Replay};
pub use report::{
    Cell, ChannelSummary, CompareReport, Confusable, Correlation, DiagnoseReport, FieldDirection,
    NavComparison, NoiseFloor, RankedEffect,
};
pub use row_cache::RowCache;
pub use rows::{Rows, RowsInfo};
pub use selection::Diagnosis;

/// What to compute and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Longest window, s.
    pub window_s: f64,
    /// Width of the temperature bins of the cell map, K.
    pub temp_bin_k: f64,
    /// Length of the time windows of the cell map, s.
    pub time_window_s: f64,
    /// Family-wise level of the cell flags and of the gate.
    pub alpha: f64,
    /// Rank the catalogue's effects, select by the gate and compare again with the selected
    /// effects removed (`rins diagnose`); `false` compares the model as given only
    /// (`rins compare`).
    pub diagnose: bool,
    /// After the catalogue's ranking, search a library of regressors built from the declared
    /// effects' signals for what the catalogue lacks (`rins diagnose --discover`); needs
    /// `diagnose`.
    pub discover: bool,
    /// Effects to switch on and fit into the model (`rins diagnose --apply`); empty: none.
    pub apply: Vec<Effect>,
    /// The column map the data were read with (listed in the reports), if any.
    pub column_map: Option<colmap::MapSummary>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            window_s: 30.0,
            temp_bin_k: 5.0,
            time_window_s: 3600.0,
            alpha: 0.01,
            diagnose: false,
            discover: false,
            apply: Vec::new(),
            column_map: None,
        }
    }
}

/// Everything a comparison (and, when asked, a diagnosis) produced.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// Where the data came from (the history's `source`).
    pub source: String,
    /// Run names.
    pub run_names: Vec<String>,
    /// The replay: windows (inputs, residual and regressor sums), candidate groups, residual
    /// Allan accumulators and the navigation tracks on measured vs modelled increments.
    pub replay: Replay,
    /// Noise floors.
    pub noise: Vec<NoiseFloor>,
    /// Per-channel window data the fits use (residual sums, noise variances, durations, folds).
    pub data: Vec<ChannelData>,
    /// The options it was computed with.
    pub opts: Options,
    /// Runs.
    pub runs: usize,
    /// The model as given against the measurements (`rins compare`).
    pub comparison: CompareReport,
    /// Ranking, selection, fitted predictions and the comparison after them (`opts.diagnose`).
    pub diagnosis: Option<Diagnosis>,
    /// The model with `opts.apply` fitted (`None` when `opts.apply` is empty; `Err` says why
    /// the effects cannot be fitted on this data).
    pub applied: Option<Result<Applied, String>>,
}

impl Analysis {
    /// Per channel and window, the selected effects' fitted contribution (`None` without a
    /// diagnosis): what the figures and the Rerun recording draw against the residual.
    pub fn predictions(&self) -> Option<&[Vec<f64>]> {
        self.diagnosis.as_ref().map(|d| d.predictions.as_slice())
    }

    /// The comparison after the selected effects (`None` without a diagnosis).
    pub fn after(&self) -> Option<&CompareReport> {
        self.diagnosis.as_ref().map(|d| &d.after)
    }
}

/// Replays `model` on `h` (a [`History`] in memory or a [`RowCache`]) once and computes what `opts` asks: the comparison of the model as
/// given, and with `opts.diagnose` the ranking, forward selection, fitted predictions and the
/// comparison after them, and with `opts.apply` the model with those effects fitted.
pub fn analyse(model: &PlantConfig, h: &(impl Rows + ?Sized), opts: &Options) -> Analysis {
    let source = h.info().source;
    let mut p = prepare::prepare(model, h, opts);
    let comparison = p.compare_report(&source, &p.zero_pred());
    let mut diagnosis = opts
        .diagnose
        .then(|| selection::diagnose(&p, &source, &comparison));
    if let Some(first) = diagnosis.as_mut().filter(|_| opts.discover) {
        // The search runs on the catalogue's remainder; its proposals then join the ranking
        // and the forward selection as declared candidates.
        let found = discover::search(model, h, &p, &first.selected);
        if found.augment(model, &mut p) {
            let mut again = selection::diagnose(&p, &source, &comparison);
            let report = found.finish(first, &mut again);
            again.report.discovery = Some(report);
            *first = again;
        } else {
            first.report.discovery = Some(found.into_report());
        }
    }
    let applied = (!opts.apply.is_empty()).then(|| apply::apply(model, &p, &opts.apply));
    let prepare::Prepared {
        run_names,
        replay,
        noise,
        data,
        opts,
        runs,
        ..
    } = p;
    Analysis {
        source,
        run_names,
        replay,
        noise,
        data,
        opts,
        runs,
        comparison,
        diagnosis,
        applied,
    }
}
