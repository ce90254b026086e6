#!/usr/bin/env python3
"""The anchor issue 22 names, measured on this machine beside shoal's models.

Issue 22 compares shoal's convex models with "trajectory SOCPs of the same size and kind":
the lossless-convexification powered-descent problem of the QOCO benchmark set (Açıkmeşe and
Ploen's rocket landing: 6 states, 3 thrust inputs, log-mass z and slack σ per step; double-
integrator dynamics under gravity; ‖u‖ ≤ σ, a thrust-vector cone, σ between a lower bound
quadratic and an upper bound linear in z, z between two bounds; maximise the final mass).
This script builds it at T steps with cvxpy, as that set does, solves it with Clarabel at its
default settings on one thread (median of REPEATS set-up + solve), and writes it as a Clarabel
JSON problem file (DIR/anchor_T{T}.json), so that `cargo run --release --example model_fill --
FILE ...` counts its factorisation by the same rule as shoal's models
(`cargo run --release --example export_models -- DIR`).

Install (one command): python3 -m pip install -r scripts/other_solvers.txt
Run: python3 scripts/anchor_lcvx.py DIR [T ...]   (default T = 150 420 520; n = 1963, 5473,
6773 variables in cvxpy's form, near P5's 1760 at N = 5 and 6860 at N = 20)
Results: BENCHMARKS.md, "The convex solve against the anchor and other solvers".
"""

import json
import statistics
import sys
import time
from pathlib import Path

import clarabel
import cvxpy as cp
import numpy as np
import scipy.sparse as sp


def powered_descent(steps):
    """The lossless-convexification landing problem at `steps` steps over 20 s (the QOCO
    benchmark set's parameters; its start drawn from a seeded generator)."""
    rng = np.random.default_rng(123)
    dt = 20.0 / (steps - 1)
    x0 = np.array([rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(200, 400), 0, 0, 0])
    g, tvc_max, rho1, rho2 = 9.807, np.deg2rad(45.0), 100.0, 500.0
    m_dry, m_fuel, isp = 25.0, 10.0, 100.0
    m0, alpha = m_dry + m_fuel, 1.0 / (isp * 9.807)
    a = np.eye(6)
    a[0, 3] = a[1, 4] = a[2, 5] = dt
    b = np.vstack([0.5 * dt**2 * np.eye(3), dt * np.eye(3)])
    grav = np.array([0, 0, -0.5 * g * dt**2, 0, 0, -g * dt])
    x = cp.Variable((6, steps + 1))
    z = cp.Variable(steps + 1)
    u = cp.Variable((3, steps + 1))
    s = cp.Variable(steps + 1)
    con = [x[:, 0] == x0, x[:, steps] == 0, z[0] == np.log(m0), z[steps] >= np.log(m_dry)]
    for k in range(steps):
        con += [x[:, k + 1] == a @ x[:, k] + b @ u[:, k] + grav,
                z[k + 1] == z[k] - alpha * s[k] * dt]
    for k in range(steps + 1):
        z0 = np.log(m0 - alpha * rho2 * k * dt)
        mu1, mu2 = rho1 * np.exp(-z0), rho2 * np.exp(-z0)
        con += [
            cp.norm(u[:, k]) <= s[k],
            mu1 * (1 - (z[k] - z0) + 0.5 * (z[k] - z0) ** 2) <= s[k],
            s[k] <= mu2 * (1 - (z[k] - z0)),
            z0 <= z[k],
            z[k] <= np.log(m0 - alpha * rho1 * k * dt),
            u[2, k] >= cp.norm(u[:, k]) * np.cos(tvc_max),
        ]
    return cp.Problem(cp.Minimize(-z[steps]), con)


def clarabel_data(problem):
    """P (upper triangle), q, A, b and the cones as (kind, size), as cvxpy hands them to
    Clarabel."""
    data, _, _ = problem.get_problem_data(cp.CLARABEL)
    a = data["A"].tocsc()
    p = data.get("P")
    p = sp.triu(p).tocsc() if p is not None else sp.csc_matrix((a.shape[1], a.shape[1]))
    dims = data["dims"]
    cones = [("ZeroConeT", dims.zero)] if dims.zero else []
    cones += [("NonnegativeConeT", dims.nonneg)] if dims.nonneg else []
    cones += [("SecondOrderConeT", d) for d in dims.soc]
    return p, np.asarray(data["c"]), a, np.asarray(data["b"]), cones


def save(path, p, q, a, b, cones):
    def csc(m):
        return {"m": m.shape[0], "n": m.shape[1], "colptr": m.indptr.tolist(),
                "rowval": m.indices.tolist(), "nzval": m.data.tolist()}

    path.write_text(json.dumps({"P": csc(p), "q": q.tolist(), "A": csc(a), "b": b.tolist(),
                                "cones": [{k: d} for k, d in cones]}))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    steps = [int(t) for t in sys.argv[2:]] or [150, 420, 520]
    kinds = {"ZeroConeT": clarabel.ZeroConeT, "NonnegativeConeT": clarabel.NonnegativeConeT,
             "SecondOrderConeT": clarabel.SecondOrderConeT}
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.max_threads = 1
    print("T n m iterations status ms ms_per_iteration")
    for t in steps:
        p, q, a, b, cones = clarabel_data(powered_descent(t))
        times = []
        for _ in range(7):
            start = time.perf_counter()
            sol = clarabel.DefaultSolver(p, q, a, b, [kinds[k](d) for k, d in cones],
                                         settings).solve()
            times.append(time.perf_counter() - start)
        ms = 1e3 * statistics.median(times)
        print(t, a.shape[1], a.shape[0], sol.iterations, sol.status, f"{ms:.2f}",
              f"{ms / sol.iterations:.3f}")
        save(root / f"anchor_T{t}.json", p, q, a, b, cones)


if __name__ == "__main__":
    main()
