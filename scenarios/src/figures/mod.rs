//! Every figure the commands write, one file per result family, on the shared plotting helpers
//! and palette of [`plot`], drawn by the rules of [`rules`]: a plant run ([`run`]), the verification reports ([`analytic`]), the
//! paired paper studies ([`paper`]), calibration and campaign ([`calibration`]), and with the
//! `rerun` feature the Rerun recordings ([`rerun`]). The model-vs-measurement report figures
//! are drawn by `crate::diagnose::write_report` on the same helpers.

pub mod analytic;
pub mod calibration;
pub mod paper;
pub mod plot;
#[cfg(feature = "rerun")]
pub mod rerun;
pub mod rules;
pub mod run;
pub mod sweep;

pub use run::RunFigures;
