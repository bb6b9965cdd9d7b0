"""The `rins` Python package (python/, PyO3 + maturin) against the `rins` command line.

- One simulated hour of builtin:paper-16pos-short run to numpy equals `rins run`'s imu.csv bit
  for bit (the CSV prints shortest round-trip floats; increments are summed from zero there, so
  they are compared after adding 0.0, which only turns -0.0 into 0.0), column by column; the
  same hour in chunks equals the one-call run; the hour's wall time is printed beside FMPy's.
- The GIL is released while Rust runs (a Python thread keeps running during a call).
- Bad scenarios raise rins.ScenarioError naming the file, line and field.
- Monte Carlo end figures equal `rins paper table4 --json`'s per-seed figures bit for bit, and
  `rins.navigate` agrees with them; `rins.table4` equals the CLI's study.
- Dask: a sweep of 2 parameter points x 8 seeds on a LocalCluster(n_workers=2, processes=True)
  equals the in-process run bit for bit.
- Sweep files: `rins.sweep_file` of docs/examples/sweep-dbeta-dwell.toml shortened (4 points,
  2 seeds, 0.05 days) equals `rins sweep FILE --json` bit for bit (swept values, per-seed
  figures of both navigators, medians and bands); the same on a LocalCluster(n_workers=2,
  processes=True) equals the in-process result bit for bit; a bad sweep file raises
  rins.SweepError naming the file, line and key with the CLI's words.
- Memory: under a 6 GiB address-space limit, `rins.run` of the week raises MemoryError naming
  the bytes it needs (and `Simulation(chunk=…)`, `step(n)`, `navigate` likewise) before
  allocating, and the interpreter carries on.
- Ctrl-C: SIGINT stops `rins.montecarlo` of the week (8 seeds), `rins.run` (two days) and
  `rins.navigate` (the week) within 2 s with KeyboardInterrupt; an interrupted `Simulation.step` leaves the simulation
  where it was.
- Arguments: whole numbers out of range raise ValueError (TypeError for a non-integer) naming
  the argument and its range; a repeated seed and a NaN in a dict scenario name the entry.

Usage: python test_package.py RINS_BINARY WORK_DIR
"""

import json
import math
import os
import re
import signal
import subprocess
import sys
import threading
import time
import tomllib

import numpy as np

import rins

RINS, WORK = sys.argv[1:3]
HOUR_S = 3600.0
FMPY_FMI2_HOUR_S = 3.0  # docs/fmu.md, Performance: FMPy, 1 hour at 100 Hz, FMI 2
SHORT = "builtin:paper-16pos-short"
WEEK = "builtin:paper-16pos-week"
DAYS = 0.05


