/*
 * The rins transport wire types (layout version 3) in C11 (and C++), for C/C++ peers of
 * `rins serve` / `rins nav` over iceoryx2 (docs/transport.md, "Wire types from Python and C").
 *
 * The structs mirror transport/src/layout.rs field for field (names, types, order, units), and
 * transport/wire/rins_wire.py does the same in Python. The static asserts state every size,
 * alignment and field offset, so a compiler with another layout stops here; the test
 * `cargo test -p rins-transport --lib layout::wire` compares their numbers, the type names,
 * the field types and the constants with the Rust definitions and with rins_wire.py, and
 * compiles this header with `cc -std=c11 -fsyntax-only` (and `c++ -std=c++17`).
 *
 * All little-endian, `#[repr(C)]` without padding, 8-byte aligned (the asserts fail on an ABI
 * that aligns double at 4 inside structs, e.g. 32-bit x86).
 *
 * iceoryx2 identifies a payload by type name, size and alignment. C: pass RINS_*_TYPE_NAME,
 * sizeof and alignof to iox2_service_builder_pub_sub_set_payload_type_details. C++: the
 * bindings read the IOX2_TYPE_NAME member each struct has there.
 */
#ifndef RINS_WIRE_H
#define RINS_WIRE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
/* C++ spells C11's _Static_assert and _Alignof as static_assert and alignof. */
#ifndef _Static_assert
#define _Static_assert static_assert
#endif
#ifndef _Alignof
#define _Alignof alignof
#endif
/* The iceoryx2 C++ bindings take a payload's type name from this static member. */
#define RINS_WIRE_TYPE_NAME(name) static constexpr const char *IOX2_TYPE_NAME = name;
#else
/* C has no static members: the names are the RINS_*_TYPE_NAME macros. */
#define RINS_WIRE_TYPE_NAME(name)
#endif

/* Version of the layout below (LAYOUT_VERSION); a peer with another one is refused. */
#define RINS_LAYOUT_VERSION 3
/* Records per rins_ImuBatch message. */
#define RINS_BATCH_CAPACITY 64
/* Bytes of rins_ImuBatch.reason. */
#define RINS_REASON_BYTES 1024

/* rins_ImuBatch.flags bits. */
/* The last message of a run. */
#define RINS_FLAG_END 1
/* The run ended early (SIGINT/SIGTERM on the plant side). */
#define RINS_FLAG_INTERRUPTED 2
/* With RINS_FLAG_END: the plant refused the navigator's last command; `reason` says why. */
#define RINS_FLAG_REFUSED 4
/* The truth block is filled (rins serve always fills it): error measures may use it. */
#define RINS_FLAG_TRUTH 8

/* rins_NavCommand.kind values. */
/* Acknowledge a batch (lockstep), nothing else. */
#define RINS_KIND_ACK 0
/* Acknowledge and move the table to (outer_rad, inner_rad) at rate_rps from the next batch. */
#define RINS_KIND_MOVE_TO 1
/* Ask the plant to end the run after this batch. */
#define RINS_KIND_STOP 2
/* A navigator has (re)joined: the plant resends the batch it is waiting on. */
#define RINS_KIND_HELLO 3
/* Acknowledge and switch azimuth isolation on from the next batch (moving carrier only). */
#define RINS_KIND_AZIMUTH_ISOLATION_ON 4
/* Acknowledge and switch azimuth isolation off from the next batch. */
#define RINS_KIND_AZIMUTH_ISOLATION_OFF 5

/* The iceoryx2 payload type names (Rust: #[type_name(...)]). */
#define RINS_IMU_RECORD_TYPE_NAME "rins::ImuRecord"
#define RINS_TRUTH_RECORD_TYPE_NAME "rins::TruthRecord"
#define RINS_START_RECORD_TYPE_NAME "rins::StartRecord"
#define RINS_IMU_BATCH_TYPE_NAME "rins::ImuBatch"
#define RINS_NAV_COMMAND_TYPE_NAME "rins::NavCommand"
#define RINS_NAV_SOLUTION_TYPE_NAME "rins::NavSolution"

