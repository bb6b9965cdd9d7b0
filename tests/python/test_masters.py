"""The IMU FMU in real co-simulation masters: OSP libcosim (FMI 2, libcosimpy 0.0.6) and ecos
(FMI 2 and 3, ecospy 0.7.2), from the shipped system files in fmi-wrapper/examples/system/
(OspSystemStructure.xml, SystemStructure.ssd with the .ssv parameter sets, packed into an .ssp).

Checks: the outputs are bit-identical to the in-process plant (`rins run`) and to FMPy for the
same parameters; an .ssv parameter set reaches the plant (a changed gyro bias shifts the
angular increments by bias x step); a chamber input set at t = 0 before initialization
changes the initial temperatures, one set at t = 100.00 s (a thermal update) or 100.37 s
(between updates) is in effect in the first step after it. (The wall time of a 1-hour run in
each master is a benchmark, not a test: bench_masters.py.)

The carrier -> IMU system (fmi-wrapper/examples/system/carrier-imu/: RinsCarrier.fmu driving
the IMU's carrier inputs): libcosim (OSP, SSP) and ecos (SSP), FMI 2, give IMU outputs
bit-identical to the two FMUs connected through FMPy's API in the masters' Jacobi order, which
equal the two models connected in process (examples/carrier_imu); the carrier FMUs validate and
reproduce their _ref.csv in FMPy. ecos runs the same system with the FMI 3
FMUs (fmi3/SystemStructure.ssd), connected through the scalar views of their array elements.

Each master runs in its own process (a libcosim error aborts its process; ecos needs
libtbb preloaded).

Usage: python test_masters.py FMU_DIR RINS_BINARY WORK_DIR
"""

import ctypes
import json
import math
import os
import shutil
import stat
import subprocess
import sys
import time
import zipfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "fmi-wrapper", "examples", "system")
STEP = 0.01

# The system: component name -> FMU file per FMI version (the carrier FMU joins here).
SYSTEM = {"imu": {2: "RinsImu.fmu", 3: "RinsImu3.fmu"}}

# Outputs compared (FMI 2 names; FMI 3 reads the array elements of the same names).
DTHETA = [f"imu.dtheta_rad[{i}]" for i in range(3)]
THERMAL = ["thermal.chamber_c", "thermal.housing_c", "thermal.board_c"]
OUTPUTS = DTHETA + THERMAL

# The parameters the OSP file sets (its <InitialValues>); the SSP sets them from the .ssv.
OSP_START = {"run.seed": 5, "sensor.gyro.bias.dph[2]": 0.02}

SCENARIO = """
[scenario]
name = "masters-check"
duration_s = {duration}
[run]
rate_hz = 100.0
seed = 5
[sensor]
preset = "paper-table3"
gyro.bias.dph = [0.01, 0.01, 0.02]
[outputs]
decimation = {decimation}
truth = {truth}
"""


# ---------------------------------------------------------------- workers (one process each)

