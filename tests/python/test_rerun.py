"""A Rerun recording read back with rerun-sdk==0.36.3: entity paths, row counts, time columns and
every logged value against the run's own CSV (bucket statistics recomputed here from the rows);
`rerun rrd verify`; same seed, same logged values; Ctrl-C still leaves a readable recording;
`rins paper table4`, `rins diagnose` and `rins serve` recordings against their own outputs;
`--rerun connect` to a headless viewer (`rerun --port P --save FILE`) receives what a save holds;
a ship's attitude and track against its CSV (test_rerun_carrier.py).

Usage: python test_rerun.py RINS_BINARY WORK_DIR
"""

import csv
import os
import signal
import subprocess
import sys
import time
import warnings
from collections import defaultdict

import pyarrow as pa
import rerun as rr

RINS, WORK = sys.argv[1:3]
RERUN_CLI = os.path.join(os.path.dirname(sys.executable), "rerun")
NODES = ["board", "gyro_x", "gyro_y", "gyro_z", "accel", "housing"]


def read_rrd(path):
    """entity path -> list of (step, sim_time ns, values) rows of its temporal chunks, plus the
    static rows per entity."""
    rows, static = defaultdict(list), defaultdict(int)
    for ch in rr.experimental.RrdReader(path).stream().to_chunks():
        b = ch.to_record_batch()
        names = b.schema.names
        ent = str(ch.entity_path)
        if "step" not in names:
            static[ent] += ch.num_rows
            continue
        steps = b.column("step").to_pylist()
        t_ns = b.column("sim_time").cast(pa.int64()).to_pylist()
        vals = b.column("Scalars:scalars").to_pylist() if "Scalars:scalars" in names else [None] * len(steps)
        rows[ent].extend(zip(steps, t_ns, vals))
    for r in rows.values():
        r.sort(key=lambda x: x[0])
    return rows, static


def check_blueprint(path, entities, plant=True):
    """The recording carries a blueprint whose every view shows entities that exist."""
    reader = rr.experimental.RrdReader(path)
    stores = reader.blueprints()
    assert len(stores) == 1, stores
    views = []
    for ch in reader.stream(store=stores[0]).to_chunks():
        b = ch.to_record_batch()
        if "ViewBlueprint:space_origin" in b.schema.names:
            views.append((b.column("ViewBlueprint:class_identifier").to_pylist()[0][0], b.column("ViewBlueprint:space_origin").to_pylist()[0][0]))
    assert (("3D", "/world") in views) == plant, views
    for kind, origin in views:
        if kind in ("3D", "TimeSeries"):
            assert any(e == origin or e.startswith(origin + "/") for e in entities), (kind, origin)
    return views


def read_csv(path):
    with open(path) as f:
        rd = csv.DictReader(f)
        return rd.fieldnames, list(rd)


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def verify(path):
    v = subprocess.run([RERUN_CLI, "rrd", "verify", path], capture_output=True, text=True)
    assert v.returncode == 0, v.stdout + v.stderr


def run(args, **kw):
    return subprocess.run([RINS, *args], capture_output=True, text=True, check=True, **kw)


# Every process started in the background here, stopped by stop_all whatever fails.
STARTED = []


def start(args, **kw):
    """subprocess.Popen, in a process group of its own and remembered for stop_all. The group is
    what gets killed: the `rerun` command is a Python wrapper that runs the viewer binary as its
    child (subprocess.call), so killing the wrapper alone left the viewer (`rerun --port P
    --save FILE`) running after the suite."""
    p = subprocess.Popen(args, start_new_session=True, **kw)
    STARTED.append(p)
    return p


