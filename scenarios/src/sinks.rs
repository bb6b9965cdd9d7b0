//! Output sinks for the runner: the CSV (and Parquet) file of a run and its static figures.

pub mod csv;
pub mod run_figures;

pub use csv::CsvSink;
pub use run_figures::RunFigures;
