//! # rins-report
//!
//! How `rins` shows a result: every figure (SVG and PNG at print size, by the rules of
//! [`figures::rules`]), the self-contained HTML page of each result command, opening with its
//! verdict in words and numbers ([`html`]), and the terminal text of the results ([`text`]),
//! including how a `diagnose --iterate` run is shown ([`iteration`]) and a simulation's own
//! truth beside what the calibration estimates of it ([`truth`]). It takes finished results;
//! running them is the application's (`rins-scenarios`).

pub mod figures;
pub mod html;
pub mod iteration;
pub mod text;
pub mod truth;