def group_members(pgid):
    """PIDs of the processes of group `pgid` still running (zombies excluded: they only wait to
    be reaped by whoever inherited them), from /proc."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat") as f:
                stat = f.read()
        except OSError:
            continue  # ended meanwhile
        # pid (comm) state ppid pgrp ...: comm may hold spaces and parentheses.
        state, _ppid, pgrp = stat[stat.rindex(")") + 2:].split()[:3]
        if state != "Z" and int(pgrp) == pgid:
            pids.append(int(d))
    return pids


def stop(p):
    """Kills p and everything it started (its process group), waits for p and until no member
    of the group runs."""
    # p's PID names its group only while p (even unreaped) or a member of the group exists: the
    # kernel reuses the number only after both are gone, when it may be another's to signal.
    if p.poll() is None or group_members(p.pid):
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass  # ended meanwhile
    p.wait(timeout=30)
    for _ in range(100):
        if not group_members(p.pid):
            return
        time.sleep(0.1)
    raise AssertionError(f"{p.args}: processes {group_members(p.pid)} of its group still run after SIGKILL")


def stop_all():
    """Stops every process start() started (those that ended are only waited for)."""
    errors = []
    while STARTED:
        p = STARTED.pop()
        try:
            stop(p)
        except Exception as e:  # stop the others too, then report
            errors.append(e)
    if errors:
        raise errors[0]


SLOW_SAMPLES = 64  # temperatures and effects: mean over every (bucket // 64)th sample


def check_against_csv(out, bucket):
    """Every series of out/run.rrd against out/imu.csv with `bucket` samples per row."""
    stride = max(1, bucket // SLOW_SAMPLES)
    rrd = os.path.join(out, "run.rrd")
    v = subprocess.run([RERUN_CLI, "rrd", "verify", rrd], capture_output=True, text=True)
    assert v.returncode == 0, v.stdout + v.stderr
    fields, csv_rows = read_csv(os.path.join(out, "imu.csv"))
    rows, static = read_rrd(rrd)
    n = len(csv_rows)
    buckets = [csv_rows[i:i + bucket] for i in range(0, n, bucket)]
    gyro_keys = sorted({f[len("gyro_"):-len("_x_dph")] for f in fields if f.startswith("gyro_") and f.endswith("_x_dph")})
    accel_keys = sorted({f[len("accel_"):-len("_x_ug")] for f in fields if f.startswith("accel_") and f.endswith("_x_ug")})
    expected = {f"/imu/{q}/{a}" for q in ("dtheta_rad", "dv_mps") for a in "xyz"}
    expected |= {"/gimbal/outer_deg", "/gimbal/inner_deg", "/thermal/temps_c", "/world/base/outer", "/world/base/outer/inner",
                 "/world/base/outer/inner/imu", "/status/position"}
    expected |= {f"/effects/gyro/{k}_dph" for k in gyro_keys} | {f"/effects/accel/{k}_ug" for k in accel_keys}
    missing = expected - set(rows)
    assert not missing, f"missing entities {missing}; have {sorted(rows)}"
    extra = {e for e in rows if e.startswith("/effects/")} - expected
    assert not extra, f"effect entities without a CSV column: {extra}"
    for e in expected - {"/world/base/outer", "/world/base/outer/inner", "/world/base/outer/inner/imu", "/status/position"}:
        assert len(rows[e]) == len(buckets), (e, len(rows[e]), len(buckets))
        assert static[e] == 1, (e, "one static SeriesLines row with the legend names")
    checked = 0

    def close(a, b, scale):
        return abs(a - b) <= 1e-12 * max(scale, 1e-300) + 1e-300

    for k, rowsb in enumerate(buckets):
        last = rowsb[-1]
        step, t_ns, _ = rows["/imu/dtheta_rad/x"][k]
        assert step == int(last["sample"]), (k, step, last["sample"])
        assert t_ns == round(float(last["t_s"]) * 1e9), (k, t_ns, last["t_s"])
        for q, col in (("dtheta_rad", "dtheta_{}_rad"), ("dv_mps", "dv_{}_mps")):
            for a in "xyz":
                xs = [float(r[col.format(a)]) for r in rowsb]
                mean, lo, hi = rows[f"/imu/{q}/{a}"][k][2]
                assert lo == min(xs) and hi == max(xs), (q, a, k)
                assert close(mean, sum(xs) / len(xs), max(map(abs, xs))), (q, a, k, mean, sum(xs) / len(xs))
                checked += 3
        for g in ("outer", "inner"):
            xs = [float(r[f"{g}_deg"]) for r in rowsb]
            mean, lo, hi = rows[f"/gimbal/{g}_deg"][k][2]
            assert lo == min(xs) and hi == max(xs) and close(mean, sum(xs) / len(xs), max(map(abs, xs)) + 1.0), (g, k)
            checked += 3
        slow = rowsb[::stride]
        temps = rows["/thermal/temps_c"][k][2]
        for i, name in enumerate(NODES + ["chamber"]):
            xs = [float(r[f"temp_{name}_c"]) for r in slow]
            assert close(temps[i], sum(xs) / len(xs), max(map(abs, xs))), (name, k)
            checked += 1
        for kind, keys, unit in (("gyro", gyro_keys, "dph"), ("accel", accel_keys, "ug")):
            for key in keys:
                got = rows[f"/effects/{kind}/{key}_{unit}"][k][2]
                for i, a in enumerate("xyz"):
                    xs = [float(r[f"{kind}_{key}_{a}_{unit}"]) for r in slow]
                    assert close(got[i], sum(xs) / len(xs), max(map(abs, xs))), (kind, key, a, k, got[i], sum(xs) / len(xs))
                    checked += 1
    # One label per dwell change of the CSV's position column.
    changes = sum(1 for i, r in enumerate(csv_rows) if i == 0 or r["position"] != csv_rows[i - 1]["position"])
    assert len(rows["/status/position"]) == changes, (len(rows["/status/position"]), changes)
    assert len(rows["/world/base/outer/inner/imu"]) == changes
    return checked, rows


def main():
    # 1. Bucket of one sample: every logged value is a CSV value, bit for bit.
    out1 = os.path.join(WORK, "rr-exact")
    run(["run", "builtin:paper-16pos-short", "--out", out1, "--duration-s", "20", "--rerun", f"save:{out1}/run.rrd", "--rerun-bucket-s", "0.01"])
    checked1, rows1 = check_against_csv(out1, 1)
    for k, (_, _, (mean, lo, hi)) in enumerate(rows1["/imu/dtheta_rad/z"]):
        assert mean == lo == hi, k
    # 2. Buckets of 50 samples over a move and dwells, with the navigator recorded.
    out2 = os.path.join(WORK, "rr-bucket")
    run(["run", "builtin:paper-16pos-short", "--out", out2, "--duration-s", "400", "--rerun", f"save:{out2}/run.rrd", "--rerun-bucket-s", "0.5", "--nav"])
    checked2, rows2 = check_against_csv(out2, 50)
    views = check_blueprint(os.path.join(out2, "run.rrd"), set(rows2))
    assert ("TimeSeries", "/nav/reference/trms_nmi") in views, views
    for q in ("attitude_error_deg", "velocity_error_mps", "position_error_nmi", "trms_nmi"):
        assert len(rows2[f"/nav/reference/{q}"]) == 800, (q, len(rows2[f"/nav/reference/{q}"]))
    # 2b. Buckets of 200 samples: temperatures and effects from every 3rd sample.
    out2b = os.path.join(WORK, "rr-strided")
    run(["run", "builtin:paper-16pos-short", "--out", out2b, "--duration-s", "300", "--rerun", f"save:{out2b}/run.rrd", "--rerun-bucket-s", "2"])
    checked2b, _ = check_against_csv(out2b, 200)
    checked2 += checked2b
    # 3. Same scenario and seed: the same logged values.
    out3 = os.path.join(WORK, "rr-again")
    run(["run", "builtin:paper-16pos-short", "--out", out3, "--duration-s", "400", "--rerun", f"save:{out3}/run.rrd", "--rerun-bucket-s", "0.5", "--nav"])
    rows3, _ = read_rrd(os.path.join(out3, "run.rrd"))
    for e, r in rows2.items():
        if e.startswith(("/imu", "/effects", "/thermal", "/nav", "/gimbal")):
            assert r == rows3[e], e
    # 4. Ctrl-C: the run stops, exits 130, and the recording is complete up to there.
    out4 = os.path.join(WORK, "rr-interrupted")
    p = start([RINS, "run", "builtin:paper-16pos-week", "--out", out4, "--rerun", f"save:{out4}/run.rrd", "--rerun-bucket-s", "10"],
                         stderr=subprocess.PIPE, text=True)
    time.sleep(2.0)
    assert p.poll() is None, "the week-long run ended before the interrupt"
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, err)
    assert "interrupted after" in err, err
    v = subprocess.run([RERUN_CLI, "rrd", "verify", f"{out4}/run.rrd"], capture_output=True, text=True)
    assert v.returncode == 0, v.stdout + v.stderr
    rows4, _ = read_rrd(f"{out4}/run.rrd")
    n4 = len(rows4["/imu/dtheta_rad/x"])
    assert 0 < n4 < 60480, n4
    with open(f"{out4}/imu.csv", "rb") as f:
        data = f.read()
    assert data.endswith(b"\n"), "the CSV ends on a whole row"
    # 5. The result commands record too: Table 4 (both cases, as many rows as the JSON's first
    #    seed has records), diagnose (one row per analysis window), serve (the served stream).
    t4 = os.path.join(WORK, "rr-t4")
    out = run(["paper", "table4", "--runs", "1", "--days", "0.05", "--json", "--out", t4, "--rerun", f"save:{t4}/t4.rrd"]).stdout
    import json
    d = json.loads(out)
    verify(f"{t4}/t4.rrd")
    rows5, _ = read_rrd(f"{t4}/t4.rrd")
    check_blueprint(f"{t4}/t4.rrd", set(rows5))
    for k, case in ((1, "uncompensated"), (2, "compensated")):
        # One record per 60 s of navigation; the last equals the first seed's end figures.
        assert len(rows5[f"/nav/{case}/trms_nmi"]) == round(0.05 * 86400 / 60), (case, len(rows5[f"/nav/{case}/trms_nmi"]))
        end = d["per_seed"][0][k]
        assert abs(rows5[f"/nav/{case}/trms_nmi"][-1][2][0] - end["trms_nm"]) <= 1e-12 * end["trms_nm"], case
        assert abs(rows5[f"/nav/{case}/position_error_nmi"][-1][2][2] - end["horizontal_nm"]) <= 1e-12 * end["horizontal_nm"], case
    assert len(rows5["/imu/dtheta_rad/x"]) > 0 and len(rows5["/status/position"]) > 1
    unit = os.path.join(WORK, "rr-unit.csv")
    run(["measure", "docs/examples/diagnosis-truth.toml", "--out", unit, "--duration-s", "3600"], cwd=ROOT)
    dg = run(["diagnose", "--model", "docs/examples/diagnosis-model.toml", "--data", unit, "--json", "--rerun", f"save:{WORK}/rr-diag.rrd"], cwd=ROOT).stdout
    verify(f"{WORK}/rr-diag.rrd")
    rows6, _ = read_rrd(f"{WORK}/rr-diag.rrd")
    views = check_blueprint(f"{WORK}/rr-diag.rrd", set(rows6), plant=False)
    assert ("TimeSeries", "/diagnosis/residual/gyro_x") in views, views
    windows = json.loads(run(["compare", "--model", "docs/examples/diagnosis-model.toml", "--data", unit, "--json"], cwd=ROOT).stdout)["windows"]
    for ch in ("gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"):
        assert len(rows6[f"/diagnosis/residual/{ch}"]) == windows, (ch, len(rows6[f"/diagnosis/residual/{ch}"]), windows)
        assert len(rows6[f"/diagnosis/residual/{ch}"][0][2]) == 3, "residual, fitted, up_z"
    assert json.loads(dg)["ranking"], "diagnose still prints its report"
    # --iterate records the error falling: per channel one row per step, residual/floor as in
    # the history JSON the same run prints.
    it = json.loads(run(["diagnose", "--model", "docs/examples/diagnosis-model.toml", "--data", unit, "--iterate",
                         "--out", f"{WORK}/rr-iterated.toml", "--json", "--rerun", f"save:{WORK}/rr-iter.rrd"], cwd=ROOT).stdout)
    verify(f"{WORK}/rr-iter.rrd")
    rows_it, _ = read_rrd(f"{WORK}/rr-iter.rrd")
    views = check_blueprint(f"{WORK}/rr-iter.rrd", set(rows_it), plant=False)
    assert ("TimeSeries", "/diagnosis/iteration/gyro_x") in views, views
    assert len(it["steps"]) >= 2, "the dataset needs at least one fit"
    for c, ch in enumerate(("gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z")):
        got = rows_it[f"/diagnosis/iteration/{ch}"]
        assert len(got) == len(it["steps"]), (ch, len(got), len(it["steps"]))
        for st, row in zip(it["steps"], got):
            assert row[2][0] == st["levels"][c]["ratio"], (ch, st["step"], row, st["levels"][c])
    session = f"rr{os.getpid()}"
    plant = start([RINS, "serve", "builtin:paper-16pos-week", "--session", session, "--duration-s", "600",
                              "--rerun", f"save:{WORK}/rr-serve.rrd", "--rerun-bucket-s", "1"], stderr=subprocess.PIPE, text=True)
    nav = subprocess.run([RINS, "nav", "--connect", session, "builtin:paper-16pos-week", "--duration-s", "600"], capture_output=True, text=True, timeout=120)
    _, err = plant.communicate(timeout=60)
    assert nav.returncode == 0 and plant.returncode == 0, (nav.stderr, err)
    verify(f"{WORK}/rr-serve.rrd")
    rows7, _ = read_rrd(f"{WORK}/rr-serve.rrd")
    assert len(rows7["/imu/dtheta_rad/x"]) == 600, len(rows7["/imu/dtheta_rad/x"])
    # The served stream is the in-process plant's: same first-bucket statistics as `rins run`.
    ref = os.path.join(WORK, "rr-serve-ref")
    run(["run", "builtin:paper-16pos-week", "--out", ref, "--duration-s", "600", "--rerun", f"save:{ref}/run.rrd", "--rerun-bucket-s", "1"])
    rows8, _ = read_rrd(f"{ref}/run.rrd")
    assert rows7["/imu/dtheta_rad/x"] == rows8["/imu/dtheta_rad/x"]
    # 6. --rerun connect: a headless `rerun --port P --save FILE` receives the same rows as a save.
    port = 20000 + os.getpid() % 20000
    got = os.path.join(WORK, "rr-connect.rrd")
    log_path = os.path.join(WORK, "rr-connect-server.log")
    # The server's log goes to a file: a pipe nobody reads fills up and blocks its shutdown.
    with open(log_path, "w") as log:
        server = start([RERUN_CLI, "--port", str(port), "--save", got], stdout=log, stderr=subprocess.STDOUT)
    try:
        for _ in range(300):
            with open(log_path) as f:
                if "Saving incoming log stream" in f.read():
                    break
            assert server.poll() is None, open(log_path).read()
            time.sleep(0.1)
        out6 = os.path.join(WORK, "rr-connect")
        run(["run", "builtin:paper-16pos-short", "--out", out6, "--duration-s", "20", "--rerun", f"connect:127.0.0.1:{port}", "--rerun-bucket-s", "0.1"])
        # The viewer writes as it receives; read its file while it runs (how it reacts to
        # signals depends on the parent's signal dispositions, so it is killed afterwards).
        rows9 = {}
        for _ in range(100):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the viewer's file has no footer until it stops
                try:
                    rows9, _ = read_rrd(got)
                except Exception:  # a partly written last message
                    rows9 = {}
            if len(rows9.get("/imu/dtheta_rad/x", [])) >= 200:
                break
            time.sleep(0.2)
    finally:
        # The viewer binary too, not only the `rerun` wrapper that started it.
        stop(server)
        STARTED.remove(server)
    run(["run", "builtin:paper-16pos-short", "--out", out6, "--duration-s", "20", "--rerun", f"save:{out6}/run.rrd", "--rerun-bucket-s", "0.1"])
    rows10, _ = read_rrd(f"{out6}/run.rrd")
    assert len(rows9["/imu/dtheta_rad/x"]) == 200 and rows9["/imu/dtheta_rad/x"] == rows10["/imu/dtheta_rad/x"]
    # 7. A ship: carrier attitude, the table on it and the track against the CSV's carrier truth.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from test_rerun_carrier import check_ship
    check_ship(RINS, WORK)
    print(f"1 passed, 0 failed: rerun recordings (exact {checked1} values, bucketed {checked2} values, "
          f"deterministic, interrupted after {n4} of 60480 rows and still readable; paper, diagnose, serve and connect)")


if __name__ == "__main__":
    try:
        main()
    finally:
        stop_all()