/* rins::ImuRecord (128 bytes): one IMU output sample, only what the unit outputs. */
typedef struct rins_ImuRecord {
    RINS_WIRE_TYPE_NAME(RINS_IMU_RECORD_TYPE_NAME)
    /* Sample number (the plant's integer tick counter at output rate). */
    uint64_t tick;
    /* End of the sample interval, s. */
    double t_s;
    /* Angular increment, body axes, rad. */
    double dtheta_rad[3];
    /* Velocity increment, body axes, m/s. */
    double dv_mps[3];
    /* Outer (azimuth) gimbal encoder reading at the end of the interval, rad. */
    double outer_rad;
    /* Inner gimbal encoder reading, rad. */
    double inner_rad;
    /* Temperature-sensor readings (board, gyro x, y, z, accelerometers, housing), deg C. */
    double temps_c[6];
} rins_ImuRecord;

/*
 * rins::TruthRecord (112 bytes): the carrier and the IMU attitude at the end of a record's
 * sample interval. For error measures and loggers only: a navigator must not use it.
 */
typedef struct rins_TruthRecord {
    RINS_WIRE_TYPE_NAME(RINS_TRUTH_RECORD_TYPE_NAME)
    /* Carrier reference point latitude (WGS-84), rad. */
    double lat_rad;
    /* Longitude, rad. */
    double lon_rad;
    /* Ellipsoidal height, m. */
    double height_m;
    /* Carrier ground velocity, ENU, m/s. */
    double v_enu_mps[3];
    /* Carrier attitude q_c^n (w, x, y, z): carrier axes (x starboard, y bow, z up) to ENU. */
    double q_cn[4];
    /* True IMU attitude q_b^n (w, x, y, z): C_c^n C_v^c R_z(outer) R_x(inner), true gimbal angles. */
    double q_bn[4];
} rins_TruthRecord;

/*
 * rins::StartRecord (96 bytes): the navigation state at the start of a batch's first record,
 * where a navigator that begins with this batch starts (docs/transport.md, "Start state").
 */
typedef struct rins_StartRecord {
    RINS_WIRE_TYPE_NAME(RINS_START_RECORD_TYPE_NAME)
    /* Samples before the batch: the tick of records[0] (the state is at the start of its interval). */
    uint64_t tick;
    /* Time of the state, s (the start of records[0]'s interval). */
    double t_s;
    /* Latitude (WGS-84), rad. */
    double lat_rad;
    /* Longitude, rad. */
    double lon_rad;
    /* Ellipsoidal height, m (the vertical channel is held there). */
    double height_m;
    /* Velocity, ENU, m/s. */
    double v_enu_mps[3];
    /* IMU attitude q_b^n (w, x, y, z). */
    double q_bn[4];
} rins_StartRecord;

/*
 * rins::ImuBatch (16504 bytes), the payload of service rins/S/imu: a 24-byte header, the
 * records, the truth block, the start state and the plant's reason when it refused a command.
 */
typedef struct rins_ImuBatch {
    RINS_WIRE_TYPE_NAME(RINS_IMU_BATCH_TYPE_NAME)
    /* RINS_LAYOUT_VERSION of the sender. */
    uint32_t layout_version;
    /* sizeof(rins_ImuRecord) of the sender. */
    uint32_t record_size;
    /* Batch sequence number, from 0, +1 per message: a gap means a lost message. */
    uint64_t seq;
    /* Valid records. */
    uint32_t count;
    /* RINS_FLAG_END, RINS_FLAG_INTERRUPTED, RINS_FLAG_REFUSED, RINS_FLAG_TRUTH. */
    uint32_t flags;
    /* The records; the first `count` are valid. */
    rins_ImuRecord records[RINS_BATCH_CAPACITY];
    /* The truth over each record (truth[k] goes with records[k]): error measures only. */
    rins_TruthRecord truth[RINS_BATCH_CAPACITY];
    /* The navigation state at the start of records[0] (filled in every batch). */
    rins_StartRecord start;
    /* With RINS_FLAG_REFUSED: the plant's reason, UTF-8, padded with NUL bytes. */
    uint8_t reason[RINS_REASON_BYTES];
} rins_ImuBatch;

