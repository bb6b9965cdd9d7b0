//! The report page of each result command: which tables (from the result's JSON), which paper
//! values beside them, which figures with what caption. The commands call these with their
//! result and output folder.
//!
//! One file a page (named for the command whose result it shows); the pieces several pages
//! share are in `page_parts`. The `rins sweep` page is [`super::sweep`].

mod analytic;
mod calibration;
mod campaign;
mod compare;
mod diagnose;
mod iterate;
mod page_parts;
mod paired;
mod schemes;
pub mod sea;

pub use analytic::analytic_sections;
pub use calibration::calibration;
pub use campaign::campaign;
pub use compare::compare;
pub use diagnose::diagnose;
pub use iterate::iterate;
pub use paired::{paired, paired_sections, paired_verdict};
pub use schemes::{schemes_analyse, schemes_design};
pub use sea::sea;
