"""What the library's independent checker found: :class:`CheckReport` and its
:class:`Family` rows, read from the JSON the compiled module gives."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import List, Tuple, Union


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


def report_of(raw: Tuple[str, str]) -> CheckReport:
    """The report of ``RawPlan.check()``: its JSON and its text table."""
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
