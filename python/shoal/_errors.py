"""The exceptions and warnings of shoal: the error classes of the compiled module (every one a
:class:`ShoalError`), :class:`CheckFailed` and :class:`ShoalWarning`."""

from __future__ import annotations

from ._check import CheckReport

# The classes the compiled module defines (their __module__ is "shoal"), here with the rest.
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


class CheckFailed(ShoalError):
    """``Plan.check(strict=True)`` found a constraint family violated; ``report`` holds the
    :class:`CheckReport` and the message its table."""

    def __init__(self, report: "CheckReport") -> None:
        super().__init__(report.table)
        self.report = report


class ShoalWarning(UserWarning):
    """What the seafloor's loader warns of (a likely sign-convention mistake, an assumed
    datum), as ``shoal plan`` prints it."""


__all__ = [
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
