"""What a caller gives, as the compiled module takes it: lattices of seafloor arrays, the
arrays, scenario and study dictionaries (as JSON) and ``key=value`` overrides; and the default
scenario to start one from."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _shoal
from ._errors import ScenarioError, SeafloorError

PathLike = Union[str, "os.PathLike[str]"]


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


def lattice_tuple(lattice: Optional[LatticeLike]) -> Optional[Tuple[float, float, float, float]]:
    """``lattice`` as ``(x0, y0, dx, dy)``; ``None`` when not given."""
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


def floor_array(z: Any) -> np.ndarray:
    """A seafloor array as the compiled module takes it: 2-D, float64, C-contiguous."""
    a = np.ascontiguousarray(z, dtype=np.float64)
    if a.ndim != 2:
        raise SeafloorError(
            f"the seafloor array must be 2-D (rows along y, columns along x), not {a.ndim}-D "
            f"of shape {a.shape}"
        )
    return a


def toml_value(value: Any) -> str:
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
        inner = ", ".join(f"{json.dumps(str(k))} = {toml_value(v)}" for k, v in value.items())
        return "{" + inner + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise ScenarioError(f"cannot write {value!r} ({type(value).__name__}) as a scenario value")


def jsonable(value: Any) -> Any:
    """``value`` with its mappings, sequences, numpy values and paths as JSON takes them."""
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def split_dotted(d: Mapping[str, Any]) -> Tuple[Dict[str, Any], List[str]]:
    """A dictionary's nested keys, and its dotted ones ("team.auvs": 3) as overrides."""
    nested: Dict[str, Any] = {}
    dotted: List[str] = []
    for k, v in d.items():
        if "." in str(k):
            if v is not None:
                dotted.append(f"{k}={toml_value(v)}")
        else:
            nested[str(k)] = v
    return nested, dotted


def override_list(overrides: Union[None, Mapping[str, Any], Sequence[str]]) -> List[str]:
    """Overrides (a mapping or ``key=value`` strings) as a list of ``key=value`` strings."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{k}={toml_value(v)}" for k, v in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    return [str(o) for o in overrides]


def default_scenario_toml() -> str:
    """The embedded default scenario as commented TOML (what ``shoal init`` writes)."""
    return _shoal.default_scenario_toml()
