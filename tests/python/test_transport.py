"""The Python subscriber against a served stream: it starts before the plant (creating the
services with the documented settings), sees no gap, and its per-position mean rates equal the
in-process plant's (from `rins run`) to rounding.

Usage: python test_transport.py RINS_BINARY WORK_DIR
"""

import csv
import json
import math
import os
import subprocess
import sys

RINS, WORK = sys.argv[1:3]
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from imu_subscriber import DwellMeans  # noqa: E402

DURATION = "4320"  # one 16-position cycle at 100 Hz: 432,000 samples


def main():
    session = f"py{os.getpid()}"
    # The client starts first and creates the services with the documented settings; the plant
    # must accept them (issue 16, A1).
    sub = subprocess.Popen([sys.executable, os.path.join(HERE, "imu_subscriber.py"), session],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    ready = sub.stderr.readline()
    assert ready.strip() == "service ready", ready + sub.stderr.read()
    plant = subprocess.Popen([RINS, "serve", "builtin:paper-16pos-week", "--session", session, "--mode", "free",
                              "--duration-s", DURATION], stderr=subprocess.PIPE, text=True)
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
    got = json.loads(out)
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
    print("1 passed, 0 failed")


main()
