//! Every figure of a result, one file per result family, on the shared plotting helpers and
//! palette of [`plot`], drawn by the rules of [`rules`]: the verification reports
//! ([`analytic`]), the paired paper studies ([`paper`]), calibration and campaign
//! ([`calibration`]), sweeps ([`sweep`]). Figures drawn while a run streams (a plant run's, the
//! Rerun recordings) are sinks of the application (`rins_scenarios::sinks::RunFigures`,
//! `rins_scenarios::recordings`); the model-vs-measurement report figures are drawn by
//! `rins_scenarios::diagnose::write_report`; both on the same helpers.

pub mod analytic;
pub mod calibration;
pub mod paper;
pub mod plot;
pub mod rules;
pub mod sweep;
