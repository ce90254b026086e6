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

import json
import os
import tempfile
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _shoal
from ._shoal import (
    InfeasibleError,
    PlanFileError,
    PlanningError,
    ScenarioError,
    SeafloorError,
    ShoalError,
    SolverError,
    SweepError,
)

__all__ = [
    "plan",
    "sweep",
    "Plan",
    "Lattice",
    "CheckReport",
    "Family",
    "default_scenario_toml",
    "ShoalError",
    "ScenarioError",
    "SeafloorError",
    "PlanningError",
    "InfeasibleError",
    "SolverError",
    "PlanFileError",
    "SweepError",
    "CheckFailed",
    "ShoalWarning",
]

__version__ = _shoal.version()

PathLike = Union[str, "os.PathLike[str]"]


class CheckFailed(ShoalError):
    """``Plan.check(strict=True)`` found a constraint family violated; ``report`` holds the
    :class:`CheckReport` and the message its table."""

    def __init__(self, report: "CheckReport") -> None:
        super().__init__(report.table)
        self.report = report


class ShoalWarning(UserWarning):
    """What the seafloor's loader warns of (a likely sign-convention mistake, an assumed
    datum), as ``shoal plan`` prints it."""


@dataclass(frozen=True)
class Lattice:
    """The nodes of a seafloor array: node ``z[j, i]`` is at ``(x0 + i*dx, y0 + j*dy)``, row
    ``j = 0`` the southernmost, in metres in the planner's frame (x east, y north)."""

    x0: float
    """x of the south-west node (column 0), metres."""
    y0: float
    """y of the south-west node (row 0), metres."""
    dx: float
    """Spacing between columns (east), metres, > 0."""
    dy: Optional[float] = None
    """Spacing between rows (north), metres, > 0; ``None``: the same as ``dx``."""

    def as_tuple(self) -> Tuple[float, float, float, float]:
        return (
            float(self.x0),
            float(self.y0),
            float(self.dx),
            float(self.dx if self.dy is None else self.dy),
        )


LatticeLike = Union[Lattice, Mapping[str, float], Sequence[float]]


def _lattice(lattice: Optional[LatticeLike]) -> Optional[Tuple[float, float, float, float]]:
    if lattice is None:
        return None
    if isinstance(lattice, Lattice):
        return lattice.as_tuple()
    if isinstance(lattice, Mapping):
        unknown = set(lattice) - {"x0", "y0", "dx", "dy"}
        missing = {"x0", "y0", "dx"} - set(lattice)
        if unknown or missing:
            raise SeafloorError(
                f"lattice: expected the keys x0, y0, dx and optionally dy; "
                f"{'unknown ' + ', '.join(sorted(unknown)) if unknown else ''}"
                f"{'; ' if unknown and missing else ''}"
                f"{'missing ' + ', '.join(sorted(missing)) if missing else ''}"
            )
        return Lattice(**{k: float(v) for k, v in lattice.items()}).as_tuple()
    values = [float(v) for v in lattice]
    if len(values) not in (3, 4):
        raise SeafloorError(
            f"lattice: expected (x0, y0, dx) or (x0, y0, dx, dy), got {len(values)} numbers"
        )
    return Lattice(*values).as_tuple()


def _floor_array(z: Any) -> np.ndarray:
    a = np.ascontiguousarray(z, dtype=np.float64)
    if a.ndim != 2:
        raise SeafloorError(
            f"the seafloor array must be 2-D (rows along y, columns along x), not {a.ndim}-D "
            f"of shape {a.shape}"
        )
    return a


def _toml_value(value: Any) -> str:
    """A Python value as a TOML value (for a ``key=value`` override)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, (str, os.PathLike)):
        return json.dumps(os.fspath(value))
    if isinstance(value, Mapping):
        inner = ", ".join(f"{json.dumps(str(k))} = {_toml_value(v)}" for k, v in value.items())
        return "{" + inner + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise ScenarioError(f"cannot write {value!r} ({type(value).__name__}) as a scenario value")


def _jsonable(value: Any) -> Any:
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def _split_dotted(d: Mapping[str, Any]) -> Tuple[Dict[str, Any], List[str]]:
    """A dictionary's nested keys, and its dotted ones ("team.auvs": 3) as overrides."""
    nested: Dict[str, Any] = {}
    dotted: List[str] = []
    for k, v in d.items():
        if "." in str(k):
            if v is not None:
                dotted.append(f"{k}={_toml_value(v)}")
        else:
            nested[str(k)] = v
    return nested, dotted


