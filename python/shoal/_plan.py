"""Plans: :func:`plan` makes one from a scenario, :class:`Plan` holds it (its arrays, metrics,
the check, the plan file's text)."""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _shoal
from ._check import CheckReport, report_of
from ._errors import CheckFailed, ScenarioError, SeafloorError, ShoalWarning
from ._inputs import (
    LatticeLike,
    PathLike,
    floor_array,
    jsonable,
    lattice_tuple,
    override_list,
    split_dotted,
)


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
    extra = override_list(overrides)
    if seed is not None:
        extra.append(f"seed={int(seed)}")
    z = lat = None
    if seafloor is not None:
        if isinstance(seafloor, (str, os.PathLike)):
            extra.append(f"seafloor.file={json.dumps(os.path.abspath(os.fspath(seafloor)))}")
        else:
            z = floor_array(seafloor)
            lat = lattice_tuple(lattice)
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
        nested, dotted = split_dotted(scenario)
        kind, text = "json", json.dumps(jsonable(nested))
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
        report = report_of(self._raw.check())
        if strict and not report.passed:
            raise CheckFailed(report)
        return report

    def to_json(self) -> str:
        """The plan file's text: what ``shoal plan`` writes to plan.json (format
        ``shoal-plan/5``, docs/plan-format.md)."""
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
            lat = lattice_tuple(lattice)
            if lat is None:
                raise SeafloorError("a seafloor array needs its lattice")
            raw = _shoal.plan_from_json(text, None, floor_array(seafloor), lat)
        return cls(raw)

    def __repr__(self) -> str:
        m = self._summary["metrics"]
        return (
            f"<shoal.Plan {self.method}: N = {self.auvs} AUVs, {self.windows} window(s) of "
            f"{self._summary['steps_per_window']} steps of {self.dt:g} s, seed {self.seed}, "
            f"explored {m['explored_area_km2']:.3f} km²>"
        )
