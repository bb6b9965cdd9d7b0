//! The wire types, `#[repr(C)]` with explicit iceoryx2 type names. iceoryx2 itself checks only
//! name, size and alignment; every message also carries [`LAYOUT_VERSION`] and the record size,
//! so a peer built against another layout is refused with a clear message (docs/transport.md).
//!
//! Version 2 adds a truth block to each batch ([`TruthRecord`], one per record): what really
//! happened, for error measures only. It sits beside the records, not in them, so the records
//! stay the unit's measured outputs; the navigator side never reads it.

// The ZeroCopySend derive emits `unsafe impl`: the types are plain old data, self-contained and
// position-independent, which is what the trait requires.
#![allow(unsafe_code)]

use iceoryx2::prelude::*;

/// Version of the layout below; bump on any change (2: the truth block of [`ImuBatch`]).
pub const LAYOUT_VERSION: u32 = 2;
/// Records per [`ImuBatch`] message (batching is what reaches millions of samples per second).
pub const BATCH_CAPACITY: usize = 64;

/// One IMU output sample with the table and thermal state (128 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq, ZeroCopySend)]
#[type_name("rins::ImuRecord")]
#[repr(C)]
pub struct ImuRecord {
    /// Sample number (the plant's integer tick counter at output rate).
    pub tick: u64,
    /// End of the sample interval, s.
    pub t_s: f64,
    /// Angular increment, body axes, rad.
    pub dtheta_rad: [f64; 3],
    /// Velocity increment, body axes, m/s.
    pub dv_mps: [f64; 3],
    /// Outer (azimuth) gimbal encoder reading at the end of the interval, rad.
    pub outer_rad: f64,
    /// Inner gimbal encoder reading, rad.
    pub inner_rad: f64,
    /// Temperature-sensor readings (board, gyro x, y, z, accelerometers, housing), °C.
    pub temps_c: [f64; 6],
}

impl ImuRecord {
    /// The record of one plant output sample: only what the unit outputs (increments, encoder
    /// angles, temperature-sensor readings).
    pub fn from_sample(s: &rins_plant::ImuSample) -> Self {
        Self {
            tick: s.index,
            t_s: s.t_s,
            dtheta_rad: s.dtheta_rad.into(),
            dv_mps: s.dv_mps.into(),
            outer_rad: s.encoder.outer_rad,
            inner_rad: s.encoder.inner_rad,
            temps_c: s.temps_c,
        }
    }
}

/// The truth over one record (112 bytes): the carrier and the IMU attitude at the end of the
/// sample interval, from the plant's [`rins_plant::Truth`]. For error measures and loggers
/// only: a navigator must not use it (a real unit does not output it).
#[derive(Clone, Copy, Debug, Default, PartialEq, ZeroCopySend)]
#[type_name("rins::TruthRecord")]
#[repr(C)]
pub struct TruthRecord {
    /// Carrier reference point latitude (WGS-84), rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Ellipsoidal height, m.
    pub height_m: f64,
    /// Carrier ground velocity, ENU, m/s.
    pub v_enu_mps: [f64; 3],
    /// Carrier attitude q_c^n (w, x, y, z): carrier axes (x starboard, y bow, z up) to ENU.
    pub q_cn: [f64; 4],
    /// True IMU attitude q_b^n (w, x, y, z): C_c^n·C_v^c·R_z(outer)·R_x(inner) with the true
    /// gimbal angles (docs/carrier.md, Frames).
    pub q_bn: [f64; 4],
}

impl TruthRecord {
    /// The truth of `plant` now (after its last step). The static carrier gives the site, zero
    /// velocity and the `[vehicle]` attitude.
    pub fn from_plant(plant: &rins_plant::Plant) -> Self {
        let c = plant.carrier_truth();
        let q_cn = c.q_cn.quaternion();
        let q_bn = nalgebra::UnitQuaternion::from_rotation_matrix(
            &nalgebra::Rotation3::from_matrix_unchecked(plant.attitude_c_bn()),
        );
        let q_bn = q_bn.quaternion();
        Self {
            lat_rad: c.lat_rad,
            lon_rad: c.lon_rad,
            height_m: c.height_m,
            v_enu_mps: c.v_n.into(),
            q_cn: [q_cn.w, q_cn.i, q_cn.j, q_cn.k],
            q_bn: [q_bn.w, q_bn.i, q_bn.j, q_bn.k],
        }
    }
}

/// Flag: the last message of a run.
pub const FLAG_END: u32 = 1;
/// Flag: the run ended early (SIGINT/SIGTERM on the plant side).
pub const FLAG_INTERRUPTED: u32 = 2;

