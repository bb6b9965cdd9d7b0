"""Real-client checks of the FMUs with FMPy: validation, simulation of both FMUs, bit-identity
with the in-process plant, and the Dask Monte Carlo example.

Usage: python test_fmu.py FMU_DIR RINS_BINARY WORK_DIR
"""

import csv
import os
import subprocess
import sys

import numpy as np

FMU_DIR, RINS, WORK = sys.argv[1:4]
FMU2 = os.path.join(FMU_DIR, "RinsImu.fmu")
FMU3 = os.path.join(FMU_DIR, "RinsImu3.fmu")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "fmi-wrapper", "examples"))

SCENARIO = """
[scenario]
name = "fmpy-check"
duration_s = 600.0
[run]
rate_hz = 100.0
seed = 5
[scheme]
kind = "sixteen-position"
rate_dps = 2.0
accel_dps2 = 20.0
dwell_s = 180.0
[sensor]
preset = "paper-table3"
gyro.bias.dph = [0.01, 0.01, 0.02]
[thermal]
chamber = { temp_c = 25.0 }
[outputs]
decimation = 1
truth = true
"""
START = {"run.seed": 5, "sensor.gyro.bias.dph[2]": 0.02}
START3 = {"run.seed": 5, "sensor.gyro.bias.dph": [0.01, 0.01, 0.02]}


def test_validate():
    from fmpy.validation import validate_fmu
    for f in (FMU2, FMU3):
        problems = validate_fmu(f)
        assert problems == [], (f, problems)
    for f in (FMU2, FMU3):
        out = subprocess.run([sys.executable, "-m", "fmpy.cli", "validate", f], capture_output=True, text=True)
        assert out.returncode == 0 and "No problems found" in out.stdout, (f, out.stdout, out.stderr)


def in_process():
    path = os.path.join(WORK, "fmpy-check.toml")
    with open(path, "w") as f:
        f.write(SCENARIO)
    subprocess.run([RINS, "run", path, "--out", os.path.join(WORK, "inproc")], check=True, capture_output=True)
    with open(os.path.join(WORK, "inproc", "imu.csv")) as f:
        rows = list(csv.DictReader(f))
    # float() of the shortest round-trip text is the exact double.
    cols = ["dtheta_x_rad", "dtheta_y_rad", "dtheta_z_rad", "dv_x_mps", "dv_y_mps", "dv_z_mps", "q_bn_w"]
    return {c: np.array([float(r[c]) for r in rows]) for c in cols}


def test_fmpy_equals_in_process_to_the_last_bit():
    from fmpy import simulate_fmu
    ref = in_process()
    n = len(ref["dtheta_x_rad"])
    assert n == 60000, n
    names = [f"imu.dtheta_rad[{i}]" for i in range(3)] + [f"imu.dv_mps[{i}]" for i in range(3)]
    r2 = simulate_fmu(FMU2, stop_time=600.0, output_interval=0.01, start_values=START, output=names)
    r3 = simulate_fmu(FMU3, stop_time=600.0, output_interval=0.01, start_values=START3, output=["imu.dtheta_rad", "imu.dv_mps"])
    assert len(r2) == n + 1 and len(r3) == n + 1, (len(r2), len(r3))
    # Row 0 is the initial output; row k+1 is IMU sample k.
    for i, ax in enumerate("xyz"):
        a2 = r2[f"imu.dtheta_rad[{i}]"][1:]
        a3 = r3["imu.dtheta_rad"][1:, i]
        assert np.array_equal(a2, ref[f"dtheta_{ax}_rad"]), ("FMI2 dtheta", ax, np.abs(a2 - ref[f"dtheta_{ax}_rad"]).max())
        assert np.array_equal(a3, ref[f"dtheta_{ax}_rad"]), ("FMI3 dtheta", ax)
        assert np.array_equal(r2[f"imu.dv_mps[{i}]"][1:], ref[f"dv_{ax}_mps"]), ("FMI2 dv", ax)
        assert np.array_equal(r3["imu.dv_mps"][1:, i], ref[f"dv_{ax}_mps"]), ("FMI3 dv", ax)
    # Time stamps are the integer tick times.
    assert np.array_equal(r2["time"], np.arange(n + 1) / 100.0) or np.abs(r2["time"] - np.arange(n + 1) / 100.0).max() < 1e-9


def test_fmpy_rejects_a_bad_parameter_with_the_reason():
    from fmpy import simulate_fmu
    messages = []

    def logger(*args):
        messages.append(" ".join(str(a) for a in args))
    try:
        simulate_fmu(FMU2, stop_time=1.0, output_interval=0.01, start_values={"sensor.gyro.bias.dph[0]": 1e6}, logger=logger)
    except Exception as e:  # FMPy raises on the error status
        messages.append(str(e))
    else:
        raise AssertionError("an out-of-range parameter must fail")
    assert any("outside its range" in m for m in messages), messages


def test_dask_monte_carlo_matches_serial_runs_and_the_arw_spread():
    import dask_monte_carlo as mc
    seeds = list(range(1, 17))
    with open(FMU2, "rb") as f:
        fmu_bytes = f.read()
    warmup_s, run_s = 60.0, 300.0
    distributed = mc.run(FMU2, seeds, warmup_s, run_s, workers=2)
    serial = sorted(mc.simulate_seeds(seeds, fmu_bytes, warmup_s, run_s))
    assert distributed == serial, "runs on the cluster must equal runs in this process, bit for bit"
    rates = np.array([r for _, r in serial])
    # The spread of a T-second mean rate is ARW/sqrt(T): Table 3 ARW 0.003 deg/sqrt(h).
    sigma = 0.003 / np.sqrt(run_s / 3600.0)
    s = rates.std(axis=0, ddof=1)
    # 99 % chi-square band for 15 degrees of freedom: [0.55, 1.48] sigma.
    assert np.all((s > 0.55 * sigma) & (s < 1.48 * sigma)), (s, sigma)
    assert len({tuple(r) for r in rates.tolist()}) == len(seeds), "every seed gives its own noise"


