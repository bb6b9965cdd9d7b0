//! Output sinks for the runner.

pub mod csv;

pub use csv::CsvSink;