def bits(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def same_bits(a, b, what):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    assert a.shape == b.shape, f"{what}: shapes {a.shape} vs {b.shape}"
    diff = np.flatnonzero(bits(a).ravel() != bits(b).ravel())
    assert diff.size == 0, f"{what}: {diff.size} values differ, first at {diff[0]}: {a.ravel()[diff[0]]!r} vs {b.ravel()[diff[0]]!r}"


def read_csv(path):
    """imu.csv as {column: array}; floats parsed by numpy and spot-checked against float()."""
    with open(path) as f:
        header = f.readline().strip().split(",")
        pos_col = header.index("position")
        lines = f.read().splitlines()
    positions = np.array([ln.split(",")[pos_col] for ln in lines])
    cols = [i for i in range(len(header)) if i != pos_col]
    data = np.loadtxt(lines, delimiter=",", usecols=cols, dtype=np.float64, ndmin=2)
    # numpy's parser against Python's correctly rounded float() on a spread of rows.
    for r in range(0, len(lines), max(1, len(lines) // 500)):
        cells = lines[r].split(",")
        ref = [float(cells[i]) for i in cols]
        same_bits(data[r], ref, f"CSV row {r} parsed by numpy vs float()")
    out = {h: data[:, k] for k, h in enumerate(header[i] for i in cols)}
    out["position"] = positions
    return out


def test_hour_equals_csv():
    out = os.path.join(WORK, "hour")
    subprocess.run([RINS, "run", SHORT, "--out", out, "--duration-s", str(int(HOUR_S))],
                   check=True, capture_output=True)
    d = rins.run(SHORT, duration_s=HOUR_S)
    n = int(HOUR_S * 100)
    assert d["t_s"].shape == (n,), d["t_s"].shape
    csv = read_csv(os.path.join(out, "imu.csv"))
    assert len(csv["t_s"]) == n
    ax = "xyz"
    np.testing.assert_array_equal(csv["sample"].astype(np.uint64), d["sample"])
    same_bits(csv["t_s"], d["t_s"], "t_s")
    summed = {"dtheta_{}_rad": "dtheta_rad", "dv_{}_mps": "dv_mps",
              "dtheta_true_{}_rad": "dtheta_true_rad", "dv_true_{}_mps": "dv_true_mps"}
    compared = 2
    for pat, key in summed.items():
        for i, a in enumerate(ax):
            same_bits(csv[pat.format(a)], d[key][:, i] + 0.0, pat.format(a))
            compared += 1
    for key in ("outer_deg", "inner_deg", "temp_chamber_c"):
        same_bits(csv[key], d[key], key)
        compared += 1
    for i, node in enumerate(rins.TEMP_NODES):
        same_bits(csv[f"temp_{node}_c"], d["temps_c"][:, i], f"temp_{node}_c")
        compared += 1
    for i, c in enumerate("wxyz"):
        same_bits(csv[f"q_bn_{c}"], d["q_bn"][:, i], f"q_bn_{c}")
        compared += 1
    for group, unit in (("gyro", "dph"), ("accel", "ug")):
        terms = d[f"{group}_effects_{unit}"]
        assert terms, f"no {group} effects in the scenario"
        for key, arr in terms.items():
            for i, a in enumerate(ax):
                col = f"{group}_{key}_{a}_{unit}"
                same_bits(csv[col], arr[:, i] + 0.0, col)
                compared += 1
    labels = np.array(rins.POSITION_LABELS)[d["position"]]
    assert (labels == csv["position"]).all(), "position labels differ"
    compared += 1
    csv_cols = len(csv)
    assert compared == csv_cols, f"compared {compared} of the CSV's {csv_cols} columns"
    print(f"one simulated hour ({n} samples, {compared} columns) equals rins run's CSV bit for bit")
    # The hour's cost beside FMPy's (which reads the 6 increments only): the measured outputs
    # alone, and every column (the CSV's attitude quaternion dominates that one). CPU time is
    # compared: this machine may be shared, FMPy's figure is from a quiet one.
    for truth in (False, True):
        t0, c0 = time.perf_counter(), time.process_time()
        r = rins.run(SHORT, duration_s=HOUR_S, truth=truth)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        same_bits(r["dtheta_rad"], d["dtheta_rad"], f"dtheta_rad with truth={truth}")
        what = "every column" if truth else "measured outputs"
        print(f"one simulated hour to numpy ({what}, {len(r)} keys): wall {wall:.3f} s, CPU {cpu:.3f} s "
              f"({cpu * 1e9 / n:.0f} ns/sample) vs FMPy (FMI 2, 6 outputs) {FMPY_FMI2_HOUR_S} s: "
              f"{FMPY_FMI2_HOUR_S / cpu:.1f}x")
        if not truth:
            assert cpu < FMPY_FMI2_HOUR_S, f"rins.run took {cpu:.2f} s CPU, FMPy takes {FMPY_FMI2_HOUR_S} s"

    # The same hour in chunks (a non-divisor chunk size) equals the one-call run.
    sim = rins.Simulation(SHORT, duration_s=HOUR_S, chunk=70_001)
    chunks = list(sim)
    assert [len(c["t_s"]) for c in chunks] == [70_001] * 5 + [n - 5 * 70_001]
    for key in ("t_s", "dtheta_rad", "dv_mps", "temps_c", "q_bn", "dtheta_true_rad"):
        same_bits(np.concatenate([c[key] for c in chunks]), d[key], f"chunked {key}")
    assert sim.samples_done == n
    print(f"the hour in {len(chunks)} chunks equals the one-call run")


def test_gil_released():
    """A Python thread keeps running while another thread is inside rins.run."""
    done = threading.Event()
    call = {}

    def work():
        t0 = time.perf_counter()
        rins.run(SHORT, duration_s=2 * HOUR_S, truth=False)
        call["wall"] = time.perf_counter() - t0
        done.set()

    th = threading.Thread(target=work)
    stamps = []
    th.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
    th.join()
    gaps = np.diff(stamps)
    gap = gaps.max() if gaps.size else float("inf")
    print(f"GIL: the main thread's longest pause during a {call['wall']:.3f} s rins.run call: {gap * 1e3:.1f} ms")
    assert gap < 0.5 * call["wall"], "the main thread stalled: the GIL was held while Rust ran"


def test_errors():
    bad = tomllib.loads(rins.builtin_toml(SHORT))
    bad["run"]["rate_hz"] = -5.0
    try:
        rins.Scenario(bad)
        raise AssertionError("a negative rate was accepted")
    except rins.ScenarioError as e:
        msg = str(e)
        assert "run.rate_hz" in msg and "got -5" in msg and "line" in msg, msg
    path = os.path.join(WORK, "bad.toml")
    with open(path, "w") as f:
        f.write('[scenario]\nname = "bad"\nduration_s = 60.0\n\n[site]\nlat_deg = 123.0\n')
    try:
        rins.run(path)
        raise AssertionError("latitude 123 was accepted")
    except rins.ScenarioError as e:
        msg = str(e)
        assert path in msg and "line 6" in msg and "site.lat_deg" in msg, msg
        print(f"bad file -> rins.ScenarioError: {msg.strip().splitlines()[-1].strip()}")
    with open(path, "w") as f:
        f.write('[scenario]\nname = "bad"\nduration_s = 60.0\n\n[site]\nlat_dgs = 12.0\n')
    try:
        rins.Scenario(path)
        raise AssertionError("an unknown key was accepted")
    except rins.ScenarioError as e:
        assert "lat_dgs" in str(e) and "line 6" in str(e), str(e)
    for call, exc in ((lambda: rins.run(SHORT, duration_s=-1.0), ValueError),
                      (lambda: rins.Scenario("builtin:nope"), rins.ScenarioError),
                      (lambda: rins.navigate(SHORT, duration_s=60.0, alignment="sideways"), ValueError)):
        try:
            call()
            raise AssertionError("accepted")
        except exc:
            pass
    # Self-alignment while the table turns: the session's error as rins.NavigationError.
    try:
        rins.navigate(SHORT, duration_s=60.0, alignment=("self", 300.0, 600.0))
        raise AssertionError("self-alignment on a turning table was accepted")
    except rins.NavigationError as e:
        assert "during self-alignment" in str(e), str(e)


def test_montecarlo_equals_cli():
    out = os.path.join(WORK, "t4")
    cli = json.loads(subprocess.run(
        [RINS, "paper", "table4", "--runs", "2", "--days", str(DAYS), "--json", "--out", out],
        check=True, capture_output=True, text=True).stdout)
    seeds = [s for s, _, _ in cli["per_seed"]]
    # The CLI's study updates its navigators every 4 intervals (--subsamples 4, its default).
    assert cli["nav_subsamples"] == 4, cli["nav_subsamples"]
    mc = rins.montecarlo(WEEK, seeds, duration_s=DAYS * 86400.0, subsamples=4)
    np.testing.assert_array_equal(mc["seed"], np.array(seeds, dtype=np.uint64))
    for k, case in enumerate(("uncompensated", "compensated")):
        for name in rins.FIGURES:
            same_bits(mc[case][name], [row[1 + k][name] for row in cli["per_seed"]], f"{case} {name}")
    print(f"montecarlo: seeds {seeds}, {len(rins.FIGURES)} figures x 2 cases equal `rins paper table4 --json` bit for bit")
    # The navigator on its own agrees with the Monte Carlo's figures of the same seed.
    nav = rins.navigate(WEEK, duration_s=DAYS * 86400.0, seed=seeds[1], compensated=True, subsamples=4)
    same_bits(nav["horizontal_m"][-1] / 1852.0, mc["compensated"]["horizontal_nm"][1], "navigate horizontal")
    same_bits(nav["up_att_mean_abs_rad"] * (180.0 / math.pi), mc["compensated"]["up_att_mean_deg"][1],
              "navigate mean |phi_U|")
    assert nav["t_s"][-1] == DAYS * 86400.0, nav["t_s"][-1]
    # The whole study in-process equals the CLI's (wall time aside).
    t4 = rins.table4(WEEK, runs=2, days=DAYS)
    for key in ("uncompensated", "compensated", "improvement_pct", "noise_free", "per_seed", "runs", "days",
                "nav_subsamples"):
        assert t4[key] == cli[key], key
    # Every interval an update is another navigator: its figures differ, a little.
    every = rins.montecarlo(WEEK, seeds[:1], duration_s=DAYS * 86400.0, subsamples=1)
    diff = abs(every["uncompensated"]["lon_nm"][0] - mc["uncompensated"]["lon_nm"][0])
    assert 0.0 < diff < 0.05, diff
    for bad in (5, -1, 300):
        try:
            rins.montecarlo(WEEK, seeds[:1], duration_s=60.0, subsamples=bad)
            raise AssertionError(f"subsamples={bad} was accepted")
        except ValueError as e:
            assert "1 to 4" in str(e), str(e)
    print("rins.table4 equals `rins paper table4 --json` (statistics, improvements, noise-free pair)")


def test_dask_sweep():
    from dask.distributed import Client, LocalCluster

    base = tomllib.loads(rins.builtin_toml(WEEK))
    points = []
    for lat in (36.6, 52.0):
        d = json.loads(json.dumps(base))
        d["site"]["lat_deg"] = lat
        points.append(d)
    seeds = list(range(100, 108))
    t0 = time.perf_counter()
    local = rins.sweep(points, seeds, duration_s=DAYS * 86400.0)
    t_local = time.perf_counter() - t0
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        t0 = time.perf_counter()
        remote = rins.sweep(points, seeds, duration_s=DAYS * 86400.0, client=client, seeds_per_task=2)
        t_remote = time.perf_counter() - t0
        workers = len(client.scheduler_info()["workers"])
    assert workers == 2, workers
    for p, (a, b) in enumerate(zip(local, remote)):
        np.testing.assert_array_equal(a["seed"], b["seed"])
        for case in ("uncompensated", "compensated"):
            for name in rins.FIGURES:
                same_bits(a[case][name], b[case][name], f"point {p} {case} {name}")
                # A real sweep: the seeds and the parameter points give different figures.
                assert len(set(a[case][name].tolist())) == len(seeds), f"point {p} {case} {name}: repeated values"
    assert not np.array_equal(local[0]["uncompensated"]["lat_nm"], local[1]["uncompensated"]["lat_nm"])
    print(f"dask: 2 points x {len(seeds)} seeds on LocalCluster(n_workers=2, processes=True) equal the "
          f"in-process sweep bit for bit ({t_remote:.1f} s vs {t_local:.1f} s in-process)")


EXAMPLE_SWEEP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "examples",
                             "sweep-dbeta-dwell.toml")


def short_sweep_file():
    """docs/examples/sweep-dbeta-dwell.toml shortened: 2 x 2 points, 2 seeds, 0.05 days."""
    with open(EXAMPLE_SWEEP, "rb") as f:
        d = tomllib.load(f)
    d["sweep"]["days"] = DAYS
    d["sweep"]["seeds"] = 2
    d["parameter"][0]["values"] = d["parameter"][0]["values"][::2]  # delta-beta_z 0 and 0.02 deg/h
    assert [len(p["values"]) for p in d["parameter"]] == [2, 2], d["parameter"]
    path = os.path.join(WORK, "sweep-short.toml")
    with open(path, "w") as f:
        f.write(rins.to_toml(d))
    return path


def test_sweep_file_equals_cli():
    """Returns the sweep file and its in-process result (test_dask_sweep_file compares with it)."""
    path = short_sweep_file()
    t0 = time.perf_counter()
    cli = json.loads(subprocess.run([RINS, "sweep", path, "--json", "--out", os.path.join(WORK, "sweep-cli")],
                                    check=True, capture_output=True, text=True).stdout)
    t_cli = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = rins.sweep_file(path)
    t_py = time.perf_counter() - t0
    pts = cli["points"]
    n_pts, n_seeds = len(pts), len(cli["seeds"])
    assert (n_pts, n_seeds) == (4, 2), (n_pts, n_seeds)
    for key in ("name", "description", "sweep_file", "scenario", "duration_s", "days", "alignment", "combine",
                "parameters", "outputs"):
        assert r[key] == cli[key], (key, r[key], cli[key])
    np.testing.assert_array_equal(r["seeds"], np.array(cli["seeds"], dtype=np.uint64))
    assert r["labels"] == [p["label"] for p in pts]
    for i, par in enumerate(cli["parameters"]):
        same_bits(r["points"][par["key"]], [p["values"][i] for p in pts], f"points {par['key']}")
    compared = 0
    for nav in ("uncompensated", "compensated"):
        for name in rins.FIGURES:
            a = r["per_seed"][nav][name]
            assert a.shape == (n_pts, n_seeds), a.shape
            same_bits(a, [[s[nav][name] for s in p["per_seed"]] for p in pts], f"per_seed {nav} {name}")
            # A real sweep: every point x seed gives its own figure.
            assert len(set(a.ravel().tolist())) == a.size, f"{nav} {name}: repeated values"
            compared += a.size
        for o in cli["outputs"]:
            for q in ("median", "p05", "p95"):
                same_bits(r["summary"][nav][o["name"]][q], [p[nav][o["name"]][q] for p in pts],
                          f"summary {nav} {o['name']} {q}")
                compared += n_pts
            # The bands against numpy's percentiles of the per-seed figures (linear, as documented).
            xs = r["per_seed"][nav][o["name"]]
            for q, pct in (("median", 50), ("p05", 5), ("p95", 95)):
                np.testing.assert_allclose(r["summary"][nav][o["name"]][q], np.percentile(xs, pct, axis=1),
                                           rtol=1e-12, err_msg=f"{nav} {o['name']} {q} vs numpy")
    print(f"sweep_file: {n_pts} points x {n_seeds} seeds, {compared} numbers equal `rins sweep --json` bit for bit "
          f"({t_py:.1f} s in-process vs {t_cli:.1f} s for the CLI with its files and figures)")
    # The GIL is released while the sweep runs: this thread keeps stamping meanwhile.
    done, stamps, again = threading.Event(), [], {}
    th = threading.Thread(target=lambda: (again.update(r=rins.sweep_file(path, as_json=True)), done.set()))
    t0 = time.perf_counter()
    th.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
    th.join()
    wall = time.perf_counter() - t0
    gap = np.diff(stamps).max() if len(stamps) > 1 else float("inf")
    assert gap < 0.5 * wall, f"the main thread stalled {gap:.3f} s of {wall:.3f} s: the GIL was held"
    assert again["r"]["points"] == cli["points"], "the JSON form differs from the CLI's"
    print(f"sweep_file: the main thread's longest pause during the {wall:.2f} s sweep: {gap * 1e3:.1f} ms; "
          f"as_json=True equals the CLI's points")
    return path, r


def test_dask_sweep_file(path, local):
    from dask.distributed import Client, LocalCluster, get_task_stream

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        t0 = time.perf_counter()
        with get_task_stream(client) as ts:
            remote = rins.sweep_file(path, client=client, seeds_per_task=1)
        t_remote = time.perf_counter() - t0
        workers = len(client.scheduler_info()["workers"])
    assert workers == 2, workers
    # The work ran on the workers: one task per point x seed, on both of them.
    tasks = [t for t in ts.data if t["key"].startswith("_task")]
    assert len(tasks) == len(local["labels"]) * len(local["seeds"]), len(tasks)
    assert len({t["worker"] for t in tasks}) == 2, {t["worker"] for t in tasks}
    for key in ("name", "sweep_file", "duration_s", "parameters", "outputs", "labels"):
        assert remote[key] == local[key], key
    np.testing.assert_array_equal(remote["seeds"], local["seeds"])
    for key, v in local["points"].items():
        np.testing.assert_array_equal(remote["points"][key], v)
    for nav in ("uncompensated", "compensated"):
        for name in rins.FIGURES:
            same_bits(remote["per_seed"][nav][name], local["per_seed"][nav][name], f"dask per_seed {nav} {name}")
        for o, qs in local["summary"][nav].items():
            for q, v in qs.items():
                same_bits(remote["summary"][nav][o][q], v, f"dask summary {nav} {o} {q}")
    print(f"dask: the sweep file's {len(local['labels'])} points x {len(local['seeds'])} seeds (one seed per task) on "
          f"LocalCluster(n_workers=2, processes=True) equal the in-process result bit for bit ({t_remote:.1f} s, "
          f"{local['wall_s']:.1f} s in-process)")


def test_sweep_file_errors():
    path = os.path.join(WORK, "bad-sweep.toml")
    with open(path, "w") as f:
        f.write('[sweep]\nscenario = "builtin:paper-16pos-week"\ndays = 0.05\nseeds = 2\noutputs = ["lon_nm"]\n\n'
                '[[parameter]]\nkey = "scheme.dwel_s"\nvalues = [180.0]\n\n'
                '[[parameter]]\nkey = "site.lat_deg"\nvalues = [36.6, 123.0]\n')
    try:
        rins.sweep_file(path)
        raise AssertionError("an unknown key and latitude 123 were accepted")
    except rins.SweepError as e:
        msg = str(e)
    assert isinstance(rins.SweepError("x"), rins.ScenarioError) and isinstance(rins.SweepError("x"), ValueError)
    for part in (path, "line 8, column 7: parameter[0].key", '"scheme.dwel_s"', "scheme.dwell_s",
                 "line 13", "parameter[1].values[1]: site.lat_deg", "got 123"):
        assert part in msg, (part, msg)
    # The CLI says the same.
    cli = subprocess.run([RINS, "sweep", path, "--out", os.path.join(WORK, "bad-sweep-out")],
                         capture_output=True, text=True)
    assert cli.returncode != 0
    for line in msg.splitlines():
        assert line.strip() in cli.stderr, (line, cli.stderr)
    print(f"bad sweep file -> rins.SweepError, the CLI's words: {msg.splitlines()[1].strip()}")
    # A dict sweep: lines refer to rins.to_toml(d); a TOML syntax error names its line too.
    with open(EXAMPLE_SWEEP, "rb") as f:
        d = tomllib.load(f)
    d["sweep"]["outputs"] = ["lon_nmi"]
    try:
        rins.sweep_file(d)
        raise AssertionError("an unknown output was accepted")
    except rins.SweepError as e:
        assert str(e).startswith("dict:") and "sweep.outputs[0]" in str(e) and "lon_nmi" in str(e), str(e)
    with open(path, "w") as f:
        f.write('[sweep]\nscenario = "builtin:paper-16pos-week"\nseeds = [1, 2\n')
    try:
        rins.sweep_file(path)
        raise AssertionError("a broken list was accepted")
    except rins.SweepError as e:
        assert path in str(e) and "line 3" in str(e), str(e)
    try:
        rins.sweep_file(3)
        raise AssertionError("a number was accepted as a sweep file")
    except TypeError:
        pass


def child(code, **kw):
    """Runs `code` in a child Python (this interpreter, the same rins) from WORK."""
    return subprocess.Popen([sys.executable, "-c", code], cwd=WORK, text=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, **kw)


MEMORY_CHILD = f"""
import resource
resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))
import rins
for what, call in (
        ("run", lambda: rins.run({WEEK!r})),
        ("chunk", lambda: rins.Simulation({WEEK!r}, chunk=10**9)),
        ("step", lambda: rins.Simulation({WEEK!r}).step(10**12)),
        ("navigate", lambda: rins.navigate({WEEK!r}, record_every_s=0.01))):
    try:
        call()
        print(what, "accepted")
    except MemoryError as e:
        print(what, "MemoryError", e)
# The interpreter carries on: a short run fits.
print("after", len(rins.run({SHORT!r}, duration_s=60.0)["t_s"]))
"""


def test_memory_error():
    """Under a 6 GiB address-space limit the week's arrays do not fit: MemoryError, not SIGABRT."""
    p = child(MEMORY_CHILD)
    out, err = p.communicate(timeout=120)
    assert p.returncode == 0, (p.returncode, out, err)
    lines = dict(ln.split(" ", 1) for ln in out.splitlines())
    week = 7 * 86400 * 100
    for what in ("run", "chunk", "step", "navigate"):
        assert lines[what].startswith("MemoryError "), (what, lines[what])
    # The least of the bounds is named: the 6 GiB limit here, unless the machine has less free.
    m = re.search(r"rins\.run: (\d+) samples × (\d+) bytes = (\d+) bytes \([\d.]+ GB\) of arrays, more than this "
                  r"process can still allocate \((\d+) bytes \([\d.]+ [MG]B\) under (its address-space limit|"
                  r"its cgroup's memory limit|the machine's available memory)", lines["run"])
    assert m, lines["run"]
    n, per, need, left = map(int, m.groups()[:4])
    assert n == week and need == n * per and left < need <= 2**40, (n, per, need, left)
    assert "rins.Simulation(scenario, chunk=N)" in lines["run"] and "duration_s=" in lines["run"], lines["run"]
    assert "chunk=1000000000: 60480000 samples" in lines["chunk"] and "smaller chunk" in lines["chunk"], lines["chunk"]
    assert f"Simulation.step: {10**12} samples" in lines["step"], lines["step"]
    assert "rins.navigate: 60480001 error records" in lines["navigate"] and "record_every_s=" in lines["navigate"]
    assert lines["after"] == "6000", lines["after"]
    print(f"6 GiB address space: rins.run(week) -> MemoryError: {lines['run'][len('MemoryError '):]}")


# Ctrl-C as a terminal delivers it: Python raises KeyboardInterrupt only where SIGINT was not
# ignored when the interpreter started, and a shell ignores it in commands it starts in the
# background without job control (`cmd &` in a script, nohup): a suite started that way would
# see every signal of these tests ignored. Each process that is signalled sets Python's own
# handler first.
INTERRUPT_CHILD = """
import signal, sys, rins
signal.signal(signal.SIGINT, signal.default_int_handler)
call = {
    "montecarlo": lambda: rins.montecarlo(%(week)r, range(1, 33)),
    "run": lambda: rins.run(%(week)r, duration_s=2 * 86400.0, truth=False),
    "navigate": lambda: rins.navigate(%(week)r),
}[sys.argv[1]]
print("ready", flush=True)
call()
print("finished", flush=True)
""" % {"week": WEEK}


def test_interrupt():
    """SIGINT (Ctrl-C) 3 s into a long call (a week's Monte Carlo of 32 seeds, over a minute; 1 s
    into `rins.run` of two days, measured outputs: 2.4 GB of arrays, a few seconds) stops it
    within 2 s with KeyboardInterrupt."""
    for what, after_s in (("montecarlo", 3.0), ("run", 1.0), ("navigate", 3.0)):
        p = subprocess.Popen([sys.executable, "-c", INTERRUPT_CHILD, what], cwd=WORK, text=True,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        assert p.stdout.readline().strip() == "ready"
        started = time.perf_counter()
        time.sleep(after_s)
        assert p.poll() is None, f"{what} ended before the signal"
        t0 = time.perf_counter()
        p.send_signal(signal.SIGINT)
        try:
            out, err = p.communicate(timeout=30)
        finally:
            p.kill()
        dt = time.perf_counter() - t0
        # What a failure needs to be read: when the signal went, how long the child took after
        # it, how it ended, and the system's load.
        seen = (what, out, err[-2000:], f"signal {t0 - started:.2f} s after ready", f"exit {dt:.2f} s after it",
                f"returncode {p.returncode}", f"load {os.getloadavg()}")
        assert "KeyboardInterrupt" in err and "finished" not in out, seen
        assert p.returncode != 0, p.returncode
        assert dt < 2.0, f"{what}: {dt:.2f} s from SIGINT to exit"
        print(f"Ctrl-C: {what} stopped with KeyboardInterrupt {dt:.2f} s after SIGINT ({after_s:.0f} s into it)")
    # An interrupted step leaves the simulation where it was: the next step gives the samples a
    # fresh simulation gives.
    sim = rins.Simulation(SHORT, truth=False)
    first = sim.step(1000)
    sent = []
    signal.signal(signal.SIGINT, signal.default_int_handler)  # see INTERRUPT_CHILD
    timer = threading.Timer(0.5, lambda: (sent.append(time.perf_counter()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        sim.step(2 * 10**7)
        raise AssertionError("step(2 * 10**7) was not interrupted")
    except KeyboardInterrupt:
        dt = time.perf_counter() - sent[0]
    timer.join()
    assert dt < 2.0, dt
    assert sim.samples_done == 1000, sim.samples_done
    again = sim.step(5000)
    fresh = rins.Simulation(SHORT, truth=False)
    fresh.step(1000)
    ref = fresh.step(5000)
    for key in ("t_s", "dtheta_rad", "dv_mps"):
        same_bits(again[key], ref[key], f"{key} of the step after an interrupted one")
    assert first["t_s"][-1] < again["t_s"][0]
    print(f"Ctrl-C: Simulation.step(2 * 10**7) stopped {dt:.2f} s after SIGINT, the simulation unchanged")


BIG = 2**64


def raises(call, exc, *parts):
    try:
        call()
    except exc as e:
        msg = str(e)
        for part in parts:
            assert part in msg, (part, msg)
        return msg
    raise AssertionError(f"accepted: expected {exc.__name__} with {parts}")


def test_argument_errors():
    top = f"[0, {BIG - 1}]"
    sim = rins.Simulation(SHORT, duration_s=60.0)
    nan = tomllib.loads(rins.builtin_toml(SHORT))
    nan["site"]["lat_deg"] = float("nan")
    inf = json.loads(json.dumps(tomllib.loads(rins.builtin_toml(SHORT))))
    inf["sensor"] = {"gyro": {"position_bias": {"dph": [0.0, float("-inf"), 0.0]}}}
    cases = [
        (lambda: rins.run(SHORT, duration_s=1.0, seed=-1), ValueError, f"seed: expected a whole number in {top}, got -1"),
        (lambda: rins.run(SHORT, duration_s=1.0, seed=BIG), ValueError, f"seed: expected a whole number in {top}, got {BIG}"),
        (lambda: rins.run(SHORT, duration_s=1.0, seed=1.5), TypeError, f"seed: expected a whole number in {top}, got float 1.5"),
        (lambda: rins.Simulation(SHORT, chunk=-1), ValueError, f"chunk: expected a whole number in [1, {BIG - 1}], got -1"),
        (lambda: rins.Simulation(SHORT, chunk=0), ValueError, f"chunk: expected a whole number in [1, {BIG - 1}], got 0"),
        (lambda: rins.Simulation(SHORT, seed=-2), ValueError, f"seed: expected a whole number in {top}, got -2"),
        (lambda: sim.step(-3), ValueError, f"n: expected a whole number in {top}, got -3"),
        (lambda: sim.step(BIG), ValueError, f"n: expected a whole number in {top}, got {BIG}"),
        (lambda: rins.navigate(SHORT, duration_s=60.0, seed=-1), ValueError, f"seed: expected a whole number in {top}, got -1"),
        (lambda: rins.navigate(SHORT, duration_s=60.0, subsamples=2**70), ValueError,
         f"subsamples: expected a whole number in [1, 4], got {2**70}", "1 to 4"),
        (lambda: rins.montecarlo(WEEK, [3, -1], duration_s=60.0), ValueError,
         f"seeds[1]: expected a whole number in {top}, got -1"),
        (lambda: rins.montecarlo(WEEK, [BIG], duration_s=60.0), ValueError, f"seeds[0]: expected a whole number in {top}, got {BIG}"),
        (lambda: rins.montecarlo(WEEK, [1, 2, 1], duration_s=60.0), ValueError,
         "seeds[2]: seed 1 is listed twice (also seeds[0]); each seed runs once"),
        (lambda: rins.montecarlo(WEEK, [], duration_s=60.0), ValueError, "seeds: expected at least one seed, got none"),
        (lambda: rins.montecarlo(WEEK, [1.5], duration_s=60.0), TypeError, f"seeds[0]: expected a whole number in {top}, got float 1.5"),
        (lambda: rins.end_figures(WEEK, [7, 7], 60.0), ValueError, "seeds[1]: seed 7 is listed twice (also seeds[0])"),
        (lambda: sys.modules["rins.montecarlo"]._batches([1, 2], 0), ValueError,
         f"seeds_per_task: expected a whole number in [1, {BIG - 1}], got 0"),
        (lambda: rins.table4(WEEK, runs=0, days=0.001), ValueError, "runs: expected a whole number in [1, "),
        (lambda: rins.table4(WEEK, runs=-1, days=0.001), ValueError, "runs: expected a whole number in [1, ", "got -1"),
        (lambda: rins.Scenario(nan), rins.ScenarioError, "dict: site.lat_deg: expected a finite number, got NaN"),
        (lambda: rins.to_toml(inf), rins.ScenarioError, "dict: sensor.gyro.position_bias.dph[1]: expected a finite number, got -inf"),
        (lambda: rins.to_toml({"scenario": {"name": "x"}, "site": {"lat_deg": None}}), rins.ScenarioError,
         "dict: site.lat_deg: expected a string, number, bool, list or dict, got None, which has no TOML form"),
        (lambda: rins.to_toml({"run": {"seed": 2**70}}), rins.ScenarioError,
         f"dict: run.seed: expected a whole number in [-9223372036854775808, 9223372036854775807] (TOML's integers), got {2**70}"),
        (lambda: rins.to_toml({"run": {1: 2}}), rins.ScenarioError, "dict: run: expected string keys, got the key 1"),
    ]
    for call, exc, *parts in cases:
        msg = raises(call, exc, *parts)
    print(f"arguments: {len(cases)} bad values raise ValueError/TypeError naming the argument, e.g. {msg!r}")
    # numpy integers and the largest seed are whole numbers too.
    a = rins.run(SHORT, duration_s=1.0, seed=np.uint64(BIG - 1), truth=False)
    b = rins.run(SHORT, duration_s=1.0, seed=BIG - 1, truth=False)
    same_bits(a["dtheta_rad"], b["dtheta_rad"], "seed as numpy uint64")
    assert len(rins.Simulation(SHORT, duration_s=1.0, chunk=np.int64(30)).step(np.int32(7))["t_s"]) == 7
    # A dict is walked straight into TOML (no JSON): numpy scalars are numbers, and the text is
    # what the TOML writer makes of the same values given as Python's own.
    plain = {"scenario": {"name": "np", "duration_s": 10.0}, "run": {"seed": 3, "rate_hz": 100.0}}
    numpy_d = {"scenario": {"name": "np", "duration_s": np.float64(10.0)},
               "run": {"seed": np.int64(3), "rate_hz": np.float32(100.0)}}
    assert rins.to_toml(numpy_d) == rins.to_toml(plain), (rins.to_toml(numpy_d), rins.to_toml(plain))
    assert tomllib.loads(rins.to_toml(plain)) == plain
    s1 = rins.Scenario(plain)
    assert rins.Scenario(s1).toml == s1.toml and rins.Scenario(s1).seed == 3


if __name__ == "__main__":
    os.makedirs(WORK, exist_ok=True)
    test_hour_equals_csv()
    test_gil_released()
    test_errors()
    test_argument_errors()
    test_memory_error()
    test_interrupt()
    test_montecarlo_equals_cli()
    test_dask_sweep()
    sweep_path, sweep_local = test_sweep_file_equals_cli()
    test_dask_sweep_file(sweep_path, sweep_local)
    test_sweep_file_errors()
    print("test_package.py: all passed")
