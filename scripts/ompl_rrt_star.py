#!/usr/bin/env python3
"""Reference sampling planner beside shoal's MPC: RRT* from OMPL, through OMPL's own Python
bindings, for the AUVs of a shoal plan. A benchmark baseline only, in no default test run.
Paper: "Integrated Localization and Path Planning for an Ocean Exploring Team of AUVs with Consensus
Graph Model Predictive Control", arXiv 2505.07484: its Fig. 6 sets an RRT-like sampling planner
beside the MPC; the issue asks for "a stronger reference: RRT* from OMPL".

Install: python3 -m pip install -r scripts/ompl-requirements.txt     (ompl 2.0.1, numpy)
Run: python3 scripts/ompl_rrt_star.py PLAN.json --floor FLOOR.asc -o WAYPOINTS.json [--time S]
         [--iterations I] [--seed S] [--planner rrtstar|informedrrtstar]    (--help: all options)
PLAN.json: DIR/plan.json of `shoal plan -o DIR`. FLOOR.asc: its floor, `shoal seafloor export -o
FLOOR.asc` with the plan's --set overrides (it depends on `seed`; checked against plan.seafloor).
Output: shoal-waypoints/1 for `shoal plan --waypoints`, written atomically; exit status 2 and no
file when no path reaches the goal.

Window 0 only. The USV is not planned: it follows the MPC plan's track windows[0].final.usv.position
(linear in time between its K + 1 points), and the N AUVs are planned against that same track.
Modelling choices ([option default]):
* State: RealVectorStateSpace(3N + 1): per AUV (x − x_usv(t), y − y_usv(t), z), then c·t, t in
  [0, Kδ] [--time-scale c 0.1 m/s]. Offsets from the USV, so that OMPL's uniform sampling (Python
  cannot set a sampler) draws formations around it; c < 1 makes nearest neighbours alike in
  formation rather than in time, since an extension is feasible only when the offsets change slowly
  (the USV cruises at 1.5 m/s, the AUVs' cap is 1.7). Bounds: each AUV within [--box 150 m] of its
  start offset and ±d_max; z from the lowest floor node under that box along the track +
  floor_clearance to −surface_clearance.
* Motion s1 → s2: offsets, z and t linear: straight in x, y, z between step times, bent where the
  USV track bends. Valid (MotionValidator) when t2 > t1 and, on each piece between the step times it
  crosses: every AUV's average speed ≤ [--speed-factor 0.85]·max_speed (with the ZOH model
  V[k+1] ≈ −0.07·V[k] + 1.07·ΔP/δ the implied velocities then stay under max_speed); z ≤
  −surface_clearance and distance to (P_usv(t), 0) ≤ d_max at the piece ends (both convex); inside
  the grid; z − Z ≥ floor_clearance + [--floor-margin 1 m] at the samples of 𝓛_r (n = max(1,
  ⌈horizontal length / r⌉), r = min(resolution, 5 m), as `shoal check`); at each step time kδ in
  (t1, t2] the interpolated team holds the chain: the AUV nearest the USV (z = 0) within d_s in line
  of sight, and a Hamiltonian path through the AUVs with every link within d_s in line of sight
  (all N! orders, N ≤ 8). The margin covers the chords between waypoints, which cut corners.
* Goal (GoalSampleableRegion): t ≥ Kδ − [--goal-time-tol 5 s], every AUV within d_s −
  [--goal-margin 1 m] of (P_usv[K], 0). Samples: the start offsets ±20 m, 6-8 m above the floor,
  shrunk into that ball, at Kδ. A path ending before Kδ is held (offsets kept) to Kδ, validated.
* Cost (OptimizationObjective, per motion, summed over its pieces): (w1·E + w2·H)/N as shoal's P2
  objective (of1_2 = "height", per-AUV scaling). E: the steady-state part of Σ‖U‖² (holding V
  takes U_i = g_i·V_i, g_i = (1 − vv_i)/vu_i): a piece of duration h moving ΔP costs
  Σ_n Σ_i (g_i·ΔP_i/h)²·h/δ; accelerations at path vertices are not priced. H: Σ_n mean height
  above the floor at the piece's ends ·h/δ. The heading rate (constraint 2) is only evaluated.
  InformedRRTstar gets no cost-to-go heuristic (the bindings cannot set one): its informed
  sampling rejects nothing.
* Then og.PathSimplifier reduceVertices + partialShortcutPath (200 steps each), kept if every
  motion stays valid and the cost does not rise [--no-simplify]; waypoints at t = kδ (k = 0 exactly
  the plan's start); the model's implied velocities and inputs; constraints 1-6 of `shoal check`
  printed with their worst margins (nothing repaired); objective terms beside the MPC plan's.
* ompl.util.RNG.setSeed(seed) precedes every OMPL object; RRT* is single-threaded. With
  [--iterations I] the run stops after I iterations and repeats exactly; on the clock alone
  (--time) the result depends on how many iterations fit.
* samples_drawn = RRT* iterations (numIterations: one sample each); samples_kept = tree vertices.
OMPL 2.x's bindings are nanobind: the Python subclasses of MotionValidator, OptimizationObjective
and GoalSampleableRegion here are trampolines; os._exit at the end skips nanobind's leak report of
their reference cycles.
"""

