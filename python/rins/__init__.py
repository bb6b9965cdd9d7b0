"""rins: the rotating ring-laser-gyro INS plant model from Python.

Load a scenario (a file path, ``"builtin:NAME"``, or a dict laid out like the TOML file), run
it to numpy arrays (``run``, or chunk by chunk with ``Simulation``), run the reference
navigator on it (``navigate``), run Monte Carlo seeds (``montecarlo``, ``sweep``) and sweep
files as ``rins sweep FILE`` runs them (``sweep_file``), in-process or on a Dask cluster. Rust
runs with the GIL released. See docs/python.md.
"""

from ._rins import (  # noqa: F401
    FIGURES,
    POSITION_LABELS,
    TEMP_NODES,
    NavigationError,
    Scenario,
    ScenarioError,
    Simulation,
    SweepError,
    SweepPlan,
    __version__,
    builtin_toml,
    builtins,
    end_figures,
    navigate,
    run,
    to_toml,
)
from .montecarlo import montecarlo, sweep, table4  # noqa: F401
from .sweep_file import sweep_file  # noqa: F401

__all__ = [
    "FIGURES",
    "POSITION_LABELS",
    "TEMP_NODES",
    "NavigationError",
    "Scenario",
    "ScenarioError",
    "Simulation",
    "SweepError",
    "SweepPlan",
    "builtin_toml",
    "builtins",
    "end_figures",
    "montecarlo",
    "navigate",
    "run",
    "sweep",
    "sweep_file",
    "table4",
    "to_toml",
]
