"""The rins transport wire types (layout version 3) as ctypes structures, for Python peers of
`rins serve` / `rins nav` over iceoryx2 (docs/transport.md, "Wire types from Python and C").

Python standard library only (ctypes): import it next to the PyPI iceoryx2 package
(`pip install iceoryx2==0.10.0`), which takes a payload type's service type name from its
`type_name()` static method:

    sys.path.insert(0, "transport/wire")
    import rins_wire
    service = node.service_builder(name).publish_subscribe(rins_wire.ImuBatch)...

The types mirror transport/src/layout.rs field for field (names, types, order, units), and
transport/wire/rins_wire.h does the same in C. The asserts at the end of this file state every
size, alignment and field offset; `cargo test -p rins-transport --lib layout::wire` compares
them, the type names, the field types and the constants with the Rust definitions and with
rins_wire.h, so the three cannot drift apart unnoticed. (Python skips asserts under `-O`; the
Rust test does not depend on them.)

All little-endian, `#[repr(C)]` without padding, 8-byte aligned. Field types: `ctypes.c_uint64`
is Rust's u64, `ctypes.c_uint32` u32, `ctypes.c_double` f64; `ImuBatch.reason` is
`ctypes.c_char` (one byte, Rust's u8) so that reading it gives `bytes` up to the first NUL.
"""

import ctypes

# Version of the layout below (transport/src/layout.rs, LAYOUT_VERSION); a peer with another one
# is refused with both versions named.
LAYOUT_VERSION = 3
# Records per ImuBatch message.
BATCH_CAPACITY = 64
# Bytes of ImuBatch.reason.
REASON_BYTES = 1024

# ImuBatch.flags bits.
# The last message of a run.
FLAG_END = 1
# The run ended early (SIGINT/SIGTERM on the plant side).
FLAG_INTERRUPTED = 2
# With FLAG_END: the plant refused the navigator's last command and ends the run; `reason` says why.
FLAG_REFUSED = 4
# The truth block is filled (rins serve always fills it): error measures may use it.
FLAG_TRUTH = 8

# NavCommand.kind values (transport/src/layout.rs, `kind`).
# Acknowledge a batch (lockstep), nothing else.
KIND_ACK = 0
# Acknowledge and move the table to (outer_rad, inner_rad) at rate_rps from the next batch's first tick.
KIND_MOVE_TO = 1
# Ask the plant to end the run after this batch.
KIND_STOP = 2
# A navigator has (re)joined: the plant resends the batch it is waiting on.
KIND_HELLO = 3
# Acknowledge and switch azimuth isolation on from the next batch (moving carrier only).
KIND_AZIMUTH_ISOLATION_ON = 4
# Acknowledge and switch azimuth isolation off from the next batch.
KIND_AZIMUTH_ISOLATION_OFF = 5