/* rins::NavCommand (40 bytes), the payload of service rins/S/cmd: navigation side to plant. */
typedef struct rins_NavCommand {
    RINS_WIRE_TYPE_NAME(RINS_NAV_COMMAND_TYPE_NAME)
    /* RINS_LAYOUT_VERSION of the sender. */
    uint32_t layout_version;
    /* One of the RINS_KIND_* values. */
    uint32_t kind;
    /* The batch this acknowledges (lockstep); commands apply after it. */
    uint64_t ack_seq;
    /* Target outer angle, rad. */
    double outer_rad;
    /* Target inner angle, rad. */
    double inner_rad;
    /* Cruise rate, rad/s. */
    double rate_rps;
} rins_NavCommand;

/* rins::NavSolution (96 bytes), the payload of service rins/S/nav: the navigator's solution. */
typedef struct rins_NavSolution {
    RINS_WIRE_TYPE_NAME(RINS_NAV_SOLUTION_TYPE_NAME)
    /* Batch it follows. */
    uint64_t seq;
    /* Last tick consumed. */
    uint64_t tick;
    /* Latitude, rad. */
    double lat_rad;
    /* Longitude, rad. */
    double lon_rad;
    /* Height, m. */
    double height_m;
    /* Velocity ENU, m/s. */
    double v_n[3];
    /* Attitude q_b^n (w, x, y, z). */
    double q_bn[4];
} rins_NavSolution;

/* The layout as numbers (one assert per line, literal numbers: the Rust test reads them). */
_Static_assert(sizeof(rins_ImuRecord) == 128, "rins_ImuRecord size");
_Static_assert(_Alignof(rins_ImuRecord) == 8, "rins_ImuRecord alignment");
_Static_assert(offsetof(rins_ImuRecord, tick) == 0, "rins_ImuRecord.tick");
_Static_assert(offsetof(rins_ImuRecord, t_s) == 8, "rins_ImuRecord.t_s");
_Static_assert(offsetof(rins_ImuRecord, dtheta_rad) == 16, "rins_ImuRecord.dtheta_rad");
_Static_assert(offsetof(rins_ImuRecord, dv_mps) == 40, "rins_ImuRecord.dv_mps");
_Static_assert(offsetof(rins_ImuRecord, outer_rad) == 64, "rins_ImuRecord.outer_rad");
_Static_assert(offsetof(rins_ImuRecord, inner_rad) == 72, "rins_ImuRecord.inner_rad");
_Static_assert(offsetof(rins_ImuRecord, temps_c) == 80, "rins_ImuRecord.temps_c");

_Static_assert(sizeof(rins_TruthRecord) == 112, "rins_TruthRecord size");
_Static_assert(_Alignof(rins_TruthRecord) == 8, "rins_TruthRecord alignment");
_Static_assert(offsetof(rins_TruthRecord, lat_rad) == 0, "rins_TruthRecord.lat_rad");
_Static_assert(offsetof(rins_TruthRecord, lon_rad) == 8, "rins_TruthRecord.lon_rad");
_Static_assert(offsetof(rins_TruthRecord, height_m) == 16, "rins_TruthRecord.height_m");
_Static_assert(offsetof(rins_TruthRecord, v_enu_mps) == 24, "rins_TruthRecord.v_enu_mps");
_Static_assert(offsetof(rins_TruthRecord, q_cn) == 48, "rins_TruthRecord.q_cn");
_Static_assert(offsetof(rins_TruthRecord, q_bn) == 80, "rins_TruthRecord.q_bn");

