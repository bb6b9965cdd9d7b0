//! The integration tests of rins-verification in one test binary (one link instead of one per file):
//! one module per former test file.

mod analytic;
mod ins_closed_form;
mod paper_table4;
