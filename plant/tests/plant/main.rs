//! The integration tests of rins-plant in one test binary (one link instead of one per file): one
//! module per former test file; `carrier_common` is what the carrier tests share.

mod carrier_common;

mod carrier_kinematics;
mod carrier_segment;
mod carrier_trajectory;
mod custom_effects;
mod dwell_cache;
mod effects;
mod gimbal_command;
mod isolation_reference;
mod readouts;
mod state;
mod state_fuzz;
mod trajectory_bytes;
mod truth_attitude;
