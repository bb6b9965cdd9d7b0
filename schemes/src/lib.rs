//! # rins-schemes
//!
//! Rotation schemes as a design space. The paper's Eq. 11 shows that the 16-position scheme
//! leaves −8·T_s·δβ_z per cycle of a position-dependent bias; this crate answers the question
//! for any scheme and any effect:
//!
//! * [`analyse`]: the per-cycle residual ∫ C_b^n·δ dt of every effect (catalogue, declared, and
//!   the general position-dependent bias b_i(u) expanded to second order in the up direction),
//!   by quadrature of the plant's own schedule and, where the moves run at constant rate, by
//!   exact integration of the trigonometric polynomial they make, with both compared;
//! * [`response`]: what a residual does to a static navigator after N days (Schuler-averaged
//!   position and heading of the linear error model);
//! * [`bound`]: the worst case over a box-bounded class of coefficients, the coefficients
//!   that attain it, and the part no scheme can remove;
//! * [`design`]: a search over schemes built from the table's moves;
//! * [`simulate`]: the same figures from week-long runs of the plant and the navigator.
//!
//! Every effect is evaluated through the plant's own models (`GyroModel`, `AccelModel`, the
//! declared-effect plans), so what is analysed is what the plant simulates.

pub mod analyse;
pub mod basis;
pub mod bound;
pub mod cycle;
pub mod design;
pub mod effects;
pub mod library;
pub mod response;
pub mod scheme_file;
pub mod simulate;
pub mod trig_exact;

pub use analyse::{AnalyseOptions, EffectResidual, SchemeAnalysis, analyse_scheme};
pub use effects::{Channel, EffectSet, Sensor};
pub use scheme_file::{SchemeFile, SchemeFileError};
