"""shoal: localization-aware path planning for one USV and N AUVs, from Python.

The planner of Eskandari, Savkin and Deghat, "Integrated Localization and Path Planning for an
Ocean Exploring Team of AUVs with Consensus Graph Model Predictive Control" (arXiv 2505.07484),
as the Rust library ``shoal`` implements it. This package is a thin layer over that library:

>>> import shoal
>>> plan = shoal.plan("default")              # the paper's experiment, N = 5 AUVs
>>> plan.positions.shape                      # (steps, N, 3): x, y, z of every AUV, metres
(21, 5, 3)
>>> plan.check().passed                       # the library's independent checker
True
>>> table = shoal.sweep({"axes": {"seed": "1..4"}})   # a pandas DataFrame, one row per run

Planning, checking and sweeping release the GIL. Errors are :class:`ShoalError` (and its
subclasses) carrying shoal's own message: the file or dictionary, the key, what is allowed.
See docs/python.md in the repository for the whole API.
"""

from __future__ import annotations

from . import _errors, _shoal
from ._check import CheckReport, Family
from ._errors import (
    CheckFailed,
    InfeasibleError,
    PlanFileError,
    PlanningError,
    ScenarioError,
    SeafloorError,
    ShoalError,
    ShoalWarning,
    SolverError,
    SweepError,
)
from ._inputs import Lattice, LatticeLike, PathLike, default_scenario_toml  # noqa: F401 (type aliases)
from ._plan import Plan, plan
from ._sweep import sweep

__all__ = [
    "plan",
    "sweep",
    "Plan",
    "Lattice",
    "CheckReport",
    "Family",
    "default_scenario_toml",
    *_errors.__all__,
]

__version__ = _shoal.version()

# The API is defined in private modules but belongs to `shoal`: its classes and functions say
# so (in repr, help and pickles), as the compiled module's exceptions do.
for _public in (
    plan,
    sweep,
    default_scenario_toml,
    Plan,
    Lattice,
    CheckReport,
    Family,
    CheckFailed,
    ShoalWarning,
):
    _public.__module__ = __name__
del _public
