//! The wire types, `#[repr(C)]` with explicit iceoryx2 type names. iceoryx2 itself checks only
//! name, size and alignment; every message also carries [`LAYOUT_VERSION`] and the record size,
//! so a peer built against another layout is refused with a clear message (docs/transport.md).
//!
//! Version 2 adds a truth block to each batch ([`TruthRecord`], one per record): what really
//! happened, for error measures only. It sits beside the records, not in them, so the records
//! stay the unit's measured outputs; the navigator side never reads it.
//!
//! Version 3 adds, after the truth block, the state a navigator starts from ([`StartRecord`]:
//! position, velocity and attitude at the start of the batch's first record, what the
//! in-process run is initialised with; a real navigator gets it from GNSS and its initial
//! alignment) and the plant's reason when it ends the run refusing a command
//! ([`FLAG_REFUSED`]).

// The ZeroCopySend derive emits `unsafe impl`: the types are plain old data, self-contained and
// position-independent, which is what the trait requires.
#![allow(unsafe_code)]

use iceoryx2::prelude::*;

/// Version of the layout below; bump on any change (2: the truth block of [`ImuBatch`]; 3: its
/// start state and refusal reason).
pub const LAYOUT_VERSION: u32 = 3;
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
    /// True IMU attitude q_b^n (w, x, y, z): q_c^n·q_v^c·q_z(outer)·q_x(inner) with the true
    /// gimbal angles, in closed form ([`rins_plant::Plant::attitude_q_bn`]; the quaternion of
    /// C_c^n·C_v^c·R_z(outer)·R_x(inner), docs/carrier.md, Frames).
    pub q_bn: [f64; 4],
}

impl TruthRecord {
    /// The truth of `plant` now (after its last step). The static carrier gives the site, zero
    /// velocity and the `[vehicle]` attitude.
    pub fn from_plant(plant: &rins_plant::Plant) -> Self {
        let c = plant.carrier_truth();
        let q_cn = c.q_cn.quaternion();
        // The plant's closed-form truth attitude, as the CSV and the FMU give it.
        let q_bn = plant.attitude_q_bn();
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

/// The navigation state at the start of a batch's first record (96 bytes): what a navigator
/// that begins with this batch starts from. The plant fills it in every batch with the state
/// the in-process navigation run is initialised with (`rins_experiments::Tracker::at_truth`):
/// the table's true attitude, and the site at rest (static carrier) or the carrier's reference
/// point with its ground velocity (moving carrier). It stands for what a real navigation
/// computer gets at start-up from outside the IMU: a GNSS fix and velocity, and an initial
/// attitude from its alignment (gyrocompassing at rest, or in-motion / transfer alignment at
/// sea); docs/transport.md, "Start state".
#[derive(Clone, Copy, Debug, Default, PartialEq, ZeroCopySend)]
#[type_name("rins::StartRecord")]
#[repr(C)]
pub struct StartRecord {
    /// Samples before the batch: the tick of `records[0]` (the state is at the start of its
    /// interval).
    pub tick: u64,
    /// Time of the state, s (the start of `records[0]`'s interval).
    pub t_s: f64,
    /// Latitude (WGS-84), rad.
    pub lat_rad: f64,
    /// Longitude, rad.
    pub lon_rad: f64,
    /// Ellipsoidal height, m (the vertical channel is held there).
    pub height_m: f64,
    /// Velocity, ENU, m/s.
    pub v_enu_mps: [f64; 3],
    /// IMU attitude q_b^n (w, x, y, z).
    pub q_bn: [f64; 4],
}

impl StartRecord {
    /// The state `plant` is in now (before its next step), as the in-process navigation run
    /// starts from it (`rins_experiments::session`'s initial state, bit for bit): the true IMU
    /// attitude, and the site at rest on the static carrier or the carrier's reference point
    /// and ground velocity on a moving one.
    pub fn from_plant(plant: &rins_plant::Plant) -> Self {
        let q = plant.attitude_q_bn();
        let q = q.quaternion();
        let (lat_rad, lon_rad, height_m, v) = if plant.moving_carrier() {
            let c = plant.carrier_truth();
            (c.lat_rad, c.lon_rad, c.height_m, c.v_n.into())
        } else {
            let s = plant.site();
            (s.lat_rad, s.lon_rad, s.height_m, [0.0; 3])
        };
        Self {
            tick: plant.samples_done(),
            t_s: plant.time_s(),
            lat_rad,
            lon_rad,
            height_m,
            v_enu_mps: v,
            q_bn: [q.w, q.i, q.j, q.k],
        }
    }

    /// The navigation state it describes (the quaternion taken as sent, bit for bit).
    pub fn nav_state(&self) -> rins_navigation::strapdown::NavState {
        let [w, i, j, k] = self.q_bn;
        rins_navigation::strapdown::NavState {
            q_bn: nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(w, i, j, k)),
            v_n: self.v_enu_mps.into(),
            lat_rad: self.lat_rad,
            lon_rad: self.lon_rad,
            height_m: self.height_m,
        }
    }
}

/// Flag: the last message of a run.
pub const FLAG_END: u32 = 1;
/// Flag: the run ended early (SIGINT/SIGTERM on the plant side).
pub const FLAG_INTERRUPTED: u32 = 2;
/// Flag (with [`FLAG_END`]): the plant refused the navigator's last command and ends the run;
/// [`ImuBatch::reason`] says why.
pub const FLAG_REFUSED: u32 = 4;
/// Flag: the truth block is filled (rins serve always fills it; a peer publishing batches of
/// its own may not): error measures may use it.
pub const FLAG_TRUTH: u32 = 8;
/// Bytes of [`ImuBatch::reason`].
pub const REASON_BYTES: usize = 1024;

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
    /// [`FLAG_END`], [`FLAG_INTERRUPTED`], [`FLAG_REFUSED`], [`FLAG_TRUTH`].
    pub flags: u32,
    /// The records; the first `count` are valid.
    pub records: [ImuRecord; BATCH_CAPACITY],
    /// The truth over each record (`truth[k]` goes with `records[k]`): for error measures
    /// only, never for navigation.
    pub truth: [TruthRecord; BATCH_CAPACITY],
    /// The navigation state at the start of `records[0]`: where a navigator that begins with
    /// this batch starts (filled in every batch).
    pub start: StartRecord,
    /// With [`FLAG_REFUSED`]: the plant's reason, UTF-8, padded with NUL bytes.
    pub reason: [u8; REASON_BYTES],
}

