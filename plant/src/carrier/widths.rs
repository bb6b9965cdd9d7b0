//! The widths of the carrier's two wide arrays, beneath both their owners (`segment`, `waves`)
//! and the CPU dispatch (`crate::simd`) that runs their loops: the kernels are written for
//! arrays of these widths, and the owners fill them.

/// Channels a tick's increments need (ω_ic^c, f^c, up axis): the first channels of a
/// segment node (`carrier::segment::CHANNELS`).
pub const POINT_CHANNELS: usize = 9;

/// Number of jet values: six degrees of freedom × (value, rate, acceleration).
pub const JET_LEN: usize = 18;
