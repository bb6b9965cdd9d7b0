//! The dual-axis rotation table: schemes as data, motion profiles, gimbal kinematics.

pub mod gimbal;
pub mod profile;
pub mod schedule;
pub mod scheme;
pub mod turn;

pub use gimbal::{
    GimbalAngles, GimbalAxis, GimbalFrame, body_to_nav, gimbal_body_rate, position_label,
};
pub use schedule::{Cursor, GimbalState, Schedule};
pub use scheme::{RotationStep, SchemeKind, SchemeSpec};
pub use turn::SmoothTurn;