def _overrides(overrides: Union[None, Mapping[str, Any], Sequence[str]]) -> List[str]:
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{k}={_toml_value(v)}" for k, v in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    return [str(o) for o in overrides]


def plan(
    scenario: Union[None, str, "os.PathLike[str]", Mapping[str, Any]] = "default",
    seafloor: Union[None, str, "os.PathLike[str]", np.ndarray] = None,
    *,
    lattice: Optional[LatticeLike] = None,
    overrides: Union[None, Mapping[str, Any], Sequence[str]] = None,
    seed: Optional[int] = None,
    method: str = "mpc",
) -> "Plan":
    """Plan every window of a scenario (Algorithm 1), as ``shoal plan`` does.

    Args:
        scenario: ``"default"`` (or ``None``) for the embedded default (the paper's
            experiment); a path to a scenario TOML file (its relative ``seafloor.file``
            resolves against the file's directory); or a dictionary with the same keys and
            sections as the file, e.g. ``{"team": {"auvs": 3}, "horizon": {"steps": 10}}``
            (dotted keys such as ``{"team.auvs": 3}`` work too; ``None`` values are left out).
        seafloor: ``None``: the floor the scenario names (its grid file or the synthetic
            floor); a path to a grid file (ESRI ASCII ``.asc``, GeoTIFF ``.tif``), the same as
            ``overrides={"seafloor.file": path}``; or a 2-D array of floor heights ``z[j, i]``
            (metres, negative below the surface; NaN marks NODATA) at
            ``(x0 + i*dx, y0 + j*dy)``, row 0 the southernmost, with ``lattice``.
        lattice: For an array floor: a :class:`Lattice`, a mapping with ``x0``, ``y0``,
            ``dx`` (and optionally ``dy``), or a tuple ``(x0, y0, dx[, dy])``.
        overrides: ``key=value`` overrides applied after the scenario, as ``--set`` takes
            them: a mapping ``{"team.auvs": 7}`` or a list ``["team.auvs=7"]``.
        seed: Overrides the scenario's ``seed`` (initial positions, synthetic floor).
        method: ``"mpc"`` (Algorithm 1, the default) or ``"rrt-like"`` (the paper's sampling
            baseline).

    Returns:
        The :class:`Plan`.

    Raises:
        ScenarioError: the scenario, an override or the method is not allowed.
        SeafloorError: the grid file or the array cannot be read or used.
        InfeasibleError, SolverError (both :class:`PlanningError`): the planner made no plan.

    The GIL is released while the library plans.
    """
    extra = _overrides(overrides)
    if seed is not None:
        extra.append(f"seed={int(seed)}")
    z = lat = None
    if seafloor is not None:
        if isinstance(seafloor, (str, os.PathLike)):
            extra.append(f"seafloor.file={json.dumps(os.path.abspath(os.fspath(seafloor)))}")
        else:
            z = _floor_array(seafloor)
            lat = _lattice(lattice)
            if lat is None:
                raise SeafloorError(
                    "a seafloor array needs its lattice: lattice=dict(x0=..., y0=..., dx=...) "
                    "(the south-west node and the spacing, metres)"
                )
    elif lattice is not None:
        raise SeafloorError("lattice is given but no seafloor array")
    if method not in ("mpc", "rrt-like"):
        raise ScenarioError(f'method {method!r}: allowed are "mpc" and "rrt-like"')
    if scenario is None or (isinstance(scenario, str) and scenario == "default"):
        kind, text = "default", ""
    elif isinstance(scenario, (str, os.PathLike)):
        kind, text = "path", os.fspath(scenario)
    elif isinstance(scenario, Mapping):
        nested, dotted = _split_dotted(scenario)
        kind, text = "json", json.dumps(_jsonable(nested))
        extra = dotted + extra
    else:
        raise ScenarioError(
            f"scenario: expected \"default\", a path or a dictionary, not "
            f"{type(scenario).__name__}"
        )
    raw = _shoal.plan(kind, text, extra, method, z, lat)
    result = Plan(raw)
    for w in result._summary["load_warnings"]:
        warnings.warn(w, ShoalWarning, stacklevel=2)
    return result