def preload_tbb():
    """ecos's libecosc.so needs libtbb.so.12, which its wheel does not ship: load the one of
    the `tbb` wheel first (the same as putting the venv's lib/ on LD_LIBRARY_PATH)."""
    lib = os.path.join(sys.prefix, "lib", "libtbb.so.12")
    ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
    # ecos starts out-of-process FMUs with its proxyfmu binary, shipped without the execute bit.
    import importlib.util
    spec = importlib.util.find_spec("ecospy")
    proxy = os.path.join(os.path.dirname(spec.origin), "binaries", "proxyfmu")
    if os.path.exists(proxy) and not os.access(proxy, os.X_OK):
        os.chmod(proxy, os.stat(proxy).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


def run_libcosim(job):
    """libcosim from an OSP file or an .ssp; records OUTPUTS after every step."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    # libcosim instantiates with loggingOn and prints trace messages by default: the FMU's
    # logEvents line for every doStep would be printed 100 times per simulated second.
    log_output_level(CosimLogLevel.WARNING)
    if job["system"].endswith(".xml"):
        ex = CosimExecution.from_osp_config_file(job["system"])
    else:
        ex = CosimExecution.from_ssp_file(job["system"])
    idx = ex.slave_index_from_instance_name("imu")
    refs = {v.name.decode(): (v.reference, v.type) for v in ex.slave_variables(idx)}
    for name, value in job.get("start", {}).items():
        vr, ty = refs[name]
        ok = {0: ex.real_initial_value, 1: ex.integer_initial_value, 3: ex.boolean_initial_value}[ty](idx, vr, value)
        assert ok, (name, value)
    t0 = time.perf_counter()
    if not job["record"]:
        # Timing: no observer. A last-value observer reads every variable after every step;
        # with it a 600 s run took 28 s instead of 0.2 s here (docs/cosimulation.md).
        assert ex.simulate_until(int(round(job["steps"] * STEP * 1e9)))
        return {"wall_s": time.perf_counter() - t0}
    obs = CosimObserver.create_last_value()
    ex.add_observer(obs)
    man = CosimManipulator.create_override()
    ex.add_manipulator(man)
    out_refs = [refs[n][0] for n in job["outputs"]]
    events = {}
    for at, name, value in job.get("events", []):
        events.setdefault(at, []).append((name, value))
    rows = []
    for k in range(job["steps"]):
        for name, value in events.get(k, []):
            vr, ty = refs[name]
            if ty == 3:
                man.slave_boolean_values(idx, [vr], [value])
            else:
                man.slave_real_values(idx, [vr], [value])
        assert ex.step(1)
        rows.append(obs.last_real_values(idx, out_refs))
    return {"rows": rows, "wall_s": time.perf_counter() - t0}


def run_ecos(job):
    """ecos from an .ssp (with a named parameter set) or a structure built in code."""
    preload_tbb()
    from ecospy import EcosLib
    from ecospy.EcosSimulation import EcosSimulation
    from ecospy.EcosSimulationStructure import EcosSimulationStructure
    EcosLib.set_log_level("warn")
    if job["system"].endswith(".ssp"):
        sim = EcosSimulation(step_size=STEP, ssp_path=job["system"])
    else:
        ss = EcosSimulationStructure()
        ss.add_model("imu", job["system"])
        sim = EcosSimulation(step_size=STEP, structure=ss)
    # Set before init: the master applies them before the FMU's initialization.
    for name, value in job.get("start", {}).items():
        setter = sim.set_bool if isinstance(value, bool) else sim.set_integer if isinstance(value, int) else sim.set_real
        setter(f"imu::{name}", value)
    sim.init(0.0, job.get("parameter_set"))
    events = {}
    for at, name, value in job.get("events", []):
        events.setdefault(at, []).append((name, value))
    t0 = time.perf_counter()
    if not job["record"]:
        sim.step(job["steps"])
        wall = time.perf_counter() - t0
        sim.terminate()
        return {"wall_s": wall}
    rows = []
    names = [f"imu::{n}" for n in job["outputs"]]
    for k in range(job["steps"]):
        for name, value in events.get(k, []):
            (sim.set_bool if isinstance(value, bool) else sim.set_real)(f"imu::{name}", value)
        sim.step(1)
        rows.append([sim.get_real(n) for n in names])
    wall = time.perf_counter() - t0
    sim.terminate()
    return {"rows": rows, "wall_s": wall}


CARRIER_SIGNALS = (["carrier.lat_deg", "carrier.lon_deg", "carrier.height_m"]
                   + [f"carrier.v_enu_mps[{i}]" for i in range(3)] + [f"carrier.q_cn[{i}]" for i in range(4)])
CARRIER_EXAMPLES = os.path.join(EXAMPLES, "carrier-imu")
CARRIER_IMU_START = {"run.seed": 5, "carrier.external_inputs": True}


def fmpy_connected(imu_fmu, carrier_fmu, steps, outputs=OUTPUTS, init_transfer=True):
    """The carrier -> IMU system through FMPy's FMU2Slave API in the masters' Jacobi order:
    both step from t, then the carrier's outputs at t + h become the IMU's inputs for the next
    step; with `init_transfer` the carrier's initial outputs are the IMU's inputs before it
    leaves initialization mode. Returns the IMU outputs after every step."""
    from fmpy import read_model_description, extract
    from fmpy.fmi2 import FMU2Slave

    def open_fmu(path, name):
        md = read_model_description(path)
        d = extract(path)
        f = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName=name)
        f.instantiate()
        return f, {v.name: v for v in md.modelVariables}

    car, cv = open_fmu(carrier_fmu, "carrier")
    imu, iv = open_fmu(imu_fmu, "imu")
    for f in (car, imu):
        f.setupExperiment(startTime=0.0)
    imu.setInteger([iv["run.seed"].valueReference], [5])
    imu.setBoolean([iv["carrier.external_inputs"].valueReference], [True])
    car.enterInitializationMode()
    car.exitInitializationMode()
    src = [cv[n].valueReference for n in CARRIER_SIGNALS]
    dst = [iv[n].valueReference for n in CARRIER_SIGNALS]
    out = [iv[n].valueReference for n in outputs]
    imu.enterInitializationMode()
    if init_transfer:
        imu.setReal(dst, car.getReal(src))
    imu.exitInitializationMode()
    rows = []
    t0 = time.perf_counter()
    for k in range(steps):
        t = k * STEP
        car.doStep(t, STEP)
        imu.doStep(t, STEP)
        imu.setReal(dst, car.getReal(src))
        rows.append(imu.getReal(out))
    wall = time.perf_counter() - t0
    for f in (car, imu):
        f.terminate()
        f.freeInstance()
    return np.array(rows), wall


def in_process_system(steps, csv=True):
    """The carrier -> IMU system in process (the two models' generic FMI state machines
    connected in the masters' order: fmi-wrapper/models/imu-fmu/examples/carrier_imu.rs, built
    beside `rins` by tests/run-all.sh): imu.dtheta_rad after every step and the wall time."""
    exe = os.path.join(os.path.dirname(RINS), "examples", "carrier_imu")
    assert os.path.exists(exe), f"{exe} missing: `cargo test --workspace --release` builds it (or cargo build --release -p rins-imu-fmu --example carrier_imu)"
    r = subprocess.run([exe, str(steps)] + (["--csv"] if csv else []), capture_output=True, text=True, check=True)
    wall = float(r.stderr.split("wall_s")[1].split()[0])
    rows = np.array([[float(x) for x in line.split(",")] for line in r.stdout.splitlines()]) if csv else None
    return rows, wall


def carrier_osp():
    """The shipped carrier -> IMU OSP file beside the built FMI 2 FMUs."""
    d = os.path.join(WORK, "osp-carrier-imu")
    os.makedirs(d, exist_ok=True)
    shutil.copy(os.path.join(CARRIER_EXAMPLES, "OspSystemStructure.xml"), d)
    for f in ("RinsImu.fmu", "RinsCarrier.fmu"):
        shutil.copy(os.path.join(FMU_DIR, f), d)
    return os.path.join(d, "OspSystemStructure.xml")


def carrier_ssp(version=2):
    """The shipped carrier -> IMU SystemStructure.ssd (FMI 2, or fmi3/SystemStructure.ssd with
    the FMI 3 FMUs) with its .ssv sets and both FMUs packed into an .ssp."""
    path = os.path.join(WORK, f"rins-carrier-imu-{version}.ssp")
    ssd = os.path.join(CARRIER_EXAMPLES, *(["fmi3"] if version == 3 else []), "SystemStructure.ssd")
    suffix = "3" if version == 3 else ""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(ssd, "SystemStructure.ssd")
        for name in ("sea-state-5", "carrier-imu"):
            z.write(os.path.join(CARRIER_EXAMPLES, f"{name}.ssv"), f"resources/{name}.ssv")
        for f in (f"RinsImu{suffix}.fmu", f"RinsCarrier{suffix}.fmu"):
            z.write(os.path.join(FMU_DIR, f), f"resources/{f}")
    return path


def worker(path):
    with open(path) as f:
        job = json.load(f)
    res = {"libcosim": run_libcosim, "ecos": run_ecos}[job["master"]](job)
    with open(path + ".out", "w") as f:
        # repr of a float round-trips exactly.
        json.dump({"wall_s": res["wall_s"], "rows": [[repr(x) for x in r] for r in res.get("rows", [])]}, f)


# ---------------------------------------------------------------- the test driver

FMU_DIR = RINS = WORK = None


def master(name, system, steps, record=True, outputs=OUTPUTS, **extra):
    """Runs one job in a fresh process; returns (rows as an array, wall time)."""
    job = dict(master=name, system=system, steps=steps, record=record, outputs=outputs, **extra)
    path = os.path.join(WORK, f"job-{name}-{len(os.listdir(WORK))}.json")
    with open(path, "w") as f:
        json.dump(job, f)
    r = subprocess.run([sys.executable, __file__, "--worker", path], capture_output=True, text=True)
    assert r.returncode == 0, (name, system, r.returncode, r.stdout[-3000:], r.stderr[-3000:])
    with open(path + ".out") as f:
        res = json.load(f)
    rows = np.array([[float(x) for x in row] for row in res["rows"]]) if res["rows"] else None
    return rows, res["wall_s"]


def master_fails(name, system, steps, **extra):
    """Runs one job that must fail; returns the worker's exit code and output."""
    job = dict(master=name, system=system, steps=steps, record=True, outputs=OUTPUTS, **extra)
    path = os.path.join(WORK, f"job-{name}-{len(os.listdir(WORK))}.json")
    with open(path, "w") as f:
        json.dump(job, f)
    r = subprocess.run([sys.executable, __file__, "--worker", path], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr, os.path.exists(path + ".out")


def osp_dir():
    """The shipped OSP file beside the built FMUs (it names them relative to itself)."""
    d = os.path.join(WORK, "osp")
    os.makedirs(d, exist_ok=True)
    shutil.copy(os.path.join(EXAMPLES, "OspSystemStructure.xml"), d)
    for files in SYSTEM.values():
        shutil.copy(os.path.join(FMU_DIR, files[2]), d)
    return os.path.join(d, "OspSystemStructure.xml")


def ssp(version, parameter_set="paper-table3", edit=None):
    """The shipped SystemStructure.ssd and .ssv sets packed with the FMUs into an .ssp; the
    component binds `parameter_set` (optionally edited: a dict of parameter -> value)."""
    with open(os.path.join(EXAMPLES, "SystemStructure.ssd")) as f:
        ssd = f.read().replace("resources/paper-table3.ssv", f"resources/{parameter_set}.ssv")
    for comp, files in SYSTEM.items():
        ssd = ssd.replace(f"resources/{files[2]}", f"resources/{files[version]}")
    tag = f"{version}-{parameter_set}-{len(edit or {})}-{abs(hash(json.dumps(edit, sort_keys=True))) % 10**8}"
    path = os.path.join(WORK, f"rins-{tag}.ssp")
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", ssd)
        for name in ("paper-table3", "nav-grade-full"):
            with open(os.path.join(EXAMPLES, f"{name}.ssv")) as f:
                text = f.read()
            for p, v in (edit or {}).items() if name == parameter_set else ():
                i = text.index(f'name="{p}"')
                j = text.index('value="', i) + 7
                k = text.index('"', j)
                text = text[:j] + repr(v) + text[k:]
            z.writestr(f"resources/{name}.ssv", text)
        for files in SYSTEM.values():
            z.write(os.path.join(FMU_DIR, files[version]), f"resources/{files[version]}")
    return path


def in_process(duration_s, decimation=1):
    """The in-process plant's increments for the OSP parameters (`rins run`); with a
    decimation (timing), every n-th sample is written and the truth columns are left out."""
    path = os.path.join(WORK, f"inproc-{duration_s}.toml")
    with open(path, "w") as f:
        f.write(SCENARIO.format(duration=duration_s, decimation=decimation,
                                truth="true" if decimation == 1 else "false"))
    out = os.path.join(WORK, f"inproc-{duration_s}")
    t0 = time.perf_counter()
    subprocess.run([RINS, "run", path, "--out", out], check=True, capture_output=True)
    wall = time.perf_counter() - t0
    import csv
    with open(os.path.join(out, "imu.csv")) as f:
        rows = list(csv.DictReader(f))
    return np.array([[float(r[f"dtheta_{a}_rad"]) for a in "xyz"] for r in rows]), wall


def fmpy_run(fmu, steps, start, outputs=OUTPUTS):
    from fmpy import simulate_fmu
    r = simulate_fmu(fmu, stop_time=steps * STEP, output_interval=STEP, start_values=start, output=outputs)
    return np.column_stack([r[n] for n in outputs])[1:]


def test_osp_and_ssp_runs_are_bit_identical_to_in_process_and_fmpy():
    n = 6000  # 60 s: the first dwell, thermal updates every second
    ref, _ = in_process(n * STEP)
    fm = fmpy_run(os.path.join(FMU_DIR, "RinsImu.fmu"), n, OSP_START)
    assert np.array_equal(fm[:, :3], ref[:n]), "FMPy vs in-process"
    runs = {
        "libcosim OSP (FMI 2)": master("libcosim", osp_dir(), n),
        "libcosim SSP (FMI 2)": master("libcosim", ssp(2, edit={"sensor.gyro.bias.dph[2]": 0.02}), n,
                                       start={"run.seed": 5}),
        "ecos SSP (FMI 2)": master("ecos", ssp(2, edit={"sensor.gyro.bias.dph[2]": 0.02}), n,
                                   start={"run.seed": 5}, parameter_set="paper-table3"),
        "ecos code (FMI 2)": master("ecos", os.path.join(FMU_DIR, "RinsImu.fmu"), n, start=OSP_START),
    }
    for name, (rows, _) in runs.items():
        assert rows.shape == fm.shape, (name, rows.shape)
        assert np.array_equal(rows[:, :3], ref[:n]), (name, np.abs(rows[:, :3] - ref[:n]).max())
        assert np.array_equal(rows, fm), (name, "thermal outputs differ from FMPy")


def test_ecos_fmi3_from_ssp_gives_the_outputs_of_fmi2():
    # ecos reads and writes FMI 3 variables with nValues 1; the FMI 3 FMU declares every array
    # element as a scalar view too (`imu.dtheta_rad[2]`, `sensor.gyro.bias.dph[2]`), so the same
    # .ssv names and output names serve both versions: arrays included, FMI 3 gives FMI 2's
    # outputs bit for bit (the array variables themselves: FMPy in test_fmu.py).
    n = 3000
    outputs = OUTPUTS + ["gimbal.outer_rad", "imu.time_s"]
    edit = {"sensor.gyro.bias.dph[2]": 0.02}
    r3, _ = master("ecos", ssp(3, edit=edit), n, outputs=outputs, start={"run.seed": 5}, parameter_set="paper-table3")
    r2, _ = master("ecos", ssp(2, edit=edit), n, outputs=outputs, start={"run.seed": 5}, parameter_set="paper-table3")
    assert np.array_equal(r3, r2), np.abs(r3 - r2).max()
    ref, _ = in_process(n * STEP)
    assert np.array_equal(r3[:, :3], ref[:n]), "FMI 3 increments (bias from the .ssv) vs in-process"
    assert abs(r3[-1, -1] - n * STEP) < 1e-9, r3[-1, -1]
    assert r3[:, 6].max() > r3[0, 6], "the table moved (gimbal angle changes)"


def test_a_parameter_set_reaches_the_plant_in_both_masters():
    n = 2000
    delta_dph = 0.05
    base = {"sensor.gyro.bias.dph[2]": 0.01}
    shifted = {"sensor.gyro.bias.dph[2]": 0.01 + delta_dph}
    # The increments change by the bias times the step, in body z (same seed, same noise).
    expected = math.radians(delta_dph / 3600.0) * STEP * n
    for name, run in [
        ("libcosim", lambda e: master("libcosim", ssp(2, edit=e), n)),
        ("ecos FMI 2", lambda e: master("ecos", ssp(2, edit=e), n, parameter_set="paper-table3")),
        ("ecos FMI 3", lambda e: master("ecos", ssp(3, edit=e), n, parameter_set="paper-table3")),
    ]:
        a, _ = run(base)
        b, _ = run(shifted)
        shift = (b[:, 2] - a[:, 2]).sum()
        # Quantisation carries its remainder: the sum is within a few quanta of the shift.
        assert abs(shift - expected) < 0.01 * expected, (name, shift, expected)
        assert np.array_equal(a[:, :2], b[:, :2]), (name, "x and y unchanged")
    # The two grades differ: nav-grade-full has terms paper-table3 has off.
    p, _ = master("ecos", ssp(2, "paper-table3"), n, parameter_set="paper-table3")
    g, _ = master("ecos", ssp(2, "nav-grade-full"), n, parameter_set="nav-grade-full")
    assert not np.array_equal(p[:, :3], g[:, :3])


def test_a_refused_parameter_never_runs_with_the_default_value():
    """A value out of its documented range in the bound parameter set (the gyro z bias at
    1000 °/h, range [-100, 100]): the FMU refuses the set, refuses to leave initialization
    (FMI 2 as FMI 3) and refuses every step, so no master runs on with the default value.
    libcosim stops at initialization (the job fails before its first step). ecos 0.7.2 ignores
    the statuses and steps on (its init returns true): every increment it reads is NaN, never
    a number it could take for data. The same set in range runs (the control: the failure is
    the value's)."""
    bad = {"sensor.gyro.bias.dph[2]": 1000.0}
    good = {"sensor.gyro.bias.dph[2]": 99.0}
    code, out, wrote = master_fails("libcosim", ssp(2, edit=bad), 10)
    assert code != 0 and not wrote, ("libcosim", code, out[-2000:])
    rows, _ = master("libcosim", ssp(2, edit=good), 10)
    assert rows.shape[0] == 10 and np.isfinite(rows).all(), rows
    for version in (2, 3):
        rows, _ = master("ecos", ssp(version, edit=bad), 10, parameter_set="paper-table3")
        assert rows.shape[0] == 10 and np.isnan(rows[:, :3]).all(), (version, rows[:, :3])
        rows, _ = master("ecos", ssp(version, edit=good), 10, parameter_set="paper-table3")
        assert np.isfinite(rows).all(), (version, rows)


def test_chamber_inputs_before_initialization_and_at_100_s():
    n = 10_038
    start = {"input.chamber_override": True, "input.chamber_temp_c": 35.0}
    fm_default = fmpy_run(os.path.join(FMU_DIR, "RinsImu.fmu"), 1, {})
    fm35 = fmpy_run(os.path.join(FMU_DIR, "RinsImu.fmu"), 1, start)
    events = [[10_000, "input.chamber_override", True], [10_000, "input.chamber_temp_c", 40.0],
              [10_037, "input.chamber_temp_c", 45.0]]
    for name, (rows, _) in {
        "libcosim": master("libcosim", osp_dir(), 1, start=start),
        "ecos": master("ecos", os.path.join(FMU_DIR, "RinsImu.fmu"), 1, start=start),
    }.items():
        # Initial state at 35 degC: the first step has no thermal update yet.
        assert np.array_equal(rows[0, 3:], fm35[0, 3:]), (name, rows[0, 3:], fm35[0, 3:])
        assert rows[0, 3] == 35.0 and rows[0, 4] != fm_default[0, 4], name
    for name, (rows, _) in {
        "libcosim": master("libcosim", osp_dir(), n, events=events),
        "ecos": master("ecos", os.path.join(FMU_DIR, "RinsImu.fmu"), n, events=events),
    }.items():
        chamber = rows[:, 3]
        assert chamber[9_999] == 25.0, (name, "until 100.00 s", chamber[9_999])
        assert chamber[10_000] == 40.0, (name, "in the step from 100.00 s", chamber[10_000])
        assert rows[10_000, 4] > rows[9_999, 4], (name, "the housing warms")
        # Between the 1 s thermal updates (100.37 s): in effect in that step too, not at 101 s.
        assert rows[10_036, 4] == rows[10_001, 4], (name, "held between updates")
        assert chamber[10_037] == 45.0, (name, "in the step from 100.37 s", chamber[10_037])
        assert rows[10_037, 4] > rows[10_036, 4], (name, "the housing warms at 100.37 s")


# A declared effect in FMU slot 0 of the gyros (docs/fmu.md, "Declared effects (slots)"):
# u_z^2 as the product u_z*u_z, 50 deg/h on x and -30 deg/h on z.
SLOT = {"sensor.gyro.slot[0].enabled": True, "sensor.gyro.slot[0].kind": 1,
        "sensor.gyro.slot[0].signal[0]": 4, "sensor.gyro.slot[0].node_or_axis[0]": 2,
        "sensor.gyro.slot[0].signal[1]": 4, "sensor.gyro.slot[0].node_or_axis[1]": 2,
        "sensor.gyro.slot[0].coef[0]": 50.0, "sensor.gyro.slot[0].coef[2]": -30.0}


def test_declared_effect_slots_are_set_by_the_masters():
    """Slot parameters set before initialization by libcosim (OSP, FMI 2: booleans, integers
    and reals through its initial-value calls) and by ecos (FMI 2, and FMI 3 through the
    element views) give the increments FMPy gives for the same start values; the slot changes
    them."""
    n = 2000
    start = dict(OSP_START, **SLOT)
    fm = fmpy_run(os.path.join(FMU_DIR, "RinsImu.fmu"), n, start)
    plain = fmpy_run(os.path.join(FMU_DIR, "RinsImu.fmu"), n, OSP_START)
    assert not np.array_equal(fm[:, [0, 2]], plain[:, [0, 2]]), "the slot acts on x and z"
    assert np.array_equal(fm[:, 1], plain[:, 1]), "and not on y"
    runs = {name: master("ecos", os.path.join(FMU_DIR, fmu), n, start=start)[0]
            for name, fmu in [("ecos FMI 2", "RinsImu.fmu"), ("ecos FMI 3", "RinsImu3.fmu")]}
    runs["libcosim OSP (FMI 2)"] = master("libcosim", osp_dir(), n, start=SLOT)[0]
    for name, rows in runs.items():
        assert np.array_equal(rows, fm), (name, np.abs(rows - fm).max())


def test_carrier_fmus_validate_and_reproduce_their_reference_results():
    """RinsCarrier(3).fmu: `fmpy validate` finds nothing, and FMPy regenerates the shipped
    <Model>_ref.csv (every output, initial row included) bit for bit."""
    from fmpy import simulate_fmu
    from fmpy.util import read_csv
    from fmpy.validation import validate_fmu
    for model in ("RinsCarrier", "RinsCarrier3"):
        base = os.path.join(FMU_DIR, model)
        assert validate_fmu(base + ".fmu") == [], model
        ref = read_csv(base + "_ref.csv")
        names = [n for n in ref.dtype.names if n != "time"]
        arrays = sorted({n.split("[")[0] for n in names}) if model.endswith("3") else names
        r = simulate_fmu(base + ".fmu", stop_time=ref["time"][-1], output_interval=STEP, output=arrays)
        assert len(r) == len(ref), (model, len(r), len(ref))
        for n in names:
            got = r[n.split("[")[0]][:, int(n[:-1].split("[")[1])] if "[" in n and model.endswith("3") else r[n]
            assert np.array_equal(got, ref[n]), (model, n)
        # The sea moves the ship: roll rate of order 0.01-0.1 rad/s.
        assert np.abs(ref["carrier.omega_nc_c_rps[1]"]).max() > 1e-3


def test_carrier_imu_system_is_bit_identical_in_every_master():
    """The carrier -> IMU system from the shipped OSP file (libcosim) and SSP file (libcosim,
    ecos; FMI 2, and ecos with the FMI 3 FMUs) gives IMU outputs bit-identical to the two FMUs connected through FMPy's API in
    the same (Jacobi) order, and those to the two models connected in process; the IMU does move with the ship (its increments differ from the
    static IMU's by the ship's rates times the step)."""
    n = 3000  # 30 s, three wave periods
    imu, car = (os.path.join(FMU_DIR, f) for f in ("RinsImu.fmu", "RinsCarrier.fmu"))
    ref, _ = fmpy_connected(imu, car, n)
    inproc, _ = in_process_system(n)
    assert np.array_equal(inproc, ref[:, :3]), "in-process system vs FMPy"
    runs = {
        "libcosim OSP (FMI 2)": master("libcosim", carrier_osp(), n),
        "libcosim SSP (FMI 2)": master("libcosim", carrier_ssp(), n),
        # ecos applies the parameter set it is given by name: the IMU's (the carrier's set is
        # its defaults).
        "ecos SSP (FMI 2)": master("ecos", carrier_ssp(), n, parameter_set="carrier-imu"),
        # FMI 3: the same connector names, which the FMI 3 FMUs declare as scalar views of their
        # array elements (ecos reads every FMI 3 variable as a scalar).
        "ecos SSP (FMI 3)": master("ecos", carrier_ssp(3), n, parameter_set="carrier-imu"),
    }
    for name, (rows, _) in runs.items():
        assert rows.shape == ref.shape, (name, rows.shape)
        assert np.array_equal(rows, ref), (name, np.flatnonzero((rows != ref).any(axis=1))[:5])
    static = fmpy_run(imu, n, {"run.seed": 5})
    moved = np.abs(ref[:, :3] - static[:, :3]).max()
    assert moved > 1e-4, moved


if __name__ == "__main__":
    if sys.argv[1] == "--worker":
        worker(sys.argv[2])
        sys.exit(0)
    FMU_DIR, RINS, WORK = sys.argv[1:4]
    WORK = os.path.join(WORK, "masters")
    os.makedirs(WORK, exist_ok=True)
    only = sys.argv[4:]
    failed = 0
    tests = [(k, v) for k, v in sorted(globals().items()) if k.startswith("test_") and (not only or k in only)]
    for name, fn in tests:
        try:
            fn()
            print(f"ok   {name}")
        except Exception as e:  # report every failure, then exit non-zero
            failed += 1
            print(f"FAIL {name}: {e!r}")
    print(f"{len(tests) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)
