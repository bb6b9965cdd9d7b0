//! # rins-rerun-sink
//!
//! Rerun recordings of rins runs: the IMU rotating through its scheme inside the gimbal frames,
//! the dwell position, Δθ/Δv, gimbal angles, temperatures, each effect's contribution and the
//! navigation errors, with a blueprint that lays them out. Streams to a file (`save:PATH.rrd`),
//! a spawned viewer or a running one. Kept out of the plant's crates: the Rerun SDK is ~500
//! crates. Entities and their units: docs/visualization.md.
//!
//! Long runs are decimated: each series gets one row per bucket of samples, holding the bucket's
//! mean (and, for the IMU output and gimbal angles, its minimum and maximum); the legend of every
//! series says which.

pub mod blueprint;
pub mod bucket;
pub mod carrier;
pub mod nav;
pub mod recorder;
pub mod run;
pub mod scene;
pub mod series;
pub mod target;

pub use blueprint::Layout;
pub use recorder::Recorder;
pub use run::{RunOptions, RunRecorder};
pub use target::Target;