@dataclass(frozen=True)
class Family:
    """One constraint family of the check: its worst margin over every individual check (in
    ``unit``; positive is inside the constraint, negative violated by that much)."""

    name: str
    """E.g. ``"C2_2 floor clearance"``."""
    checked: int
    """How many individual checks were made."""
    worst_margin: float
    """Smallest margin (``inf`` when nothing was checked, ``-inf`` when not evaluable)."""
    unit: str
    """``"m"``, ``"m/s"``, ``"rad/s"``, ``"relative"``, ``"problems"``, …"""
    tolerance: float
    """The family passes when ``worst_margin >= -tolerance``."""
    where: str
    """Where the worst margin is: window, step, vehicle (and what was wrong)."""
    passed: bool


@dataclass(frozen=True)
class CheckReport:
    """What the library's independent checker found (``shoal check``)."""

    passed: bool
    """Every family holds within its tolerance."""
    families: List[Family]
    """Every constraint family, in the order of the table."""
    problems: List[str]
    """Structural problems (malformed arrays, indices naming no vehicle); empty normally."""
    table: str = field(repr=False)
    """The checker's text table, as ``shoal check`` prints it."""

    @property
    def violations(self) -> List[Family]:
        """The families that fail (empty when ``passed``)."""
        return [f for f in self.families if not f.passed]

    def __str__(self) -> str:
        return self.table


def _float(v: Union[float, str]) -> float:
    # ±inf travel as the strings "inf" and "-inf" (JSON has no infinity)
    return float(v)


def _report(raw: Tuple[str, str]) -> CheckReport:
    data, table = json.loads(raw[0]), raw[1]
    families = [
        Family(
            name=f["name"],
            checked=int(f["checked"]),
            worst_margin=_float(f["worst_margin"]),
            unit=f["unit"],
            tolerance=_float(f["tolerance"]),
            where=f["where"],
            passed=bool(f["passed"]),
        )
        for f in data["families"]
    ]
    return CheckReport(
        passed=bool(data["passed"]),
        families=families,
        problems=list(data["problems"]),
        table=table,
    )


