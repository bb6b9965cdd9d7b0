//! The integration tests of rins-experiments in one test binary (one link instead of one per
//! file): one module per former test file.

mod alignment;
mod azimuth_isolation;
mod calibration;
mod campaign;
mod encoder_error;
mod moving_base_nav;
