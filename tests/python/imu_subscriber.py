"""Example navigation-side client in Python: subscribes to a served rins IMU stream with the PyPI
iceoryx2 package, checks the layout and sequence numbers, and prints the mean z angular rate per
dwell position (A/B/C/D of Eq. 5) as JSON.

Usage: python imu_subscriber.py SESSION [--truth FILE]
With --truth it also writes the truth block (layout version 2 and later: the carrier and the
true IMU attitude of every record, for error measures only) to FILE as CSV, numbers in repr form
(reading them back gives the same bits).
The plant: rins serve builtin:paper-16pos-week --session SESSION --mode free --duration-s 4320
(before or after this client: it opens or creates the service with the documented settings,
prints "service ready" on stderr, creates its subscriber once the plant's publisher exists and
prints "subscribed")
"""

import ctypes
import json
import math
import os
import sys
import time

import iceoryx2 as iox2

# The wire types (every rins type, with its iceoryx2 type name and layout asserts) come from the
# standalone module transport/wire/rins_wire.py, checked against the Rust definitions.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "transport", "wire"))
from rins_wire import FLAG_END, FLAG_REFUSED, LAYOUT_VERSION, ImuBatch, ImuRecord  # noqa: E402


TRUTH_COLUMNS = ["tick", "lat_rad", "lon_rad", "height_m", "v_e_mps", "v_n_mps", "v_u_mps",
                 "q_cn_w", "q_cn_x", "q_cn_y", "q_cn_z", "q_bn_w", "q_bn_x", "q_bn_y", "q_bn_z"]


def truth_row(tick, t):
    """One truth record as CSV fields (repr: shortest round trip)."""
    values = [t.lat_rad, t.lon_rad, t.height_m, *t.v_enu_mps, *t.q_cn, *t.q_bn]
    return ",".join([str(tick)] + [repr(v) for v in values])


def position(outer: float, inner: float) -> str:
    """A/B/C/D of Eq. 5 from the gimbal angles at a dwell."""
    def near(a, b):
        d = (a - b) % (2 * math.pi)
        return min(d, 2 * math.pi - d) < 1e-6
    if near(outer, 0) and near(inner, 0):
        return "A"
    if near(outer, math.pi) and near(inner, 0):
        return "B"
    if near(outer, math.pi) and near(inner, math.pi):
        return "C"
    if near(outer, 0) and near(inner, math.pi):
        return "D"
    return "other"


class DwellMeans:
    """Mean z rate per position over dwelling samples (angles unchanged since the previous one)."""

    def __init__(self):
        self.sum = {}
        self.n = {}
        self.prev = None

    def push(self, outer, inner, dtheta_z, dt):
        # Angles compared at 1e-9 rad, so that a log with angles in degrees classifies alike.
        outer, inner = round(outer, 9), round(inner, 9)
        if self.prev is not None and self.prev == (outer, inner):
            p = position(outer, inner)
            self.sum[p] = self.sum.get(p, 0.0) + dtheta_z / dt
            self.n[p] = self.n.get(p, 0) + 1
        self.prev = (outer, inner)

    def result(self):
        return {p: self.sum[p] / self.n[p] for p in sorted(self.sum)}


def main(session: str, truth_path=None) -> None:
    truth_file = open(truth_path, "w") if truth_path else None
    if truth_file:
        truth_file.write(",".join(TRUTH_COLUMNS) + "\n")
    cfg = iox2.config.default()
    cfg.global_cfg.prefix = iox2.FileName.new(f"rins_{session}_")
    node = iox2.NodeBuilder.new().config(cfg).create(iox2.ServiceType.Ipc)
    name = iox2.ServiceName.new(f"rins/{session}/imu")
    deadline = time.time() + 30
    while True:
        try:
            # The documented settings of rins/S/imu (docs/transport.md, Services): this client
            # may start before `rins serve` and create the service itself.
            service = (node.service_builder(name).publish_subscribe(ImuBatch)
                       .enable_safe_overflow(False).subscriber_max_buffer_size(16).history_size(0)
                       .max_publishers(1).max_subscribers(8).open_or_create())
            break
        except Exception:  # being created or removed by another process at this moment
            if time.time() > deadline:
                raise
            time.sleep(0.05)
    print("service ready", file=sys.stderr, flush=True)
    # The subscriber port only once the plant's publisher exists: a subscriber that polls while
    # a publisher is being created can fail to connect to it for good (iceoryx2 0.10 logs
    # "Unable to establish connection to new sender"; seen in 1 of 17 runs here). The plant
    # sends nothing before a subscriber is connected, so no sample is lost by waiting.
    while service.dynamic_config.number_of_publishers == 0:
        if time.time() > deadline:
            raise SystemExit("no plant published on the service within 30 s")
        time.sleep(0.01)
    time.sleep(0.05)
    subscriber = service.subscriber_builder().create()
    print("subscribed", file=sys.stderr, flush=True)
    means = DwellMeans()
    expected = None
    samples = 0
    # A plant that failed sends nothing more: give up after a minute of silence instead of
    # waiting forever (the error then names the last batch seen).
    last_batch = time.time()
    while True:
        sample = subscriber.receive()
        if sample is None:
            if time.time() - last_batch > 60:
                raise SystemExit(f"no batch for 60 s; the last one was {expected}")
            time.sleep(0.0002)
            continue
        last_batch = time.time()
        b = sample.payload().contents
        if b.layout_version != LAYOUT_VERSION or b.record_size != ctypes.sizeof(ImuRecord):
            raise SystemExit(f"layout version {b.layout_version} / record size {b.record_size} not supported")
        if expected is not None and b.seq != expected:
            raise SystemExit(f"sequence gap: expected {expected}, got {b.seq}")
        expected = b.seq + 1
        for k in range(b.count):
            r = b.records[k]
            means.push(r.outer_rad, r.inner_rad, r.dtheta_rad[2], 0.01)
            if truth_file:
                truth_file.write(truth_row(r.tick, b.truth[k]) + "\n")
            samples += 1
        if b.flags & FLAG_REFUSED:
            raise SystemExit("the plant ended the run: " + b.reason.decode("utf-8", "replace"))
        if b.flags & FLAG_END:
            break
    if truth_file:
        truth_file.close()
    print(json.dumps({"samples": samples, "batches": expected, "mean_rate_z_rps": means.result()}))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--truth" else None)
