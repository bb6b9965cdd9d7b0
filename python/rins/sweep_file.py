"""Sweep files (``rins sweep FILE``, docs/sweeps.md) from Python, in-process or on a Dask cluster.

In-process the whole file runs through the sweep engine ``rins sweep`` uses (GIL released).
On a cluster every (point, seed batch) is a task carrying the point's plant as TOML text and a
few seeds, never arrays; the client gathers a few numbers per seed and makes the report with the
engine's own code. A seed's figures do not depend on the seeds run beside it, so the cluster's
result equals the in-process one bit for bit.
"""

import json
import time

import numpy as np

from . import _rins
from .montecarlo import _batches

NAVIGATORS = ("uncompensated", "compensated")
BAND = ("median", "p05", "p95")


def _task(plant_toml, seeds, duration_s, alignment):
    """One Dask task: the per-seed figures of one point for ``seeds`` (runs on a worker)."""
    return _rins.sweep_seed_figures(plant_toml, seeds, duration_s, alignment)


def _values(xs):
    """A swept key's values per point: floats, whole numbers or switches as a numpy array of
    that kind, names as a string array."""
    if all(isinstance(x, bool) for x in xs):
        return np.array(xs, dtype=bool)
    if all(isinstance(x, int) and not isinstance(x, bool) for x in xs):
        return np.array(xs, dtype=np.uint64)
    if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in xs):
        return np.array(xs, dtype=np.float64)
    return np.array([str(x) for x in xs])


def _result(report):
    """The report (the dict ``rins sweep --json`` prints) as numpy arrays, points first."""
    points = report["points"]
    n_seeds = len(report["seeds"])
    out = {k: report[k] for k in ("name", "description", "sweep_file", "scenario", "duration_s",
                                  "days", "alignment", "combine", "parameters", "outputs", "wall_s")}
    out["seeds"] = np.array(report["seeds"], dtype=np.uint64)
    out["labels"] = [p["label"] for p in points]
    out["points"] = {par["key"]: _values([p["values"][i] for p in points])
                     for i, par in enumerate(report["parameters"])}
    # JSON null (a NaN figure) becomes NaN through dtype=float64.
    out["per_seed"] = {
        nav: {f: np.array([[s[nav][f] for s in p["per_seed"]] for p in points],
                          dtype=np.float64).reshape(len(points), n_seeds)
              for f in _rins.FIGURES}
        for nav in NAVIGATORS
    }
    out["summary"] = {
        nav: {o["name"]: {q: np.array([p[nav][o["name"]][q] for p in points], dtype=np.float64)
                          for q in BAND}
              for o in report["outputs"]}
        for nav in NAVIGATORS
    }
    return out


def sweep_file(source, *, client=None, seeds_per_task=4, as_json=False):
    """Runs a sweep file as ``rins sweep FILE`` does and returns its result as numpy data.

    ``source``: the sweep file's path (a relative base scenario is taken from the file's
    folder, as the CLI does) or a dict laid out like the file (written as TOML first, so error
    lines refer to ``rins.to_toml(d)``; a relative base scenario is taken from the working
    folder). A bad file raises ``rins.SweepError`` (a ``rins.ScenarioError``) naming the file,
    line, column and key, with the CLI's wording.

    ``client=None`` runs in-process (every core, GIL released); with a
    ``dask.distributed.Client`` each point's seeds go to the workers ``seeds_per_task`` at a
    time, every task submitted before any is gathered. Both give the same bits.

    Returns a dict: ``name``, ``description``, ``sweep_file``, ``scenario``, ``duration_s``,
    ``days``, ``alignment``, ``combine``, ``parameters`` and ``outputs`` (lists of dicts, as in
    the JSON), ``wall_s``; ``seeds`` (uint64, S); ``labels`` (P strings, ``key = value, ...``);
    ``points`` {key: array of its value at each of the P points}; ``per_seed``
    {navigator: {figure: P x S float64}} with the figures of ``rins.FIGURES``; ``summary``
    {navigator: {output: {"median"|"p05"|"p95": P float64}}} for the file's outputs. Navigators
    are ``"uncompensated"`` and ``"compensated"``. ``as_json=True`` returns instead the dict
    ``rins sweep FILE --json`` prints (the same numbers, unconverted).
    """
    plan = _rins.SweepPlan(source)
    if client is None:
        text = plan.run_json()
    else:
        batches = _batches(list(plan.seeds), seeds_per_task)
        t0 = time.perf_counter()
        futures = [
            [client.submit(_task, plant, b, plan.duration_s, plan.alignment, pure=False) for b in batches]
            for plant in plan.point_plants()
        ]
        parts = client.gather(futures)
        wall_s = time.perf_counter() - t0
        text = plan.report_json([[row for part in point for row in part] for point in parts], wall_s)
    report = json.loads(text)
    return report if as_json else _result(report)
