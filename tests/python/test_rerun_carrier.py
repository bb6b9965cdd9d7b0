"""A ship in the Rerun recording, read back with rerun-sdk==0.36.3 and checked against the run's
own CSV (carrier truth columns, docs/scenario-format.md): at every bucket end the carrier
rotation (`world/carrier`) is q_c^n, the table base (`world/base`) is q_c^n times the mount, the
IMU under the gimbals therefore has the CSV's q_b^n, and the track (`track/ship` points and the
`track/path` strip) is the CSV's position in the local ENU frame of the first bucket end,
computed here independently through ECEF.

Usage: python test_rerun_carrier.py RINS_BINARY WORK_DIR (test_rerun.py also runs it)
"""

import csv
import math
import os
import subprocess
import sys
from collections import defaultdict

import rerun as rr

A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2.0 - F)

SHIP = """[scenario]
name = "ship-rerun"
duration_s = 120.0
[carrier]
kind = "ship"
[carrier.ship]
legs = [
  { heading_deg = 30.0, speed_kn = 14.0, duration_s = 40.0 },
  { heading_deg = 120.0, speed_kn = 10.0, duration_s = 3600.0 },
]
[carrier.ship.sea]
spectrum = "jonswap"
sea_state = 5
[vehicle]
azimuth_deg = 30.0
[outputs]
truth = true
"""


def ecef(lat, lon, h):
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - E2) + h) * math.sin(lat))


def enu(origin, p):
    lat, lon, h = origin
    o, x = ecef(lat, lon, h), ecef(*p)
    d = [x[i] - o[i] for i in range(3)]
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    return (-so * d[0] + co * d[1], -sl * co * d[0] - sl * so * d[1] + cl * d[2],
            cl * co * d[0] + cl * so * d[1] + sl * d[2])


def qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def qdiff(a, b):
    """Largest component difference of two attitudes (q and -q are the same)."""
    s = -1.0 if sum(x * y for x, y in zip(a, b)) < 0 else 1.0
    return max(abs(x - s * y) for x, y in zip(a, b))


def read(path, entity_columns):
    """entity -> {step: value} of the named column (the last row per step)."""
    got = defaultdict(dict)
    for ch in rr.experimental.RrdReader(path).stream().to_chunks():
        ent = str(ch.entity_path)
        if ent not in entity_columns:
            continue
        b = ch.to_record_batch()
        col = entity_columns[ent]
        if "step" not in b.schema.names or col not in b.schema.names:
            continue
        for step, v in zip(b.column("step").to_pylist(), b.column(col).to_pylist()):
            got[ent][step] = v
    return got


def check_ship(rins, work):
    scen = os.path.join(work, "ship-rerun.toml")
    with open(scen, "w") as f:
        f.write(SHIP)
    out = os.path.join(work, "ship-rerun")
    rrd = os.path.join(out, "run.rrd")
    subprocess.run([rins, "run", scen, "--out", out, "--rerun", f"save:{rrd}", "--rerun-bucket-s", "1"],
                   check=True, capture_output=True, text=True)
    v = subprocess.run([os.path.join(os.path.dirname(sys.executable), "rerun"), "rrd", "verify", rrd],
                       capture_output=True, text=True)
    assert v.returncode == 0, v.stdout + v.stderr
    with open(os.path.join(out, "imu.csv")) as f:
        rows = list(csv.DictReader(f))
    ends = rows[99::100]  # bucket ends: 1 s of 100 Hz samples
    assert len(ends) == 120
    q = "Transform3D:quaternion"
    got = read(rrd, {"/world/carrier": q, "/world/base": q, "/world/base/outer": q, "/world/base/outer/inner": q,
                     "/track/ship": "Points3D:positions", "/track/path": "LineStrips3D:strips"})
    for e in ("/world/carrier", "/world/base", "/track/ship"):
        assert len(got[e]) == 120, (e, len(got[e]))
    az = math.radians(30.0)
    mount = (math.cos(az / 2), 0.0, 0.0, math.sin(az / 2))  # [vehicle] azimuth: R_z(30°)
    first = ends[0]
    origin = tuple(math.radians(float(first[k])) for k in ("lat_deg", "lon_deg")) + (float(first["height_m"]),)
    worst_q, worst_imu, worst_m, track = 0.0, 0.0, 0.0, []
    for r in ends:
        step = int(r["sample"])
        q_cn = tuple(float(r[f"q_cn_{c}"]) for c in "wxyz")
        x, y, z, w = got["/world/carrier"][step][0]  # one quaternion per row, xyzw
        worst_q = max(worst_q, qdiff((w, x, y, z), q_cn))
        x, y, z, w = got["/world/base"][step][0]
        base = (w, x, y, z)
        worst_q = max(worst_q, qdiff(base, qmul(q_cn, mount)))
        # The IMU's attitude in the scene: base, then the latest gimbal rotations (logged at
        # each bucket end and each dwell change).
        outer = max(s for s in got["/world/base/outer"] if s <= step)
        inner = max(s for s in got["/world/base/outer/inner"] if s <= step)
        ox, oy, oz, ow = got["/world/base/outer"][outer][0]
        ix, iy, iz, iw = got["/world/base/outer/inner"][inner][0]
        imu = qmul(qmul(base, (ow, ox, oy, oz)), (iw, ix, iy, iz))
        worst_imu = max(worst_imu, qdiff(imu, tuple(float(r[f"q_bn_{c}"]) for c in "wxyz")))
        p = (math.radians(float(r["lat_deg"])), math.radians(float(r["lon_deg"])), float(r["height_m"]))
        want = enu(origin, p)
        have = got["/track/ship"][step][0]
        worst_m = max(worst_m, max(abs(a - b) for a, b in zip(have, want)))
        track.append(have)
    # Sent as f32: attitudes to ~1e-7, positions (up to ~0.6 km here) to ~1e-4 m.
    assert worst_q < 1e-6, worst_q
    assert worst_imu < 1e-6, worst_imu
    assert worst_m < 1e-3, worst_m
    last_path = got["/track/path"][max(got["/track/path"])][0]
    assert len(last_path) == 120 and [tuple(p) for p in last_path] == [tuple(p) for p in track]
    span = math.dist(track[0], track[-1])
    assert span > 400, span  # 2 min at 10-14 kn
    print(f"ok   ship in the rerun recording: 120 bucket ends, carrier/base/IMU attitudes within {max(worst_q, worst_imu):.1e}, "
          f"track within {worst_m:.1e} m of the CSV through ECEF ({span:.0f} m travelled)")


if __name__ == "__main__":
    check_ship(*sys.argv[1:3])
    print("1 passed, 0 failed")