import argparse, itertools, json, math, os, sys, tempfile, time
from importlib.metadata import version

import numpy as np
from ompl import base as ob, geometric as og, util as ou

HEADER_KEYS = {"ncols", "nrows", "xllcorner", "xllcenter", "yllcorner", "yllcenter", "cellsize",
               "dx", "dy", "nodata_value"}


class Floor:
    """shoal's floor (src/seafloor/esri_ascii.rs, field.rs): nodes (x0 + i·dx, y0 + j·dy), a
    header corner being the south-west cell's outer corner (node = corner + cellsize/2), rows
    north to south in the file; Z bilinear in the cell holding (x, y), coordinates within 1e-9
    cells of a node line snapped onto it; a cell touching a NODATA or land node is an obstacle."""

    def __init__(self, path):
        tokens, head = open(path, encoding="utf-8-sig").read().split(), {}
        while tokens[0].lower() in HEADER_KEYS:
            head[tokens[0].lower()], tokens = tokens[1], tokens[2:]
        self.nx, self.ny = int(head["ncols"]), int(head["nrows"])
        self.dx = float(head.get("dx", head.get("cellsize")))
        self.dy = float(head.get("dy", head.get("cellsize")))
        corner = lambda axis, d: float(head[axis + "corner"]) + d / 2
        self.x0 = float(head["xllcenter"]) if "xllcenter" in head else corner("xll", self.dx)
        self.y0 = float(head["yllcenter"]) if "yllcenter" in head else corner("yll", self.dy)
        z = np.array(tokens[:self.nx * self.ny], float).reshape(self.ny, self.nx)[::-1]
        bad = (z >= 0) | ~np.isfinite(z) | (z == float(head.get("nodata_value", "nan")))
        self.blocked = bad[:-1, :-1] | bad[1:, :-1] | bad[:-1, 1:] | bad[1:, 1:]
        self.z = np.where(bad, np.nan, z)
        self.x1, self.y1 = self.x0 + (self.nx - 1) * self.dx, self.y0 + (self.ny - 1) * self.dy

    @staticmethod
    def cell(u, n):
        r = np.round(u)
        u = np.where(np.abs(u - r) <= 1e-9, r, u)
        i = np.minimum(np.floor(np.maximum(u, 0.0)), n - 2).astype(int)
        return i, np.clip(u - i, 0.0, 1.0)

    def elevation(self, xs, ys):
        """Z at points inside the grid (NaN over an obstacle cell)."""
        i, t = self.cell((np.asarray(xs) - self.x0) / self.dx, self.nx)
        j, s = self.cell((np.asarray(ys) - self.y0) / self.dy, self.ny)
        z = self.z
        south = (1 - t) * z[j, i] + t * z[j, i + 1]
        north = (1 - t) * z[j + 1, i] + t * z[j + 1, i + 1]
        return np.where(self.blocked[j, i], np.nan, (1 - s) * south + s * north)

    def segment_clearance(self, a, b, r):
        """Least z − Z over the samples of 𝓛_r of each segment a[m] → b[m], ends included; −inf
        for every segment when one has an end off the grid, and over an obstacle."""
        a, b = np.atleast_2d(a), np.atleast_2d(b)
        ends = np.vstack([a, b])
        if not np.all((ends[:, 0] >= self.x0) & (ends[:, 0] <= self.x1)
                      & (ends[:, 1] >= self.y0) & (ends[:, 1] <= self.y1)):
            return np.full(len(a), -np.inf)
        n = np.maximum(1, np.ceil(np.hypot(*(b - a)[:, :2].T) / r)).astype(int)
        seg, first = np.repeat(np.arange(len(a)), n + 1), np.cumsum(n + 1) - (n + 1)
        f = (np.arange(seg.size) - first[seg]) / n[seg]
        p = a[seg] + f[:, None] * (b - a)[seg]
        p = np.clip(p, np.minimum(a, b)[seg], np.maximum(a, b)[seg])
        c = p[:, 2] - self.elevation(p[:, 0], p[:, 1])
        return np.minimum.reduceat(np.nan_to_num(c, nan=-np.inf), first)


