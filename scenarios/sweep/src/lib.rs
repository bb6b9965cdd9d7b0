//! Parameter sweeps (`rins sweep FILE`, docs/sweeps.md): a sweep file names a base scenario,
//! the scenario keys to vary over a list or a grid, the seeds, the navigation time and the
//! outputs; every point × seed runs through the Monte Carlo engine with the uncompensated and
//! the δβ-compensated navigator, as `rins paper table4` runs them.
//!
//! [`spec`] loads and checks the file, [`engine`] runs it, [`result`] is what it returns,
//! [`outputs`] the end figures it can tabulate, [`tables`] the per-seed CSV and Parquet.

pub mod engine;
pub mod outputs;
pub mod result;
pub mod spec;
pub mod tables;

pub use engine::run;
pub use result::{NAVIGATORS, SweepReport, value_text};
pub use spec::{SweepError, SweepPlan};
