#!/usr/bin/env python3
"""How much a convex model of the SCP would gain if it held only the rows that can bind.

Issue 22 asks for rows "only where a constraint can be active": screen them by the
reference's margin, verify every row after the solve, add the violated ones and re-solve.
This script bounds that lever on the models `cargo run --release --example export_models --
DIR` writes (the same models as `cargo bench --bench model`), with Clarabel at shoal's
settings (QDLDL, one thread), for each pair `p5_N{n}_a.json`, `p5_N{n}_b.json` (two models
of one SCP in a row; b is linearised about a's solution):

- ideal: model a with only the rows active at its own optimum (a nonnegative row or a
  second-order cone whose slack, in the solver's units, is below 1): a screen that knew the
  answer before the solve. A lower bound on what any screen can reach.
- screened: model b with its second-order cones and the nonnegative rows whose margin at its
  reference (a's solution) is below THRESHOLD; then every row of b is checked at the solution,
  the violated ones added, and the model solved again until none is violated: the scheme the
  issue describes, as an SCP would run it (Clarabel cannot warm-start, so every round is a new
  set-up and a cold solve).

Install (one command): python3 -m pip install -r scripts/other_solvers.txt
Run: python3 scripts/screen_rows.py DIR [THRESHOLD ...]   (default thresholds 1 3 10 30)
Results: docs/design-decisions.md, "Probes not kept".
"""

import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from other_solvers import clarabel, clarabel_settings, load

CONES = {
    "ZeroConeT": clarabel.ZeroConeT,
    "NonnegativeConeT": clarabel.NonnegativeConeT,
    "SecondOrderConeT": clarabel.SecondOrderConeT,
}


def solve(P, q, A, b, cones, settings):
    """Clarabel on (P, q, A, b, cones): the solution and the wall time of set-up + solve."""
    t = time.perf_counter()
    sol = clarabel.DefaultSolver(P, q, A, b, [CONES[c](d) for c, d in cones], settings).solve()
    return sol, time.perf_counter() - t


def margins(A, b, cones, x):
    """Per cone: (first row, size, kind, margin): the slacks b − Ax of a nonnegative cone, the
    distance s0 − ‖s1‖ of a second-order cone to its boundary, none for a zero cone."""
    s = b - A @ x
    out, r = [], 0
    for kind, d in cones:
        seg = s[r:r + d]
        if kind == "NonnegativeConeT":
            m = seg
        elif kind == "SecondOrderConeT":
            m = np.array([seg[0] - np.linalg.norm(seg[1:])])
        else:
            m = np.full(1, -np.inf)
        out.append((r, d, kind, m))
        r += d
    return out


def restrict(A, b, marg, keep):
    """The rows of (A, b) that `keep` (per cone, a mask over its margins) selects, and their
    cones."""
    rows, cones = [], []
    for (r, d, kind, _), k in zip(marg, keep):
        idx = np.arange(r, r + d)[k] if kind == "NonnegativeConeT" else np.arange(r, r + d)
        if kind != "NonnegativeConeT" and not k.all():
            continue
        if len(idx):
            rows.append(idx)
            cones.append((kind, len(idx)))
    rows = np.concatenate(rows)
    return A[rows].tocsc(), b[rows], cones


def ideal(path, settings):
    P, q, A, b, cones = load(path)
    P = sp.triu(P).tocsc()
    full, t_full = solve(P, q, A, b, cones, settings)
    marg = margins(A, b, cones, np.array(full.x))
    keep = [m < 1.0 for (_, _, _, m) in marg]
    A2, b2, c2 = restrict(A, b, marg, keep)
    sol, t = solve(P, q, A2, b2, c2, settings)
    print(f"{path.stem} ideal: rows {A2.shape[0]} of {A.shape[0]}, "
          f"{full.iterations} -> {sol.iterations} iterations, "
          f"{1e3 * t_full:.1f} -> {1e3 * t:.1f} ms, objective {rel(sol.obj_val, full.obj_val)}")


def screened(first, second, settings, threshold):
    Pa, qa, Aa, ba, ca = load(first)
    P, q, A, b, cones = load(second)
    ref, _ = solve(sp.triu(Pa).tocsc(), qa, Aa, ba, ca, settings)
    P = sp.triu(P).tocsc()
    full, t_full = solve(P, q, A, b, cones, settings)
    marg = margins(A, b, cones, np.array(ref.x))
    keep = [m < threshold if kind == "NonnegativeConeT" else np.ones(1, bool)
            for (_, _, kind, m) in marg]
    rounds, total = [], 0.0
    while True:
        A2, b2, c2 = restrict(A, b, marg, keep)
        sol, t = solve(P, q, A2, b2, c2, settings)
        total += t
        rounds.append(f"{sol.iterations} ({sol.status})")
        added = 0
        for i, (_, _, kind, m) in enumerate(margins(A, b, cones, np.array(sol.x))):
            if kind == "NonnegativeConeT":
                grown = keep[i] | (m < -1e-6)
                added += int((grown & ~keep[i]).sum())
                keep[i] = grown
        if added == 0 or len(rounds) == 10:
            break
    print(f"{second.stem} screened at {threshold:g}: rows {A2.shape[0]} of {A.shape[0]}, "
          f"{len(rounds)} rounds [{', '.join(rounds)}], {1e3 * t_full:.1f} -> "
          f"{1e3 * total:.1f} ms, objective {rel(sol.obj_val, full.obj_val)}")


def rel(obj, ref):
    return f"{(obj - ref) / max(abs(ref), 1.0):+.1e} relative"


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    thresholds = [float(t) for t in sys.argv[2:]] or [1.0, 3.0, 10.0, 30.0]
    for first in sorted(root.glob("p5_*_a.json")):
        second = first.with_name(first.stem[:-2] + "_b.json")
        settings = clarabel_settings(first)
        ideal(first, settings)
        for threshold in thresholds:
            screened(first, second, settings, threshold)


if __name__ == "__main__":
    main()