_Static_assert(sizeof(rins_StartRecord) == 96, "rins_StartRecord size");
_Static_assert(_Alignof(rins_StartRecord) == 8, "rins_StartRecord alignment");
_Static_assert(offsetof(rins_StartRecord, tick) == 0, "rins_StartRecord.tick");
_Static_assert(offsetof(rins_StartRecord, t_s) == 8, "rins_StartRecord.t_s");
_Static_assert(offsetof(rins_StartRecord, lat_rad) == 16, "rins_StartRecord.lat_rad");
_Static_assert(offsetof(rins_StartRecord, lon_rad) == 24, "rins_StartRecord.lon_rad");
_Static_assert(offsetof(rins_StartRecord, height_m) == 32, "rins_StartRecord.height_m");
_Static_assert(offsetof(rins_StartRecord, v_enu_mps) == 40, "rins_StartRecord.v_enu_mps");
_Static_assert(offsetof(rins_StartRecord, q_bn) == 64, "rins_StartRecord.q_bn");

_Static_assert(sizeof(rins_ImuBatch) == 16504, "rins_ImuBatch size");
_Static_assert(_Alignof(rins_ImuBatch) == 8, "rins_ImuBatch alignment");
_Static_assert(offsetof(rins_ImuBatch, layout_version) == 0, "rins_ImuBatch.layout_version");
_Static_assert(offsetof(rins_ImuBatch, record_size) == 4, "rins_ImuBatch.record_size");
_Static_assert(offsetof(rins_ImuBatch, seq) == 8, "rins_ImuBatch.seq");
_Static_assert(offsetof(rins_ImuBatch, count) == 16, "rins_ImuBatch.count");
_Static_assert(offsetof(rins_ImuBatch, flags) == 20, "rins_ImuBatch.flags");
_Static_assert(offsetof(rins_ImuBatch, records) == 24, "rins_ImuBatch.records");
_Static_assert(offsetof(rins_ImuBatch, truth) == 8216, "rins_ImuBatch.truth");
_Static_assert(offsetof(rins_ImuBatch, start) == 15384, "rins_ImuBatch.start");
_Static_assert(offsetof(rins_ImuBatch, reason) == 15480, "rins_ImuBatch.reason");

_Static_assert(sizeof(rins_NavCommand) == 40, "rins_NavCommand size");
_Static_assert(_Alignof(rins_NavCommand) == 8, "rins_NavCommand alignment");
_Static_assert(offsetof(rins_NavCommand, layout_version) == 0, "rins_NavCommand.layout_version");
_Static_assert(offsetof(rins_NavCommand, kind) == 4, "rins_NavCommand.kind");
_Static_assert(offsetof(rins_NavCommand, ack_seq) == 8, "rins_NavCommand.ack_seq");
_Static_assert(offsetof(rins_NavCommand, outer_rad) == 16, "rins_NavCommand.outer_rad");
_Static_assert(offsetof(rins_NavCommand, inner_rad) == 24, "rins_NavCommand.inner_rad");
_Static_assert(offsetof(rins_NavCommand, rate_rps) == 32, "rins_NavCommand.rate_rps");

_Static_assert(sizeof(rins_NavSolution) == 96, "rins_NavSolution size");
_Static_assert(_Alignof(rins_NavSolution) == 8, "rins_NavSolution alignment");
_Static_assert(offsetof(rins_NavSolution, seq) == 0, "rins_NavSolution.seq");
_Static_assert(offsetof(rins_NavSolution, tick) == 8, "rins_NavSolution.tick");
_Static_assert(offsetof(rins_NavSolution, lat_rad) == 16, "rins_NavSolution.lat_rad");
_Static_assert(offsetof(rins_NavSolution, lon_rad) == 24, "rins_NavSolution.lon_rad");
_Static_assert(offsetof(rins_NavSolution, height_m) == 32, "rins_NavSolution.height_m");
_Static_assert(offsetof(rins_NavSolution, v_n) == 40, "rins_NavSolution.v_n");
_Static_assert(offsetof(rins_NavSolution, q_bn) == 64, "rins_NavSolution.q_bn");

#endif /* RINS_WIRE_H */