/// A batch of consecutive records, the unit of the IMU service.
#[derive(Clone, Copy, Debug, ZeroCopySend)]
#[type_name("rins::ImuBatch")]
#[repr(C)]
pub struct ImuBatch {
    /// [`LAYOUT_VERSION`] of the sender.
    pub layout_version: u32,
    /// `size_of::<ImuRecord>()` of the sender.
    pub record_size: u32,
    /// Batch sequence number, from 0, +1 per message: a gap means a lost message.
    pub seq: u64,
    /// Valid records.
    pub count: u32,
    /// [`FLAG_END`], [`FLAG_INTERRUPTED`].
    pub flags: u32,
    /// The records; the first `count` are valid.
    pub records: [ImuRecord; BATCH_CAPACITY],
    /// The truth over each record (`truth[k]` goes with `records[k]`): for error measures
    /// only, never for navigation.
    pub truth: [TruthRecord; BATCH_CAPACITY],
}

impl Default for ImuBatch {
    fn default() -> Self {
        Self {
            layout_version: LAYOUT_VERSION,
            record_size: std::mem::size_of::<ImuRecord>() as u32,
            seq: 0,
            count: 0,
            flags: 0,
            records: [ImuRecord::default(); BATCH_CAPACITY],
            truth: [TruthRecord::default(); BATCH_CAPACITY],
        }
    }
}

/// Command kinds.
pub mod kind {
    /// Acknowledge a batch (lockstep), nothing else.
    pub const ACK: u32 = 0;
    /// Acknowledge and move the table to (`outer_rad`, `inner_rad`) at `rate_rps`, starting at
    /// the first tick of the next batch.
    pub const MOVE_TO: u32 = 1;
    /// Ask the plant to end the run after this batch.
    pub const STOP: u32 = 2;
    /// A navigator has (re)joined: the plant resends the batch it is waiting on. Covers a
    /// restarted navigator that cleaned up its dead predecessor before the plant noticed.
    pub const HELLO: u32 = 3;
    /// Acknowledge and switch azimuth isolation on from the first tick of the next batch (a
    /// moving carrier of the plant's scenario only; docs/carrier.md, "Azimuth isolation").
    pub const AZIMUTH_ISOLATION_ON: u32 = 4;
    /// Acknowledge and switch azimuth isolation off from the first tick of the next batch (the
    /// outer offset stays where it is).
    pub const AZIMUTH_ISOLATION_OFF: u32 = 5;
}

/// From the navigation side to the plant.
#[derive(Clone, Copy, Debug, Default, PartialEq, ZeroCopySend)]
#[type_name("rins::NavCommand")]
#[repr(C)]
pub struct NavCommand {
    /// [`LAYOUT_VERSION`] of the sender.
    pub layout_version: u32,
    /// One of [`kind`].
    pub kind: u32,
    /// The batch this acknowledges (lockstep); commands apply after it.
    pub ack_seq: u64,
    /// Target outer angle, rad.
    pub outer_rad: f64,
    /// Target inner angle, rad.
    pub inner_rad: f64,
    /// Cruise rate, rad/s.
    pub rate_rps: f64,
}

/// The navigator's solution after a batch (published for other consumers).
#[derive(Clone, Copy, Debug, Default, PartialEq, ZeroCopySend)]
#[type_name("rins::NavSolution")]
#[repr(C)]
pub struct NavSolution {
    /// Batch it follows.
    pub seq: u64,
    /// Last tick consumed.
    pub tick: u64,
    /// Latitude, rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Height, m.
    pub height_m: f64,
    /// Velocity ENU, m/s.
    pub v_n: [f64; 3],
    /// Attitude q_b^n (w, x, y, z).
    pub q_bn: [f64; 4],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_the_documented_ones() {
        // docs/transport.md gives these offsets and sizes to C and Python peers.
        assert_eq!(std::mem::size_of::<ImuRecord>(), 128);
        assert_eq!(std::mem::size_of::<TruthRecord>(), 112);
        assert_eq!(
            std::mem::size_of::<ImuBatch>(),
            24 + (128 + 112) * BATCH_CAPACITY
        );
        assert_eq!(std::mem::offset_of!(ImuBatch, truth), 24 + 128 * 64);
        assert_eq!(std::mem::offset_of!(TruthRecord, q_cn), 48);
        assert_eq!(std::mem::offset_of!(TruthRecord, q_bn), 80);
        assert_eq!(std::mem::align_of::<ImuBatch>(), 8);
        assert_eq!(std::mem::size_of::<NavCommand>(), 40);
        assert_eq!(std::mem::size_of::<NavSolution>(), 96);
        assert_eq!(std::mem::offset_of!(ImuBatch, records), 24);
        assert_eq!(std::mem::offset_of!(ImuRecord, temps_c), 80);
    }
}
