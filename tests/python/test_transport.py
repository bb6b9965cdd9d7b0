"""The Python subscriber against a served stream: it starts before the plant (creating the
services with the documented settings), sees no gap, and its per-position mean rates equal the
in-process plant's (from `rins run`) to rounding. On a ship, the truth block it receives (layout
version 2 and later) equals the in-process plant's carrier truth (`rins run`'s carrier columns) bit for bit.

Usage: python test_transport.py RINS_BINARY WORK_DIR
"""

import csv
import ctypes
import json
import math
import os
import subprocess
import sys

RINS, WORK = sys.argv[1:3]
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
# The wire types from the standalone module the Rust tests check against transport/src/layout.rs.
sys.path.insert(0, os.path.join(HERE, "..", "..", "transport", "wire"))
from imu_subscriber import DwellMeans  # noqa: E402
from rins_wire import ImuBatch, StartRecord, TruthRecord  # noqa: E402

DURATION = "4320"  # one 16-position cycle at 100 Hz: 432,000 samples


def serve_and_subscribe(session, scenario, duration, truth_path=None):
    """Starts the subscriber first, then `rins serve`; returns the subscriber's JSON result."""
    extra = ["--truth", truth_path] if truth_path else []
    sub = subprocess.Popen([sys.executable, os.path.join(HERE, "imu_subscriber.py"), session, *extra],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    ready = sub.stderr.readline()
    assert ready.strip() == "service ready", ready + sub.stderr.read()
    plant = subprocess.Popen([RINS, "serve", scenario, "--session", session, "--mode", "free",
                              "--duration-s", duration], stderr=subprocess.PIPE, text=True)
    try:
        out, sub_err = sub.communicate(timeout=300)
        _, err = plant.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        sub.kill()
        plant.kill()
        _, sub_err = sub.communicate()
        _, err = plant.communicate()
        raise AssertionError(f"timed out; subscriber said: {sub_err}\nplant said: {err}")
    assert sub.returncode == 0, f"subscriber: {sub_err}\nplant (exit {plant.returncode}): {err}"
    assert plant.returncode == 0, err
    return json.loads(out)


SHIP = """[scenario]
name = "ship"
duration_s = 300.0
[carrier]
kind = "ship"
lever_arm_m = [1.0, 5.0, -2.0]
[carrier.ship]
legs = [
  { heading_deg = 30.0, speed_kn = 14.0, duration_s = 60.0 },
  { heading_deg = 120.0, speed_kn = 10.0, duration_s = 3600.0 },
]
[carrier.ship.sea]
spectrum = "jonswap"
sea_state = 5
[outputs]
truth = true
"""

# Rust's f64::to_degrees multiplies by this constant (the double nearest 180/pi); the CSV's
# degrees are compared through the same product, bit for bit.
RUST_DEG_PER_RAD = float("57.2957795130823208767981548141051703")


def ship_truth():
    """The truth block on a ship equals the in-process plant's carrier truth bit for bit."""
    assert ctypes.sizeof(TruthRecord) == 112 and ctypes.sizeof(StartRecord) == 96
    assert ctypes.sizeof(ImuBatch) == 24 + 64 * (128 + 112) + 96 + 1024 == 16504
    assert ImuBatch.start.offset == 15384 and ImuBatch.reason.offset == 15480
    scen = os.path.join(WORK, "ship.toml")
    with open(scen, "w") as f:
        f.write(SHIP)
    truth_csv = os.path.join(WORK, "ship-truth.csv")
    got = serve_and_subscribe(f"pyship{os.getpid()}", scen, "300", truth_csv)
    assert got["samples"] == 30000, got
    out = os.path.join(WORK, "inproc-ship")
    subprocess.run([RINS, "run", scen, "--out", out], check=True, capture_output=True)
    with open(truth_csv) as f:
        served = list(csv.DictReader(f))
    with open(os.path.join(out, "imu.csv")) as f:
        inproc = list(csv.DictReader(f))
    assert len(served) == len(inproc) == 30000, (len(served), len(inproc))
    worst_q_bn = 0.0
    for s, r in zip(served, inproc):
        assert int(s["tick"]) == int(r["sample"]), (s["tick"], r["sample"])
        assert float(s["lat_rad"]) * RUST_DEG_PER_RAD == float(r["lat_deg"]), (s, r)
        assert float(s["lon_rad"]) * RUST_DEG_PER_RAD == float(r["lon_deg"]), (s, r)
        for k in ("height_m", "v_e_mps", "v_n_mps", "v_u_mps", "q_cn_w", "q_cn_x", "q_cn_y", "q_cn_z"):
            assert float(s[k]) == float(r[k]), (k, s, r)
        # q_bn: the CSV and the wire both take the plant's closed-form composition
        # (rins_plant::true_attitude), so they are expected to agree bit for bit; the bound
        # (and q ~ -q) is the one of the former matrix routes.
        a = [float(s[f"q_bn_{c}"]) for c in "wxyz"]
        b = [float(r[f"q_bn_{c}"]) for c in "wxyz"]
        sign = -1.0 if a[0] * b[0] < 0 else 1.0
        worst_q_bn = max(worst_q_bn, max(abs(x - sign * y) for x, y in zip(a, b)))
    assert worst_q_bn < 1e-14, worst_q_bn
    moved = math.hypot(float(inproc[-1]["lat_deg"]) - float(inproc[0]["lat_deg"]),
                       float(inproc[-1]["lon_deg"]) - float(inproc[0]["lon_deg"]))
    assert moved > 0.005, moved
    print(f"ok   python subscriber on a ship: 30000 truth records equal the in-process carrier truth bit for bit (q_bn within {worst_q_bn:.1e})")


def main():
    session = f"py{os.getpid()}"
    # The client starts first and creates the services with the documented settings; the plant
    # must accept them (issue 16, A1).
    got = serve_and_subscribe(session, "builtin:paper-16pos-week", DURATION)
    assert got["samples"] == 432000, got
    # The same figure from the in-process plant's CSV.
    out = os.path.join(WORK, "inproc-transport")
    scen = os.path.join(WORK, "one-cycle.toml")
    text = subprocess.run([RINS, "scenarios", "paper-16pos-week"], capture_output=True, text=True, check=True).stdout
    text = text.replace("decimation = 100", "decimation = 1")
    with open(scen, "w") as f:
        f.write(text)
    subprocess.run([RINS, "run", scen, "--out", out, "--duration-s", DURATION], check=True, capture_output=True)
    means = DwellMeans()
    with open(os.path.join(out, "imu.csv")) as f:
        for r in csv.DictReader(f):
            # Degrees in the CSV; DwellMeans compares angles at 1e-9 rad.
            means.push(math.radians(float(r["outer_deg"])), math.radians(float(r["inner_deg"])), float(r["dtheta_z_rad"]), 0.01)
    want = means.result()
    assert set(want) == set(got["mean_rate_z_rps"]), (want, got)
    for p, w in want.items():
        g = got["mean_rate_z_rps"][p]
        assert abs(g - w) <= 1e-12 * max(abs(w), 1e-9), (p, g, w)
    print(f"ok   python subscriber (started before the plant): {got['samples']} samples, no gap, per-position mean rates equal the in-process run: {want}")
    ship_truth()
    print("2 passed, 0 failed")


main()
