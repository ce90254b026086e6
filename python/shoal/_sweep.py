"""Studies: :func:`sweep` runs one (``shoal sweep``) into a ``pandas.DataFrame``."""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Mapping, Optional, Union

from . import _shoal
from ._errors import ScenarioError
from ._inputs import PathLike, jsonable, split_dotted


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
        nested, dotted = split_dotted(study)
        if dotted:
            raise ScenarioError(
                "study dict: dotted keys belong in its \"set\" or \"axes\" tables, not at the "
                f"top: {', '.join(d.split('=')[0] for d in dotted)}"
            )
        kind, text = "json", json.dumps(jsonable(nested))
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