class Plan:
    """A plan of the whole mission, as ``shoal plan`` writes it to plan.json.

    Arrays cover the mission's steps: every window's final stage (Step 3, the plan the team
    executes), window w > 0 without its step 0, which is window w − 1's last step. So a
    mission of W windows of K steps has ``steps = W*K + 1``. Axis order: step, vehicle,
    coordinate; AUVs are numbered 0..N−1 as in the plan file.

    ============== ======================== ========= =============================================
    attribute      shape                    dtype     meaning
    ============== ======================== ========= =============================================
    positions      (steps, N, 3)            float64   AUV x, y, z, metres (z < 0 below the surface)
    velocities     (steps, N, 3)            float64   AUV velocity V_x, V_y, V_z, m/s
    inputs         (steps − 1, N, 3)        float64   AUV input U (per-mass force), m/s²; input t
                                                      acts from step t to t + 1
    usv_positions  (steps, 2)               float64   USV x, y, metres (on the surface, z = 0)
    usv_inputs     (steps − 1, 2)           float64   USV velocity, m/s
    times          (steps,)                 float64   seconds since the start of the mission
    window         (steps,)                 int64     the window of each step
    links          (steps, N, 2)            int64     planned links: row 0 the A2U link
                                                      ``(auv, -1)`` (−1 is the USV), then the
                                                      N − 1 A2A edges ``(i, j)`` of the chain
    ============== ======================== ========= =============================================

    ``metrics`` is the mission's metrics (dict, as plan.json's ``metrics``), ``window_metrics``
    each window's. The arrays are new copies at every access.
    """

    def __init__(self, raw: "_shoal.RawPlan") -> None:
        self._raw = raw
        self._summary: Dict[str, Any] = json.loads(raw.summary_json())

    # -- arrays ------------------------------------------------------------------------------

    @property
    def positions(self) -> np.ndarray:
        """AUV positions, (steps, N, 3) float64, metres: x east, y north, z up (z < 0)."""
        return self._raw.positions()

    @property
    def velocities(self) -> np.ndarray:
        """AUV velocities, (steps, N, 3) float64, m/s."""
        return self._raw.velocities()

    @property
    def inputs(self) -> np.ndarray:
        """AUV inputs U (per-mass force), (steps − 1, N, 3) float64, m/s²."""
        return self._raw.inputs()

    @property
    def usv_positions(self) -> np.ndarray:
        """USV positions, (steps, 2) float64, metres (z = 0)."""
        return self._raw.usv_positions()

    @property
    def usv_inputs(self) -> np.ndarray:
        """USV inputs (its velocity), (steps − 1, 2) float64, m/s."""
        return self._raw.usv_inputs()

    @property
    def times(self) -> np.ndarray:
        """Time of every step, (steps,) float64, seconds since the start of the mission."""
        return self._raw.times()

    @property
    def window(self) -> np.ndarray:
        """The window of every step, (steps,) int64."""
        return self._raw.window_of_step()

    @property
    def links(self) -> np.ndarray:
        """Planned links, (steps, N, 2) int64: ``links[t, 0]`` is the A2U link ``(auv, -1)``,
        ``links[t, 1:]`` the A2A edges ``(i, j)`` of the chain in path order; −1 pads."""
        return self._raw.links()

    # -- scalars and dictionaries ---------------------------------------------------------------

    @property
    def metrics(self) -> Dict[str, float]:
        """The mission's metrics (plan.json's ``metrics``): ``input_energy``,
        ``explored_area_km2``, ``revisited_area_km2``, ``mean_height``, ``min_height``,
        ``connected_fraction``, ``chain_fraction``, ``max_heading_rate``, ``step1_time_s``,
        ``step2_time_s``, ``step3_time_s``."""
        return dict(self._summary["metrics"])

    @property
    def window_metrics(self) -> List[Dict[str, float]]:
        """Each window's metrics, in order."""
        return [dict(m) for m in self._summary["window_metrics"]]

    @property
    def seed(self) -> int:
        """The scenario's seed."""
        return int(self._summary["seed"])

    @property
    def method(self) -> str:
        """The planner: ``"mpc"`` or ``"rrt-like"``."""
        return str(self._summary["method"])

    @property
    def auvs(self) -> int:
        """N, the number of AUVs."""
        return int(self._summary["auvs"])

    @property
    def windows(self) -> int:
        """The number of receding-horizon windows."""
        return int(self._summary["windows"])

    @property
    def dt(self) -> float:
        """δ, the time step, seconds."""
        return float(self._summary["dt"])

    @property
    def warnings(self) -> List[str]:
        """What the planner warns of (a stage that did not converge: feasible, not optimal)."""
        return list(self._summary["warnings"])

    @property
    def scenario(self) -> Dict[str, Any]:
        """The fully resolved scenario (every parameter), as a dictionary; it can be given back
        to :func:`plan`."""
        return json.loads(json.dumps(self._summary["scenario"]))

    @property
    def seafloor_record(self) -> Dict[str, Any]:
        """Where the floor came from, its lattice and fingerprint (plan.json's ``seafloor``)."""
        return dict(self._summary["seafloor"])

    def seafloor(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The floor the plan was made on: ``(x, y, z)`` with ``x`` (nx,) and ``y`` (ny,) the
        node coordinates (metres) and ``z`` (ny, nx) the heights (NaN at NODATA nodes), so that
        ``matplotlib``'s ``contourf(x, y, z)`` draws it."""
        z, (x0, y0, dx, dy) = self._raw.seafloor()
        ny, nx = z.shape
        return x0 + dx * np.arange(nx), y0 + dy * np.arange(ny), z

    # -- the library's functions ---------------------------------------------------------------

    def check(self, strict: bool = False) -> CheckReport:
        """Verify every constraint of the plan against its floor with the library's
        independent checker (``shoal check``). Returns the :class:`CheckReport`; with
        ``strict=True`` a failing check raises :class:`CheckFailed` instead. Releases the
        GIL."""
        report = _report(self._raw.check())
        if strict and not report.passed:
            raise CheckFailed(report)
        return report

    def to_json(self) -> str:
        """The plan file's text: what ``shoal plan`` writes to plan.json (format
        ``shoal-plan/4``, docs/plan-format.md)."""
        return self._raw.to_json()

    def save(self, path: PathLike) -> None:
        """Write :meth:`to_json` to ``path`` (then ``shoal check path`` works on it)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json())

    @classmethod
    def from_json(
        cls,
        text: str,
        seafloor: Union[None, str, "os.PathLike[str]", np.ndarray] = None,
        *,
        lattice: Optional[LatticeLike] = None,
    ) -> "Plan":
        """A plan from plan.json's text, over the floor it names (``None``: the synthetic
        floor regenerated, or its grid file), a grid file, or an array with its ``lattice``.
        The floor must be the one the plan was made on (its fingerprint), else
        :class:`SeafloorError`."""
        if seafloor is None:
            raw = _shoal.plan_from_json(text)
        elif isinstance(seafloor, (str, os.PathLike)):
            raw = _shoal.plan_from_json(text, os.fspath(seafloor))
        else:
            lat = _lattice(lattice)
            if lat is None:
                raise SeafloorError("a seafloor array needs its lattice")
            raw = _shoal.plan_from_json(text, None, _floor_array(seafloor), lat)
        return cls(raw)

    def __repr__(self) -> str:
        m = self._summary["metrics"]
        return (
            f"<shoal.Plan {self.method}: N = {self.auvs} AUVs, {self.windows} window(s) of "
            f"{self._summary['steps_per_window']} steps of {self.dt:g} s, seed {self.seed}, "
            f"explored {m['explored_area_km2']:.3f} km²>"
        )


def sweep(
    study: Union[str, "os.PathLike[str]", Mapping[str, Any]],
    out: Optional[PathLike] = None,
) -> "pandas.DataFrame":  # noqa: F821
    """Run a study (``shoal sweep``): every combination of its axes, on every core, no
    progress bar.

    Args:
        study: a path to a study TOML file, or a dictionary with the same keys
            (``scenario``, ``method``, ``keep_plans``, ``simulate``, ``set``, ``axes``; see
            docs/sweep.md), e.g. ``{"set": {"horizon.steps": 10}, "axes": {"seed": "1..4",
            "team.auvs": [3, 5]}}``. A dictionary's relative paths resolve against the current
            directory.
        out: the directory for ``runs.csv`` (and, with ``keep_plans``, ``plans/``); ``None``:
            a temporary directory, removed afterwards.

    Returns:
        A ``pandas.DataFrame`` with one row per run, sorted by ``run``: ``run``, a column per
        swept key (but ``seed``, which the row has), then the row's columns (``scenario``,
        ``method``, ``auvs``, ``seed``, ``status`` — ``"passed"``, ``"violated"`` or
        ``"failed"`` —, ``error``, ``wall_s``, the metrics and the check's margins; with
        ``simulate`` the ``sim_*`` columns). Numbers are int64 or float64 (NaN where a run made
        no plan), text columns str (``error`` is ``""`` when there is none).

    Raises:
        ScenarioError: the study is malformed (a run's own bad override fails that run only).
        SweepError: the table cannot be written.

    The GIL is released while the study runs.
    """
    import pandas as pd

    if isinstance(study, Mapping):
        nested, dotted = _split_dotted(study)
        if dotted:
            raise ScenarioError(
                "study dict: dotted keys belong in its \"set\" or \"axes\" tables, not at the "
                f"top: {', '.join(d.split('=')[0] for d in dotted)}"
            )
        kind, text = "json", json.dumps(_jsonable(nested))
        base = os.path.join(os.getcwd(), "study.toml")
    elif isinstance(study, (str, os.PathLike)):
        kind, text, base = "path", os.fspath(study), os.fspath(study)
    else:
        raise ScenarioError(f"study: expected a path or a dictionary, not {type(study).__name__}")

    def run(directory: str) -> "pd.DataFrame":
        table, _, _, _ = _shoal.sweep(kind, text, base, directory)
        # numbers without a value are written "NaN"; an empty text field is "" (no error)
        words = {c: str for c in ("scenario", "method", "status", "error", "sim_status")}
        frame = pd.read_csv(table, keep_default_na=False, na_values=["NaN", "nan"], dtype=words)
        for col in frame.columns:
            if frame[col].dtype == object:
                frame[col] = frame[col].astype(str)
        return frame

    if out is None:
        with tempfile.TemporaryDirectory(prefix="shoal-sweep-") as d:
            return run(d)
    os.makedirs(out, exist_ok=True)
    return run(os.fspath(out))


def default_scenario_toml() -> str:
    """The embedded default scenario as commented TOML (what ``shoal init`` writes)."""
    return _shoal.default_scenario_toml()

