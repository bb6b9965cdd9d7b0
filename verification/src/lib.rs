//! # rins-verification
//!
//! Verification of the plant and navigator against independent references: the analytic
//! cancellation of Eq. 8, the δβ residual of Eq. 11, Table 2 of the paper, and (in later
//! modules) closed-form INS error responses and the paper's tables side by side with ours.

pub mod analytic;
pub mod ins;
pub mod paper;
pub mod quadrature;
pub mod report;
pub mod table2;
