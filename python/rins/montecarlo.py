"""Monte Carlo over seeds, in-process or on a Dask cluster.

A task carries a scenario (as its TOML text: a ``rins.Scenario`` pickles that way) and a short
list of seeds, never arrays; a worker runs the seeds (both cores of its machine) and sends back
the end figures, a few numbers per seed. A seed gives the same bits on any worker, so a
cluster's result equals the in-process one exactly.
"""

import json

import numpy as np

from . import _rins

CASES = ("uncompensated", "compensated")


def _task(scenario, seeds, duration_s, alignment, subsamples=1):
    """One Dask task: the per-seed end figures of ``seeds`` (runs on a worker)."""
    return _rins.end_figures(scenario, seeds, duration_s, alignment, subsamples)


def _batches(seeds, seeds_per_task):
    seeds_per_task = _rins.whole(seeds_per_task, "seeds_per_task", 1, 2**64 - 1)
    return [seeds[i : i + seeds_per_task] for i in range(0, len(seeds), seeds_per_task)]


def _assemble(rows):
    """Per-seed tuples to ``{"seed": array, case: {figure: array}}``."""
    out = {"seed": np.array([r[0] for r in rows], dtype=np.uint64)}
    for k, case in enumerate(CASES):
        vals = np.array([r[1 + k] for r in rows], dtype=np.float64).reshape(len(rows), len(_rins.FIGURES))
        out[case] = {name: vals[:, i].copy() for i, name in enumerate(_rins.FIGURES)}
    return out


def _seeds(seeds):
    """The seeds as a list, checked before any task is sent (the compiled call's own check:
    whole numbers in [0, 2**64 - 1], at least one, none twice; ValueError or TypeError naming
    the entry)."""
    return _rins.check_seeds(seeds)


def sweep(scenarios, seeds, *, duration_s=None, alignment="truth", client=None, seeds_per_task=4,
          subsamples=1):
    """``montecarlo`` for several scenarios (parameter points) at once: every (scenario, seed
    batch) task is submitted before any is gathered, so a cluster works on all of them.
    Returns one result per scenario, in order."""
    points = [_rins.Scenario(s) for s in scenarios]
    seeds = _seeds(seeds)
    if client is None:
        return [_assemble(_task(p, seeds, duration_s, alignment, subsamples)) for p in points]
    batches = _batches(seeds, seeds_per_task)
    futures = [
        [client.submit(_task, p, b, duration_s, alignment, subsamples, pure=False) for b in batches]
        for p in points
    ]
    results = client.gather(futures)
    return [_assemble([row for part in parts for row in part]) for parts in results]


def montecarlo(scenario, seeds, *, duration_s=None, alignment="truth", client=None, seeds_per_task=4,
               subsamples=1):
    """Navigation end figures for each seed of one scenario: uncompensated and with the
    plant's δβ compensated (the per-seed numbers of ``rins paper table4``).

    ``scenario``: a path, ``"builtin:NAME"``, a dict or a ``rins.Scenario``; ``seeds``: the
    ``run.seed`` values; ``duration_s``: navigation time (default: the scenario's);
    ``alignment``: ``"truth"`` or ``"self"``; ``subsamples``: IMU intervals per navigator
    update, 1 to 4 (``rins paper table4`` uses 4). With a ``dask.distributed.Client`` the seeds go
    to its workers ``seeds_per_task`` at a time; with ``client=None`` they run in-process.

    Returns ``{"seed": uint64 array, "uncompensated": {figure: array}, "compensated": {...}}``
    with the figures of ``rins.FIGURES`` (nmi; mean |phi_U| in degrees).
    """
    return sweep([scenario], seeds, duration_s=duration_s, alignment=alignment, client=client,
                 seeds_per_task=seeds_per_task, subsamples=subsamples)[0]


def table4(scenario="builtin:paper-16pos-week", runs=2, days=7.0, alignment="truth", subsamples=4):
    """The ``rins paper table4`` study in-process (seeds from the scenario's ``run.seed``, plus
    the noise-free pair, navigators updated every ``subsamples`` intervals as the CLI's
    ``--subsamples``): the dict ``rins paper table4 --json`` prints."""
    return json.loads(_rins.table4_json(scenario, runs, days, alignment, subsamples))