class ImuRecord(ctypes.Structure):
    """rins::ImuRecord (128 bytes): one IMU output sample with the table and thermal state, only
    what the unit outputs."""

    _fields_ = [
        # Sample number (the plant's integer tick counter at output rate).
        ("tick", ctypes.c_uint64),
        # End of the sample interval, s.
        ("t_s", ctypes.c_double),
        # Angular increment, body axes, rad.
        ("dtheta_rad", ctypes.c_double * 3),
        # Velocity increment, body axes, m/s.
        ("dv_mps", ctypes.c_double * 3),
        # Outer (azimuth) gimbal encoder reading at the end of the interval, rad.
        ("outer_rad", ctypes.c_double),
        # Inner gimbal encoder reading, rad.
        ("inner_rad", ctypes.c_double),
        # Temperature-sensor readings (board, gyro x, y, z, accelerometers, housing), °C.
        ("temps_c", ctypes.c_double * 6),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::ImuRecord"


class TruthRecord(ctypes.Structure):
    """rins::TruthRecord (112 bytes): the carrier and the IMU attitude at the end of a record's
    sample interval. For error measures and loggers only: a navigator must not use it (a real
    unit does not output it)."""

    _fields_ = [
        # Carrier reference point latitude (WGS-84), rad.
        ("lat_rad", ctypes.c_double),
        # Longitude, rad.
        ("lon_rad", ctypes.c_double),
        # Ellipsoidal height, m.
        ("height_m", ctypes.c_double),
        # Carrier ground velocity, ENU, m/s.
        ("v_enu_mps", ctypes.c_double * 3),
        # Carrier attitude q_c^n (w, x, y, z): carrier axes (x starboard, y bow, z up) to ENU.
        ("q_cn", ctypes.c_double * 4),
        # True IMU attitude q_b^n (w, x, y, z): C_c^n·C_v^c·R_z(outer)·R_x(inner) with the true
        # gimbal angles (docs/carrier.md, Frames).
        ("q_bn", ctypes.c_double * 4),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::TruthRecord"


class StartRecord(ctypes.Structure):
    """rins::StartRecord (96 bytes): the navigation state at the start of a batch's first record,
    where a navigator that begins with this batch starts (a real one gets it from GNSS and its
    initial alignment; docs/transport.md, "Start state")."""

    _fields_ = [
        # Samples before the batch: the tick of records[0] (the state is at the start of its interval).
        ("tick", ctypes.c_uint64),
        # Time of the state, s (the start of records[0]'s interval).
        ("t_s", ctypes.c_double),
        # Latitude (WGS-84), rad.
        ("lat_rad", ctypes.c_double),
        # Longitude, rad.
        ("lon_rad", ctypes.c_double),
        # Ellipsoidal height, m (the vertical channel is held there).
        ("height_m", ctypes.c_double),
        # Velocity, ENU, m/s.
        ("v_enu_mps", ctypes.c_double * 3),
        # IMU attitude q_b^n (w, x, y, z).
        ("q_bn", ctypes.c_double * 4),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::StartRecord"


class ImuBatch(ctypes.Structure):
    """rins::ImuBatch (16504 bytes), the payload of service rins/S/imu: a 24-byte header, the
    records, the truth block, the start state and the plant's reason when it refused a command."""

    _fields_ = [
        # LAYOUT_VERSION of the sender.
        ("layout_version", ctypes.c_uint32),
        # sizeof(ImuRecord) of the sender.
        ("record_size", ctypes.c_uint32),
        # Batch sequence number, from 0, +1 per message: a gap means a lost message.
        ("seq", ctypes.c_uint64),
        # Valid records.
        ("count", ctypes.c_uint32),
        # FLAG_END, FLAG_INTERRUPTED, FLAG_REFUSED, FLAG_TRUTH.
        ("flags", ctypes.c_uint32),
        # The records; the first `count` are valid.
        ("records", ImuRecord * BATCH_CAPACITY),
        # The truth over each record (truth[k] goes with records[k]): for error measures only,
        # never for navigation.
        ("truth", TruthRecord * BATCH_CAPACITY),
        # The navigation state at the start of records[0] (filled in every batch).
        ("start", StartRecord),
        # With FLAG_REFUSED: the plant's reason, UTF-8, padded with NUL bytes.
        ("reason", ctypes.c_char * REASON_BYTES),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::ImuBatch"


class NavCommand(ctypes.Structure):
    """rins::NavCommand (40 bytes), the payload of service rins/S/cmd: from the navigation side
    to the plant."""

    _fields_ = [
        # LAYOUT_VERSION of the sender.
        ("layout_version", ctypes.c_uint32),
        # One of the KIND_* values.
        ("kind", ctypes.c_uint32),
        # The batch this acknowledges (lockstep); commands apply after it.
        ("ack_seq", ctypes.c_uint64),
        # Target outer angle, rad.
        ("outer_rad", ctypes.c_double),
        # Target inner angle, rad.
        ("inner_rad", ctypes.c_double),
        # Cruise rate, rad/s.
        ("rate_rps", ctypes.c_double),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::NavCommand"


class NavSolution(ctypes.Structure):
    """rins::NavSolution (96 bytes), the payload of service rins/S/nav: the navigator's solution
    after a batch (published for other consumers)."""

    _fields_ = [
        # Batch it follows.
        ("seq", ctypes.c_uint64),
        # Last tick consumed.
        ("tick", ctypes.c_uint64),
        # Latitude, rad.
        ("lat_rad", ctypes.c_double),
        # Longitude, rad.
        ("lon_rad", ctypes.c_double),
        # Height, m.
        ("height_m", ctypes.c_double),
        # Velocity ENU, m/s.
        ("v_n", ctypes.c_double * 3),
        # Attitude q_b^n (w, x, y, z).
        ("q_bn", ctypes.c_double * 4),
    ]

    @staticmethod
    def type_name() -> str:
        """The iceoryx2 payload type name (Rust: #[type_name(...)])."""
        return "rins::NavSolution"


# The layout, stated once more as numbers: ctypes computes the left-hand sides from the
# declarations above, the Rust test reads the right-hand sides (one assert per line, literal
# numbers).
assert ctypes.sizeof(ImuRecord) == 128
assert ctypes.alignment(ImuRecord) == 8
assert ImuRecord.tick.offset == 0
assert ImuRecord.t_s.offset == 8
assert ImuRecord.dtheta_rad.offset == 16
assert ImuRecord.dv_mps.offset == 40
assert ImuRecord.outer_rad.offset == 64
assert ImuRecord.inner_rad.offset == 72
assert ImuRecord.temps_c.offset == 80

assert ctypes.sizeof(TruthRecord) == 112
assert ctypes.alignment(TruthRecord) == 8
assert TruthRecord.lat_rad.offset == 0
assert TruthRecord.lon_rad.offset == 8
assert TruthRecord.height_m.offset == 16
assert TruthRecord.v_enu_mps.offset == 24
assert TruthRecord.q_cn.offset == 48
assert TruthRecord.q_bn.offset == 80

assert ctypes.sizeof(StartRecord) == 96
assert ctypes.alignment(StartRecord) == 8
assert StartRecord.tick.offset == 0
assert StartRecord.t_s.offset == 8
assert StartRecord.lat_rad.offset == 16
assert StartRecord.lon_rad.offset == 24
assert StartRecord.height_m.offset == 32
assert StartRecord.v_enu_mps.offset == 40
assert StartRecord.q_bn.offset == 64

assert ctypes.sizeof(ImuBatch) == 16504
assert ctypes.alignment(ImuBatch) == 8
assert ImuBatch.layout_version.offset == 0
assert ImuBatch.record_size.offset == 4
assert ImuBatch.seq.offset == 8
assert ImuBatch.count.offset == 16
assert ImuBatch.flags.offset == 20
assert ImuBatch.records.offset == 24
assert ImuBatch.truth.offset == 8216
assert ImuBatch.start.offset == 15384
assert ImuBatch.reason.offset == 15480

assert ctypes.sizeof(NavCommand) == 40
assert ctypes.alignment(NavCommand) == 8
assert NavCommand.layout_version.offset == 0
assert NavCommand.kind.offset == 4
assert NavCommand.ack_seq.offset == 8
assert NavCommand.outer_rad.offset == 16
assert NavCommand.inner_rad.offset == 24
assert NavCommand.rate_rps.offset == 32

assert ctypes.sizeof(NavSolution) == 96
assert ctypes.alignment(NavSolution) == 8
assert NavSolution.seq.offset == 0
assert NavSolution.tick.offset == 8
assert NavSolution.lat_rad.offset == 16
assert NavSolution.lon_rad.offset == 24
assert NavSolution.height_m.offset == 32
assert NavSolution.v_n.offset == 40
assert NavSolution.q_bn.offset == 64
