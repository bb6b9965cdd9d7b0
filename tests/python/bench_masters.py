"""Wall time of a 1-hour run (360 000 steps of 10 ms) in each co-simulation master, in FMPy and
in process: the IMU FMU alone, and the carrier -> IMU system. A benchmark, run by hand (the
figures in docs/cosimulation.md come from it); test_masters.py checks that the same runs give
the same bits, and reuses nothing from here.

Each master runs in its own process (test_masters.py's worker). Needs the FMUs (`rins fmu build
--out FMU_DIR`), the release `rins` with its examples beside it (`cargo test --workspace
--release` builds examples/carrier_imu) and the venv of tests/run-all.sh.

Usage: python bench_masters.py FMU_DIR RINS_BINARY WORK_DIR
"""

import os
import sys
import time

import test_masters as tm


def one_hour_imu(n):
    """The IMU FMU alone: in process, FMPy, libcosim (OSP), ecos (FMI 2 and 3)."""
    times = {}
    _, times["in-process (rins run, every 100th sample written)"] = tm.in_process(n * tm.STEP, decimation=100)
    from fmpy import simulate_fmu
    t0 = time.perf_counter()
    simulate_fmu(os.path.join(tm.FMU_DIR, "RinsImu.fmu"), stop_time=n * tm.STEP, output_interval=tm.STEP,
                 start_values=tm.OSP_START, output=tm.DTHETA)
    times["FMPy simulate_fmu (FMI 2)"] = time.perf_counter() - t0
    _, times["libcosim OSP (FMI 2)"] = tm.master("libcosim", tm.osp_dir(), n, record=False)
    _, times["ecos (FMI 2)"] = tm.master("ecos", os.path.join(tm.FMU_DIR, "RinsImu.fmu"), n, record=False,
                                         start=tm.OSP_START)
    _, times["ecos (FMI 3)"] = tm.master("ecos", os.path.join(tm.FMU_DIR, "RinsImu3.fmu"), n, record=False,
                                         start={"run.seed": 5})
    return times


def one_hour_carrier_imu(n):
    """The carrier -> IMU system: in process, FMPy's API, libcosim (OSP, SSP), ecos (SSP, FMI 2
    and 3)."""
    imu, car = (os.path.join(tm.FMU_DIR, f) for f in ("RinsImu.fmu", "RinsCarrier.fmu"))
    times = {}
    _, times["in-process (the two models' FMI state machines, examples/carrier_imu)"] = tm.in_process_system(n, csv=False)
    _, times["FMPy FMU2Slave API, both FMUs (FMI 2, 6 outputs read per step)"] = tm.fmpy_connected(imu, car, n)
    _, times["libcosim OSP (FMI 2)"] = tm.master("libcosim", tm.carrier_osp(), n, record=False)
    _, times["libcosim SSP (FMI 2)"] = tm.master("libcosim", tm.carrier_ssp(), n, record=False)
    _, times["ecos SSP (FMI 2)"] = tm.master("ecos", tm.carrier_ssp(), n, record=False, parameter_set="carrier-imu")
    _, times["ecos SSP (FMI 3)"] = tm.master("ecos", tm.carrier_ssp(3), n, record=False, parameter_set="carrier-imu")
    return times


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    tm.FMU_DIR, tm.RINS, work = sys.argv[1:4]
    tm.WORK = os.path.join(work, "bench-masters")
    os.makedirs(tm.WORK, exist_ok=True)
    n = 360_000
    for k, v in one_hour_imu(n).items():
        print(f"1 h at 10 ms, {k}: {v:.2f} s")
    for k, v in one_hour_carrier_imu(n).items():
        print(f"carrier -> IMU, 1 h at 10 ms, {k}: {v:.2f} s")