class Problem:
    """The fields of a shoal plan the planner uses (docs/plan-format.md), and the chain test."""

    def __init__(self, plan, floor, args):
        s, m = plan["scenario"], plan["model"]["auv"]
        auv, ac = s["auv"], s["acoustic"]
        self.floor, self.K, self.dt = floor, s["horizon"]["steps"], s["horizon"]["dt"]
        self.N, self.T = s["team"]["auvs"], self.K * self.dt
        self.vmax, self.v_heading = auv["max_speed"], auv["min_heading_speed"]
        self.turn_max = auv["max_heading_rate"] * self.dt
        self.clear, self.surface = auv["floor_clearance"], auv["surface_clearance"]
        self.d_s, self.d_max = ac["sonar_range"], ac["max_range"]
        self.r = min(ac["resolution"], 5.0)  # as `shoal check`
        self.w1, self.w2 = s["weights"]["w1"], s["weights"]["w2"]
        self.pv, self.pu, self.vv, self.vu = (np.array(m[k], float) for k in "pv pu vv vu".split())
        self.gain = (1 - self.vv) / self.vu  # steady-state input per unit velocity
        self.cap, self.margin = args.speed_factor * self.vmax, args.floor_margin
        self.c = args.time_scale
        self.usv = np.array(plan["windows"][0]["final"]["usv"]["position"], float)
        self.p0 = np.array([a["position"] for a in plan["initial"]["auvs"]], float)
        self.v0 = np.array([a["velocity"] for a in plan["initial"]["auvs"]], float)
        self.start = self.p0 - np.append(self.usv[0], 0.0)  # start offsets
        self.orders = np.array(list(itertools.permutations(range(self.N))))
        if len(self.usv) != self.K + 1 or len(self.p0) != self.N or self.N > 8:
            raise SystemExit("plan.json: needs K + 1 USV positions and N ≤ 8 initial AUVs")

    def usv_at(self, t):
        k = min(int(t // self.dt), self.K - 1)
        f = (t - k * self.dt) / self.dt
        return (1 - f) * self.usv[k] + f * self.usv[k + 1]

    def absolute(self, t, offsets):
        p = offsets.copy()
        p[:, :2] += self.usv_at(t)
        return p

    def chain_margin(self, team, k, early=False):
        """(d_s − distance from the USV at step k (z = 0) to the nearest AUV, d_s − longest link
        of the best Hamiltonian path through the AUVs), m; a link in range without line of sight
        counts as infinitely long. With early: (−1, −1) as soon as the lengths alone fail."""
        usv = np.array([*self.usv[k], 0.0])
        to_usv = np.linalg.norm(team - usv, axis=1)
        near = int(np.argmin(to_usv))
        d = np.linalg.norm(team[:, None] - team[None], axis=2)
        if early and (to_usv[near] > self.d_s or bottleneck(d, self.orders) > self.d_s):
            return -1.0, -1.0
        i, j = np.triu_indices(self.N, 1)
        i, j = i[d[i, j] <= self.d_s], j[d[i, j] <= self.d_s]
        a, b = np.vstack([usv, team[i]]), np.vstack([team[near], team[j]])
        blocked = self.floor.segment_clearance(a, b, self.r) < -1e-6
        d[i[blocked[1:]], j[blocked[1:]]] = d[j[blocked[1:]], i[blocked[1:]]] = np.inf
        a2u = -np.inf if blocked[0] and to_usv[near] <= self.d_s else self.d_s - to_usv[near]
        return a2u, self.d_s - bottleneck(d, self.orders)


def bottleneck(d, orders):
    """Least, over the orders (Hamiltonian paths), of the longest link in d."""
    return d[orders[:, :-1], orders[:, 1:]].max(axis=1, initial=0.0).min()


def unpack(p, state):
    """(t, (N, 3) offsets) of an OMPL state."""
    v = state[0:3 * p.N + 1]
    return v[-1] / p.c, np.array(v[:-1]).reshape(p.N, 3)


def make_state(si, p, t, offsets):
    s = si.allocState()
    s[0:3 * p.N + 1] = [*np.asarray(offsets).ravel(), t * p.c]
    return s


def motion(p, s1, s2):
    """The motion s1 → s2 cut at the step times it crosses: times (M + 1), offsets and absolute
    positions (M + 1, N, 3), and [(index, k)] of the step times kδ in (t1, t2] among them."""
    (ta, oa), (tb, ob_) = unpack(p, s1), unpack(p, s2)
    inner = [k for k in range(1, p.K) if ta < k * p.dt < tb]
    ts = np.array([ta] + [k * p.dt for k in inner] + [tb])
    steps = [(i + 1, k) for i, k in enumerate(inner)]
    if tb > ta and abs(tb - round(tb / p.dt) * p.dt) <= 1e-9 * p.dt:
        steps.append((len(ts) - 1, round(tb / p.dt)))
    f = ((ts - ta) / (tb - ta) if tb != ta else np.zeros(len(ts)))[:, None, None]
    offs = (1 - f) * oa + f * ob_
    pos = offs.copy()
    pos[:, :, :2] += np.array([p.usv_at(t) for t in ts])[:, None]
    return ts, offs, pos, steps


class TeamMotion(ob.MotionValidator):
    """Validity of a motion (module docs); counts why motions are refused."""

    def __init__(self, si, p):
        super().__init__(si)
        self.p, self.refused = p, {}

    def refuse(self, why):
        self.refused[why] = self.refused.get(why, 0) + 1
        return False

    def checkMotion(self, s1, s2):
        p = self.p
        if s2[3 * p.N] <= s1[3 * p.N]:
            return self.refuse("time not increasing")
        ts, offs, pos, steps = motion(p, s1, s2)
        if np.any(np.linalg.norm(np.diff(pos, axis=0), axis=2).max(axis=1) > p.cap * np.diff(ts)):
            return self.refuse("speed")
        if np.max(offs[:, :, 2]) > -p.surface:
            return self.refuse("surface")
        if np.max(np.linalg.norm(offs, axis=2)) > p.d_max:
            return self.refuse("range")
        low = p.floor.segment_clearance(pos[:-1].reshape(-1, 3), pos[1:].reshape(-1, 3), p.r)
        if np.min(low) < p.clear + p.margin:
            return self.refuse("floor")
        if not all(min(p.chain_margin(pos[i], k, early=True)) >= 0 for i, k in steps):
            return self.refuse("chain")
        return True


def state_valid(p, s):
    """One state: inside the grid, below the surface, above the floor, within d_max."""
    t, o = unpack(p, s)
    x = p.absolute(t, o)
    return bool(np.max(o[:, 2]) <= -p.surface and np.max(np.linalg.norm(o, axis=1)) <= p.d_max
                and np.min(p.floor.segment_clearance(x, x, p.r)) >= p.clear)


class TeamCost(ob.OptimizationObjective):
    """(w1·E + w2·H)/N of a motion (module docs), in either order of its states."""

    def __init__(self, si, p):
        super().__init__(si)
        self.p = p

    def stateCost(self, s):
        return ob.Cost(0.0)

    def motionCost(self, s1, s2):
        p = self.p
        ts, _, pos, _ = motion(p, s1, s2) if s1[3 * p.N] <= s2[3 * p.N] else motion(p, s2, s1)
        if ts[-1] <= ts[0]:
            return ob.Cost(math.inf)
        h = np.diff(ts)
        energy = np.sum(p.gain ** 2 * np.diff(pos, axis=0) ** 2 / (h[:, None, None] * p.dt))
        up = pos[:, :, 2] - p.floor.elevation(pos[:, :, 0], pos[:, :, 1])
        height = np.sum((up[:-1] + up[1:]) / 2 * h[:, None]) / p.dt
        total = (p.w1 * energy + p.w2 * height) / p.N
        return ob.Cost(float(total) if np.isfinite(total) else math.inf)


class TeamGoal(ob.GoalSampleableRegion):
    """t ≥ Kδ − tol and every AUV within d_s − margin of (P_usv[K], 0)."""

    def __init__(self, si, p, args):
        super().__init__(si)
        self.p, self.tol, self.rng = p, args.goal_time_tol, ou.RNG()
        self.radius = p.d_s - args.goal_margin

    def distanceGoal(self, s):
        t, o = unpack(self.p, s)
        beyond = float(np.max(np.linalg.norm(o, axis=1))) - self.radius
        return max(self.p.T - self.tol - t, beyond, 0.0)

    def sampleGoal(self, s):
        p, o, rng = self.p, self.p.start.copy(), self.rng
        o[:, :2] += [[rng.uniformReal(-20, 20), rng.uniformReal(-20, 20)] for _ in o]
        for _ in range(2):  # near the floor, then shrunk into the ball
            x = p.absolute(p.T, o)
            z = p.floor.elevation(x[:, 0], x[:, 1]) + p.clear + p.margin + rng.uniformReal(0, 2)
            o[:, 2] = np.clip(z, -0.8 * self.radius, -p.surface)
            room = 0.95 * np.sqrt(self.radius ** 2 - o[:, 2] ** 2)
            o[:, :2] *= min(1.0, float(np.min(room / np.linalg.norm(o[:, :2], axis=1))))
        s[0:3 * p.N + 1] = [*o.ravel(), p.T * p.c]

    def maxSampleCount(self):
        return 1 << 30


def state_space(p, box):
    """RealVectorStateSpace(3N + 1) with the bounds of the module docs."""
    lo = np.maximum(p.start[:, :2] - box, -p.d_max)
    hi = np.minimum(p.start[:, :2] + box, p.d_max)
    f = p.floor
    i0, j0 = ((p.usv.min(axis=0) + lo.min(axis=0) - [f.x0, f.y0]) // [f.dx, f.dy]).astype(int)
    i1, j1 = ((p.usv.max(axis=0) + hi.max(axis=0) - [f.x0, f.y0]) // [f.dx, f.dy]).astype(int)
    z_low = min(np.nanmin(f.z[max(0, j0):j1 + 2, max(0, i0):i1 + 2]) + p.clear, p.p0[:, 2].min())
    bounds = ob.RealVectorBounds(3 * p.N + 1)
    for n in range(p.N):
        for d, (low, high) in enumerate([(lo[n, 0], hi[n, 0]), (lo[n, 1], hi[n, 1]),
                                         (z_low, -p.surface)]):
            bounds.setLow(3 * n + d, low)
            bounds.setHigh(3 * n + d, high)
    bounds.setLow(3 * p.N, 0.0)
    bounds.setHigh(3 * p.N, p.T * p.c)
    space = ob.RealVectorStateSpace(3 * p.N + 1)
    space.setBounds(bounds)
    return space


def plan_team(p, args):
    """Solve with OMPL: ([(t, offsets)] from t = 0 to Kδ, or None; what happened)."""
    si = ob.SpaceInformation(state_space(p, args.box))
    si.setStateValidityChecker(lambda s: state_valid(p, s))
    validator = TeamMotion(si, p)
    si.setMotionValidator(validator)
    si.setup()
    pdef = ob.ProblemDefinition(si)
    pdef.addStartState(make_state(si, p, 0.0, p.start))
    goal, cost = TeamGoal(si, p, args), TeamCost(si, p)
    goal.setThreshold(1e-9)
    pdef.setGoal(goal)
    pdef.setOptimizationObjective(cost)
    informed = args.planner == "informedrrtstar"
    planner = og.InformedRRTstar(si) if informed else og.RRTstar(si)
    planner.setProblemDefinition(pdef)
    planner.setRange(args.range)
    planner.setGoalBias(args.goal_bias)
    planner.setup()
    began = time.perf_counter()
    done = lambda: time.perf_counter() - began > args.time or (
        args.iterations is not None and planner.numIterations() >= args.iterations)
    status = planner.solve(ob.PlannerTerminationCondition(done))
    data = ob.PlannerData(si)
    planner.getPlannerData(data)
    times = [unpack(p, data.getVertex(i).getState())[0] for i in range(data.numVertices())]
    info = {"status": status.asString(), "drawn": planner.numIterations(), "kept": len(times),
            "refused": dict(validator.refused), "solve_s": time.perf_counter() - began,
            "latest": max(times)}
    if not pdef.hasExactSolution():
        if pdef.hasApproximateSolution():
            info["status"] += " only, %.1f from the goal" % pdef.getSolutionDifference()
        return None, info
    path = pdef.getSolutionPath()
    info["raw_cost"] = info["cost"] = path.cost(cost).value()
    if not args.no_simplify:
        simpler = og.PathGeometric(path)
        simplifier = og.PathSimplifier(si, goal, cost)
        simplifier.reduceVertices(simpler, 200)
        simplifier.partialShortcutPath(simpler, 200)
        states = simpler.getStates()
        valid = all(validator.checkMotion(a, b) for a, b in zip(states, states[1:]))
        if valid and simpler.cost(cost).value() <= info["cost"]:
            path, info["cost"] = simpler, simpler.cost(cost).value()
    states = [unpack(p, s) for s in path.getStates()]
    if states[-1][0] < p.T:  # hold the offsets to Kδ
        last, end = make_state(si, p, *states[-1]), make_state(si, p, p.T, states[-1][1])
        if not validator.checkMotion(last, end):
            info["status"] = "the path ends at t = %.3f s, cannot be held to Kδ" % states[-1][0]
            return None, info
        info["cost"] += cost.motionCost(last, end).value()
        states.append((p.T, states[-1][1]))
    info["plan_s"] = time.perf_counter() - began
    return states, info


def waypoints(p, path):
    """(K + 1, N, 3) positions at t = kδ along the path [(t, offsets)]; k = 0 the plan's start."""
    ts, out = np.array([t for t, _ in path]), [p.p0.copy()]
    for k in range(1, p.K + 1):
        m = min(int(np.searchsorted(ts, k * p.dt)), len(ts) - 1)
        (ta, oa), (tb, ob_) = path[m - 1], path[m]
        f = (k * p.dt - ta) / (tb - ta)
        out.append(p.absolute(k * p.dt, (1 - f) * oa + f * ob_))
    return np.array(out)


def implied_motion(p, P):
    """Velocities (K + 1, N, 3) and inputs (K, N, 3) that the model gives for the waypoints."""
    V, U = [p.v0], []
    for k in range(p.K):
        U.append((P[k + 1] - P[k] - p.pv * V[k]) / p.pu)
        V.append(p.vv * V[k] + p.vu * U[k])
    return np.array(V), np.array(U)


def evaluate(p, P):
    """Worst margin of constraints 1-6 over k = 1..K (≥ 0 holds), Σ‖U‖² and Σ heights."""
    V, U = implied_motion(p, P)
    speed = np.hypot(V[:, :, 0], V[:, :, 1])
    turn = np.diff(np.arctan2(V[:, :, 1], V[:, :, 0]), axis=0)
    turn = np.abs((turn + np.pi) % (2 * np.pi) - np.pi)
    turn = turn[(speed[:-1] >= p.v_heading) & (speed[1:] >= p.v_heading)]
    to_usv = np.linalg.norm(P - np.c_[p.usv, np.zeros(p.K + 1)][:, None], axis=2)
    chain = np.array([p.chain_margin(P[k], k) for k in range(1, p.K + 1)])
    floor = p.floor.segment_clearance(P[:-1].reshape(-1, 3), P[1:].reshape(-1, 3), p.r)
    margins = {
        "1 speed ≤ max_speed (m/s)": p.vmax - np.max(np.linalg.norm(V[1:], axis=2)),
        "2 heading turn ≤ max_heading_rate·δ (rad)": p.turn_max - np.max(turn, initial=0.0),
        "3 z ≤ −surface_clearance (m)": -p.surface - np.max(P[1:, :, 2]),
        "4 floor clearance, waypoints + segments (m)": np.min(floor) - p.clear,
        "5 range ≤ d_max (m)": p.d_max - np.max(to_usv[1:]),
        "5 range at K ≤ d_s (m)": p.d_s - np.max(to_usv[-1]),
        "6 chain: A2U link (m)": np.min(chain[:, 0]),
        "6 chain: A2A Hamiltonian path (m)": np.min(chain[:, 1]),
    }
    heights = P[1:, :, 2] - p.floor.elevation(P[1:, :, 0], P[1:, :, 1])
    return {k: float(v) for k, v in margins.items()}, float(np.sum(U ** 2)), float(np.sum(heights))


def write_atomically(path, doc):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), prefix=".waypoints-")
    with os.fdopen(fd, "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(tmp, path)


def parse_args():
    a = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    a.add_argument("plan", help="plan.json written by `shoal plan`")
    a.add_argument("--floor", required=True, help="the plan's floor, an ESRI ASCII grid")
    a.add_argument("-o", "--out", required=True, help="waypoints file to write")
    a.add_argument("--time", type=float, default=60.0, help="time limit, s (default 60)")
    a.add_argument("--iterations", type=int, help="also stop after this many RRT* iterations")
    a.add_argument("--seed", type=int, default=1, help="OMPL's RNG seed (default 1)")
    a.add_argument("--planner", choices=["rrtstar", "informedrrtstar"], default="rrtstar")
    a.add_argument("--range", type=float, default=300.0, help="RRT* range, state units")
    a.add_argument("--time-scale", type=float, default=0.1, help="c, m/s: time coordinate c·t")
    a.add_argument("--box", type=float, default=150.0, help="m, offsets from the start offset")
    a.add_argument("--goal-bias", type=float, default=0.05, help="RRT* goal bias")
    a.add_argument("--speed-factor", type=float, default=0.85, help="speed cap / max_speed")
    a.add_argument("--floor-margin", type=float, default=1.0, help="m over floor_clearance")
    a.add_argument("--goal-margin", type=float, default=1.0, help="m inside d_s at Kδ")
    a.add_argument("--goal-time-tol", type=float, default=5.0, help="s before Kδ in the goal")
    a.add_argument("--no-simplify", action="store_true", help="skip og.PathSimplifier")
    a.add_argument("-v", "--verbose", action="store_true", help="OMPL's own log")
    return a.parse_args()


def main():
    args = parse_args()
    ou.RNG.setSeed(args.seed)
    ou.setLogLevel(ou.LOG_INFO if args.verbose else ou.LOG_WARN)
    plan = json.load(open(args.plan))
    try:
        floor = Floor(args.floor)
    except (IndexError, KeyError, ValueError) as e:
        raise SystemExit("ompl_rrt_star: %s is not an ESRI ASCII grid (%r)" % (args.floor, e))
    keys = ("nx", "ny", "x0", "y0", "dx", "dy")
    if [getattr(floor, k) for k in keys] != [plan["seafloor"][k] for k in keys]:
        print("ompl_rrt_star: %s is not the floor of %s" % (args.floor, args.plan), file=sys.stderr)
        return 1
    p = Problem(plan, floor, args)
    name = "InformedRRTstar" if args.planner == "informedrrtstar" else "RRTstar"
    limit = "%g s" % args.time
    if args.iterations is not None:
        limit += " or %d iterations" % args.iterations
    print("OMPL %s og.%s: N = %d, K = %d, δ = %g s, state dimension %d, limit %s, seed %d%s"
          % (version("ompl"), name, p.N, p.K, p.dt, 3 * p.N + 1, limit, args.seed,
             "" if len(plan["windows"]) == 1 else " (window 0 of %d)" % len(plan["windows"])))
    path, info = plan_team(p, args)
    print("%s: %s in %.2f s; %d samples drawn, %d tree vertices, latest time reached %.1f s of %g"
          % (name, info["status"], info["solve_s"], info["drawn"], info["kept"], info["latest"],
             p.T))
    refused = sorted(info["refused"].items(), key=lambda kv: -kv[1])
    print("motions refused: " + ", ".join("%s %d" % kv for kv in refused))
    if path is None:
        print("ompl_rrt_star: no solution (%s): the goal, t ≥ %g s with every AUV within %g m of "
              "the USV's final position, was not reached; nothing written"
              % (info["status"], p.T - args.goal_time_tol, p.d_s - args.goal_margin),
              file=sys.stderr)
        return 2
    P = waypoints(p, path)
    margins, energy, height = evaluate(p, P)
    print("cost (planner's objective): %.2f from RRT*, %.2f final; %d path states; planning %.2f s"
          % (info["raw_cost"], info["cost"], len(path), info["plan_s"]))
    print("%-46s %11s  holds" % ("constraint on the waypoints (worst margin)", "margin"))
    for what, m in margins.items():
        print("%-46s %11.4f  %s" % (what, m, "yes" if m >= -1e-6 else "NO"))
    mpc, objective = plan["windows"][0]["final"]["objective"], (p.w1 * energy + p.w2 * height) / p.N
    print("energy Σ‖U‖² %.4f (MPC %.4f); mean height %.3f m (MPC %.3f); (w1·E + w2·H)/N %.2f "
          "(MPC %.2f)" % (energy, mpc["energy"], height / (p.N * p.K),
                          plan["metrics"]["mean_height"], objective,
                          (p.w1 * mpc["energy"] + p.w2 * mpc["height"]) / p.N))
    broken = [what for what, m in margins.items() if m < -1e-6]
    verdict = "violated: " + "; ".join(broken) if broken else "constraints 1-6 hold"
    notes = ("OMPL %s og.%s (Python bindings), single-threaded, seed %d, limit %s, range %g, goal "
             "bias %g, time scale %g m/s, box %g m; cost (w1·E + w2·H)/N, E the steady-state "
             "input energy, H the heights at piece ends: %.4f; speed cap %g·max_speed, floor "
             "margin %g m; USV on the MPC plan's track; samples_drawn = RRT* iterations, "
             "samples_kept = tree vertices; %s"
             % (version("ompl"), name, args.seed, limit, args.range, args.goal_bias,
                args.time_scale, args.box, info["cost"], args.speed_factor, args.floor_margin,
                verdict))
    window = {"usv": p.usv.tolist(), "auvs": P.transpose(1, 0, 2).tolist(),
              "samples_drawn": info["drawn"], "samples_kept": info["kept"],
              "solve_time_s": info["plan_s"]}
    write_atomically(args.out, {"format": "shoal-waypoints/1", "method": "ompl-" + args.planner,
                                "seed": args.seed, "solve_time_s": info["plan_s"], "notes": notes,
                                "windows": [window]})
    print("wrote " + args.out)
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush(), sys.stderr.flush()
    os._exit(code)  # skip nanobind's leak report of the trampolines' reference cycles
