"""Monte Carlo of the rins FMU over noise seeds with FMPy on a Dask cluster.

The pattern of FMPy's parameter_variation example, with one difference that matters for long
warm-ups: each partition instantiates the FMU once, runs the warm-up once, saves the FMU state,
and for every seed restores that post-warm-up state, sets `input.noise_seed` and simulates.
Every run is deterministic (same seed, same bits), wherever it runs.

Local (two worker processes):
    python dask_monte_carlo.py --fmu out/fmu/RinsImu.fmu --seeds 16

On many machines: start `dask scheduler` on one host, `dask worker tcp://HOST:8786 --nworkers N
--nthreads 1` on each machine (same Python packages), then pass `--scheduler tcp://HOST:8786`.
The FMU's bytes travel with the tasks and each worker unpacks them once into its own temp folder,
so no shared file system is needed.
"""

import argparse
import json
import os
import shutil
import tempfile

import numpy as np

DEG_PER_H = 180.0 / np.pi * 3600.0


def simulate_seeds(seeds, fmu_bytes, warmup_s, run_s):
    """Runs every seed of one partition on one FMU instance; returns (seed, mean rate °/h ×3)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    seeds = list(seeds)
    if not seeds:
        return []
    work = tempfile.mkdtemp(prefix="rins-dask-")
    try:
        path = os.path.join(work, "RinsImu.fmu")
        with open(path, "wb") as f:
            f.write(fmu_bytes)
        md = read_model_description(path)
        vr = {v.name: v.valueReference for v in md.modelVariables}
        unzipdir = extract(path, unzipdir=os.path.join(work, "x"))
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="mc")
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        # Warm-up once (thermal transient, first dwells), then keep that state.
        fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=warmup_s)
        warm = fmu.getFMUstate()
        dtheta = [vr[f"imu.dtheta_rad[{i}]"] for i in range(3)]
        out = []
        for seed in seeds:
            fmu.setFMUstate(warm)
            fmu.setInteger([vr["input.noise_seed"]], [int(seed)])
            # One communication step: the Δθ output is the sum over the whole step.
            fmu.doStep(currentCommunicationPoint=warmup_s, communicationStepSize=run_s)
            rate = [x / run_s * DEG_PER_H for x in fmu.getReal(dtheta)]
            out.append((int(seed), rate))
        fmu.freeFMUstate(warm)
        fmu.terminate()
        fmu.freeInstance()
        return out
    finally:
        shutil.rmtree(work, ignore_errors=True)


def run(fmu_path, seeds, warmup_s, run_s, scheduler=None, workers=2):
    import dask.bag as db
    from dask.distributed import Client, LocalCluster

    with open(fmu_path, "rb") as f:
        fmu_bytes = f.read()
    if scheduler:
        client = Client(scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        bag = db.from_sequence(seeds, npartitions=max(1, 2 * workers))
        results = bag.map_partitions(simulate_seeds, fmu_bytes, warmup_s, run_s).compute()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return sorted(results)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fmu", required=True)
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--warmup-s", type=float, default=60.0)
    ap.add_argument("--run-s", type=float, default=300.0)
    ap.add_argument("--scheduler", default=None, help="tcp://HOST:8786 of a running dask scheduler")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    res = run(a.fmu, list(range(1, a.seeds + 1)), a.warmup_s, a.run_s, a.scheduler, a.workers)
    rates = np.array([r for _, r in res])
    print(json.dumps({"runs": len(res), "mean_rate_dph": rates.mean(axis=0).tolist(),
                      "std_rate_dph": rates.std(axis=0, ddof=1).tolist()}))


if __name__ == "__main__":
    main()