impl ImuBatch {
    /// Writes `text` into [`ImuBatch::reason`], cut at a character boundary to fit.
    pub fn set_reason(&mut self, text: &str) {
        let mut end = text.len().min(REASON_BYTES);
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        self.reason = [0; REASON_BYTES];
        self.reason[..end].copy_from_slice(&text.as_bytes()[..end]);
    }

    /// [`ImuBatch::reason`] as text (up to the first NUL byte; invalid UTF-8 replaced).
    pub fn reason_text(&self) -> String {
        let end = self
            .reason
            .iter()
            .position(|&b| b == 0)
            .unwrap_or(REASON_BYTES);
        String::from_utf8_lossy(&self.reason[..end]).into_owned()
    }
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
            start: StartRecord::default(),
            reason: [0; REASON_BYTES],
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
        assert_eq!(std::mem::size_of::<StartRecord>(), 96);
        assert_eq!(
            std::mem::size_of::<ImuBatch>(),
            24 + (128 + 112) * BATCH_CAPACITY + 96 + REASON_BYTES
        );
        assert_eq!(std::mem::size_of::<ImuBatch>(), 16504);
        assert_eq!(std::mem::offset_of!(ImuBatch, truth), 24 + 128 * 64);
        assert_eq!(std::mem::offset_of!(ImuBatch, start), 15384);
        assert_eq!(std::mem::offset_of!(ImuBatch, reason), 15480);
        assert_eq!(std::mem::offset_of!(StartRecord, v_enu_mps), 40);
        assert_eq!(std::mem::offset_of!(StartRecord, q_bn), 64);
        assert_eq!(std::mem::offset_of!(TruthRecord, q_cn), 48);
        assert_eq!(std::mem::offset_of!(TruthRecord, q_bn), 80);
        assert_eq!(std::mem::align_of::<ImuBatch>(), 8);
        assert_eq!(std::mem::size_of::<NavCommand>(), 40);
        assert_eq!(std::mem::size_of::<NavSolution>(), 96);
        assert_eq!(std::mem::offset_of!(ImuBatch, records), 24);
        assert_eq!(std::mem::offset_of!(ImuRecord, temps_c), 80);
    }

    /// The records carry the plant's output columns ([`rins_plant::output_columns`]) as the
    /// table reads them: [`ImuRecord`] every measured column, [`TruthRecord`] the attitude and
    /// the carrier's truth. The layout is fixed (`#[repr(C)]`, [`LAYOUT_VERSION`]), so a column
    /// added to the table fails here until it is put on the wire (a new layout version) or
    /// named as one the wire leaves out.
    #[test]
    fn the_records_carry_the_output_columns_of_the_table() {
        use rins_plant::output_columns::{Group, Reading, every_entry_read};
        let cfg = rins_plant::presets::paper_16pos_config();
        let mut plant = rins_plant::Plant::new(&cfg).unwrap();
        let mut s = plant.step();
        for _ in 0..300 {
            s = plant.step();
        }
        let (truth, mount) = (plant.truth(), plant.truth_mount());
        let r = Reading {
            sample: &s,
            truth: &truth,
            mount: &mount,
        };
        let (rec, tr) = (ImuRecord::from_sample(&s), TruthRecord::from_plant(&plant));
        for (e, want) in every_entry_read(&r) {
            let got: Vec<f64> = match e.column.key {
                "sample" => {
                    assert_eq!(rec.tick, s.index);
                    continue;
                }
                "t_s" => vec![rec.t_s],
                "dtheta_rad" => rec.dtheta_rad.to_vec(),
                "dv_mps" => rec.dv_mps.to_vec(),
                "outer_deg" => vec![rec.outer_rad.to_degrees()],
                "inner_deg" => vec![rec.inner_rad.to_degrees()],
                "temps_c" => rec.temps_c.to_vec(),
                "q_bn" => tr.q_bn.to_vec(),
                "carrier" => [
                    tr.lat_rad.to_degrees(),
                    tr.lon_rad.to_degrees(),
                    tr.height_m,
                ]
                .into_iter()
                .chain(tr.v_enu_mps)
                .chain(tr.q_cn)
                .collect(),
                // Not on the wire: the test set-up (station label, chamber) and the truth a
                // navigator's error measures do not take from the batch (the error-free
                // increments, the gimbal angles, the per-term errors).
                "position" | "temp_chamber_c" | "dtheta_true_rad" | "dv_true_mps"
                | "gimbal_outer_rad" | "gimbal_inner_rad" | "gyro_effects_dph"
                | "accel_effects_ug" => continue,
                k => panic!(
                    "the output column {k} is not on the wire: add it to ImuRecord (measured) \
                     or TruthRecord (truth) with a new LAYOUT_VERSION, or list it here as left out"
                ),
            };
            assert_eq!(got, want, "column {}", e.column.key);
            assert_eq!(
                matches!(e.column.group, Group::Measured),
                e.column.key != "q_bn" && e.column.key != "carrier",
                "{}: the measured columns ride in ImuRecord, the truth in TruthRecord",
                e.column.key
            );
        }
    }

    #[test]
    fn a_reason_is_cut_at_a_character_boundary_and_read_back() {
        let mut b = ImuBatch::default();
        b.set_reason("refused: ü");
        assert_eq!(b.reason_text(), "refused: ü");
        // All but one byte ASCII, then a 2-byte character: it does not fit and is left out.
        let long = format!("{}ü", "x".repeat(REASON_BYTES - 1));
        b.set_reason(&long);
        assert_eq!(b.reason_text(), "x".repeat(REASON_BYTES - 1));
        b.set_reason("");
        assert_eq!(b.reason_text(), "");
    }
}

// The Python and C mirrors of these types (transport/wire) checked against them.
#[cfg(test)]
mod wire;
