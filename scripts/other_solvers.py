#!/usr/bin/env python3
"""Other conic solvers on exactly the convex models shoal's SCP solves.

Issue 22 allows another well-kept solver behind shoal's `conic` interface only if it beats
Clarabel on the benchmark. This script measures the candidates on the models that
`cargo bench --bench model` solves, written as Clarabel JSON problem files by
`cargo run --release --example export_models -- DIR`:

- Clarabel itself (the same version as shoal's, from its Python wheel; settings as shoal's,
  read from the file): the reference, with shoal's QDLDL; then with its other LDL backends,
  faer (supernodal or simplicial, faer's choice) and Intel MKL's PARDISO (only where MKL is
  installed: python3 -m pip install mkl, about 250 MB);
- SCS (a first-order ADMM conic solver, at tolerances 1e-4 and 1e-6; cold, and warm-started
  on the second P5 model from the first one's solution, as an SCP would use it);
- QOCO (an interior-point SOCP solver with a quasidefinite KKT system, like Clarabel's).

Install (one command): python3 -m pip install -r scripts/other_solvers.txt
Run: python3 scripts/other_solvers.py DIR [REPEATS]
Prints one line per model and solver: iterations, wall time of set-up and solve in ms (median
of REPEATS, default 5; one thread; SCS can update only b and q between models, so an SCP
would set it up again for every model), status, and the objective's relative difference to
Clarabel's. Not part of the
test run. Results: BENCHMARKS.md, "The convex solve against the anchor and other solvers".
"""

import json
import statistics
import sys
import time
from pathlib import Path

import os
import tempfile

import numpy as np
import qoco
import scipy.sparse as sp
import scs


def find_mkl():
    """Clarabel loads MKL's PARDISO at run time from a file named libmkl_rt.so; the mkl wheel
    installs it as libmkl_rt.so.N. Link it under the plain name, beside MKL's other libraries,
    in a temporary directory named by MKL_PARDISO_PATH, before clarabel is imported. True if
    found."""
    libs = sorted(Path(sys.prefix, "lib").glob("libmkl_rt.so.*"))
    if not libs or "MKL_PARDISO_PATH" in os.environ:
        return bool(libs) or "MKL_PARDISO_PATH" in os.environ
    link_dir = tempfile.mkdtemp(prefix="shoal-mkl-")
    os.symlink(libs[-1], os.path.join(link_dir, "libmkl_rt.so"))
    # libmkl_rt loads MKL's other libraries from its own directory
    for lib in Path(sys.prefix, "lib").glob("lib*.so*"):
        if lib.name.startswith(("libmkl_", "libiomp", "libtbb")):
            os.symlink(lib, os.path.join(link_dir, lib.name))
    os.environ["MKL_PARDISO_PATH"] = link_dir
    os.environ.setdefault("MKL_NUM_THREADS", "1")
    return True


HAVE_MKL = find_mkl()
import clarabel  # noqa: E402  (after MKL_PARDISO_PATH is set)


def load(path):
    """P (upper triangle), q, A, b and the cones of a Clarabel JSON problem file."""
    d = json.loads(Path(path).read_text())

    def csc(m):
        return sp.csc_matrix(
            (m["nzval"], m["rowval"], m["colptr"]), shape=(m["m"], m["n"])
        )

    cones = []
    for c in d["cones"]:
        ((kind, dim),) = c.items()
        cones.append((kind, dim))
    return csc(d["P"]), np.array(d["q"]), csc(d["A"]), np.array(d["b"]), cones


def split_cones(cones):
    """Zero rows, nonnegative rows and second-order cone sizes, in that (shoal's) order."""
    kinds = [k for k, _ in cones]
    order = {"ZeroConeT": 0, "NonnegativeConeT": 1, "SecondOrderConeT": 2}
    assert [order[k] for k in kinds] == sorted(order[k] for k in kinds), "cone order"
    z = sum(d for k, d in cones if k == "ZeroConeT")
    nonneg = sum(d for k, d in cones if k == "NonnegativeConeT")
    soc = [d for k, d in cones if k == "SecondOrderConeT"]
    return z, nonneg, soc