def test_reference_results_are_reproduced_by_fmpy():
    """`rins fmu build` ships <Model>_ref.opt, _in.csv and _ref.csv beside each FMU (as
    modelica/Reference-FMUs do); FMPy simulating the FMU with those inputs and that experiment
    regenerates _ref.csv bit for bit, the initial row (initialization mode) included."""
    from fmpy import simulate_fmu
    from fmpy.util import read_csv
    for model in ("RinsImu", "RinsImu3"):
        base = os.path.join(FMU_DIR, model)
        opt = {}
        with open(base + "_ref.opt") as f:
            for line in f:
                k, v = line.split(",")
                opt[k.strip()] = float(v)
        ref = read_csv(base + "_ref.csv")
        inputs = read_csv(base + "_in.csv")
        names = [n for n in ref.dtype.names if n != "time"]
        # FMI 3 arrays are one variable: ask for the array, compare its elements.
        arrays = sorted({n.split("[")[0] for n in names}) if model.endswith("3") else names
        r = simulate_fmu(base + ".fmu", start_time=opt["StartTime"], stop_time=opt["StopTime"],
                         output_interval=opt["OutputInterval"], input=inputs, output=arrays)
        assert len(r) == len(ref), (model, len(r), len(ref))
        for n in names:
            if "[" in n and model.endswith("3"):
                a, i = n[:-1].split("[")
                got = r[a][:, int(i)]
            else:
                got = r[n]
            assert np.array_equal(got, ref[n]), (model, n, np.flatnonzero(got != ref[n])[:5])
        assert np.abs(r["time"] - ref["time"]).max() < 1e-9
        # The chamber input switched at 10.00 s, a thermal update time, is in effect in the
        # step from 10.00 s: the row at 10.01 s is the first at 40 degC.
        k = np.flatnonzero(ref["thermal.chamber_c"] == 40.0)[0]
        assert abs(ref["time"][k] - 10.01) < 1e-9, ref["time"][k]
        assert ref["thermal.housing_c"][0] > 26.0, "initial outputs are the initial state"


def test_fault_sequences_through_fmpy():
    """Issue 29 with FMPy's API as a master that carries on after an error (as ecos does): a
    refused parameter set makes leaving initialization mode fail in FMI 2 as in FMI 3, and
    after a refused step the increments read NaN in both while the time stays readable; the
    log says why, naming the variable."""
    import math
    import shutil
    from fmpy import extract, read_model_description
    from fmpy.fmi1 import FMICallException
    from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                           fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
    from fmpy.fmi3 import FMU3Slave
    from fmpy import calloc, free

    def status(call, *args):
        try:
            call(*args)
            return 0
        except FMICallException as e:
            return e.status

    for path in (FMU2, FMU3):
        md = read_model_description(path)
        vr = {v.name: v.valueReference for v in md.modelVariables}
        d = extract(path)
        fmi3 = md.fmiVersion.startswith("3")
        log = []
        if fmi3:
            def on_log(env, st, cat, msg):
                log.append(msg.decode())
            cls = FMU3Slave
        else:
            def on_log(env, name, st, cat, msg):
                log.append(msg.decode())
            cb = fmi2CallbackFunctions()
            cb.logger = fmi2CallbackLoggerTYPE(on_log)
            cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            cls = FMU2Slave
        f = cls(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                instanceName="faults")
        if fmi3:
            f.instantiate(logMessage=on_log)
            get, set_ = f.getFloat64, f.setFloat64
            enter = lambda: f.enterInitializationMode(startTime=0.0)
        else:
            f.instantiate(callbacks=cb)
            get, set_ = f.getReal, f.setReal
            enter = lambda: (f.setupExperiment(startTime=0.0), f.enterInitializationMode())
        bias = vr["sensor.gyro.bias.dph[0]"]
        # A refused set, then the master goes on: no initialization, no step.
        assert status(set_, [bias], [1e6]) == 3, path
        assert status(enter) == (3 if fmi3 else 0), (path, log)
        assert status(f.exitInitializationMode) == 3, (path, log)
        assert status(f.doStep, 0.0, 0.01) == 3, (path, log)
        text = "\n".join(log)
        assert "sensor.gyro.bias.dph[0] = 1000000 is outside its range" in text, text
        assert ("an earlier call setting a value was refused" in text) != fmi3, text
        assert "the instance is in the error state" in text, text
        # After a reset: a good step, then a refused one (wrong time) leaves NaN increments.
        f.reset()
        enter()
        f.exitInitializationMode()
        f.doStep(0.0, 0.01)
        inc = [vr["imu.dtheta_rad[0]"], vr["imu.dv_mps[2]"], vr["truth.dtheta_rad[1]"]]
        assert all(math.isfinite(x) for x in get(inc)), path
        assert status(f.doStep, 0.5, 0.01) == 3, path
        assert all(math.isnan(x) for x in get(inc)), (path, get(inc))
        assert get([vr["imu.time_s"]]) == [0.01], path
        f.terminate() if not fmi3 else None
        f.freeInstance()
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    failed = 0
    tests = [(k, v) for k, v in sorted(globals().items()) if k.startswith("test_")]
    for name, fn in tests:
        try:
            fn()
            print(f"ok   {name}")
        except Exception as e:  # report every failure, then exit non-zero
            failed += 1
            print(f"FAIL {name}: {e!r}")
    print(f"{len(tests) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)