def median_time(solve, repeats):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = solve()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def clarabel_settings(path):
    """The file's settings (shoal's), with shoal's linear solver (QDLDL) on one thread."""
    settings = clarabel.DefaultSettings()
    for key, value in json.loads(Path(path).read_text())["settings"].items():
        setattr(settings, key, value)
    settings.direct_solve_method = "qdldl"
    settings.max_threads = 1
    return settings


def run_clarabel(path, repeats, method="qdldl"):
    """Median wall time of set-up + solve, and the solution (its solve_time excludes the
    set-up, as in shoal's SCP, which keeps the symbolic factorisation between models)."""
    settings = clarabel_settings(path)
    settings.direct_solve_method = method
    return median_time(lambda: clarabel.load_from_file(str(path), settings).solve(), repeats)


def run_scs(P, q, A, b, cones, repeats, eps, warm=None):
    z, nonneg, soc = split_cones(cones)
    data = {"P": sp.triu(P).tocsc(), "A": A, "b": b, "c": q}
    cone = {"z": z, "l": nonneg, "q": soc}

    def solve():
        s = scs.SCS(data, cone, eps_abs=eps, eps_rel=eps, max_iters=100000, verbose=False)
        if warm is None:
            return s.solve()
        return s.solve(warm_start=True, x=warm["x"], y=warm["y"], s=warm["s"])

    return median_time(solve, repeats)


def run_qoco(P, q, A, b, cones, repeats):
    z, nonneg, soc = split_cones(cones)
    n = P.shape[0]
    a_eq, b_eq = A[:z].tocsc(), b[:z]
    g, h = A[z:].tocsc(), b[z:]

    def solve():
        s = qoco.QOCO()
        s.setup(
            n, g.shape[0], z, sp.triu(P).tocsc(), q, a_eq, b_eq, g, h,
            nonneg, len(soc), np.array(soc, dtype=np.int32), verbose=0,
        )
        return s.solve()

    return median_time(solve, repeats)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    print("model solver iterations ms status objective_vs_clarabel")
    for path in sorted(root.glob("*.json")):
        P, q, A, b, cones = load(path)
        t, ref = run_clarabel(path, repeats)
        name = path.stem
        print(name, "clarabel", ref.iterations, f"{1e3 * t:.1f}", ref.status, "0",
              f"(solve alone {1e3 * ref.solve_time:.1f} ms)")

        def rel(obj):
            return f"{(obj - ref.obj_val) / max(abs(ref.obj_val), 1.0):+.1e}"

        for method in ("faer", "mkl"):
            if method == "mkl" and not HAVE_MKL:
                print(name, "clarabel-mkl", "-", "-", "MKL not installed", "-")
                continue
            t, sol = run_clarabel(path, repeats, method)
            print(name, f"clarabel-{method}", sol.iterations, f"{1e3 * t:.1f}", sol.status,
                  rel(sol.obj_val))

        for eps in (1e-4, 1e-6):
            t, sol = run_scs(P, q, A, b, cones, repeats, eps)
            print(name, f"scs-{eps:.0e}", sol["info"]["iter"], f"{1e3 * t:.1f}",
                  sol["info"]["status"], rel(sol["info"]["pobj"]))
            if name.endswith("_b"):
                first = path.with_name(name[:-2] + "_a.json")
                s0 = clarabel.load_from_file(str(first), clarabel_settings(first)).solve()
                warm = {"x": np.array(s0.x), "y": np.array(s0.z), "s": np.array(s0.s)}
                t, sol = run_scs(P, q, A, b, cones, repeats, eps, warm)
                print(name, f"scs-{eps:.0e}-warm", sol["info"]["iter"], f"{1e3 * t:.1f}",
                      sol["info"]["status"], rel(sol["info"]["pobj"]))
        t, sol = run_qoco(P, q, A, b, cones, repeats)
        print(name, "qoco", sol.iters, f"{1e3 * t:.1f}", sol.status, rel(sol.obj))


if __name__ == "__main__":
    main()
